//! The smoothing spline's optimality system (`docs/method.md` §12) as a
//! symmetric block-tridiagonal matrix, factored by block elimination; solves,
//! and the diagonal of the inverse that the trace of the influence matrix
//! needs, each in O(N).
//!
//! Unknowns per interior knot `k`: the knot value `phi_k`, the deviation `d_k`
//! and the multiplier `m_k` of the continuity row of §11,
//! `c_k = lo_k d_{k-1} + di_k d_k + up_k d_{k+1} - (q_k (phi_{k+1} - phi_k) - p_k (phi_k - phi_{k-1}))`.
//!
//! A leading section of the matrix is the optimality system of a smaller
//! problem, regular exactly when it holds a point of positive weight (§12).
//! So the first block, the *head*, holds `phi_0` and every knot up to the
//! first point of positive weight (knot 1 when `w_0 > 0`), factored densely;
//! every later interior knot is a 3 by 3 block `(phi_k, d_k, m_k)`; and
//! `phi_{N-1}` closes the sequence in a block of its own (padded to 3 by 3
//! with two decoupled unit rows). The head is inverted by Gauss-Jordan with
//! partial pivoting, each 3 by 3 pivot block from its cofactors. A score of
//! `lambda` needs one pass forward (pivots and forward sweeps side by side)
//! and one back (backward sweeps and the trace's recurrence).

// Small fixed-size matrices read best indexed as they are written on paper.
#![allow(clippy::needless_range_loop)]

use crate::lanes::{lane3, lane33, pair3, pair33, Lane, F2};
use crate::method::{alpha_terms, neighbour_weights, through_row};

/// A 3 by 3 block, of `f64` or of lanes ([`Lane`]).
pub(super) type M3<T = f64> = [[T; 3]; 3];

pub(super) fn mul<T: Lane>(a: &M3<T>, b: &M3<T>) -> M3<T> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
    })
}

/// `a * b^T`.
pub(super) fn mul_t<T: Lane>(a: &M3<T>, b: &M3<T>) -> M3<T> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[j][0] + a[i][1] * b[j][1] + a[i][2] * b[j][2])
    })
}

/// `a^T * b`.
pub(super) fn t_mul<T: Lane>(a: &M3<T>, b: &M3<T>) -> M3<T> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[0][i] * b[0][j] + a[1][i] * b[1][j] + a[2][i] * b[2][j])
    })
}

#[inline(always)]
pub(super) fn apply<T: Lane>(a: &M3<T>, v: &[T; 3]) -> [T; 3] {
    let row = |r: &[T; 3]| r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    [row(&a[0]), row(&a[1]), row(&a[2])]
}

#[inline(always)]
pub(super) fn apply_t<T: Lane>(a: &M3<T>, v: &[T; 3]) -> [T; 3] {
    let col = |j: usize| a[0][j] * v[0] + a[1][j] * v[1] + a[2][j] * v[2];
    [col(0), col(1), col(2)]
}

/// `B P` for a link block `B` (five entries, the others zero: see
/// [`Grid::link`]) and any `P`.
#[inline(always)]
pub(super) fn link_mul<T: Lane>(b: &M3<T>, p: &M3<T>) -> M3<T> {
    let comb = |x: T, r: &[T; 3], y: T, t: &[T; 3]| {
        [
            x * r[0] + y * t[0],
            x * r[1] + y * t[1],
            x * r[2] + y * t[2],
        ]
    };
    [
        p[2].map(|v| b[0][2] * v),
        comb(b[1][1], &p[1], b[1][2], &p[2]),
        comb(b[2][0], &p[0], b[2][1], &p[1]),
    ]
}

/// `B v` for a link block `B` (five entries: see [`Grid::link`]): the
/// products with its zeros left out, which leaves every sum as [`apply`]
/// forms it (adding a product with zero changes no finite sum but the sign
/// of a zero one).
#[inline(always)]
fn link_apply<T: Lane>(b: &M3<T>, v: &[T; 3]) -> [T; 3] {
    [
        b[0][2] * v[2],
        b[1][1] * v[1] + b[1][2] * v[2],
        b[2][0] * v[0] + b[2][1] * v[1],
    ]
}

/// `B^T v` for a link block `B`, as [`link_apply`] for [`apply_t`].
#[inline(always)]
fn link_apply_t<T: Lane>(b: &M3<T>, v: &[T; 3]) -> [T; 3] {
    [
        b[2][0] * v[2],
        b[1][1] * v[1] + b[2][1] * v[2],
        b[0][2] * v[0] + b[1][2] * v[1],
    ]
}

/// The pivot block `A - B P B^T` of block elimination: `own` the diagonal
/// block `A`, `link` the block `B` below the previous pivot, `prev` that
/// pivot's inverse `P`. Symmetric: only the upper triangle is formed (from
/// the five entries of `B`, the products with its zeros left out), the
/// lower mirrors it.
#[inline(always)]
pub(super) fn pivot<T: Lane>(mut own: M3<T>, link: &M3<T>, prev: &M3<T>) -> M3<T> {
    let (b02, b11, b12, b20, b21) = (link[0][2], link[1][1], link[1][2], link[2][0], link[2][1]);
    let p = prev;
    // Rows of B P (the entries the upper triangle uses).
    let a0 = [b02 * p[2][0], b02 * p[2][1], b02 * p[2][2]];
    let a1 = [
        b11 * p[1][0] + b12 * p[2][0],
        b11 * p[1][1] + b12 * p[2][1],
        b11 * p[1][2] + b12 * p[2][2],
    ];
    let a20 = b20 * p[0][0] + b21 * p[1][0];
    let a21 = b20 * p[0][1] + b21 * p[1][1];
    own[0][0] -= a0[2] * b02;
    own[0][1] -= a0[1] * b11 + a0[2] * b12;
    own[0][2] -= a0[0] * b20 + a0[1] * b21;
    own[1][1] -= a1[1] * b11 + a1[2] * b12;
    own[1][2] -= a1[0] * b20 + a1[1] * b21;
    own[2][2] -= a20 * b20 + a21 * b21;
    own[1][0] = own[0][1];
    own[2][0] = own[0][2];
    own[2][1] = own[1][2];
    own
}

/// One step back of the recurrence for the diagonal blocks of the inverse:
/// from `zm = Z_{b+1}`, the link block `B_{b+1}` below pivot `b` and that
/// pivot's inverse, `(Z_{b+1} L, Z_b)` with `L = B_{b+1} S_b^-1` and
/// `Z_b = S_b^-1 + L^T Z_{b+1} L`.
#[inline(always)]
fn inverse_block<T: Lane>(link: &M3<T>, inv: &M3<T>, zm: &M3<T>) -> (M3<T>, M3<T>) {
    let l = link_mul(link, inv);
    let zl = mul(zm, &l);
    let mut z = t_mul(&l, &zl);
    for i in 0..3 {
        for j in 0..3 {
            z[i][j] += inv[i][j];
        }
    }
    (zl, z)
}

