//! The `smooth` subcommand: the lines and rings of a GeoJSON or TopoJSON
//! document replaced by the method's curves with their positions as control
//! points, flattened to a tolerance.
//!
//! By default a document is smoothed as one coverage ([`bzspline_geo`]):
//! borders that features share are smoothed once and stay shared, nodes stay
//! where they are, and what was valid stays valid. `--independent` smooths
//! every ring on its own ([`independent`]), as do documents whose positions
//! carry z. Newline-delimited GeoJSON is streamed, a coverage per line; a
//! table of points (or `--example`) is one LineString.

use bzspline_io::smooth::{chains, coverage, default_tolerance, independent, positions};

use std::io::{BufRead, BufReader, IsTerminal, Read, Write};
use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use bzspline_geo::{SmoothOptions, Stats};
use geojson::{Feature, GeoJson, Geometry, GeometryValue, Position};
use serde_json::Value;

use crate::cli::{InputFormat, SmoothArgs, SmoothFormat, UsageError};
use crate::input;
use crate::output::Sink;
use crate::topojson;

/// Everything `smooth` decided from its arguments.
struct Job<'a> {
    args: &'a SmoothArgs,
    lib: SmoothOptions,
    limits: input::Limits,
    output: SmoothFormat,
    /// The name of the object a GeoJSON input becomes in TopoJSON output.
    object_name: String,
    /// Where positions with z sent a document ring by ring (said once the
    /// output is written; not for tables, which are one line anyway).
    z_at: Option<String>,
    /// Positions cut to x, y, z (more than 3 numbers), and where the first was.
    cut: (usize, Option<String>),
    /// Totals over the documents (lines of a stream).
    total: Stats,
    features: usize,
}

/// Runs `smooth`.
///
/// # Errors
///
/// Bad options; `FILE:LINE: ...` for invalid JSON, GeoJSON or TopoJSON;
/// `FILE: feature i, ...: ...` for a geometry that cannot be smoothed; I/O
/// errors.
pub fn run(a: &SmoothArgs) -> Result<()> {
    let alpha = a.alpha.unwrap_or(bzspline::DEFAULT_ALPHA);
    crate::cli::check_alpha("--alpha", alpha)?;
    let mut lib = SmoothOptions::default().alpha(alpha).param(a.param.clone());
    lib.tolerance = a.tolerance;
    lib.keep_angle = a.keep_angle;
    lib.through = a.through;
    let out_path = a.output.output.as_deref();
    let output = a.output_format.unwrap_or_else(|| {
        match out_path.and_then(Path::extension).and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("topojson") => SmoothFormat::Topojson,
            _ => SmoothFormat::Geojson,
        }
    });
    let file = a.input.file.as_deref();
    let format = match (a.input.example, a.input.input_format) {
        (Some(_), _) => InputFormat::Csv,
        (None, Some(f)) => f,
        (None, None) => match input::format_of(file, None) {
            f @ (InputFormat::Geojsonseq | InputFormat::Tsv | InputFormat::Topojson) => f,
            InputFormat::Csv
                if file.is_some_and(|f| f != Path::new("-") && has_table_extension(f)) =>
            {
                InputFormat::Csv
            }
            _ => InputFormat::Geojson,
        },
    };
    if output == SmoothFormat::Topojson {
        if a.independent {
            return Err(UsageError::new(
                "--independent smooths ring by ring and has no topology to write as TopoJSON",
            )
            .into());
        }
        if format == InputFormat::Geojsonseq {
            return Err(UsageError::new(
                "newline-delimited GeoJSON is streamed and cannot be written as TopoJSON",
            )
            .into());
        }
    }
    let object_name = file
        .filter(|f| *f != Path::new("-"))
        .and_then(Path::file_stem)
        .and_then(|s| s.to_str())
        .unwrap_or("collection")
        .to_owned();
    let mut job = Job {
        args: a,
        lib,
        limits: a.input.limits(),
        output,
        object_name,
        z_at: None,
        cut: (0, None),
        total: Stats::default(),
        features: 0,
    };
    let mut sink = Sink::create(out_path)?;
    match format {
        InputFormat::Geojsonseq => job.stream(file, &mut sink)?,
        InputFormat::Csv | InputFormat::Tsv => {
            // A table (or an example) is one line: its rows are the vertices.
            let points = a.input.load()?;
            input::check_columns(&points, &[2, 3], "2 or 3 coordinates")?;
            let line: Vec<Position> = points.rows().map(|r| Position::from(r.to_vec())).collect();
            let mut feature = Feature::from(Geometry::new(GeometryValue::LineString {
                coordinates: line,
            }));
            feature.set_property("source", points.source.clone());
            let out = job.document(GeoJson::Feature(feature), &points.source, false)?;
            write_line(&mut sink, &out)?;
        }
        InputFormat::Json | InputFormat::Geojson | InputFormat::Topojson => {
            let (name, bytes) = input::read_source(file, job.limits.max_bytes)?;
            let text = input::utf8(&name, &bytes)?;
            let value: Value = serde_json::from_str(text)
                .map_err(|e| anyhow!("{name}:{}: invalid JSON: {e}", e.line()))?;
            drop(bytes);
            let out = if topojson::is_topology(&value) {
                job.topology(&name, value)?
            } else {
                let doc = job.checked(&name, value)?;
                job.document(doc, &name, true)?
            };
            write_line(&mut sink, &out)?;
        }
    }
    sink.finish()?;
    if let (n @ 1.., Some(at)) = &job.cut {
        eprintln!("note: {}", input::cut_note(at, *n));
    }
    if let Some(at) = &job.z_at {
        eprintln!("note: {at}: positions with z: smoothed ring by ring (the coverage's topology is planar)");
    }
    if a.stats || std::io::stderr().is_terminal() {
        eprint!("{}", job.summary());
    }
    Ok(())
}

