//! Pointwise confidence bands of a smoothing fit (`docs/method.md` §13): the
//! Bayesian posterior covariance of the fitted curve, `sigma^2` times the
//! inverse of the optimality system restricted to the knot values and
//! deviations, of which a fit keeps the few entries a point needs; the
//! standard error at any `x`, and the band `S(x) +- z se(x)` at a level.

use crate::error::Error;

/// What the standard error of a smoothing fit needs, kept with the fit: the
/// knots and alphas, the posterior covariance (over `sigma^2`) of each
/// knot's value and deviation and of neighbouring knots', and the noise
/// variance of each coordinate, `RSS / (n - dof)` (weights of mean 1). Seven
/// numbers a knot, O(N).
#[derive(Clone, Debug, PartialEq)]
pub struct Posterior {
    knots: Vec<f64>,
    alphas: Vec<f64>,
    cov: Vec<[f64; 7]>,
    /// `sigma^2` of each coordinate; `None` when the fit interpolates (no
    /// residual degrees of freedom to estimate it).
    sigma2: Option<Vec<f64>>,
}

impl Posterior {
    pub(crate) fn new(
        knots: &[f64],
        alphas: &[f64],
        cov: Vec<[f64; 7]>,
        sigma2: Option<Vec<f64>>,
    ) -> Self {
        Posterior {
            knots: knots.to_vec(),
            alphas: alphas.to_vec(),
            cov,
            sigma2,
        }
    }

    /// What the posterior holds, to store it (a pickle).
    #[must_use]
    pub fn parts(&self) -> PosteriorParts<'_> {
        PosteriorParts {
            knots: &self.knots,
            alphas: &self.alphas,
            cov: &self.cov,
            noise: self.sigma2.as_deref(),
        }
    }

    /// A posterior from its [`Posterior::parts`].
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] when the lengths disagree (fewer than 2
    /// knots, alphas not one fewer, covariances not one a knot), the knots
    /// do not increase, a number is not finite, or a noise variance is
    /// negative.
    pub fn from_parts(parts: PosteriorParts<'_>) -> Result<Posterior, Error> {
        let PosteriorParts {
            knots,
            alphas,
            cov,
            noise: sigma2,
        } = parts;
        let bad = |what| {
            Err(Error::InvalidArgument {
                what,
                value: knots.len() as f64,
            })
        };
        if knots.len() < 2 || alphas.len() + 1 != knots.len() || cov.len() != knots.len() {
            return bad("a posterior's knots, alphas and covariances do not agree in length");
        }
        let finite = knots
            .iter()
            .chain(alphas)
            .chain(cov.iter().flatten())
            .all(|v| v.is_finite())
            && knots.windows(2).all(|w| w[0] < w[1]);
        let noise_ok =
            sigma2.is_none_or(|s| !s.is_empty() && s.iter().all(|v| v.is_finite() && *v >= 0.0));
        if !finite || !noise_ok {
            return bad("a posterior's numbers must be finite (noise variances >= 0)");
        }
        Ok(Posterior {
            knots: knots.to_vec(),
            alphas: alphas.to_vec(),
            cov: cov.to_vec(),
            sigma2: sigma2.map(<[f64]>::to_vec),
        })
    }

    /// The noise variance estimated for each coordinate (one for a spline
    /// y(x)), `sum_j w_j r_j^2 / (mean(w) (n - dof))` with `n` the points of
    /// positive weight: the variance of a point of mean weight.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] when the fit interpolates its points
    /// (`dof = n`, as at `lambda = 0`): nothing is left to estimate the noise.
    pub fn noise_variance(&self) -> Result<&[f64], Error> {
        self.sigma2.as_deref().ok_or(Error::InvalidArgument {
            what: "the fit passes through its points (dof = n): no residual degrees of \
                   freedom are left to estimate the noise, so it has no standard error",
            value: (self.knots.len()) as f64,
        })
    }

    /// `b(x)^T Z b(x)`: the posterior variance of the fit at `x` over
    /// `sigma^2`, `b` the weights of the four knot values and deviations of
    /// `x`'s piece in `S(x)`.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfDomain`] for `x` outside the knots, or not finite.
    pub fn unit_variance(&self, x: f64) -> Result<f64, Error> {
        let n = self.knots.len();
        let (lo, hi) = (self.knots[0], self.knots[n - 1]);
        if !(x >= lo && x <= hi) {
            return Err(Error::OutOfDomain {
                x,
                min: lo,
                max: hi,
            });
        }
        let k = self.knots.partition_point(|&t| t <= x).clamp(1, n - 1) - 1;
        let h = self.knots[k + 1] - self.knots[k];
        let t = ((x - self.knots[k]) / h).clamp(0.0, 1.0);
        let b = weights(t, self.alphas[k]);
        let (c0, c1) = (&self.cov[k], &self.cov[k + 1]);
        // The 4 by 4 covariance of (phi_k, d_k, phi_{k+1}, d_{k+1}).
        let z = [
            [c0[0], c0[1], c0[3], c0[4]],
            [c0[1], c0[2], c0[5], c0[6]],
            [c0[3], c0[5], c1[0], c1[1]],
            [c0[4], c0[6], c1[1], c1[2]],
        ];
        let mut v = 0.0;
        for i in 0..4 {
            for j in 0..4 {
                v += b[i] * z[i][j] * b[j];
            }
        }
        // Rounding can leave a variance of zero (at an end of weight 0
        // with a huge lambda) a hair below it.
        Ok(v.max(0.0))
    }

    /// The standard error of coordinate `coord` of the fit at `x`,
    /// `sqrt(sigma^2 b(x)^T Z b(x))`.
    ///
    /// # Errors
    ///
    /// As [`Posterior::noise_variance`] and [`Posterior::unit_variance`];
    /// [`Error::InvalidArgument`] for a coordinate the fit does not have.
    pub fn se(&self, x: f64, coord: usize) -> Result<f64, Error> {
        let s2 = self.noise_variance()?;
        let s2 = *s2.get(coord).ok_or(Error::InvalidArgument {
            what: "the fit has no such coordinate",
            value: coord as f64,
        })?;
        Ok((s2 * self.unit_variance(x)?).sqrt())
    }

    /// The confidence band at `x` around the fit's value `value` there (of
    /// coordinate `coord`): `value -+ z se(x)` with `z` the standard normal
    /// quantile of `(1 + level) / 2`.
    ///
    /// # Errors
    ///
    /// As [`Posterior::se`]; [`Error::InvalidArgument`] for a level outside
    /// `(0, 1)`.
    pub fn band(&self, value: f64, x: f64, level: f64, coord: usize) -> Result<(f64, f64), Error> {
        let z = band_z(level)?;
        let se = self.se(x, coord)?;
        Ok((value - z * se, value + z * se))
    }
}

