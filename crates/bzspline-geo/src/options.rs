//! How to smooth: [`SmoothOptions`] and the checks of every option's range,
//! which the command, its server and the bindings call instead of checking
//! ranges themselves; the default tolerance.

use bzspline::Param;

use crate::error::Error;

/// The default flattening tolerance as a fraction of the diagonal of the
/// data's bounding box.
pub const DEFAULT_TOLERANCE_FRACTION: f64 = 1e-4;

/// How to smooth.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SmoothOptions {
    /// Largest distance between the smooth curve and the output polyline;
    /// `None`: [`DEFAULT_TOLERANCE_FRACTION`] of the data's bounding-box
    /// diagonal.
    pub tolerance: Option<f64>,
    /// The shape parameter of every interval, in `[1/3, 2/3]`.
    pub alpha: f64,
    /// How the curve's parameters follow the positions.
    pub param: Param,
    /// Positions where the polyline turns by more than this many degrees stay
    /// where they are, as corners (in the geographic frame, the angle on the
    /// ground).
    pub keep_angle: Option<f64>,
    /// Pass through every position (the interpolating variant,
    /// `docs/method.md` §11) instead of cutting the corners: the output keeps
    /// every position of the input.
    pub through: bool,
    /// What the positions are: points of the plane, or longitude and
    /// latitude on the Earth (then the tolerance is in metres).
    pub frame: Frame,
}

/// What positions are, and so in what units the tolerance is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Frame {
    /// Points of the plane (projected coordinates, pixels): curves are built
    /// and flattened in the positions' own units.
    #[default]
    Plane,
    /// Longitude and latitude in degrees (then height in metres) on WGS 84:
    /// curves are built through the positions' places on the ellipsoid
    /// ([`crate::geodesy`]) and flattened to a tolerance in metres, so that
    /// parameters and tolerance are ground distances at every latitude,
    /// across the antimeridian and around the poles; output longitudes are
    /// written as the input writes them (`[-180, 180]`, `[0, 360]`, or
    /// continuous); corners for [`SmoothOptions::keep_angle`] are measured
    /// on the ground, and so is snapping in a coverage built in this frame
    /// ([`crate::CoverageBuilder::frame`]).
    Geographic,
}

impl Default for SmoothOptions {
    fn default() -> Self {
        SmoothOptions {
            tolerance: None,
            alpha: bzspline::DEFAULT_ALPHA,
            param: Param::Centripetal,
            keep_angle: None,
            through: false,
            frame: Frame::Plane,
        }
    }
}

impl SmoothOptions {
    /// Sets what the positions are (the plane, or longitude and latitude).
    #[must_use]
    pub fn frame(mut self, frame: Frame) -> Self {
        self.frame = frame;
        self
    }

    /// The tolerance to flatten to when none is given, from the default of
    /// the data's extent in its coordinates ([`default_tolerance_of`]): in
    /// the geographic frame that many degrees as metres of a great circle.
    #[must_use]
    pub fn default_tolerance_from(&self, extent_default: f64) -> f64 {
        match self.frame {
            Frame::Plane => extent_default,
            Frame::Geographic => extent_default * crate::geodesy::METRES_PER_DEGREE,
        }
    }

    /// Sets the flattening tolerance.
    #[must_use]
    pub fn tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = Some(tolerance);
        self
    }

    /// Sets the shape parameter.
    #[must_use]
    pub fn alpha(mut self, alpha: f64) -> Self {
        self.alpha = alpha;
        self
    }

    /// Sets the parametrisation.
    #[must_use]
    pub fn param(mut self, param: Param) -> Self {
        self.param = param;
        self
    }

    /// Passes through every position (`true`) or cuts the corners (`false`, the
    /// default).
    #[must_use]
    pub fn through(mut self, through: bool) -> Self {
        self.through = through;
        self
    }

    /// Keeps corners sharper than `degrees`.
    #[must_use]
    pub fn keep_angle(mut self, degrees: f64) -> Self {
        self.keep_angle = Some(degrees);
        self
    }

    /// Checks every option's range: alpha in `[1/3, 2/3]`
    /// ([`bzspline::check_alpha`]), a tolerance positive and finite, a
    /// keep-angle from 0 to 180 degrees. Smoothing checks them first; the
    /// command, its server and the bindings check them here too, before
    /// reading any data. The keep-angle is a turning angle in the plane (x,
    /// y) everywhere, positions with z included.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidOption`] naming the first option at fault.
    pub fn validate(&self) -> Result<(), Error> {
        if bzspline::check_alpha(self.alpha).is_err() {
            return Err(Error::InvalidOption {
                option: "alpha",
                rule: "must be in [1/3, 2/3]",
                value: self.alpha,
            });
        }
        if let Some(t) = self.tolerance {
            check_tolerance(t)?;
        }
        if let Some(a) = self.keep_angle {
            check_keep_angle(a)?;
        }
        Ok(())
    }
}

/// A flattening tolerance: a positive finite number.
///
/// # Errors
///
/// [`Error::InvalidOption`] otherwise.
pub fn check_tolerance(tolerance: f64) -> Result<f64, Error> {
    if tolerance.is_finite() && tolerance > 0.0 {
        Ok(tolerance)
    } else {
        Err(Error::InvalidOption {
            option: "tolerance",
            rule: "must be a positive number",
            value: tolerance,
        })
    }
}

/// A keep-angle: degrees from 0 to 180, the turning angle in the plane.
///
/// # Errors
///
/// [`Error::InvalidOption`] otherwise (NaN included).
pub fn check_keep_angle(degrees: f64) -> Result<f64, Error> {
    if (0.0..=180.0).contains(&degrees) {
        Ok(degrees)
    } else {
        Err(Error::InvalidOption {
            option: "keep-angle",
            rule: "must be an angle from 0 to 180 degrees",
            value: degrees,
        })
    }
}

/// A snap distance ([`crate::snap`], [`crate::CoverageBuilder::snap`]): a finite
/// number of at least 0.
///
/// # Errors
///
/// [`Error::InvalidOption`] otherwise.
pub fn check_snap(eps: f64) -> Result<f64, Error> {
    if eps.is_finite() && eps >= 0.0 {
        Ok(eps)
    } else {
        Err(Error::InvalidOption {
            option: "snap",
            rule: "must be a number of at least 0",
            value: eps,
        })
    }
}

/// The flattening tolerance smoothing takes when none is given: the
/// fraction [`DEFAULT_TOLERANCE_FRACTION`] of the diagonal of the box from
/// `lo` to `hi` (the data's extent, `[x, y]`), or 1 when that diagonal is zero
/// or not finite (a single position, no positions). Every entry point (the
/// command, ring by ring too, and the bindings) takes its default from here.
#[must_use]
pub fn default_tolerance_of(lo: [f64; 2], hi: [f64; 2]) -> f64 {
    let diag = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    if diag.is_finite() && diag > 0.0 {
        diag * DEFAULT_TOLERANCE_FRACTION
    } else {
        1.0
    }
}
