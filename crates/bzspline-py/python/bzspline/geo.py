"""Smoothing lines and polygons of shapely and geopandas with the method.

``smooth`` takes a shapely geometry, a numpy array of them or a geopandas
GeoSeries and returns the same kind (a GeoSeries keeps its index and CRS).
With ``coverage=True`` (the default) the whole array is one coverage: every
border two polygons (or a polygon and a line) share is smoothed once, the same
way for both, and valid polygons stay valid, as ``bzspline smooth`` does;
``coverage=False`` smooths each geometry on its own. Coordinates go to the
Rust library through shapely's ragged arrays (``shapely.to_ragged_array``),
not one Python call per vertex.

A coverage too large for one process is smoothed over the partitions of a
dask-geopandas GeoSeries: ``smooth(series)`` finds, in one cheap pass, the
junctions a partition cannot see by itself (``nodes``), smooths every
partition with them and with the geometries of other partitions that come near
it, and runs the rounds of the conflict search (where curves that would cross
are refined) over all partitions together, merging the refinement levels
between rounds. The result is, bit for bit, what one process smoothing the
whole gives: every border the same in every partition that holds it, nothing
crossing.
"""

from typing import Optional, Union

import numpy as np

from . import _core
from ._arrays import Nodes, _groups, _is_dask, _like, _smooth_array, _values

