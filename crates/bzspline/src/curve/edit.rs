//! Moving one control point of a curve and updating only what changes.

use super::{check_query, check_tolerance, row, Curve, ParamKind};
use crate::error::Error;
use crate::spline::power_of_two_scale;
use crate::tridiag::{CyclicThomas, Thomas};

impl Curve {
    /// Moves control point `index` to `new_point` and updates the curve,
    /// returning the indices of the knots whose knot point moved by more than
    /// `tol` (largest coordinate change), in increasing order.
    ///
    /// The continuity system is linear, so with uniform or given parameters
    /// (the matrix does not change) the change of the deviations solves the same
    /// system for a right-hand side that is nonzero in at most three rows. It
    /// decays by about 0.1 per knot at alpha 1/2, so it is solved on a window
    /// around `index` that grows until the change at the window's edges is below
    /// `tol`; knots outside the window keep their old deviations (they would
    /// change by less than about `tol`). The window falls back to the whole
    /// curve when it must. With chordal or centripetal parameters, and when the
    /// point changes a coordinate's power-of-two scale, the parameters or the
    /// scaling change too and the curve is solved again in full.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for an index past the last point;
    /// [`Error::LengthMismatch`] / [`Error::NonFinite`] (field
    /// [`Field::Query`]) for a point of the wrong dimension or with a
    /// non-finite coordinate; [`Error::NonFinite`] / [`Error::InvalidArgument`]
    /// for a tolerance that is not finite and non-negative;
    /// [`Error::RepeatedPoint`] / [`Error::RepeatedClosingPoint`] when the new
    /// point equals a neighbour. On error the curve is unchanged.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let pts: Vec<[f64; 2]> = (0..40).map(|i| [i as f64, (i % 2) as f64]).collect();
    /// let mut c = Curve::open(&pts)?;
    /// let changed = c.move_point(20, &[20.0, 5.0], 1e-12)?;
    /// assert!(changed.contains(&20));
    /// assert!(changed.len() < 30); // far knots move by less than 1e-12
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn move_point(
        &mut self,
        index: usize,
        new_point: &[f64],
        tol: f64,
    ) -> Result<Vec<usize>, Error> {
        let (n, dim) = (self.n_points(), self.dim);
        if index >= n {
            return Err(Error::InvalidArgument {
                what: "no control point with this index",
                value: index as f64,
            });
        }
        check_query(new_point, dim)?;
        check_tolerance("the tolerance must not be negative", tol)?;
        let neighbours = [
            (index > 0 || self.closed).then(|| (index + n - 1) % n),
            (index + 1 < n || self.closed).then(|| (index + 1) % n),
        ];
        for nb in neighbours {
            let Some(j) = nb else { continue };
            if self.point(j) == Some(new_point) {
                let (a, b) = (index.min(j), index.max(j));
                return Err(if self.closed && a == 0 && b == n - 1 {
                    Error::RepeatedClosingPoint { last: b }
                } else {
                    Error::RepeatedPoint { index: b }
                });
            }
        }
        let old = self.knot_points();
        let mut points = self.points.clone();
        points[index * dim..(index + 1) * dim].copy_from_slice(new_point);
        let rescaled = (0..dim)
            .any(|c| power_of_two_scale(points.iter().skip(c).step_by(dim)) != self.scales[c]);
        let full = rescaled || matches!(self.kind, ParamKind::Chordal | ParamKind::Centripetal);
        if full {
            let given = (self.kind == ParamKind::Given).then(|| self.knots.clone());
            let rebuilt = Self::solve_new(
                dim,
                self.closed,
                self.kind.clone(),
                points,
                self.dropped.clone(),
                given,
                self.alphas.clone(),
            )?;
            *self = rebuilt;
            let new = self.knot_points();
            return Ok((0..n)
                .filter(|&i| {
                    old[i]
                        .iter()
                        .zip(&new[i])
                        .any(|(a, b)| (a - b).abs() > tol || a.is_nan() != b.is_nan())
                })
                .collect());
        }
        self.points = points;
        let mut touched: Vec<usize> = vec![index];
        for (c, &v) in new_point.iter().enumerate() {
            let inv = 1.0 / self.scales[c];
            let delta = v * inv - self.f[index * dim + c];
            self.f[index * dim + c] = v * inv;
            if delta == 0.0 {
                continue;
            }
            let tol_c = tol * inv;
            for (i, dd) in self.local_change(index, delta, tol_c) {
                self.d[i * dim + c] += dd;
                touched.push(i);
            }
        }
        touched.sort_unstable();
        touched.dedup();
        let mut legs: Vec<usize> = Vec::with_capacity(2 * touched.len());
        for &i in &touched {
            if i < self.len() {
                legs.push(i);
            }
            if i > 0 {
                legs.push(i - 1);
            } else if self.closed {
                legs.push(n - 1);
            }
        }
        legs.sort_unstable();
        legs.dedup();
        for k in legs {
            self.update_segment(k);
        }
        Ok(touched
            .into_iter()
            .filter(|&i| {
                (0..dim).any(|c| {
                    let now = (self.f[i * dim + c] + self.d[i * dim + c]) * self.scales[c];
                    (now - old[i][c]).abs() > tol
                })
            })
            .collect())
    }

    /// Row of the continuity system at knot `i` (interior for an open curve).
    fn system_row(&self, i: usize) -> (f64, f64, f64, f64) {
        let n = self.n_points();
        let l = if i == 0 { n - 1 } else { i - 1 };
        let h = |k: usize| self.knots[k + 1] - self.knots[k];
        row(h(l), h(i), self.alphas[l], self.alphas[i])
    }

