//! Smoothing shapely geometries: shapely's ragged arrays (coordinates and
//! offsets, innermost first, as `shapely.to_ragged_array` gives them) to
//! geo-types, through `bzspline-geo`, and back in the same layout.

use geo_types::{Coord, Geometry, LineString, MultiLineString, MultiPolygon, Polygon, Rect};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyString;

use bzspline_geo::parts::{self, across, meetings, Levels, Meeting};
use bzspline_geo::{coverage_chains, smooth_line, Coverage, Frame, Nodes, SmoothOptions};
use bzspline_io::distance::{parse_distance, Distance, Space, DISTANCE_FORMS};
use bzspline_io::layer::Crs;

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

/// Nodes for Python: positions `(n, 2)` and the extent.
type PyNodes<'py> = (Bound<'py, PyArray2<f64>>, Option<[f64; 4]>);

/// One ragged array from Python: shapely's geometry type, coordinates
/// `(n, 2)`, offsets innermost first, and each geometry's index in the
/// caller's array (for error messages).
type Group<'py> = (
    u8,
    PyReadonlyArray2<'py, f64>,
    Vec<PyReadonlyArray1<'py, i64>>,
    PyReadonlyArray1<'py, i64>,
);

/// The geometries of every group, in order, and each one's index in the
/// caller's array.
fn gather(groups: &[Group<'_>]) -> PyResult<(Vec<Geometry<f64>>, Vec<i64>)> {
    let (mut geoms, mut index) = (Vec::new(), Vec::new());
    for (kind, coords, offsets, idx) in groups {
        let view = coords.as_array();
        if view.ncols() != 2 {
            return Err(PyValueError::new_err("coordinates must be 2-D (x, y)"));
        }
        let pts: Vec<[f64; 2]> = view.rows().into_iter().map(|r| [r[0], r[1]]).collect();
        let offs: Vec<Vec<i64>> = offsets.iter().map(|o| o.as_array().to_vec()).collect();
        let gs = geometries(*kind, &pts, &offs)?;
        let idx = idx.as_array();
        if idx.len() != gs.len() {
            return Err(PyValueError::new_err(
                "one index per geometry of the ragged array",
            ));
        }
        for (g, &i) in gs.iter().zip(idx.iter()) {
            if let Some(k) = first_non_finite(g) {
                return Err(Fault {
                    coordinate: Some(k),
                    ..Fault::of(
                        i,
                        format!("geometry {i}, coordinate {k}: not a finite number"),
                    )
                }
                .into());
            }
        }
        geoms.extend(gs);
        index.extend(idx.iter().copied());
    }
    Ok((geoms, index))
}

/// The position (counted over the geometry's lines and rings in order) of
/// the first coordinate that is not finite.
fn first_non_finite(g: &Geometry<f64>) -> Option<usize> {
    let lines: Vec<&LineString<f64>> = match g {
        Geometry::LineString(l) => vec![l],
        Geometry::MultiLineString(m) => m.0.iter().collect(),
        Geometry::Polygon(p) => std::iter::once(p.exterior()).chain(p.interiors()).collect(),
        Geometry::MultiPolygon(m) => {
            m.0.iter()
                .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
                .collect()
        }
        _ => Vec::new(),
    };
    lines
        .iter()
        .flat_map(|l| l.0.iter())
        .position(|c| !(c.x.is_finite() && c.y.is_finite()))
}

/// The coordinates as a numpy `(n, 2)` array.
fn coords_array<'py>(py: Python<'py>, c: &[[f64; 2]]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    if c.is_empty() {
        return Ok(PyArray2::zeros(py, [0, 2], false));
    }
    let rows: Vec<Vec<f64>> = c.iter().map(|p| p.to_vec()).collect();
    PyArray2::from_vec2(py, &rows).map_err(|e| PyRuntimeError::new_err(e.to_string()))
}

/// An error of a coverage, naming the geometry by its index in the caller's
/// array.
fn coverage_error(c: &Coverage, index: &[i64], e: &bzspline_geo::Error) -> Fault {
    match c.locate(e) {
        Some(l) => {
            let at = index.get(l.geometry).copied().unwrap_or(l.geometry as i64);
            let mut msg = format!("geometry {at}, member {}", l.member);
            if let Some(r) = l.ring {
                msg.push_str(&format!(", ring {r}"));
            }
            Fault {
                member: Some(l.member),
                ring: l.ring,
                ..Fault::of(at, format!("{msg}: {e}"))
            }
        }
        None => Fault::option(e.to_string()),
    }
}