__all__ = ["Nodes", "nodes", "smooth", "tolerance"]

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
        then cut as one process smoothing the whole would cut it, and its
        default tolerance is the whole's. (``smooth`` of a dask series does
        this, and more, itself.)

    Examples
    --------
    >>> parts = np.array_split(cells, 4)                     # doctest: +SKIP
    >>> n = bzspline.geo.nodes(cells)                        # doctest: +SKIP
    >>> [bzspline.geo.smooth(p, nodes=n) for p in parts]     # doctest: +SKIP
    """
    if _is_dask(obj):
        from . import _dask

        return _dask.nodes(obj)
    groups, _ = _groups(_values(obj))
    if not groups:
        return Nodes(np.zeros((0, 2)))
    positions, extent = _core._nodes_of(groups)
    return Nodes(positions, extent)


def smooth(obj, *, tolerance: Union[float, str, None] = None, coverage: bool = True, through: bool = False,
           keep_angle: Optional[float] = None, alpha: float = 0.5, nodes: Optional[Nodes] = None,
           snap: Union[float, str, None] = None, crs=None):
    """Smooth lines and polygon rings with the method, keeping coverages valid.

    Parameters
    ----------
    obj : shapely.Geometry, array of shapely geometries, geopandas.GeoSeries or dask_geopandas.GeoSeries
        Points and empty or missing geometries pass through unchanged. A dask
        series is smoothed as one coverage over its partitions (see the module
        docs); sort it spatially (``spatial_shuffle``) so that partitions are
        compact, since each one also reads the geometries of the others that
        meet its extent.
    tolerance : float or str, optional
        Largest distance between the smooth curve and the output polyline: a
        number in coordinate units, or a distance with a unit, ``"50m"``,
        ``"2km"`` or ``"0.001deg"``, measured in the coordinate system
        (``crs``, or the GeoSeries' own). On longitude and latitude, metres
        smooth on the WGS 84 ellipsoid, as ``bzspline smooth --tolerance 50m``
        does: the same ground distance at every latitude and across the
        antimeridian; on projected data they become the system's units. By
        default 1e-4 of the diagonal of the data's bounding box.
    coverage : bool, default True
        Smooth the whole array as one coverage (shared borders once), or each
        geometry on its own as a coverage of its own, with its own default
        tolerance (``bzspline smooth --independent``).
    through : bool, default False
        Pass through every vertex (the interpolating variant) instead of
        cutting the corners.
    keep_angle : float, optional
        Vertices where a line turns by more than this many degrees stay. The
        turning angle is taken in the plane (x, y), for geometries with z too.
    alpha : float, default 0.5
        The shape parameter, in [1/3, 2/3].
    nodes : Nodes, optional
        With ``obj`` one part of a larger coverage split by hand: the whole's
        junctions and extent, from :func:`nodes`. Every arc of the part is then
        cut as smoothing the whole in one process would cut it. It is smoothed
        the same where the part also holds the geometries of other parts that
        meet its extent (a ring across a border decides how many positions the
        border keeps) and no refinement (a smoothed arc coming too close to
        another) is needed: that is decided within the part, and a border
        between parts can then differ. A dask series takes care of all this
        itself.
    snap : float or str, optional
        Merge positions closer than this distance first (each to the first met
        within it), so that borders digitised twice with small differences
        become one. Within ``obj`` only: snap a whole coverage before
        splitting it into parts. A number or a distance with a unit, as
        ``tolerance`` (on longitude and latitude ``"0.5m"`` is half a metre
        on the ground, east-west as north-south).
    crs : pyproj.CRS or str, optional
        The coordinate system, for distances with a unit: a ``pyproj.CRS``,
        ``"EPSG:4326"``, ``"OGC:CRS84"`` or WKT. By default a GeoSeries'
        ``crs``; arrays of shapely geometries have none.

    Returns
    -------
    The same kind as ``obj``. Geometries whose coordinates have z are
    smoothed ring by ring, each line and ring a curve in space (x, y, z), as
    ``bzspline smooth`` does, with a warning: the coverage's topology is
    planar, so their borders are not shared. For a dask series, a dask-geopandas GeoSeries
    with the same partitions (the smoothing is done, the result persisted on
    the workers).

    Raises
    ------
    bzspline.errors.GeometryError
        A ``ValueError`` for a geometry that cannot be smoothed (coordinates
        that are not finite), with the geometry's ``index`` (and ``member``,
        ``ring``, ``coordinate`` where they apply; ``partition`` and ``label``
        for a dask series).
    ValueError
        For an option out of range, or a distance with a unit on data whose
        coordinate system is unknown or cannot measure it.
    TypeError
        For ``nodes`` that is not a :class:`Nodes`.
    """
    import shapely

    given = tolerance
    if isinstance(tolerance, str) or isinstance(snap, str):
        crs = _crs_text(crs if crs is not None else getattr(obj, "crs", None))
    else:
        crs = _crs_text(crs)
    tolerance, snap, geographic = _core._distances(tolerance, snap, crs)
    args = (tolerance, coverage, through, keep_angle, alpha, nodes, snap)
    if _is_dask(obj):
        if nodes is not None or snap is not None:
            raise ValueError("a dask series finds its own nodes; snap the coverage before partitioning it")
        if not coverage:
            return obj.map_partitions(smooth, tolerance=given, coverage=False, through=through,
                                      keep_angle=keep_angle, alpha=alpha, crs=crs, meta=obj._meta)
        from . import _dask

        return _dask.smooth(obj, tolerance, through, keep_angle, alpha, geographic)
    if isinstance(obj, shapely.Geometry):
        return _smooth_array(np.array([obj], dtype=object), *args, geographic=geographic)[0][0]
    try:
        import geopandas
    except ImportError:
        geopandas = None
    if geopandas is not None and isinstance(obj, geopandas.GeoSeries):
        values, _ = _smooth_array(np.asarray(obj.values, dtype=object), *args, geographic=geographic)
        return _like(obj, values)
    arr = np.asarray(obj, dtype=object)
    return _smooth_array(arr.ravel(), *args, geographic=geographic)[0].reshape(arr.shape)


def tolerance(value: Union[float, str, None] = None, *, crs=None, bounds=None) -> float:
    """A tolerance in the data's units, read as :func:`smooth` reads one.

    A number is in the data's units already; a distance with a unit
    (``"50m"``, ``"0.5km"``, ``"0.001deg"``) is converted to the units of
    ``crs`` (a ``pyproj.CRS`` or text such as ``"EPSG:3857"``); ``None`` gives
    :func:`smooth`'s default for data within ``bounds``
    (``(xmin, ymin, xmax, ymax)``). For example for ``Curve.flatten``.

    Raises
    ------
    ValueError
        For a distance that cannot be read or converted, a distance in metres
        on longitude and latitude (:func:`smooth` measures those on the
        ellipsoid; project the data first), or ``None`` without ``bounds``.
    """
    if value is None:
        if bounds is None:
            raise ValueError("a default tolerance needs the data's bounds (xmin, ymin, xmax, ymax)")
        xmin, ymin, xmax, ymax = (float(b) for b in bounds)
        return _core._default_tolerance(xmin, ymin, xmax, ymax)
    t, _, geographic = _core._distances(value, None, _crs_text(crs))
    if geographic:
        raise ValueError(f"the tolerance {value!r} is a distance on the ellipsoid, not in degrees: "
                         "project the data first, or give degrees")
    return t


def _crs_text(crs):
    """A coordinate system as the library reads it: a ``pyproj.CRS`` (or
    anything with ``to_wkt``) as its WKT, text as it is, ``None`` as none."""
    if crs is None:
        return None
    if hasattr(crs, "to_wkt"):
        return crs.to_wkt()
    if isinstance(crs, str):
        return crs
    raise TypeError(f"crs must be a pyproj.CRS or a string such as 'EPSG:4326', not {type(crs).__name__}")
