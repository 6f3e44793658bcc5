"""QGIS's own Smooth (native:smoothgeometry, Chaikin's corner cutting,
feature by feature) beside bzspline's Smooth coverage on the public
coverages, in one headless QGIS: vertices out, valid polygons made invalid,
neighbours (valid polygons sharing a border) that came apart or overlap,
by GEOS's intersections, and time.

    export BZSPLINE_ATLAS=$(bash bench/atlas.sh)
    QT_QPA_PLATFORM=offscreen python bench/qgis/compare.py     # QGIS's Python, with bzspline and shapely 2

Prints a Markdown table (BENCHMARKS.md, "QGIS").
"""

import os
import pathlib
import platform
import sys
import time

import numpy as np
import shapely

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "qgis"))

from qgis.core import QgsApplication, QgsVectorLayer  # noqa: E402

QgsApplication.setPrefixPath("/usr", True)
app = QgsApplication([], False)
app.initQgis()
sys.path.append("/usr/share/qgis/python/plugins")
import processing  # noqa: E402
from processing.core.Processing import Processing  # noqa: E402

Processing.initialize()
from bzspline_processing.provider import BzsplineProvider  # noqa: E402

provider = BzsplineProvider()
QgsApplication.processingRegistry().addProvider(provider)


def geometries(layer):
    return np.array([None if f.geometry().isNull() else shapely.from_wkb(bytes(f.geometry().asWkb()))
                     for f in layer.getFeatures()], dtype=object)


def neighbours(g):
    """The pairs (i, j), i < j, of valid polygons that share a border (not
    just a point), and the length of each border."""
    ok = np.flatnonzero(~shapely.is_missing(g) & shapely.is_valid(g))
    tree = shapely.STRtree(g[ok])
    a, b = tree.query(g[ok], predicate="intersects")
    keep = a < b
    i, j = ok[a[keep]], ok[b[keep]]
    shared = shapely.length(shapely.intersection(shapely.boundary(g[i]), shapely.boundary(g[j])))
    line = shared > 0
    return i[line], j[line], shared[line]


def parted(out, i, j, shared):
    """How many neighbour pairs came apart (their outputs share less than
    half the border's length: a gap opened) and how many overlap (their
    interiors meet over an area)."""
    a, b = out[i], out[j]
    now = shapely.length(shapely.intersection(shapely.boundary(a), shapely.boundary(b)))
    overlap = shapely.area(shapely.intersection(a, b))
    return int((now < 0.5 * shared).sum()), int((overlap > 1e-12 * shapely.area(a)).sum())


def measure(alg, params, layer, valid, pairs):
    t = time.perf_counter()
    out = processing.run(alg, dict(params, INPUT=layer, OUTPUT="memory:"))["OUTPUT"]
    seconds = time.perf_counter() - t
    g = geometries(out)
    gaps, overlaps = parted(g, *pairs)
    return (int(shapely.get_num_coordinates(g).sum()), int((~shapely.is_valid(g[valid])).sum()),
            gaps, overlaps, seconds)


def main():
    folder = pathlib.Path(os.environ.get("BZSPLINE_ATLAS", ROOT / "bench/atlas/data"))
    runs = [
        ("Smooth, default (1 iteration, offset 0.25)", "native:smoothgeometry", {}),
        ("Smooth, 3 iterations", "native:smoothgeometry", {"ITERATIONS": 3}),
        ("bzspline Smooth coverage, 500 m", "bzspline:smoothcoverage", {"TOLERANCE": 500.0}),
        ("bzspline Smooth coverage, 50 m", "bzspline:smoothcoverage", {"TOLERANCE": 50.0}),
    ]
    from qgis.core import Qgis

    with open("/proc/cpuinfo") as f:
        cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")),
                   platform.machine())
    print(f"QGIS {Qgis.QGIS_VERSION}, {cpu}, {os.cpu_count()} cores\n")
    print("| layer | tool | vertices | valid polygons made invalid | neighbours parted | neighbours overlapping | time |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
    for name in ("states", "counties", "countries"):
        layer = QgsVectorLayer(str(folder / f"{name}.geojson"), name, "ogr")
        given = geometries(layer)
        valid = ~shapely.is_missing(given) & shapely.is_valid(given)
        pairs = neighbours(given)
        gaps, overlaps = parted(given, *pairs)
        n = int(shapely.get_num_coordinates(given).sum())
        print(f"| {name} ({len(given)}) | input | {n:,} | {int((~valid).sum())} invalid given | "
              f"{gaps} of {len(pairs[0]):,} pairs | {overlaps} | |")
        for label, alg, params in runs:
            v, broken, gaps, overlaps, s = measure(alg, params, layer, valid, pairs)
            print(f"| | {label} | {v:,} | {broken} | {gaps} | {overlaps} | {s:.2f} s |")


if __name__ == "__main__":
    main()
