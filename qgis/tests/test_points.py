"""Spline through points and Smooth noisy track through ``processing.run``:
the lines are the package's on the same points, in the field's order and
groups; the track's smoothing weight is GCV's and the smoothed track is
nearer the truth than the noisy fixes."""

import numpy as np
import pytest
import shapely
from conftest import features, run
from qgis.core import QgsFeature, QgsGeometry, QgsPointXY, QgsProcessingException, QgsVectorLayer
from qgis.PyQt.QtCore import QDateTime, Qt

import bzspline
import bzspline.geo


def points_layer(crs, rows, fields):
    """A memory point layer with ``rows`` of ((x, y), attributes)."""
    layer = QgsVectorLayer(f"Point?crs={crs}{fields}", "points", "memory")
    feats = []
    for xy, attrs in rows:
        f = QgsFeature(layer.fields())
        if xy is not None:
            f.setGeometry(QgsGeometry.fromPointXY(QgsPointXY(*xy)))
        f.setAttributes(attrs)
        feats.append(f)
    assert layer.dataProvider().addFeatures(feats)
    return layer


def test_splines_follow_the_order_field_in_each_group(tmp_path):
    rng = np.random.default_rng(7)
    rows, truth = [], {}
    for group in ("north", "south"):
        t = np.linspace(0, 3, 9)
        xy = np.c_[100 * t, 40 * np.sin(t) + (500 if group == "north" else 0)]
        truth[group] = xy
        rows += [(tuple(p), [group, float(k)]) for k, p in enumerate(xy)]
    rows = [rows[i] for i in rng.permutation(len(rows))]
    layer = points_layer("EPSG:32633", rows, "&field=road:string&field=km:double")
    for closed in (False, True):
        out = tmp_path / f"splines{closed}.gpkg"
        run("splinethroughpoints", INPUT=layer, ORDER_FIELD="km", GROUP_FIELD="road", CLOSED=closed,
            TOLERANCE=0.05, TOLERANCE_UNIT=0, OUTPUT=str(out))
        got = {a["road"]: (a["points"], g) for a, g in features(out)}
        assert set(got) == {"north", "south"}
        for group, xy in truth.items():
            n, line = got[group]
            assert n == len(xy)
            given = shapely.Polygon(xy) if closed else shapely.LineString(xy)
            ours = bzspline.geo.smooth(given, tolerance=0.05, coverage=False, through=True)
            want = shapely.get_coordinates(ours.exterior if closed else ours)
            assert np.array_equal(shapely.get_coordinates(line), want)
            # Through every point, in the order of the field.
            coords = shapely.get_coordinates(line)
            at = [int(np.flatnonzero((coords == p).all(axis=1))[0]) for p in xy]
            assert at == sorted(at)
            assert line.is_closed == closed


def test_a_group_of_one_point_is_skipped_and_null_orders_are_named(tmp_path):
    layer = points_layer("EPSG:3857", [((0, 0), ["a", 1]), ((1, 1), ["a", 2]), ((2, 0), ["a", 3]),
                                       ((5, 5), ["b", 1])], "&field=g:string&field=o:integer")
    out = tmp_path / "one.gpkg"
    run("splinethroughpoints", INPUT=layer, ORDER_FIELD="o", GROUP_FIELD="g", OUTPUT=str(out))
    assert [a["g"] for a, _ in features(out)] == ["a"]
    nulls = points_layer("EPSG:3857", [((0, 0), [1]), ((1, 1), [None]), ((2, 0), [3])], "&field=o:integer")
    bad = tmp_path / "bad.gpkg"
    with pytest.raises(QgsProcessingException, match="feature 2: its o is NULL"):
        run("splinethroughpoints", INPUT=nulls, ORDER_FIELD="o", OUTPUT=str(bad))
    assert not bad.exists()


