//! Solving a curve: surveying its points, the parameter steps, the control
//! points of a curve through its points, the open and closed systems
//! (factored once, solved once a coordinate) and the pieces.

use super::{norm, norm_of, norm_parts, Curve, ParamKind};
use crate::error::Error;
use crate::fast::{self, Piece};
use crate::method::{alpha_terms, piece_coefs_with, through_controls, ClosedSystem, OpenSystem};
use crate::method::{one_alpha, power_of_two_scale, scale_for_max};
use crate::pieces::Pieces;
use crate::traits::ParamCurve;
use crate::validate::{check_knots, Alphas};

/// One pass over points of `dim` coordinates: `None` if a coordinate is not
/// finite, else whether two consecutive points are equal; `maxes` (`dim`
/// long) gets the largest magnitude of each coordinate.
pub(super) fn survey(points: &[f64], dim: usize, maxes: &mut [f64]) -> Option<bool> {
    pub(super) fn fixed<const D: usize>(points: &[f64], maxes: &mut [f64]) -> Option<bool> {
        let (pts, _) = points.as_chunks::<D>();
        let mut mx = [0.0f64; D];
        let mut finite = true;
        let mut repeat = false;
        let mut prev = [f64::NAN; D];
        for p in pts {
            for c in 0..D {
                let a = p[c].abs();
                // Branch-free: NaN fails `a <= MAX`, infinities too.
                finite &= a <= f64::MAX;
                mx[c] = if a > mx[c] { a } else { mx[c] };
            }
            repeat |= *p == prev;
            prev = *p;
        }
        for (m, x) in maxes.iter_mut().zip(mx) {
            *m = x;
        }
        finite.then_some(repeat)
    }
    match dim {
        1 => fixed::<1>(points, maxes),
        2 => fixed::<2>(points, maxes),
        3 => fixed::<3>(points, maxes),
        _ => {
            maxes.fill(0.0);
            if points.iter().any(|v| !v.is_finite()) {
                return None;
            }
            let mut repeat = false;
            let mut prev: Option<&[f64]> = None;
            for p in points.chunks_exact(dim.max(1)) {
                for (m, v) in maxes.iter_mut().zip(p) {
                    *m = m.max(v.abs());
                }
                repeat |= prev == Some(p);
                prev = Some(p);
            }
            Some(repeat)
        }
    }
}

/// The parameter step of the leg from `a` to `b` in units of `chord_scale`
/// (before multiplying by the curve's `knot_unit`): the chord length, or its
/// square root for centripetal parameters.
pub(super) fn chord_step(
    kind: &ParamKind,
    a: &[f64],
    b: &[f64],
    chord_scale: f64,
    buf: &mut [f64],
) -> f64 {
    leg_step(
        *kind == ParamKind::Centripetal,
        a,
        b,
        1.0 / chord_scale,
        buf,
    )
}

/// [`chord_step`] with `inv = 1 / chord_scale` formed by the caller: every
/// leg of a curve takes the same operations in the same order.
#[inline(always)]
fn leg_step(centripetal: bool, a: &[f64], b: &[f64], inv: f64, buf: &mut [f64]) -> f64 {
    step_of(centripetal, norm(leg(a, b, inv, buf)))
}

/// The vector of the leg from `a` to `b` in units of `1 / inv`, in `buf`.
#[inline(always)]
fn leg<'b>(a: &[f64], b: &[f64], inv: f64, buf: &'b mut [f64]) -> &'b [f64] {
    for ((d, x), y) in buf.iter_mut().zip(a).zip(b) {
        *d = y * inv - x * inv;
    }
    buf
}

/// The parameter step of a leg of chord length `len`.
#[inline(always)]
fn step_of(centripetal: bool, len: f64) -> f64 {
    if centripetal {
        len.sqrt()
    } else {
        len
    }
}