/// A geometry that cannot be smoothed, raised as
/// `bzspline.errors.GeometryError` with its fields; a plain `ValueError`
/// when the fault is in no one geometry (`index` `None`: an option).
struct Fault {
    message: String,
    index: Option<i64>,
    member: Option<usize>,
    ring: Option<usize>,
    coordinate: Option<usize>,
}

impl Fault {
    /// The fault of geometry `index`, nothing more precise known.
    fn of(index: i64, message: String) -> Fault {
        Fault {
            message,
            index: Some(index),
            member: None,
            ring: None,
            coordinate: None,
        }
    }

    /// A fault in no one geometry (an option): a plain `ValueError`.
    fn option(message: String) -> Fault {
        Fault {
            message,
            index: None,
            member: None,
            ring: None,
            coordinate: None,
        }
    }
}

impl From<Fault> for PyErr {
    fn from(f: Fault) -> PyErr {
        let Some(index) = f.index else {
            return PyValueError::new_err(f.message);
        };
        Python::with_gil(|py| {
            let raised = (|| -> PyResult<PyErr> {
                let class = py.import("bzspline.errors")?.getattr("GeometryError")?;
                let kwargs = pyo3::types::PyDict::new(py);
                kwargs.set_item("member", f.member)?;
                kwargs.set_item("ring", f.ring)?;
                kwargs.set_item("coordinate", f.coordinate)?;
                let e = class.call((f.message.as_str(), index), Some(&kwargs))?;
                Ok(PyErr::from_value(e))
            })();
            raised.unwrap_or_else(|e| e)
        })
    }
}

/// The nodes handed to a part: positions `(n, 2)` and the whole's extent
/// `(xmin, ymin, xmax, ymax)`.
fn given_nodes(
    positions: Option<PyReadonlyArray2<'_, f64>>,
    extent: Option<[f64; 4]>,
) -> PyResult<Nodes> {
    let mut nodes = match positions {
        None => Nodes::default(),
        Some(p) => {
            let v = p.as_array();
            if v.ncols() != 2 {
                return Err(PyValueError::new_err("nodes must be an (n, 2) array"));
            }
            Nodes::new(v.rows().into_iter().map(|r| Coord { x: r[0], y: r[1] }))
        }
    };
    if let Some([x0, y0, x1, y1]) = extent {
        if !([x0, y0, x1, y1].iter().all(|v| v.is_finite()) && x0 <= x1 && y0 <= y1) {
            return Err(PyValueError::new_err(format!(
                "extent ({x0}, {y0}, {x1}, {y1}) is not a finite box"
            )));
        }
        nodes = nodes.with_extent(Rect::new(Coord { x: x0, y: y0 }, Coord { x: x1, y: y1 }));
    }
    Ok(nodes)
}

fn extent_tuple(r: Option<Rect<f64>>) -> Option<[f64; 4]> {
    r.map(|r| [r.min().x, r.min().y, r.max().x, r.max().y])
}

