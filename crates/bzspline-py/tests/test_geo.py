"""bzspline.geo.smooth on shapely coverages: shared borders stay shared,
valid polygons stay valid, the kind of input comes back."""

import numpy as np
import pytest

shapely = pytest.importorskip("shapely")

import bzspline  # noqa: E402


def grid(n, m, wiggle=0.2, seed=0):
    """A mosaic of n x m cells whose shared vertices are jittered once, so
    that neighbours share their borders exactly."""
    rng = np.random.default_rng(seed)
    k = 4  # vertices per cell side
    xs = np.linspace(0, n, n * k + 1)
    ys = np.linspace(0, m, m * k + 1)
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    inner = (slice(1, -1), slice(1, -1))
    gx[inner] += rng.uniform(-wiggle, wiggle, gx[inner].shape) / k
    gy[inner] += rng.uniform(-wiggle, wiggle, gy[inner].shape) / k
    cells = []
    for i in range(n):
        for j in range(m):
            a, b = i * k, j * k
            ring = (
                [(gx[a + t, b], gy[a + t, b]) for t in range(k)]
                + [(gx[a + k, b + t], gy[a + k, b + t]) for t in range(k)]
                + [(gx[a + k - t, b + k], gy[a + k - t, b + k]) for t in range(k)]
                + [(gx[a, b + k - t], gy[a, b + k - t]) for t in range(k)]
            )
            cells.append(shapely.Polygon(ring))
    return np.array(cells, dtype=object)


def test_coverage_keeps_borders_shared_and_polygons_valid():
    cells = grid(4, 3)
    assert shapely.is_valid(cells).all()
    out = bzspline.geo.smooth(cells, tolerance=1e-3)
    assert out.shape == cells.shape
    assert shapely.is_valid(out).all()
    assert all(shapely.get_type_id(g) == 3 for g in out)
    # Smoothing changed the rings.
    assert any(len(shapely.get_coordinates(a)) != len(shapely.get_coordinates(b)) for a, b in zip(out, cells))
    # Neighbours: no overlap, and still a common border.
    for i in range(len(out)):
        for j in range(i + 1, len(out)):
            if cells[i].touches(cells[j]) and cells[i].intersection(cells[j]).length > 0:
                assert out[i].intersection(out[j]).area < 1e-12
                assert out[i].intersection(out[j]).length > 0
    # The union keeps its area (no gaps between the cells).
    assert np.isclose(shapely.union_all(out).area, sum(g.area for g in out), rtol=1e-9)


def test_kinds_come_back():
    line = shapely.LineString([(0, 0), (1, 2), (3, 2), (4, 0)])
    out = bzspline.geo.smooth(line, tolerance=0.01)
    assert isinstance(out, shapely.LineString)
    c = shapely.get_coordinates(out)
    assert tuple(c[0]) == (0.0, 0.0) and tuple(c[-1]) == (4.0, 0.0)
    mixed = np.array([shapely.Point(1, 1), None, line, shapely.MultiLineString([[(0, 0), (1, 1), (2, 0)]])], dtype=object)
    out = bzspline.geo.smooth(mixed, tolerance=0.01)
    assert out[0].equals(mixed[0]) and out[1] is None
    assert shapely.get_type_id(out[2]) == 1 and shapely.get_type_id(out[3]) == 5
    geopandas = pytest.importorskip("geopandas")
    s = geopandas.GeoSeries(grid(2, 2), index=[10, 11, 12, 13], crs="EPSG:3857")
    out = bzspline.geo.smooth(s, tolerance=1e-3)
    assert isinstance(out, geopandas.GeoSeries) and list(out.index) == [10, 11, 12, 13]
    assert out.crs == s.crs


def test_bad_options_raise_value_error():
    line = shapely.LineString([(0, 0), (1, 2), (3, 2), (4, 0)])
    with pytest.raises(ValueError):
        bzspline.geo.smooth(line, tolerance=-1.0)
    with pytest.raises(ValueError):
        bzspline.geo.smooth(line, alpha=0.9)


def test_a_road_along_a_border_is_smoothed_with_it():
    cells = grid(2, 1, seed=3)
    # The road runs along the border the two cells share, then away.
    ring1 = set(map(tuple, shapely.get_coordinates(cells[1])))
    shared = [p for p in map(tuple, shapely.get_coordinates(cells[0])) if p in ring1]
    road = shapely.LineString(shared + [(1.5, -1.0)])
    assert len(shared) >= 3
    out = bzspline.geo.smooth(np.array([*cells, road], dtype=object), tolerance=1e-3)
    # Where the road follows the border, both cells and the road have the
    # same smoothed positions.
    on_road = set(map(tuple, shapely.get_coordinates(out[2])))
    common = on_road & set(map(tuple, shapely.get_coordinates(out[0]))) & set(map(tuple, shapely.get_coordinates(out[1])))
    assert len(common) > len(shared), "the shared stretch was not smoothed once for all three"
    assert shapely.is_valid(out[:2]).all()


