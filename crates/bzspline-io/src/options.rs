//! The options more than one entry point takes (the command, its server,
//! the bindings), parsed once: shape parameters as decimals or fractions
//! ([`bzspline::text::parse_fraction`], [`bzspline::text::parse_alpha`], re-exported
//! here). The parametrisation's names are [`bzspline::Param`]'s own
//! (`"centripetal".parse()`), the smoothing options' checks and defaults
//! [`bzspline_geo::SmoothOptions`]'s ([`bzspline_geo::SmoothOptions::validate`],
//! [`bzspline_geo::check_snap`]).

pub use bzspline::text::{parse_alpha, parse_fraction};
use bzspline::Smoothing;

/// What `--smooth` (and the bindings' `smooth`) must be, for messages.
pub const LAMBDA_RULE: &str = "must be auto or a number of at least 0";

/// A smoothing weight, as `--smooth` and the bindings take it: `auto` (or
/// `gcv`) for the `lambda` of least generalized cross-validation score, or
/// a `lambda` itself, a finite number of at least 0 ([`Smoothing::check`]).
///
/// # Errors
///
/// Anything else, as the words of the option's message.
pub fn parse_smoothing(s: &str) -> Result<Smoothing, String> {
    let t = s.trim();
    if t.eq_ignore_ascii_case("auto") || t.eq_ignore_ascii_case("gcv") {
        return Ok(Smoothing::Gcv);
    }
    t.parse::<f64>()
        .ok()
        .and_then(|v| Smoothing::Lambda(v).check().ok())
        .ok_or_else(|| format!("{LAMBDA_RULE} (got {s})"))
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
}
