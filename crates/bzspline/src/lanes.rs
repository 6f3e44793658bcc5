//! Numbers of one or two lanes: `f64` for one problem, [`F2`] for two side
//! by side (two scores of `lambda` in the smoothing system's block
//! arithmetic, two chunks of the construction sweeps). A lane of an [`F2`]
//! goes through the same IEEE operations in the same order as an `f64`
//! would (no fused multiply-adds), so each problem of a pair has the bits of
//! that problem taken alone, while the two lanes share the instructions (the
//! compiler keeps an `F2` in one SSE2 register).

use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A number of one or more lanes, each an `f64`.
pub(crate) trait Lane:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
{
    /// How many lanes.
    const LANES: usize;
    /// `v` in every lane.
    fn splat(v: f64) -> Self;
    /// Lane `i`.
    fn lane(self, i: usize) -> f64;
    /// The lanes from the first `LANES` values of `s`.
    fn load(s: &[f64]) -> Self;
    /// The lanes into the first `LANES` values of `s`.
    fn store(self, s: &mut [f64]);
    /// Lane `i` from `f(i)`.
    fn from_lanes(f: impl FnMut(usize) -> f64) -> Self;
}

impl Lane for f64 {
    const LANES: usize = 1;
    #[inline(always)]
    fn splat(v: f64) -> f64 {
        v
    }
    #[inline(always)]
    fn lane(self, _: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn load(s: &[f64]) -> f64 {
        s[0]
    }
    #[inline(always)]
    fn store(self, s: &mut [f64]) {
        s[0] = self;
    }
    #[inline(always)]
    fn from_lanes(mut f: impl FnMut(usize) -> f64) -> f64 {
        f(0)
    }
}

/// Two lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(align(16))]
pub(crate) struct F2(pub(crate) [f64; 2]);

impl Lane for F2 {
    const LANES: usize = 2;
    #[inline(always)]
    fn splat(v: f64) -> F2 {
        F2([v, v])
    }
    #[inline(always)]
    fn lane(self, i: usize) -> f64 {
        self.0[i]
    }
    #[inline(always)]
    fn load(s: &[f64]) -> F2 {
        F2([s[0], s[1]])
    }
    #[inline(always)]
    fn store(self, s: &mut [f64]) {
        s[..2].copy_from_slice(&self.0);
    }
    #[inline(always)]
    fn from_lanes(mut f: impl FnMut(usize) -> f64) -> F2 {
        F2([f(0), f(1)])
    }
}

macro_rules! lanewise {
    ($op:ident, $f:ident, $sym:tt, $assign:ident, $fa:ident) => {
        impl $op for F2 {
            type Output = F2;
            #[inline(always)]
            fn $f(self, o: F2) -> F2 {
                F2([self.0[0] $sym o.0[0], self.0[1] $sym o.0[1]])
            }
        }
        impl $assign for F2 {
            #[inline(always)]
            fn $fa(&mut self, o: F2) {
                *self = *self $sym o;
            }
        }
    };
}

lanewise!(Add, add, +, AddAssign, add_assign);
lanewise!(Sub, sub, -, SubAssign, sub_assign);
lanewise!(Mul, mul, *, MulAssign, mul_assign);
lanewise!(Div, div, /, DivAssign, div_assign);

impl Neg for F2 {
    type Output = F2;
    #[inline(always)]
    fn neg(self) -> F2 {
        F2([-self.0[0], -self.0[1]])
    }
}

/// Lane `i` of a 3-vector of lanes.
pub(crate) fn lane3<T: Lane>(v: &[T; 3], i: usize) -> [f64; 3] {
    v.map(|x| x.lane(i))
}

/// Lane `i` of a 3 by 3 matrix of lanes.
pub(crate) fn lane33<T: Lane>(m: &[[T; 3]; 3], i: usize) -> [[f64; 3]; 3] {
    m.map(|r| r.map(|x| x.lane(i)))
}

/// Two 3-vectors side by side.
pub(crate) fn pair3(a: &[f64; 3], b: &[f64; 3]) -> [F2; 3] {
    std::array::from_fn(|i| F2([a[i], b[i]]))
}

/// Two 3 by 3 matrices side by side.
pub(crate) fn pair33(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[F2; 3]; 3] {
    std::array::from_fn(|i| pair3(&a[i], &b[i]))
}
