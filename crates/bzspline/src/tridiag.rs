//! Tridiagonal solvers (Thomas algorithm).
//!
//! The spline's system is diagonally dominant for every alpha in `[1/3, 2/3]`
//! (`docs/method.md` §5), so Gaussian elimination without pivoting is stable.
//! The matrix does not depend on the right-hand side: a curve in `R^d` factors it
//! once and solves `d` right-hand sides.

/// A tridiagonal matrix factored for repeated solves by the Thomas algorithm.
///
/// Row `i` reads `lower[i] * x[i-1] + diag[i] * x[i] + upper[i] * x[i+1] = r[i]`
/// (`lower[0]` and `upper[n-1]` are ignored).
#[derive(Clone, Debug, Default)]
pub(crate) struct Thomas {
    /// `lower[i]` for the forward sweep.
    lower: Vec<f64>,
    /// Reciprocal of the eliminated pivot of row `i`.
    inv_pivot: Vec<f64>,
    /// Modified super-diagonal `upper[i] / pivot[i]`.
    upper: Vec<f64>,
}

impl Thomas {
    /// Factors the matrix. The three slices must have the same length.
    ///
    /// Returns `None` if a pivot is zero or not finite, which cannot happen for a
    /// diagonally dominant matrix with a strictly dominant first row.
    #[must_use]
    pub(crate) fn factor(lower: &[f64], diag: &[f64], upper: &[f64]) -> Option<Self> {
        let n = diag.len();
        if lower.len() != n || upper.len() != n {
            return None;
        }
        Self::factor_rows(n, |i| (lower[i], diag[i], upper[i]))
    }

    /// Factors the `n`-row matrix whose row `i` is `row(i) = (lower, diag,
    /// upper)`, asking for the rows in order `0, 1, .., n - 1` once each, so
    /// that the caller needs no arrays for them.
    ///
    /// Returns `None` as [`Self::factor`] does.
    pub(crate) fn factor_rows(
        n: usize,
        mut row: impl FnMut(usize) -> (f64, f64, f64),
    ) -> Option<Self> {
        let mut lower = Vec::with_capacity(n);
        let mut inv_pivot = Vec::with_capacity(n);
        let mut up = Vec::with_capacity(n);
        let mut prev_up = 0.0;
        for i in 0..n {
            let (l, d, u) = row(i);
            let pivot = d - if i > 0 { l * prev_up } else { 0.0 };
            if pivot == 0.0 || !pivot.is_finite() {
                return None;
            }
            let inv = 1.0 / pivot;
            lower.push(l);
            inv_pivot.push(inv);
            prev_up = if i + 1 < n { u * inv } else { 0.0 };
            up.push(prev_up);
        }
        Some(Thomas {
            lower,
            inv_pivot,
            upper: up,
        })
    }

    /// Number of unknowns.
    #[must_use]
    pub(crate) fn len(&self) -> usize {
        self.inv_pivot.len()
    }

    /// Solves in place: on entry `rhs` holds the right-hand side, on return the
    /// solution. `rhs.len()` must equal [`Self::len`]; other lengths leave `rhs`
    /// untouched and return `false`.
    pub(crate) fn solve_in_place(&self, rhs: &mut [f64]) -> bool {
        let n = self.len();
        if rhs.len() != n {
            return false;
        }
        if n == 0 {
            return true;
        }
        rhs[0] *= self.inv_pivot[0];
        for i in 1..n {
            rhs[i] = (rhs[i] - self.lower[i] * rhs[i - 1]) * self.inv_pivot[i];
        }
        for i in (0..n - 1).rev() {
            rhs[i] -= self.upper[i] * rhs[i + 1];
        }
        true
    }
}

/// A cyclic tridiagonal matrix factored for repeated solves: the Thomas
/// factorization of a modified matrix plus one Sherman-Morrison correction.
///
/// Row `i` reads `lower[i] * x[i-1] + diag[i] * x[i] + upper[i] * x[i+1] = r[i]`
/// with indices taken modulo `n`, so `lower[0]` couples to `x[n-1]` and
/// `upper[n-1]` to `x[0]`. A closed curve's continuity system has this form.
///
/// With `gamma = -diag[0]`, the matrix is `B + u v^T` where `B` is tridiagonal
/// with `diag[0] - gamma` and `diag[n-1] - lower[0] upper[n-1] / gamma` on the
/// ends of its diagonal, `u = (gamma, 0, .., upper[n-1])` and
/// `v = (1, 0, .., lower[0] / gamma)`. `B` stays diagonally dominant when the
/// cyclic matrix is, so each solve is two Thomas sweeps and one update.
#[derive(Clone, Debug)]
pub(crate) struct CyclicThomas {
    thomas: Thomas,
    /// `B^-1 u`.
    z: Vec<f64>,
    /// `lower[0] / gamma`, the last entry of `v`.
    v_last: f64,
    /// `1 + v . z`.
    denom: f64,
}

