//! Arc length of a curve, its inverse, and resampling at equal arc-length
//! steps: adaptive Gauss-Legendre quadrature of the speed `|dr/dt|` per segment.
//!
//! Each segment is first cut where its speed turns (the real roots of
//! `r' . r''`, a cubic), and geometrically around each dip of the speed (see
//! `Curve::seg_cuts`), so that near a cusp every piece is about as wide as its
//! distance from it. Each piece is integrated with an 8-point rule, then with
//! the rule on both halves; where the two differ by more than the segment's share of the
//! accuracy, each half is refined with half the tolerance (to a depth of 40, and
//! never below the rounding of the sum). The comparison is trusted only below
//! the first halving (every piece is cut at least into quarters): the rule on
//! a piece and on its halves can agree by accident while both are off by far
//! more than the tolerance. Random curves found cases that each of the two
//! measures alone left wrong (the cuts alone, or the deeper halving alone);
//! see the tests and `proptest-regressions/curves.txt`.

use super::{check_tolerance, dot, norm, Curve};
use crate::error::{Error, Field};
use crate::poly::quadratic_roots;
use crate::polyline::Polyline;
use crate::traits::Arclen;
use crate::traits::ParamCurve;

/// The 8-point Gauss-Legendre rule on `[-1, 1]`: nodes (the roots of the
/// Legendre polynomial P8) and weights, as Newton's method on P8 gives them in
/// doubles (the test `gauss_legendre_rule` redoes the computation, and checks
/// them against the published values and the rule's exactness). A constant
/// rather than computed at first use: nothing to initialise, and no cosine
/// in the WebAssembly module.
const GL_X: [f64; GL_N] = [
    0.9602898564975363,
    0.7966664774136268,
    0.525532409916329,
    0.18343464249564978,
    -0.18343464249564978,
    -0.525532409916329,
    -0.7966664774136268,
    -0.9602898564975363,
];
const GL_W: [f64; GL_N] = [
    0.10122853629037679,
    0.22238103445337445,
    0.3137066458778874,
    0.362683783378362,
    0.362683783378362,
    0.3137066458778874,
    0.22238103445337445,
    0.10122853629037679,
];

const GL_N: usize = 8;
const MAX_DEPTH: u32 = 40;
/// Halvings before the two estimates' agreement is trusted (with the graded
/// cuts, one was enough on every case the tests hold; two cost twice as much).
const MIN_DEPTH: u32 = 1;

impl Curve {
    /// Speed `|dr/dt|` of segment `k` at local `t`, in units of the largest scale.
    fn speed(&self, k: usize, t: f64, buf: &mut [f64]) -> f64 {
        self.local(k, t, 1, buf);
        norm(buf)
    }

    fn gl(&self, k: usize, a: f64, b: f64, buf: &mut [f64]) -> f64 {
        let (x, w) = (&GL_X, &GL_W);
        let (m, r) = (0.5 * (a + b), 0.5 * (b - a));
        let mut s = 0.0;
        for (xi, wi) in x.iter().zip(w) {
            s += wi * self.speed(k, m + r * xi, buf);
        }
        s * r
    }

    /// Length of segment `k` from local `a` to `b`, in units of the largest scale, with
    /// absolute error about `tol` (same units).
    /// The length of segment `k` between local parameters `a <= b`, to `tol`
    /// (in units of [`Curve::unit`]).
    fn seg_length(&self, k: usize, a: f64, b: f64, tol: f64) -> f64 {
        self.seg_length_cut(k, a, b, tol, &self.seg_cuts(k))
    }

    /// [`Curve::seg_length`] with the segment's [`Curve::seg_cuts`] given, so
    /// that repeated lengths in one segment find them once.
    fn seg_length_cut(&self, k: usize, a: f64, b: f64, tol: f64, cuts: &[f64]) -> f64 {
        let mut buf = vec![0.0; self.dim()];
        let inner = cuts.iter().copied().filter(|&t| t > a && t < b);
        let pieces = inner.clone().count() + 1;
        let tol = tol / pieces as f64;
        let mut lo = a;
        let mut total = 0.0;
        for hi in inner.chain(core::iter::once(b)) {
            let whole = self.gl(k, lo, hi, &mut buf);
            total += self.adapt(k, lo, hi, whole, tol, 0, &mut buf);
            lo = hi;
        }
        total
    }

