//! Flattening a curve (see [`crate::flatten`] for the bound on one segment).
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
//! search is one pass. A nearly straight segment, whose inner control points
//! project inside its own chord and lie within `w <= tol / 2` of it, is held
//! by its end points alone with the tolerance `tol - w`; a run gives up a few
//! knots after its last good end.

use super::{norm, Curve};
use crate::error::Error;
use crate::fast::Piece;
use crate::flatten::{check_tol, steps, MAX_FLATTEN_VERTICES};
use crate::polyline::Polyline;
use crate::traits::Flatten;
use crate::traits::ParamCurve;

/// Knots past the last good end of a chord that the chord search tries
/// before it settles for that end.
const PATIENCE: usize = 2;

impl Curve {
    /// [`Curve::flatten`] with every knot point a vertex too (a knot that
    /// the flattening's chords passed over is inserted, at its parameter), so
    /// that a curve through its points ([`crate::CurveBuilder::through`]) keeps
    /// them all. Inserting a point of the curve into a chord keeps every
    /// point of the curve within `tol` of the polyline.
    ///
    /// # Errors
    ///
    /// As [`Curve::flatten`].
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::{Curve, Flatten};
    /// let line = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]])?;
    /// assert_eq!(line.flatten(1e-9)?.len(), 2);
    /// assert_eq!(line.flatten_with_knots(1e-9)?.params(), line.knots());
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn flatten_with_knots(&self, tol: f64) -> Result<Polyline, Error> {
        let p = self.flatten(tol)?;
        let dim = self.dim();
        let knots = self.knots();
        let mut coords = Vec::with_capacity(p.coords().len() + knots.len() * dim);
        let mut params = Vec::with_capacity(p.len() + knots.len());
        let mut k = 0;
        let mut point = vec![0.0; dim];
        for (i, &t) in p.params().iter().enumerate() {
            while k < knots.len() && knots[k] < t {
                if params.last().is_none_or(|&last| last < knots[k]) {
                    self.eval_into(knots[k], &mut point)?;
                    coords.extend_from_slice(&point);
                    params.push(knots[k]);
                }
                k += 1;
            }
            if k < knots.len() && knots[k] == t {
                k += 1;
            }
            coords.extend_from_slice(&p.coords()[i * dim..(i + 1) * dim]);
            params.push(t);
        }
        Ok(Polyline::new(dim, coords, params))
    }

    /// For a planar curve, the last knot `e > k` such that the chord from
    /// knot point `k` to knot point `e` stays within the window's `tol` (in
    /// units of [`Curve::unit`]) of the curve between them. Segment `k` alone always
    /// qualifies (the caller has found that it needs one step).
    ///
    /// Each segment lies in the convex hull of its Bezier control points, and
    /// the distance to a line segment is convex, so the chord `A B` is close
    /// enough when every control point `p` of the run is: either `|p - A| <=
    /// tol`, or the direction of `B - A` is within `asin(tol / |p - A|)` of
    /// `p - A` (the cone of directions whose ray from `A` passes within `tol` of
    /// `p`) and `|B - A| >= |p - A|` (so `p` projects inside the chord). The
    /// cones are intersected as the run grows: one pass, no square loop.
    ///
    /// A nearly straight segment, whose inner control points lie within `w <=
    /// tol / 2` of its own chord ([`Segment::straight_gap`]), is held by its
    /// end points alone, with the tolerance `tol - w`: its inner control
    /// points are then within `tol` of `A B` by the triangle inequality. One
    /// cone a segment instead of three, and no Bezier points formed; a knot
    /// takes the smaller tolerance of the two segments it joins. The
    /// [`Window`] has each segment's `w` and each knot's tolerance.
    fn chord_run(&self, k: usize, window: &mut Window) -> usize {
        let (rel, tol) = (window.rel, window.tol);
        let n = self.len();
        let mut run = Run::new(self.unit_knot_2d(k, rel));
        let (base, _) = window.fill(self, k);
        // Segment k's inner points, unless it is nearly straight.
        if !window.straight(k - base) && !self.hold_inner(&mut run, k, rel, tol) {
            return k + 1;
        }
        let mut best = k + 1;
        let mut e = k + 1;
        while e < n {
            let (base, len) = window.fill(self, e);
            for i in e - base..len {
                // The knot between segments e - 1 and e, its value exactly.
                let p = [window.x[i], window.y[i]];
                match run.hold_end(p, window.knot_tol[i]) {
                    None => return best,
                    Some(true) => best = e,
                    // Knots whose chords fail one after another: the run
                    // is bending away, and a chord that passes again much
                    // further on is rare.
                    Some(false) if e - best >= PATIENCE => return best,
                    Some(false) => {}
                }
                if !window.straight(i) && !self.hold_inner(&mut run, e, rel, tol) {
                    return best;
                }
                e += 1;
            }
        }
        // The curve's last knot, held by segment n - 1.
        let (base, _) = window.fill(self, n - 1);
        let w = window.gap[n - base];
        let p = self.unit_knot_2d(n, rel);
        if run.hold_end(p, tol - if w > 0.0 { w } else { 0.0 }) == Some(true) {
            best = n;
        }
        best
    }