/// Inverts the `n x n` row-major matrix `a` into `inv` by Gauss-Jordan with
/// partial pivoting (destroying `a`); `false` when a pivot vanishes.
fn invert(a: &mut [f64], n: usize, inv: &mut [f64]) -> bool {
    inv[..n * n].fill(0.0);
    for i in 0..n {
        inv[i * n + i] = 1.0;
    }
    let norm = a[..n * n].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for col in 0..n {
        let mut p = col;
        for r in col + 1..n {
            if a[r * n + col].abs() > a[p * n + col].abs() {
                p = r;
            }
        }
        let big = a[p * n + col].abs();
        if !(big > norm * 1e-300 && big.is_finite()) {
            return false;
        }
        if p != col {
            for j in 0..n {
                a.swap(p * n + j, col * n + j);
                inv.swap(p * n + j, col * n + j);
            }
        }
        let piv = 1.0 / a[col * n + col];
        for j in 0..n {
            a[col * n + j] *= piv;
            inv[col * n + j] *= piv;
        }
        for r in 0..n {
            let f = a[r * n + col];
            if r != col && f != 0.0 {
                for j in 0..n {
                    a[r * n + j] -= f * a[col * n + j];
                    inv[r * n + j] -= f * inv[col * n + j];
                }
            }
        }
    }
    true
}

/// The inverse of a symmetric 3 by 3 matrix from its cofactors (each a 2 by
/// 2 determinant, so a diagonal scaling of the matrix scales them alike and
/// does not cost accuracy); where the determinant cancels, by
/// [`invert3_pivoting`] (lane by lane for several lanes).
#[inline(always)]
pub(super) fn invert3<T: Pivoting>(m: &M3<T>) -> Option<M3<T>> {
    let [[a, b, c], [_, d, e], [_, _, f]] = *m;
    let c00 = d * f - e * e;
    let c01 = c * e - b * f;
    let c02 = b * e - c * d;
    let det = a * c00 + b * c01 + c * c02;
    let size = T::abs(a * c00) + T::abs(b * c01) + T::abs(c * c02);
    if !T::cofactors_hold(det, size) {
        return T::pivoting(m);
    }
    let r = T::splat(1.0) / det;
    let c11 = a * f - c * c;
    let c12 = b * c - a * e;
    let c22 = a * d - b * b;
    Some([
        [c00 * r, c01 * r, c02 * r],
        [c01 * r, c11 * r, c12 * r],
        [c02 * r, c12 * r, c22 * r],
    ])
}

/// What [`invert3`] needs beyond arithmetic: the test of its cofactors and
/// the pivoting inverse where they fail.
pub(super) trait Pivoting: Lane {
    fn abs(self) -> Self;
    /// Whether the cofactors' determinant `det` stands clear of rounding
    /// beside `size`, in every lane.
    fn cofactors_hold(det: Self, size: Self) -> bool;
    /// [`invert3_pivoting`], in every lane; `None` when any lane's fails.
    fn pivoting(m: &M3<Self>) -> Option<M3<Self>>;
}

impl Pivoting for f64 {
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline(always)]
    fn cofactors_hold(det: f64, size: f64) -> bool {
        det.abs() > 1e-8 * size && det.is_finite()
    }
    fn pivoting(m: &M3) -> Option<M3> {
        invert3_pivoting(m)
    }
}

impl Pivoting for F2 {
    #[inline(always)]
    fn abs(self) -> F2 {
        F2(self.0.map(f64::abs))
    }
    #[inline(always)]
    fn cofactors_hold(det: F2, size: F2) -> bool {
        f64::cofactors_hold(det.0[0], size.0[0]) && f64::cofactors_hold(det.0[1], size.0[1])
    }
    #[cold]
    fn pivoting(m: &M3<F2>) -> Option<M3<F2>> {
        // Each lane as it goes alone: the cofactors where they hold.
        Some(pair33(&invert3(&lane33(m, 0))?, &invert3(&lane33(m, 1))?))
    }
}

/// The inverse of a 3 by 3 matrix by Gauss-Jordan with partial pivoting,
/// unrolled; `None` when a pivot vanishes.
#[cold]
#[inline(never)]
fn invert3_pivoting(m: &M3) -> Option<M3> {
    let norm = m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut a = *m;
    let mut inv = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for col in 0..3 {
        let mut p = col;
        for r in col + 1..3 {
            if a[r][col].abs() > a[p][col].abs() {
                p = r;
            }
        }
        let big = a[p][col].abs();
        if !(big > norm * 1e-300 && big.is_finite()) {
            return None;
        }
        a.swap(p, col);
        inv.swap(p, col);
        let piv = 1.0 / a[col][col];
        for j in 0..3 {
            a[col][j] *= piv;
            inv[col][j] *= piv;
        }
        for r in 0..3 {
            if r != col {
                let f = a[r][col];
                for j in 0..3 {
                    a[r][j] -= f * a[col][j];
                    inv[r][j] -= f * inv[col][j];
                }
            }
        }
    }
    Some(inv)
}

/// The continuity row of an interior knot: `(lo, di, up)` of §11 and the
/// neighbour weights `p`, `q`.
#[derive(Clone, Copy, Default)]
pub(super) struct Row {
    pub(super) lo: f64,
    pub(super) di: f64,
    pub(super) up: f64,
    pub(super) p: f64,
    pub(super) q: f64,
}

/// A factored optimality system, open or closed: what the fit and its
/// search for `lambda` ask of it.
pub(crate) trait System {
    /// Factors for `lambda` (normalised units); `false` when singular.
    fn factor(&mut self, lambda: f64) -> bool;
    /// The knot values and deviations of the data `y`, one a point.
    fn solve(&mut self, y: &[f64], phi: &mut [f64], d: &mut [f64]);
    /// The trace of the influence matrix.
    fn trace(&self) -> f64;
    /// [`System::trace`], with its bits, and the posterior covariances a
    /// [`super::Posterior`] keeps, one a knot (a system may form both in
    /// one pass).
    fn trace_and_covariances(&self) -> (f64, Vec<[f64; 7]>);
    /// What one score of `lambda` needs: factors for it, solves for the knot
    /// values of each coordinate `ys[c]` into `phis[c]` (of length N, as the
    /// data) and returns the trace; `None` when singular. `d` is scratch.
    fn evaluate(
        &mut self,
        lambda: f64,
        ys: &[&[f64]],
        phis: &mut [Vec<f64>],
        d: &mut Vec<f64>,
    ) -> Option<f64> {
        evaluate_in_turn(self, lambda, ys, phis, d)
    }
    /// [`System::evaluate`] of `lambdas[0]` into `phis[0]` and of
    /// `lambdas[1]` into `phis[1]`, with the bits of each in turn (a
    /// system may take both at once).
    fn evaluate_two(
        &mut self,
        lambdas: [f64; 2],
        ys: &[&[f64]],
        phis: [&mut [Vec<f64>]; 2],
        d: &mut Vec<f64>,
    ) -> [Option<f64>; 2] {
        evaluate_apart(self, lambdas, ys, phis, d)
    }
}

