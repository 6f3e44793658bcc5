//! The `smooth` subcommand: every LineString and Polygon ring of a GeoJSON
//! document is replaced by the paper's curve through its vertices (open for
//! lines, closed for rings), flattened to within `--tolerance`.
//!
//! Properties, ids, bounding boxes and foreign members are kept; Points and
//! MultiPoints pass through; a third coordinate (z) is carried along as a 3D
//! curve. Lines keep their end points exactly; rings come out closed (first
//! vertex = last). Lines or rings with too few distinct vertices for a curve
//! pass through unchanged. Newline-delimited GeoJSON is streamed line by line.
//! A table of points (or `--example`) is read as one LineString.

use std::io::{BufRead, BufReader, IsTerminal, Read, Write};
use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use bzspline::{CurveBuilder, Param, Repeats};
use geojson::{Feature, GeoJson, Geometry, GeometryValue, Position};

use crate::cli::{InputFormat, ParamArg, SmoothArgs};
use crate::input;
use crate::output::Sink;

/// The validated options of `smooth`.
#[derive(Debug, Clone, PartialEq)]
struct Options {
    alpha: f64,
    param: Param,
    tolerance: f64,
    limits: input::Limits,
}

/// Runs `smooth`.
///
/// # Errors
///
/// Bad options; `FILE:LINE: ...` for invalid JSON or GeoJSON;
/// `FILE: feature i: ...` for a geometry the curve cannot take (mixed or
/// unsupported coordinate counts, a tolerance too small); I/O errors.
pub fn run(a: &SmoothArgs) -> Result<()> {
    let alpha = a.alpha.unwrap_or(bzspline::DEFAULT_ALPHA);
    crate::cli::check_alpha("--alpha", alpha)?;
    if !(a.tolerance.is_finite() && a.tolerance > 0.0) {
        bail!(
            "--tolerance must be a positive number (got {})",
            a.tolerance
        );
    }
    let opts = Options {
        alpha,
        param: match a.param {
            ParamArg::Uniform => Param::Uniform,
            ParamArg::Chordal => Param::Chordal,
            ParamArg::Centripetal => Param::Centripetal,
        },
        tolerance: a.tolerance,
        limits: input::Limits::of(&a.input),
    };
    let file = a.input.file.as_deref();
    let format = match (a.input.example, a.input.input_format) {
        (Some(_), _) => InputFormat::Csv,
        (None, Some(f)) => f,
        (None, None) => match input::format_of(file, None) {
            InputFormat::Geojsonseq => InputFormat::Geojsonseq,
            InputFormat::Csv
                if file.is_some_and(|f| f != Path::new("-") && has_table_extension(f)) =>
            {
                InputFormat::Csv
            }
            InputFormat::Tsv => InputFormat::Tsv,
            _ => InputFormat::Geojson,
        },
    };
    let mut sink = Sink::create(a.output.output.as_deref())?;
    let doc = match format {
        InputFormat::Geojson | InputFormat::Json => {
            let (name, bytes) = input::read_source(file, opts.limits.max_bytes)?;
            let text = input::utf8(&name, &bytes)?;
            let doc: GeoJson = serde_json::from_str(text)
                .map_err(|e| anyhow!("{name}:{}: invalid GeoJSON: {e}", e.line()))?;
            smooth_document(doc, &opts, &name, true)?
        }
        InputFormat::Geojsonseq => {
            stream(file, &opts, &mut sink)?;
            return sink.finish();
        }
        InputFormat::Csv | InputFormat::Tsv => {
            // A table (or an example) is one line: its rows are the vertices.
            let points = input::load(&a.input)?;
            input::check_columns(&points, &[2, 3], "2 or 3 coordinates")?;
            let line: Vec<Position> = points.rows().map(|r| Position::from(r.to_vec())).collect();
            let mut feature = Feature::from(Geometry::new(GeometryValue::LineString {
                coordinates: line,
            }));
            feature.set_property("source", points.source.clone());
            smooth_document(GeoJson::Feature(feature), &opts, &points.source, false)?
        }
    };
    let s = serde_json::to_string(&doc).context("formatting GeoJSON")?;
    sink.write_all(s.as_bytes())
        .and_then(|()| sink.write_all(b"\n"))
        .context("writing output")?;
    sink.finish()
}