    /// [`Run::hold`] of the inner Bezier points of segment `e`.
    fn hold_inner(&self, run: &mut Run, e: usize, rel: [f64; 2], tol: f64) -> bool {
        let q = self.coefficients();
        let ctrl = Segment::new(q[2 * e], q[2 * e + 1], rel).bezier();
        run.hold(ctrl[1], tol) && run.hold(ctrl[2], tol)
    }
}

/// Segments a chord search looks at, formed a block at a time in a loop of
/// their own (which the compiler runs two segments at a time), once per
/// segment rather than once per visit: a run that ends goes back at most
/// [`PATIENCE`] knots, and a new block keeps those.
struct Window {
    /// The first segment held.
    base: usize,
    /// Segments held.
    len: usize,
    /// The tolerance of the chord search, in units of [`Curve::unit`].
    tol: f64,
    /// [`Curve::unit_rel`] of both coordinates.
    rel: [f64; 2],
    /// The knot point at the start of each segment, in units of
    /// [`Curve::unit`].
    x: [f64; WINDOW],
    y: [f64; WINDOW],
    /// For the segment before the first and each held, the bound on the
    /// distance of its inner points from its chord when that is at most half
    /// the tolerance (the segment is nearly straight), else -1.
    gap: [f64; WINDOW + 1],
    /// The tolerance at the knot at the start of the segment: the search's,
    /// less the larger `w` of the two segments it joins.
    knot_tol: [f64; WINDOW],
}

/// Segments in a [`Window`].
const WINDOW: usize = 128;

impl Window {
    fn new(tol: f64, rel: [f64; 2]) -> Self {
        Window {
            base: 0,
            len: 0,
            tol,
            rel,
            x: [0.0; WINDOW],
            y: [0.0; WINDOW],
            gap: [0.0; WINDOW + 1],
            knot_tol: [0.0; WINDOW],
        }
    }

    /// Whether held segment `i` is nearly straight.
    #[inline(always)]
    fn straight(&self, i: usize) -> bool {
        self.gap[i + 1] >= 0.0
    }

    /// Makes segment `e` (less than the curve's length) held; the first
    /// segment held and the count held.
    #[inline]
    fn fill(&mut self, curve: &Curve, e: usize) -> (usize, usize) {
        if e < self.base || e >= self.base + self.len {
            self.refill(curve, e);
        }
        (self.base, self.len)
    }

