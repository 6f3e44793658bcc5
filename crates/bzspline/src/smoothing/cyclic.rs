//! The smoothing system of a closed curve (`docs/method.md` §15): every knot
//! interior, its rows and penalty taken modulo N, so the block-tridiagonal
//! matrix of §12 gains corner blocks. Knot 0 is eliminated last as a border:
//! the chain of knots `1 .. N-1` is factored by the same 3 by 3 block
//! elimination, the border's coupling solved through it (three right-hand
//! sides) into a 3 by 3 Schur complement. Solves, the trace and the
//! posterior covariances follow in O(N).

// Small fixed-size matrices read best indexed as they are written on paper.
#![allow(clippy::needless_range_loop)]

use super::system::{
    apply, apply_t, continuity_row, invert3, link_mul, mul, mul_t, penalty_forms, pivot, t_mul,
    Row, System, M3,
};
use crate::method::alpha_terms;

/// One closed smoothing problem's grid and weights in the normalised units
/// of §12, everything that does not depend on `lambda` formed once.
pub(crate) struct CyclicGrid {
    /// One weight per knot (point).
    w: Vec<f64>,
    /// The continuity row of every knot.
    rows: Vec<Row>,
    /// `Q[k][k]`, and `Q[k+1][k]` (indices modulo N), at `k`.
    q_diag: Vec<f64>,
    q_off: Vec<f64>,
}

impl CyclicGrid {
    /// `widths` and `alphas`, one per leg (N, the closing leg last), one
    /// weight per point (N >= 3).
    pub(crate) fn new(widths: &[f64], alphas: &[f64], weights: &[f64]) -> Self {
        let n = weights.len();
        let terms: Vec<[f64; 4]> = alphas.iter().map(|&a| alpha_terms(a)).collect();
        let forms = penalty_forms(widths, &terms);
        let prev = |k: usize| (k + n - 1) % n;
        let rows = (0..n)
            .map(|k| continuity_row(widths[prev(k)], widths[k], &terms[prev(k)], &terms[k]))
            .collect();
        CyclicGrid {
            w: weights.to_vec(),
            rows,
            q_diag: (0..n).map(|k| forms[prev(k)][2] + forms[k][0]).collect(),
            q_off: (0..n).map(|k| forms[k][1]).collect(),
        }
    }

    fn n(&self) -> usize {
        self.w.len()
    }

    /// The diagonal block of knot `k`: rows and columns `(phi_k, d_k, m_k)`.
    fn own(&self, k: usize, lambda: f64) -> M3 {
        let r = self.rows[k];
        [
            [self.w[k], 0.0, 1.0],
            [0.0, lambda * self.q_diag[k], r.di],
            [1.0, r.di, 0.0],
        ]
    }

    /// `H[knot k, knot k-1]` (knot `N - 1` before knot 0).
    fn link(&self, k: usize, lambda: f64) -> M3 {
        let j = (k + self.n() - 1) % self.n();
        let (prev, r) = (self.rows[j], self.rows[k]);
        [
            [0.0, 0.0, -prev.q],
            [0.0, lambda * self.q_off[j], prev.up],
            [-r.p, r.lo, 0.0],
        ]
    }
}

/// The closed system factored for one `lambda` at a time.
pub(crate) struct CyclicFactored<'a> {
    grid: &'a CyclicGrid,
    lambda: f64,
    /// Pivot inverses of the chain, knots `1 ..= N-1` at `k - 1`.
    inv: Vec<M3>,
    /// `U = T^-1 E`: the chain's solution for the border's three columns,
    /// knot `k` at `k - 1` (rows its unknowns, columns the border's).
    u: Vec<M3>,
    /// The inverse of the border's Schur complement `A_0 - E^T U`.
    border: M3,
    /// The forward sweep's right-hand sides, kept between solves.
    z: Vec<[f64; 3]>,
}

impl<'a> CyclicFactored<'a> {
    /// The system of `grid`, not yet factored.
    pub(crate) fn new(grid: &'a CyclicGrid) -> Self {
        CyclicFactored {
            grid,
            lambda: f64::NAN,
            inv: Vec::with_capacity(grid.n() - 1),
            u: Vec::with_capacity(grid.n() - 1),
            border: [[0.0; 3]; 3],
            z: Vec::new(),
        }
    }