/// A distance as `bzspline.geo.smooth` takes one: a number in the data's
/// units, or text with a unit (`"50m"`, `"2km"`, `"0.001deg"`), parsed by
/// [`parse_distance`].
fn distance(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Distance> {
    if let Ok(s) = value.downcast::<PyString>() {
        return parse_distance(&s.to_cow()?)
            .map_err(|e| PyValueError::new_err(format!("{name} {e}")));
    }
    value.extract::<f64>().map(Distance::data).map_err(|_| {
        PyTypeError::new_err(format!(
            "{name} must be {DISTANCE_FORMS}, not {}",
            value
                .get_type()
                .name()
                .map_or_else(|_| "?".into(), |n| n.to_string())
        ))
    })
}

/// The tolerance and snap distance of `bzspline.geo.smooth` in the data's
/// units, and whether to smooth on the ellipsoid: a distance in metres or
/// degrees is measured in the coordinate system `crs` (`EPSG:4326`, WKT, as
/// [`Crs::parse`] reads it) by [`Space::resolve`], as the command does.
#[pyfunction]
#[pyo3(signature = (tolerance=None, snap=None, crs=None))]
pub fn _distances(
    tolerance: Option<&Bound<'_, PyAny>>,
    snap: Option<&Bound<'_, PyAny>>,
    crs: Option<&str>,
) -> PyResult<(Option<f64>, Option<f64>, bool)> {
    let tolerance = tolerance.map(|t| distance("tolerance", t)).transpose()?;
    let snap = snap.map(|s| distance("snap", s)).transpose()?;
    let space = match crs {
        Some(text) => Space::of_crs(Some(
            &Crs::parse(text).map_err(|e| PyValueError::new_err(format!("crs: {e}")))?,
        )),
        None => Space::Unknown(
            "no coordinate system is given (pass crs=, for example crs=\"EPSG:4326\", or a GeoSeries with one)"
                .into(),
        ),
    };
    let (mut t, mut geographic) = (None, false);
    if let Some(d) = tolerance {
        let (v, frame) = space
            .resolve(d)
            .map_err(|e| PyValueError::new_err(format!("the tolerance {e}")))?;
        t = Some(v);
        geographic = frame == Frame::Geographic;
    }
    let s = snap
        .map(|d| {
            space
                .resolve_snap(d)
                .map_err(|e| PyValueError::new_err(format!("the snap distance {e}")))
        })
        .transpose()?;
    Ok((t, s, geographic))
}

/// `bzspline.geo.smooth`'s keyword arguments as the library's options,
/// checked by the library ([`SmoothOptions::validate`]); `geographic`:
/// longitude and latitude, the tolerance in metres.
fn smooth_options(
    tolerance: Option<f64>,
    through: bool,
    keep_angle: Option<f64>,
    alpha: f64,
    geographic: bool,
) -> PyResult<SmoothOptions> {
    let frame = if geographic {
        Frame::Geographic
    } else {
        Frame::Plane
    };
    let mut opts = SmoothOptions::default()
        .alpha(alpha)
        .through(through)
        .frame(frame);
    opts.tolerance = tolerance;
    opts.keep_angle = keep_angle;
    opts.validate()
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(opts)
}

/// Smooths the geometries of ragged arrays (lines and polygons in one
/// coverage: shared borders smoothed once), or each geometry on its own;
/// with `nodes` (and `extent`) as one part of a larger coverage; with `snap`,
/// positions closer than that are merged first; with `geographic`, the
/// positions are longitude and latitude and the tolerance is in metres
/// (see [`_distances`]). Returns each group's ragged array of the result.
#[pyfunction]
#[pyo3(signature = (groups, tolerance=None, coverage=true, through=false, keep_angle=None, alpha=0.5, nodes=None, extent=None, snap=None, levels=None, round=None, exact=None, geographic=false))]
#[allow(clippy::too_many_arguments)] // the keyword arguments of bzspline.geo.smooth
pub fn _smooth_ragged<'py>(
    py: Python<'py>,
    groups: Vec<Group<'py>>,
    tolerance: Option<f64>,
    coverage: bool,
    through: bool,
    keep_angle: Option<f64>,
    alpha: f64,
    nodes: Option<PyReadonlyArray2<'py, f64>>,
    extent: Option<[f64; 4]>,
    snap: Option<f64>,
    levels: Option<PyLevelsIn<'py>>,
    round: Option<usize>,
    exact: Option<usize>,
    geographic: bool,
) -> PyResult<(Vec<PyRagged<'py>>, PyLevels<'py>)> {
    crate::guard(|| {
        let (geoms, index) = gather(&groups)?;
        let nodes = given_nodes(nodes, extent)?;
        let opts = smooth_options(tolerance, through, keep_angle, alpha, geographic)?;
        let start = match levels {
            Some(l) => levels_from(l)?,
            None => Levels::default(),
        };
        let smoothed = py.allow_threads(|| -> Result<(Vec<Geometry<f64>>, Levels), Fault> {
            let run = |gs: Vec<Geometry<f64>>,
                       index: &[i64]|
             -> Result<(Vec<Geometry<f64>>, Levels), Fault> {
                let c = Coverage::builder(gs)
                    .snap(snap)
                    .frame(opts.frame)
                    .nodes(nodes.clone())
                    .build()
                    .map_err(|e| Fault::option(e.to_string()))?;
                // The caller's first `exact` geometries, wherever they are here.
                let marks: Vec<bool> = match exact {
                    Some(e) => index
                        .iter()
                        .map(|&i| usize::try_from(i).is_ok_and(|i| i < e))
                        .collect(),
                    None => Vec::new(),
                };
                crate::threads::install(|| match round {
                    Some(r) => c.smooth_round(&opts, &start, r, &marks),
                    None => c.smooth_from(&opts, &start),
                })
                .map(|(out, _, ended)| (out, ended))
                .map_err(|e| coverage_error(&c, index, &e))
            };
            if coverage {
                run(geoms, &index)
            } else {
                let (mut out, mut ended) = (Vec::with_capacity(geoms.len()), Levels::default());
                for (g, i) in geoms.into_iter().zip(&index) {
                    let (o, l) = run(vec![g], std::slice::from_ref(i))?;
                    out.extend(o);
                    ended.merge(&l);
                }
                Ok((out, ended))
            }
        });
        let (smoothed, ended) = smoothed?;
        let mut out = Vec::with_capacity(groups.len());
        let mut start = 0;
        for (kind, _, _, idx) in &groups {
            let n = idx.as_array().len();
            let (c, o) = ragged(*kind, &smoothed[start..start + n])?;
            start += n;
            out.push((
                coords_array(py, &c)?,
                o.into_iter().map(|v| v.into_pyarray(py)).collect(),
            ));
        }
        Ok((out, levels_to(py, &ended)))
    })
}

