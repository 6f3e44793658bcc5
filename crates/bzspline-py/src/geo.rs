//! Smoothing shapely geometries: shapely's ragged arrays (coordinates and
//! offsets, innermost first, as `shapely.to_ragged_array` gives them) to
//! geo-types, through `bzspline-geo`, and back in the same layout.

use geo_types::{Coord, Geometry, LineString, MultiLineString, MultiPolygon, Polygon};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

use bzspline_geo::{Coverage, SmoothOptions};

/// Coordinates and offsets (innermost first) of a ragged array.
type Ragged = (Vec<[f64; 2]>, Vec<Vec<i64>>);

/// A ragged array as numpy arrays.
type PyRagged<'py> = (Bound<'py, PyArray2<f64>>, Vec<Bound<'py, PyArray1<i64>>>);

/// shapely's `GeometryType` values with lines to smooth.
const LINESTRING: u8 = 1;
const POLYGON: u8 = 3;
const MULTILINESTRING: u8 = 5;
const MULTIPOLYGON: u8 = 6;

/// The `(start, end)` pairs of an offsets array, checked against `len`.
fn spans(o: &[i64], len: usize) -> PyResult<Vec<(usize, usize)>> {
    o.windows(2)
        .map(|w| match (usize::try_from(w[0]), usize::try_from(w[1])) {
            (Ok(a), Ok(b)) if a <= b && b <= len => Ok((a, b)),
            _ => Err(PyValueError::new_err(
                "offsets do not describe the coordinates",
            )),
        })
        .collect()
}

fn line(coords: &[[f64; 2]], (a, b): (usize, usize)) -> LineString<f64> {
    LineString(
        coords[a..b]
            .iter()
            .map(|c| Coord { x: c[0], y: c[1] })
            .collect(),
    )
}

fn polygons(
    coords: &[[f64; 2]],
    rings: &[(usize, usize)],
    polys: &[(usize, usize)],
) -> Vec<Polygon<f64>> {
    polys
        .iter()
        .map(|&(a, b)| {
            let mut rs = rings[a..b].iter().map(|&r| line(coords, r));
            let shell = rs.next().unwrap_or_else(|| LineString(Vec::new()));
            Polygon::new(shell, rs.collect())
        })
        .collect()
}

/// The geometries of a ragged array of `kind`.
fn geometries(kind: u8, coords: &[[f64; 2]], offsets: &[Vec<i64>]) -> PyResult<Vec<Geometry<f64>>> {
    let level = |i: usize, len: usize| -> PyResult<Vec<(usize, usize)>> {
        let o = offsets
            .get(i)
            .ok_or_else(|| PyValueError::new_err("too few offsets arrays for the geometry type"))?;
        spans(o, len)
    };
    Ok(match kind {
        LINESTRING => level(0, coords.len())?
            .into_iter()
            .map(|s| Geometry::LineString(line(coords, s)))
            .collect(),
        MULTILINESTRING => {
            let lines = level(0, coords.len())?;
            level(1, lines.len())?
                .into_iter()
                .map(|(a, b)| {
                    Geometry::MultiLineString(MultiLineString(
                        lines[a..b].iter().map(|&s| line(coords, s)).collect(),
                    ))
                })
                .collect()
        }
        POLYGON => {
            let rings = level(0, coords.len())?;
            let polys = level(1, rings.len())?;
            polygons(coords, &rings, &polys)
                .into_iter()
                .map(Geometry::Polygon)
                .collect()
        }
        MULTIPOLYGON => {
            let rings = level(0, coords.len())?;
            let polys = level(1, rings.len())?;
            let all = polygons(coords, &rings, &polys);
            level(2, all.len())?
                .into_iter()
                .map(|(a, b)| Geometry::MultiPolygon(MultiPolygon(all[a..b].to_vec())))
                .collect()
        }
        other => {
            return Err(PyValueError::new_err(format!(
                "geometry type {other}: only lines and polygons are smoothed"
            )))
        }
    })
}

/// Appends a line's coordinates and its end offset.
fn push_line(l: &LineString<f64>, coords: &mut Vec<[f64; 2]>, ends: &mut Vec<i64>) {
    coords.extend(l.0.iter().map(|c| [c.x, c.y]));
    ends.push(coords.len() as i64);
}

fn push_polygon(
    p: &Polygon<f64>,
    coords: &mut Vec<[f64; 2]>,
    rings: &mut Vec<i64>,
    polys: &mut Vec<i64>,
) {
    push_line(p.exterior(), coords, rings);
    for r in p.interiors() {
        push_line(r, coords, rings);
    }
    polys.push(rings.len() as i64 - 1);
}

