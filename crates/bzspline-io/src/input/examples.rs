//! The paper's two examples, the data of `--example 1|2`.

use super::{Points, Pos, Positions};

/// The paper's Example 1: tau = 1..11.
pub const EXAMPLE1: [f64; 11] = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];
/// The paper's Example 2: points of `y = sqrt(x - x^2)` at x = 0, 0.1, ..., 1, with
/// the digits the paper prints.
pub const EXAMPLE2: [f64; 11] = [
    0.0,
    0.3,
    0.4,
    0.458257569,
    0.489897949,
    0.5,
    0.4898979495,
    0.458257569,
    0.4,
    0.3,
    0.0,
];

/// The paper's example `n` (1 or 2) as points `(tau, F)`.
#[must_use]
pub fn example(n: u8) -> Points {
    let coords: Vec<f64> = if n == 1 {
        EXAMPLE1
            .iter()
            .enumerate()
            .flat_map(|(i, &y)| [i as f64 + 1.0, y])
            .collect()
    } else {
        // 0.1 * i, written as i / 10 so that 0.3 is the double nearest 0.3.
        EXAMPLE2
            .iter()
            .enumerate()
            .flat_map(|(i, &y)| [i as f64 / 10.0, y])
            .collect()
    };
    Points::new(
        &format!("example {n}"),
        (2, EXAMPLE1.len()),
        coords,
        Positions::Items,
        Pos::Item(11),
    )
}