def test_parts_smoothed_with_the_whole_nodes_are_the_whole():
    cells = grid(5, 4, seed=1)
    want = bzspline.geo.smooth(cells)
    n = bzspline.geo.nodes(cells)
    assert len(n) > 0 and n.extent == tuple(shapely.total_bounds(cells))
    order = np.random.default_rng(0).permutation(len(cells))
    got = np.empty_like(cells)
    for chunk in np.array_split(order, 4):
        got[chunk] = bzspline.geo.smooth(cells[chunk], nodes=n)
    assert all(a.equals_exact(b, 0.0) for a, b in zip(got, want))
    # Without the whole's nodes the parts part ways along their borders.
    alone = np.empty_like(cells)
    for chunk in np.array_split(order, 4):
        alone[chunk] = bzspline.geo.smooth(cells[chunk])
    assert not all(a.equals_exact(b, 0.0) for a, b in zip(alone, want))


def test_nodes_are_immutable_and_pickle():
    import pickle

    n = bzspline.geo.nodes(grid(2, 2))
    m = pickle.loads(pickle.dumps(n))
    assert np.array_equal(m.positions, n.positions) and m.extent == n.extent
    with pytest.raises(AttributeError):
        n.extent = None
    with pytest.raises(ValueError):
        n.positions[0, 0] = 1.0
    with pytest.raises(TypeError):
        bzspline.geo.smooth(grid(1, 1), nodes=n.positions)


@pytest.mark.filterwarnings("ignore:invalid value:RuntimeWarning")
def test_bad_coordinates_name_the_geometry():
    cells = list(grid(2, 1))
    line = shapely.LineString([(0, 0), (1, np.nan), (2, 0)])
    with pytest.raises(ValueError, match="geometry 3, coordinate 1"):
        bzspline.geo.smooth(np.array([cells[0], None, cells[1], line], dtype=object))


def test_snap_joins_borders_digitised_twice():
    left = shapely.Polygon([(0, 0), (1, 0), (1.2, 0.5), (1, 1), (0, 1)])
    # The neighbour's copy of the border is off by a nanometre.
    e = 1e-9
    right = shapely.Polygon([(1 + e, 0), (2, 0), (2, 1), (1 - e, 1), (1.2 + e, 0.5)])
    cells = np.array([left, right], dtype=object)
    apart = bzspline.geo.smooth(cells, tolerance=1e-3)
    joined = bzspline.geo.smooth(cells, tolerance=1e-3, snap=1e-6)
    shared = lambda a, b: set(map(tuple, shapely.get_coordinates(a))) & set(map(tuple, shapely.get_coordinates(b)))
    assert len(shared(*apart)) == 0
    assert len(shared(*joined)) > 3
    assert joined[0].intersection(joined[1]).area < 1e-12


def test_geometries_with_z_are_smoothed_in_space():
    line = shapely.LineString([(0, 0, 10), (1, 2, 14), (3, 2, 11), (4, 0, 13)])
    ring = shapely.Polygon([(0, 0, 1), (2, 0, 2), (2, 1, 3), (0, 1, 4)])
    cells = grid(2, 1)
    mixed = np.array([line, ring, *cells], dtype=object)
    with pytest.warns(UserWarning, match="with z"):
        out = bzspline.geo.smooth(mixed, tolerance=1e-3)
    assert shapely.has_z(out[:2]).all() and not shapely.has_z(out[2:]).any()
    c = shapely.get_coordinates(out[0], include_z=True)
    assert tuple(c[0]) == (0, 0, 10) and tuple(c[-1]) == (4, 0, 13) and len(c) > 4
    # In the hull of the control points, z included.
    assert ((c[:, 2] >= 10) & (c[:, 2] <= 14)).all()
    r = shapely.get_coordinates(out[1].exterior, include_z=True)
    assert tuple(r[0]) == tuple(r[-1]) and ((r[:, 2] >= 1) & (r[:, 2] <= 4)).all()
    assert shapely.get_type_id(out[1]) == 3
    # The planar cells are still one coverage.
    assert out[2].intersection(out[3]).length > 0 and out[2].intersection(out[3]).area < 1e-12
    # keep_angle applies in space as in the plane: the ring's right-angled
    # corners stay, and a keep-angle out of range is refused by the library.
    with pytest.warns(UserWarning, match="with z"):
        kept = bzspline.geo.smooth(ring, tolerance=1e-3, keep_angle=45)
    k = shapely.get_coordinates(kept.exterior, include_z=True)
    for corner in shapely.get_coordinates(ring.exterior, include_z=True):
        assert (k == corner).all(axis=1).any(), corner
    with pytest.raises(ValueError, match="keep-angle"), pytest.warns(UserWarning):
        bzspline.geo.smooth(line, keep_angle=200)



FEET = ('PROJCS["NAD83 / North Carolina (ftUS)",GEOGCS["NAD83",UNIT["degree",0.0174532925199433]],'
        'PROJECTION["Lambert_Conformal_Conic_2SP"],UNIT["US survey foot",0.304800609601219]]')


def same(a, b):
    return len(a) == len(b) and all(
        np.array_equal(shapely.get_coordinates(p), shapely.get_coordinates(q)) for p, q in zip(a, b))