/// Refinement levels for Python: arc keys `(m,)`, offsets `(m + 1,)` into the
/// legs' levels.
type PyLevels<'py> = (
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray1<i64>>,
    Bound<'py, PyArray1<u8>>,
);

/// Refinement levels from Python, as [`PyLevels`].
type PyLevelsIn<'py> = (
    PyReadonlyArray1<'py, u64>,
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray1<'py, u8>,
);

fn levels_from(l: PyLevelsIn<'_>) -> PyResult<Levels> {
    let (keys, offs, vals) = (l.0.as_array(), l.1.as_array(), l.2.as_array());
    let offs = offs.to_vec();
    let vals = vals.to_vec();
    let spans = spans(&offs, vals.len())?;
    if spans.len() != keys.len() {
        return Err(PyValueError::new_err("levels: one offset span per arc key"));
    }
    let mut out = Levels::default();
    for (&k, (a, b)) in keys.iter().zip(spans) {
        out.insert(k, vals[a..b].to_vec());
    }
    Ok(out)
}

fn levels_to<'py>(py: Python<'py>, l: &Levels) -> PyLevels<'py> {
    let mut rows: Vec<(u64, &[u8])> = l.iter().collect();
    rows.sort_unstable_by_key(|r| r.0);
    let mut offs = vec![0i64];
    let mut vals = Vec::new();
    for (_, v) in &rows {
        vals.extend_from_slice(v);
        offs.push(vals.len() as i64);
    }
    let keys: Vec<u64> = rows.iter().map(|r| r.0).collect();
    (
        keys.into_pyarray(py),
        offs.into_pyarray(py),
        vals.into_pyarray(py),
    )
}

/// The rounds of the conflict search the partitions of a coverage run
/// together ([`parts::Rounds`]): `round` and `levels` to run the next from,
/// `finish(ended)` with the levels every partition ended it at.
#[pyclass(module = "bzspline._core", name = "_Rounds")]
pub struct Rounds(parts::Rounds);

#[pymethods]
impl Rounds {
    #[new]
    fn new() -> Self {
        Rounds(parts::Rounds::new())
    }

    /// The round to run (from 1).
    #[getter]
    fn round(&self) -> usize {
        self.0.round()
    }

    /// The levels every partition runs the round from.
    #[getter]
    fn levels<'py>(&self, py: Python<'py>) -> PyLevels<'py> {
        levels_to(py, self.0.levels())
    }

    /// Ends the round: True when another is to run, False when the
    /// partitions' results of this round are the whole's. RuntimeError past
    /// the cap of rounds.
    fn finish(&mut self, ended: Vec<PyLevelsIn<'_>>) -> PyResult<bool> {
        let ended: Vec<Levels> = ended
            .into_iter()
            .map(levels_from)
            .collect::<PyResult<_>>()?;
        self.0
            .finish(&ended)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }
}

