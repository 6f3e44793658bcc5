//! Flattening: a polyline within a given distance of a curve.
//!
//! On a segment with local parameter `t` in `[0, 1]`, the chord between the
//! points at `t0` and `t0 + delta` deviates from the curve by at most
//! `delta^2 / 8 * max |r''(t)|` (the interpolation error of a straight line,
//! which holds for vectors as for scalars). `r''` of a cubic is linear in `t`,
//! so its largest norm is at an end of the segment. With
//! `m = ceil(sqrt(max |r''| / (8 tol)))` equal parameter steps per segment every
//! point of the curve is within `tol` of the polyline; this is the fewest equal
//! steps the bound allows. Vertices are points of the curve, and the first and
//! last are the curve's ends exactly.
//!
//! A planar curve through many points often needs fewer vertices than it has
//! knots: where consecutive segments each need one step, the chord from a knot
//! point `A` is extended over as many of them as it can span. Each segment lies
//! in the convex hull of its four Bezier control points and the distance to a
//! line segment is a convex function, so the chord `A B` is within `tol` of the
//! curve between when every control point of the run is; that holds for a
//! control point `p` when `|p - A| <= tol`, or when `B - A` lies within
//! `asin(tol / |p - A|)` of the direction of `p - A` and `|B - A| >= |p - A|`.
//! The cones of allowed directions are intersected as the run grows, so the
//! search is one pass.

use crate::curve::Curve;
use crate::error::{Error, Field};
use crate::spline::{alpha_terms, Spline};

/// The most vertices one flattening may produce; a tolerance that would need
/// more is refused.
pub const MAX_FLATTEN_VERTICES: usize = 1 << 24;

/// Points along a curve, with the parameter of each.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Polyline {
    dim: usize,
    coords: Vec<f64>,
    params: Vec<f64>,
}

impl Polyline {
    pub(crate) fn new(dim: usize, coords: Vec<f64>, params: Vec<f64>) -> Self {
        Polyline {
            dim,
            coords,
            params,
        }
    }

    /// The dimension of the points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Number of vertices.
    #[must_use]
    pub fn len(&self) -> usize {
        self.params.len()
    }

    /// True when there are no vertices.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.params.is_empty()
    }

    /// The vertices, flat, [`Polyline::dim`] numbers each.
    #[must_use]
    pub fn coords(&self) -> &[f64] {
        &self.coords
    }

    /// The curve parameter of each vertex.
    #[must_use]
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// Vertex `i`.
    #[must_use]
    pub fn point(&self, i: usize) -> Option<&[f64]> {
        self.coords.get(i * self.dim..(i + 1) * self.dim)
    }

    /// The vertices as arrays; `None` when `D` is not the dimension.
    #[must_use]
    pub fn to_arrays<const D: usize>(&self) -> Option<Vec<[f64; D]>> {
        if D != self.dim {
            return None;
        }
        Some(
            self.coords
                .chunks_exact(D)
                .map(|c| {
                    let mut a = [0.0; D];
                    a.copy_from_slice(c);
                    a
                })
                .collect(),
        )
    }
}

fn check_tol(tol: f64) -> Result<(), Error> {
    if !tol.is_finite() {
        return Err(Error::NonFinite {
            field: Field::Tolerance,
            index: 0,
            value: tol,
        });
    }
    if tol <= 0.0 {
        return Err(Error::InvalidArgument {
            what: "the flattening tolerance must be positive",
            value: tol,
        });
    }
    Ok(())
}

/// Steps for a segment whose `|r''|` is at most `accel`, for tolerance `tol`
/// (same units). A small margin covers the rounding of the vertices.
fn steps(accel: f64, tol: f64) -> Result<usize, Error> {
    let x = (accel / (8.0 * tol * 0.999)).sqrt();
    // The ceiling by hand (f64::ceil is a library call on baseline x86-64);
    // the comparison also catches NaN.
    let m = if x < MAX_FLATTEN_VERTICES as f64 {
        let m = x as usize;
        m + usize::from((m as f64) < x)
    } else {
        MAX_FLATTEN_VERTICES
    };
    if m >= MAX_FLATTEN_VERTICES {
        return Err(Error::InvalidArgument {
            what:
                "the flattening tolerance is too small for the curve: too many vertices; tolerance",
            value: tol,
        });
    }
    Ok(m.max(1))
}

