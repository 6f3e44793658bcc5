//! The options more than one entry point takes (the command, its server,
//! the bindings), parsed once: shape parameters as decimals or fractions
//! ([`bzspline::text::parse_fraction`], [`bzspline::text::parse_alpha`], re-exported
//! here). The parametrisation's names are [`bzspline::Param`]'s own
//! (`"centripetal".parse()`), the smoothing options' checks and defaults
//! [`bzspline_geo::SmoothOptions`]'s.

pub use bzspline::text::{parse_alpha, parse_fraction};
use bzspline::Smoothing;

/// A smoothing weight, as `--smooth` and the bindings take it: `auto` (or
/// `gcv`) for the `lambda` of least generalized cross-validation score, or
/// a `lambda` itself, a finite number of at least 0.
///
/// # Errors
///
/// Anything else, as the words of the option's message.
pub fn parse_smoothing(s: &str) -> Result<Smoothing, String> {
    let t = s.trim();
    if t.eq_ignore_ascii_case("auto") || t.eq_ignore_ascii_case("gcv") {
        return Ok(Smoothing::Gcv);
    }
    match t.parse::<f64>() {
        Ok(v) => check_lambda(v)
            .map(Smoothing::Lambda)
            .map_err(str::to_owned),
        Err(_) => Err(format!("must be auto or a number of at least 0 (got {s})")),
    }
}

/// A smoothing `lambda`: a finite number of at least 0.
///
/// # Errors
///
/// Negative, infinite or NaN, as the words of the option's message (`must be ...`).
pub fn check_lambda(v: f64) -> Result<f64, &'static str> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err("must be auto or a number of at least 0")
    }
}

/// A flattening tolerance (or a sampling step): a positive finite number.
///
/// # Errors
///
/// Zero, negative, infinite or NaN, as the words of the option's message (`must be ...`).
pub fn check_positive(v: f64) -> Result<f64, &'static str> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err("must be a positive number")
    }
}

/// A snap distance: a finite number of at least 0.
///
/// # Errors
///
/// Negative, infinite or NaN, as the words of the option's message (`must be ...`).
pub fn check_snap(v: f64) -> Result<f64, &'static str> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err("must be a number of at least 0")
    }
}

/// A keep-angle: degrees from 0 to 180.
///
/// # Errors
///
/// Outside [0, 180] or NaN, as the words of the option's message (`must be ...`).
pub fn check_keep_angle(v: f64) -> Result<f64, &'static str> {
    if (0.0..=180.0).contains(&v) {
        Ok(v)
    } else {
        Err("must be an angle from 0 to 180 degrees")
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn smoothing_is_auto_or_a_lambda() {
        use super::parse_smoothing;
        use bzspline::Smoothing;
        assert_eq!(parse_smoothing("auto"), Ok(Smoothing::Gcv));
        assert_eq!(parse_smoothing(" GCV "), Ok(Smoothing::Gcv));
        assert_eq!(parse_smoothing("0"), Ok(Smoothing::Lambda(0.0)));
        assert_eq!(parse_smoothing("1e-3"), Ok(Smoothing::Lambda(1e-3)));
        for bad in ["-1", "nan", "inf", "", "lots"] {
            assert!(parse_smoothing(bad).is_err(), "{bad}");
        }
    }

    use super::*;

    #[test]
    fn ranges() {
        assert!(check_positive(0.0).is_err());
        assert!(check_positive(f64::INFINITY).is_err());
        assert_eq!(check_snap(0.0), Ok(0.0));
        assert!(check_snap(-1e-9).is_err());
        assert!(check_keep_angle(f64::NAN).is_err());
        assert_eq!(check_keep_angle(180.0), Ok(180.0));
    }
}
