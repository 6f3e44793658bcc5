//! Smoothing as a trait on geo-types, as geo's `ChaikinSmoothing` and
//! `Simplify` are: `polygon.smooth(&opts)`, `line_string.smooth(&opts)`, and
//! through `Geometry` for any of them.
//!
//! A geometry is smoothed as a coverage of its own ([`Coverage`]): the rings
//! of a polygon, and the members of a multi-geometry or collection, keep the
//! borders and positions they share, and what was valid stays valid. To keep
//! borders shared *between* geometries, smooth them together as one
//! [`Coverage`].

use geo_types::{
    Geometry, GeometryCollection, LineString, MultiLineString, MultiPolygon, Polygon, Rect,
    Triangle,
};

use crate::coverage::Coverage;
use crate::error::Error;
use crate::options::SmoothOptions;

/// Geometries smoothed with the method's curves, each as a coverage of its
/// own (see the crate docs).
///
/// # Examples
///
/// ```
/// use bzspline_geo::{Smooth, SmoothOptions};
/// use geo_types::{line_string, polygon};
///
/// let road = line_string![(x: 0.0, y: 0.0), (x: 2.0, y: 2.0), (x: 4.0, y: 0.0)];
/// let smooth = road.smooth(&SmoothOptions::default().tolerance(1e-3))?;
/// // The ends stay; the corner is cut by a curve.
/// assert_eq!(smooth.0.first(), road.0.first());
/// assert_eq!(smooth.0.last(), road.0.last());
/// assert!(smooth.0.len() > road.0.len());
///
/// let square = polygon![(x: 0.0, y: 0.0), (x: 1.0, y: 0.0), (x: 1.0, y: 1.0), (x: 0.0, y: 1.0)];
/// let round = square.smooth(&SmoothOptions::default())?;
/// assert!(round.exterior().0.len() > 5);
/// # Ok::<(), bzspline_geo::Error>(())
/// ```
pub trait Smooth {
    /// What smoothing gives: the same type, but a Polygon for a [`Rect`] or
    /// [`Triangle`].
    type Output;

    /// The geometry smoothed with `opts` (the tolerance by default
    /// [`DEFAULT_TOLERANCE_FRACTION`](crate::DEFAULT_TOLERANCE_FRACTION) of
    /// its own extent's diagonal). Points and MultiPoints come back as they
    /// are; a Line, as the two positions it is.
    ///
    /// # Errors
    ///
    /// As [`Coverage::new`] and [`Coverage::smooth`]: a coordinate that is not
    /// finite, an option out of range.
    fn smooth(&self, opts: &SmoothOptions) -> Result<Self::Output, Error>;
}

/// One geometry smoothed as a coverage of its own.
fn alone(g: Geometry<f64>, opts: &SmoothOptions) -> Result<Geometry<f64>, Error> {
    let (mut out, _) = Coverage::new(vec![g])?.smooth(opts)?;
    // A coverage gives back one geometry for each it was given.
    Ok(out
        .pop()
        .unwrap_or(Geometry::GeometryCollection(GeometryCollection(vec![]))))
}

impl Smooth for Geometry<f64> {
    type Output = Geometry<f64>;

    fn smooth(&self, opts: &SmoothOptions) -> Result<Geometry<f64>, Error> {
        alone(self.clone(), opts)
    }
}

/// Implements [`Smooth`] for a geo-types type that comes back as `$out`
/// (the `Geometry` variant it is smoothed as).
macro_rules! smooth_as {
    ($t:ty, $in:ident, $out:ident) => {
        impl Smooth for $t {
            type Output = $out<f64>;

            fn smooth(&self, opts: &SmoothOptions) -> Result<$out<f64>, Error> {
                match alone(Geometry::$in(self.clone()), opts)? {
                    Geometry::$out(g) => Ok(g),
                    // A coverage keeps every geometry's kind (Rects and
                    // Triangles become Polygons); nothing else comes back.
                    _ => unreachable!("smoothing keeps the kind of a {}", stringify!($t)),
                }
            }
        }
    };
}

smooth_as!(LineString<f64>, LineString, LineString);
smooth_as!(MultiLineString<f64>, MultiLineString, MultiLineString);
smooth_as!(Polygon<f64>, Polygon, Polygon);
smooth_as!(MultiPolygon<f64>, MultiPolygon, MultiPolygon);
smooth_as!(
    GeometryCollection<f64>,
    GeometryCollection,
    GeometryCollection
);
smooth_as!(Rect<f64>, Rect, Polygon);
smooth_as!(Triangle<f64>, Triangle, Polygon);

#[cfg(test)]
mod tests {
    use super::*;
    use geo_types::{coord, polygon};

    #[test]
    fn a_geometry_alone_is_its_own_coverage() {
        let a = polygon![(x: 0.0, y: 0.0), (x: 2.0, y: 0.0), (x: 2.0, y: 1.0), (x: 1.0, y: 2.0), (x: 0.0, y: 1.0)];
        let b = polygon![(x: 2.0, y: 0.0), (x: 4.0, y: 0.0), (x: 4.0, y: 2.0), (x: 2.0, y: 1.0)];
        let opts = SmoothOptions::default().tolerance(1e-3);
        let both = MultiPolygon(vec![a.clone(), b.clone()]);
        let got = both.smooth(&opts).unwrap();
        let (want, _) = Coverage::new(vec![Geometry::MultiPolygon(both.clone())])
            .unwrap()
            .smooth(&opts)
            .unwrap();
        assert_eq!(Geometry::MultiPolygon(got.clone()), want[0]);
        // The two members keep their border: (2, 0) - (2, 1) in both.
        for p in &got.0 {
            assert!(p.exterior().0.contains(&coord! { x: 2.0, y: 1.0 }), "{p:?}");
        }
        // Through Geometry, the same.
        assert_eq!(Geometry::MultiPolygon(both).smooth(&opts).unwrap(), want[0]);
        // Alone, a member is smoothed as its own coverage.
        assert_eq!(
            Geometry::Polygon(a.smooth(&opts).unwrap()),
            Geometry::Polygon(a).smooth(&opts).unwrap()
        );
    }

    #[test]
    fn rects_come_back_polygons_and_bad_coordinates_are_errors() {
        let r = Rect::new(coord! { x: 0.0, y: 0.0 }, coord! { x: 2.0, y: 1.0 });
        let p = r.smooth(&SmoothOptions::default()).unwrap();
        assert!(p.exterior().0.len() > 5);
        let bad = LineString::from(vec![(0.0, 0.0), (1.0, f64::NAN), (2.0, 0.0)]);
        assert!(matches!(
            bad.smooth(&SmoothOptions::default()),
            Err(Error::NonFinite { .. })
        ));
        let opts = SmoothOptions::default().tolerance(-1.0);
        assert!(r.smooth(&opts).is_err());
    }
}