    #[inline(never)]
    fn refill(&mut self, curve: &Curve, e: usize) {
        let (rel, tol) = (self.rel, self.tol);
        // Past the end: keep the knots a run that ends there goes back to.
        let base = if e == self.base + self.len {
            e.saturating_sub(PATIENCE + 1).max(self.base)
        } else {
            e
        };
        let len = (curve.len() - base).min(WINDOW);
        let q = curve.coefficients();
        let half = 0.5 * tol;
        let (before, gaps) = self.gap.split_at_mut(1);
        for (((s, x), y), gap) in q[2 * base..2 * (base + len)]
            .chunks_exact(2)
            .zip(&mut self.x)
            .zip(&mut self.y)
            .zip(gaps)
        {
            let seg = Segment::new(s[0], s[1], rel);
            [*x, *y] = seg.start();
            *gap = seg.straight_gap(half);
        }
        before[0] = match base.checked_sub(1) {
            Some(b) => Segment::new(q[2 * b], q[2 * b + 1], rel).straight_gap(half),
            None => 0.0,
        };
        for (t, w) in self.knot_tol.iter_mut().zip(self.gap[..=len].windows(2)) {
            let m = if w[0] > w[1] { w[0] } else { w[1] };
            *t = tol - if m > 0.0 { m } else { 0.0 };
        }
        self.base = base;
        self.len = len;
    }
}

/// A planar segment's power-basis coefficients in units of [`Curve::unit`].
struct Segment {
    x: [f64; 4],
    y: [f64; 4],
}

impl Segment {
    #[inline(always)]
    fn new(Piece(qx): Piece, Piece(qy): Piece, rel: [f64; 2]) -> Self {
        Segment {
            x: qx.map(|v| v * rel[0]),
            y: qy.map(|v| v * rel[1]),
        }
    }

    /// The first point, `c0`.
    #[inline(always)]
    fn start(&self) -> [f64; 2] {
        [self.x[0], self.y[0]]
    }

    /// The Bezier control points: `b0 = c0`, `b1 = c0 + c1 / 3`, `b2 = b1 +
    /// (c1 + c2) / 3`, `b3 = c0 + c1 + c2 + c3` (the last place may differ
    /// from [`Curve::segment_points`]).
    #[inline(always)]
    fn bezier(&self) -> [[f64; 2]; 4] {
        let third = 1.0 / 3.0;
        let col = |q: &[f64; 4]| {
            let b1 = q[0] + q[1] * third;
            [
                q[0],
                b1,
                b1 + (q[1] + q[2]) * third,
                (q[0] + q[1]) + (q[2] + q[3]),
            ]
        };
        let (bx, by) = (col(&self.x), col(&self.y));
        [
            [bx[0], by[0]],
            [bx[1], by[1]],
            [bx[2], by[2]],
            [bx[3], by[3]],
        ]
    }

    /// A bound on the distance of the inner Bezier control points from the
    /// chord: `max |r''| / 6` over the ends. With `D1 = b0 - 2 b1 + b2` and `D2
    /// = b1 - 2 b2 + b3` (so `r''(0) = 6 D1`, `r''(1) = 6 D2`), `b1 - (2 b0 +
    /// b3) / 3 = -(2 D1 + D2) / 3` and `b2 - (b0 + 2 b3) / 3 = -(D1 + 2 D2) /
    /// 3`, and both points subtracted lie on the chord. Given squared (no
    /// square root), times 36: `max |r''|^2`; infinite or NaN when the
    /// squares overflow. (The tests' check of [`Segment::chord_gap`].)
    #[cfg(test)]
    fn bow_squared_36(&self) -> f64 {
        let (x, y) = (&self.x, &self.y);
        let (ax, ay) = (2.0 * x[2], 2.0 * y[2]);
        let (bx, by) = (2.0 * x[2] + 6.0 * x[3], 2.0 * y[2] + 6.0 * y[3]);
        let (a2, b2) = (ax * ax + ay * ay, bx * bx + by * by);
        if a2 > b2 {
            a2
        } else {
            b2
        }
    }

    /// The distance of the inner control points from the chord
    /// ([`Segment::chord_gap`]) when they project inside it and it is at most
    /// `half`, else -1. A segment whose inner points project outside its chord
    /// is rare (it turns sharply or runs unevenly) and has them held
    /// themselves. A bound for it (the bow, `max |r''| / 6`, compared squared)
    /// cost 14 instructions a control point and saved no vertex on the
    /// benchmark's spiral (2,918 with it, 2,917 without).
    #[inline(always)]
    fn straight_gap(&self, half: f64) -> f64 {
        let gap = self.chord_gap();
        // NaN fails.
        if gap <= half {
            gap
        } else {
            -1.0
        }
    }