impl Curve {
    /// A polyline whose distance from the curve is at most `tol` everywhere,
    /// with few vertices (see [`crate::flatten`]): each segment gets the fewest
    /// equal parameter steps that the bound on its second derivative allows,
    /// and in the plane a run of segments that stays within `tol` of one chord
    /// becomes that one chord (so vertices need not fall on the knots). The
    /// first vertex is the start of the curve and the last its end (the start
    /// again for a closed curve), exactly.
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] / [`Error::InvalidArgument`] for a tolerance that is
    /// not a finite positive number, or one so small that more than
    /// [`MAX_FLATTEN_VERTICES`] vertices would be needed.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::closed(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])?;
    /// let p = c.flatten(1e-3)?;
    /// assert_eq!(p.point(0), p.point(p.len() - 1)); // closed
    /// assert!(p.len() > 8);
    /// // Points on a straight line: one chord.
    /// let line = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]])?;
    /// assert_eq!(line.flatten(1e-9)?.len(), 2);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn flatten(&self, tol: f64) -> Result<Polyline, Error> {
        check_tol(tol)?;
        let scaled_tol = tol / self.unit();
        let too_many = || Error::InvalidArgument {
            what:
                "the flattening tolerance is too small for the curve: too many vertices; tolerance",
            value: tol,
        };
        let dim = self.dim();
        let knots = self.knots();
        let mut coords = Vec::with_capacity((self.len() + 1) * dim);
        let mut params = Vec::with_capacity(self.len() + 1);
        coords.extend(self.segment_point(0, 0.0));
        params.push(knots[0]);
        // The alpha terms once for all segments when the alphas are all one.
        let alphas = self.alphas();
        let uniform = alphas
            .first()
            .filter(|&&a| alphas.iter().all(|&b| b == a))
            .map(|&a| alpha_terms(a));
        let mut k = 0;
        while k < self.len() {
            let m = steps(self.accel_bound(k), scaled_tol)?;
            if params.len().saturating_add(m) > MAX_FLATTEN_VERTICES {
                return Err(too_many());
            }
            if m == 1 && dim == 2 {
                // One chord from knot k to the farthest knot it can reach.
                let end = self.chord_run(k, uniform, 0.999 * scaled_tol);
                coords.extend(self.segment_point(end - 1, 1.0));
                params.push(knots[end]);
                k = end;
                continue;
            }
            let h = knots[k + 1] - knots[k];
            for j in 1..=m {
                let t = j as f64 / m as f64;
                coords.extend(self.segment_point(k, t));
                params.push(if j == m {
                    knots[k + 1]
                } else {
                    knots[k] + t * h
                });
            }
            k += 1;
        }
        Ok(Polyline::new(dim, coords, params))
    }

    /// For a planar curve, the last knot `e > k` such that the chord from
    /// knot point `k` to knot point `e` stays within `tol` (in units of
    /// [`Curve::unit`]) of the curve between them. Segment `k` alone always
    /// qualifies (the caller has found that it needs one step). `uniform`
    /// holds the alpha terms when every segment has the same alpha.
    ///
    /// Each segment lies in the convex hull of its Bezier control points, and
    /// the distance to a line segment is convex, so the chord `A B` is close
    /// enough when every control point `p` of the run is: either `|p - A| <=
    /// tol`, or the direction of `B - A` is within `asin(tol / |p - A|)` of
    /// `p - A` (the cone of directions whose ray from `A` passes within `tol` of
    /// `p`) and `|B - A| >= |p - A|` (so `p` projects inside the chord). The
    /// cones are intersected as the run grows: one pass, no square loop.
    fn chord_run(&self, k: usize, uniform: Option<[f64; 4]>, tol: f64) -> usize {
        let alphas = self.alphas();
        let terms = |e: usize| uniform.unwrap_or_else(|| alpha_terms(alphas[e]));
        let rel = [self.unit_rel(0), self.unit_rel(1)];
        let a = self.unit_bezier_2d(k, terms(k), rel)[0];
        let tol2 = tol * tol;
        let mut cone: Option<([f64; 2], [f64; 2])> = None;
        // The largest squared distance from `a` of a control point that
        // constrains the direction.
        let mut reach2 = 0.0f64;
        let mut best = k + 1;
        let mut e = k;
        'run: while e < self.len() {
            let ctrl = self.unit_bezier_2d(e, terms(e), rel);
            for p in &ctrl[1..] {
                let c = [p[0] - a[0], p[1] - a[1]];
                let r2 = c[0] * c[0] + c[1] * c[1];
                if !r2.is_finite() {
                    break 'run;
                }
                if r2 <= tol2 {
                    continue;
                }
                reach2 = reach2.max(r2);
                // `c` turned by -/+ asin(tol / |c|), both scaled by |c|:
                // c sqrt(|c|^2 - tol^2) -/+ perp(c) tol.
                let q = (r2 - tol2).sqrt();
                let right = [c[0] * q + c[1] * tol, c[1] * q - c[0] * tol];
                let left = [c[0] * q - c[1] * tol, c[1] * q + c[0] * tol];
                cone = match cone {
                    None => Some((right, left)),
                    Some(arc) => match intersect_arcs(arc, (right, left)) {
                        Some(x) => Some(x),
                        None => break 'run,
                    },
                };
            }
            let b = ctrl[3];
            let v = [b[0] - a[0], b[1] - a[1]];
            let ok = match cone {
                None => true,
                Some(arc) => v[0] * v[0] + v[1] * v[1] >= reach2 && in_arc(arc, v),
            };
            if ok {
                best = e + 1;
            }
            e += 1;
        }
        best
    }
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Whether the direction `v` lies in the arc from `right` counter-clockwise to
/// `left` (an arc of less than half a turn).
fn in_arc((right, left): ([f64; 2], [f64; 2]), v: [f64; 2]) -> bool {
    cross(right, v) >= 0.0 && cross(v, left) >= 0.0
}

