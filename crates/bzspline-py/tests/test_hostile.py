"""Hostile input to every entry point of the Python package: a correct result
or a TypeError/ValueError naming the index, never a crash; missing and empty
geometries come back as they went in. And an independent judge: the public
coverages smoothed, then checked with GEOS through shapely."""

import os
import pathlib

import numpy as np
import pytest

import bzspline

X = np.array([0.0, 1.0, 2.0, 4.0])
Y = np.array([0.0, 2.0, 1.0, 3.0])
SQUARE = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]


def same_spline(a, b):
    assert np.array_equal(a.segments, b.segments) and np.array_equal(a.x, b.x)


# -- Spline and Curve --------------------------------------------------------

@pytest.mark.parametrize("dtype", [np.float32, np.int32, np.int64, np.uint8, np.float16])
def test_spline_takes_any_real_dtype_as_float64(dtype):
    x, y = X.astype(dtype), Y.astype(dtype)
    same_spline(bzspline.Spline(x, y), bzspline.Spline(x.astype(np.float64), y.astype(np.float64)))


def test_spline_takes_non_contiguous_views_and_lists():
    big_x = np.repeat(X, 3)[::3]
    big_y = np.stack([Y, Y], axis=1)[:, 1]
    assert not big_y.flags.c_contiguous
    same_spline(bzspline.Spline(big_x, big_y), bzspline.Spline(X, Y))
    same_spline(bzspline.Spline(list(X), tuple(Y)), bzspline.Spline(X, Y))
    s = bzspline.Spline(X, Y)
    q = np.linspace(0, 4, 20)[::2]
    assert np.array_equal(s(q), s(np.ascontiguousarray(q)))


def test_spline_refuses_what_is_not_real_numbers():
    # Strings of numbers are read as numpy reads them (as scipy does).
    same_spline(bzspline.Spline(np.array(["0", "1", "2", "4"]), Y), bzspline.Spline(X, Y))
    with pytest.raises(TypeError):
        bzspline.Spline(np.array(["0", "one", "2"]), [1.0, 2.0, 3.0])
    # None in an object array is NaN: refused at its index.
    with pytest.raises(ValueError, match=r"knots\[1\]"):
        bzspline.Spline(np.array([0.0, None, 2.0], dtype=object), [1.0, 2.0, 3.0])
    with pytest.raises(TypeError):
        bzspline.Spline([0.0, 1.0, 2.0], np.array([1 + 1j, 2, 3]))
    with pytest.raises(ValueError, match="knots|x"):
        bzspline.Spline(np.float64(1.0), np.float64(2.0))
    with pytest.raises(ValueError, match=r"\[1\]"):
        bzspline.Spline([0.0, np.inf, 2.0], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"\[2\]"):
        bzspline.Spline([0.0, 1.0, 2.0], [1.0, 2.0, -np.inf])
    with pytest.raises(ValueError):
        bzspline.Spline([], [])


def test_spline_queries_take_0d_arrays_and_refuse_nan():
    s = bzspline.Spline(X, Y)
    assert s(np.float64(1.0)) == s(1.0)
    assert np.ndim(s(np.array(1.0))) == 0
    assert s(np.array(1, dtype=np.int8)) == s(1.0)
    v = s(np.array([0.5, np.nan]))
    assert np.isnan(v[1]) and np.isfinite(v[0])
    with pytest.raises(TypeError):
        s(np.array(["x"]))


@pytest.mark.parametrize("dtype", [np.float32, np.int64])
def test_curve_takes_any_real_dtype_and_views(dtype):
    pts = np.array(SQUARE + [[3.0, 5.0]])
    want = bzspline.Curve(pts)
    got = bzspline.Curve(pts.astype(dtype))
    assert np.array_equal(got.knots, bzspline.Curve(pts.astype(dtype).astype(np.float64)).knots)
    wide = np.zeros((5, 4))
    wide[:, ::2] = pts
    got = bzspline.Curve(wide[:, ::2])
    assert np.array_equal(got.knots, want.knots)