    /// The change of the deviations (one coordinate, scaled) when scaled point
    /// `index` moves by `delta`: `(knot, change)` pairs over the window used.
    fn local_change(&self, index: usize, delta: f64, tol: f64) -> Vec<(usize, f64)> {
        let n = self.n_points();
        // Unknowns: knots 1..n-1 (open) or 0..n (closed), the rows of the system.
        let (first, last) = if self.closed {
            (0, n - 1)
        } else {
            (1, n.saturating_sub(2))
        };
        if n < 3 || last < first {
            return Vec::new();
        }
        let count = last - first + 1;
        // Right-hand side change: rows index-1, index, index+1.
        let rhs_at = |i: usize| -> f64 {
            let (_, _, _, p) = self.system_row(i);
            if i == index {
                -delta
            } else if (i + 1) % n == index {
                (1.0 - p) * delta
            } else if (index + 1) % n == i {
                p * delta
            } else {
                0.0
            }
        };
        let mut radius = 8usize;
        loop {
            if 2 * radius + 1 >= count {
                // The whole system.
                let idx: Vec<usize> = (first..=last).collect();
                let (mut lo, mut di, mut up) = (vec![], vec![], vec![]);
                for &i in &idx {
                    let (l, d, u, _) = self.system_row(i);
                    lo.push(l);
                    di.push(d);
                    up.push(u);
                }
                let mut r: Vec<f64> = idx.iter().map(|&i| rhs_at(i)).collect();
                let ok = if self.closed {
                    CyclicThomas::factor(&lo, &di, &up).is_some_and(|s| s.solve_in_place(&mut r))
                } else {
                    Thomas::factor(&lo, &di, &up).is_some_and(|s| s.solve_in_place(&mut r))
                };
                return if ok {
                    idx.into_iter().zip(r).collect()
                } else {
                    Vec::new()
                };
            }
            // Window of unknowns around index (cyclic for a closed curve, clipped
            // for an open one).
            let idx: Vec<usize> = if self.closed {
                (0..=2 * radius)
                    .map(|j| (index + n + j - radius) % n)
                    .collect()
            } else {
                let lo = index.saturating_sub(radius).max(first);
                let hi = (index + radius).min(last);
                (lo..=hi).collect()
            };
            let (mut lo, mut di, mut up) = (vec![], vec![], vec![]);
            for &i in &idx {
                let (l, d, u, _) = self.system_row(i);
                lo.push(l);
                di.push(d);
                up.push(u);
            }
            let mut r: Vec<f64> = idx.iter().map(|&i| rhs_at(i)).collect();
            if !Thomas::factor(&lo, &di, &up).is_some_and(|s| s.solve_in_place(&mut r)) {
                radius = count;
                continue;
            }
            let m = r.len();
            let left_open = self.closed || idx[0] > first;
            let right_open = self.closed || idx[m - 1] < last;
            let edge_ok = (!left_open || r[0].abs() <= tol && r[1.min(m - 1)].abs() <= tol)
                && (!right_open || r[m - 1].abs() <= tol && r[m.saturating_sub(2)].abs() <= tol);
            if edge_ok {
                return idx.into_iter().zip(r).collect();
            }
            radius *= 2;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Param;

    #[test]
    fn move_point_agrees_with_a_fresh_solve() {
        let pts: Vec<[f64; 2]> = (0..200).map(|i| [i as f64, ((i * 7) % 5) as f64]).collect();
        for closed in [false, true] {
            for param in [Param::Uniform, Param::Chordal] {
                let mut c = Curve::builder_from(&pts)
                    .closed(closed)
                    .param(param.clone())
                    .alpha(0.45)
                    .build()
                    .unwrap();
                let old = c.knot_points();
                let mut moved = pts.clone();
                for (idx, p) in [
                    (30usize, [30.5, 2.5]),
                    (0, [-1.0, 3.0]),
                    (199, [200.0, 1.0]),
                ] {
                    moved[idx] = p;
                    let changed = c.move_point(idx, &p, 1e-13).unwrap();
                    assert!(changed.contains(&idx), "{changed:?}");
                    if param == Param::Uniform {
                        assert!(changed.len() < 40, "{changed:?}");
                    }
                    let fresh = Curve::builder_from(&moved)
                        .closed(closed)
                        .param(param.clone())
                        .alpha(0.45)
                        .build()
                        .unwrap();
                    for (i, (a, b)) in c.knot_points().iter().zip(fresh.knot_points()).enumerate() {
                        for j in 0..2 {
                            assert!(
                                (a[j] - b[j]).abs() < 1e-11,
                                "closed {closed} {param:?} knot {i}: want {}, got {}",
                                b[j],
                                a[j]
                            );
                        }
                    }
                    for s in [0.0, 12.3, 29.9, 58.7] {
                        let (a, b) = (c.eval(s).unwrap(), fresh.eval(s).unwrap());
                        assert!((a[0] - b[0]).abs() < 1e-11 && (a[1] - b[1]).abs() < 1e-11);
                    }
                }
                if param == Param::Uniform {
                    // Far knots did not move.
                    let now = c.knot_points();
                    assert_eq!(now[100], old[100]);
                }
            }
        }
        let mut c = Curve::open(&pts).unwrap();
        assert!(matches!(
            c.move_point(3, &pts[4], 0.0),
            Err(Error::RepeatedPoint { index: 4 })
        ));
        assert!(c.move_point(200, &[0.0, 0.0], 0.0).is_err());
        assert!(c.move_point(3, &[0.0], 0.0).is_err());
    }
}