    /// A bound on the distance of the inner Bezier control points from the
    /// chord when both project inside it (NaN otherwise), at most 8.3 % above
    /// the distance. With `d = b3 - b0 = c1 + c2 + c3`, `b1 - b0 = c1 / 3` and
    /// `b2 - b0 = (2 c1 + c2) / 3`; the distance from the chord's line is `|d x
    /// (b - b0)| / |d|`. Sharper than the bow `max |r''| / 6`, which also
    /// counts the acceleration along the chord.
    #[inline(always)]
    fn chord_gap(&self) -> f64 {
        let (x, y) = (&self.x, &self.y);
        let u = [x[1], y[1]];
        let v = [2.0 * x[1] + x[2], 2.0 * y[1] + y[2]];
        let d = [x[1] + x[2] + x[3], y[1] + y[2] + y[3]];
        let dd = d[0] * d[0] + d[1] * d[1];
        // Projections 3 (b - b0) . d / |d|^2 inside [0, 3]. (A chord of
        // length 0 passes, and gives 0 / 0.)
        let (su, sv) = (d[0] * u[0] + d[1] * u[1], d[0] * v[0] + d[1] * v[1]);
        let (lo, hi) = if su < sv { (su, sv) } else { (sv, su) };
        let (cu, cv) = (cross(d, u).abs(), cross(d, v).abs());
        let c = if cu > cv { cu } else { cv };
        if lo >= 0.0 && hi <= 3.0 * dd {
            // |d| from below without a square root: at least the larger
            // component and at least their sum over sqrt 2 (at most 8 %
            // short, when d is 22.5 degrees off an axis).
            let (ax, ay) = (d[0].abs(), d[1].abs());
            let m = if ax > ay { ax } else { ay };
            let s = (ax + ay) * core::f64::consts::FRAC_1_SQRT_2;
            c / (3.0 * if m > s { m } else { s })
        } else {
            f64::NAN
        }
    }
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The cone of chord directions from `a` allowed by the points seen so far.
///
/// Directions are kept as slopes `y / x` in the frame of `axis`, the offset
/// from `a` of the first point that constrained them (`x` along it, `y` a
/// quarter turn counter-clockwise): that point's cone lies within a quarter
/// turn of it, so every allowed direction has `x > 0` and the slope orders
/// them. Narrowing the cone is then a max and a min, without the branches on
/// the order of arc ends that an intersection of arcs takes.
struct Run {
    a: [f64; 2],
    /// Zero until a point constrains the direction.
    axis: [f64; 2],
    /// The allowed slopes, `lo <= hi`.
    lo: f64,
    hi: f64,
    /// The largest squared distance from `a` of a point that constrains the
    /// direction.
    reach2: f64,
}

/// A point that [`Run::narrow`] took in.
enum Held {
    /// Within the tolerance of the chord's start: no constraint.
    Near,
    /// A constraint; whether a chord may end at the point.
    Far { ends: bool },
}

impl Run {
    fn new(a: [f64; 2]) -> Self {
        Run {
            a,
            axis: [0.0; 2],
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
            reach2: 0.0,
        }
    }

    /// `v` in the frame of the axis (scaled by the axis' length).
    #[inline(always)]
    fn frame(&self, v: [f64; 2]) -> (f64, f64) {
        let ax = self.axis;
        (ax[0] * v[0] + ax[1] * v[1], cross(ax, v))
    }