/// [`leg_step`] of the legs `a` to `b` and `b` to `c`: the same operations,
/// each square root of the two legs taken in one instruction.
#[inline(always)]
fn two_leg_steps<const D: usize>(
    centripetal: bool,
    [a, b, c]: [&[f64; D]; 3],
    inv: f64,
) -> [f64; 2] {
    let (mut u, mut v) = ([0.0; D], [0.0; D]);
    let (ma, sa) = norm_parts(leg(a, b, inv, &mut u));
    let (mb, sb) = norm_parts(leg(b, c, inv, &mut v));
    let root = [sa.unwrap_or(0.0).sqrt(), sb.unwrap_or(0.0).sqrt()];
    [norm_of(ma, root[0]), norm_of(mb, root[1])].map(|len| step_of(centripetal, len))
}

/// The parameter step of every leg into `steps` (one a leg; the leg from
/// the last point to the first closes a closed curve), [`chord_step`]'s:
/// in stretches side by side on large curves ([`fast::chunks::each`]),
/// each step from its own two points. Points of one to three coordinates
/// go through code for their number (the same operations).
fn chord_steps(kind: &ParamKind, points: &[f64], dim: usize, chord_scale: f64, steps: &mut [f64]) {
    let (centripetal, inv) = (*kind == ParamKind::Centripetal, 1.0 / chord_scale);
    match dim {
        1 => steps_of::<1>(centripetal, points, inv, steps),
        2 => steps_of::<2>(centripetal, points, inv, steps),
        3 => steps_of::<3>(centripetal, points, inv, steps),
        _ => {
            let n = points.len() / dim;
            each_stretch(n, steps, dim, |buf, first, out| {
                for (k, step) in (first..).zip(out.iter_mut()) {
                    let j = (k + 1) % n;
                    let (a, b) = (
                        &points[k * dim..(k + 1) * dim],
                        &points[j * dim..(j + 1) * dim],
                    );
                    *step = leg_step(centripetal, a, b, inv, buf);
                }
            });
        }
    }
}

/// [`chord_steps`] of points of `D` coordinates.
fn steps_of<const D: usize>(centripetal: bool, points: &[f64], inv: f64, steps: &mut [f64]) {
    let (pts, _) = points.as_chunks::<D>();
    let n = pts.len();
    each_stretch(n, steps, 0, |_, first, out| {
        let Some(from) = pts.get(first..) else {
            return;
        };
        let buf = &mut [0.0; D];
        // Two legs at a time, then the one left over and the leg that
        // closes a closed curve.
        let mut done = 0;
        for (w, o) in from.windows(3).step_by(2).zip(out.chunks_exact_mut(2)) {
            let [x, y] = two_leg_steps(centripetal, [&w[0], &w[1], &w[2]], inv);
            (o[0], o[1]) = (x, y);
            done += 2;
        }
        for (k, step) in (first + done..).zip(out.iter_mut().skip(done)) {
            let (Some(a), Some(b)) = (pts.get(k), pts.get(k + 1).or(pts.first())) else {
                return;
            };
            *step = leg_step(centripetal, a, b, inv, buf);
        }
    });
}

/// Runs `f(buf, first, out)` on stretches of `steps` (`out` the steps of
/// legs `first..`), side by side on large curves of `n` points; `buf` holds
/// `dim` numbers.
fn each_stretch(
    n: usize,
    steps: &mut [f64],
    dim: usize,
    f: impl Fn(&mut [f64], usize, &mut [f64]) + Sync + Send,
) {
    /// Legs a stretch.
    const STRETCH: usize = 1 << 14;
    let mut jobs: Vec<(usize, &mut [f64])> = steps
        .chunks_mut(STRETCH)
        .enumerate()
        .map(|(i, s)| (i * STRETCH, s))
        .collect();
    fast::chunks::each(
        n,
        &mut jobs,
        || vec![0.0; dim],
        |buf, (first, out)| f(buf, *first, out),
    );
}

