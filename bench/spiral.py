#!/usr/bin/env python3
"""The flattening target on its own: the 10^5-point spiral of the `throughput`
example, built, rebuilt and flattened, over many short runs.

    python3 bench/spiral.py [--runs 16] [--repeats 20]

Each run is one `throughput` process with a small N (so that it spends its
time on the spiral) and `BZ_MIN=1` (the smallest of --repeats timings).
Prints, in nanoseconds per control point, the smallest and the median over
the runs of `Curve::open` (build), `CurveBuilder::build_into` (rebuild) and
`Curve::flatten` to 1e-3 of the curve's size, and the median of each run's
ratio of flattening to rebuild and to build. Many short runs rather than one
long one, because this machine's speed drifts within seconds.
"""

import argparse
import json
import os
import statistics
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KEYS = {
    "build": "spiral_1e5_construct_ns_per_point",
    "rebuild": "spiral_1e5_rebuild_ns_per_point",
    "flatten": "spiral_1e5_flatten_ns_per_point",
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=16)
    ap.add_argument("--repeats", type=int, default=20)
    a = ap.parse_args()
    subprocess.run(
        ["cargo", "build", "--release", "--quiet", "-p", "bzspline", "--example", "throughput"],
        cwd=ROOT,
        check=True,
    )
    exe = os.path.join(ROOT, "target", "release", "examples", "throughput")
    env = dict(os.environ, BZ_MIN="1")
    runs = []
    for _ in range(max(1, a.runs)):
        out = subprocess.run(
            [exe, "--n", "1000", "--m", "1000", "--repeats", str(max(1, a.repeats))],
            cwd=ROOT,
            env=env,
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        runs.append(json.loads(out))
    vertices = sorted({r["spiral_1e5_flatten_vertices"] for r in runs})
    print(f"{len(runs)} runs, smallest of {a.repeats} each; {vertices} vertices")
    for name, key in KEYS.items():
        v = [r[key] for r in runs]
        print(f"{name:8} smallest {min(v):6.2f}  median {statistics.median(v):6.2f} ns/point")
    for base in ("rebuild", "build"):
        ratio = [r[KEYS["flatten"]] / r[KEYS[base]] for r in runs]
        print(
            f"flatten / {base}: median {statistics.median(ratio):.2f} "
            f"({min(ratio):.2f} .. {max(ratio):.2f})"
        )


if __name__ == "__main__":
    main()