/// [`System::evaluate_two`] by [`System::evaluate`] of each in turn.
fn evaluate_apart<S: System + ?Sized>(
    system: &mut S,
    lambdas: [f64; 2],
    ys: &[&[f64]],
    [pa, pb]: [&mut [Vec<f64>]; 2],
    d: &mut Vec<f64>,
) -> [Option<f64>; 2] {
    [
        system.evaluate(lambdas[0], ys, pa, d),
        system.evaluate(lambdas[1], ys, pb, d),
    ]
}

/// [`System::evaluate`] by [`System::factor`], [`System::solve`] and
/// [`System::trace`] in turn.
fn evaluate_in_turn<S: System + ?Sized>(
    system: &mut S,
    lambda: f64,
    ys: &[&[f64]],
    phis: &mut [Vec<f64>],
    d: &mut Vec<f64>,
) -> Option<f64> {
    if !system.factor(lambda) {
        return None;
    }
    for (y, phi) in ys.iter().zip(phis.iter_mut()) {
        d.resize(y.len(), 0.0);
        system.solve(y, phi, d);
    }
    Some(system.trace())
}

impl System for Factored<'_> {
    fn factor(&mut self, lambda: f64) -> bool {
        Factored::factor(self, lambda)
    }
    fn solve(&mut self, y: &[f64], phi: &mut [f64], d: &mut [f64]) {
        Factored::solve(self, y, phi, d);
    }
    fn trace(&self) -> f64 {
        Factored::trace(self)
    }
    fn trace_and_covariances(&self) -> (f64, Vec<[f64; 7]>) {
        Factored::trace_and_covariances(self)
    }
    fn evaluate(
        &mut self,
        lambda: f64,
        ys: &[&[f64]],
        phis: &mut [Vec<f64>],
        d: &mut Vec<f64>,
    ) -> Option<f64> {
        match ys.len() {
            1 => self.evaluate_fused::<1>(lambda, ys, phis),
            2 => self.evaluate_fused::<2>(lambda, ys, phis),
            3 => self.evaluate_fused::<3>(lambda, ys, phis),
            _ => evaluate_in_turn(self, lambda, ys, phis, d),
        }
    }
    fn evaluate_two(
        &mut self,
        lambdas: [f64; 2],
        ys: &[&[f64]],
        phis: [&mut [Vec<f64>]; 2],
        d: &mut Vec<f64>,
    ) -> [Option<f64>; 2] {
        let [pa, pb] = phis;
        let both = match ys.len() {
            // Without two-lane registers a pair costs what two scores do.
            _ if !PAIRED => None,
            1 => self.evaluate_pair::<1>(lambdas, ys, [&mut *pa, &mut *pb]),
            2 => self.evaluate_pair::<2>(lambdas, ys, [&mut *pa, &mut *pb]),
            3 => self.evaluate_pair::<3>(lambdas, ys, [&mut *pa, &mut *pb]),
            _ => None,
        };
        match both {
            Some([a, b]) => [Some(a), Some(b)],
            // Singular for one of them (or many coordinates): each alone.
            None => evaluate_apart(self, lambdas, ys, [pa, pb], d),
        }
    }
}

/// Whether two scores are taken in one pass ([`Factored::evaluate_pair`]):
/// where the target has registers of two doubles (SSE2, NEON, WebAssembly's
/// SIMD). Elsewhere each is scored alone, with the same bits.
const PAIRED: bool = cfg!(any(
    target_arch = "x86_64",
    target_arch = "aarch64",
    all(target_arch = "wasm32", target_feature = "simd128")
));

/// The penalty `int S''^2` of each interval as a form in `(d_k, d_{k+1})`:
/// `[Q00, Q01, Q11]` (§12). `S''` at the interval's ends in its local
/// variable, `e0` and `e1`, is linear in them, and
/// `int_0^1 (e0 (1-t) + e1 t)^2 dt / h^3 = (e0^2 + e0 e1 + e1^2) / (3 h^3)`.
pub(super) fn penalty_forms(widths: &[f64], terms: &[[f64; 4]]) -> Vec<[f64; 3]> {
    widths
        .iter()
        .zip(terms)
        .map(|(&h, &[al, b1, b2, cr])| {
            let e0 = [-2.0 * (3.0 - 2.0 * b2 - al), -2.0 * (2.0 * cr + b1 - 3.0)];
            let e1 = [2.0 * (3.0 - b2 - 2.0 * al), 2.0 * (cr + 2.0 * b1 - 3.0)];
            let c = 1.0 / (3.0 * h * h * h);
            let f = |i: usize, j: usize| {
                c * (e0[i] * e0[j] + 0.5 * (e0[i] * e1[j] + e1[i] * e0[j]) + e1[i] * e1[j])
            };
            [f(0, 0), f(0, 1), f(1, 1)]
        })
        .collect()
}

/// The continuity row of the knot between intervals of widths `hl`, `hr`
/// and alpha terms `left`, `right`.
pub(super) fn continuity_row(hl: f64, hr: f64, left: &[f64; 4], right: &[f64; 4]) -> Row {
    let (p, q) = neighbour_weights(hl, hr);
    let [al, b1, _, _] = *left;
    let [_, _, b2, cr] = *right;
    let (lo, di, up) = through_row(p, q, al, b1, b2, cr);
    Row { lo, di, up, p, q }
}

/// One knot's share of the optimality system apart from `lambda`: its
/// diagonal block and its link block to the knot before (see [`Grid::own`]
/// and [`Grid::link`]), side by side in memory.
#[derive(Clone, Copy, Default)]
struct Knot {
    /// The weight.
    w: f64,
    /// `Q[k][k]` of the penalty `int S''^2 = d^T Q d`.
    q_diag: f64,
    /// `Q[k][k-1]`.
    q_off: f64,
    /// `di` of the knot's continuity row; `lo` and `p` likewise.
    di: f64,
    lo: f64,
    p: f64,
    /// `up` and `q` of the previous knot's continuity row.
    up_prev: f64,
    q_prev: f64,
}

/// One smoothing problem's grid and weights in the normalised units of §12
/// (knots spanning 1, weights of mean 1), with everything that does not
/// depend on `lambda` formed once.
pub(crate) struct Grid {
    /// One a knot.
    knots: Vec<Knot>,
    /// The last knot of the head block.
    head: usize,
}

