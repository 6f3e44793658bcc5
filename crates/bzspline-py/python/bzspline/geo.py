"""Smoothing lines and polygons of shapely and geopandas with the method.

``smooth`` takes a shapely geometry, a numpy array of them or a geopandas
GeoSeries and returns the same kind (a GeoSeries keeps its index and CRS).
With ``coverage=True`` (the default) the whole array is one coverage: every
border two polygons share is smoothed once, the same way for both, and valid
polygons stay valid, as ``bzspline smooth`` does; ``coverage=False`` smooths
each geometry on its own. Coordinates go to the Rust library through shapely's
ragged arrays (``shapely.to_ragged_array``), not one Python call per vertex.
"""

import numpy as np

from . import _core

__all__ = ["smooth"]

def _smooth_array(arr, tolerance, coverage, through, keep_angle, alpha):
    import shapely

    out = arr.copy()
    todo = ~(shapely.is_missing(arr) | shapely.is_empty(arr))
    types = shapely.get_type_id(arr[todo])
    lines = np.isin(types, [1, 5])
    polys = np.isin(types, [3, 6])
    # Lines and polygons go to the library as two ragged arrays (shapely keeps
    # one geometry family per array), each smoothed as a coverage of its own.
    idx = np.flatnonzero(todo)
    for mask in (lines, polys):
        if not mask.any():
            continue
        part = arr[idx[mask]]
        kind, coords, offsets = shapely.to_ragged_array(part, include_z=False)
        offsets = [np.asarray(o, dtype=np.int64) for o in offsets]
        c, o = _core._smooth_ragged(
            int(kind),
            np.ascontiguousarray(coords, dtype=np.float64),
            offsets,
            tolerance=tolerance,
            coverage=coverage,
            through=through,
            keep_angle=keep_angle,
            alpha=alpha,
        )
        back = shapely.from_ragged_array(kind, c, tuple(o))
        if int(kind) in (3, 6):
            # Single polygons stay polygons where the ragged array made them multi.
            single = shapely.get_type_id(part) == 3
            parts = shapely.get_parts(back[single]) if single.any() else None
            if parts is not None and len(parts) == single.sum():
                back[single] = parts
        elif int(kind) == 5:
            single = shapely.get_type_id(part) == 1
            parts = shapely.get_parts(back[single]) if single.any() else None
            if parts is not None and len(parts) == single.sum():
                back[single] = parts
        out[idx[mask]] = back
    return out


def smooth(obj, tolerance=None, coverage=True, through=False, keep_angle=None, alpha=0.5):
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

    Returns
    -------
    The same kind as ``obj``.

    Raises
    ------
    ValueError
        For an option out of range or coordinates that are not finite, naming
        the geometry.
    """
    import shapely

    args = (tolerance, coverage, through, keep_angle, alpha)
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
