//! One line or ring smoothed on its own, in any dimension.

use bzspline::Flatten;
use bzspline::{CurveBuilder, Error, Repeats};

use crate::smooth::SmoothOptions;

/// The smoothed positions of one line (`closed` false) or ring, `dim`
/// numbers a position, flattened to within `tolerance`: the method's curve
/// with the positions as control points (open for a line, closed for a
/// ring), with no regard for neighbours. This is what smoothing ring by ring
/// means; positions with z are smoothed as a curve in space.
///
/// A line keeps its end positions exactly; a ring comes out closed, its last
/// position bit for bit its first (a ring's closing repeat in the input is
/// optional). Consecutive repeated positions are dropped first; a line of
/// fewer than two distinct positions or a ring of fewer than three comes back
/// as it was. With [`SmoothOptions::through`] every position of the input is
/// in the output, exactly. `opts.tolerance` is not read.
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
/// let out = smooth_line(&pts, 3, false, 1e-3, &SmoothOptions::default())?;
/// assert_eq!(&out[..3], &pts[..3]);
/// assert_eq!(&out[out.len() - 3..], &pts[9..]);
/// # Ok::<(), bzspline::Error>(())
/// ```
pub fn smooth_line(
    points: &[f64],
    dim: usize,
    closed: bool,
    tolerance: f64,
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
    let flat: Vec<f64> = distinct.concat();
    let curve = CurveBuilder::new(&flat, dim)
        .closed(closed)
        .param(opts.param.clone())
        .alpha(opts.alpha)
        .repeats(Repeats::Drop)
        .through(opts.through)
        .build()?;
    let poly = if opts.through {
        curve.flatten_with_knots(tolerance)
    } else {
        curve.flatten(tolerance)
    }?;
    let mut out = poly.coords().to_vec();
    if opts.through {
        // Every position is a knot point: put back its exact value.
        let knots = curve.knots();
        let mut k = 0;
        for (o, &t) in out.chunks_exact_mut(dim).zip(poly.params()) {
            while k < knots.len() && knots[k] < t {
                k += 1;
            }
            if k < knots.len() && knots[k] == t {
                o.copy_from_slice(distinct[k % distinct.len()]);
            }
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_in_space_keeps_its_ends_and_stays_in_its_hull() {
        let pts = [
            0.0, 0.0, 10.0, 1.0, 2.0, 14.0, 3.0, 2.0, 11.0, 4.0, 0.0, 13.0,
        ];
        let out = smooth_line(&pts, 3, false, 1e-4, &SmoothOptions::default()).unwrap();
        assert!(out.len() > pts.len());
        assert_eq!((&out[..3], &out[out.len() - 3..]), (&pts[..3], &pts[9..]));
        // The curve lies in the convex hull of its control points: z too.
        assert!(out.chunks(3).all(|p| (10.0..=14.0).contains(&p[2])));
    }

    #[test]
    fn a_ring_closes_and_through_keeps_every_position() {
        let ring = [0.0, 0.0, 2.0, 0.0, 2.0, 1.0, 0.0, 1.0, 0.0, 0.0];
        let out = smooth_line(&ring, 2, true, 1e-3, &SmoothOptions::default()).unwrap();
        assert_eq!(&out[..2], &out[out.len() - 2..]);
        let through = smooth_line(
            &ring,
            2,
            true,
            1e-3,
            &SmoothOptions::default().through(true),
        )
        .unwrap();
        for p in ring.chunks(2) {
            assert!(through.chunks(2).any(|q| q == p), "{p:?} is not kept");
        }
    }

    #[test]
    fn too_few_positions_pass_through_and_bad_ones_are_refused() {
        let two = [1.0, 1.0, 1.0, 1.0];
        assert_eq!(
            smooth_line(&two, 2, false, 0.1, &SmoothOptions::default()).unwrap(),
            two
        );
        let nan = [0.0, 0.0, f64::NAN, 1.0, 2.0, 0.0];
        assert!(smooth_line(&nan, 2, false, 0.1, &SmoothOptions::default()).is_err());
    }
}