/// Boxes `(n, 4)` as `xmin, ymin, xmax, ymax` rows; `None` for a row with
/// NaN (an empty geometry's bounds).
fn rects(bounds: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<Option<Rect<f64>>>> {
    let b = bounds.as_array();
    if b.ncols() != 4 {
        return Err(PyValueError::new_err("bounds must be an (n, 4) array"));
    }
    Ok(b.rows()
        .into_iter()
        .map(|r| {
            r.iter()
                .all(|v| !v.is_nan())
                .then(|| Rect::new(Coord { x: r[0], y: r[1] }, Coord { x: r[2], y: r[3] }))
        })
        .collect())
}

fn rect(b: (f64, f64, f64, f64)) -> Rect<f64> {
    Rect::new(Coord { x: b.0, y: b.1 }, Coord { x: b.2, y: b.3 })
}

/// Which of the boxes are context of a part whose extent is `part`
/// ([`parts::is_context`]).
#[pyfunction]
pub fn _context_of<'py>(
    py: Python<'py>,
    bounds: PyReadonlyArray2<'py, f64>,
    part: (f64, f64, f64, f64),
) -> PyResult<Bound<'py, PyArray1<bool>>> {
    let part = rect(part);
    let mask: Vec<bool> = rects(&bounds)?
        .iter()
        .map(|r| r.as_ref().is_some_and(|r| parts::is_context(r, &part)))
        .collect();
    Ok(mask.into_pyarray(py))
}

/// Which of the boxes are held around a part (extent `part`, with its
/// context `outer`) for the topology only ([`parts::is_around`]).
#[pyfunction]
pub fn _around_of<'py>(
    py: Python<'py>,
    bounds: PyReadonlyArray2<'py, f64>,
    part: (f64, f64, f64, f64),
    outer: (f64, f64, f64, f64),
) -> PyResult<Bound<'py, PyArray1<bool>>> {
    let (part, outer) = (rect(part), rect(outer));
    let mask: Vec<bool> = rects(&bounds)?
        .iter()
        .map(|r| {
            r.as_ref()
                .is_some_and(|r| parts::is_around(r, &part, &outer))
        })
        .collect();
    Ok(mask.into_pyarray(py))
}

/// The extent of a part and its context's boxes ([`parts::outer`]).
#[pyfunction]
pub fn _outer(
    part: (f64, f64, f64, f64),
    context: PyReadonlyArray2<'_, f64>,
) -> PyResult<(f64, f64, f64, f64)> {
    let part = rect(part);
    let boxes = rects(&context)?;
    let o = parts::outer(&part, boxes.iter().flatten());
    Ok((o.min().x, o.min().y, o.max().x, o.max().y))
}

/// The tolerance smoothing takes when none is given, for data whose extent
/// is `(xmin, ymin, xmax, ymax)` ([`bzspline_geo::default_tolerance_of`]).
#[pyfunction]
#[must_use]
pub fn _default_tolerance(xmin: f64, ymin: f64, xmax: f64, ymax: f64) -> f64 {
    bzspline_geo::default_tolerance_of([xmin, ymin], [xmax, ymax])
}

/// Every junction of the coverage the groups make, and its extent.
#[pyfunction]
pub fn _nodes_of<'py>(py: Python<'py>, groups: Vec<Group<'py>>) -> PyResult<PyNodes<'py>> {
    crate::guard(|| {
        let (geoms, _) = gather(&groups)?;
        let chains = coverage_chains(&geoms);
        let nodes = py
            .allow_threads(|| Nodes::of(&chains))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let p: Vec<[f64; 2]> = nodes.positions().iter().map(|c| [c.x, c.y]).collect();
        Ok((coords_array(py, &p)?, extent_tuple(nodes.extent())))
    })
}

/// Meetings for Python: positions, pair hashes, junction flags.
type PyMeetings<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray1<bool>>,
);

