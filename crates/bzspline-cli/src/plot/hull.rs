//! The convex hull of points in the plane (Andrew's monotone chain).

/// The convex hull of the finite points of `points`, counter-clockwise from the
/// lowest-leftmost point, without collinear points. Fewer than three distinct
/// points give those points (a segment or a point). O(n log n).
#[must_use]
pub fn convex_hull(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut p: Vec<[f64; 2]> = points
        .iter()
        .copied()
        .filter(|q| q[0].is_finite() && q[1].is_finite())
        .collect();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    // Cross product of (a - o) and (b - o), on coordinates halved so that it stays
    // finite for any finite input; only its sign is used.
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        let (ax, ay) = (a[0] / 2.0 - o[0] / 2.0, a[1] / 2.0 - o[1] / 2.0);
        let (bx, by) = (b[0] / 2.0 - o[0] / 2.0, b[1] / 2.0 - o[1] / 2.0);
        ax * by - ay * bx
    };
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * p.len());
    for pass in [false, true] {
        let start = hull.len();
        let pts: Box<dyn Iterator<Item = &[f64; 2]>> = if pass {
            Box::new(p.iter().rev())
        } else {
            Box::new(p.iter())
        };
        for &q in pts {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        // The last point of each chain is the first of the other.
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_known_points() {
        let pts = [
            [0.0, 0.0],
            [2.0, 0.0],
            [1.0, 1.0],
            [2.0, 2.0],
            [0.0, 2.0],
            [1.0, 0.0],
            [0.5, 1.5],
            [f64::NAN, 7.0],
            [2.0, 2.0],
        ];
        let h = convex_hull(&pts);
        assert_eq!(h, vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
    }

    #[test]
    fn hull_of_example_1_and_degenerate_input() {
        let f = crate::input::EXAMPLE1;
        let pts: Vec<[f64; 2]> = f
            .iter()
            .enumerate()
            .map(|(i, y)| [i as f64 + 1.0, *y])
            .collect();
        let h = convex_hull(&pts);
        assert_eq!(
            h,
            vec![[1.0, 1.0], [8.0, 1.0], [11.0, 1.5], [9.0, 10.0], [2.0, 3.0]]
        );
        assert_eq!(convex_hull(&[]), Vec::<[f64; 2]>::new());
        assert_eq!(convex_hull(&[[1.0, 1.0], [1.0, 1.0]]), vec![[1.0, 1.0]]);
        // Collinear points: the two ends.
        let line = convex_hull(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]);
        assert_eq!(line, vec![[0.0, 0.0], [2.0, 2.0]]);
        let big = convex_hull(&[[-f64::MAX, 0.0], [f64::MAX, 0.0], [0.0, f64::MAX]]);
        assert_eq!(big.len(), 3);
    }
}