    /// Where segment `k` is cut before integrating, increasing, in `(0, 1)`:
    /// the speed's turning points, and around each minimum `t*` cuts at
    /// `t* - delta 2^j` and `t* + delta 2^j`, where `delta` is the width of the
    /// dip: near a cusp the speed behaves like `sqrt(s^2 + kappa (t - t*)^2)`
    /// with `s = |r'(t*)|` and `kappa = |r''|^2 + r' . r'''`, whose complex
    /// singularities lie `delta = s / sqrt(kappa)` from `t*`. Each piece is
    /// then about as wide as its distance from the dip, where the 8-point rule
    /// converges fast and the halving's estimates can be trusted.
    fn seg_cuts(&self, k: usize) -> Vec<f64> {
        let (turns, nt) = self.speed_turns(k);
        let mut cuts = Vec::new();
        let mut d = [
            vec![0.0; self.dim()],
            vec![0.0; self.dim()],
            vec![0.0; self.dim()],
        ];
        for &t in &turns[..nt] {
            cuts.push(t);
            for (order, buf) in (1..).zip(d.iter_mut()) {
                self.local(k, t, order, buf);
            }
            let kappa = dot(&d[1], &d[1]) + dot(&d[0], &d[2]);
            let delta = norm(&d[0]) / kappa.sqrt();
            // A maximum (kappa < 0) or a dip as wide as the segment: no grading.
            if !(delta.is_finite() && delta > 0.0 && delta < 0.25) {
                continue;
            }
            let mut step = delta;
            while step < 1.0 {
                cuts.extend(
                    [t - step, t + step]
                        .into_iter()
                        .filter(|&c| c > 0.0 && c < 1.0),
                );
                step *= 2.0;
            }
        }
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        cuts
    }

