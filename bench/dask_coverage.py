#!/usr/bin/env python3
"""Time bzspline.geo.smooth on one coverage: one process against a dask
cluster of worker processes, and check that they agree feature by feature.

    python3 bench/dask_coverage.py [--nx 300] [--ny 200] [--workers 2] [--npartitions 8]

The coverage is an nx by ny mosaic of cells whose shared vertices are jittered
once (every border shared exactly by its two cells), 4 vertices per cell side.
Three runs, each timed from the GeoSeries in memory to the smoothed GeoSeries:

- one process: ``bzspline.geo.smooth(series)``;
- the cluster: ``bzspline.geo.smooth`` of the dask-geopandas series on a
  ``distributed.LocalCluster`` of --workers processes, one thread each, with
  the partitions already on the workers (``persist``, as when the workers read
  the data themselves; neither the cluster's start-up nor that persist is
  timed): the nodes alone, the smoothing with the result left on the workers
  (as before writing it out from them), and with the result gathered into the
  client;
- the partitions smoothed each on its own (``map_partitions``), to show the
  borders that then part.

Prints seconds per run (best of --repeats), positions per second, and how many
features differ from the one-process result bit for bit.

On first use it creates the virtual environment bench/.venv, installs
geopandas, dask-geopandas and distributed into it and this tree's package
(crates/bzspline-py), then re-runs itself there.
"""

import argparse
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
VENV = os.path.join(HERE, ".venv")
VPY = os.path.join(VENV, "bin", "python")
NEEDS = ["numpy", "shapely", "geopandas", "dask-geopandas", "distributed"]


def ensure_venv():
    """Re-exec inside bench/.venv with the packages and bzspline installed."""
    if os.path.realpath(sys.prefix) == os.path.realpath(VENV):
        return
    if not os.path.exists(VPY):
        subprocess.run([sys.executable, "-m", "venv", VENV], check=True)
    subprocess.run([VPY, "-m", "pip", "install", "--quiet", *NEEDS], check=True)
    subprocess.run([VPY, "-m", "pip", "install", "--quiet", "--force-reinstall", "--no-deps",
                    os.path.join(ROOT, "crates", "bzspline-py")], check=True)
    os.execv(VPY, [VPY, *sys.argv])


def mosaic(nx, ny, k=4, wiggle=0.2, seed=0):
    """nx * ny cells as shapely polygons, built with numpy in one go."""
    import numpy as np
    import shapely

    rng = np.random.default_rng(seed)
    gx, gy = np.meshgrid(np.linspace(0, nx, nx * k + 1), np.linspace(0, ny, ny * k + 1), indexing="ij")
    inner = (slice(1, -1), slice(1, -1))
    gx[inner] += rng.uniform(-wiggle, wiggle, gx[inner].shape) / k
    gy[inner] += rng.uniform(-wiggle, wiggle, gy[inner].shape) / k
    t = np.arange(k)
    # Offsets of one cell's ring from its lower-left grid vertex, counter-clockwise.
    di = np.concatenate([t, np.full(k, k), k - t, np.zeros(k, int), [0]])
    dj = np.concatenate([np.zeros(k, int), t, np.full(k, k), k - t, [0]])
    i0 = (np.arange(nx) * k)[:, None].repeat(ny, 1).ravel()
    j0 = (np.arange(ny) * k)[None, :].repeat(nx, 0).ravel()
    ii, jj = i0[:, None] + di, j0[:, None] + dj
    rings = np.stack([gx[ii, jj], gy[ii, jj]], axis=-1)
    return shapely.polygons(rings)


def best(f, repeats):
    out, times = None, []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nx", type=int, default=300)
    ap.add_argument("--ny", type=int, default=200)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--npartitions", type=int, default=8)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    ensure_venv()

    import dask_geopandas
    import distributed
    import geopandas
    import numpy as np
    import shapely

    import bzspline

    cells = mosaic(args.nx, args.ny)
    series = geopandas.GeoSeries(cells, crs="EPSG:3857")
    positions = int(shapely.get_num_coordinates(cells).sum())
    print(f"coverage: {len(cells)} cells, {positions} positions; "
          f"{args.workers} worker processes, {args.npartitions} partitions; best of {args.repeats}")

    one, want = best(lambda: bzspline.geo.smooth(series), args.repeats)

    def differing(got):
        return int(sum(not a.equals_exact(b, 0.0) for a, b in zip(got.values, want.values)))

    with distributed.LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                                  dashboard_address=None, silence_logs=40) as cluster, \
            distributed.Client(cluster):
        frame = geopandas.GeoDataFrame(geometry=series)
        d = dask_geopandas.from_geopandas(frame, npartitions=args.npartitions).geometry.persist()
        distributed.wait(d)

        def cluster_run(together, gather=True):
            if together:
                out = bzspline.geo.smooth(d)
            else:
                out = d.map_partitions(bzspline.geo.smooth, meta=d._meta)
            if gather:
                return out.compute()
            return distributed.wait(out.persist())

        cluster_run(True)  # warm the workers: imports, first tasks
        reduction, nodes = best(lambda: bzspline.geo.nodes(d), args.repeats)
        kept, _ = best(lambda: cluster_run(True, gather=False), args.repeats)
        many, got = best(lambda: cluster_run(True), args.repeats)
        naive, got_naive = best(lambda: cluster_run(False), args.repeats)

    print(f"nodes: {len(nodes)} positions where partitions meet")
    rows = [
        ("one process", one, 0),
        ("cluster, the nodes alone", reduction, None),
        ("cluster, smooth, kept on workers", kept, None),
        ("cluster, smooth + gather", many, differing(got)),
        (f"cluster, {args.npartitions} partitions each alone", naive, differing(got_naive)),
    ]
    print(f"{'run':<40} {'seconds':>8} {'Mpos/s':>7} {'vs one':>7} {'features differing':>19}")
    for name, s, diff in rows:
        diff = "" if diff is None else diff
        print(f"{name:<40} {s:8.2f} {positions / s / 1e6:7.2f} {one / s:6.2f}x {diff:>19}")


if __name__ == "__main__":
    main()
