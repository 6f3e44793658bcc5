"""bzspline.smoothing_spline against scipy.interpolate.make_smoothing_spline,
both choosing lam by generalized cross-validation, on the same noisy samples
of three test functions at two noise levels: the mean squared error to the
true function (mean over --seeds noise draws), and the time; then the sizes
scipy's fit does not reach. x is evenly spaced on [0, 10], where scipy's fit
works up to 30,000 points (on sorted random x it fails from 10,000: "Seems
like the problem is ill-posed").

    pip install ./crates/bzspline-py scipy matplotlib
    python3 bench/smoothing.py [--sizes 1000,10000] [--large 100000,1000000]
                               [--figure docs/smoothing.png]
"""

import argparse
import time

import numpy as np
from scipy.interpolate import make_smoothing_spline

import bzspline

SPAN = 10.0  # x in [0, 10]: scipy's search for lam runs over (0, n) in x's units

FUNCTIONS = {
    "sine": lambda t: np.sin(4 * np.pi * t),
    "bump": lambda t: np.exp(-(((t - 0.5) / 0.08) ** 2)),
    "smoothed step": lambda t: 1 / (1 + np.exp(-(t - 0.5) / 0.02)),
}


def sample(name, n, sigma, seed, random_x=False):
    rng = np.random.default_rng(seed)
    x = np.sort(rng.uniform(0, SPAN, n)) if random_x else np.linspace(0, SPAN, n)
    truth = FUNCTIONS[name](x / SPAN)
    return x, truth + rng.normal(0, sigma, n), truth


def timed(f):
    start = time.perf_counter()
    out = f()
    return out, time.perf_counter() - start


def mse(s, x, truth):
    return float(np.mean((s(x) - truth) ** 2))


def compare(sizes, seeds, random_x=False):
    where = "sorted uniform random" if random_x else "evenly spaced"
    print(f"\nx {where} on [0, 10]; MSE: mean over {seeds} noise draws; time: the median draw")
    print("| function | sigma | n | MSE data | MSE bzspline | MSE scipy | ratio | bzspline s | scipy s | speed-up |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name in FUNCTIONS:
        for sigma in (0.05, 0.3):
            for n in sizes:
                rows = []
                for seed in range(seeds):
                    x, y, truth = sample(name, n, sigma, seed, random_x)
                    ours, t_ours = timed(lambda: bzspline.smoothing_spline(x, y))
                    try:
                        theirs, t_theirs = timed(lambda: make_smoothing_spline(x, y))
                        m_theirs = mse(theirs, x, truth)
                    except ValueError:
                        t_theirs, m_theirs = float("nan"), float("nan")
                    rows.append((float(np.mean((y - truth) ** 2)), mse(ours, x, truth), m_theirs,
                                 t_ours, t_theirs))
                data, m_ours, m_theirs = (float(np.mean([r[i] for r in rows])) for i in range(3))
                t_ours, t_theirs = (float(np.median([r[i] for r in rows])) for i in (3, 4))
                if np.isnan(m_theirs):
                    cells = "fails | | " + f"{t_ours:.4f} | | "
                else:
                    cells = (f"{m_theirs:.3e} | {m_ours / m_theirs:.2f} | {t_ours:.4f} | "
                             f"{t_theirs:.3f} | {t_theirs / t_ours:.0f}x")
                print(f"| {name} | {sigma} | {n} | {data:.3e} | {m_ours:.3e} | {cells} |", flush=True)


def large(sizes, seed):
    print()
    print("| n | bzspline s | MSE data | MSE bzspline | dof | scipy |")
    print("|---|---|---|---|---|---|")
    for n in sizes:
        x, y, truth = sample("sine", n, 0.3, seed)
        ours, t = timed(lambda: bzspline.smoothing_spline(x, y))
        if n <= 100_000:
            try:
                _, ts = timed(lambda: make_smoothing_spline(x, y))
                theirs = f"{ts:.2f} s"
            except ValueError as e:
                theirs = f"fails: {e}"
        else:
            theirs = "not run"
        print(f"| {n} | {t:.3f} | {np.mean((y - truth) ** 2):.3e} | {mse(ours, x, truth):.3e} | {ours.dof:.1f} | {theirs} |", flush=True)


def figure(path, seed):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x, y, truth = sample("bump", 300, 0.1, seed, random_x=True)
    ours = bzspline.smoothing_spline(x, y)
    theirs = make_smoothing_spline(x, y)
    grid = np.linspace(0, SPAN, 2000)
    fig, ax = plt.subplots(figsize=(8, 4.2), dpi=110)
    ax.plot(x, y, ".", color="0.55", ms=3.5, label="data (bump + noise, sigma 0.1, random x)")
    ax.plot(grid, FUNCTIONS["bump"](grid / SPAN), color="0.2", lw=1, ls=":", label="true function")
    ax.plot(grid, theirs(grid), color="#d95f02", lw=1.6,
            label=f"scipy make_smoothing_spline (MSE {mse(theirs, x, truth):.2e})")
    ax.plot(grid, ours(grid), color="#1f5fa0", lw=1.8,
            label=f"bzspline.smoothing_spline (MSE {mse(ours, x, truth):.2e}, dof {ours.dof:.1f})")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.legend(loc="upper left", fontsize=8, frameon=False)
    fig.tight_layout()
    fig.savefig(path)
    print(f"\nwrote {path}")


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", default="1000,10000")
    p.add_argument("--large", default="1000,10000,30000,100000,1000000")
    p.add_argument("--seeds", type=int, default=3)
    p.add_argument("--figure")
    a = p.parse_args()
    import scipy

    print(f"scipy {scipy.__version__}, numpy {np.__version__}, bzspline {bzspline.__version__}")
    compare([int(v) for v in a.sizes.split(",")], a.seeds)
    compare([1000], a.seeds, random_x=True)
    large([int(v) for v in a.large.split(",") if v], 0)
    x, y, _ = sample("sine", 10_000, 0.3, 0, random_x=True)
    try:
        make_smoothing_spline(x, y)
        print("\nscipy on 10,000 sorted random x: fits")
    except ValueError as e:
        print(f"\nscipy on 10,000 sorted random x: {e}")
    if a.figure:
        figure(a.figure, 0)


if __name__ == "__main__":
    main()