    /// Narrows the cone to the directions whose ray from `a` passes within
    /// `tol` of `p`: those within `asin(tol / |p - a|)` of `p - a`. `None` when
    /// none is left (or `p` is not finite).
    #[inline(always)]
    fn narrow(&mut self, p: [f64; 2], tol: f64) -> Option<Held> {
        let c = [p[0] - self.a[0], p[1] - self.a[1]];
        let r2 = c[0] * c[0] + c[1] * c[1];
        let tol2 = tol * tol;
        if !r2.is_finite() {
            return None;
        }
        if r2 <= tol2 {
            return Some(Held::Near);
        }
        let beyond = r2 >= self.reach2;
        if r2 > self.reach2 {
            if self.reach2 == 0.0 {
                self.axis = c;
            }
            self.reach2 = r2;
        }
        let (x, y) = self.frame(c);
        // Whether a chord may end at p, from the cone before p narrows it:
        // the direction of p lies in p's own cone, so only the earlier
        // constraints can exclude it. (Known before the square root and the
        // divisions below, so a mispredicted branch on it costs less.)
        let ends = beyond && self.admits(x, y);
        // The cone's edges: (x, y) turned by -/+ asin(tol / |c|), both scaled
        // by |c|: (x, y) sqrt(|c|^2 - tol^2) -/+ (-y, x) tol.
        let q = (r2 - tol2).sqrt();
        let (rx, ry) = (q * x + tol * y, q * y - tol * x);
        let (lx, ly) = (q * x - tol * y, q * y + tol * x);
        // An edge past a quarter turn from the axis leaves that side open; a
        // cone with both edges past it misses the axis' cone altogether.
        let lo = if rx > 0.0 {
            ry / rx
        } else if lx > 0.0 {
            f64::NEG_INFINITY
        } else {
            return None;
        };
        let hi = if lx > 0.0 { ly / lx } else { f64::INFINITY };
        // Selections rather than branches: which side narrows is as good as
        // random.
        self.lo = if lo > self.lo { lo } else { self.lo };
        self.hi = if hi < self.hi { hi } else { self.hi };
        (self.lo <= self.hi).then_some(Held::Far { ends })
    }

    /// [`Run::narrow`]; false when the cone is empty.
    #[inline(always)]
    fn hold(&mut self, p: [f64; 2], tol: f64) -> bool {
        self.narrow(p, tol).is_some()
    }

    /// [`Run::hold`] of `p`, and whether the chord may end at `p` then
    /// ([`Run::reaches`] of it): `None` when the cone is empty.
    #[inline(always)]
    fn hold_end(&mut self, p: [f64; 2], tol: f64) -> Option<bool> {
        Some(match self.narrow(p, tol)? {
            Held::Near => self.reaches(p),
            Held::Far { ends } => ends,
        })
    }

    /// Whether the direction `(x, y)` in the axis frame lies in the cone.
    #[inline(always)]
    fn admits(&self, x: f64, y: f64) -> bool {
        x > 0.0 && y >= self.lo * x && y <= self.hi * x
    }

    /// Whether the chord from `a` to `b` satisfies every constraint so far:
    /// its direction in the cone, and no constraining point beyond its end.
    #[inline(always)]
    fn reaches(&self, b: [f64; 2]) -> bool {
        if self.reach2 == 0.0 {
            return true;
        }
        let v = [b[0] - self.a[0], b[1] - self.a[1]];
        let (x, y) = self.frame(v);
        self.admits(x, y) && v[0] * v[0] + v[1] * v[1] >= self.reach2
    }
}

/// What the flattening reads of a curve, in units of its largest scale.
impl Curve {
    /// The unit of mixed-coordinate geometry (a power of two).
    fn unit(&self) -> f64 {
        self.pieces.unit()
    }

    /// The largest `|d^2 r / dt^2|` on segment `k`, in units of [`Self::unit`].
    fn accel_bound(&self, k: usize) -> f64 {
        // r'' = 2 c2 + 6 c3 t per coordinate: its norm at t = 0 and t = 1.
        let dim = self.dim();
        let (mut s0, mut s1) = (0.0f64, 0.0f64);
        let mut big = false;
        for c in 0..dim {
            let q = self.pieces.piece(k, c);
            let rel = self.pieces.scale(c) / self.pieces.unit();
            let (a0, a1) = (2.0 * q[2] * rel, (2.0 * q[2] + 6.0 * q[3]) * rel);
            s0 += a0 * a0;
            s1 += a1 * a1;
            big |= !(a0.abs() < 1e150 && a1.abs() < 1e150);
        }
        if big {
            // Squares could overflow: the norms the careful way.
            let mut a = vec![0.0; dim];
            self.local(k, 0.0, 2, &mut a);
            let m0 = norm(&a);
            self.local(k, 1.0, 2, &mut a);
            return m0.max(norm(&a));
        }
        s0.max(s1).sqrt()
    }

