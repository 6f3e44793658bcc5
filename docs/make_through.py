#!/usr/bin/env python3
"""Draw docs/through.{svg,png} and docs/step.{svg,png}: curves through the paper's
Example 1 and through a step-like chart series, by bzspline --through, scipy's
CubicSpline, PchipInterpolator and makima (Akima1DInterpolator), and d3's
curveCatmullRom; print how far each goes above the data's maximum and below its
minimum.

Run from anywhere in a clone:  python3 docs/make_through.py

It uses docs/.venv (numpy, scipy), made by make_compare.py's bootstrap on the
first run. bzspline's curve comes from the command (`bzspline sample --through`),
sampled at 20,001 points like the scipy curves; d3's curveCatmullRom (alpha 0.5)
is rebuilt from d3-shape's rule (src/curve/catmullRom.js) as cubic Bezier
pieces, each sampled at 2,001 points.
"""

import json
import subprocess
import sys
import tempfile
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS))
from make_compare import ensure_numpy_scipy  # noqa: E402

EXAMPLE1 = ([float(i) for i in range(1, 12)],
            [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5])
STEP = ([float(i) for i in range(12)], [0.0] * 6 + [1.0] * 6)


def catmull_rom_segments(points, alpha=0.5):
    """d3-shape's curveCatmullRom: Bezier pieces [[p0, p1, p2, p3], ...].

    For the piece from P1 to P2 with neighbours P0 and P3 and l_ij = |Pi Pj|^alpha,
    the first inner control point is (P1 a - P0 l12^2 + P2 l01^2) / n with
    a = 2 l01^2 + 3 l01 l12 + l12^2, n = 3 l01 (l01 + l12), and the second
    (P2 b + P1 l23^2 - P3 l12^2) / m with b = 2 l23^2 + 3 l23 l12 + l12^2,
    m = 3 l23 (l23 + l12); at the ends, where P0 or P3 is missing, the control
    point is the piece's own end point.
    """
    def dist_a(p, q):
        d2 = (p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2
        return d2 ** (alpha / 2), d2 ** alpha

    segs = []
    n = len(points)
    for i in range(n - 1):
        p1, p2 = points[i], points[i + 1]
        c1, c2 = list(p1), list(p2)
        l12, l12_2 = dist_a(p1, p2)
        if i > 0:
            p0 = points[i - 1]
            l01, l01_2 = dist_a(p0, p1)
            a = 2 * l01_2 + 3 * l01 * l12 + l12_2
            m = 3 * l01 * (l01 + l12)
            c1 = [(p1[k] * a - p0[k] * l12_2 + p2[k] * l01_2) / m for k in range(2)]
        if i + 2 < n:
            p3 = points[i + 2]
            l23, l23_2 = dist_a(p2, p3)
            b = 2 * l23_2 + 3 * l23 * l12 + l12_2
            m = 3 * l23 * (l23 + l12)
            c2 = [(p2[k] * b + p1[k] * l23_2 - p3[k] * l12_2) / m for k in range(2)]
        segs.append([list(p1), c1, c2, list(p2)])
    return segs


def bzspline_through(np, x, y, samples):
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "data.csv"
        path.write_text("".join(f"{a!r},{b!r}\n" for a, b in zip(x, y)))
        out = subprocess.run(
            ["cargo", "run", "--quiet", "-p", "bzspline-cli", "--", "sample", str(path),
             "--through", "--n", str(samples)],
            cwd=ROOT, check=True, capture_output=True, text=True).stdout
    rows = [line.split(",") for line in out.splitlines()[1:]]
    return np.array([[float(a), float(b)] for a, b in rows])


def compare(np, name, x, y, title, stem):
    from scipy.interpolate import Akima1DInterpolator, CubicSpline, PchipInterpolator

    xs = np.linspace(x[0], x[-1], 20001)
    bz = bzspline_through(np, x, y, 20001)
    curves = [
        ("bzspline --through (α = 1/2)", bz[:, 1]),
        ("scipy CubicSpline", CubicSpline(x, y)(xs)),
        ("scipy PchipInterpolator", PchipInterpolator(x, y)(xs)),
        ("scipy makima", Akima1DInterpolator(x, y, method="makima")(xs)),
    ]
    segs = catmull_rom_segments(list(zip(x, y)))
    t = np.linspace(0.0, 1.0, 2001)[:, None]
    cr = np.concatenate([
        (1 - t) ** 3 * np.array(p[0]) + 3 * (1 - t) ** 2 * t * np.array(p[1])
        + 3 * (1 - t) * t ** 2 * np.array(p[2]) + t ** 3 * np.array(p[3])
        for p in segs
    ])
    curves.append(("d3 curveCatmullRom", cr[:, 1]))
    hi, lo = max(y), min(y)
    print(f"\n{name}\n")
    print(f"| method | max | min | above max = {hi:g} | below min = {lo:g} |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for label, v in curves:
        print(f"| {label} | {v.max():.3f} | {v.min():.3f} "
              f"| {max(v.max() - hi, 0.0):.3f} | {max(lo - v.min(), 0.0):.3f} |")
    overlay = [
        {"label": label, "points": [[float(a), float(b)] for a, b in zip(xs[::20], v[::20])]}
        for label, v in curves[1:-1]
    ]
    overlay.append({"label": "d3 curveCatmullRom",
                    "points": [[float(a), float(b)] for a, b in cr[::50]],
                    "segments": segs})
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "overlay.json"
        path.write_text(json.dumps(overlay))
        data = Path(tmp) / "data.csv"
        data.write_text("".join(f"{a!r},{b!r}\n" for a, b in zip(x, y)))
        for ext in ["svg", "png"]:
            subprocess.run(
                ["cargo", "run", "--quiet", "-p", "bzspline-cli", "--", "plot", str(data),
                 "--through", "--data-range", "--no-tangents", "--overlay", str(path),
                 "--title", title, "-o", str(DOCS / f"{stem}.{ext}")],
                cwd=ROOT, check=True)


def main():
    ensure_numpy_scipy(__file__)
    import numpy as np

    compare(np, "Example 1", *EXAMPLE1, "Example 1 through its points", "through")
    compare(np, "A step: six points at 0, six at 1", *STEP,
            "A step through its points", "step")
    print("\nwrote docs/through.{svg,png} and docs/step.{svg,png}", file=sys.stderr)


if __name__ == "__main__":
    main()