fn write_line(sink: &mut Sink, v: &Value) -> Result<()> {
    crate::model::write_json_compact(&mut *sink, v).context("writing output")?;
    sink.write_all(b"\n").context("writing output")
}

/// True for `.csv`, `.tsv`, `.tab` and `.txt` files.
fn has_table_extension(f: &Path) -> bool {
    f.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| ["csv", "tsv", "tab", "txt"].contains(&e.to_ascii_lowercase().as_str()))
}

impl Job<'_> {
    /// A GeoJSON document checked ([`input::to_geojson`]) and converted;
    /// positions cut to x, y, z are counted for the note.
    fn checked(&mut self, where_: &str, value: Value) -> Result<GeoJson> {
        let (doc, cut) = input::to_geojson(where_, value)?;
        if cut > 0 {
            self.cut.0 += cut;
            self.cut.1.get_or_insert_with(|| where_.to_owned());
        }
        Ok(doc)
    }

    /// Smooths one GeoJSON document (a whole file or a line of a stream)
    /// and gives the output document, GeoJSON or TopoJSON.
    fn document(&mut self, doc: GeoJson, where_: &str, number_single: bool) -> Result<Value> {
        self.features += match &doc {
            GeoJson::FeatureCollection(fc) => fc.features.len(),
            _ => 1,
        };
        let z = coverage::document_has_z(&doc);
        if self.args.independent || z {
            if z && !self.args.independent && number_single && self.z_at.is_none() {
                self.z_at = Some(where_.to_owned());
            }
            let tolerance = self
                .lib
                .tolerance
                .unwrap_or_else(|| default_tolerance(&doc));
            let opts = independent::Options {
                alpha: self.lib.alpha,
                param: self.lib.param.clone(),
                tolerance,
                limits: self.limits,
                through: self.args.through,
            };
            let positions_in = positions(&doc);
            let (rings, lines) = chains(&doc);
            let out = independent::smooth_document(doc, &opts, where_, number_single)?;
            let mut s = Stats::default();
            s.rings = rings;
            s.lines = lines;
            s.positions_in = positions_in;
            s.positions_out = positions(&out);
            s.tolerance = tolerance;
            add(&mut self.total, &s);
            return serde_json::to_value(&out).context("formatting GeoJSON");
        }
        let s = coverage::smooth_document(
            doc,
            &self.lib,
            self.args.snap,
            self.limits.max_points,
            where_,
            number_single,
        )?;
        add(&mut self.total, &s.stats);
        match self.output {
            SmoothFormat::Geojson => serde_json::to_value(&s.doc).context("formatting GeoJSON"),
            SmoothFormat::Topojson => Ok(topojson::from_features(
                &self.object_name,
                &coverage::features(&s.doc),
                s.coverage.topology(),
                &s.arcs,
            )),
        }
    }

    /// Smooths a TopoJSON Topology on its own arcs (or, with `--snap` or
    /// `--independent`, as the GeoJSON of its objects).
    fn topology(&mut self, name: &str, value: Value) -> Result<Value> {
        let topo = topojson::read(name, value)?;
        let object = self.args.object.as_deref();
        if self.args.independent || self.args.snap.is_some() {
            let fc = topo
                .to_geojson(topo.topology.arcs(), object)
                .map_err(|e| anyhow!("{name}: {e}"))?;
            let doc = self.checked(name, fc)?;
            return self.document(doc, name, true);
        }
        let s = topo
            .topology
            .smooth(&self.lib)
            .map_err(|e| anyhow!("{name}: {}", topo.describe(&e)))?;
        self.features += topo.features;
        add(&mut self.total, &s.stats);
        match self.output {
            SmoothFormat::Topojson => Ok(topo.to_topojson(&s.arcs)),
            SmoothFormat::Geojson => topo
                .to_geojson(&s.arcs, object)
                .map_err(|e| anyhow!("{name}: {e}")),
        }
    }

    /// Smooths newline-delimited GeoJSON one line at a time (RFC 8142 record
    /// separators are accepted), with a progress bar when stderr is a terminal.
    fn stream(&mut self, file: Option<&Path>, sink: &mut Sink) -> Result<()> {
        let (name, reader, size): (String, Box<dyn Read>, Option<u64>) = match file {
            Some(p) if p != Path::new("-") => {
                let name = p.display().to_string();
                let f = std::fs::File::open(p).with_context(|| format!("reading {name}"))?;
                let size = f.metadata().ok().map(|m| m.len());
                (name, Box::new(f), size)
            }
            _ => ("<stdin>".to_owned(), Box::new(std::io::stdin()), None),
        };
        let bar = if std::io::stderr().is_terminal() {
            let bar = match size {
                Some(n) => indicatif::ProgressBar::new(n),
                None => indicatif::ProgressBar::new_spinner(),
            };
            bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
            Some(bar)
        } else {
            None
        };
        let mut reader = BufReader::new(reader);
        let mut buf = Vec::new();
        let mut line_no = 0usize;
        let max_bytes = self.limits.max_bytes;
        loop {
            buf.clear();
            let n = (&mut reader)
                .take(max_bytes.saturating_add(1))
                .read_until(b'\n', &mut buf)
                .with_context(|| format!("reading {name}"))?;
            if n == 0 {
                break;
            }
            line_no += 1;
            if n as u64 > max_bytes {
                bail!("{name}:{line_no}: a line longer than {max_bytes} bytes (--max-bytes)");
            }
            if let Some(bar) = &bar {
                bar.inc(n as u64);
            }
            let here = format!("{name}:{line_no}");
            let text = input::utf8(&here, &buf)
                .map_err(|_| anyhow!("{here}: not valid UTF-8"))?
                .trim_matches(|c: char| c.is_whitespace() || c == '\u{1e}');
            if text.is_empty() {
                continue;
            }
            let value: Value =
                serde_json::from_str(text).map_err(|e| anyhow!("{here}: invalid JSON: {e}"))?;
            let doc = self.checked(&here, value)?;
            let out = self.document(doc, &here, false)?;
            write_line(sink, &out)?;
        }
        if let Some(bar) = bar {
            bar.finish_and_clear();
        }
        Ok(())
    }

    /// The summary printed on standard error.
    fn summary(&self) -> String {
        let t = &self.total;
        let mut s = format!(
            "smooth: {} features, {} rings, {} lines",
            self.features, t.rings, t.lines
        );
        if t.arcs > 0 {
            s += &format!(
                "; {} arcs ({} shared, {} not, {} closed)",
                t.arcs,
                t.shared_arcs,
                t.arcs - t.shared_arcs,
                t.closed_arcs
            );
        }
        s += &format!(
            "\n  positions {} -> {}; tolerance {}{}\n",
            t.positions_in,
            t.positions_out,
            t.tolerance,
            if self.lib.tolerance.is_none() {
                " (the default: 1e-4 of the extent's diagonal)"
            } else {
                ""
            }
        );
        if !self.args.independent {
            s += &format!(
                "  refined {} legs ({} kept as original edges) in {} rounds; {} pairs of edges already met in the input (left as they were)\n",
                t.refined_legs, t.straight_legs, t.rounds, t.input_conflicts
            );
        }
        if t.area_in > 0.0 {
            s += &format!(
                "  polygon area {:+.4} %\n",
                100.0 * (t.area_out - t.area_in) / t.area_in
            );
        }
        s
    }
}

/// Adds one document's statistics to the totals.
fn add(total: &mut Stats, s: &Stats) {
    total.lines += s.lines;
    total.rings += s.rings;
    total.arcs += s.arcs;
    total.shared_arcs += s.shared_arcs;
    total.closed_arcs += s.closed_arcs;
    total.positions_in += s.positions_in;
    total.positions_out += s.positions_out;
    total.refined_legs += s.refined_legs;
    total.straight_legs += s.straight_legs;
    total.rounds = total.rounds.max(s.rounds);
    total.input_conflicts += s.input_conflicts;
    total.kept_pieces += s.kept_pieces;
    total.area_in += s.area_in;
    total.area_out += s.area_out;
    total.tolerance = s.tolerance;
}