def test_curve_refuses_what_is_not_points():
    with pytest.raises(TypeError):
        bzspline.Curve(np.array([["0", "0"], ["1", "one"]]))
    with pytest.raises(ValueError, match=r"points\[1\]"):
        bzspline.Curve(np.array([[0.0, 0.0], [None, 1.0], [2.0, 0.0]], dtype=object))
    with pytest.raises(ValueError, match=r"points\[2\]"):
        bzspline.Curve([[0.0, 0.0], [1.0, 1.0], [np.nan, 0.0]])
    with pytest.raises(ValueError):
        bzspline.Curve(np.float64(3.0))
    with pytest.raises(ValueError):
        bzspline.Curve(np.zeros((0, 2)))


# -- geo.smooth --------------------------------------------------------------

shapely = pytest.importorskip("shapely")


def cells():
    a = shapely.Polygon([(0, 0), (1, 0), (1.2, 0.5), (1, 1), (0, 1)])
    b = shapely.Polygon([(1, 0), (2, 0), (2, 1), (1, 1), (1.2, 0.5)])
    return [a, b]


def test_missing_and_empty_geometries_come_back_as_they_went_in():
    empty = [shapely.Polygon(), shapely.LineString(), shapely.GeometryCollection(), shapely.Point()]
    arr = np.array([None, *cells(), *empty], dtype=object)
    out = bzspline.geo.smooth(arr, tolerance=1e-3)
    assert out[0] is None
    for g, o in zip(empty, out[3:]):
        assert o.is_empty and o.geom_type == g.geom_type
    geopandas = pytest.importorskip("geopandas")
    s = geopandas.GeoSeries(list(arr), index=[10, 11, 12, 13, 14, 15, 16])
    o = bzspline.geo.smooth(s, tolerance=1e-3)
    assert list(o.index) == list(s.index) and o.isna().tolist() == s.isna().tolist()
    assert o.is_empty[13:].all()


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_coordinates_name_the_geometry(bad):
    poly = shapely.Polygon([(0, 0), (1, 0), (1, bad), (0, 1)])
    with pytest.raises(ValueError, match="geometry 2"):
        bzspline.geo.smooth(np.array([*cells(), poly], dtype=object))
    with pytest.raises(ValueError, match="geometry 2"):
        bzspline.geo.smooth(np.array([*cells(), poly], dtype=object), coverage=False)


def test_collections_and_points_pass_through_or_are_smoothed():
    gc = shapely.GeometryCollection([shapely.Point(0, 0), shapely.LineString([(0, 0), (1, 1), (2, 0)])])
    out = bzspline.geo.smooth(np.array([gc, shapely.Point(3, 3), *cells()], dtype=object), tolerance=1e-3)
    assert out[1].equals(shapely.Point(3, 3))
    assert shapely.get_type_id(out[0]) == 7


def test_an_invalid_polygon_is_smoothed_without_a_crash():
    bowtie = shapely.Polygon([(0, 0), (2, 2), (2, 0), (0, 2)])
    assert not bowtie.is_valid
    out = bzspline.geo.smooth(np.array([bowtie, *cells()], dtype=object), tolerance=1e-3)
    assert shapely.get_type_id(out[0]) == 3
    assert np.isfinite(shapely.get_coordinates(out[0])).all()
    assert shapely.is_valid(out[1:]).all()


def test_what_is_not_a_geometry_is_a_type_error():
    with pytest.raises(TypeError):
        bzspline.geo.smooth(np.array(["POLYGON ((0 0, 1 0, 1 1, 0 0))"], dtype=object))
    with pytest.raises(TypeError):
        bzspline.geo.smooth(np.array([1.5, None], dtype=object))
    with pytest.raises(TypeError):
        bzspline.geo.smooth("not a geometry")