impl Grid {
    /// `widths` (N - 1), one alpha per interval, one weight per knot, at least
    /// one positive.
    pub(crate) fn new(widths: &[f64], alphas: &[f64], weights: &[f64]) -> Self {
        let n = weights.len();
        let terms: Vec<[f64; 4]> = alphas.iter().map(|&a| alpha_terms(a)).collect();
        let forms = penalty_forms(widths, &terms);
        let mut rows = vec![Row::default(); n];
        for k in 1..n - 1 {
            rows[k] = continuity_row(widths[k - 1], widths[k], &terms[k - 1], &terms[k]);
        }
        let knots = (0..n)
            .map(|k| {
                let interior = k > 0 && k < n - 1;
                let r = rows[k];
                Knot {
                    w: weights[k],
                    q_diag: if interior {
                        forms[k - 1][2] + forms[k][0]
                    } else {
                        0.0
                    },
                    q_off: if k > 1 { forms[k - 1][1] } else { 0.0 },
                    di: r.di,
                    lo: r.lo,
                    p: r.p,
                    up_prev: if k > 0 { rows[k - 1].up } else { 0.0 },
                    q_prev: if k > 0 { rows[k - 1].q } else { 0.0 },
                }
            })
            .collect();
        let first = weights
            .iter()
            .position(|&w| w >= super::NEGLIGIBLE_WEIGHT)
            .unwrap_or(0);
        Grid {
            knots,
            head: first.clamp(1, n - 2),
        }
    }

    fn n(&self) -> usize {
        self.knots.len()
    }

    /// The weight of knot `k`.
    fn w(&self, k: usize) -> f64 {
        self.knots[k].w
    }

    /// The diagonal block of interior knot `k` (or of `phi_{N-1}`, padded,
    /// for `k = N - 1`), for one `lambda` or several side by side.
    #[inline(always)]
    fn own<T: Lane>(&self, k: usize, lambda: T) -> M3<T> {
        let kn = &self.knots[k];
        let (o, i) = (T::splat(0.0), T::splat(1.0));
        if k == self.n() - 1 {
            return [[T::splat(kn.w), o, o], [o, i, o], [o, o, i]];
        }
        let di = T::splat(kn.di);
        [
            [T::splat(kn.w), o, i],
            [o, lambda * T::splat(kn.q_diag), di],
            [i, di, o],
        ]
    }

    /// `H[knot k, knot k-1]`: rows `(phi, d, m)` of knot `k` (or `phi_{N-1}`
    /// and padding for `k = N - 1`), columns those of knot `k - 1`.
    #[inline(always)]
    fn link<T: Lane>(&self, k: usize, lambda: T) -> M3<T> {
        let kn = &self.knots[k];
        let o = T::splat(0.0);
        if k == self.n() - 1 {
            return [[o, o, T::splat(-kn.q_prev)], [o; 3], [o; 3]];
        }
        [
            [o, o, T::splat(-kn.q_prev)],
            [o, lambda * T::splat(kn.q_off), T::splat(kn.up_prev)],
            [T::splat(-kn.p), T::splat(kn.lo), o],
        ]
    }

    /// Size of the head block: `phi_0`, then `(phi, d, m)` of knots `1..=head`.
    fn head_size(&self) -> usize {
        1 + 3 * self.head
    }

    /// The head block, row-major.
    fn head_block(&self, lambda: f64) -> Vec<f64> {
        let sz = self.head_size();
        let mut a = vec![0.0; sz * sz];
        let at = |k: usize, o: usize| 1 + 3 * (k - 1) + o;
        let mut put = |i: usize, j: usize, v: f64| {
            a[i * sz + j] = v;
            a[j * sz + i] = v;
        };
        put(0, 0, self.w(0));
        put(at(1, 2), 0, -self.knots[1].p);
        for k in 1..=self.head {
            let own = self.own(k, lambda);
            for i in 0..3 {
                for j in 0..=i {
                    put(at(k, i), at(k, j), own[i][j]);
                }
            }
            if k > 1 {
                let link = self.link(k, lambda);
                for i in 0..3 {
                    for j in 0..3 {
                        if link[i][j] != 0.0 {
                            put(at(k, i), at(k - 1, j), link[i][j]);
                        }
                    }
                }
            }
        }
        a
    }
}

/// The head block factored for one `lambda`: its inverse, dense.
#[derive(Default)]
struct Head {
    lambda: f64,
    inv: Vec<f64>,
}

impl Head {
    /// Inverts the head block of `grid` for `lambda`. Returns the inverse's
    /// block at the head's last knot, all that the first later pivot needs
    /// of it (that block meets the head through its last knot only:
    /// `S = A - B (S_head^-1)_tail B^T`); `None` when the head is singular.
    fn factor(&mut self, grid: &Grid, lambda: f64) -> Option<M3> {
        self.lambda = lambda;
        let sz = grid.head_size();
        let mut a = grid.head_block(lambda);
        self.inv.clear();
        self.inv.resize(sz * sz, 0.0);
        if !invert(&mut a, sz, &mut self.inv) {
            return None;
        }
        let tail = sz - 3;
        let hi = &self.inv;
        Some([0, 1, 2].map(|i| [0, 1, 2].map(|j| hi[(tail + i) * sz + tail + j])))
    }

    /// The forward sweep through the head for the data `y`: its right-hand
    /// side into `z0` (head-sized), and `S_head^-1 z0` at the head's last
    /// knot, which the next block needs.
    fn forward(&self, g: &Grid, y: &[f64], z0: &mut [f64]) -> [f64; 3] {
        let sz = g.head_size();
        let tail = sz - 3;
        z0.fill(0.0);
        z0[0] = g.w(0) * y[0];
        for k in 1..=g.head {
            z0[1 + 3 * (k - 1)] = g.w(k) * y[k];
        }
        let mut s0z0 = [0.0; 3];
        for (i, v) in s0z0.iter_mut().enumerate() {
            let row = &self.inv[(tail + i) * sz..(tail + i + 1) * sz];
            *v = row.iter().zip(&*z0).map(|(a, b)| a * b).sum();
        }
        s0z0
    }

    /// The backward sweep through the head, from its forward right-hand side
    /// `z0` (spent) and the first later block's solution `next`: the knot
    /// values of knots `0..=head` into `phi`, their deviations into `d` when
    /// asked for.
    fn backward(
        &self,
        g: &Grid,
        z0: &mut [f64],
        next: &[f64; 3],
        phi: &mut [f64],
        d: Option<&mut [f64]>,
    ) {
        let sz = g.head_size();
        let tail = sz - 3;
        let bt = link_apply_t(&g.link(g.head + 1, self.lambda), next);
        for i in 0..3 {
            z0[tail + i] -= bt[i];
        }
        let x = |i: usize| -> f64 {
            self.inv[i * sz..(i + 1) * sz]
                .iter()
                .zip(&*z0)
                .map(|(a, b)| a * b)
                .sum()
        };
        phi[0] = x(0);
        for k in 1..=g.head {
            phi[k] = x(1 + 3 * (k - 1));
        }
        if let Some(d) = d {
            for k in 1..=g.head {
                d[k] = x(2 + 3 * (k - 1));
            }
        }
    }

