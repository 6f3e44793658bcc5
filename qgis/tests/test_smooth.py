"""Smooth coverage and Smooth lines or polygons independently, run through
``processing.run`` on the public coverages (us-atlas states and counties,
world-atlas countries): features and attributes kept, every polygon valid,
the coverage still a coverage (GEOS's validator: no overlaps, borders still
shared), and the same geometries ``bzspline.geo.smooth`` gives."""

import numpy as np
import pytest
import shapely
from conftest import features, geojson, run
from qgis.core import QgsProcessingException, QgsVectorLayer

import bzspline.geo


def faulty(coverage):
    """Positions of the polygons with edges GEOS's coverage validator
    finds invalid (an overlap, a border not shared exactly)."""
    return set(np.flatnonzero(~shapely.is_empty(shapely.coverage_invalid_edges(coverage))).tolist())


def same(a, b):
    return all(np.array_equal(shapely.get_coordinates(p), shapely.get_coordinates(q)) for p, q in zip(a, b))


@pytest.mark.parametrize("name, tolerance, unit", [
    ("states", 200.0, 0),      # 200 m on the ellipsoid
    ("counties", 0.0, 0),      # the default tolerance
    ("countries", 1.0, 1),     # 1 km
])
def test_a_coverage_stays_a_coverage(atlas, tmp_path, name, tolerance, unit):
    src = atlas / f"{name}.geojson"
    given = geojson(src)
    geoms = np.array([g for _, g in given], dtype=object)
    out = tmp_path / f"{name}.gpkg"
    res = run("smoothcoverage", INPUT=str(src), TOLERANCE=tolerance, TOLERANCE_UNIT=unit, OUTPUT=str(out))
    assert res["OUTPUT"] == str(out)
    got = features(out)
    assert len(got) == len(given)
    assert [a["name"] for a, _ in got] == [p["name"] for p, _ in given]
    smoothed = np.array([g for _, g in got], dtype=object)
    present = ~shapely.is_missing(geoms)
    assert (shapely.is_missing(smoothed) == ~present).all()
    # What was valid stays valid; a valid coverage stays one.
    valid = present & shapely.is_valid(geoms)
    assert shapely.is_valid(smoothed[valid]).all()
    # No border parts: the polygons whose edges GEOS finds unshared or
    # overlapping (a few counties, as the atlas gives them) are no more.
    assert faulty(smoothed[valid]) <= faulty(geoms[valid])
    # Fewer vertices than the input's curves would need at this tolerance,
    # and not the input itself.
    assert not same(smoothed[present], geoms[present])
    # Exactly the package's result on the same geometries.
    text = None if tolerance == 0 else f"{tolerance!r}{['m', 'km'][unit]}"
    ours = bzspline.geo.smooth(geoms, tolerance=text, crs="EPSG:4326")
    assert same(smoothed[present], ours[present])


def test_feature_by_feature_smoothing_parts_shared_borders(atlas, tmp_path):
    src = atlas / "states.geojson"
    geoms = np.array([g for _, g in geojson(src)], dtype=object)
    out = tmp_path / "alone.gpkg"
    run("smoothindependently", INPUT=str(src), TOLERANCE=0.001, TOLERANCE_UNIT=2, OUTPUT=str(out))
    alone = np.array([g for _, g in features(out)], dtype=object)
    assert same(alone, bzspline.geo.smooth(geoms, tolerance=0.001, coverage=False))
    # Borders smoothed twice part: the layer is no longer a coverage.
    valid = shapely.is_valid(geoms)
    assert shapely.coverage_is_valid(geoms[valid])
    assert not shapely.coverage_is_valid(alone[valid])
    # The coverage algorithm's own per-feature switch is the same thing.
    out2 = tmp_path / "alone2.gpkg"
    run("smoothcoverage", INPUT=str(src), TOLERANCE=0.001, TOLERANCE_UNIT=2, PER_FEATURE=True, OUTPUT=str(out2))
    assert same(alone, [g for _, g in features(out2)])


