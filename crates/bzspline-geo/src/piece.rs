//! One piece of a smoothed line or arc: the method's curve on its control
//! points, built with the smoothing options, flattened, and (through the
//! points) every control point put back as a vertex with its exact value.
//! Ring-by-ring smoothing ([`crate::smooth_line`]) and the coverage's arcs
//! both smooth through here. In the geographic frame the control points
//! (longitude, latitude, height) are taken to their places on the WGS 84
//! ellipsoid (ECEF, metres), the curve is built and flattened there, and
//! its vertices are brought back to longitude and latitude written as the
//! control points write them.

use bzspline::{Curve, CurveBuilder, Flatten};

use crate::geodesy::{self, Convention};
use crate::options::{Frame, SmoothOptions};

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
    let ecef;
    let (pts, d) = match opts.frame {
        Frame::Plane => (ctrl, dim),
        Frame::Geographic => {
            ecef = ctrl
                .chunks_exact(dim)
                .flat_map(|p| geodesy::to_ecef(p[0], p[1], if dim > 2 { p[2] } else { 0.0 }))
                .collect::<Vec<f64>>();
            (ecef.as_slice(), 3)
        }
    };
    CurveBuilder::new(pts, d)
        .closed(closed)
        .param(opts.param.clone())
        .alpha(opts.alpha)
        .through(opts.through)
        .build()
}

/// ECEF vertices (flat, 3 a vertex) as longitude, latitude (and height
/// when `dim` is 3): each longitude within 180 degrees of the one before
/// (from the first control point's), then written in the control points'
/// convention; an open curve's end vertices are its end control points
/// exactly, and a closed curve's last vertex its first.
fn from_ecef(xyz: &[f64], ctrl: &[f64], dim: usize, closed: bool) -> Vec<f64> {
    let convention = Convention::of(ctrl.chunks_exact(dim).map(|p| p[0]));
    let mut out = Vec::with_capacity(xyz.len() / 3 * dim);
    let mut prev = ctrl[0];
    for p in xyz.chunks_exact(3) {
        let (lon, lat, h) = geodesy::from_ecef([p[0], p[1], p[2]]);
        let lon = geodesy::unwrap_near(lon, prev);
        prev = lon;
        out.push(convention.apply(lon));
        out.push(lat);
        if dim > 2 {
            out.push(h);
        }
    }
    let n = out.len();
    if n >= dim {
        if closed {
            if xyz[..3] == xyz[xyz.len() - 3..] {
                let first = out[..dim].to_vec();
                out[n - dim..].copy_from_slice(&first);
            }
        } else {
            out[..dim].copy_from_slice(&ctrl[..dim]);
            out[n - dim..].copy_from_slice(&ctrl[ctrl.len() - dim..]);
        }
    }
    out
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
    let mut coords = match opts.frame {
        Frame::Plane => poly.coords().to_vec(),
        Frame::Geographic => from_ecef(poly.coords(), ctrl, dim, curve.is_closed()),
    };
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