/// The intersection of two arcs of directions, each less than half a turn
/// (so the intersection is one arc or empty).
fn intersect_arcs(
    a: ([f64; 2], [f64; 2]),
    b: ([f64; 2], [f64; 2]),
) -> Option<([f64; 2], [f64; 2])> {
    match (in_arc(a, b.0), in_arc(a, b.1)) {
        (true, true) => Some(b),
        (true, false) => Some((b.0, a.1)),
        (false, true) => Some((a.0, b.1)),
        (false, false) => in_arc(b, a.0).then_some(a),
    }
}

impl Spline {
    /// The graph `(x, S(x))` flattened to a polyline within `tol` of it; see
    /// [`Curve::flatten`]. Vertices' parameters are their abscissas.
    ///
    /// # Errors
    ///
    /// As [`Curve::flatten`].
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Spline;
    /// let s = Spline::new(&[0.0, 1.0, 2.0], &[0.0, 1.0, 0.0])?;
    /// let p = s.flatten(1e-4)?;
    /// assert_eq!(p.point(0), Some(&[0.0, 0.0][..]));
    /// assert_eq!(p.point(p.len() - 1), Some(&[2.0, 0.0][..]));
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn flatten(&self, tol: f64) -> Result<Polyline, Error> {
        check_tol(tol)?;
        let knots = self.knots();
        let mut coords = Vec::new();
        let mut params = Vec::new();
        for k in 0..self.len() {
            let c = self.unit_coefficients(k).unwrap_or([0.0; 4]);
            let accel = (2.0 * c[2]).abs().max((2.0 * c[2] + 6.0 * c[3]).abs());
            let m = steps(accel, tol)?;
            if params.len().saturating_add(m) > MAX_FLATTEN_VERTICES {
                return Err(Error::InvalidArgument {
                    what: "the flattening tolerance is too small for the curve: too many vertices; tolerance",
                    value: tol,
                });
            }
            let h = knots[k + 1] - knots[k];
            for j in usize::from(k > 0)..=m {
                let x = if j == m {
                    knots[k + 1]
                } else {
                    knots[k] + (j as f64 / m as f64) * h
                };
                let y = self.eval(x)?;
                coords.push(x);
                coords.push(y);
                params.push(x);
            }
        }
        Ok(Polyline::new(2, coords, params))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance from `p` to the segment `a`-`b`.
    fn seg_dist(p: &[f64], a: &[f64], b: &[f64]) -> f64 {
        let ab: Vec<f64> = a.iter().zip(b).map(|(a, b)| b - a).collect();
        let ap: Vec<f64> = a.iter().zip(p).map(|(a, p)| p - a).collect();
        let l2: f64 = ab.iter().map(|v| v * v).sum();
        let t = if l2 > 0.0 {
            (ab.iter().zip(&ap).map(|(u, v)| u * v).sum::<f64>() / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        ap.iter()
            .zip(&ab)
            .map(|(v, u)| (v - t * u) * (v - t * u))
            .sum::<f64>()
            .sqrt()
    }

    #[test]
    fn curve_flattening_stays_within_tolerance() {
        let pts = [[0.0, 0.0], [2.0, 3.0], [4.0, -1.0], [5.0, 2.0], [3.0, 5.0]];
        for closed in [false, true] {
            let c = Curve::builder_from(&pts).closed(closed).build().unwrap();
            for tol in [1e-1, 1e-2, 1e-4] {
                let p = c.flatten(tol).unwrap();
                assert_eq!(p.point(0).unwrap(), c.eval(0.0).unwrap().as_slice());
                let (lo, hi) = c.domain();
                assert_eq!(
                    p.point(p.len() - 1).unwrap(),
                    c.eval(hi).unwrap().as_slice()
                );
                let params = p.params();
                let mut worst = 0.0f64;
                for i in 0..=4000 {
                    let s = lo + (hi - lo) * i as f64 / 4000.0;
                    let q = c.eval(s).unwrap();
                    let j = params.partition_point(|&x| x <= s).clamp(1, p.len() - 1);
                    let d = seg_dist(&q, p.point(j - 1).unwrap(), p.point(j).unwrap());
                    worst = worst.max(d);
                }
                assert!(worst <= tol, "tol {tol}: distance {worst}");
                // Not wastefully many vertices: the bound is within a factor of
                // a few of what is needed.
                assert!(worst > tol / 20.0, "tol {tol}: only {worst} reached");
            }
        }
    }

    #[test]
    fn spline_flattening_stays_within_tolerance() {
        let x = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let f = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0];
        let s = Spline::new(&x, &f).unwrap();
        let tol = 1e-3;
        let p = s.flatten(tol).unwrap();
        assert_eq!(p.point(0).unwrap(), &[1.0, 1.0]);
        assert_eq!(p.point(p.len() - 1).unwrap(), &[6.0, 7.0]);
        for i in 0..=5000 {
            let xq = 1.0 + 5.0 * i as f64 / 5000.0;
            let q = [xq, s.eval(xq).unwrap()];
            let j = p
                .params()
                .partition_point(|&v| v <= xq)
                .clamp(1, p.len() - 1);
            let d = seg_dist(&q, p.point(j - 1).unwrap(), p.point(j).unwrap());
            assert!(d <= tol, "at x = {xq}: {d}");
        }
    }

    #[test]
    fn bad_tolerances_are_refused() {
        let c = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]]).unwrap();
        for tol in [0.0, -1.0] {
            assert!(matches!(c.flatten(tol), Err(Error::InvalidArgument { .. })));
        }
        assert!(matches!(
            c.flatten(f64::NAN),
            Err(Error::NonFinite {
                field: Field::Tolerance,
                ..
            })
        ));
        assert!(matches!(
            c.flatten(1e-300),
            Err(Error::InvalidArgument { .. })
        ));
        // A straight planar curve is one chord; in space, one step per segment.
        let line = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]).unwrap();
        assert_eq!(line.flatten(1e-9).unwrap().len(), 2);
        let line = Curve::open(&[[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]).unwrap();
        assert_eq!(line.flatten(1e-9).unwrap().len(), 3);
    }
}
