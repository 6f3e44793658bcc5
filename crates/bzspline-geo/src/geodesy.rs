//! Longitude and latitude on the WGS 84 ellipsoid, as Earth-centred,
//! Earth-fixed (ECEF) coordinates in metres and back: the frame in which
//! [`crate::Frame::Geographic`] builds and flattens curves, so that their
//! parameters and tolerance are ground distances everywhere, with no seam
//! at the antimeridian and no singularity at the poles.

/// WGS 84's semi-major axis, in metres.
pub const WGS84_A: f64 = 6_378_137.0;

/// WGS 84's flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;

/// Metres in one degree of a great circle on a sphere of WGS 84's mean
/// radius (6,371,008.8 m): how a default tolerance found in degrees becomes
/// one in metres.
pub const METRES_PER_DEGREE: f64 = 6_371_008.8 * std::f64::consts::PI / 180.0;

/// The square of the first eccentricity.
fn e2() -> f64 {
    WGS84_F * (2.0 - WGS84_F)
}

// Every transcendental function here is `libm`'s (a port of musl's), not
// the platform's, so that a curve comes out the same to the bit natively and
// in WebAssembly, on every operating system.
use libm::{atan2, cos, hypot, sin};

fn sin_cos(x: f64) -> (f64, f64) {
    (sin(x), cos(x))
}

/// ECEF coordinates (metres) of longitude and latitude in degrees and the
/// height above the ellipsoid in metres.
#[must_use]
pub fn to_ecef(lon: f64, lat: f64, h: f64) -> [f64; 3] {
    let (sl, cl) = sin_cos(lon.to_radians());
    let (sp, cp) = sin_cos(lat.to_radians());
    let n = WGS84_A / (1.0 - e2() * sp * sp).sqrt();
    [
        (n + h) * cp * cl,
        (n + h) * cp * sl,
        (n * (1.0 - e2()) + h) * sp,
    ]
}

/// Longitude (in `(-180, 180]`) and latitude in degrees and the height in
/// metres of ECEF coordinates: Bowring's formula with two refinements,
/// exact to well under a micrometre near the surface.
#[must_use]
pub fn from_ecef([x, y, z]: [f64; 3]) -> (f64, f64, f64) {
    let a = WGS84_A;
    let b = a * (1.0 - WGS84_F);
    let e2 = e2();
    let ep2 = e2 / (1.0 - e2);
    let p = hypot(x, y);
    let lon = atan2(y, x);
    // Bowring's first estimate, then Newton-like refinements.
    let mut lat = atan2(z * a, p * b);
    let (s, c) = sin_cos(lat);
    lat = atan2(z + ep2 * b * s * s * s, p - e2 * a * c * c * c);
    for _ in 0..2 {
        let (s, c) = sin_cos(lat);
        let n = a / (1.0 - e2 * s * s).sqrt();
        let h = if c.abs() > 1e-12 {
            p / c - n
        } else {
            z.abs() - b
        };
        lat = atan2(z, p * (1.0 - e2 * n / (n + h)));
    }
    let (s, c) = sin_cos(lat);
    let n = a / (1.0 - e2 * s * s).sqrt();
    let h = if c.abs() > 1e-9 {
        p / c - n
    } else {
        z.abs() / s.abs() - n * (1.0 - e2)
    };
    (lon.to_degrees(), lat.to_degrees(), h)
}

/// `lon` moved by whole turns to lie within 180 degrees of `reference`.
#[must_use]
pub fn unwrap_near(lon: f64, reference: f64) -> f64 {
    let d = lon - reference;
    lon - 360.0 * (d / 360.0).round()
}

/// How a set of longitudes is written: within `[-180, 180]`, within
/// `[0, 360]`, or neither (unwrapped along a line).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// `[-180, 180]`.
    Signed,
    /// `[0, 360]`.
    Positive,
    /// Anything else: kept continuous.
    Unwrapped,
}

impl Convention {
    /// The convention longitudes follow.
    pub fn of(lons: impl IntoIterator<Item = f64>) -> Convention {
        let (mut signed, mut positive) = (true, true);
        for l in lons {
            signed &= (-180.0..=180.0).contains(&l);
            positive &= (0.0..=360.0).contains(&l);
        }
        match (signed, positive) {
            (true, _) => Convention::Signed,
            (false, true) => Convention::Positive,
            _ => Convention::Unwrapped,
        }
    }

    /// `lon` written in this convention (unchanged when unwrapped).
    #[must_use]
    pub fn apply(self, lon: f64) -> f64 {
        match self {
            Convention::Signed if lon > 180.0 => lon - 360.0,
            Convention::Signed if lon < -180.0 => lon + 360.0,
            Convention::Positive if lon < 0.0 => lon + 360.0,
            Convention::Positive if lon > 360.0 => lon - 360.0,
            _ => lon,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ecef_round_trips_everywhere_including_the_poles() {
        for lat in [
            -90.0,
            -89.999_999,
            -45.0,
            0.0,
            12.5,
            60.0,
            85.0,
            89.99,
            90.0,
        ] {
            for lon in [-180.0, -179.5, -1.0, 0.0, 33.3, 179.999, 180.0] {
                for h in [0.0, -50.0, 1234.5] {
                    let (lo, la, hh) = from_ecef(to_ecef(lon, lat, h));
                    assert!((la - lat).abs() < 1e-11, "{lon} {lat}: lat {la}");
                    assert!((hh - h).abs() < 1e-6, "{lon} {lat}: h {hh}");
                    if lat.abs() < 90.0 {
                        let d = unwrap_near(lo, lon) - lon;
                        assert!(
                            d.abs() * lat.to_radians().cos() < 1e-11,
                            "{lon} {lat}: lon {lo}"
                        );
                    }
                }
            }
        }
        // The equator's radius and the pole's distance are WGS 84's axes.
        assert!((to_ecef(0.0, 0.0, 0.0)[0] - WGS84_A).abs() < 1e-6);
        assert!((to_ecef(0.0, 90.0, 0.0)[2] - WGS84_A * (1.0 - WGS84_F)).abs() < 1e-6);
    }

    #[test]
    fn conventions_are_kept() {
        assert_eq!(Convention::of([-179.0, 178.0]), Convention::Signed);
        assert_eq!(Convention::of([190.0, 350.0]), Convention::Positive);
        assert_eq!(Convention::of([-10.0, 190.0]), Convention::Unwrapped);
        assert_eq!(Convention::Signed.apply(180.5), -179.5);
        assert_eq!(Convention::Positive.apply(-0.5), 359.5);
        assert_eq!(unwrap_near(-179.0, 179.0), 181.0);
    }
}