/// The ragged layout of `geoms` (all of `kind`'s family): coordinates and
/// offsets, innermost first.
fn ragged(kind: u8, geoms: &[Geometry<f64>]) -> PyResult<Ragged> {
    let mut coords = Vec::new();
    let (mut o0, mut o1, mut o2) = (vec![0i64], vec![0i64], vec![0i64]);
    let wrong = || PyRuntimeError::new_err("smoothing changed a geometry's type");
    for g in geoms {
        match (kind, g) {
            (LINESTRING, Geometry::LineString(l)) => push_line(l, &mut coords, &mut o0),
            (MULTILINESTRING, Geometry::MultiLineString(m)) => {
                for l in &m.0 {
                    push_line(l, &mut coords, &mut o0);
                }
                o1.push(o0.len() as i64 - 1);
            }
            (MULTILINESTRING, Geometry::LineString(l)) => {
                push_line(l, &mut coords, &mut o0);
                o1.push(o0.len() as i64 - 1);
            }
            (POLYGON, Geometry::Polygon(p)) => push_polygon(p, &mut coords, &mut o0, &mut o1),
            (MULTIPOLYGON, Geometry::MultiPolygon(m)) => {
                for p in &m.0 {
                    push_polygon(p, &mut coords, &mut o0, &mut o1);
                }
                o2.push(o1.len() as i64 - 1);
            }
            (MULTIPOLYGON, Geometry::Polygon(p)) => {
                push_polygon(p, &mut coords, &mut o0, &mut o1);
                o2.push(o1.len() as i64 - 1);
            }
            _ => return Err(wrong()),
        }
    }
    let offsets = match kind {
        LINESTRING => vec![o0],
        MULTILINESTRING | POLYGON => vec![o0, o1],
        _ => vec![o0, o1, o2],
    };
    Ok((coords, offsets))
}

/// Smooths the geometries of a ragged array: as one coverage (shared borders
/// smoothed once) or each on its own. Returns the ragged array of the result.
#[pyfunction]
#[pyo3(signature = (kind, coords, offsets, tolerance=None, coverage=true, through=false, keep_angle=None, alpha=0.5))]
#[allow(clippy::too_many_arguments)] // the keyword arguments of bzspline.geo.smooth
pub fn _smooth_ragged<'py>(
    py: Python<'py>,
    kind: u8,
    coords: PyReadonlyArray2<'py, f64>,
    offsets: Vec<PyReadonlyArray1<'py, i64>>,
    tolerance: Option<f64>,
    coverage: bool,
    through: bool,
    keep_angle: Option<f64>,
    alpha: f64,
) -> PyResult<PyRagged<'py>> {
    let view = coords.as_array();
    if view.ncols() != 2 {
        return Err(PyValueError::new_err("coordinates must be 2-D (x, y)"));
    }
    let pts: Vec<[f64; 2]> = view.rows().into_iter().map(|r| [r[0], r[1]]).collect();
    let offs: Vec<Vec<i64>> = offsets.iter().map(|o| o.as_array().to_vec()).collect();
    let geoms = geometries(kind, &pts, &offs)?;
    let mut opts = SmoothOptions::default().alpha(alpha).through(through);
    if let Some(t) = tolerance {
        opts = opts.tolerance(t);
    }
    if let Some(k) = keep_angle {
        opts = opts.keep_angle(k);
    }
    let smoothed = py.allow_threads(|| -> Result<Vec<Geometry<f64>>, String> {
        let run = |gs: Vec<Geometry<f64>>| -> Result<Vec<Geometry<f64>>, String> {
            let c = Coverage::new(gs, None).map_err(|e| e.to_string())?;
            c.smooth(&opts)
                .map(|(out, _)| out)
                .map_err(|e| c.describe(&e))
        };
        if coverage {
            run(geoms)
        } else {
            let mut out = Vec::with_capacity(geoms.len());
            for g in geoms {
                out.extend(run(vec![g])?);
            }
            Ok(out)
        }
    });
    let smoothed = smoothed.map_err(PyValueError::new_err)?;
    let (c, o) = ragged(kind, &smoothed)?;
    let rows: Vec<Vec<f64>> = c.iter().map(|p| p.to_vec()).collect();
    let coords = if rows.is_empty() {
        PyArray2::zeros(py, [0, 2], false)
    } else {
        PyArray2::from_vec2(py, &rows).map_err(|e| PyRuntimeError::new_err(e.to_string()))?
    };
    Ok((coords, o.into_iter().map(|v| v.into_pyarray(py)).collect()))
}