    /// The trace `tr` of the knots after the head, completed with the head's
    /// share, given `zm`, the inverse's diagonal block of the first later
    /// block.
    fn trace(&self, g: &Grid, zm: &M3, mut tr: f64) -> f64 {
        // L = B (rows of S_head^-1 at its last knot), 3 x size;
        // (Z_head)_ii = (S_head^-1)_ii + l_i^T Z l_i for column l_i of L.
        let sz = g.head_size();
        let tail = sz - 3;
        let b = g.link(g.head + 1, self.lambda);
        let phis = std::iter::once(0).chain((1..=g.head).map(|k| 1 + 3 * (k - 1)));
        let knot = |i: usize| if i == 0 { 0 } else { (i - 1) / 3 + 1 };
        for i in phis {
            let col: [f64; 3] = [0, 1, 2].map(|r| {
                (0..3)
                    .map(|c| b[r][c] * self.inv[(tail + c) * sz + i])
                    .sum()
            });
            let zl = apply(zm, &col);
            let quad: f64 = (0..3).map(|r| col[r] * zl[r]).sum();
            tr += g.w(knot(i)) * (self.inv[i * sz + i] + quad);
        }
        tr
    }
}

/// The pivot inverses of the knots after the head and the forward sweep's
/// right-hand sides there, block by block (each block's coordinates in
/// turn), of one `lambda` or of several side by side, their lanes
/// interleaved: one set of buffers serves scores taken alone and in pairs,
/// grown to the larger and never shrunk.
#[derive(Default)]
struct Sweeps {
    inv: Vec<f64>,
    z: Vec<f64>,
}

/// A block of lanes from its place in a buffer of [`Sweeps`].
#[inline(always)]
fn load3<T: Lane>(s: &[f64]) -> [T; 3] {
    std::array::from_fn(|i| T::load(&s[i * T::LANES..(i + 1) * T::LANES]))
}

#[inline(always)]
fn store3<T: Lane>(v: &[T; 3], s: &mut [f64]) {
    for (x, s) in v.iter().zip(s.chunks_exact_mut(T::LANES)) {
        x.store(s);
    }
}

#[inline(always)]
fn load33<T: Lane>(s: &[f64]) -> M3<T> {
    std::array::from_fn(|i| load3(&s[3 * i * T::LANES..3 * (i + 1) * T::LANES]))
}

#[inline(always)]
fn store33<T: Lane>(m: &M3<T>, s: &mut [f64]) {
    for (r, s) in m.iter().zip(s.chunks_exact_mut(3 * T::LANES)) {
        store3(r, s);
    }
}

/// `v` grown to `n` values (never shrunk: its room serves every width).
fn at_least(v: &mut Vec<f64>, n: usize) {
    if v.len() < n {
        v.resize(n, 0.0);
    }
}

impl Sweeps {
    /// The forward sweep after the head for the data `ys`, `sz` holding each
    /// one's `S_head^-1 z0` at the head's last knot ([`Head::forward`]):
    /// the right-hand sides `z_b = r_b - B_b S_{b-1}^-1 z_{b-1}` into `z`.
    /// With `FACTOR` the pivot inverses are formed on the way (`prev` the
    /// head inverse's block at its last knot, from [`Head::factor`]), else
    /// those kept are used. `false` when a pivot is singular.
    #[inline(always)]
    fn forward<T: Pivoting, const D: usize, const FACTOR: bool>(
        &mut self,
        g: &Grid,
        lambda: T,
        ys: [&[f64]; D],
        mut sz: [[T; 3]; D],
        mut prev: M3<T>,
    ) -> bool {
        let (n, first) = (g.n(), g.head + 1);
        let (bi, bz) = (9 * T::LANES, 3 * T::LANES);
        let blocks = n - first;
        at_least(&mut self.z, D * blocks * bz);
        if FACTOR {
            at_least(&mut self.inv, blocks * bi);
        }
        let ys = ys.map(|y| &y[..n]);
        for b in 0..blocks {
            let k = first + b;
            let link = g.link(k, lambda);
            let inv = &mut self.inv[b * bi..(b + 1) * bi];
            let si = if FACTOR {
                let Some(si) = invert3(&pivot(g.own(k, lambda), &link, &prev)) else {
                    return false;
                };
                store33(&si, inv);
                prev = si;
                si
            } else {
                load33(inv)
            };
            let zs = &mut self.z[D * b * bz..D * (b + 1) * bz];
            for c in 0..D {
                let lz = link_apply(&link, &sz[c]);
                let zb = [T::splat(g.w(k) * ys[c][k]) - lz[0], -lz[1], -lz[2]];
                sz[c] = apply(&si, &zb);
                store3(&zb, &mut zs[c * bz..(c + 1) * bz]);
            }
        }
        true
    }

    /// The backward sweep after the head, from the right-hand sides in `z`:
    /// `x_b = S_b^-1 (z_b - B_{b+1}^T x_{b+1})`, the knot values of
    /// coordinate `c` in lane `l` into `phis[c * T::LANES + l]` (and the
    /// first one's deviations into `d` when given). With `TRACE`, beside it
    /// the recurrence for the inverse's diagonal blocks, `Z_b = S_b^-1 +
    /// L^T Z_{b+1} L` with `L = B_{b+1} S_b^-1`, summing the trace of the
    /// knots after the head. Returns the first later block's solutions (for
    /// [`Head::backward`]), and its `Z` with that sum (for [`Head::trace`]).
    #[inline(always)]
    fn backward<T: Pivoting, const D: usize, const TRACE: bool>(
        &self,
        g: &Grid,
        lambda: T,
        phis: &mut [&mut [f64]],
        mut d: Option<&mut [f64]>,
    ) -> ([[T; 3]; D], (M3<T>, T)) {
        let (n, first) = (g.n(), g.head + 1);
        let (bi, bz) = (9 * T::LANES, 3 * T::LANES);
        let last = n - first - 1;
        let inv_at = |b: usize| load33::<T>(&self.inv[b * bi..(b + 1) * bi]);
        let z_at = |b: usize, c: usize| load3::<T>(&self.z[(D * b + c) * bz..(D * b + c + 1) * bz]);
        let mut next = [[T::splat(0.0); 3]; D];
        let mut put = |c: usize, k: usize, v: T| {
            for l in 0..T::LANES {
                phis[c * T::LANES + l][k] = v.lane(l);
            }
        };
        // Knot N - 1: phi_{N-1} and padding.
        let inv = inv_at(last);
        for c in 0..D {
            next[c] = apply(&inv, &z_at(last, c));
            put(c, n - 1, next[c][0]);
        }
        let mut zm = inv;
        let mut tr = if TRACE {
            T::splat(g.w(n - 1)) * zm[0][0]
        } else {
            T::splat(0.0)
        };
        for b in (0..last).rev() {
            let k = first + b;
            let inv = inv_at(b);
            let link = g.link(k + 1, lambda);
            for c in 0..D {
                let mut rhs = z_at(b, c);
                let bt = link_apply_t(&link, &next[c]);
                for i in 0..3 {
                    rhs[i] -= bt[i];
                }
                next[c] = apply(&inv, &rhs);
                put(c, k, next[c][0]);
            }
            if let Some(d) = d.as_deref_mut() {
                d[k] = next[0][1].lane(0);
            }
            if TRACE {
                zm = inverse_block(&link, &inv, &zm).1;
                tr += T::splat(g.w(k)) * zm[0][0];
            }
        }
        (next, (zm, tr))
    }
}