    /// What multiplies scaled coordinate `c` to give it in units of
    /// [`Self::unit`] (a power of two).
    fn unit_rel(&self, c: usize) -> f64 {
        self.pieces.scale(c) / self.pieces.unit()
    }

    /// Knot point `e` (0 to [`Self::len`]; the last of a closed curve is the
    /// first) of a planar curve in units of [`Self::unit`]: the value the
    /// flattening's vertices take, before the multiplication by the unit.
    #[inline(always)]
    fn unit_knot_2d(&self, e: usize, rel: [f64; 2]) -> [f64; 2] {
        let j = if e == self.len() && self.closed { 0 } else { e };
        let d = &self.d[2 * j..2 * j + 2];
        [
            (self.fv(j, 0) + d[0]) * rel[0],
            (self.fv(j, 1) + d[1]) * rel[1],
        ]
    }

    /// The power-basis coefficients of every segment, `dim` per segment (one
    /// per coordinate), in scaled units.
    fn coefficients(&self) -> &[Piece] {
        self.pieces.coefs()
    }

    /// Appends the point of segment `k` at local `t`, in the curve's units,
    /// to `out`.
    fn push_segment_point(&self, k: usize, t: f64, out: &mut Vec<f64>) {
        let start = out.len();
        out.resize(start + self.dim(), 0.0);
        let p = &mut out[start..];
        self.local(k, t, 0, p);
        for v in p {
            *v = (*v * self.pieces.unit()).clamp(-f64::MAX, f64::MAX);
        }
    }
}

impl Flatten for Curve {
    /// A polyline whose distance from the curve is at most `tol` everywhere,
    /// with few vertices (see [`Flatten`](crate::Flatten)): each segment gets the fewest
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
    /// use bzspline::{Curve, Flatten};
    /// let c = Curve::closed(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])?;
    /// let p = c.flatten(1e-3)?;
    /// assert_eq!(p.point(0), p.point(p.len() - 1)); // closed
    /// assert!(p.len() > 8);
    /// // Points on a straight line: one chord.
    /// let line = Curve::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]])?;
    /// assert_eq!(line.flatten(1e-9)?.len(), 2);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    fn flatten(&self, tol: f64) -> Result<Polyline, Error> {
        check_tol(tol)?;
        let scaled_tol = tol / self.unit();
        let too_many = || Error::TooManyVertices { tolerance: tol };
        let dim = self.dim();
        let knots = self.knots();
        let mut coords = Vec::with_capacity((self.len() + 1) * dim);
        let mut params = Vec::with_capacity(self.len() + 1);
        self.push_segment_point(0, 0.0, &mut coords);
        params.push(knots[0]);
        // Read only by the chord search, which runs on planar curves.
        let rel = [self.unit_rel(0), self.unit_rel(dim.min(2) - 1)];
        let mut window = Window::new(0.999 * scaled_tol, rel);
        let mut k = 0;
        while k < self.len() {
            let m = steps(self.accel_bound(k), scaled_tol).map_err(|_| too_many())?;
            if params.len().saturating_add(m) > MAX_FLATTEN_VERTICES {
                return Err(too_many());
            }
            if m == 1 && dim == 2 {
                // One chord from knot k to the farthest knot it can reach.
                let end = self.chord_run(k, &mut window);
                // The point of segment end - 1 at t = 1 (`push_segment_point`),
                // without its general evaluation.
                let p = self.unit_knot_2d(end, rel);
                coords.extend(p.map(|v| (v * self.unit()).clamp(-f64::MAX, f64::MAX)));
                params.push(knots[end]);
                k = end;
                continue;
            }
            let h = knots[k + 1] - knots[k];
            for j in 1..=m {
                let t = j as f64 / m as f64;
                self.push_segment_point(k, t, &mut coords);
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::flatten::tests::seg_dist;
    use crate::traits::Bounds;

    fn segment(c: &Curve, k: usize, rel: [f64; 2]) -> Segment {
        let q = c.coefficients();
        Segment::new(q[2 * k], q[2 * k + 1], rel)
    }

    /// Whether the chord from `a` to `b` meets the constraint of point `p` at
    /// tolerance `t` (see [`Run`]), by angles, with the distance of the
    /// nearest boundary relative to its scale.
    fn allowed(a: [f64; 2], p: [f64; 2], t: f64, b: [f64; 2]) -> (bool, f64) {
        let c = [p[0] - a[0], p[1] - a[1]];
        let v = [b[0] - a[0], b[1] - a[1]];
        let (r2, v2) = (c[0] * c[0] + c[1] * c[1], v[0] * v[0] + v[1] * v[1]);
        if r2 <= t * t {
            return (true, (r2 - t * t).abs() / r2);
        }
        // Within asin(t / |c|) of c: |c x v| <= t |v| on c's side.
        let side = (cross(c, v).abs() - t * v2.sqrt()) / (t * v2.sqrt());
        let dot = c[0] * v[0] + c[1] * v[1];
        let ok = dot > 0.0 && side <= 0.0 && v2 >= r2;
        (ok, side.abs().min((v2 - r2).abs() / r2))
    }

    #[test]
    fn slope_cone_matches_the_angle_test() {
        let mut rng = crate::spline::tests::Rng(0x5eed);
        let mut checked = [0usize; 2];
        let mut checked_end = [0usize; 2];
        for _ in 0..3000 {
            let a = [4.0 * rng.next() - 2.0, 4.0 * rng.next() - 2.0];
            let tol = 10f64.powf(-3.0 + 2.0 * rng.next());
            let th = 7.0 * rng.next();
            let bend = 0.2 * (rng.next() - 0.5);
            let step = tol * 10f64.powf(-0.5 + 2.0 * rng.next());
            let mut run = Run::new(a);
            let mut held = Vec::new();
            for i in 1..30 {
                let ang = th + bend * f64::from(i) + 0.05 * (rng.next() - 0.5);
                let r = step * f64::from(i);
                let p = [a[0] + r * ang.cos(), a[1] + r * ang.sin()];
                let t = tol * (0.5 + 0.5 * rng.next());
                // A chord may end at p itself when every earlier point allows
                // it (p's own constraint holds: its direction, at its distance).
                let (mut want_end, mut near_end) = (true, f64::INFINITY);
                for &(q, tq) in &held {
                    let (ok, m) = allowed(a, q, tq, p);
                    want_end &= ok;
                    near_end = near_end.min(m);
                }
                let Some(ends) = run.hold_end(p, t) else {
                    break;
                };
                if near_end > 1e-9 {
                    assert_eq!(ends, want_end, "a {a:?} end {p:?} held {held:?}");
                    checked_end[usize::from(want_end)] += 1;
                }
                held.push((p, t));
                let b = [
                    p[0] + step * (rng.next() - 0.3),
                    p[1] + step * (rng.next() - 0.5),
                ];
                let (mut want, mut near) = (true, f64::INFINITY);
                for &(p, t) in &held {
                    let (ok, m) = allowed(a, p, t, b);
                    want &= ok;
                    near = near.min(m);
                }
                if near > 1e-9 {
                    assert_eq!(run.reaches(b), want, "a {a:?} b {b:?} held {held:?}");
                    checked[usize::from(want)] += 1;
                }
            }
        }
        // Both answers are exercised.
        assert!(checked[0] > 1000 && checked[1] > 1000, "{checked:?}");
        assert!(
            checked_end[0] > 100 && checked_end[1] > 1000,
            "{checked_end:?}"
        );
    }

    #[test]
    fn bow_and_chord_gap_bound_the_inner_control_points() {
        // Random planar curves: the inner Bezier points of every segment lie
        // within the bow (max |r''| / 6) of the chord, and the chord gap is
        // their distance from it whenever both project inside.
        let mut rng = crate::spline::tests::Rng(17);
        let mut sharp = 0;
        for case in 0..60 {
            let n = 3 + case % 9;
            let pts: Vec<[f64; 2]> = (0..n)
                .map(|_| [10.0 * rng.next(), 10.0 * rng.next() - 5.0])
                .collect();
            let Ok(c) = Curve::builder_from(&pts).closed(case % 2 == 0).build() else {
                continue;
            };
            let rel = [c.unit_rel(0), c.unit_rel(1)];
            for k in 0..c.len() {
                let seg = segment(&c, k, rel);
                let b = seg.bezier();
                let gap = seg_dist(&b[1], &b[0], &b[3]).max(seg_dist(&b[2], &b[0], &b[3]));
                let scale = 1e-12 * (1.0 + b.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())));
                let bow = seg.bow_squared_36().sqrt() / 6.0;
                assert!(
                    gap <= bow + scale,
                    "case {case} segment {k}: {gap} > bow {bow}"
                );
                let sharp_gap = seg.chord_gap();
                if sharp_gap.is_finite() {
                    // The chord's length is taken from below, at most 8.3 %
                    // short (1 / cos 22.5 degrees).
                    assert!(
                        sharp_gap >= gap - scale && sharp_gap <= 1.0824 * gap + scale,
                        "case {case} segment {k}: {sharp_gap} vs {gap}"
                    );
                    sharp += usize::from(sharp_gap < 0.8 * bow);
                }
            }
        }
        assert!(
            sharp > 20,
            "{sharp} segments where the gap is sharper than the bow"
        );
    }

