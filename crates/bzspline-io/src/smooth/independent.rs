//! Smoothing ring by ring (documents whose positions carry z, which the
//! planar coverage cannot hold): every LineString and Polygon ring is replaced by the
//! method's curve with its vertices as control points (open for lines, closed
//! for rings), flattened to within the tolerance, on its own, with no regard
//! for neighbours.
//!
//! Properties, ids and foreign members are kept; Points and MultiPoints pass
//! through; a third coordinate (z) is carried along as a 3D curve. Lines keep
//! their end points exactly; rings come out closed (first vertex = last).
//! Lines or rings with too few distinct vertices for a curve pass through
//! unchanged.

use anyhow::{anyhow, bail, Result};
use bzspline_geo::SmoothOptions;
use geojson::{Feature, GeoJson, Geometry, GeometryValue, Position};

/// Smooths every feature of a document with `opts` (their tolerance set, or
/// each line's own default), no line of more than `max_points` positions;
/// errors name `where_` and the feature
/// (a lone feature or geometry is `feature 0` when `number_single`, else just
/// `where_`, the line of newline-delimited input).
pub fn smooth_document(
    doc: GeoJson,
    opts: &SmoothOptions,
    max_points: usize,
    where_: &str,
    number_single: bool,
) -> Result<GeoJson> {
    let opts = &Ctx { opts, max_points };
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

/// The options and the limit, as every function below takes them.
struct Ctx<'a> {
    opts: &'a SmoothOptions,
    max_points: usize,
}

fn smooth_feature(mut f: Feature, opts: &Ctx<'_>) -> Result<Feature> {
    if let Some(g) = f.geometry.take() {
        f.geometry = Some(smooth_geometry(g, opts)?);
    }
    Ok(f)
}

fn smooth_geometry(mut g: Geometry, opts: &Ctx<'_>) -> Result<Geometry> {
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

fn smooth_rings(rings: &[Vec<Position>], opts: &Ctx<'_>) -> Result<Vec<Vec<Position>>> {
    rings
        .iter()
        .enumerate()
        .map(|(i, r)| smooth_line(r, true, opts).map_err(|e| anyhow!("ring {i}: {e}")))
        .collect()
}

/// The smoothed vertices of one line (or ring, `closed`).
fn smooth_line(line: &[Position], closed: bool, opts: &Ctx<'_>) -> Result<Vec<Position>> {
    let Some(dim) = line.first().map(Position::len) else {
        return Ok(Vec::new());
    };
    if !(2..=3).contains(&dim) {
        bail!("coordinate 0 has {dim} numbers; only 2 (x, y) or 3 (x, y, z) are supported");
    }
    let max = opts.max_points;
    if line.len() > max {
        bail!("more than {max} positions (--max-points)");
    }
    if let Some(i) = line.iter().position(|p| p.len() != dim) {
        bail!(
            "coordinate {i} has {} numbers, coordinate 0 has {dim}",
            line[i].len()
        );
    }
    let flat: Vec<f64> = line
        .iter()
        .flat_map(|p| p.as_slice().iter().copied())
        .collect();
    let out =
        bzspline_geo::smooth_line(&flat, dim, closed, opts.opts).map_err(|e| anyhow!("{e}"))?;
    Ok(out
        .chunks_exact(dim)
        .map(|c| Position::from(c.to_vec()))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn smooth(line: &[Position], closed: bool, tol: f64) -> Result<Vec<Position>> {
        let opts = SmoothOptions::default().tolerance(tol);
        let ctx = Ctx {
            opts: &opts,
            max_points: 1000,
        };
        smooth_line(line, closed, &ctx)
    }

    fn pos(v: &[[f64; 2]]) -> Vec<Position> {
        v.iter().map(|&p| Position::from(p)).collect()
    }

    #[test]
    fn a_line_keeps_its_ends_and_gains_vertices() {
        let line = pos(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]);
        let out = smooth(&line, false, 1e-3).unwrap();
        assert!(out.len() > line.len(), "{} vertices", out.len());
        assert_eq!(out[0], line[0]);
        assert_eq!(out[out.len() - 1], line[3]);
    }

    #[test]
    fn a_ring_comes_out_closed_and_inside_the_square() {
        let ring = pos(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]]);
        let out = smooth(&ring, true, 1e-3).unwrap();
        assert_eq!(out[0], out[out.len() - 1]);
        for p in &out {
            let [x, y] = [p[0], p[1]];
            assert!((-1e-12..=1.0 + 1e-12).contains(&x) && (-1e-12..=1.0 + 1e-12).contains(&y));
        }
    }

    #[test]
    fn degenerate_lines_pass_through_and_mixed_dimensions_are_refused() {
        let line = pos(&[[0.0, 0.0], [0.0, 0.0]]);
        assert_eq!(smooth(&line, false, 0.1).unwrap(), line);
        let mixed = vec![Position::from([0.0, 0.0]), Position::from([1.0, 1.0, 1.0])];
        let e = smooth(&mixed, false, 0.1).unwrap_err();
        assert!(e.to_string().contains("coordinate 1 has 3"), "{e}");
    }
}
