//! One line or ring smoothed on its own, in any dimension.

use bzspline::Error;

use crate::options::{default_tolerance_of, SmoothOptions};
use crate::piece;

/// The smoothed positions of one line (`closed` false) or ring, `dim`
/// numbers a position, flattened to within the options' tolerance: the
/// method's curve with the positions as control points (open for a line,
/// closed for a ring), with no regard for neighbours. This is what
/// smoothing ring by ring means; positions with z are smoothed as a curve in
/// space.
///
/// A line keeps its end positions exactly; a ring comes out closed, its last
/// position bit for bit its first (a ring's closing repeat in the input is
/// optional). Consecutive repeated positions are dropped first; a line of
/// fewer than two distinct positions or a ring of fewer than three comes back
/// as it was. With [`SmoothOptions::through`] every position of the input is
/// in the output, exactly. With [`SmoothOptions::keep_angle`] every position
/// where the line turns by more than that many degrees in the plane (x, y:
/// the turning angle is a planar property; z is carried along) stays where
/// it is as a corner, and the runs between corners are smoothed as open
/// curves, as the coverage's arcs are. Without a tolerance the default of the
/// line's own extent is taken ([`default_tolerance_of`]). The options are
/// the caller's to check ([`SmoothOptions::validate`]); out of range, the
/// curve or the flattening refuses them.
///
/// # Errors
///
/// The curve's errors ([`Error::NonFinite`] for a coordinate that is not
/// finite, among others); [`Error::Overflow`] when the smoothed line leaves
/// the range of a double.
///
/// # Examples
///
/// ```
/// use bzspline_geo::{smooth_line, SmoothOptions};
///
/// // A line in space: x, y, z.
/// let pts = [0.0, 0.0, 10.0, 1.0, 2.0, 11.0, 3.0, 2.0, 12.0, 4.0, 0.0, 13.0];
/// let out = smooth_line(&pts, 3, false, &SmoothOptions::default().tolerance(1e-3))?;
/// assert_eq!(&out[..3], &pts[..3]);
/// assert_eq!(&out[out.len() - 3..], &pts[9..]);
/// # Ok::<(), bzspline::Error>(())
/// ```
pub fn smooth_line(
    points: &[f64],
    dim: usize,
    closed: bool,
    opts: &SmoothOptions,
) -> Result<Vec<f64>, Error> {
    if dim == 0 || points.len() < dim {
        return Ok(points.to_vec());
    }
    let pos: Vec<&[f64]> = points.chunks_exact(dim).collect();
    // Repeated positions are dropped; what remains must still make a curve.
    let mut distinct: Vec<&[f64]> = Vec::with_capacity(pos.len());
    for p in &pos {
        if distinct.last() != Some(p) {
            distinct.push(p);
        }
    }
    if closed {
        while distinct.len() > 1 && distinct.first() == distinct.last() {
            distinct.pop();
        }
    }
    if distinct.len() < if closed { 3 } else { 2 } {
        return Ok(points.to_vec());
    }
    let tol = opts
        .tolerance
        .unwrap_or_else(|| opts.default_tolerance_from(extent_tolerance(&distinct)));
    let corners = corners(&distinct, closed, opts.keep_angle, opts.frame);
    let mut out = if corners.is_empty() {
        smooth_piece(&distinct, closed, opts, tol)?
    } else {
        // From corner to corner (a ring from its first corner round to it).
        let n = distinct.len();
        let walk: Vec<usize> = if closed {
            (0..=n).map(|j| (corners[0] + j) % n).collect()
        } else {
            (0..n).collect()
        };
        let mut out: Vec<f64> = Vec::with_capacity(points.len() * 4);
        let mut j0 = 0;
        for j in 1..walk.len() {
            if j + 1 != walk.len() && corners.binary_search(&walk[j]).is_err() {
                continue;
            }
            let run: Vec<&[f64]> = walk[j0..=j].iter().map(|&i| distinct[i]).collect();
            j0 = j;
            let piece = if run.len() == 2 {
                run.concat()
            } else {
                smooth_piece(&run, false, opts, tol)?
            };
            // The piece starts where the last one ended, at the corner.
            let skip = if out.is_empty() { 0 } else { dim };
            out.extend_from_slice(&piece[skip..]);
            let n = out.len();
            out[n - dim..].copy_from_slice(run[run.len() - 1]);
        }
        out
    };
    if !out.iter().all(|v| v.is_finite()) {
        return Err(Error::Overflow {
            what: "the smoothed line",
        });
    }
    let n = out.len();
    if closed {
        // The ring closes on its first position, bit for bit.
        let (head, tail) = out.split_at_mut(n - dim);
        tail.copy_from_slice(&head[..dim]);
    } else {
        // A line keeps its end positions exactly.
        out[..dim].copy_from_slice(pos[0]);
        out[n - dim..].copy_from_slice(pos[pos.len() - 1]);
    }
    Ok(out)
}

/// One run of distinct positions smoothed as one curve (open, or `closed`).
fn smooth_piece(
    run: &[&[f64]],
    closed: bool,
    opts: &SmoothOptions,
    tol: f64,
) -> Result<Vec<f64>, Error> {
    let dim = run[0].len();
    let ctrl: Vec<f64> = run.concat();
    let curve = piece::build(&ctrl, dim, closed, opts)?;
    Ok(piece::flatten(&curve, &ctrl, dim, opts, tol, 0)?.coords)
}

