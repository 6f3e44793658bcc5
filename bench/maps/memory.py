#!/usr/bin/env python3
"""Peak memory of `bzspline smooth` on one large coverage in every layer
format: a mosaic of nx by ny cells (bench/dask_coverage.py's, every border
shared by its two cells) written as GeoJSON, GeoPackage, FlatGeobuf and ESRI
Shapefile (by pyogrio's GDAL) and GeoParquet (by geopandas and pyarrow), each
smoothed as one coverage into a file of its own format.

    cargo build --release -p bzspline-cli
    cargo build --release -p bzspline-io --all-features --example layer_memory
    python3 bench/maps/memory.py [--nx 1000] [--ny 1000] [--k 2] [--bin target/release/bzspline]

Needs geopandas, pyogrio and pyarrow. Prints, per format, the input's size
S (a Shapefile's `.shp`, `.shx` and `.dbf` together), the peak resident memory of the command (GNU time's maximum resident set
size), that peak over S, the seconds, the reference of 2 S plus the
coverage's positions (16 bytes each), and, from the layer_memory example
(for the layer formats), the peak once the layer is read, before its
coverage is built.
"""

import argparse
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))

from dask_coverage import mosaic  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nx", type=int, default=1000)
    ap.add_argument("--ny", type=int, default=1000)
    ap.add_argument("--k", type=int, default=2, help="vertices per cell side")
    ap.add_argument("--bin", default=os.path.join(ROOT, "target/release/bzspline"))
    ap.add_argument("--phases", default=os.path.join(ROOT, "target/release/examples/layer_memory"),
                    help="the layer_memory example")
    ap.add_argument("--dir", default=None, help="where the files go (default: a temporary folder)")
    args = ap.parse_args()

    import geopandas
    import numpy as np
    import shapely

    cells = mosaic(args.nx, args.ny, k=args.k)
    n = len(cells)
    gdf = geopandas.GeoDataFrame(
        {"id": np.arange(n, dtype="int64"), "name": [f"cell {i}" for i in range(n)]},
        geometry=cells, crs="EPSG:3857")
    positions = int(shapely.get_num_coordinates(cells).sum())
    print(f"coverage: {n:,} cells, {positions:,} positions ({args.nx} x {args.ny}, k = {args.k})")
    with tempfile.TemporaryDirectory(dir=args.dir) as d:
        files = {
            "GeoJSON": os.path.join(d, "cells.geojson"),
            "GeoPackage": os.path.join(d, "cells.gpkg"),
            "FlatGeobuf": os.path.join(d, "cells.fgb"),
            "GeoParquet": os.path.join(d, "cells.parquet"),
            "Shapefile": os.path.join(d, "cells.shp"),
        }
        gdf.to_parquet(files["GeoParquet"])
        for name, driver in [("GeoJSON", "GeoJSON"), ("GeoPackage", "GPKG"), ("FlatGeobuf", "FlatGeobuf"),
                             ("Shapefile", "ESRI Shapefile")]:
            gdf.to_file(files[name], driver=driver, engine="pyogrio")
        print("| input | S, MB | peak, MB | peak / S | 2 S + positions, MB | s | peak once read, MB |")
        print("|---|---:|---:|---:|---:|---:|---:|")
        for name, path in files.items():
            out = os.path.join(d, "out" + os.path.splitext(path)[1])
            r = subprocess.run(["/usr/bin/time", "-f", "%M %e", args.bin, "smooth", path, "-o", out],
                               capture_output=True, text=True)
            if r.returncode != 0:
                sys.exit(f"{name}: {r.stderr}")
            kb, secs = r.stderr.strip().splitlines()[-1].split()
            size = sum(os.path.getsize(f) for f in siblings(path)) / 1e6
            peak = int(kb) / 1e3
            ref = 2 * size + positions * 16 / 1e6
            read = "-"
            if name != "GeoJSON" and os.path.exists(args.phases):
                # Its allocator set as the command sets it (crates/bzspline-cli/src/alloc.rs).
                env = dict(os.environ, MIMALLOC_PURGE_DELAY="0", MIMALLOC_ARENA_PURGE_MULT="0")
                r = subprocess.run([args.phases, path], capture_output=True, text=True, env=env)
                if r.returncode != 0:
                    sys.exit(f"{name}: layer_memory: {r.stderr}")
                read = next(f"{int(l.split()[2]):,}" for l in r.stdout.splitlines()
                            if l.startswith("reading"))
            print(f"| {name} | {size:,.0f} | {peak:,.0f} | {peak / size:.1f} | {ref:,.0f} | {float(secs):.1f} | {read} |")
            for f in siblings(out, (".shx", ".dbf", ".prj", ".cpg")):
                os.remove(f)


def siblings(path, exts=(".shx", ".dbf")):
    """The file at `path`, with those of a Shapefile's files `exts` that are there."""
    stem, ext = os.path.splitext(path)
    if ext != ".shp":
        return [path]
    return [path] + [stem + e for e in exts if os.path.exists(stem + e)]


if __name__ == "__main__":
    main()