/// The parts of a [`Posterior`], as [`Posterior::parts`] gives them and
/// [`Posterior::from_parts`] takes them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PosteriorParts<'a> {
    /// The knots (the curve's parameters for a curve).
    pub knots: &'a [f64],
    /// One alpha per interval.
    pub alphas: &'a [f64],
    /// Per knot, the posterior covariances over `sigma^2` of its value and
    /// deviation and of those of the next knot: `(phi, phi)`, `(phi, d)`,
    /// `(d, d)`, then `(phi, phi')`, `(phi, d')`, `(d, phi')`, `(d, d')`.
    pub cov: &'a [[f64; 7]],
    /// The noise variance of each coordinate; `None` for a fit that
    /// interpolates.
    pub noise: Option<&'a [f64]>,
}

/// How `S(x)` on a piece, at `t = (x - tau_k) / h_k`, weighs
/// `(phi_k, d_k, phi_{k+1}, d_{k+1})`: the Bernstein ordinates of §3,
/// `phi_k`, `phi_k + h S'(tau_k + 0) / 3`, `phi_{k+1} - h S'(tau_{k+1} - 0) / 3`,
/// `phi_{k+1}`, with `dF = (phi_{k+1} - d_{k+1}) - (phi_k - d_k)`, written in
/// those four.
fn weights(t: f64, a: f64) -> [f64; 4] {
    let s = 1.0 - t;
    let bern = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
    let third = 1.0 / 3.0;
    // h S'(tau_k + 0) = dF - d_k (2/(1-a) + 1) + d_{k+1} (1-a)^2/a^2
    // h S'(tau_{k+1} - 0) = dF + d_{k+1} (2/a + 1) - d_k a^2/(1-a)^2
    let r = (1.0 - a) / a;
    let p1 = [
        1.0 - third,
        third * (1.0 - (2.0 / (1.0 - a) + 1.0)),
        third,
        third * (-1.0 + r * r),
    ];
    let p2 = [
        third,
        -third * (1.0 - 1.0 / (r * r)),
        1.0 - third,
        -third * (-1.0 + 2.0 / a + 1.0),
    ];
    let p0 = [1.0, 0.0, 0.0, 0.0];
    let p3 = [0.0, 0.0, 1.0, 0.0];
    [0, 1, 2, 3].map(|i| bern[0] * p0[i] + bern[1] * p1[i] + bern[2] * p2[i] + bern[3] * p3[i])
}