/// What [`Curve::solve_into`] solves: validated points (`dim` coordinates a
/// point, flat) with the largest magnitude of each coordinate, the points a
/// builder dropped, the kind of parameters (the parameters themselves when
/// given), checked alphas, and whether the curve passes through the points
/// rather than taking them as its control points.
pub(super) struct Input<'a> {
    pub(super) dim: usize,
    pub(super) closed: bool,
    pub(super) kind: ParamKind,
    pub(super) points: &'a [f64],
    pub(super) maxes: &'a [f64],
    pub(super) dropped: Vec<usize>,
    pub(super) given: Option<&'a [f64]>,
    pub(super) alphas: Alphas<'a>,
    pub(super) through: bool,
}

/// The control points of the curve through `points` at the parameters
/// `knots` (§11): an open curve's system in the fused sweeps (in chunks when
/// long), a closed curve's cyclic one through the same sweeps
/// ([`fast::ring`]) or, when the ring is short, assembled and factored.
/// `None` when a control value leaves the range of a double.
pub(super) fn through_points(
    knots: &[f64],
    points: &[f64],
    dim: usize,
    closed: bool,
    alphas: Alphas<'_>,
) -> Option<Vec<f64>> {
    let (given, uniform) = alphas.parts();
    if !closed {
        return fast::through::curve_controls(knots, points, dim, given, uniform);
    }
    let ring = match dim {
        1 => ring_controls::<1>(knots, points, given, uniform),
        2 => ring_controls::<2>(knots, points, given, uniform),
        3 => ring_controls::<3>(knots, points, given, uniform),
        _ => None,
    };
    if let Some(solved) = ring {
        return solved;
    }
    let widths: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
    let resolved = match uniform {
        Some(a) => vec![a; widths.len()],
        None => given.to_vec(),
    };
    through_controls(&widths, &resolved, points, dim, closed)
}

/// [`fast::ring::closed_controls`] of points of `D` coordinates (flat), each
/// coordinate scaled by the power of two of its largest magnitude.
pub(super) fn ring_controls<const D: usize>(
    knots: &[f64],
    points: &[f64],
    alphas: &[f64],
    uniform: Option<f64>,
) -> Option<Option<Vec<f64>>> {
    let (pts, _) = points.as_chunks::<D>();
    let scale = core::array::from_fn(|c| power_of_two_scale(pts.iter().map(|p| &p[c])));
    let solved = fast::ring::closed_controls::<D>(knots, pts, alphas, uniform, scale)?;
    Some(solved.map(|g| g.into_flattened()))
}

impl Curve {
    /// A curve with no points, to be built into.
    pub(super) fn empty() -> Self {
        Curve {
            closed: false,
            kind: ParamKind::Uniform,
            points: Vec::new(),
            dropped: Vec::new(),
            pieces: Pieces::default(),
            alphas: Vec::new(),
            chord_scale: 1.0,
            knot_unit: 1.0,
            inv_scales: Vec::new(),
            d: Vec::new(),
        }
    }

