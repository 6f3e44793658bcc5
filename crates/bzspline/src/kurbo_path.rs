//! Conversion into [`kurbo::BezPath`] (feature `kurbo`).

use crate::curve::Curve;
use crate::error::Error;
use crate::spline::Spline;
use kurbo::{BezPath, Point};

fn check(v: &[f64]) -> Result<(), Error> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::Overflow {
            what: "a Bezier control point",
        })
    }
}

impl Curve {
    /// The planar curve as a [`kurbo::BezPath`]: one `curve_to` per segment,
    /// closed with `close_path` for a closed curve.
    ///
    /// # Errors
    ///
    /// As [`Curve::to_svg_path`].
    ///
    /// # Examples
    ///
    /// ```
    /// use bzspline::Curve;
    /// let c = Curve::closed(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])?;
    /// let path = c.to_bez_path()?;
    /// assert_eq!(path.segments().count(), 4);
    /// # Ok::<(), bzspline::Error>(())
    /// ```
    pub fn to_bez_path(&self) -> Result<BezPath, Error> {
        self.check_planar("a kurbo path needs a planar curve; dimension")?;
        let mut path = BezPath::new();
        for k in 0..self.len() {
            let p = self.segment_points(k).unwrap_or_default();
            check(&p)?;
            if k == 0 {
                path.move_to(Point::new(p[0], p[1]));
            }
            path.curve_to(
                Point::new(p[2], p[3]),
                Point::new(p[4], p[5]),
                Point::new(p[6], p[7]),
            );
        }
        if self.is_closed() {
            path.close_path();
        }
        Ok(path)
    }
}

impl Spline {
    /// The graph of the spline as a [`kurbo::BezPath`], one `curve_to` per
    /// piece (see [`Spline::segment`]).
    ///
    /// # Errors
    ///
    /// [`Error::Overflow`] when a Bezier control point exceeds the range of a
    /// double.
    pub fn to_bez_path(&self) -> Result<BezPath, Error> {
        let mut path = BezPath::new();
        for (k, s) in self.segments().iter().enumerate() {
            check(s.p.as_flattened())?;
            if k == 0 {
                path.move_to(Point::new(s.p[0][0], s.p[0][1]));
            }
            path.curve_to(
                Point::new(s.p[1][0], s.p[1][1]),
                Point::new(s.p[2][0], s.p[2][1]),
                Point::new(s.p[3][0], s.p[3][1]),
            );
        }
        Ok(path)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::{ParamCurve, PathEl};

    #[test]
    fn curve_path_has_the_same_segments() {
        let c = Curve::closed(&[[0.0, 0.0], [2.0, 0.5], [1.0, 3.0], [-1.0, 1.0]]).unwrap();
        let path = c.to_bez_path().unwrap();
        let els = path.elements();
        assert!(matches!(els[0], PathEl::MoveTo(_)));
        assert!(matches!(els[els.len() - 1], PathEl::ClosePath));
        for (k, seg) in path.segments().enumerate() {
            let want = c.segment::<2>(k).unwrap();
            for i in 0..=10 {
                let t = i as f64 / 10.0;
                let (p, w) = (seg.eval(t), want.eval(t));
                assert!((p.x - w[0]).abs() < 1e-14 && (p.y - w[1]).abs() < 1e-14);
            }
        }
        let c3 = Curve::open(&[[0.0; 3], [1.0; 3]]).unwrap();
        assert!(c3.to_bez_path().is_err());
    }

    #[test]
    fn spline_path_follows_the_graph() {
        let s = Spline::new(&[0.0, 1.0, 2.5, 3.0], &[1.0, -1.0, 2.0, 0.0]).unwrap();
        let path = s.to_bez_path().unwrap();
        assert_eq!(path.segments().count(), 3);
        for seg in path.segments() {
            let p = seg.eval(0.37);
            let y = s.eval(p.x).unwrap();
            assert!(
                (p.y - y).abs() < 1e-12,
                "at x = {}: want {y}, got {}",
                p.x,
                p.y
            );
        }
    }
}
