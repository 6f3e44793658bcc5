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
