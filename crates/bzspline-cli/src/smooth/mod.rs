//! The `smooth` subcommand: the lines and rings of a GeoJSON or TopoJSON
//! document replaced by the method's curves with their positions as control
//! points, flattened to a tolerance.
//!
//! By default a document is smoothed as one coverage ([`bzspline_geo`]):
//! borders that features share are smoothed once and stay shared, nodes stay
//! where they are, and what was valid stays valid. `--independent` smooths
//! every feature's geometry on its own, as a coverage of its own; documents
//! whose positions carry z are smoothed ring by ring. Newline-delimited GeoJSON is streamed, a coverage per line; a
//! table of points (or `--example`) is one LineString.

use bzspline_io::smooth::document::{Document, SmoothedTopology};
use bzspline_io::smooth::job::{Job, Output, Settings};

use std::io::{BufRead, BufReader, IsTerminal, Read, Write};
use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use bzspline_geo::SmoothOptions;
use serde_json::Value;

use crate::cli::{InputFormat, SmoothArgs, UsageError};
use crate::input;
use crate::output::Sink;
use bzspline_io::distance::Unit;
use bzspline_io::files;

/// Runs `smooth`.
///
/// # Errors
///
/// Bad options; `FILE:LINE: ...` for invalid JSON, GeoJSON or TopoJSON;
/// `FILE: feature i, ...: ...` for a geometry that cannot be smoothed; I/O
/// errors.
pub fn run(a: &SmoothArgs) -> Result<()> {
    let alpha = a.alpha.unwrap_or(bzspline::DEFAULT_ALPHA);
    let mut lib = SmoothOptions::default().alpha(alpha).param(a.param.clone());
    lib.tolerance = a.tolerance.map(|d| d.value);
    lib.keep_angle = a.keep_angle;
    lib.through = a.through;
    let out_path = a.output.output.as_deref();
    let output = a
        .output_format
        .unwrap_or_else(|| out_path.map_or(Output::Geojson, Output::of_path));
    let file = a.input.file.as_deref();
    let format = match (a.input.example, a.input.input_format) {
        (Some(_), _) => InputFormat::Csv,
        (None, Some(f)) => f,
        (None, None) => match input::format_of(file, None) {
            f @ (InputFormat::Geojsonseq
            | InputFormat::Tsv
            | InputFormat::Topojson
            | InputFormat::Shapefile
            | InputFormat::Geopackage
            | InputFormat::Flatgeobuf
            | InputFormat::Geoparquet) => f,
            InputFormat::Csv
                if file.is_some_and(|f| f != Path::new("-") && has_table_extension(f)) =>
            {
                InputFormat::Csv
            }
            _ => InputFormat::Geojson,
        },
    };
    let settings = Settings {
        options: lib,
        independent: a.independent,
        snap: a.snap.map(|d| d.value),
        tolerance_unit: a.tolerance.map_or(Unit::Data, |d| d.unit),
        snap_unit: a.snap.map_or(Unit::Data, |d| d.unit),
        object: a.object.clone(),
        output,
        object_name: file
            .filter(|f| *f != Path::new("-"))
            .and_then(Path::file_stem)
            .and_then(|s| s.to_str())
            .unwrap_or_default()
            .to_owned(),
        limits: a.input.limits(),
    };
    settings.check().map_err(|e| UsageError::new(&e))?;
    if output == Output::Topojson && format == InputFormat::Geojsonseq {
        return Err(UsageError::new(
            "newline-delimited GeoJSON is streamed and cannot be written as TopoJSON",
        )
        .into());
    }
    let layer_out = match (files::writes_layer(output), out_path) {
        (false, _) => None,
        (true, _) if format == InputFormat::Geojsonseq => {
            return Err(UsageError::new(&format!(
                "newline-delimited GeoJSON is streamed and cannot be written as {}",
                output.name()
            ))
            .into())
        }
        (true, Some(p)) if p != Path::new("-") => Some(p),
        (true, _) => {
            return Err(UsageError::new(&format!(
                "{} is written as a file, not to standard output: give -o NAME.{}",
                output.name(),
                output.extension()
            ))
            .into())
        }
    };
    if a.input.layer.is_some() && format != InputFormat::Geopackage {
        return Err(UsageError::new(&format!(
            "--layer chooses a layer of a GeoPackage; the input is {}",
            files::format_name(format)
        ))
        .into());
    }
    let mut job = Job::new(settings);
    if format == InputFormat::Geojsonseq {
        let mut sink = Sink::create(out_path)?;
        stream(&mut job, file, &mut sink)?;
        sink.finish()?;
    } else {
        let (out, schema) = match format {
            InputFormat::Csv | InputFormat::Tsv => {
                (Smoothed::Document(job.table(&a.input.load(None)?)?), None)
            }
            f if files::is_layer(f) => {
                let Some(path) = file.filter(|f| *f != Path::new("-")) else {
                    return Err(UsageError::new(&format!(
                        "{} is read from its file, not from standard input",
                        files::format_name(f)
                    ))
                    .into());
                };
                let max_bytes = job.settings().limits.max_bytes;
                let mut layer = files::read(path, f, a.input.layer.as_deref(), max_bytes)?;
                let name = path.display().to_string();
                let crs = layer.schema.crs.clone();
                let out = match job.layer(&name, &mut layer.features, crs.as_ref())? {
                    Some(doc) => Smoothed::Document(doc),
                    None => Smoothed::Layer(layer.features),
                };
                (out, Some(layer.schema))
            }
            _ => {
                let max_bytes = job.settings().limits.max_bytes;
                // A file is read a feature at a time from the file, its text
                // never held; what declines is read whole below, which says
                // what is wrong, and standard input is read whole.
                let path = file.filter(|f| *f != Path::new("-"));
                let streamed = path.and_then(|p| job.read_collection_file(p));
                if let (Some(mut c), Some(path)) = (streamed, path) {
                    let name = path.display().to_string();
                    job.collection(&name, &mut c)?;
                    (Smoothed::Collection(c), None)
                } else {
                    let (name, bytes) = input::read_source(file, max_bytes)?;
                    let text = input::utf8(&name, &bytes)?;
                    let read = match path {
                        Some(_) => None,
                        None => job.read_collection(text),
                    };
                    if let Some(mut c) = read {
                        drop(bytes);
                        job.collection(&name, &mut c)?;
                        (Smoothed::Collection(c), None)
                    } else {
                        let value: Value = serde_json::from_str(text)
                            .map_err(|e| anyhow!("{name}:{}: invalid JSON: {e}", e.line()))?;
                        drop(bytes);
                        let out = match job.smooth_document(&name, value)? {
                            Document::Value(v) => Smoothed::Document(v),
                            Document::Topology(t) => Smoothed::Topology(t),
                        };
                        (out, None)
                    }
                }
            }
        };
        match (layer_out, &out) {
            (Some(path), Smoothed::Document(doc)) => {
                files::write_document(path, output, doc, schema.as_ref())?;
            }
            (Some(path), Smoothed::Layer(features)) => {
                files::write(path, output, features, schema.as_ref())?;
            }
            (Some(path), Smoothed::Collection(c)) => {
                files::write(path, output, c, None)?;
            }
            (Some(path), Smoothed::Topology(t)) => {
                files::write(path, output, &t.features()?, None)?;
            }
            (None, Smoothed::Document(doc)) => {
                let mut sink = Sink::create(out_path)?;
                write_line(&mut sink, doc)?;
                sink.finish()?;
            }
            (None, Smoothed::Layer(features)) => {
                let mut sink = Sink::create(out_path)?;
                features
                    .write_geojson(&mut sink)
                    .and_then(|()| sink.write_all(b"\n"))
                    .context("writing output")?;
                sink.finish()?;
            }
            (None, Smoothed::Topology(t)) => {
                let mut sink = Sink::create(out_path)?;
                t.write(&mut sink).context("writing output")?;
                sink.write_all(b"\n").context("writing output")?;
                sink.finish()?;
            }
            (None, Smoothed::Collection(c)) => {
                let mut sink = Sink::create(out_path)?;
                c.write_geojson(&mut sink)
                    .and_then(|()| sink.write_all(b"\n"))
                    .context("writing output")?;
                sink.finish()?;
            }
        }
    }
    for note in job.notes() {
        eprintln!("note: {note}");
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

/// What smoothing gave: a document, or a layer's or FeatureCollection's
/// features smoothed where they are.
enum Smoothed {
    Document(Value),
    Layer(bzspline_io::features::Features),
    Collection(bzspline_io::smooth::collection::Collection),
    /// A TopoJSON Topology smoothed on its own arcs, written from them.
    Topology(Box<SmoothedTopology>),
}

/// Smooths newline-delimited GeoJSON one line at a time (RFC 8142 record
/// separators are accepted), with a progress bar when stderr is a terminal.
fn stream(job: &mut Job, file: Option<&Path>, sink: &mut Sink) -> Result<()> {
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
    let max_bytes = job.settings().limits.max_bytes;
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
        let text = input::utf8(&here, &buf).map_err(|_| anyhow!("{here}: not valid UTF-8"))?;
        if let Some(out) = job.line(&here, text)? {
            write_line(sink, &out)?;
        }
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    Ok(())
}