/// The standard normal quantile `z` with `P(Z <= z) = p`, by Wichura's
/// algorithm AS 241 (PPND16, about 1e-16 relative).
///
/// # Errors
///
/// [`Error::InvalidArgument`] for `p` outside `(0, 1)`.
pub fn normal_quantile(p: f64) -> Result<f64, Error> {
    if !(p > 0.0 && p < 1.0) {
        return Err(Error::InvalidArgument {
            what: "a probability must lie strictly between 0 and 1",
            value: p,
        });
    }
    let q = p - 0.5;
    if q.abs() <= 0.425 {
        let r = 0.180_625 - q * q;
        let num = ((((((r * 2_509.080_928_730_122_7 + 33_430.575_583_588_13) * r
            + 67_265.770_927_008_7)
            * r
            + 45_921.953_931_549_87)
            * r
            + 13_731.693_765_509_46)
            * r
            + 1_971.590_950_306_551_4)
            * r
            + 133.141_667_891_784_38)
            * r
            + 3.387_132_872_796_366_6;
        let den = ((((((r * 5_226.495_278_852_546 + 28_729.085_735_721_943) * r
            + 39_307.895_800_092_71)
            * r
            + 21_213.794_301_586_597)
            * r
            + 5_394.196_021_424_751)
            * r
            + 687.187_007_492_057_9)
            * r
            + 42.313_330_701_600_91)
            * r
            + 1.0;
        return Ok(q * num / den);
    }
    let tail = if q < 0.0 { p } else { 1.0 - p };
    let mut r = (-tail.ln()).sqrt();
    let z = if r <= 5.0 {
        r -= 1.6;
        let num = ((((((r * 7.745_450_142_783_414e-4 + 0.022_723_844_989_269_184) * r
            + 0.241_780_725_177_450_6)
            * r
            + 1.270_458_252_452_368_4)
            * r
            + 3.647_848_324_763_204_5)
            * r
            + 5.769_497_221_460_691)
            * r
            + 4.630_337_846_156_545)
            * r
            + 1.423_437_110_749_683_5;
        let den = ((((((r * 1.050_750_071_644_416_8e-9 + 5.475_938_084_995_345e-4) * r
            + 0.015_198_666_563_616_457)
            * r
            + 0.148_103_976_427_480_08)
            * r
            + 0.689_767_334_985_1)
            * r
            + 1.676_384_830_183_803_8)
            * r
            + 2.053_191_626_637_759)
            * r
            + 1.0;
        num / den
    } else {
        r -= 5.0;
        let num = ((((((r * 2.010_334_399_292_288e-7 + 2.711_555_568_743_487_6e-5) * r
            + 0.001_242_660_947_388_078_4)
            * r
            + 0.026_532_189_526_576_124)
            * r
            + 0.296_560_571_828_504_9)
            * r
            + 1.784_826_539_917_291_3)
            * r
            + 5.463_784_911_164_114)
            * r
            + 6.657_904_643_501_103;
        let den = ((((((r * 2.044_263_103_389_939_8e-15 + 1.421_511_758_316_446e-7) * r
            + 1.846_318_317_510_054_8e-5)
            * r
            + 7.868_691_311_456_133e-4)
            * r
            + 0.014_875_361_290_850_615)
            * r
            + 0.136_929_880_922_735_8)
            * r
            + 0.599_832_206_555_888)
            * r
            + 1.0;
        num / den
    };
    Ok(if q < 0.0 { -z } else { z })
}

/// The `z` of a two-sided band at `level`: `normal_quantile((1 + level) / 2)`.
///
/// # Errors
///
/// [`Error::InvalidArgument`] for a level outside `(0, 1)`.
pub fn band_z(level: f64) -> Result<f64, Error> {
    if !(level > 0.0 && level < 1.0) {
        return Err(Error::InvalidArgument {
            what: "a confidence level must lie strictly between 0 and 1 (0.95 for 95 %)",
            value: level,
        });
    }
    normal_quantile(0.5 + 0.5 * level)
}
