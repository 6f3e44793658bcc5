"""Smoothing lines and polygons of shapely and geopandas with the method.

``smooth`` takes a shapely geometry, a numpy array of them or a geopandas
GeoSeries and returns the same kind (a GeoSeries keeps its index and CRS).
With ``coverage=True`` (the default) the whole array is one coverage: every
border two polygons (or a polygon and a line) share is smoothed once, the same
way for both, and valid polygons stay valid, as ``bzspline smooth`` does;
``coverage=False`` smooths each geometry on its own. Coordinates go to the
Rust library through shapely's ragged arrays (``shapely.to_ragged_array``),
not one Python call per vertex.

A coverage too large for one process is smoothed in parts (the partitions of
a dask-geopandas GeoSeries, say): ``nodes`` finds, in one cheap pass over the
parts, the junctions a part cannot see by itself, and ``smooth(part,
nodes=...)`` then cuts and smooths every arc of the part exactly as one
process smoothing the whole would.
"""

import numpy as np

from . import _core

__all__ = ["Nodes", "nodes", "smooth"]

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
        kind, coords, offsets = shapely.to_ragged_array(arr[idx[mask]], include_z=False)
        groups.append((
            int(kind),
            np.ascontiguousarray(coords, dtype=np.float64),
            [np.asarray(o, dtype=np.int64) for o in offsets],
            idx[mask].astype(np.int64),
        ))
        picks.append(idx[mask])
    return groups, picks


def _smooth_array(arr, tolerance, coverage, through, keep_angle, alpha, nodes, snap):
    import shapely

    if nodes is not None and not isinstance(nodes, Nodes):
        raise TypeError(f"nodes must be bzspline.geo.Nodes (from bzspline.geo.nodes), not {type(nodes).__name__}")
    out = arr.copy()
    groups, picks = _groups(arr)
    if not groups:
        return out
    results = _core._smooth_ragged(
        groups,
        tolerance=tolerance,
        coverage=coverage,
        through=through,
        keep_angle=keep_angle,
        alpha=alpha,
        nodes=None if nodes is None else np.ascontiguousarray(nodes.positions),
        extent=None if nodes is None else nodes.extent,
        snap=snap,
    )
    for (kind, _, _, _), pick, (c, o) in zip(groups, picks, results):
        back = shapely.from_ragged_array(kind, c, tuple(o))
        # Single geometries stay single where the ragged array made them multi.
        single_type = 3 if kind in _POLYGONS else 1
        single = shapely.get_type_id(arr[pick]) == single_type
        if single.any() and kind in (5, 6):
            parts = shapely.get_parts(back[single])
            if len(parts) == single.sum():
                back[single] = parts
        out[pick] = back
    return out


def _values(obj):
    """The geometries of ``obj`` as a 1-D object array."""
    import shapely

    if isinstance(obj, shapely.Geometry):
        return np.array([obj], dtype=object)
    return np.asarray(getattr(obj, "values", obj), dtype=object).ravel()


def _part_extent(part):
    """The bounding box of a partition's lines and polygons, or None."""
    import shapely

    arr = _values(part)
    ok = ~(shapely.is_missing(arr) | shapely.is_empty(arr))
    ok[ok] = np.isin(shapely.get_type_id(arr[ok]), _LINES + _POLYGONS)
    if not ok.any():
        return None
    return tuple(float(v) for v in shapely.total_bounds(arr[ok]))


def _part_meetings(part, boxes, i):
    """The meetings of partition ``i`` at positions that another partition's
    extent holds (only those can be met by two partitions)."""
    groups, _ = _groups(_values(part))
    if not groups:
        return np.zeros((0, 2)), np.zeros(0, np.uint64), np.zeros(0, bool)
    pos, between, junction, _ = _core._meetings(groups)
    keep = np.zeros(len(pos), dtype=bool)
    x, y = pos[:, 0], pos[:, 1]
    for j, (x0, y0, x1, y1) in enumerate(boxes):
        if j != i:
            keep |= (x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)
    return pos[keep], between[keep], junction[keep]