def noisy_track(seed=3, n=400, sigma=4.0):
    """A drive along a smooth path (metres, 1 fix a second) and its fixes with noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(n, dtype=float)
    truth = np.c_[8 * t, 300 * np.sin(t / 60)]
    return t, truth, truth + rng.normal(0, sigma, truth.shape)


def test_a_noisy_track_is_smoothed_with_the_weight_gcv_chooses(tmp_path):
    t, truth, fixes = noisy_track()
    start = QDateTime.fromString("2026-05-01T08:00:00Z", Qt.ISODate)
    rows = [(tuple(p), [start.addSecs(int(s))]) for s, p in zip(t, fixes)]
    order = np.random.default_rng(1).permutation(len(rows))
    layer = points_layer("EPSG:32633", [rows[i] for i in order], "&field=time:datetime")
    out = tmp_path / "track.gpkg"
    run("smoothtrack", INPUT=layer, TIME_FIELD="time", TOLERANCE=0.01, TOLERANCE_UNIT=0, OUTPUT=str(out))
    (attrs, line), = features(out)
    curve = bzspline.smoothing_curve(fixes, param=t)
    assert attrs["points"] == len(t)
    assert attrs["lam"] == pytest.approx(curve.lam, rel=1e-12)
    assert attrs["gcv"] == pytest.approx(curve.gcv, rel=1e-12)
    assert np.allclose(shapely.get_coordinates(line), curve.flatten(0.01), rtol=0, atol=1e-9)
    # Nearer the path driven than the fixes are.
    path = shapely.LineString(truth)
    err_fixes = np.sqrt(np.mean(shapely.distance(shapely.points(fixes), path) ** 2))
    err_line = np.sqrt(np.mean(shapely.distance(shapely.points(curve(t)), path) ** 2))
    assert err_line < 0.5 * err_fixes


def test_a_track_in_longitude_and_latitude_is_smoothed_in_metres(tmp_path):
    t, truth, fixes = noisy_track(seed=5)
    # Metres to degrees near 60 N.
    lonlat = np.c_[10 + fixes[:, 0] / (111_320 * 0.5), 60 + fixes[:, 1] / 111_320]
    layer = points_layer("EPSG:4326", [(tuple(p), [float(s), "x"]) for s, p in zip(t, lonlat)],
                         "&field=t:double&field=id:string")
    out = tmp_path / "track.gpkg"
    run("smoothtrack", INPUT=layer, TIME_FIELD="t", GROUP_FIELD="id", TOLERANCE=0.5, TOLERANCE_UNIT=0,
        OUTPUT=str(out))
    (attrs, line), = features(out)
    assert attrs["id"] == "x" and attrs["lam"] > 0
    c = shapely.get_coordinates(line)
    assert 9.9 < c[:, 0].min() and c[:, 0].max() < 10.1 and 59.99 < c[:, 1].min() < c[:, 1].max() < 60.01
    bad = tmp_path / "bad.gpkg"
    with pytest.raises(QgsProcessingException, match="metres or kilometres"):
        run("smoothtrack", INPUT=layer, TIME_FIELD="t", TOLERANCE=0.001, TOLERANCE_UNIT=3, OUTPUT=str(bad))
    assert not bad.exists()


def test_two_fixes_at_one_time_name_both(tmp_path):
    layer = points_layer("EPSG:3857", [((0, 0), [1.0]), ((1, 1), [2.0]), ((2, 0), [2.0]), ((3, 1), [4.0])],
                         "&field=t:double")
    bad = tmp_path / "bad.gpkg"
    with pytest.raises(QgsProcessingException, match="features 2 and 3 have the same time"):
        run("smoothtrack", INPUT=layer, TIME_FIELD="t", OUTPUT=str(bad))
    assert not bad.exists()


def test_jumps_are_ignored_when_asked_and_counted(tmp_path):
    t, truth, fixes = noisy_track(seed=7)
    jumps = [50, 200, 333]
    fixes[jumps] += [[0, 400], [-350, 0], [300, 300]]
    layer = points_layer("EPSG:32633", [(tuple(p), [float(s)]) for s, p in zip(t, fixes)],
                         "&field=t:double")
    path = shapely.LineString(truth)
    rms = lambda line: np.sqrt(np.mean(shapely.distance(
        shapely.points(shapely.get_coordinates(line)), path) ** 2))
    plain, robust = tmp_path / "plain.gpkg", tmp_path / "robust.gpkg"
    run("smoothtrack", INPUT=layer, TIME_FIELD="t", TOLERANCE=0.01, OUTPUT=str(plain))
    run("smoothtrack", INPUT=layer, TIME_FIELD="t", TOLERANCE=0.01, ROBUST=True, OUTPUT=str(robust))
    (pa, pline), = features(plain)
    (ra, rline), = features(robust)
    assert "outliers" not in pa and ra["outliers"] >= len(jumps)
    curve = bzspline.smoothing_curve(fixes, param=t, robust=True)
    assert ra["outliers"] == np.count_nonzero(curve.robustness == 0)
    assert np.all(curve.robustness[jumps] == 0)
    assert np.allclose(shapely.get_coordinates(rline), curve.flatten(0.01), rtol=0, atol=1e-9)
    assert rms(rline) < 0.5 * rms(pline)
