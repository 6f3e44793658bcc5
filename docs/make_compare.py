#!/usr/bin/env python3
"""Draw docs/compare.svg and docs/compare.png: the paper's Example 1 through
bzspline, scipy's CubicSpline and PchipInterpolator, and d3's curveBasis.

Run from anywhere in a clone:  python3 docs/make_compare.py

The first run makes a virtual environment docs/.venv with numpy and scipy
(ignored by git) and runs itself again inside it. The scipy curves are sampled
as polylines; d3's curveBasis is rebuilt here from d3-shape's rule (src/curve/
basis.js) as exact cubic Bezier pieces. Everything is written to an overlay file
that `bzspline plot --overlay` draws on top of the bzspline figure. The script
also prints, for each method, how far the curve goes above max F and below min F.
"""

import json
import os
import subprocess
import sys
import tempfile
import venv
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
VENV = DOCS / ".venv"
VENV_PY = VENV / "bin" / "python"

# The paper's Example 1.
TAU = [float(i) for i in range(1, 12)]
F = [1.0, 3.0, 3.0, 1.0, 2.0, 7.0, 1.5, 1.0, 10.0, 2.0, 1.5]


def ensure_numpy_scipy(script=__file__):
    """Re-run `script` (this one by default) inside docs/.venv, creating it
    first if needed."""
    try:
        import numpy  # noqa: F401
        import scipy  # noqa: F401

        return
    except ImportError:
        pass
    if Path(sys.prefix).resolve() == VENV.resolve():
        sys.exit("numpy/scipy missing inside docs/.venv; delete it and run again")
    if not VENV_PY.exists():
        print("creating docs/.venv with numpy and scipy", file=sys.stderr)
        venv.create(VENV, with_pip=True)
        subprocess.run(
            [str(VENV_PY), "-m", "pip", "install", "--quiet", "numpy>=1.24", "scipy>=1.10"],
            check=True,
        )
    os.execv(str(VENV_PY), [str(VENV_PY), str(Path(script).resolve()), *sys.argv[1:]])


def d3_basis_segments(points):
    """d3-shape's curveBasis as cubic Bezier pieces [[p0, p1, p2, p3], ...].

    basis.js: moveTo(P0); at the third point lineTo((5 P0 + P1) / 6); for every
    point P from the third on, bezierCurveTo((2 A + B) / 3, (A + 2 B) / 3,
    (A + 4 B + P) / 6) with A, B the two points before it; at the end the same
    with P = B (the last point repeated), then lineTo(last point). Straight
    pieces are written as Bezier pieces with control points at thirds.
    """

    def lerp(a, b, t):
        return [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]

    def line(a, b):
        return [a, lerp(a, b, 1 / 3), lerp(a, b, 2 / 3), b]

    def comb(*terms):
        return [sum(w * p[0] for w, p in terms), sum(w * p[1] for w, p in terms)]

    pts = [list(p) for p in points]
    if len(pts) < 3:
        return [line(pts[0], pts[-1])]
    segs = []
    start = comb((5 / 6, pts[0]), (1 / 6, pts[1]))
    segs.append(line(pts[0], start))
    cur = start
    sequence = pts[2:] + [pts[-1]]
    a, b = pts[0], pts[1]
    for p in sequence:
        c1 = comb((2 / 3, a), (1 / 3, b))
        c2 = comb((1 / 3, a), (2 / 3, b))
        end = comb((1 / 6, a), (4 / 6, b), (1 / 6, p))
        segs.append([cur, c1, c2, end])
        cur = end
        a, b = b, p
    segs.append(line(cur, pts[-1]))
    return segs