/// The default tolerance of the positions' extent in the plane.
fn extent_tolerance(pos: &[&[f64]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in pos {
        let y = p.get(1).copied().unwrap_or(0.0);
        lo = [lo[0].min(p[0]), lo[1].min(y)];
        hi = [hi[0].max(p[0]), hi[1].max(y)];
    }
    default_tolerance_of(lo, hi)
}

/// The positions (indices, increasing) where the line turns by more than
/// `keep_angle` degrees (in the plane, or on the ground in the geographic
/// frame); a line's ends are not corners.
fn corners(
    pos: &[&[f64]],
    closed: bool,
    keep_angle: Option<f64>,
    frame: crate::Frame,
) -> Vec<usize> {
    let Some(deg) = keep_angle.filter(|_| pos[0].len() >= 2) else {
        return Vec::new();
    };
    let n = pos.len();
    let xy = |i: usize| geo_types::Coord {
        x: pos[i][0],
        y: pos[i][1],
    };
    (0..n)
        .filter(|&i| {
            let (prev, next) = match (closed, i) {
                (true, _) => ((i + n - 1) % n, (i + 1) % n),
                (false, 0) => return false,
                (false, _) if i + 1 == n => return false,
                (false, _) => (i - 1, i + 1),
            };
            crate::smooth::turning_degrees(xy(prev), xy(i), xy(next), frame) > deg
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_in_space_keeps_its_ends_and_stays_in_its_hull() {
        let pts = [
            0.0, 0.0, 10.0, 1.0, 2.0, 14.0, 3.0, 2.0, 11.0, 4.0, 0.0, 13.0,
        ];
        let out = smooth_line(&pts, 3, false, &SmoothOptions::default().tolerance(1e-4)).unwrap();
        assert!(out.len() > pts.len());
        assert_eq!((&out[..3], &out[out.len() - 3..]), (&pts[..3], &pts[9..]));
        // The curve lies in the convex hull of its control points: z too.
        assert!(out.chunks(3).all(|p| (10.0..=14.0).contains(&p[2])));
    }

    #[test]
    fn a_ring_closes_and_through_keeps_every_position() {
        let ring = [0.0, 0.0, 2.0, 0.0, 2.0, 1.0, 0.0, 1.0, 0.0, 0.0];
        let out = smooth_line(&ring, 2, true, &SmoothOptions::default().tolerance(1e-3)).unwrap();
        assert_eq!(&out[..2], &out[out.len() - 2..]);
        let through = smooth_line(
            &ring,
            2,
            true,
            &SmoothOptions::default().tolerance(1e-3).through(true),
        )
        .unwrap();
        for p in ring.chunks(2) {
            assert!(through.chunks(2).any(|q| q == p), "{p:?} is not kept");
        }
    }

    #[test]
    fn keep_angle_keeps_the_corners_of_a_line_with_z() {
        // The command's example: right-angled corners at (1, 0) and (1, 1)
        // and (2, 1), z rising along the line.
        let pts = [
            0.0, 0.0, 1.0, 1.0, 0.0, 2.0, 1.0, 1.0, 3.0, 2.0, 1.0, 4.0, 2.0, 0.0, 5.0,
        ];
        let opts = SmoothOptions::default().tolerance(1e-3);
        let smooth = smooth_line(&pts, 3, false, &opts).unwrap();
        let kept = smooth_line(&pts, 3, false, &opts.clone().keep_angle(30.0)).unwrap();
        let has = |out: &[f64], p: &[f64]| out.chunks(3).any(|q| q == p);
        for p in pts.chunks(3) {
            assert!(has(&kept, p), "corner {p:?} is not kept");
        }
        assert!(
            !has(&smooth, &pts[3..6]),
            "without keep_angle the corner is cut"
        );
        // Between the corners the legs are straight: every vertex lies on them.
        for q in kept.chunks(3) {
            let on_leg = pts.chunks(3).collect::<Vec<_>>().windows(2).any(|w| {
                let (a, b) = (w[0], w[1]);
                let cross = (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]);
                cross.abs() < 1e-12
            });
            assert!(on_leg, "{q:?} leaves the legs");
        }
        // A right angle is not sharper than 90 degrees: nothing is kept.
        assert_eq!(
            smooth_line(&pts, 3, false, &opts.clone().keep_angle(90.0)).unwrap(),
            smooth
        );
    }

    #[test]
    fn keep_angle_on_a_ring_keeps_its_corners_and_closes() {
        let ring = [0.0, 0.0, 2.0, 0.0, 2.0, 1.0, 0.0, 1.0, 0.0, 0.0];
        let opts = SmoothOptions::default().tolerance(1e-3).keep_angle(45.0);
        let out = smooth_line(&ring, 2, true, &opts).unwrap();
        assert_eq!(&out[..2], &out[out.len() - 2..]);
        for p in ring.chunks(2) {
            assert!(out.chunks(2).any(|q| q == p), "{p:?} is not kept");
        }
    }

    #[test]
    fn too_few_positions_pass_through_and_bad_ones_are_refused() {
        let two = [1.0, 1.0, 1.0, 1.0];
        assert_eq!(
            smooth_line(&two, 2, false, &SmoothOptions::default().tolerance(0.1)).unwrap(),
            two
        );
        let nan = [0.0, 0.0, f64::NAN, 1.0, 2.0, 0.0];
        assert!(smooth_line(&nan, 2, false, &SmoothOptions::default().tolerance(0.1)).is_err());
    }
}