def test_distances_take_units_in_the_coordinate_system():
    cells = grid(3, 2)
    # Projected in US survey feet: metres become feet; degrees are refused.
    feet = bzspline.geo.smooth(cells, tolerance="0.01m", snap="1e-4 m", crs=FEET)
    assert same(feet, bzspline.geo.smooth(cells, tolerance=0.01 / 0.304800609601219,
                                          snap=1e-4 / 0.304800609601219))
    assert same(bzspline.geo.smooth(cells, tolerance="0.00001km", crs="EPSG:3857"),
                bzspline.geo.smooth(cells, tolerance=0.01))
    with pytest.raises(ValueError, match="projected, not in degrees"):
        bzspline.geo.smooth(cells, tolerance="0.1deg", crs="EPSG:3857")
    # Degrees on longitude and latitude are the coordinates' own units.
    assert same(bzspline.geo.smooth(cells, tolerance="0.01deg", crs="OGC:CRS84"),
                bzspline.geo.smooth(cells, tolerance=0.01))
    # A bare number needs no coordinate system, and keeps to the plane.
    assert same(bzspline.geo.smooth(cells, tolerance=0.01, crs="EPSG:4326"),
                bzspline.geo.smooth(cells, tolerance=0.01))


def test_distances_that_cannot_be_measured_say_why():
    cells = grid(2, 2)
    with pytest.raises(ValueError, match=r"tolerance 50 m cannot be measured: no coordinate system.*crs="):
        bzspline.geo.smooth(cells, tolerance="50m")
    with pytest.raises(ValueError, match="snap distance 1 m cannot be measured: EPSG:2193 is not"):
        bzspline.geo.smooth(cells, snap="1m", crs="EPSG:2193")
    with pytest.raises(ValueError, match="50m, 0.5km, 0.001deg"):
        bzspline.geo.smooth(cells, tolerance="50 miles", crs="EPSG:4326")
    with pytest.raises(ValueError, match="crs: .*not a coordinate system"):
        bzspline.geo.smooth(cells, tolerance="50m", crs="WGS 84")
    with pytest.raises(TypeError, match="tolerance must be"):
        bzspline.geo.smooth(cells, tolerance=[50])
    with pytest.raises(TypeError, match="crs must be"):
        bzspline.geo.smooth(cells, tolerance="50m", crs=4326)
    # Metres on the ellipsoid still check the tolerance's range.
    with pytest.raises(ValueError, match="tolerance"):
        bzspline.geo.smooth(cells, tolerance="-5m", crs="EPSG:4326")


def test_a_geoseries_measures_in_its_own_crs():
    geopandas = pytest.importorskip("geopandas")
    cells = grid(3, 2)
    lonlat = geopandas.GeoSeries(grid(3, 2), crs="EPSG:4326")
    out = bzspline.geo.smooth(lonlat, tolerance="200m")
    assert out.crs == lonlat.crs
    assert same(out.values, bzspline.geo.smooth(cells, tolerance="200m", crs="EPSG:4326"))
    utm = geopandas.GeoSeries(grid(3, 2), crs="EPSG:32633")
    assert same(bzspline.geo.smooth(utm, tolerance="0.01m").values, bzspline.geo.smooth(cells, tolerance=0.01))


def test_tolerance_reads_a_distance_as_smooth_does():
    # Numbers are in the data's units; units convert to the CRS's own.
    assert bzspline.geo.tolerance(2.5) == 2.5
    assert bzspline.geo.tolerance("1km", crs="EPSG:3857") == pytest.approx(1000.0, rel=1e-12)
    # A projection in US survey feet, as a .prj file writes it.
    feet = ('PROJCS["NAD83 / New York Long Island (ftUS)",GEOGCS["NAD83",DATUM["North_American_Datum_1983",'
            'SPHEROID["GRS 1980",6378137,298.257222101]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],'
            'PROJECTION["Lambert_Conformal_Conic_2SP"],UNIT["US survey foot",0.304800609601219]]')
    assert bzspline.geo.tolerance("1m", crs=feet) == pytest.approx(1 / 0.304800609601219, rel=1e-12)
    with pytest.raises(ValueError, match="ellipsoid"):
        bzspline.geo.tolerance("50m", crs="EPSG:4326")
    with pytest.raises(ValueError, match="bounds"):
        bzspline.geo.tolerance()
    with pytest.raises(ValueError):
        bzspline.geo.tolerance("50 parsecs", crs="EPSG:3857")
    # No value: the tolerance smooth takes by itself for data of those bounds.
    ring = shapely.Polygon([(0, 0), (40, 3), (55, 30), (20, 45), (-5, 25)])
    default = bzspline.geo.tolerance(bounds=ring.bounds)
    assert shapely.equals_exact(bzspline.geo.smooth(ring), bzspline.geo.smooth(ring, tolerance=default), 0.0)
    assert not shapely.equals_exact(bzspline.geo.smooth(ring), bzspline.geo.smooth(ring, tolerance=default * 4), 0.0)