    /// Parameters for the kind, validates them, and solves into `c`, reusing
    /// its allocations; `c` changes only on success. With `through` the
    /// curve passes through the points: its control points are solved from
    /// them first (§11), and its parameters are then given ones.
    pub(super) fn solve_into(c: &mut Curve, input: Input<'_>) -> Result<(), Error> {
        let Input {
            dim,
            closed,
            kind,
            points,
            maxes,
            dropped,
            given,
            alphas,
            through,
        } = input;
        let n = points.len() / dim;
        let legs = if closed { n } else { n - 1 };
        let mut chord_scale = 1.0;
        let mut knot_unit = 1.0;
        // Parameters other than uniform ones are formed aside and validated
        // before anything in `c` changes.
        let aside: Option<Vec<f64>> = match (&kind, given) {
            (ParamKind::Given, Some(g)) => Some(g.to_vec()),
            (ParamKind::Uniform, _) | (ParamKind::Given, None) => None,
            (ParamKind::Chordal | ParamKind::Centripetal, _) => {
                // The largest magnitude of all the points, from the survey's.
                chord_scale = scale_for_max(maxes.iter().fold(0.0f64, |m, &v| m.max(v)));
                let mut knots = vec![0.0; legs + 1];
                chord_steps(&kind, points, dim, chord_scale, &mut knots[1..]);
                // Summed in order, for the same bits on any number of threads.
                let mut acc = 0.0;
                for k in &mut knots[1..] {
                    acc += *k;
                    *k = acc;
                }
                let unit = if kind == ParamKind::Chordal {
                    chord_scale
                } else {
                    chord_scale.sqrt()
                };
                // Back to the points' units unless the total would overflow.
                if (acc * unit).is_finite() {
                    knot_unit = unit;
                    for k in &mut knots {
                        *k *= unit;
                    }
                }
                Some(knots)
            }
        };
        if let Some(k) = &aside {
            check_knots(k)?;
        }
        let uniform_knots = || (0..=legs).map(|i| i as f64);
        // Through the points: the control points, and the curve is then the
        // one on them at these parameters, given.
        let (mut kind, mut own_maxes) = (kind, Vec::new());
        let controls = if through {
            let uniform: Vec<f64>;
            let knots = match &aside {
                Some(k) => &k[..],
                None => {
                    uniform = uniform_knots().collect();
                    &uniform[..]
                }
            };
            let controls =
                through_points(knots, points, dim, closed, alphas).ok_or(Error::Overflow {
                    what: "a solved control point",
                })?;
            own_maxes.resize(dim, 0.0);
            survey(&controls, dim, &mut own_maxes);
            (kind, chord_scale, knot_unit) = (ParamKind::Given, 1.0, 1.0);
            Some(controls)
        } else {
            None
        };
        let (points, maxes) = match &controls {
            Some(g) => (&g[..], &own_maxes[..]),
            None => (points, maxes),
        };
        // From here on nothing fails.
        let parts = c.pieces.parts_mut();
        match aside {
            Some(k) => *parts.knots = k,
            None => {
                parts.knots.clear();
                parts.knots.extend(uniform_knots());
            }
        }
        c.pieces.knots_changed();
        c.pieces.set_scales(maxes.iter().map(|&m| scale_for_max(m)));
        c.alphas.clear();
        match alphas {
            Alphas::Uniform(a) => c.alphas.resize(legs, a),
            Alphas::PerInterval(a) => c.alphas.extend_from_slice(a),
        }
        c.inv_scales.clear();
        c.inv_scales
            .extend(c.pieces.scales().iter().map(|s| 1.0 / s));
        c.closed = closed;
        c.kind = kind;
        c.dropped = dropped;
        c.chord_scale = chord_scale;
        c.knot_unit = knot_unit;
        // One alpha for every leg: known here, no pass over them to find it.
        c.solve_all(points, alphas.parts().1);
        Ok(())
    }

    /// [`Self::solve_into`] for a new curve.
    #[allow(clippy::too_many_arguments)] // the parts of a curve, validated
    pub(super) fn solve_new(
        dim: usize,
        closed: bool,
        kind: ParamKind,
        points: &[f64],
        dropped: Vec<usize>,
        given: Option<&[f64]>,
        alphas: &[f64],
    ) -> Result<Self, Error> {
        let mut c = Curve::empty();
        let mut maxes = vec![0.0; dim];
        survey(points, dim, &mut maxes);
        let input = Input {
            dim,
            closed,
            kind,
            points,
            maxes: &maxes,
            dropped,
            given,
            alphas: Alphas::PerInterval(alphas),
            through: false,
        };
        Self::solve_into(&mut c, input)?;
        Ok(c)
    }

