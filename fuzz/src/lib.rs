//! What the fuzz targets share: fuzzer bytes decoded into spline inputs
//! ([`Reader`], [`Data`]), into coverages ([`mosaic`]) and run as `bzspline
//! smooth` runs a file ([`document`]); the formats of `bzspline-io` as the
//! command uses them; the coverage tests' judges ([`judge`]).
//!
//! Half of the inputs are raw doubles (any bit pattern: NaN, infinities,
//! subnormals, unsorted knots), the other half are built so that they are
//! usually valid (increasing knots with widths over many decades, values of
//! any magnitude, alphas in or just outside `[1/3, 2/3]`), so that the
//! properties of accepted input are exercised as well as the refusals.

use bzspline::{ALPHA_MAX, ALPHA_MIN};

// The formats, as the command uses them.
pub use bzspline_io::{api as serve_api, fgb, geoparquet, gpkg, input, model, shp, time, topojson};

/// The checks of smoothed coverages that do not use the code under test
/// (validity from `geo`, crossings by brute force, shared borders), as the
/// coverage tests use them.
pub use bzspline_testing as judge;

pub mod document;
pub mod mosaic;

/// No NaN or infinity in a written JSON value: serde_json writes them as
/// `null`, so a `null` anywhere (or a number that is not finite) fails.
#[must_use]
pub fn finite(v: &serde_json::Value) -> bool {
    use serde_json::Value;
    match v {
        Value::Null => false,
        Value::Number(n) => n.as_f64().is_some_and(f64::is_finite),
        Value::Array(a) => a.iter().all(finite),
        Value::Object(o) => o.values().all(finite),
        _ => true,
    }
}

/// The point limit the reader targets run with, small enough to be reached.
pub const MAX_POINTS: usize = 64;

/// Checks what a reader returned: rows of one width, finite numbers, one
/// position per row; or a one-line message naming the source.
pub fn check_points(name: &str, result: &anyhow::Result<input::Points>) {
    match result {
        Ok(p) => {
            assert_eq!(p.coords.len(), p.len() * p.width, "rows of one width");
            assert!(p.len() <= MAX_POINTS, "more points than the limit");
            if let input::Positions::Lines(l) | input::Positions::Features(l) = &p.pos {
                assert_eq!(l.len(), p.len(), "one position per row");
            }
            assert!(
                p.coords.iter().all(|v| v.is_finite()),
                "non-finite accepted"
            );
            // The command turns library errors into messages with positions.
            if p.width == 2 && !p.is_empty() {
                let (x, y) = (p.column(0), p.column(1));
                if let Err(e) = bzspline::Spline::new(&x, &y) {
                    let msg = input::explain(p, &e).to_string();
                    assert!(!msg.contains('\n'), "two-line message: {msg:?}");
                }
            }
        }
        Err(e) => {
            let chain: Vec<String> = e.chain().map(ToString::to_string).collect();
            let msg = chain.join(": ");
            assert!(
                !msg.contains('\n') && !msg.contains('\r'),
                "two-line message: {msg:?}"
            );
            assert!(
                msg.starts_with(name),
                "message does not name the source: {msg:?}"
            );
        }
    }
}

/// Reads bytes from the front of the fuzzer's input; zeros once it runs out.
pub struct Reader<'a> {
    data: &'a [u8],
}

impl<'a> Reader<'a> {
    /// A reader over `data`.
    pub fn new(data: &'a [u8]) -> Self {
        Reader { data }
    }

    /// Whether every byte has been read.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// The next byte.
    pub fn u8(&mut self) -> u8 {
        match self.data.split_first() {
            Some((b, rest)) => {
                self.data = rest;
                *b
            }
            None => 0,
        }
    }

