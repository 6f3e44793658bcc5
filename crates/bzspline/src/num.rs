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
        // The shortest digits once, in exponent notation (the plain form
        // has the same digits), on the stack: `-d.ddddddddddddddddde-308`
        // at most.
        let mut buf = Buf::default();
        fmt::Write::write_fmt(&mut buf, format_args!("{v:e}"))?;
        let exp_form = buf.as_str()?;
        let (sign, rest) = match exp_form.strip_prefix('-') {
            Some(r) => ("-", r),
            None => ("", exp_form),
        };
        let (mantissa, e) = rest.split_once('e').ok_or(fmt::Error)?;
        let e: i32 = e.parse().map_err(|_| fmt::Error)?;
        // The digits `d1 d2 ..`, of value `0.d1 d2 .. * 10^(e + 1)`: one
        // before the point, the rest after it.
        let lead = mantissa.get(..1).ok_or(fmt::Error)?;
        let tail = mantissa.get(1..).unwrap_or_default();
        let tail = tail.strip_prefix('.').unwrap_or(tail);
        let n = 1 + tail.len() as i32;
        // The plain form: the digits with the point after `e + 1` of them,
        // padded with zeros, no point when they are all before it.
        let plain_len = if e >= 0 {
            if n <= e + 1 {
                e + 1
            } else {
                n + 1
            }
        } else {
            n + 1 - e
        };
        if (exp_form.len() - sign.len()) < plain_len as usize {
            return f.write_str(exp_form);
        }
        f.write_str(sign)?;
        if e < 0 {
            f.write_str("0.")?;
            zeros(f, (-e - 1) as usize)?;
            f.write_str(lead)?;
            f.write_str(tail)
        } else if n <= e + 1 {
            f.write_str(lead)?;
            f.write_str(tail)?;
            zeros(f, (e + 1 - n) as usize)
        } else {
            let (whole, fraction) = tail.split_at(e as usize);
            f.write_str(lead)?;
            f.write_str(whole)?;
            f.write_str(".")?;
            f.write_str(fraction)
        }
    }
}

/// Writes `k` zeros.
fn zeros(f: &mut fmt::Formatter<'_>, mut k: usize) -> fmt::Result {
    const Z: &str = "00000000000000000000000000000000";
    while k > 0 {
        let step = k.min(Z.len());
        f.write_str(&Z[..step])?;
        k -= step;
    }
    Ok(())
}

/// A double's text on the stack.
struct Buf {
    bytes: [u8; 40],
    len: usize,
}

impl Default for Buf {
    fn default() -> Self {
        Buf {
            bytes: [0; 40],
            len: 0,
        }
    }
}

impl Buf {
    fn as_str(&self) -> Result<&str, fmt::Error> {
        core::str::from_utf8(&self.bytes[..self.len]).map_err(|_| fmt::Error)
    }
}

impl fmt::Write for Buf {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        let end = self.len + s.len();
        self.bytes
            .get_mut(self.len..end)
            .ok_or(fmt::Error)?
            .copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
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
        // Numbers as data holds them: coordinates and measurements with a
        // few decimals, integers, powers of ten and their neighbours.
        for k in 0..20_000u64 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let unit = (x >> 11) as f64 / (1u64 << 53) as f64;
            let e = (k % 48) as i32 - 24;
            let decimals = 10f64.powi((k % 9) as i32);
            values.push((unit * 360.0 - 180.0) * 10f64.powi(e));
            values.push(((unit * 1e6).round() / decimals) * if k % 2 == 0 { 1.0 } else { -1.0 });
            values.push(10f64.powi(e));
            values.push(f64::from_bits(10f64.powi(e).to_bits() + 1));
            values.push(f64::from_bits(10f64.powi(e).to_bits() - 1));
            values.push((x >> 40) as f64);
        }
        for v in values {
            let s = Shortest(v).to_string();
            let back: f64 = s.parse().unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{v:e} -> {s}");
            // Rust's two forms, the shorter (plain on a tie).
            let (plain, exp) = (format!("{v}"), format!("{v:e}"));
            let want = if exp.len() < plain.len() { exp } else { plain };
            assert_eq!(s, want, "{v:e}");
        }
        assert_eq!(Shortest(1e15).to_string(), "1e15");
        assert_eq!(Shortest(-0.0).to_string(), "-0");
        assert_eq!(Shortest(123456.0).to_string(), "123456");
    }
}