/// The system factored for one `lambda` at a time: the inverse of the head's
/// pivot block and of every later pivot block (the multipliers of the
/// elimination are formed again where they are used). Factoring again for
/// another `lambda` reuses the memory.
pub(crate) struct Factored<'a> {
    grid: &'a Grid,
    head: Head,
    /// The sweeps of scores taken alone and in pairs.
    sweeps: Sweeps,
    /// The head's right-hand sides, one head-sized run a coordinate.
    z0: Vec<f64>,
    /// What a score of two `lambda`s side by side needs beyond one's.
    pair: Option<Box<Pair>>,
}

/// The second lane's head and right-hand sides, of
/// [`Factored::evaluate_pair`].
#[derive(Default)]
struct Pair {
    head: Head,
    z0: Vec<f64>,
}

impl<'a> Factored<'a> {
    /// The system of `grid`, not yet factored.
    pub(crate) fn new(grid: &'a Grid) -> Self {
        Factored {
            grid,
            head: Head {
                lambda: f64::NAN,
                inv: Vec::new(),
            },
            sweeps: Sweeps::default(),
            z0: Vec::new(),
            pair: None,
        }
    }

    /// Factors the system for `lambda` (normalised units); `false` when a
    /// pivot block is singular: the problem has no unique solution.
    pub(crate) fn factor(&mut self, lambda: f64) -> bool {
        let Some(prev) = self.head.factor(self.grid, lambda) else {
            return false;
        };
        self.sweeps
            .forward::<f64, 0, true>(self.grid, lambda, [], [], prev)
    }

    /// Solves for the knot values `phi` and deviations `d` (both length N,
    /// `d` zero at the ends) of the data `y`.
    pub(crate) fn solve(&mut self, y: &[f64], phi: &mut [f64], d: &mut [f64]) {
        let (g, lambda) = (self.grid, self.head.lambda);
        let n = g.n();
        let mut z0 = std::mem::take(&mut self.z0);
        z0.resize(g.head_size(), 0.0);
        let sz = self.head.forward(g, y, &mut z0);
        self.sweeps
            .forward::<f64, 1, false>(g, lambda, [y], [sz], [[0.0; 3]; 3]);
        let (next, _) =
            self.sweeps
                .backward::<f64, 1, false>(g, lambda, &mut [&mut *phi], Some(&mut *d));
        self.head.backward(g, &mut z0, &next[0], phi, Some(d));
        d[0] = 0.0;
        d[n - 1] = 0.0;
        self.z0 = z0;
    }

    /// [`System::evaluate`] for `D` coordinates in one pass forward and one
    /// back: the pivot chain beside the forward sweeps, then the backward
    /// sweeps beside the trace's recurrence, so that their chains of
    /// dependent operations overlap and the pivot inverses are read twice,
    /// not four times. The same operations as [`Factored::factor`],
    /// [`Factored::solve`] and [`Factored::trace`] in turn: the same bits.
    fn evaluate_fused<const D: usize>(
        &mut self,
        lambda: f64,
        ys: &[&[f64]],
        phis: &mut [Vec<f64>],
    ) -> Option<f64> {
        let g = self.grid;
        let size = g.head_size();
        let ys: [&[f64]; D] = std::array::from_fn(|c| ys[c]);
        let prev = self.head.factor(g, lambda)?;
        let mut z0 = std::mem::take(&mut self.z0);
        z0.resize(size * D, 0.0);
        let mut heads = z0.chunks_exact_mut(size);
        let sz = ys.map(|y| {
            self.head
                .forward(g, y, heads.next().expect("a head a coordinate"))
        });
        let factored = self.sweeps.forward::<f64, D, true>(g, lambda, ys, sz, prev);
        let mut phis: Vec<&mut [f64]> = phis.iter_mut().map(Vec::as_mut_slice).collect();
        let trace = factored.then(|| {
            let (next, (zm, tr)) = self
                .sweeps
                .backward::<f64, D, true>(g, lambda, &mut phis, None);
            for (c, z0) in z0.chunks_exact_mut(size).enumerate() {
                self.head.backward(g, z0, &next[c], phis[c], None);
            }
            self.head.trace(g, &zm, tr)
        });
        self.z0 = z0;
        trace
    }

    /// [`Factored::evaluate_fused`] for two `lambdas` at once, each in a
    /// lane of [`F2`]: every score the bits it has alone, in about the
    /// instructions of one. `None` when either is singular (then score each
    /// alone). Leaves the system factored for neither.
    fn evaluate_pair<const D: usize>(
        &mut self,
        lambdas: [f64; 2],
        ys: &[&[f64]],
        phis: [&mut [Vec<f64>]; 2],
    ) -> Option<[f64; 2]> {
        let g = self.grid;
        let size = g.head_size();
        let ys: [&[f64]; D] = std::array::from_fn(|c| ys[c]);
        let pair = self.pair.get_or_insert_with(Box::default);
        let prev = pair33(
            &self.head.factor(g, lambdas[0])?,
            &pair.head.factor(g, lambdas[1])?,
        );
        let (mut z0a, mut z0b) = (std::mem::take(&mut self.z0), std::mem::take(&mut pair.z0));
        z0a.resize(size * D, 0.0);
        z0b.resize(size * D, 0.0);
        let (mut ha, mut hb) = (z0a.chunks_exact_mut(size), z0b.chunks_exact_mut(size));
        let sz = ys.map(|y| {
            let a = self
                .head
                .forward(g, y, ha.next().expect("a head a coordinate"));
            let b = pair
                .head
                .forward(g, y, hb.next().expect("a head a coordinate"));
            pair3(&a, &b)
        });
        let lambda = F2(lambdas);
        let factored = self.sweeps.forward::<F2, D, true>(g, lambda, ys, sz, prev);
        let [pa, pb] = phis;
        let traces = factored.then(|| {
            let mut outs: Vec<&mut [f64]> = Vec::with_capacity(2 * D);
            for (a, b) in pa.iter_mut().zip(pb.iter_mut()) {
                outs.push(a.as_mut_slice());
                outs.push(b.as_mut_slice());
            }
            let (next, (zm, tr)) = self
                .sweeps
                .backward::<F2, D, true>(g, lambda, &mut outs, None);
            for c in 0..D {
                let (za, zb) = (
                    &mut z0a[c * size..(c + 1) * size],
                    &mut z0b[c * size..(c + 1) * size],
                );
                self.head
                    .backward(g, za, &lane3(&next[c], 0), outs[2 * c], None);
                pair.head
                    .backward(g, zb, &lane3(&next[c], 1), outs[2 * c + 1], None);
            }
            [
                self.head.trace(g, &lane33(&zm, 0), tr.lane(0)),
                pair.head.trace(g, &lane33(&zm, 1), tr.lane(1)),
            ]
        });
        self.z0 = z0a;
        pair.z0 = z0b;
        traces
    }