    /// The local parameters in `(0, 1)`, increasing, where the speed of segment
    /// `k` has a turning point: the real roots of `r' . r''`, a cubic (each
    /// coordinate of `r'` is quadratic). Found by bisection on the stretches
    /// where the cubic is monotone.
    fn speed_turns(&self, k: usize) -> ([f64; 3], usize) {
        let dim = self.dim();
        let (mut a3, mut a2, mut a1, mut a0) = (0.0, 0.0, 0.0, 0.0);
        for c in 0..dim {
            let rel = self.pieces.scale(c) / self.pieces.unit();
            let [_, c1, c2, c3] = self.pieces.piece(k, c).map(|v| v * rel);
            a3 += 18.0 * c3 * c3;
            a2 += 18.0 * c2 * c3;
            a1 += 6.0 * c1 * c3 + 4.0 * c2 * c2;
            a0 += 2.0 * c1 * c2;
        }
        let g = |t: f64| ((a3 * t + a2) * t + a1) * t + a0;
        let mut ends = [0.0; 4];
        let mut ne = 1;
        for r in quadratic_roots(3.0 * a3, 2.0 * a2, a1) {
            if r > ends[ne - 1] && r < 1.0 && ne < 3 {
                ends[ne] = r;
                ne += 1;
            }
        }
        ends[ne] = 1.0;
        let mut out = [0.0; 3];
        let mut n = 0;
        for w in ends[..=ne].windows(2) {
            let (mut lo, mut hi) = (w[0], w[1]);
            let (glo, ghi) = (g(lo), g(hi));
            if !(glo.is_finite() && ghi.is_finite()) || glo.signum() == ghi.signum() || glo == 0.0 {
                continue;
            }
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if g(mid).signum() == glo.signum() {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            if n < 3 {
                out[n] = 0.5 * (lo + hi);
                n += 1;
            }
        }
        (out, n)
    }

    #[allow(clippy::too_many_arguments)] // recursion state: segment, interval, estimate, tolerance, depth, scratch
    fn adapt(
        &self,
        k: usize,
        a: f64,
        b: f64,
        whole: f64,
        tol: f64,
        depth: u32,
        buf: &mut [f64],
    ) -> f64 {
        let m = 0.5 * (a + b);
        let l = self.gl(k, a, m, buf);
        let r = self.gl(k, m, b, buf);
        let both = l + r;
        let floor = 8.0 * f64::EPSILON * both.abs();
        // A non-finite estimate cannot improve by subdividing: stop and let the
        // caller report the overflow.
        if !both.is_finite()
            || (depth >= MIN_DEPTH && (both - whole).abs() <= tol.max(floor))
            || depth >= MAX_DEPTH
            || m <= a
            || m >= b
        {
            return both;
        }
        self.adapt(k, a, m, l, tol * 0.5, depth + 1, buf)
            + self.adapt(k, m, b, r, tol * 0.5, depth + 1, buf)
    }

    /// Segment lengths in units of the largest scale, each to `tol` (same units).
    fn seg_lengths(&self, tol: f64) -> Vec<f64> {
        (0..self.len())
            .map(|k| self.seg_length(k, 0.0, 1.0, tol))
            .collect()
    }

    fn check_accuracy(accuracy: f64) -> Result<(), Error> {
        check_tolerance("the accuracy must be positive", accuracy)?;
        if accuracy == 0.0 {
            return Err(Error::InvalidArgument {
                what: "the accuracy must be positive",
                value: accuracy,
            });
        }
        Ok(())
    }

    /// The length of the curve between parameters `a` and `b` (negative when
    /// `b < a`), both inside the domain, with absolute error about `accuracy`.
    ///
    /// # Errors
    ///
    /// As [`Curve::arclen`]; as [`Curve::eval`] for `a` and `b`, except that
    /// a closed curve also refuses them outside its domain.
    pub fn arclen_range(&self, a: f64, b: f64, accuracy: f64) -> Result<f64, Error> {
        Self::check_accuracy(accuracy)?;
        if b < a {
            return self.arclen_range(b, a, accuracy).map(|v| -v);
        }
        let (lo, hi) = self.domain();
        for (i, x) in [a, b].into_iter().enumerate() {
            if !x.is_finite() {
                return Err(Error::NonFinite {
                    field: Field::Query,
                    index: i,
                    value: x,
                });
            }
            if !(lo..=hi).contains(&x) {
                return Err(Error::OutOfDomain {
                    x,
                    min: lo,
                    max: hi,
                });
            }
        }
        let (ka, ta) = self.locate(a)?;
        let (kb, tb) = self.locate(b)?;
        let tol = accuracy / self.pieces.unit() / (kb - ka + 1) as f64;
        let mut total = 0.0;
        for k in ka..=kb {
            let t0 = if k == ka { ta } else { 0.0 };
            let t1 = if k == kb { tb } else { 1.0 };
            if t1 > t0 {
                total += self.seg_length(k, t0, t1, tol);
            }
        }
        self.to_units(total, "the arc length")
    }

    /// Local parameter in segment `k` at which the length from its start is
    /// `target` (in units of the largest scale), to `tol`.
    fn solve_length(&self, k: usize, target: f64, seg_len: f64, tol: f64) -> f64 {
        if target <= 0.0 {
            return 0.0;
        }
        if target >= seg_len {
            return 1.0;
        }
        let mut buf = vec![0.0; self.dim()];
        let cuts = self.seg_cuts(k);
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        let mut t = target / seg_len;
        for _ in 0..100 {
            let f = self.seg_length_cut(k, 0.0, t, tol * 0.5, &cuts) - target;
            if f.abs() <= tol {
                return t;
            }
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let sp = self.speed(k, t, &mut buf);
            let newton = t - f / sp;
            t = if sp > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if hi - lo <= f64::EPSILON {
                break;
            }
        }
        t
    }

    /// The parameter at which the length from the start is `length` (the
    /// inverse of [`Curve::arclen_range`] from the start), to `accuracy` in
    /// length, by safeguarded Newton steps.
    ///
    /// # Errors
    ///
    /// As [`Curve::arclen`]; [`Error::NonFinite`] for a non-finite length and
    /// [`Error::OutOfDomain`] for one outside `[0, arclen]` by more than the
    /// accuracy (a length that close past an end gives that end).
    pub fn param_at_length(&self, length: f64, accuracy: f64) -> Result<f64, Error> {
        let mut v = self.params_for_lengths(|_| vec![length], accuracy)?;
        Ok(v.pop().unwrap_or(self.pieces.knots()[0]))
    }

    /// Parameters at the lengths that `lengths` returns for the total length.
    fn params_for_lengths(
        &self,
        lengths: impl FnOnce(f64) -> Vec<f64>,
        accuracy: f64,
    ) -> Result<Vec<f64>, Error> {
        Self::check_accuracy(accuracy)?;
        // The accuracy is shared: a quarter for the cumulative lengths of the
        // segments before the one found, a quarter for the partial length in
        // it (`solve_length` halves its own half), and half for the stop.
        let tol = accuracy / self.pieces.unit() / (4 * self.len()) as f64;
        let segs = self.seg_lengths(tol);
        let mut cum = Vec::with_capacity(segs.len() + 1);
        let mut acc = 0.0;
        cum.push(0.0);
        for s in &segs {
            acc += s;
            cum.push(acc);
        }
        let total = self.to_units(acc, "the arc length")?;
        let lengths = lengths(total);
        let mut out = Vec::with_capacity(lengths.len());
        for (i, &len) in lengths.iter().enumerate() {
            if !len.is_finite() {
                return Err(Error::NonFinite {
                    field: Field::Query,
                    index: i,
                    value: len,
                });
            }
            // Within the accuracy of the total, a length past either end is
            // taken as that end.
            if !(-accuracy..=total + accuracy).contains(&len) {
                return Err(Error::OutOfDomain {
                    x: len,
                    min: 0.0,
                    max: total,
                });
            }
            let target = len.clamp(0.0, total) / self.pieces.unit();
            let k = cum
                .partition_point(|&c| c <= target)
                .saturating_sub(1)
                .min(self.len() - 1);
            let t = self.solve_length(
                k,
                target - cum[k],
                segs[k],
                0.5 * accuracy / self.pieces.unit(),
            );
            let h = self.pieces.width(k);
            out.push((self.pieces.knots()[k] + t * h).min(self.pieces.knots()[k + 1]));
        }
        Ok(out)
    }

    /// `count >= 2` points at equal arc-length steps from the start to the end
    /// (a closed curve's last point is its first), with their parameters.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for `count < 2`; as [`Curve::arclen`].
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 0.0]])?;
    /// let r = c.resample(5, 1e-9)?;
    /// assert_eq!(r.len(), 5);
    /// assert_eq!(r.point(4), Some(&[2.0, 0.0][..]));
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn resample(&self, count: usize, accuracy: f64) -> Result<Polyline, Error> {
        if count < 2 {
            return Err(Error::InvalidArgument {
                what: "resampling needs at least 2 points",
                value: count as f64,
            });
        }
        let mut params = self.params_for_lengths(
            |total| {
                (0..count)
                    .map(|i| (total * (i as f64 / (count - 1) as f64)).min(total))
                    .collect()
            },
            accuracy,
        )?;
        params[count - 1] = self.domain().1;
        let mut coords = Vec::with_capacity(count * self.dim());
        for &s in &params {
            coords.extend(self.eval(s)?);
        }
        Ok(Polyline::new(self.dim(), coords, params))
    }
}

