"""Geometry arrays as the library takes them, shared by :mod:`bzspline.geo`
and its dask adapter: shapely's ragged arrays to and from the library, one
array smoothed (a coverage, or in space for geometries with z), and the
:class:`Nodes` of a whole coverage."""

import warnings

import numpy as np

from . import _core

_LINES = (1, 5)  # LineString, MultiLineString
_POLYGONS = (3, 6)  # Polygon, MultiPolygon


class Nodes:
    """Junctions of a whole coverage, and its extent, for smoothing its parts.

    Made by :func:`nodes`; passed to :func:`smooth` as ``nodes=``. Immutable
    and picklable (dask ships it to every worker).

    Parameters
    ----------
    positions : array_like, shape (n, 2)
        The junctions: positions where the whole coverage cuts its lines and
        rings but a part might not.
    extent : tuple of 4 floats, optional
        ``(xmin, ymin, xmax, ymax)`` of the whole coverage; the default
        tolerance of :func:`smooth` is a fraction of its diagonal.
    """

    __slots__ = ("_positions", "_extent")

    def __init__(self, positions, extent=None):
        p = np.array(positions, dtype=np.float64).reshape(-1, 2)
        p.setflags(write=False)
        object.__setattr__(self, "_positions", p)
        e = None if extent is None else tuple(float(v) for v in extent)
        if e is not None and len(e) != 4:
            raise ValueError(f"extent must be (xmin, ymin, xmax, ymax), not {extent!r}")
        object.__setattr__(self, "_extent", e)

    def __setattr__(self, name, value):
        raise AttributeError("Nodes is immutable")

    @property
    def positions(self):
        """numpy.ndarray, shape (n, 2): the junctions, ordered by x then y."""
        return self._positions

    @property
    def extent(self):
        """tuple or None: ``(xmin, ymin, xmax, ymax)`` of the whole coverage."""
        return self._extent

    def __len__(self):
        return len(self._positions)

    def __repr__(self):
        return f"Nodes({len(self)} positions, extent={self._extent})"

    def __reduce__(self):
        return (Nodes, (self._positions, self._extent))


def _groups(arr):
    """The lines and the polygons of a 1-D object array as ragged arrays
    ``(kind, coords, offsets, indices)``, and the masks that pick them."""
    import shapely

    todo = ~(shapely.is_missing(arr) | shapely.is_empty(arr))
    idx = np.flatnonzero(todo)
    types = shapely.get_type_id(arr[idx])
    groups, picks = [], []
    # shapely keeps one geometry family per ragged array: lines and polygons
    # go as two, smoothed together as one coverage.
    for family in (_LINES, _POLYGONS):
        mask = np.isin(types, family)
        if not mask.any():
            continue
        kind, coords, offsets = _ragged(arr[idx[mask]], include_z=False)
        groups.append((
            int(kind),
            np.ascontiguousarray(coords, dtype=np.float64),
            [np.asarray(o, dtype=np.int64) for o in offsets],
            idx[mask].astype(np.int64),
        ))
        picks.append(idx[mask])
    return groups, picks


def _ragged(geoms, include_z):
    """``shapely.to_ragged_array`` of x, y (and z): a measure (M) is dropped,
    as ``bzspline smooth`` keeps x, y, z of longer positions."""
    import shapely

    try:
        return shapely.to_ragged_array(geoms, include_z=include_z, include_m=False)
    except TypeError:  # shapely before 2.1 has no M
        return shapely.to_ragged_array(geoms, include_z=include_z)


def _warn_measures(arr):
    """Warns once when some geometry of ``arr`` carries M (shapely >= 2.1 on
    GEOS >= 3.12; with an older GEOS no geometry has M)."""
    import shapely

    if not hasattr(shapely, "has_m") or shapely.geos_version < (3, 12, 0):
        return
    idx = np.flatnonzero(_smoothable(arr))
    n = int(shapely.has_m(arr[idx]).sum())
    if n:
        warnings.warn(f"{n} geometries with M: the measure is dropped, x, y (and z) are kept", stacklevel=4)


_NO_LEVELS = (np.zeros(0, np.uint64), np.zeros(1, np.int64), np.zeros(0, np.uint8))