    /// The posterior covariance (over `sigma^2`) of each knot's value and
    /// deviation, and of those of neighbouring knots, from the blocks of the
    /// inverse that the recurrence of [`Factored::trace`] passes through
    /// (`docs/method.md` §13): at knot `k`, `[Z(phi_k, phi_k), Z(phi_k, d_k),
    /// Z(d_k, d_k), Z(phi_k, phi_{k+1}), Z(phi_k, d_{k+1}), Z(d_k, phi_{k+1}),
    /// Z(d_k, d_{k+1})]` (the last four zero at `N - 1`; `d_0 = d_{N-1} = 0`
    /// have none). The off-diagonal blocks follow from `Z L = L^-T D^-1`
    /// being block upper triangular: `Z_{b+1,b} = -Z_{b+1} L_{b+1,b}`.
    /// With them, the trace of [`Factored::trace`], summed from the same
    /// blocks in the same order: its bits.
    pub(crate) fn trace_and_covariances(&self) -> (f64, Vec<[f64; 7]>) {
        let g = self.grid;
        let (lambda, head_inv) = (self.head.lambda, &self.head.inv);
        let inv = |b: usize| load33::<f64>(&self.sweeps.inv[9 * b..9 * (b + 1)]);
        let n = g.n();
        let mut out = vec![[0.0; 7]; n];
        let last = n - g.head - 2;
        let mut zm = inv(last);
        out[n - 1][0] = zm[0][0];
        let mut tr = g.w(n - 1) * zm[0][0];
        for b in (0..last).rev() {
            let k = g.head + 1 + b;
            // Z_{k+1,k} = -Z_{k+1} L: rows knot k+1, columns knot k.
            let cross;
            (cross, zm) = inverse_block(&g.link(k + 1, lambda), &inv(b), &zm);
            out[k] = [
                zm[0][0],
                zm[0][1],
                zm[1][1],
                -cross[0][0],
                -cross[1][0],
                -cross[0][1],
                -cross[1][1],
            ];
            tr += g.w(k) * zm[0][0];
        }
        let tr = self.head.trace(g, &zm, tr);
        // The head: with L = B S_head^-1 (3 x size, B meeting the head's last
        // knot only), Z_head = S_head^-1 + L^T Z L and Z_{head+1,head} = -Z L.
        let sz = g.head_size();
        let tail = sz - 3;
        let b = g.link(g.head + 1, lambda);
        let lcol = |i: usize| -> [f64; 3] {
            [0, 1, 2].map(|r| {
                (0..3)
                    .map(|c| b[r][c] * head_inv[(tail + c) * sz + i])
                    .sum()
            })
        };
        let cols: Vec<[f64; 3]> = (0..sz).map(lcol).collect();
        let zl: Vec<[f64; 3]> = cols.iter().map(|c| apply(&zm, c)).collect();
        let z = |i: usize, j: usize| -> f64 {
            head_inv[i * sz + j] + (0..3).map(|r| cols[i][r] * zl[j][r]).sum::<f64>()
        };
        // Positions of phi_k and d_k in the head (d_0 has none).
        let phi_at = |k: usize| if k == 0 { 0 } else { 1 + 3 * (k - 1) };
        let d_at = |k: usize| (k > 0).then(|| 2 + 3 * (k - 1));
        let zz = |a: Option<usize>, c: Option<usize>| match (a, c) {
            (Some(a), Some(c)) => z(a, c),
            _ => 0.0,
        };
        for k in 0..=g.head {
            let (p, d) = (Some(phi_at(k)), d_at(k));
            out[k][0] = zz(p, p);
            out[k][1] = zz(p, d);
            out[k][2] = zz(d, d);
            if k < g.head {
                let (p1, d1) = (Some(phi_at(k + 1)), d_at(k + 1));
                out[k][3] = zz(p, p1);
                out[k][4] = zz(p, d1);
                out[k][5] = zz(d, p1);
                out[k][6] = zz(d, d1);
            } else {
                // Against knot head + 1: -(Z L)[row of knot head + 1][column].
                let at = |i: Option<usize>, r: usize| i.map_or(0.0, |i| -zl[i][r]);
                out[k][3] = at(p, 0);
                out[k][4] = if g.head + 1 == n - 1 { 0.0 } else { at(p, 1) };
                out[k][5] = at(d, 0);
                out[k][6] = if g.head + 1 == n - 1 { 0.0 } else { at(d, 1) };
            }
        }
        (tr, out)
    }