    /// The next two bytes as a little-endian `u16`.
    pub fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }

    /// The next eight bytes as the bits of a double (any value).
    pub fn raw_f64(&mut self) -> f64 {
        let mut b = [0u8; 8];
        for v in &mut b {
            *v = self.u8();
        }
        f64::from_le_bytes(b)
    }

    /// A power of ten `10^e`, `e` in `lo..=hi`.
    pub fn pow10(&mut self, lo: i32, hi: i32) -> f64 {
        let span = (hi - lo + 1) as u32;
        let e = lo + (u32::from(self.u16()) % span) as i32;
        10f64.powi(e)
    }

    /// A double in `[-1, 1]` with 15 bits of resolution.
    pub fn unit(&mut self) -> f64 {
        f64::from(self.u16() as i16) / 32768.0
    }

    /// A value: raw bits, or a unit number times a shared magnitude.
    pub fn value(&mut self, magnitude: f64) -> f64 {
        match self.u8() % 16 {
            0 => self.raw_f64(),
            1 => 0.0,
            2 => f64::MAX.copysign(self.unit()),
            _ => self.unit() * magnitude,
        }
    }

    /// A shape parameter: mostly inside `[ALPHA_MIN, ALPHA_MAX]`, sometimes a
    /// bound, the double next to a bound, or any bits.
    pub fn alpha(&mut self) -> f64 {
        match self.u8() % 32 {
            0 => ALPHA_MIN,
            1 => ALPHA_MAX,
            2 => ALPHA_MIN.next_down(),
            3 => ALPHA_MAX.next_up(),
            4 => self.raw_f64(),
            _ => ALPHA_MIN + (ALPHA_MAX - ALPHA_MIN) * f64::from(self.u8()) / 255.0,
        }
    }
}

/// Knots, values and alphas decoded from fuzzer bytes.
#[derive(Debug, Clone)]
pub struct Data {
    /// Knots (possibly invalid).
    pub knots: Vec<f64>,
    /// Values (possibly of another length).
    pub values: Vec<f64>,
    /// Alphas (possibly of another length).
    pub alphas: Vec<f64>,
}

impl Data {
    /// Decodes one data set; lengths are kept small (at most 64 knots).
    pub fn decode(r: &mut Reader<'_>) -> Data {
        let mode = r.u8();
        let n = usize::from(r.u8() % 65);
        let mut knots = Vec::with_capacity(n);
        if mode.is_multiple_of(4) {
            // Hostile: any bits.
            for _ in 0..n {
                knots.push(r.raw_f64());
            }
        } else {
            // Increasing, with widths spread over `decades` around a scale.
            let scale = r.pow10(-300, 300);
            let decades = i32::from(r.u8() % 17);
            let mut x = r.unit() * r.pow10(-300, 300);
            for i in 0..n {
                if i > 0 {
                    let w = (1.0 + f64::from(r.u8())) / 256.0 * r.pow10(-decades, decades) * scale;
                    x += w;
                    if r.u8() == 0 {
                        // Now and then a repeated or decreasing knot.
                        x -= w * f64::from(r.u8() % 3);
                    }
                }
                knots.push(x);
            }
        }
        let magnitude = r.pow10(-320, 308);
        let nv = if mode & 0x10 != 0 { n + 1 } else { n };
        let values = (0..nv).map(|_| r.value(magnitude)).collect();
        let na = match (mode >> 5) % 8 {
            0 => 1,
            1 => n,
            _ => n.saturating_sub(1),
        };
        let alphas = (0..na).map(|_| r.alpha()).collect();
        Data {
            knots,
            values,
            alphas,
        }
    }

    /// The largest `|F|`, at least the smallest positive normal double.
    pub fn max_abs(&self) -> f64 {
        self.values
            .iter()
            .fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()))
    }
}

/// `c0 + c1 t + c2 t^2 + c3 t^3`.
pub fn cubic(c: &[f64; 4], t: f64) -> f64 {
    c[0] + t * (c[1] + t * (c[2] + t * c[3]))
}

/// Derivative in `t` of [`cubic`].
pub fn cubic_deriv(c: &[f64; 4], t: f64) -> f64 {
    c[1] + t * (2.0 * c[2] + 3.0 * t * c[3])
}