def _smooth_array(arr, tolerance, coverage, through, keep_angle, alpha, nodes, snap, levels=None, round=None,
                  exact=None, geographic=False):
    """Smooths a 1-D object array; returns it and the refinement levels the
    arcs ended at (keys, offsets, values). With ``round``, only that round of
    the conflict search, from ``levels``, judging conflicts only among the
    first ``exact`` geometries. With ``geographic``, coordinates are
    longitude and latitude and ``tolerance`` is in metres."""
    import shapely

    if nodes is not None and not isinstance(nodes, Nodes):
        raise TypeError(f"nodes must be bzspline.geo.Nodes (from bzspline.geo.nodes), not {type(nodes).__name__}")
    out = arr.copy()
    _warn_measures(arr)
    spatial = _with_z(arr)
    if len(spatial):
        warnings.warn(f"{len(spatial)} geometries with z are smoothed ring by ring, in space: their borders "
                      "are not shared with their neighbours' (the coverage's topology is planar)", stacklevel=3)
        if tolerance is None:
            tolerance = _default_tolerance(arr)
        out[spatial] = _smooth_in_space(arr[spatial], spatial, tolerance, through, keep_angle, alpha, geographic)
        arr = arr.copy()
        arr[spatial] = None
    groups, picks = _groups(arr)
    if not groups:
        return out, _NO_LEVELS
    results, ended = _core._smooth_ragged(
        groups,
        tolerance=tolerance,
        coverage=coverage,
        through=through,
        keep_angle=keep_angle,
        alpha=alpha,
        nodes=None if nodes is None else np.ascontiguousarray(nodes.positions),
        extent=None if nodes is None else nodes.extent,
        snap=snap,
        levels=_aligned(levels),
        round=round,
        exact=exact,
        geographic=geographic,
    )
    for (kind, _, _, _), pick, (c, o) in zip(groups, picks, results):
        out[pick] = _singles(arr[pick], shapely.from_ragged_array(kind, c, tuple(o)), kind)
    return out, ended


def _aligned(arrays):
    """The arrays (refinement levels, say) at addresses their items may be
    read from: an array unpickled from a message buffer (dask's protocol 5
    frames) may start anywhere, and the library reads them in place."""
    if arrays is None:
        return None
    return tuple(np.require(a, requirements="A") for a in arrays)


def _singles(given, back, kind):
    """``back`` with single geometries single again where the ragged array
    of a mixed family made them multi."""
    import shapely

    single = shapely.get_type_id(given) == (3 if kind in _POLYGONS else 1)
    if single.any() and kind in (5, 6):
        parts = shapely.get_parts(back[single])
        if len(parts) == single.sum():
            back[single] = parts
    return back


def _with_z(arr):
    """Positions in ``arr`` of the lines and polygons whose coordinates have z."""
    import shapely

    idx = np.flatnonzero(_smoothable(arr))
    return idx[shapely.has_z(arr[idx])]


def _default_tolerance(arr):
    """The library's default tolerance for the lines' and polygons' bounding
    box (1e-4 of its diagonal)."""
    import shapely

    x0, y0, x1, y1 = shapely.total_bounds(arr[_smoothable(arr)])
    return _core._default_tolerance(float(x0), float(y0), float(x1), float(y1))


def _smooth_in_space(geoms, index, tolerance, through, keep_angle, alpha, geographic):
    """Lines and polygons with z, every line and ring smoothed on its own as a
    curve in space (x, y, z), as ``bzspline smooth`` does."""
    import shapely

    out = geoms.copy()
    types = shapely.get_type_id(geoms)
    for family, closed in ((_LINES, False), (_POLYGONS, True)):
        sel = np.isin(types, family)
        if not sel.any():
            continue
        kind, coords, offsets = _ragged(geoms[sel], include_z=True)
        # The geometry each line or ring belongs to.
        owner = np.asarray(index, dtype=np.int64)[sel]
        for level in reversed(offsets[1:]):
            owner = np.repeat(owner, np.diff(level))
        c, spans = _core._smooth_spans(np.ascontiguousarray(coords, dtype=np.float64),
                                       np.asarray(offsets[0], dtype=np.int64), owner, closed,
                                       tolerance, through=through, keep_angle=keep_angle, alpha=alpha,
                                       geographic=geographic)
        back = shapely.from_ragged_array(kind, c, (spans, *offsets[1:]))
        out[sel] = _singles(geoms[sel], back, int(kind))
    return out


def _values(obj):
    """The geometries of ``obj`` as a 1-D object array."""
    import shapely

    if isinstance(obj, shapely.Geometry):
        return np.array([obj], dtype=object)
    return np.asarray(getattr(obj, "values", obj), dtype=object).ravel()


def _smoothable(arr):
    """Which geometries of ``arr`` are lines or polygons, not missing or empty."""
    import shapely

    ok = ~(shapely.is_missing(arr) | shapely.is_empty(arr))
    ok[ok] = np.isin(shapely.get_type_id(arr[ok]), _LINES + _POLYGONS)
    return ok


def _is_dask(obj):
    return hasattr(obj, "to_delayed") and hasattr(obj, "npartitions")


def _like(obj, values):
    """``values`` in the kind of ``obj`` (a GeoSeries keeps index, CRS, name)."""
    import geopandas

    return geopandas.GeoSeries(values, index=obj.index, crs=obj.crs, name=obj.name)