    /// The trace of the influence matrix, `sum_j w_j (H^-1)[phi_j, phi_j]`,
    /// from the diagonal blocks of the inverse, `Z_b = S_b^-1 + L_{b+1}^T
    /// Z_{b+1} L_{b+1}` with `L_{b+1} = B_{b+1} S_b^-1`, without forming any
    /// other part of it.
    pub(crate) fn trace(&self) -> f64 {
        let (_, (zm, tr)) =
            self.sweeps
                .backward::<f64, 0, true>(self.grid, self.head.lambda, &mut [], None);
        self.head.trace(self.grid, &zm, tr)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::rng;

    /// A random problem of `seed`: grids of random and many-decade widths,
    /// random and extreme alphas, weights with zeros (heads longer than one
    /// knot), one to four coordinates of data.
    fn case(seed: u64) -> (Grid, Vec<Vec<f64>>) {
        let mut next = rng(seed);
        let n = 3 + (next() * 60.0) as usize + if seed.is_multiple_of(7) { 3000 } else { 0 };
        let widths: Vec<f64> = (0..n - 1)
            .map(|_| {
                if seed % 3 == 1 {
                    10f64.powf(-6.0 * next())
                } else {
                    0.5 + next()
                }
            })
            .collect();
        let span: f64 = widths.iter().sum();
        let widths: Vec<f64> = widths.iter().map(|h| h / span).collect();
        let alphas: Vec<f64> = (0..n - 1)
            .map(|_| match seed % 4 {
                0 => 1.0 / 3.0 + next() / 3.0,
                1 => [1.0 / 3.0, 2.0 / 3.0][(next() * 2.0) as usize],
                _ => 0.5,
            })
            .collect();
        let zeros = (seed % 5) as usize;
        let mut w: Vec<f64> = (0..n)
            .map(|k| if k < zeros { 0.0 } else { 0.2 + next() })
            .collect();
        let mean = w.iter().sum::<f64>() / n as f64;
        w.iter_mut().for_each(|v| *v /= mean);
        let grid = Grid::new(&widths, &alphas, &w);
        let dim = 1 + (seed % 4) as usize;
        let ys: Vec<Vec<f64>> = (0..dim)
            .map(|_| (0..n).map(|_| next() - 0.5).collect())
            .collect();
        (grid, ys)
    }

    /// The fused evaluation gives the bits of factoring, solving and taking
    /// the trace in turn, for one to four coordinates, on grids of random
    /// and many-decade widths, random and extreme alphas, weights with zeros
    /// (heads longer than one knot), and lambdas from interpolation to the
    /// straight line.
    #[test]
    fn fused_evaluation_is_factor_solve_trace_bit_for_bit() {
        let mut cases = 0;
        for seed in 0..40u64 {
            let (grid, ys) = case(seed);
            let (n, dim) = (ys[0].len(), ys.len());
            let ys: Vec<&[f64]> = ys.iter().map(Vec::as_slice).collect();
            for t in [-12.0, -7.0, -3.5, -1.0, 0.0, 2.0, 6.0] {
                let lambda = 10f64.powf(t);
                let (mut fused, mut in_turn) = (Factored::new(&grid), Factored::new(&grid));
                let mut a = vec![vec![0.0; n]; dim];
                let mut b = vec![vec![0.0; n]; dim];
                let mut d = Vec::new();
                // Twice, so that reused buffers are exercised too.
                for _ in 0..2 {
                    let ta = System::evaluate(&mut fused, lambda, &ys, &mut a, &mut d);
                    let tb = evaluate_in_turn(&mut in_turn, lambda, &ys, &mut b, &mut d);
                    let (Some(ta), Some(tb)) = (ta, tb) else {
                        assert_eq!(ta.is_some(), tb.is_some(), "seed {seed}, lambda {lambda:e}");
                        continue;
                    };
                    assert_eq!(
                        ta.to_bits(),
                        tb.to_bits(),
                        "trace, seed {seed}, lambda {lambda:e}"
                    );
                    for c in 0..dim {
                        for k in 0..n {
                            assert_eq!(
                                a[c][k].to_bits(),
                                b[c][k].to_bits(),
                                "seed {seed}, lambda {lambda:e}, coordinate {c}, knot {k}"
                            );
                        }
                    }
                    assert!(ta > 0.0 && ta <= n as f64 + 1e-6, "trace {ta}");
                    cases += 1;
                }
            }
        }
        assert!(cases > 400, "{cases} cases compared");
    }

    /// Two lambdas scored at once give each the bits of scoring it alone,
    /// knot values and trace, or `None` alike, for every pair of lambdas
    /// from interpolation to the straight line (the same one twice too).
    #[test]
    fn two_lambdas_at_once_are_each_alone_bit_for_bit() {
        let ts = [-12.0, -7.0, -3.5, -1.0, 0.0, 2.0, 6.0];
        let mut cases = 0;
        for seed in 0..40u64 {
            let (grid, ys) = case(seed);
            let (n, dim) = (ys[0].len(), ys.len());
            let ys: Vec<&[f64]> = ys.iter().map(Vec::as_slice).collect();
            let mut two = Factored::new(&grid);
            let mut d = Vec::new();
            for (i, &ta) in ts.iter().enumerate() {
                for &tb in &ts[i..] {
                    let lambdas = [10f64.powf(ta), 10f64.powf(tb)];
                    let mut pa = vec![vec![0.0; n]; dim];
                    let mut pb = vec![vec![0.0; n]; dim];
                    let got = two.evaluate_two(lambdas, &ys, [&mut pa, &mut pb], &mut d);
                    for (l, (lambda, phis)) in lambdas.iter().zip([&pa, &pb]).enumerate() {
                        let mut alone = Factored::new(&grid);
                        let mut want = vec![vec![0.0; n]; dim];
                        let t = System::evaluate(&mut alone, *lambda, &ys, &mut want, &mut d);
                        let at = format!("seed {seed}, lambdas {lambdas:?}, lane {l}");
                        assert_eq!(got[l].map(f64::to_bits), t.map(f64::to_bits), "{at}");
                        if t.is_some() {
                            for c in 0..dim {
                                for k in 0..n {
                                    assert_eq!(
                                        phis[c][k].to_bits(),
                                        want[c][k].to_bits(),
                                        "{at}, {c}, {k}"
                                    );
                                }
                            }
                            cases += 1;
                        }
                    }
                }
            }
        }
        assert!(cases > 1500, "{cases} cases compared");
    }

    /// The link blocks' products without their zeros are the dense
    /// products, every entry the same number (a zero's sign aside), on the
    /// blocks of random grids (every knot, the last one's padding included)
    /// and random vectors and pivots.
    #[test]
    fn link_products_are_the_dense_ones() {
        let mut next = rng(5);
        let mut cases = 0;
        for seed in 0..20u64 {
            let (grid, _) = case(seed);
            for k in grid.head + 1..grid.n() {
                let lambda = 10f64.powf(12.0 * next() - 9.0);
                let b = grid.link(k, lambda);
                let v: [f64; 3] = std::array::from_fn(|_| next() - 0.5);
                let p: M3 = std::array::from_fn(|_| std::array::from_fn(|_| next() - 0.5));
                let at = format!("seed {seed}, knot {k}");
                assert_eq!(link_apply(&b, &v), apply(&b, &v), "{at}");
                assert_eq!(link_apply_t(&b, &v), apply_t(&b, &v), "{at}");
                assert_eq!(link_mul(&b, &p), mul(&b, &p), "{at}");
                cases += 1;
            }
        }
        assert!(cases > 5000, "{cases} blocks compared");
    }

    /// The trace summed beside the covariances has the bits of the trace
    /// taken alone, and its covariances' diagonal gives it again.
    #[test]
    fn the_trace_beside_the_covariances_is_the_trace() {
        let mut cases = 0;
        for seed in 0..40u64 {
            let (grid, _) = case(seed);
            for t in [-12.0, -7.0, -3.5, -1.0, 0.0, 2.0, 6.0] {
                let mut f = Factored::new(&grid);
                if !f.factor(10f64.powf(t)) {
                    continue;
                }
                let (tr, cov) = f.trace_and_covariances();
                assert_eq!(tr.to_bits(), f.trace().to_bits(), "seed {seed}, t {t}");
                let from_cov: f64 = (0..grid.n()).map(|k| grid.w(k) * cov[k][0]).sum();
                assert!(
                    (from_cov - tr).abs() <= 1e-9 * tr.abs(),
                    "seed {seed}, t {t}: {from_cov} against {tr}"
                );
                cases += 1;
            }
        }
        assert!(cases > 200, "{cases} cases compared");
    }
}