/// True for `.csv`, `.tsv`, `.tab` and `.txt` files.
fn has_table_extension(f: &Path) -> bool {
    f.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| ["csv", "tsv", "tab", "txt"].contains(&e.to_ascii_lowercase().as_str()))
}

/// Smooths newline-delimited GeoJSON one line at a time (RFC 8142 record
/// separators are accepted), with a progress bar when stderr is a terminal.
fn stream(file: Option<&Path>, opts: &Options, sink: &mut Sink) -> Result<()> {
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
    let max_bytes = opts.limits.max_bytes;
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
        let doc: GeoJson =
            serde_json::from_str(text).map_err(|e| anyhow!("{here}: invalid GeoJSON: {e}"))?;
        let out = smooth_document(doc, opts, &here, false)?;
        let s = serde_json::to_string(&out).context("formatting GeoJSON")?;
        sink.write_all(s.as_bytes())
            .and_then(|()| sink.write_all(b"\n"))
            .context("writing output")?;
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    Ok(())
}

/// Smooths every feature of a document; errors name `where_` and the feature
/// (a lone feature or geometry is `feature 0` when `number_single`, else just
/// `where_`, the line of newline-delimited input).
fn smooth_document(
    doc: GeoJson,
    opts: &Options,
    where_: &str,
    number_single: bool,
) -> Result<GeoJson> {
    let at = |i: usize| format!("{where_}: feature {i}");
    let single = || {
        if number_single {
            at(0)
        } else {
            where_.to_owned()
        }
    };
    Ok(match doc {
        GeoJson::FeatureCollection(mut fc) => {
            let features = std::mem::take(&mut fc.features);
            fc.features = features
                .into_iter()
                .enumerate()
                .map(|(i, f)| smooth_feature(f, opts).map_err(|e| anyhow!("{}: {e}", at(i))))
                .collect::<Result<_>>()?;
            GeoJson::FeatureCollection(fc)
        }
        GeoJson::Feature(f) => {
            GeoJson::Feature(smooth_feature(f, opts).map_err(|e| anyhow!("{}: {e}", single()))?)
        }
        GeoJson::Geometry(g) => {
            GeoJson::Geometry(smooth_geometry(g, opts).map_err(|e| anyhow!("{}: {e}", single()))?)
        }
    })
}

fn smooth_feature(mut f: Feature, opts: &Options) -> Result<Feature> {
    if let Some(g) = f.geometry.take() {
        f.geometry = Some(smooth_geometry(g, opts)?);
    }
    Ok(f)
}

fn smooth_geometry(mut g: Geometry, opts: &Options) -> Result<Geometry> {
    g.value = match g.value {
        GeometryValue::LineString { coordinates } => GeometryValue::LineString {
            coordinates: smooth_line(&coordinates, false, opts)?,
        },
        GeometryValue::MultiLineString { coordinates } => GeometryValue::MultiLineString {
            coordinates: coordinates
                .iter()
                .enumerate()
                .map(|(i, l)| smooth_line(l, false, opts).map_err(|e| anyhow!("line {i}: {e}")))
                .collect::<Result<_>>()?,
        },
        GeometryValue::Polygon { coordinates } => GeometryValue::Polygon {
            coordinates: smooth_rings(&coordinates, opts)?,
        },
        GeometryValue::MultiPolygon { coordinates } => GeometryValue::MultiPolygon {
            coordinates: coordinates
                .iter()
                .enumerate()
                .map(|(i, p)| smooth_rings(p, opts).map_err(|e| anyhow!("polygon {i}: {e}")))
                .collect::<Result<_>>()?,
        },
        GeometryValue::GeometryCollection { geometries } => GeometryValue::GeometryCollection {
            geometries: geometries
                .into_iter()
                .enumerate()
                .map(|(i, g)| smooth_geometry(g, opts).map_err(|e| anyhow!("geometry {i}: {e}")))
                .collect::<Result<_>>()?,
        },
        other @ (GeometryValue::Point { .. } | GeometryValue::MultiPoint { .. }) => other,
    };
    // A bounding box of the input may no longer hold; drop it rather than lie.
    g.bbox = None;
    Ok(g)
}

fn smooth_rings(rings: &[Vec<Position>], opts: &Options) -> Result<Vec<Vec<Position>>> {
    rings
        .iter()
        .enumerate()
        .map(|(i, r)| smooth_line(r, true, opts).map_err(|e| anyhow!("ring {i}: {e}")))
        .collect()
}

