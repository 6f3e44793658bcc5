//! Data and helpers shared by the integration tests: the paper's two examples, a
//! seeded random number generator and random grids, values and alphas.

// Each test binary includes this module and uses a different subset of it.
#![allow(dead_code)]

use bzspline::{ALPHA_MAX, ALPHA_MIN};

/// The paper's Example 1: knots 1..=11.
pub const EX1_X: [f64; 11] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0];
/// The paper's Example 1: control values.
pub const EX1_F: [f64; 11] = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5];

/// The paper's Example 2: knots 0, 0.1, ..., 1.
#[must_use]
pub fn ex2_x() -> Vec<f64> {
    (0..=10).map(|i| f64::from(i) / 10.0).collect()
}

/// The paper's Example 2: points of `y = sqrt(x - x^2)`, as printed.
pub const EX2_F: [f64; 11] = [
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

/// Alphas used with both examples: both bounds, the default and values between.
pub const SAMPLE_ALPHAS: [f64; 5] = [ALPHA_MIN, 0.4, 0.5, 0.6, ALPHA_MAX];

/// A xorshift64* generator: small, seeded, reproducible on every platform.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a nonzero seed.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Rng(seed.max(1))
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Standard normal, by Box and Muller.
    pub fn gaussian(&mut self) -> f64 {
        let u = self.unit().max(1e-300);
        let v = self.unit();
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }

    /// Uniform integer in `lo..=hi`.
    pub fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as usize
    }

    /// `n` knots starting at a random offset whose widths are `10^u`, `u` uniform
    /// in `[-decades/2, decades/2]`: neighbouring widths differ by up to
    /// `10^decades`.
    pub fn grid(&mut self, n: usize, decades: f64) -> Vec<f64> {
        let mut x = self.uniform(-10.0, 10.0);
        let mut knots = Vec::with_capacity(n);
        knots.push(x);
        for _ in 1..n {
            x += 10f64.powf(self.uniform(-decades / 2.0, decades / 2.0));
            knots.push(x);
        }
        knots
    }

    /// `n` control values of a random magnitude `10^[-3, 3]`.
    pub fn values(&mut self, n: usize) -> Vec<f64> {
        let m = 10f64.powf(self.uniform(-3.0, 3.0));
        (0..n).map(|_| m * self.uniform(-1.0, 1.0)).collect()
    }

    /// `n` shape parameters in `[ALPHA_MIN, ALPHA_MAX]`; about one in six is
    /// exactly `ALPHA_MIN` and one in six exactly `ALPHA_MAX`.
    pub fn alphas(&mut self, n: usize) -> Vec<f64> {
        (0..n)
            .map(|_| match self.int(0, 5) {
                0 => ALPHA_MIN,
                1 => ALPHA_MAX,
                _ => self.uniform(ALPHA_MIN, ALPHA_MAX),
            })
            .collect()
    }
}

/// The largest absolute value (at least the smallest normal double, so that it
/// can scale a tolerance).
#[must_use]
pub fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(f64::MIN_POSITIVE, |m, x| m.max(x.abs()))
}

/// The cubic `c[0] + c[1] t + c[2] t^2 + c[3] t^3`.
#[must_use]
pub fn cubic(c: &[f64; 4], t: f64) -> f64 {
    c[0] + t * (c[1] + t * (c[2] + t * c[3]))
}

/// The derivative of [`cubic`] with respect to `t`.
#[must_use]
pub fn cubic_deriv(c: &[f64; 4], t: f64) -> f64 {
    c[1] + t * (2.0 * c[2] + 3.0 * t * c[3])
}

/// Solves `a x = b` (row-major `n x n`) by Gaussian elimination with partial
/// pivoting. `None` when a pivot is exactly zero.
pub fn gauss_solve(mut a: Vec<f64>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    assert_eq!(a.len(), n * n, "matrix size");
    for col in 0..n {
        let pivot =
            (col..n).max_by(|&i, &j| a[i * n + col].abs().total_cmp(&a[j * n + col].abs()))?;
        if a[pivot * n + col] == 0.0 {
            return None;
        }
        if pivot != col {
            for j in 0..n {
                a.swap(pivot * n + j, col * n + j);
            }
            b.swap(pivot, col);
        }
        let p = a[col * n + col];
        for i in col + 1..n {
            let factor = a[i * n + col] / p;
            if factor == 0.0 {
                continue;
            }
            for j in col..n {
                a[i * n + j] -= factor * a[col * n + j];
            }
            b[i] -= factor * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let mut s = b[i];
        for j in i + 1..n {
            s -= a[i * n + j] * x[j];
        }
        x[i] = s / a[i * n + i];
    }
    Some(x)
}

/// The basis splines `B_k` (control values `e_k`) on `x` with `alphas`.
pub fn basis(x: &[f64], alphas: &[f64]) -> Vec<bzspline::Spline> {
    let n = x.len();
    (0..n)
        .map(|k| {
            let mut e = vec![0.0; n];
            e[k] = 1.0;
            bzspline::Spline::with_alphas(x, &e, alphas).unwrap()
        })
        .collect()
}

/// The smoothing spline's normal matrix `M = B^T W B + lambda R`, row-major,
/// assembled densely from the basis splines `b` (`B` their knot values, `R`
/// the Gram matrix of their second derivatives: on each piece both are
/// linear, so `int B_i'' B_k''` is `h (a0 b0 + (a0 b1 + a1 b0) / 2 + a1 b1) / 3`
/// from their end values).
pub fn normal_matrix(x: &[f64], w: &[f64], b: &[bzspline::Spline], lambda: f64) -> Vec<f64> {
    let n = x.len();
    let kv: Vec<Vec<f64>> = b.iter().map(bzspline::Spline::knot_values).collect();
    let second = |s: &bzspline::Spline, k: usize| {
        let c = s.power_coefficients(k).unwrap();
        let h = x[k + 1] - x[k];
        (2.0 * c[2], 2.0 * c[2] + 6.0 * c[3] * h)
    };
    let mut m = vec![0.0; n * n];
    for i in 0..n {
        for k in 0..n {
            m[i * n + k] = (0..n).map(|j| kv[i][j] * w[j] * kv[k][j]).sum();
        }
    }
    for p in 0..n - 1 {
        let h = x[p + 1] - x[p];
        for i in 0..n {
            let (a0, a1) = second(&b[i], p);
            for k in 0..n {
                let (b0, b1) = second(&b[k], p);
                m[i * n + k] += lambda * h * (a0 * b0 + 0.5 * (a0 * b1 + a1 * b0) + a1 * b1) / 3.0;
            }
        }
    }
    m
}