    /// Solves the chain `T v = r` in place (`r` of knots `1 ..= N-1`).
    fn chain_solve(&mut self, r: &mut [[f64; 3]]) {
        let g = self.grid;
        let m = r.len();
        // Forward: z_b = r_b - B_b S_{b-1}^-1 z_{b-1}.
        let mut prev_sz = [0.0; 3];
        for b in 0..m {
            if b > 0 {
                let lz = apply(&g.link(b + 1, self.lambda), &prev_sz);
                for i in 0..3 {
                    r[b][i] -= lz[i];
                }
            }
            prev_sz = apply(&self.inv[b], &r[b]);
        }
        // Backward: x_b = S_b^-1 (z_b - B_{b+1}^T x_{b+1}).
        let mut next = [0.0; 3];
        for b in (0..m).rev() {
            let mut rhs = r[b];
            if b + 1 < m {
                let bt = apply_t(&g.link(b + 2, self.lambda), &next);
                for i in 0..3 {
                    rhs[i] -= bt[i];
                }
            }
            next = apply(&self.inv[b], &rhs);
            r[b] = next;
        }
    }

    /// The chain's inverse: its diagonal blocks and the blocks below them,
    /// `(Z_b, Z_{b+1,b})`, by the backward recurrence of §12.
    fn chain_inverse(&self) -> (Vec<M3>, Vec<M3>) {
        let g = self.grid;
        let m = self.inv.len();
        let mut diag = vec![[[0.0; 3]; 3]; m];
        let mut below = vec![[[0.0; 3]; 3]; m];
        diag[m - 1] = self.inv[m - 1];
        for b in (0..m - 1).rev() {
            let l = link_mul(&g.link(b + 2, self.lambda), &self.inv[b]);
            let cross = mul(&diag[b + 1], &l);
            let mut z = t_mul(&l, &cross);
            for i in 0..3 {
                for j in 0..3 {
                    z[i][j] += self.inv[b][i][j];
                    below[b][i][j] = -cross[i][j];
                }
            }
            diag[b] = z;
        }
        (diag, below)
    }
}

/// `a b c^T` for 3 by 3 matrices.
fn sandwich(a: &M3, b: &M3, c: &M3) -> M3 {
    mul_t(&mul(a, b), c)
}

fn add(a: &M3, b: &M3) -> M3 {
    let mut o = *a;
    for i in 0..3 {
        for j in 0..3 {
            o[i][j] += b[i][j];
        }
    }
    o
}

fn neg(a: &M3) -> M3 {
    a.map(|r| r.map(|v| -v))
}

fn transpose(a: &M3) -> M3 {
    let mut o = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            o[i][j] = a[j][i];
        }
    }
    o
}

