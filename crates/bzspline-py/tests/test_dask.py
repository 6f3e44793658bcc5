"""bzspline.geo.smooth on a dask LocalCluster of two worker processes: the
functions and objects travel to other processes (pickling), and every feature
comes back as one process smooths it."""

import numpy as np
import pytest

dask_geopandas = pytest.importorskip("dask_geopandas")
distributed = pytest.importorskip("distributed")
geopandas = pytest.importorskip("geopandas")
shapely = pytest.importorskip("shapely")

import bzspline  # noqa: E402


def wiggly_lines(n, seed=0):
    rng = np.random.default_rng(seed)
    lines = []
    for i in range(n):
        x = np.linspace(0, 10, 30)
        y = np.sin(x + i) + rng.normal(scale=0.1, size=x.size) + 3 * i
        lines.append(shapely.LineString(np.column_stack([x, y])))
    return geopandas.GeoSeries(lines, crs="EPSG:3857")


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as c:
            yield c


def test_partitions_smooth_each_feature_as_one_process_does(client):
    s = wiggly_lines(40)
    want = bzspline.geo.smooth(s, tolerance=1e-3, coverage=False)
    d = dask_geopandas.from_geopandas(geopandas.GeoDataFrame(geometry=s), npartitions=4)
    got = d.geometry.map_partitions(
        bzspline.geo.smooth, tolerance=1e-3, coverage=False, meta=d.geometry._meta
    ).compute()
    assert list(got.index) == list(want.index)
    assert all(a.equals_exact(b, 0.0) for a, b in zip(got, want))


def test_splines_travel_to_workers(client):
    x = np.arange(1.0, 12.0)
    s = bzspline.Spline(x, [1, 3, 3, 1, 2, 7, 1.5, 1, 10, 2, 1.5])
    q = np.linspace(1, 11, 1001)
    futures = [client.submit(lambda s, q, nu: s(q, nu), s, q, nu) for nu in range(3)]
    for nu, f in enumerate(futures):
        assert np.array_equal(f.result(), s(q, nu))


def test_a_coverage_over_partitions_smooths_as_one_process(client):
    from test_geo import grid

    cells = grid(8, 6, seed=5)
    # Partitions in an order that splits neighbours apart.
    order = np.random.default_rng(1).permutation(len(cells))
    s = geopandas.GeoSeries(cells[order], crs="EPSG:3857")
    want = bzspline.geo.smooth(s)
    d = dask_geopandas.from_geopandas(geopandas.GeoDataFrame(geometry=s), npartitions=4)
    got = bzspline.geo.smooth(d.geometry)
    assert isinstance(got, dask_geopandas.GeoSeries)
    got = got.compute()
    assert list(got.index) == list(want.index) and got.crs == want.crs
    assert all(a.equals_exact(b, 0.0) for a, b in zip(got, want))
    # The nodes alone, passed to map_partitions, give the same here (nothing
    # needed refinement); the reduction finds junctions of the whole.
    nodes = bzspline.geo.nodes(d.geometry)
    assert {tuple(p) for p in nodes.positions} <= {tuple(p) for p in bzspline.geo.nodes(s).positions}
    mapped = d.geometry.map_partitions(bzspline.geo.smooth, nodes=nodes, meta=d.geometry._meta).compute()
    assert all(a.equals_exact(b, 0.0) for a, b in zip(mapped, want))
    # Without the nodes, borders across partitions differ.
    naive = d.geometry.map_partitions(bzspline.geo.smooth, meta=d.geometry._meta).compute()
    assert not all(a.equals_exact(b, 0.0) for a, b in zip(naive, want))


def test_partitions_that_refine_smooth_as_one_process(client):
    # An L-shaped polygon, a road along its notch and a square in the notch,
    # one a partition: the shared corner must be refined in both the
    # polygon's and the road's partition, though only the square's shows why.
    l_shape = shapely.Polygon([(0, 0), (4, 0), (4, 1), (2.5, 1), (1, 1), (1, 2.5), (1, 4), (0, 4)])
    road = shapely.LineString([(2.5, 1), (1, 1), (1, 2.5)])
    square = shapely.box(1.05, 1.05, 1.6, 1.6)
    s = geopandas.GeoSeries([l_shape, road, square])
    d = dask_geopandas.from_geopandas(geopandas.GeoDataFrame(geometry=s), npartitions=3)
    assert d.npartitions == 3
    got = bzspline.geo.smooth(d.geometry, tolerance=1e-3).compute()
    want = bzspline.geo.smooth(s, tolerance=1e-3)
    assert all(a.equals_exact(b, 0.0) for a, b in zip(got, want))
    assert shapely.is_valid(got.values).all()
    assert not got[0].intersects(got[2]) and not got[1].intersects(got[2])
    ring = set(map(tuple, shapely.get_coordinates(got[0])))
    assert all(tuple(p) in ring for p in shapely.get_coordinates(got[1])), "the road left the border"
    # Alone, each partition crosses the square.
    alone = d.geometry.map_partitions(bzspline.geo.smooth, tolerance=1e-3, nodes=bzspline.geo.nodes(d.geometry),
                                      meta=d.geometry._meta).compute()
    assert alone[0].intersects(alone[2])


def notch(x, gap, size):
    """An L-shaped polygon with its inner corner at (x, 0), a road along
    its notch and a square in the notch, ``gap`` from the corner."""
    l_shape = shapely.Polygon([(x - 1, -1), (x + 3, -1), (x + 3, 0), (x + 1.5, 0), (x, 0), (x, 1.5), (x, 3),
                               (x - 1, 3)])
    road = shapely.LineString([(x + 1.5, 0), (x, 0), (x, 1.5)])
    return [l_shape, road, shapely.box(x + gap, gap, x + gap + size, gap + size)]


def test_refinement_over_many_rounds_is_the_one_process_result(client):
    # Notches whose squares sit ever closer to the corner need more rounds of
    # refinement; cut into four partitions, each feature comes out as one
    # process smoothing all gives it.
    gs = [g for i, gap in enumerate([0.2, 0.05, 0.02, 0.01, 0.006, 0.004]) for g in notch(6.0 * i, gap, 0.3)]
    s = geopandas.GeoSeries(gs)
    want = bzspline.geo.smooth(s, tolerance=1e-2)
    for k in (2, 4):
        d = dask_geopandas.from_geopandas(geopandas.GeoDataFrame(geometry=s), npartitions=k)
        got = bzspline.geo.smooth(d.geometry, tolerance=1e-2).compute()
        assert all(a.equals_exact(b, 0.0) for a, b in zip(got, want)), k
    assert shapely.is_valid(want.values).all()


@pytest.mark.filterwarnings("ignore:invalid value:RuntimeWarning")
def test_a_bad_geometry_is_named_by_partition_and_index(client):
    from test_geo import grid

    cells = list(grid(3, 2))
    cells[4] = shapely.Polygon([(0, 0), (1, np.nan), (1, 1)])
    s = geopandas.GeoSeries(cells, index=[f"cell{i}" for i in range(len(cells))])
    d = dask_geopandas.from_geopandas(geopandas.GeoDataFrame(geometry=s), npartitions=2)
    with pytest.raises(ValueError, match="index 'cell4', coordinate 1"):
        bzspline.geo.smooth(d.geometry).compute()
