//! One piece of a smoothed line or arc: the method's curve on its control
//! points, built with the smoothing options, flattened, and (through the
//! points) every control point put back as a vertex with its exact value.
//! Ring-by-ring smoothing ([`crate::smooth_line`]) and the coverage's arcs
//! both smooth through here.

use bzspline::{Curve, CurveBuilder, Flatten};

use crate::options::SmoothOptions;

/// The curve of the control points `ctrl` (`dim` numbers a point; `closed`
/// for a ring's curve) with the options' alpha, parametrisation and
/// through.
///
/// # Errors
///
/// The curve's: points too close for the parametrisation, a coordinate that
/// is not finite, among others.
pub(crate) fn build(
    ctrl: &[f64],
    dim: usize,
    closed: bool,
    opts: &SmoothOptions,
) -> Result<Curve, bzspline::Error> {
    CurveBuilder::new(ctrl, dim)
        .closed(closed)
        .param(opts.param.clone())
        .alpha(opts.alpha)
        .through(opts.through)
        .build()
}

/// A flattened piece: vertex parameters, coordinates (flat, `dim` a
/// vertex), the curve's knots.
pub(crate) struct Flat {
    pub(crate) params: Vec<f64>,
    pub(crate) coords: Vec<f64>,
    pub(crate) knots: Vec<f64>,
}

/// `curve` (built by [`build`] on `ctrl`) flattened to within `tol`, with
/// at least `min` vertices (sampled evenly in the parameter when flattening
/// gives fewer). Through the points every control point is a vertex, with
/// its coordinates exactly.
///
/// # Errors
///
/// The flattening's: a tolerance that asks for too many vertices.
pub(crate) fn flatten(
    curve: &Curve,
    ctrl: &[f64],
    dim: usize,
    opts: &SmoothOptions,
    tol: f64,
    min: usize,
) -> Result<Flat, bzspline::Error> {
    let mut poly = if opts.through {
        curve.flatten_with_knots(tol)?
    } else {
        curve.flatten(tol)?
    };
    if poly.len() < min {
        poly = curve.sample(min)?;
    }
    let knots = curve.knots().to_vec();
    let params = poly.params().to_vec();
    let mut coords = poly.coords().to_vec();
    if opts.through {
        // Every control point is a knot point: put back its exact value.
        let n = ctrl.len() / dim;
        let mut k = 0;
        for (o, &t) in coords.chunks_exact_mut(dim).zip(&params) {
            while k < knots.len() && knots[k] < t {
                k += 1;
            }
            if k < knots.len() && knots[k] == t {
                let j = k % n;
                o.copy_from_slice(&ctrl[dim * j..dim * (j + 1)]);
            }
        }
    }
    Ok(Flat {
        params,
        coords,
        knots,
    })
}
