//! Writing numbers: the shortest text that reads back as the same double.

use core::fmt;

/// A double written in its shortest round-trip form: Rust's shortest digits,
/// in plain notation (`0.1`, `3`, `-2.5`) or exponent notation (`1e308`,
/// `1.5e-7`), whichever is shorter (plain on a tie); integers without a
/// fraction. Every number this crate writes as text goes through it.
///
/// NaN and the infinities are written as Rust writes them (`NaN`, `inf`),
/// which no reader takes for a number: the writers here refuse them first.
///
/// ```
/// use bzspline::text::Shortest;
/// assert_eq!(Shortest(1e308).to_string(), "1e308");
/// assert_eq!(Shortest(0.1).to_string(), "0.1");
/// assert_eq!(Shortest(100.0).to_string(), "100");
/// assert_eq!(Shortest(1234.5).to_string(), "1234.5");
/// assert_eq!(Shortest(-1.5e-7).to_string(), "-1.5e-7");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shortest(pub f64);

impl fmt::Display for Shortest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if !v.is_finite() {
            return write!(f, "{v}");
        }
        let plain = format!("{v}");
        let exp = format!("{v:e}");
        f.write_str(if exp.len() < plain.len() {
            &exp
        } else {
            &plain
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_reads_back_exactly_and_is_the_shorter() {
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        let mut values = vec![
            0.0,
            -0.0,
            1.0,
            1e15,
            1e16,
            1e-5,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
        ];
        for _ in 0..10_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = f64::from_bits(x);
            if v.is_finite() {
                values.push(v);
            }
        }
        for v in values {
            let s = Shortest(v).to_string();
            let back: f64 = s.parse().unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{v:e} -> {s}");
            assert!(s.len() <= format!("{v}").len() && s.len() <= format!("{v:e}").len());
        }
        assert_eq!(Shortest(1e15).to_string(), "1e15");
        assert_eq!(Shortest(-0.0).to_string(), "-0");
        assert_eq!(Shortest(123456.0).to_string(), "123456");
    }
}