def nodes(obj):
    """The junctions of a whole coverage, for smoothing it in parts.

    For a dask-geopandas GeoSeries (anything with ``to_delayed`` and
    ``npartitions``) this is a reduction over the partitions, run on the
    active dask scheduler: one pass takes each partition's extent, a second
    returns, for the positions that another partition's extent holds, how the
    partition meets them; the client combines those into the positions where
    partitions meet differently. Only positions near other partitions travel,
    so spatially sorted partitions (``spatial_shuffle``) keep it small. For
    anything else (a shapely geometry, an array of them, a GeoSeries) it is
    every junction of the coverage.

    Parameters
    ----------
    obj : dask_geopandas.GeoSeries, geopandas.GeoSeries, array of shapely geometries
        The whole coverage.

    Returns
    -------
    Nodes
        To pass as ``nodes=`` to :func:`smooth` for every part: each part is
        then cut and smoothed as one process smoothing the whole would, and
        its default tolerance is the whole's.

    Examples
    --------
    >>> import dask_geopandas, bzspline                      # doctest: +SKIP
    >>> d = dask_geopandas.from_geopandas(gdf, npartitions=8)  # doctest: +SKIP
    >>> n = bzspline.geo.nodes(d.geometry)                     # doctest: +SKIP
    >>> d.geometry.map_partitions(bzspline.geo.smooth, nodes=n).compute()  # doctest: +SKIP
    """
    if hasattr(obj, "to_delayed") and hasattr(obj, "npartitions"):
        import dask

        parts = obj.to_delayed()
        extents = dask.compute(*[dask.delayed(_part_extent)(p) for p in parts])
        boxes = np.array([e if e is not None else (np.nan,) * 4 for e in extents], dtype=np.float64)
        met = dask.compute(*[dask.delayed(_part_meetings)(p, boxes, i) for i, p in enumerate(parts)])
        pos = np.concatenate([m[0] for m in met]) if met else np.zeros((0, 2))
        between = np.concatenate([m[1] for m in met]) if met else np.zeros(0, np.uint64)
        junction = np.concatenate([m[2] for m in met]) if met else np.zeros(0, bool)
        positions = _core._across(np.ascontiguousarray(pos, dtype=np.float64), between.astype(np.uint64), junction.astype(bool))
        known = [e for e in extents if e is not None]
        extent = None
        if known:
            k = np.array(known)
            extent = (k[:, 0].min(), k[:, 1].min(), k[:, 2].max(), k[:, 3].max())
        return Nodes(positions, extent)
    groups, _ = _groups(_values(obj))
    if not groups:
        return Nodes(np.zeros((0, 2)))
    positions, extent = _core._nodes_of(groups)
    return Nodes(positions, extent)


def smooth(obj, tolerance=None, coverage=True, through=False, keep_angle=None, alpha=0.5, nodes=None,
           snap=None):
    """Smooth lines and polygon rings with the method, keeping coverages valid.

    Parameters
    ----------
    obj : shapely.Geometry, array of shapely geometries, or geopandas.GeoSeries
        Points and empty or missing geometries pass through unchanged.
    tolerance : float, optional
        Largest distance between the smooth curve and the output polyline, in
        coordinate units; by default 1e-4 of the diagonal of the data's
        bounding box.
    coverage : bool, default True
        Smooth the whole array as one coverage (shared borders once), or each
        geometry on its own.
    through : bool, default False
        Pass through every vertex (the interpolating variant) instead of
        cutting the corners.
    keep_angle : float, optional
        Vertices where a line turns by more than this many degrees stay.
    alpha : float, default 0.5
        The shape parameter, in [1/3, 2/3].
    nodes : Nodes, optional
        With ``obj`` one part of a larger coverage: the whole's junctions and
        extent, from :func:`nodes`. Every arc of the part is then cut and
        smoothed as smoothing the whole in one process would (exactly,
        wherever that needed no refinement across parts: refinement, where a
        smoothed arc would come too close to another, is decided within the
        part).
    snap : float, optional
        Merge positions closer than this distance first (each to the first met
        within it), so that borders digitised twice with small differences
        become one. Within ``obj`` only: snap a whole coverage before
        splitting it into parts.

    Returns
    -------
    The same kind as ``obj``, in two dimensions: smoothing is planar, and
    z coordinates are dropped.

    Raises
    ------
    ValueError
        For an option out of range or coordinates that are not finite, naming
        the geometry.
    TypeError
        For ``nodes`` that is not a :class:`Nodes`.
    """
    import shapely

    args = (tolerance, coverage, through, keep_angle, alpha, nodes, snap)
    if isinstance(obj, shapely.Geometry):
        return _smooth_array(np.array([obj], dtype=object), *args)[0]
    try:
        import geopandas
    except ImportError:
        geopandas = None
    if geopandas is not None and isinstance(obj, geopandas.GeoSeries):
        values = _smooth_array(np.asarray(obj.values, dtype=object), *args)
        return geopandas.GeoSeries(values, index=obj.index, crs=obj.crs, name=obj.name)
    arr = np.asarray(obj, dtype=object)
    return _smooth_array(arr.ravel(), *args).reshape(arr.shape)