    /// Makes `points` the curve's points, solves every coordinate and
    /// rebuilds every segment; `uniform` is the one alpha of every leg when
    /// the caller knows it.
    pub(super) fn solve_all(&mut self, points: &[f64], uniform: Option<f64>) {
        let dim = self.dim();
        if !self.closed && (1..=3).contains(&dim) {
            // One fused sweep for all coordinates (the arithmetic of
            // `Spline`'s construction).
            let uniform = uniform.or_else(|| one_alpha(&self.alphas));
            match dim {
                1 => self.solve_fused::<1>(points, uniform),
                2 => self.solve_fused::<2>(points, uniform),
                _ => self.solve_fused::<3>(points, uniform),
            }
            return;
        }
        if self.closed && (1..=3).contains(&dim) {
            let uniform = uniform.or_else(|| one_alpha(&self.alphas));
            let fused = match dim {
                1 => self.solve_ring::<1>(points, uniform),
                2 => self.solve_ring::<2>(points, uniform),
                _ => self.solve_ring::<3>(points, uniform),
            };
            if fused {
                return;
            }
        }
        self.points.clear();
        self.points.extend_from_slice(points);
        let widths: Vec<f64> = self
            .pieces
            .knots()
            .windows(2)
            .map(|w| w[1] - w[0])
            .collect();
        self.solve_general(&widths);
    }

    /// [`Self::solve_all`] one coordinate at a time through the factored
    /// system: closed curves, more than three dimensions, and the reference
    /// the fused sweep is tested against.
    pub(super) fn solve_general(&mut self, widths: &[f64]) {
        let (n, dim) = (self.points.len() / self.dim(), self.dim());
        // The curve's own deviations and pieces are written over, their
        // allocations kept for a rebuild.
        self.d.clear();
        self.d.resize(n * dim, 0.0);
        let mut col = vec![0.0; n];
        let mut dev = Vec::with_capacity(n);
        if self.closed {
            let sys = ClosedSystem::new(widths, &self.alphas);
            dev.resize(n, 0.0);
            for c in 0..dim {
                for (i, v) in col.iter_mut().enumerate() {
                    *v = self.fv(i, c);
                }
                sys.solve(&col, &mut dev);
                for (i, v) in dev.iter().enumerate() {
                    self.d[i * dim + c] = *v;
                }
            }
        } else {
            let sys = OpenSystem::new(widths, &self.alphas);
            for c in 0..dim {
                for (i, v) in col.iter_mut().enumerate() {
                    *v = self.fv(i, c);
                }
                sys.solve(&col, &mut dev);
                for (i, v) in dev.iter().enumerate() {
                    self.d[i * dim + c] = *v;
                }
            }
        }
        // Every segment: the alpha terms formed once per leg (once in all for
        // one alpha), the closing leg of a closed curve last.
        let legs = self.len();
        let mut coefs = core::mem::take(self.pieces.parts_mut().coefs);
        coefs.clear();
        coefs.reserve_exact(legs * dim);
        let uniform = one_alpha(&self.alphas).map(alpha_terms);
        for k in 0..legs {
            let j = if k + 1 == n { 0 } else { k + 1 };
            let terms = uniform.unwrap_or_else(|| alpha_terms(self.alphas[k]));
            let (d0, d1) = (&self.d[k * dim..][..dim], &self.d[j * dim..][..dim]);
            for c in 0..dim {
                let (f0, f1) = (self.fv(k, c), self.fv(j, c));
                coefs.push(Piece(piece_coefs_with(f0, f1, d0[c], d1[c], terms)));
            }
        }
        *self.pieces.parts_mut().coefs = coefs;
    }

    pub(super) fn update_segment(&mut self, k: usize) {
        let (n, dim) = (self.n_points(), self.dim());
        let j = (k + 1) % n;
        let terms = alpha_terms(self.alphas[k]);
        for c in 0..dim {
            let piece = piece_coefs_with(
                self.fv(k, c),
                self.fv(j, c),
                self.d[k * dim + c],
                self.d[j * dim + c],
                terms,
            );
            self.pieces.parts_mut().coefs[k * dim + c] = Piece(piece);
        }
    }

    pub(super) fn n_points(&self) -> usize {
        self.points.len() / self.dim()
    }