def memory(kind, crs, rows, fields=""):
    """A memory layer of ``kind`` (``Polygon``...) with ``rows`` of (WKT, attributes)."""
    from qgis.core import QgsFeature, QgsGeometry

    layer = QgsVectorLayer(f"{kind}?crs={crs}{fields}", "input", "memory")
    feats = []
    for wkt, attrs in rows:
        f = QgsFeature(layer.fields())
        if wkt is not None:
            f.setGeometry(QgsGeometry.fromWkt(wkt))
        f.setAttributes(attrs)
        feats.append(f)
    layer.dataProvider().addFeatures(feats)
    return layer


def test_null_geometries_pass_and_attributes_keep_their_types(tmp_path):
    layer = memory("Polygon", "EPSG:3857", [
        ("POLYGON((0 0, 10 0, 10 10, 0 10, 0 0))", [1, "a", 2.5]),
        (None, [2, "b", None]),
        ("POLYGON((10 0, 20 0, 20 10, 10 10, 10 0))", [3, "c", -1.0]),
    ], "&field=n:integer&field=s:string(12)&field=v:double")
    out = tmp_path / "out.gpkg"
    run("smoothcoverage", INPUT=layer, TOLERANCE=0.01, TOLERANCE_UNIT=0, OUTPUT=str(out))
    got = features(out)
    assert [(a["n"], a["s"]) for a, _ in got] == [(1, "a"), (2, "b"), (3, "c")]
    assert got[1][1] is None or got[1][1].is_empty
    assert shapely.coverage_is_valid(np.array([got[0][1], got[2][1]], dtype=object))
    out_layer = QgsVectorLayer(str(out), "out", "ogr")
    from qgis.PyQt.QtCore import QVariant

    kinds = {f.name(): (f.type(), f.length()) for f in out_layer.fields()}
    assert kinds["n"][0] in (QVariant.Int, QVariant.LongLong)
    assert kinds["s"] == (QVariant.String, 12) and kinds["v"][0] == QVariant.Double


def test_bad_input_is_a_message_and_nothing_is_written(tmp_path):
    points = memory("Point", "EPSG:3857", [("POINT(0 0)", [])])
    out = tmp_path / "points.gpkg"
    with pytest.raises(QgsProcessingException):
        run("smoothcoverage", INPUT=points, OUTPUT=str(out))
    assert not out.exists()
    # Metres on a layer without a CRS.
    square = memory("Polygon", "", [("POLYGON((0 0, 10 0, 10 10, 0 10, 0 0))", [])])
    with pytest.raises(QgsProcessingException, match="has no CRS, so a distance in metres"):
        run("smoothcoverage", INPUT=square, TOLERANCE=5.0, TOLERANCE_UNIT=0, OUTPUT=str(out))
    assert not out.exists()
    # Degrees on a projected layer.
    metric = memory("Polygon", "EPSG:3857", [("POLYGON((0 0, 10 0, 10 10, 0 10, 0 0))", [])])
    with pytest.raises(QgsProcessingException, match="projected, not in degrees"):
        run("smoothcoverage", INPUT=metric, TOLERANCE=1.0, TOLERANCE_UNIT=3, OUTPUT=str(out))
    assert not out.exists()


def test_invalid_polygons_are_smoothed_with_a_warning(tmp_path):
    from qgis.core import QgsProcessingFeedback

    class Log(QgsProcessingFeedback):
        def __init__(self):
            super().__init__()
            self.warnings = []

        def pushWarning(self, text):  # noqa: N802
            self.warnings.append(text)

    bowtie = memory("Polygon", "EPSG:3857", [("POLYGON((0 0, 10 10, 10 0, 0 10, 0 0))", [])])
    log = Log()
    out = tmp_path / "bowtie.gpkg"
    import processing

    processing.run("bzspline:smoothcoverage", {"INPUT": bowtie, "TOLERANCE": 0.0, "OUTPUT": str(out)},
                   feedback=log)
    assert any("not valid" in w and "feature ids 1" in w for w in log.warnings), log.warnings
    assert len(features(out)) == 1