    #[test]
    fn chords_are_about_as_long_as_the_control_points_allow() {
        // A greedy chord search that checks every control point of every
        // segment against every candidate chord (quadratic): the fast search
        // uses the same hull criterion, with the cone kept as slopes and nearly
        // straight segments held by their ends, and should need at most a few
        // percent more vertices.
        let mut rng = crate::spline::tests::Rng(3);
        let mut ran = 0;
        for case in 0..12 {
            let n = 200 + 40 * case;
            let turns = 0.2 + 2.0 * rng.next();
            let noise = [0.0, 1e-4, 1e-3][case % 3];
            let pts: Vec<[f64; 2]> = (0..n)
                .map(|i| {
                    let th = turns * std::f64::consts::TAU * i as f64 / n as f64;
                    let r = 100.0 * (1.0 + 0.3 * th) * (1.0 + noise * (rng.next() - 0.5));
                    [r * th.cos(), r * th.sin()]
                })
                .collect();
            let c = Curve::open(&pts).unwrap();
            let b = c.bbox();
            let tol = 1e-3 * (b.max[0] - b.min[0]).hypot(b.max[1] - b.min[1]);
            let u = 0.999 * tol / c.unit();
            if (0..c.len()).any(|k| steps(c.accel_bound(k), tol / c.unit()).unwrap() > 1) {
                continue;
            }
            let rel = [c.unit_rel(0), c.unit_rel(1)];
            let ctrl: Vec<[[f64; 2]; 4]> =
                (0..c.len()).map(|k| segment(&c, k, rel).bezier()).collect();
            let mut brute = 1;
            let mut k = 0;
            while k < c.len() {
                let a = ctrl[k][0];
                let mut best = k + 1;
                for j in k + 1..=c.len() {
                    let b = ctrl[j - 1][3];
                    let fits = ctrl[k..j]
                        .iter()
                        .flat_map(|s| s.iter())
                        .all(|p| seg_dist(p, &a, &b) <= u);
                    if fits {
                        best = j;
                    }
                }
                brute += 1;
                k = best;
            }
            let fast = c.flatten(tol).unwrap().len();
            ran += 1;
            assert!(
                fast <= brute + brute / 20 + 1,
                "case {case}: {fast} vertices, {brute} by the exhaustive search"
            );
        }
        assert!(ran >= 8, "{ran} curves were flat enough");
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
}
