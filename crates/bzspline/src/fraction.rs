//! Numbers as people write them on a command line or in an option: a
//! decimal or a fraction `p/q` (`1/3` for the smallest shape parameter),
//! parsed once for the command, its server and every binding.

/// A number written as a decimal or a fraction `p/q` (`1/3`, `0.5`): the
/// quotient of the two parsed numbers, the nearest double to the fraction
/// when `p` and `q` are exact.
///
/// # Errors
///
/// The text is neither a finite number nor a fraction with a non-zero denominator.
pub fn parse_fraction(s: &str) -> Result<f64, String> {
    let item = s.trim();
    let v = match item.split_once('/') {
        Some((p, q)) => match (p.trim().parse::<f64>(), q.trim().parse::<f64>()) {
            (Ok(p), Ok(q)) if q != 0.0 => p / q,
            _ => f64::NAN,
        },
        None => item.parse::<f64>().unwrap_or(f64::NAN),
    };
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("{item:?} is not a number or a fraction p/q"))
    }
}

/// A shape parameter: a decimal or a fraction `p/q` ([`parse_fraction`]) in
/// `[1/3, 2/3]`.
///
/// # Errors
///
/// Text that is no number or fraction, or a value outside the range.
pub fn parse_alpha(s: &str) -> Result<f64, String> {
    let v = parse_fraction(s)?;
    crate::check_alpha(v).map_err(|_| format!("{} is outside [1/3, 2/3]", s.trim()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fractions_and_decimals() {
        assert_eq!(parse_fraction("1/3"), Ok(1.0 / 3.0));
        assert_eq!(parse_fraction(" 0.5 "), Ok(0.5));
        assert!(parse_fraction("1/0").is_err());
        assert!(parse_fraction("NaN").is_err());
        assert_eq!(parse_alpha("2/3"), Ok(2.0 / 3.0));
        assert!(parse_alpha("0.7")
            .unwrap_err()
            .contains("outside [1/3, 2/3]"));
    }
}