def bzspline_knot_deviations(np, tau, f, alpha=0.5):
    """Knot deviations d of the paper's system (16) in the deviation form of
    shared/method.md (an independent check of the numbers; the figure's
    bzspline curve is drawn by the tool itself)."""
    n = len(tau)
    h = np.diff(tau)
    s = np.diff(f) / h
    m = np.zeros((n, n))
    r = np.zeros(n)
    m[0, 0] = m[-1, -1] = 1.0
    for i in range(1, n - 1):
        a, b = alpha, alpha
        m[i, i - 1] = -(a**2) / ((1 - a) ** 2 * h[i - 1])
        m[i, i] = (2 / a + 1) / h[i - 1] + (2 / (1 - b) + 1) / h[i]
        m[i, i + 1] = -((1 - b) ** 2) / (b**2 * h[i])
        r[i] = s[i] - s[i - 1]
    return np.linalg.solve(m, r)


def bzspline_eval(np, tau, f, d, x, alpha=0.5):
    tau, f = np.asarray(tau), np.asarray(f)
    k = np.clip(np.searchsorted(tau, x, side="right") - 1, 0, len(tau) - 2)
    h = tau[k + 1] - tau[k]
    mu = alpha * h
    u = h - mu
    xi = tau[k + 1] - mu
    slope = (f[k + 1] - f[k]) / h
    leg = f[k] + slope * (x - tau[k])
    b = (d[k + 1] / mu**2 - d[k] / u**2) / h
    a = d[k + 1] / mu**2 - b * mu
    return leg + (x - xi) ** 2 * (a + b * (x - xi))


def main():
    ensure_numpy_scipy()
    import numpy as np
    from scipy.interpolate import CubicSpline, PchipInterpolator

    x = np.linspace(TAU[0], TAU[-1], 20001)
    d = bzspline_knot_deviations(np, TAU, F)
    curves = {
        "bzspline (α = 1/2)": bzspline_eval(np, TAU, F, d, x),
        "scipy CubicSpline": CubicSpline(TAU, F)(x),
        "scipy PchipInterpolator": PchipInterpolator(TAU, F)(x),
    }
    d3 = d3_basis_segments(list(zip(TAU, F)))
    t = np.linspace(0.0, 1.0, 401)[:, None]
    d3_pts = np.concatenate(
        [
            (1 - t) ** 3 * np.array(p[0])
            + 3 * (1 - t) ** 2 * t * np.array(p[1])
            + 3 * (1 - t) * t**2 * np.array(p[2])
            + t**3 * np.array(p[3])
            for p in d3
        ]
    )
    hi, lo = max(F), min(F)
    print(f"| method | passes through the data | curve max | curve min "
          f"| above max F = {hi:g} | below min F = {lo:g} |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    rows = [
        ("bzspline (α = 1/2)", curves["bzspline (α = 1/2)"], "end points; touches every leg"),
        ("scipy CubicSpline", curves["scipy CubicSpline"], "yes"),
        ("scipy PchipInterpolator", curves["scipy PchipInterpolator"], "yes"),
        ("d3 curveBasis", d3_pts[:, 1], "end points only"),
    ]
    for name, y, through in rows:
        print(
            f"| {name} | {through} | {y.max():.3f} | {y.min():.3f} "
            f"| {max(y.max() - hi, 0.0):.3f} | {max(lo - y.min(), 0.0):.3f} |"
        )

    overlay = [
        {"label": name, "points": [[float(a), float(b)] for a, b in zip(x[::20], y[::20])]}
        for name, y in curves.items()
        if not name.startswith("bzspline")
    ]
    overlay.append(
        {
            "label": "d3 curveBasis",
            "points": [[float(a), float(b)] for a, b in d3_pts[::40]],
            "segments": d3,
        }
    )
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "overlay.json"
        path.write_text(json.dumps(overlay))
        for out in ["compare.svg", "compare.png"]:
            subprocess.run(
                [
                    "cargo", "run", "--quiet", "-p", "bzspline-cli", "--",
                    "plot", "--example", "1", "--hull", "--data-range", "--no-tangents",
                    "--overlay", str(path),
                    "--title", "Example 1: bzspline, scipy and d3 on the same data",
                    "-o", str(DOCS / out),
                ],
                cwd=ROOT,
                check=True,
            )
    print("wrote docs/compare.svg and docs/compare.png", file=sys.stderr)


if __name__ == "__main__":
    main()