/// How one part meets each of its positions: positions `(m, 2)`, the hash of
/// the pair they are met between, whether each is a junction of the part.
#[pyfunction]
pub fn _meetings<'py>(py: Python<'py>, groups: Vec<Group<'py>>) -> PyResult<PyMeetings<'py>> {
    crate::guard(|| {
        let (geoms, _) = gather(&groups)?;
        let chains = coverage_chains(&geoms);
        let met = py
            .allow_threads(|| meetings(&chains))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let p: Vec<[f64; 2]> = met.iter().map(|m| [m.position.x, m.position.y]).collect();
        let between: Vec<u64> = met.iter().map(|m| m.between.unwrap_or(0)).collect();
        let junction: Vec<bool> = met.iter().map(|m| m.between.is_none()).collect();
        Ok((
            coords_array(py, &p)?,
            between.into_pyarray(py),
            junction.into_pyarray(py),
        ))
    })
}

/// The nodes where parts meet, from all parts' meetings concatenated.
#[pyfunction]
pub fn _across<'py>(
    py: Python<'py>,
    positions: PyReadonlyArray2<'py, f64>,
    between: PyReadonlyArray1<'py, u64>,
    junction: PyReadonlyArray1<'py, bool>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    crate::guard(|| {
        let (p, b, j) = (
            positions.as_array(),
            between.as_array(),
            junction.as_array(),
        );
        if p.ncols() != 2 || p.nrows() != b.len() || b.len() != j.len() {
            return Err(PyValueError::new_err(
                "meetings: positions (m, 2), between (m,) and junction (m,) must agree",
            ));
        }
        let met: Vec<Meeting> = (0..b.len())
            .map(|i| Meeting {
                position: Coord {
                    x: p[[i, 0]],
                    y: p[[i, 1]],
                },
                between: (!j[i]).then_some(b[i]),
            })
            .collect();
        let nodes = py.allow_threads(|| across(met));
        let out: Vec<[f64; 2]> = nodes.positions().iter().map(|c| [c.x, c.y]).collect();
        coords_array(py, &out)
    })
}

/// Coordinates `(n, d)` and the offsets of their lines or rings.
type PySpans<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<i64>>);

/// Smooths every line or ring of a ragged array on its own, in the
/// coordinates' dimension (2 or 3: z carried along as a curve in space):
/// `coords` `(n, d)`, `spans` the offsets of the lines or rings (`closed`
/// for rings), `owner` each one's geometry in the caller's array (for
/// errors); `geographic` as for [`_smooth_ragged`]. Returns the new
/// coordinates and spans.
#[pyfunction]
#[pyo3(signature = (coords, spans, owner, closed, tolerance=None, through=false, keep_angle=None, alpha=0.5, geographic=false))]
#[allow(clippy::too_many_arguments)] // the keyword arguments of bzspline.geo.smooth
pub fn _smooth_spans<'py>(
    py: Python<'py>,
    coords: PyReadonlyArray2<'py, f64>,
    spans: PyReadonlyArray1<'py, i64>,
    owner: PyReadonlyArray1<'py, i64>,
    closed: bool,
    tolerance: Option<f64>,
    through: bool,
    keep_angle: Option<f64>,
    alpha: f64,
    geographic: bool,
) -> PyResult<PySpans<'py>> {
    crate::guard(|| {
        let view = coords.as_array();
        let dim = view.ncols();
        let flat: Vec<f64> = view.iter().copied().collect();
        let offs = spans.as_array().to_vec();
        let ranges = self::spans(&offs, view.nrows())?;
        let owner = owner.as_array().to_vec();
        if owner.len() != ranges.len() {
            return Err(PyValueError::new_err("one owner per line or ring"));
        }
        let opts = smooth_options(tolerance, through, keep_angle, alpha, geographic)?;
        let out = py.allow_threads(|| -> Result<(Vec<f64>, Vec<i64>), Fault> {
            let (mut out, mut ends) = (Vec::with_capacity(flat.len() * 4), vec![0i64]);
            for (j, &(a, b)) in ranges.iter().enumerate() {
                let s = smooth_line(&flat[a * dim..b * dim], dim, closed, &opts)
                    .map_err(|e| Fault::of(owner[j], format!("geometry {}: {e}", owner[j])))?;
                out.extend_from_slice(&s);
                ends.push((out.len() / dim.max(1)) as i64);
            }
            Ok((out, ends))
        });
        let (out, ends) = out?;
        let rows = out.len() / dim.max(1);
        let arr = numpy::ndarray::Array2::from_shape_vec((rows, dim), out)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok((arr.into_pyarray(py), ends.into_pyarray(py)))
    })
}