impl Arclen for Curve {
    /// The length of the whole curve, with absolute error at most about
    /// `accuracy` (adaptive 8-point Gauss-Legendre per segment).
    ///
    /// # Errors
    ///
    /// [`Error::NonFinite`] / [`Error::InvalidArgument`] for an accuracy that is
    /// not a finite positive number; [`Error::Overflow`] when the length exceeds
    /// the range of a double.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Arclen, Curve, DEFAULT_ACCURACY};
    /// // A straight polygon is reproduced exactly.
    /// let c = Curve::open(&[[0.0, 0.0], [3.0, 4.0], [6.0, 8.0]])?;
    /// assert!((c.arclen(DEFAULT_ACCURACY)? - 10.0).abs() < 1e-9);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    fn arclen(&self, accuracy: f64) -> Result<f64, Error> {
        let (lo, hi) = self.domain();
        self.arclen_range(lo, hi, accuracy)
    }
    /// The parameters at the lengths `lengths` from the start (each as
    /// [`Curve::param_at_length`]), measuring the segments once for all.
    ///
    /// # Errors
    ///
    /// As [`Curve::param_at_length`], with the index of the failing length.
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Arclen, Curve, DEFAULT_ACCURACY};
    /// let c = Curve::open(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])?;
    /// let t = c.params_at_lengths(&[0.0, 1.0, 2.0], DEFAULT_ACCURACY)?;
    /// assert!((t[1] - 1.0).abs() < 1e-9 && (t[2] - 2.0).abs() < 1e-9);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    fn params_at_lengths(&self, lengths: &[f64], accuracy: f64) -> Result<Vec<f64>, Error> {
        self.params_for_lengths(|_| lengths.to_vec(), accuracy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Param;

    #[test]
    fn near_cusp_length_is_accurate() {
        // The speed drops to 7.7e-4 near t = 1.511: a near-cusp. Reference:
        // chord sum over 4e6 equal parameter steps, 31.26661399927736 (a lower
        // bound, converged to about 1e-11).
        let pts = [
            [-7.918765702598058, 1.9773139040955061],
            [7.421934851492311, 7.098260581638757],
            [6.242371725800509, 6.287957698500334],
            [-0.6897702028788676, -1.650975371689305],
        ];
        let c = Curve::builder_from(&pts)
            .closed(true)
            .param(Param::Uniform)
            .alphas(&[1.0 / 3.0, 1.0 / 3.0, 0.4099846507336324, 1.0 / 3.0])
            .build()
            .unwrap();
        let want = 31.266_613_999_277_36;
        for acc in [1e-3, 1e-6, 1e-9] {
            let got = c.arclen(acc).unwrap();
            assert!(
                (got - want).abs() <= acc,
                "accuracy {acc}: want {want}, got {got}"
            );
        }
    }

    #[test]
    fn lengths_inside_a_segment_with_a_slow_stretch_are_accurate() {
        // Closed chordal polygons with a segment that slows almost to a stop.
        // In the pentagon the rule on [0, t] and on its halves agreed to 1e-9
        // while both were 3.5e-7 off, so the fifth of seven resampled points
        // was off by 3.7 times the accuracy asked for; in the octagon the dip
        // lies near the start of a segment, and cutting at the turning point
        // alone left that segment's length 4.1e-7 off.
        let pentagon: (&[[f64; 2]], &[f64]) = (
            &[
                [-8.54753126272161, 2.4518449674538143],
                [3.4520555512083644, 5.2849662668241315],
                [-1.669628365333883, -5.902513976858627],
                [0.4575435755105498, 6.460166655974717],
                [9.655154827842903, 4.967097663127298],
            ],
            &[
                2.0 / 3.0,
                0.6601514658376175,
                2.0 / 3.0,
                1.0 / 3.0,
                2.0 / 3.0,
            ],
        );
        let (a, b) = (1.0 / 3.0, 2.0 / 3.0);
        let octagon: (&[[f64; 2]], &[f64]) = (
            &[
                [8.662254766860412, -3.7858126336866884],
                [4.203655687825096, 6.194285021721041],
                [7.849934988596831, -1.1029136185032382],
                [4.475723319057178, -2.9359053821157652],
                [-8.745805297036622, 2.9149606624813558],
                [9.289179537957947, 0.0],
                [-9.547640152884027, -3.631029947942551],
                [-2.7339591080155894, 3.866273394518474],
            ],
            &[a, b, a, b, a, a, a, 0.4222690585812141],
        );
        for (pts, alphas) in [pentagon, octagon] {
            let c = Curve::builder_from(pts)
                .closed(true)
                .param(Param::Chordal)
                .alphas(alphas)
                .build()
                .unwrap();
            let truth = c.arclen(1e-13).unwrap();
            let (lo, _) = c.domain();
            let knots = c.knots();
            for acc in [1e-5, 1e-7, 1e-9] {
                for (k, w) in knots.windows(2).enumerate() {
                    let got = c.arclen_range(w[0], w[1], acc).unwrap();
                    let want = c.arclen_range(w[0], w[1], 1e-14).unwrap();
                    assert!(
                        (got - want).abs() <= acc,
                        "{} points, accuracy {acc}, segment {k}: want {want}, got {got}",
                        pts.len()
                    );
                }
                let r = c.resample(7, acc).unwrap();
                for (i, &s) in r.params().iter().enumerate() {
                    let want = truth * i as f64 / 6.0;
                    let got = c.arclen_range(lo, s, 1e-13).unwrap();
                    assert!(
                        (got - want).abs() <= acc,
                        "{} points, accuracy {acc}, point {i}: want length {want}, got {got}",
                        pts.len()
                    );
                }
            }
        }
    }

    /// The rule by Newton's method on the three-term recurrence of the
    /// Legendre polynomials, from the classical first guesses.
    fn newton_rule() -> ([f64; GL_N], [f64; GL_N]) {
        let n = GL_N;
        let (mut x, mut w) = ([0.0; GL_N], [0.0; GL_N]);
        for i in 0..n {
            let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, z);
                for j in 2..=n {
                    let jf = j as f64;
                    let p2 = ((2.0 * jf - 1.0) * z * p1 - (jf - 1.0) * p0) / jf;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
                let dz = p1 / dp;
                z -= dz;
                if dz.abs() < 1e-16 {
                    break;
                }
            }
            x[i] = z;
            w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
        }
        (x, w)
    }

    #[test]
    // The published values with the digits as printed.
    #[allow(clippy::excessive_precision)]
    fn gauss_legendre_rule() {
        // The constants are the computed rule, bit for bit.
        let (x, w) = newton_rule();
        for i in 0..GL_N {
            assert_eq!(GL_X[i].to_bits(), x[i].to_bits(), "node {i}");
            assert_eq!(GL_W[i].to_bits(), w[i].to_bits(), "weight {i}");
        }
        // The published rule (Abramowitz and Stegun, table 25.4), to 1e-15 (the
        // recurrence leaves the weight of the outer nodes 5e-16 off).
        let published = [
            (0.183_434_642_495_649_804_939, 0.362_683_783_378_361_982_965),
            (0.525_532_409_916_328_985_818, 0.313_706_645_877_887_287_338),
            (0.796_666_477_413_626_739_592, 0.222_381_034_453_374_470_544),
            (0.960_289_856_497_536_231_684, 0.101_228_536_290_376_259_153),
        ];
        for (k, (px, pw)) in published.iter().enumerate() {
            // The nodes run from 1 to -1: the pair of nodes +-px.
            let (i, j) = (GL_N / 2 - 1 - k, GL_N / 2 + k);
            for (node, weight) in [(GL_X[i], GL_W[i]), (-GL_X[j], GL_W[j])] {
                assert!((node - px).abs() <= 1e-15, "node {k}: {node} against {px}");
                assert!(
                    (weight - pw).abs() <= 1e-15,
                    "weight {k}: {weight} against {pw}"
                );
            }
        }
        // An 8-point rule is exact to degree 15.
        for deg in 0..16 {
            let got: f64 = GL_X.iter().zip(&GL_W).map(|(x, w)| w * x.powi(deg)).sum();
            let want = if deg % 2 == 1 {
                0.0
            } else {
                2.0 / f64::from(deg + 1)
            };
            assert!(
                (got - want).abs() < 1e-14,
                "degree {deg}: want {want}, got {got}"
            );
        }
    }

    #[test]
    fn bad_accuracy_and_ranges_are_refused() {
        let c = Curve::builder(&[0.0, 0.0, 1.0, 1.0, 2.0, 0.0], 2)
            .param(Param::Uniform)
            .build()
            .unwrap();
        assert!(c.arclen(0.0).is_err());
        assert!(c.arclen(f64::NAN).is_err());
        assert!(c.arclen_range(-1.0, 1.0, 1e-9).is_err());
        let total = c.arclen(1e-12).unwrap();
        assert!(c.param_at_length(total * 1.01, 1e-9).is_err());
        let end = c.param_at_length(total, 1e-9).unwrap();
        assert!((end - 2.0).abs() < 1e-9, "{end}");
        assert_eq!(c.param_at_length(0.0, 1e-9).unwrap(), 0.0);
        let back = c.arclen_range(1.5, 0.5, 1e-12).unwrap();
        assert!(back < 0.0 && (back + c.arclen_range(0.5, 1.5, 1e-12).unwrap()).abs() < 1e-15);
        assert!(c.resample(1, 1e-9).is_err());
    }
}

#[cfg(test)]
mod overflow_tests {
    use crate::{Arclen, Curve, Error, DEFAULT_ACCURACY};

    #[test]
    fn a_length_beyond_f64_max_is_an_error_not_a_hang() {
        let c = Curve::open(&[[-1.7e308, 0.0], [1.7e308, 1e308], [-1.7e308, -1.7e308]]).unwrap();
        let d = Curve::open(&[[0.0, 0.0], [1e300, 1e300], [2e300, 0.0], [2e300, 3e300]]).unwrap();
        assert!(d.arclen(DEFAULT_ACCURACY).unwrap().is_finite());
        assert!(
            matches!(c.arclen(DEFAULT_ACCURACY), Err(Error::Overflow { .. })),
            "want Overflow, got {:?}",
            c.arclen(DEFAULT_ACCURACY)
        );
    }
}