impl CyclicThomas {
    /// Factors the cyclic matrix. The three slices must have the same length
    /// `n >= 3`.
    ///
    /// Returns `None` for other lengths, or when a pivot or the
    /// Sherman-Morrison denominator is zero or not finite (which cannot happen
    /// for a strictly diagonally dominant matrix).
    #[must_use]
    pub(crate) fn factor(lower: &[f64], diag: &[f64], upper: &[f64]) -> Option<Self> {
        let n = diag.len();
        if n < 3 || lower.len() != n || upper.len() != n {
            return None;
        }
        let gamma = -diag[0];
        if gamma == 0.0 || !gamma.is_finite() {
            return None;
        }
        let mut d = diag.to_vec();
        d[0] -= gamma;
        d[n - 1] -= lower[0] * upper[n - 1] / gamma;
        let thomas = Thomas::factor(lower, &d, upper)?;
        let mut z = vec![0.0; n];
        z[0] = gamma;
        z[n - 1] = upper[n - 1];
        thomas.solve_in_place(&mut z);
        let v_last = lower[0] / gamma;
        let denom = 1.0 + z[0] + v_last * z[n - 1];
        if denom == 0.0 || !denom.is_finite() {
            return None;
        }
        Some(CyclicThomas {
            thomas,
            z,
            v_last,
            denom,
        })
    }

    /// Number of unknowns.
    #[must_use]
    pub(crate) fn len(&self) -> usize {
        self.z.len()
    }

    /// Solves in place, as [`Thomas::solve_in_place`]: wrong lengths leave `rhs`
    /// untouched and return `false`.
    pub(crate) fn solve_in_place(&self, rhs: &mut [f64]) -> bool {
        let n = self.len();
        if !self.thomas.solve_in_place(rhs) {
            return false;
        }
        let factor = (rhs[0] + self.v_last * rhs[n - 1]) / self.denom;
        for (r, z) in rhs.iter_mut().zip(&self.z) {
            *r -= factor * z;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mul(lower: &[f64], diag: &[f64], upper: &[f64], x: &[f64]) -> Vec<f64> {
        let n = x.len();
        (0..n)
            .map(|i| {
                let mut s = diag[i] * x[i];
                if i > 0 {
                    s += lower[i] * x[i - 1];
                }
                if i + 1 < n {
                    s += upper[i] * x[i + 1];
                }
                s
            })
            .collect()
    }

    #[test]
    fn solves_a_dominant_system() {
        let n = 50;
        let lower: Vec<f64> = (0..n).map(|i| -1.0 - (i % 3) as f64 * 0.1).collect();
        let upper: Vec<f64> = (0..n).map(|i| -0.5 + (i % 5) as f64 * 0.05).collect();
        let diag: Vec<f64> = (0..n).map(|i| 3.0 + (i % 7) as f64).collect();
        let want: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
        let mut x = mul(&lower, &diag, &upper, &want);
        let t = Thomas::factor(&lower, &diag, &upper).expect("dominant");
        assert!(t.solve_in_place(&mut x));
        for (i, (a, b)) in x.iter().zip(&want).enumerate() {
            assert!((a - b).abs() < 1e-12, "x[{i}]: want {b}, got {a}");
        }
    }

    #[test]
    fn rejects_singular_and_wrong_lengths() {
        assert!(Thomas::factor(&[0.0], &[0.0], &[0.0]).is_none());
        assert!(Thomas::factor(&[0.0], &[1.0, 2.0], &[0.0, 0.0]).is_none());
        let t = Thomas::factor(&[0.0, 1.0], &[2.0, 2.0], &[1.0, 0.0]).unwrap();
        let mut wrong = [1.0];
        assert!(!t.solve_in_place(&mut wrong));
        assert_eq!(wrong, [1.0]);
        let mut empty: [f64; 0] = [];
        assert!(Thomas::factor(&[], &[], &[])
            .unwrap()
            .solve_in_place(&mut empty));
    }

    fn mul_cyclic(lower: &[f64], diag: &[f64], upper: &[f64], x: &[f64]) -> Vec<f64> {
        let n = x.len();
        (0..n)
            .map(|i| diag[i] * x[i] + lower[i] * x[(i + n - 1) % n] + upper[i] * x[(i + 1) % n])
            .collect()
    }

    #[test]
    fn solves_a_cyclic_dominant_system() {
        for n in [3, 4, 5, 17, 64] {
            let lower: Vec<f64> = (0..n).map(|i| -1.0 - (i % 3) as f64 * 0.3).collect();
            let upper: Vec<f64> = (0..n).map(|i| -0.7 + (i % 5) as f64 * 0.1).collect();
            let diag: Vec<f64> = (0..n).map(|i| 2.5 + (i % 7) as f64).collect();
            let want: Vec<f64> = (0..n).map(|i| ((i * 37) % 11) as f64 - 5.0).collect();
            let mut x = mul_cyclic(&lower, &diag, &upper, &want);
            let t = CyclicThomas::factor(&lower, &diag, &upper).expect("dominant");
            assert_eq!(t.len(), n);
            assert!(t.solve_in_place(&mut x));
            for (i, (a, b)) in x.iter().zip(&want).enumerate() {
                assert!((a - b).abs() < 1e-12, "n={n} x[{i}]: want {b}, got {a}");
            }
        }
    }

    #[test]
    fn cyclic_rejects_short_and_mismatched() {
        assert!(CyclicThomas::factor(&[1.0; 2], &[4.0; 2], &[1.0; 2]).is_none());
        assert!(CyclicThomas::factor(&[1.0; 3], &[4.0; 4], &[1.0; 4]).is_none());
        assert!(CyclicThomas::factor(&[1.0; 3], &[0.0; 3], &[1.0; 3]).is_none());
        let t = CyclicThomas::factor(&[-1.0; 3], &[4.0; 3], &[-1.0; 3]).unwrap();
        let mut wrong = [1.0; 2];
        assert!(!t.solve_in_place(&mut wrong));
        assert_eq!(wrong, [1.0; 2]);
    }
}
