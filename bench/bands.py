#!/usr/bin/env python3
"""Confidence bands of a smoothing fit: bzspline beside R's mgcv, in one run.

    pip install ./crates/bzspline-py     # a release build (maturin's default for pip)
    apt-get install r-base-core r-cran-mgcv   # for the mgcv columns; skipped without Rscript
    python3 bench/bands.py [--sizes 10000 100000 1000000] [--k 100]

On a noisy sine (sin 2 pi x + 0.3 N(0, 1), x evenly spaced on [0, 1], one draw per
size): bzspline's `smoothing_spline(x, y)` (lambda by GCV), then `s.band(x)` at every
data point; mgcv's `gam(y ~ s(x, bs = "cr", k = K), method = "GCV.Cp")`, then
`predict(fit, se.fit = TRUE)` at the same points. Prints seconds for the fit and for the
band, the band's time over the fit's, the mean width of the 95 % band, and the share of
the data points where it covers the true curve.
"""

import argparse
import os
import shutil
import subprocess
import tempfile
import time

import numpy as np

import bzspline

R_SCRIPT = r"""
suppressMessages(library(mgcv))
args <- commandArgs(trailingOnly = TRUE)
d <- read.csv(args[1])
k <- as.integer(args[2])
t0 <- proc.time()[["elapsed"]]
fit <- gam(y ~ s(x, bs = "cr", k = k), data = d, method = "GCV.Cp")
t1 <- proc.time()[["elapsed"]]
p <- predict(fit, se.fit = TRUE)
t2 <- proc.time()[["elapsed"]]
lo <- p$fit - 1.959964 * p$se.fit
hi <- p$fit + 1.959964 * p$se.fit
truth <- sin(2 * pi * d$x)
cat(t1 - t0, t2 - t1, mean(hi - lo), mean(lo <= truth & truth <= hi), sum(fit$edf), "\n")
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[10_000, 100_000, 1_000_000])
    ap.add_argument("--k", type=int, default=100, help="mgcv's basis dimension")
    args = ap.parse_args()
    rng = np.random.default_rng(1)
    rscript = shutil.which("Rscript")
    print("| n | bzspline fit, s | band at every point, s | band / fit | 95 % width | covered "
          "| dof | mgcv fit, s | mgcv se, s | mgcv width | mgcv covered | mgcv edf |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        script = os.path.join(tmp, "bands.R")
        with open(script, "w") as f:
            f.write(R_SCRIPT)
        for n in args.sizes:
            x = np.linspace(0, 1, n)
            truth = np.sin(2 * np.pi * x)
            y = truth + 0.3 * rng.standard_normal(n)
            t0 = time.perf_counter()
            s = bzspline.smoothing_spline(x, y)
            t1 = time.perf_counter()
            lo, hi = s.band(x, level=0.95)
            t2 = time.perf_counter()
            covered = np.mean((lo <= truth) & (truth <= hi))
            row = (f"| {n:,} | {t1 - t0:.3f} | {t2 - t1:.3f} | {(t2 - t1) / (t1 - t0):.2f} | "
                   f"{np.mean(hi - lo):.4f} | {covered:.3f} | {s.dof:.1f} |")
            if rscript:
                data = os.path.join(tmp, "data.csv")
                np.savetxt(data, np.column_stack([x, y]), delimiter=",", header="x,y",
                           comments="", fmt="%.17g")
                out = subprocess.run([rscript, script, data, str(args.k)], capture_output=True,
                                     text=True, check=True).stdout.split()
                fit_s, se_s, width, cov, edf = map(float, out)
                row += f" {fit_s:.3f} | {se_s:.3f} | {width:.4f} | {cov:.3f} | {edf:.1f} |"
            else:
                row += " not run | | | | |"
            print(row, flush=True)


if __name__ == "__main__":
    main()
