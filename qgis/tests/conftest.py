"""QGIS without a display for the plugin's tests: one QgsApplication with
Processing initialised and the plugin's provider registered, the public
coverages the tests smooth, and helpers to read a layer's features back."""

import json
import os
import pathlib
import sys

import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "qgis"))

from qgis.core import QgsApplication, QgsVectorLayer  # noqa: E402

QgsApplication.setPrefixPath("/usr", True)
APP = QgsApplication([], False)
APP.initQgis()
for plugins in ("/usr/share/qgis/python/plugins", "/usr/lib/qgis/python/plugins"):
    if os.path.isdir(plugins):
        sys.path.append(plugins)

import processing  # noqa: E402
from processing.core.Processing import Processing  # noqa: E402

Processing.initialize()

from bzspline_processing.provider import BzsplineProvider  # noqa: E402


_KEPT = []


def provider():
    """The registered provider, registered anew if a test removed it. Python
    must keep it alive, as the plugin does: the registry holds only the C++
    side."""
    registry = QgsApplication.processingRegistry()
    if registry.providerById("bzspline") is None:
        _KEPT[:] = [BzsplineProvider()]
        registry.addProvider(_KEPT[0])
    return _KEPT[0]


provider()


@pytest.fixture(scope="session")
def atlas():
    """The folder of us-atlas and world-atlas as GeoJSON (bench/atlas.sh)."""
    given = os.environ.get("BZSPLINE_ATLAS")
    folder = pathlib.Path(given) if given else ROOT / "bench/atlas/data"
    if not (folder / "states.geojson").is_file():
        pytest.skip("no public coverages: export BZSPLINE_ATLAS=$(bash bench/atlas.sh)")
    return folder


def run(alg, **params):
    """``processing.run("bzspline:" + alg, params)``."""
    provider()
    return processing.run(f"bzspline:{alg}", params)


def features(path):
    """A layer file's features as (attribute dict, shapely geometry) in order."""
    import shapely

    layer = QgsVectorLayer(str(path), "out", "ogr")
    assert layer.isValid(), path
    names = layer.fields().names()
    out = []
    for f in layer.getFeatures():
        g = f.geometry()
        geom = None if g.isNull() else shapely.from_wkb(bytes(g.asWkb()))
        out.append(({n: f[n] for n in names}, geom))
    return out


def geojson(path):
    """A GeoJSON file's features as (properties, shapely geometry), read
    without QGIS."""
    from shapely.geometry import shape

    doc = json.loads(pathlib.Path(path).read_text())
    return [(f.get("properties") or {}, None if f["geometry"] is None else shape(f["geometry"]))
            for f in doc["features"]]