/// The smoothed vertices of one line (or ring, `closed`).
fn smooth_line(line: &[Position], closed: bool, opts: &Options) -> Result<Vec<Position>> {
    let Some(dim) = line.first().map(Position::len) else {
        return Ok(Vec::new());
    };
    if !(2..=3).contains(&dim) {
        bail!("coordinate 0 has {dim} numbers; only 2 (x, y) or 3 (x, y, z) are supported");
    }
    let max = opts.limits.max_points;
    if line.len() > max {
        bail!("more than {max} positions (--max-points)");
    }
    if let Some(i) = line.iter().position(|p| p.len() != dim) {
        bail!(
            "coordinate {i} has {} numbers, coordinate 0 has {dim}",
            line[i].len()
        );
    }
    let mut pts: Vec<&[f64]> = line.iter().map(Position::as_slice).collect();
    if closed && pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    // Repeated vertices are dropped; what remains must still make a curve.
    let mut distinct: Vec<&[f64]> = Vec::with_capacity(pts.len());
    for p in &pts {
        if distinct.last() != Some(p) {
            distinct.push(p);
        }
    }
    if closed {
        while distinct.len() > 1 && distinct.first() == distinct.last() {
            distinct.pop();
        }
    }
    if distinct.len() < if closed { 3 } else { 2 } {
        return Ok(line.to_vec());
    }
    let flat: Vec<f64> = distinct.concat();
    let curve = CurveBuilder::new(&flat, dim)
        .closed(closed)
        .param(opts.param.clone())
        .alpha(opts.alpha)
        .repeats(Repeats::Drop)
        .build()
        .map_err(|e| anyhow!("{e}"))?;
    let poly = curve.flatten(opts.tolerance).map_err(|e| anyhow!("{e}"))?;
    let mut out: Vec<Position> = poly
        .coords()
        .chunks(dim)
        .map(|c| Position::from(c.to_vec()))
        .collect();
    if !out
        .iter()
        .all(|p| p.as_slice().iter().all(|v| v.is_finite()))
    {
        bail!("the smoothed line overflows a double");
    }
    match (closed, out.first().cloned()) {
        (true, Some(first)) => {
            // The ring closes on its first vertex, bit for bit.
            if let Some(last) = out.last_mut() {
                *last = first;
            }
        }
        (false, _) => {
            // A line keeps its end points exactly.
            if let (Some(o), Some(i)) = (out.first_mut(), line.first()) {
                *o = i.clone();
            }
            if let (Some(o), Some(i)) = (out.last_mut(), line.last()) {
                *o = i.clone();
            }
        }
        (true, None) => {}
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts(tol: f64) -> Options {
        Options {
            alpha: 0.5,
            param: Param::Centripetal,
            tolerance: tol,
            limits: input::Limits::DEFAULT,
        }
    }

    fn pos(v: &[[f64; 2]]) -> Vec<Position> {
        v.iter().map(|&p| Position::from(p)).collect()
    }

    #[test]
    fn a_line_keeps_its_ends_and_gains_vertices() {
        let line = pos(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]);
        let out = smooth_line(&line, false, &opts(1e-3)).unwrap();
        assert!(out.len() > line.len(), "{} vertices", out.len());
        assert_eq!(out[0], line[0]);
        assert_eq!(out[out.len() - 1], line[3]);
    }

    #[test]
    fn a_ring_comes_out_closed_and_inside_the_square() {
        let ring = pos(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]]);
        let out = smooth_line(&ring, true, &opts(1e-3)).unwrap();
        assert_eq!(out[0], out[out.len() - 1]);
        for p in &out {
            let [x, y] = [p[0], p[1]];
            assert!((-1e-12..=1.0 + 1e-12).contains(&x) && (-1e-12..=1.0 + 1e-12).contains(&y));
        }
    }

    #[test]
    fn degenerate_lines_pass_through_and_mixed_dimensions_are_refused() {
        let line = pos(&[[0.0, 0.0], [0.0, 0.0]]);
        assert_eq!(smooth_line(&line, false, &opts(0.1)).unwrap(), line);
        let mixed = vec![Position::from([0.0, 0.0]), Position::from([1.0, 1.0, 1.0])];
        let e = smooth_line(&mixed, false, &opts(0.1)).unwrap_err();
        assert!(e.to_string().contains("coordinate 1 has 3"), "{e}");
    }
}