def test_snap_puts_a_vertex_near_an_edge_into_it():
    hair = 1e-9
    left = shapely.Polygon([(0, 0), (1, 0), (1.1 + hair, 0.25), (1.2, 0.5), (1.1 - hair, 0.75), (1, 1), (0, 1)])
    right = shapely.Polygon([(1, 0), (2, 0), (2, 1), (1, 1), (1.2, 0.5)])
    arr = np.array([left, right], dtype=object)
    apart = bzspline.geo.smooth(arr, tolerance=1e-4)
    joined = bzspline.geo.smooth(arr, tolerance=1e-4, snap=1e-6)
    # Apart: the two copies of the border leave a sliver between the cells.
    union = shapely.union_all(apart)
    assert union.geom_type == "MultiPolygon" or len(union.interiors) > 0 or \
        apart[0].intersection(apart[1]).area > 0
    # Joined: no gap, no overlap.
    assert joined[0].intersection(joined[1]).area == 0
    u = shapely.union_all(joined)
    assert u.geom_type == "Polygon" and len(u.interiors) == 0
    assert np.isclose(u.area, joined[0].area + joined[1].area, rtol=1e-12)


# -- GEOS as the judge on the public coverages -------------------------------

ATLAS = os.environ.get("BZSPLINE_ATLAS")


@pytest.mark.skipif(not ATLAS, reason="BZSPLINE_ATLAS (bash bench/atlas.sh) not set")
@pytest.mark.skipif(not hasattr(shapely, "coverage_invalid_edges"), reason="shapely >= 2.1")
@pytest.mark.parametrize("name", ["states", "counties", "countries"])
def test_geos_finds_nothing_made_invalid_on_the_public_coverages(name):
    geoms = shapely.from_geojson(pathlib.Path(ATLAS, f"{name}.geojson").read_text())
    arr = np.asarray(shapely.get_parts(geoms), dtype=object)
    out = bzspline.geo.smooth(arr)
    assert len(out) == len(arr)
    valid_in, valid_out = shapely.is_valid(arr), shapely.is_valid(out)
    assert not (valid_in & ~valid_out).any(), np.flatnonzero(valid_in & ~valid_out)[:10]
    ok_in = shapely.is_empty(shapely.coverage_invalid_edges(arr))
    ok_out = shapely.is_empty(shapely.coverage_invalid_edges(out))
    assert not (ok_in & ~ok_out).any(), np.flatnonzero(ok_in & ~ok_out)[:10]
    # Smoothing happened.
    assert shapely.get_num_coordinates(out).sum() != shapely.get_num_coordinates(arr).sum()


@pytest.mark.skipif(not hasattr(shapely, "has_m"), reason="shapely >= 2.1 knows M")
def test_measures_are_dropped_with_a_warning_as_the_command_does():
    zm = shapely.from_wkt("LINESTRING ZM (0 0 1 7, 1 1 2 7, 2 0 3 7)")
    m = shapely.from_wkt("POLYGON M ((0 0 5, 1 0 5, 1 1 5, 0 1 5, 0 0 5))")
    with pytest.warns(UserWarning, match="2 geometries with M"):
        out = bzspline.geo.smooth(np.array([zm, m], dtype=object), tolerance=1e-2)
    assert out[0].has_z and not shapely.has_m(out[0])
    c = shapely.get_coordinates(out[0], include_z=True)
    assert tuple(c[0]) == (0, 0, 1) and tuple(c[-1]) == (2, 0, 3)
    assert not out[1].has_z and not shapely.has_m(out[1]) and out[1].is_valid
    assert shapely.get_num_coordinates(out[1]) > 5


def test_geometry_errors_carry_their_fields_and_options_are_keywords():
    import pickle

    bad = shapely.Polygon([(0, 0), (1, 0), (1, np.nan), (0, 1)])
    with pytest.raises(bzspline.errors.GeometryError) as e:
        bzspline.geo.smooth(np.array([*cells(), bad], dtype=object))
    assert isinstance(e.value, ValueError)
    assert (e.value.index, e.value.coordinate) == (2, 2), vars(e.value)
    back = pickle.loads(pickle.dumps(e.value))
    assert (type(back), str(back), back.index) == (type(e.value), str(e.value), 2)
    # An option out of range is no geometry's fault: a plain ValueError.
    with pytest.raises(ValueError) as e:
        bzspline.geo.smooth(np.array(cells(), dtype=object), snap=-1.0)
    assert not isinstance(e.value, bzspline.errors.GeometryError)
    # Options are keyword-only, as shapely 2's.
    with pytest.raises(TypeError):
        bzspline.geo.smooth(cells()[0], 1e-3)