    /// [`fast::sweep::build_open_curve`] in `D` dimensions, which also writes the
    /// copy of the points as it goes.
    pub(super) fn solve_fused<const D: usize>(&mut self, points: &[f64], uniform: Option<f64>) {
        let knots = self.pieces.knots();
        let span = knots.last().copied().unwrap_or(0.0) - knots.first().copied().unwrap_or(0.0);
        let ws = fast::inverse_power_of_two(span);
        let inv = core::array::from_fn(|c| self.inv_scales.get(c).copied().unwrap_or(1.0));
        let parts = self.pieces.parts_mut();
        fast::sweep::build_open_curve::<D>(
            parts.knots,
            points,
            inv,
            &self.alphas,
            uniform,
            ws,
            parts.coefs,
            &mut self.d,
            &mut self.points,
        );
    }

    /// [`fast::ring::build_closed_curve`] in `D` dimensions: `false`, and the
    /// curve unchanged, when the ring is too short for it.
    pub(super) fn solve_ring<const D: usize>(
        &mut self,
        points: &[f64],
        uniform: Option<f64>,
    ) -> bool {
        let inv = core::array::from_fn(|c| self.inv_scales.get(c).copied().unwrap_or(1.0));
        let parts = self.pieces.parts_mut();
        fast::ring::build_closed_curve::<D>(
            parts.knots,
            points,
            inv,
            &self.alphas,
            uniform,
            parts.coefs,
            &mut self.d,
            &mut self.points,
        )
    }

    /// Coordinate `c` of knot point `i` (the curve's point at knot `i`) in the
    /// curve's units, from `f`, the scaled control point's coordinate.
    #[inline]
    pub(super) fn knot_coord_with(&self, f: f64, i: usize, c: usize) -> f64 {
        ((f + self.d[i * self.dim() + c]) * self.pieces.scale(c)).clamp(-f64::MAX, f64::MAX)
    }

    /// Coordinate `c` of knot point `i` in the curve's units.
    #[inline]
    pub(super) fn knot_coord(&self, i: usize, c: usize) -> f64 {
        self.knot_coord_with(self.fv(i, c), i, c)
    }

    /// Coordinate `c` of control point `i`, scaled: `P / scale`.
    #[inline]
    pub(super) fn fv(&self, i: usize, c: usize) -> f64 {
        self.points[i * self.dim() + c] * self.inv_scales[c]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::tests::Rng;

    /// Every leg's parameter step, whether its square roots are taken two
    /// legs at a time or one, has the bits of the step formed from its own
    /// two points by the norm's definition: 1 to 4 coordinates, open and
    /// closed, odd and even counts, points over 600 decades and repeated.
    #[test]
    fn leg_steps_have_the_bits_of_each_legs_own_step() {
        let mut rng = Rng(29);
        for dim in 1..=4 {
            for n in [2, 3, 4, 7, 8, 40_001] {
                for mag in [1e-300, 1.0, 1e300] {
                    let mut pts: Vec<f64> = (0..n * dim)
                        .map(|_| mag * (2.0 * rng.next() - 1.0))
                        .collect();
                    // Some legs of zero length.
                    for k in (1..n).step_by(5) {
                        let (a, b) = pts.split_at_mut(k * dim);
                        b[..dim].copy_from_slice(&a[(k - 1) * dim..]);
                    }
                    let max = pts.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    let scale = scale_for_max(max);
                    for kind in [ParamKind::Chordal, ParamKind::Centripetal] {
                        for closed in [false, true] {
                            let legs = if closed { n } else { n - 1 };
                            let mut steps = vec![f64::NAN; legs];
                            chord_steps(&kind, &pts, dim, scale, &mut steps);
                            for (k, got) in steps.iter().enumerate() {
                                let j = (k + 1) % n;
                                let d: Vec<f64> = (0..dim)
                                    .map(|c| pts[j * dim + c] / scale - pts[k * dim + c] / scale)
                                    .collect();
                                let len = norm(&d);
                                let want = if kind == ParamKind::Centripetal {
                                    len.sqrt()
                                } else {
                                    len
                                };
                                assert_eq!(
                                    got.to_bits(),
                                    want.to_bits(),
                                    "dim {dim}, n {n}, {mag:e}, {kind:?}, closed {closed}, leg {k}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}