impl System for CyclicFactored<'_> {
    fn factor(&mut self, lambda: f64) -> bool {
        let g = self.grid;
        let n = g.n();
        self.lambda = lambda;
        self.inv.clear();
        // The chain: S_1 = A_1, S_k = A_k - B_k S_{k-1}^-1 B_k^T.
        let mut prev: Option<M3> = None;
        for k in 1..n {
            let s = match prev {
                Some(p) => pivot(g.own(k, lambda), &g.link(k, lambda), &p),
                None => g.own(k, lambda),
            };
            let Some(si) = invert3(&s) else {
                return false;
            };
            self.inv.push(si);
            prev = Some(si);
        }
        // E: the border's columns, B_1 at knot 1 and B_0^T at knot N-1.
        let (b1, b0) = (g.link(1, lambda), g.link(0, lambda));
        let mut cols = vec![[[0.0; 3]; 3]; n - 1];
        let mut u = vec![[0.0; 3]; n - 1];
        for c in 0..3 {
            u.iter_mut().for_each(|v| *v = [0.0; 3]);
            for i in 0..3 {
                u[0][i] += b1[i][c];
                u[n - 2][i] += b0[c][i];
            }
            self.chain_solve(&mut u);
            for (block, v) in cols.iter_mut().zip(&u) {
                for i in 0..3 {
                    block[i][c] = v[i];
                }
            }
        }
        // S_0 = A_0 - E^T U = A_0 - B_1^T U_1 - B_0 U_{N-1}.
        let mut s0 = g.own(0, lambda);
        let (t1, t0) = (t_mul(&b1, &cols[0]), mul(&b0, &cols[n - 2]));
        for i in 0..3 {
            for j in 0..3 {
                s0[i][j] -= t1[i][j] + t0[i][j];
            }
        }
        // The Schur complement is symmetric up to rounding; invert it so.
        for i in 0..3 {
            for j in 0..i {
                let m = 0.5 * (s0[i][j] + s0[j][i]);
                s0[i][j] = m;
                s0[j][i] = m;
            }
        }
        let Some(border) = invert3(&s0) else {
            return false;
        };
        self.u = cols;
        self.border = border;
        true
    }

    fn solve(&mut self, y: &[f64], phi: &mut [f64], d: &mut [f64]) {
        let g = self.grid;
        let n = g.n();
        let mut v = std::mem::take(&mut self.z);
        v.clear();
        v.extend((1..n).map(|k| [g.w[k] * y[k], 0.0, 0.0]));
        self.chain_solve(&mut v);
        // x_0 = S_0^-1 (r_0 - B_1^T v_1 - B_0 v_{N-1}); x_k = v_k - U_k x_0.
        let (b1, b0) = (g.link(1, self.lambda), g.link(0, self.lambda));
        let (e1, e0) = (apply_t(&b1, &v[0]), apply(&b0, &v[n - 2]));
        let r0 = [
            g.w[0] * y[0] - e1[0] - e0[0],
            -e1[1] - e0[1],
            -e1[2] - e0[2],
        ];
        let x0 = apply(&self.border, &r0);
        phi[0] = x0[0];
        d[0] = x0[1];
        for k in 1..n {
            let ux = apply(&self.u[k - 1], &x0);
            phi[k] = v[k - 1][0] - ux[0];
            d[k] = v[k - 1][1] - ux[1];
        }
        self.z = v;
    }

    fn trace(&self) -> f64 {
        let g = self.grid;
        let (diag, _) = self.chain_inverse();
        let mut tr = g.w[0] * self.border[0][0];
        for k in 1..g.n() {
            let u = &self.u[k - 1];
            // (U S0^-1 U^T)[phi, phi].
            let us = apply(&self.border, &u[0]);
            let quad: f64 = (0..3).map(|j| u[0][j] * us[j]).sum();
            tr += g.w[k] * (diag[k - 1][0][0] + quad);
        }
        tr
    }

    fn trace_and_covariances(&self) -> (f64, Vec<[f64; 7]>) {
        let n = self.grid.n();
        let (diag, below) = self.chain_inverse();
        let s = &self.border;
        // The whole inverse's blocks: Z_00 = S0^-1, Z_k0 = -U_k S0^-1,
        // Z_kk = T^-1_kk + U_k S0^-1 U_k^T, Z_{k+1,k} = T^-1_{k+1,k} + U_{k+1} S0^-1 U_k^T.
        let zk = |k: usize| -> M3 {
            if k == 0 {
                *s
            } else {
                let u = &self.u[k - 1];
                add(&diag[k - 1], &sandwich(u, s, u))
            }
        };
        let entries = |z: &M3, x: &M3| -> [f64; 7] {
            [
                z[0][0], z[0][1], z[1][1], x[0][0], x[1][0], x[0][1], x[1][1],
            ]
        };
        let mut out = Vec::with_capacity(n + 1);
        // Knot 0 and knot 1: X = Z_{1,0}.
        out.push(entries(s, &neg(&mul(&self.u[0], s))));
        for k in 1..n - 1 {
            let x = add(&below[k - 1], &sandwich(&self.u[k], s, &self.u[k - 1]));
            out.push(entries(&zk(k), &x));
        }
        // Knot N-1 and knot N (knot 0 again): the entries want Z_{N, N-1},
        // the transpose of Z_{N-1, 0}.
        let y = neg(&mul(&self.u[n - 2], s));
        out.push(entries(&zk(n - 1), &transpose(&y)));
        out.push([s[0][0], s[0][1], s[1][1], 0.0, 0.0, 0.0, 0.0]);
        (self.trace(), out)
    }
}
