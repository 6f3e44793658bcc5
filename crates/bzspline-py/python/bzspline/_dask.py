"""The dask adapter of :mod:`bzspline.geo`: a coverage over the partitions
of a dask-geopandas GeoSeries, smoothed by the parts protocol of
``bzspline_geo::parts`` (the junctions of the whole, each partition with the
geometries of the others near it, the rounds of the conflict search over all
of them together), so that the result is what one process gives, bit for
bit. Imported only when a dask series is given."""

import numpy as np

from . import _core
from .errors import GeometryError
from ._arrays import Nodes, _aligned, _groups, _like, _smooth_array, _smoothable, _values


def nodes(d):
    """The junctions of the coverage over ``d``'s partitions (``geo.nodes``)."""
    parts = d.to_delayed()
    return _nodes_over(parts, _extents(parts))


def _part_extent(part):
    """The bounding box of a partition's lines and polygons, or None."""
    import shapely

    arr = _values(part)
    ok = _smoothable(arr)
    if not ok.any():
        return None
    return tuple(float(v) for v in shapely.total_bounds(arr[ok]))


def _part_meetings(part, boxes, i):
    """The meetings of partition ``i`` at positions that another partition's
    extent holds (only those can be met by two partitions)."""
    groups, _ = _groups(_values(part))
    if not groups:
        return np.zeros((0, 2)), np.zeros(0, np.uint64), np.zeros(0, bool)
    try:
        pos, between, junction = _core._meetings(groups)
    except ValueError as e:
        raise _in_partition(e, part, i) from None
    keep = np.zeros(len(pos), dtype=bool)
    x, y = pos[:, 0], pos[:, 1]
    for j, (x0, y0, x1, y1) in enumerate(boxes):
        if j != i:
            keep |= (x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)
    return pos[keep], between[keep], junction[keep]


def _extents(parts):
    """Each partition's extent, as an (k, 4) array (NaN for an empty one)."""
    import dask

    extents = dask.compute(*[dask.delayed(_part_extent)(p) for p in parts])
    return np.array([e if e is not None else (np.nan,) * 4 for e in extents], dtype=np.float64).reshape(-1, 4)


def _nodes_over(parts, boxes):
    """The nodes where the partitions meet, and the extent of them all."""
    import dask

    met = dask.compute(*[dask.delayed(_part_meetings)(p, boxes, i) for i, p in enumerate(parts)])
    pos = np.concatenate([m[0] for m in met]) if met else np.zeros((0, 2))
    between = np.concatenate([m[1] for m in met]) if met else np.zeros(0, np.uint64)
    junction = np.concatenate([m[2] for m in met]) if met else np.zeros(0, bool)
    positions = _core._across(np.ascontiguousarray(pos, dtype=np.float64), between.astype(np.uint64), junction.astype(bool))
    known = boxes[~np.isnan(boxes).any(axis=1)]
    extent = None
    if len(known):
        extent = (known[:, 0].min(), known[:, 1].min(), known[:, 2].max(), known[:, 3].max())
    return Nodes(positions, extent)


def _near(part, box, inner=None):
    """The geometries of a partition that a part whose extent is ``box``
    holds by the parts protocol (``bzspline_geo::parts``): its context, or
    with ``inner`` (the part's own extent; ``box`` then the extent of part and
    context) those around it."""
    import shapely

    arr = _values(part)
    ok = ~(shapely.is_missing(arr) | shapely.is_empty(arr))
    b = np.ascontiguousarray(shapely.bounds(arr[ok]), dtype=np.float64).reshape(-1, 4)
    if inner is None:
        near = _core._context_of(b, tuple(box))
    else:
        near = _core._around_of(b, tuple(inner), tuple(box))
    return arr[ok][near]


def _bounds(arrs, box):
    """The extent of a part (``box``) and its context (the arrays ``arrs``)."""
    import shapely

    b = np.array([shapely.total_bounds(a) for a in arrs if len(a)], dtype=np.float64).reshape(-1, 4)
    return _core._outer(tuple(box), b)


def _smooth_part(part, context, around, nodes, levels, opts, number, round):
    """Round ``round`` of the conflict search on partition ``number``, with
    the geometries near it from the others (``context``, a list of arrays,
    held exactly) and those near all of them (``around``, for the context's
    topology only), from ``levels``: its own results at those levels, as a
    GeoSeries like it, and the levels after the round. An error names the
    partition and the geometry's index label (or says it is a neighbour's)."""
    own = _values(part)
    arr = np.concatenate([own, *context, *around])
    exact = len(own) + sum(len(c) for c in context)
    try:
        out, ended = _smooth_array(arr, *opts[:5], nodes, None, levels, round, exact, geographic=opts[5])
    except ValueError as e:
        raise _in_partition(e, part, number) from None
    return _like(part, out[: len(own)]), ended


def _in_partition(e, part, number):
    """The error ``e`` of partition ``number``, naming its geometry by index
    label (a position past the partition's own is a neighbour's geometry)."""
    if not isinstance(e, GeometryError):
        return ValueError(f"partition {number}: {e}")
    k = e.index
    own = k < len(part)
    label = part.index[k] if own else None
    at = f"index {label!r}" if own else "a geometry of a neighbouring partition"
    rest = str(e).split(":", 1)[-1].strip()
    where = "".join(f", {name} {v}" for name, v in (("member", e.member), ("ring", e.ring),
                                                   ("coordinate", e.coordinate)) if v is not None)
    return GeometryError(f"partition {number}, {at}{where}: {rest}", k, member=e.member, ring=e.ring,
                         coordinate=e.coordinate, partition=number, label=label)


def smooth(d, tolerance, through, keep_angle, alpha, geographic=False):
    """A coverage over dask partitions by the parts protocol of
    ``bzspline_geo::parts``: every partition smoothed with the whole's nodes,
    the other partitions' geometries it holds (its context and those around),
    one round of the conflict search at a time, all partitions from the levels
    all of them ended the round before at (``_core._Rounds``), until no
    partition raises any: the rounds of one process smoothing the whole, so
    the same result."""
    import dask
    import dask.dataframe as dd

    parts = d.to_delayed()
    boxes = _extents(parts)
    nodes = _nodes_over(parts, boxes)
    known = ~np.isnan(boxes).any(axis=1)
    filled = np.nan_to_num(boxes)

    def others(i, box):
        near = _core._context_of(np.ascontiguousarray(filled), tuple(box))
        return [j for j in np.flatnonzero(known & near) if j != i] if known[i] else []

    # The features of other partitions that may come near each one's (held
    # exactly), then those that share a position with one of them: their
    # bounding boxes meet the extent of all (for the topology only).
    contexts = [list(dask.persist(*[dask.delayed(_near)(parts[j], tuple(box)) for j in others(i, box)]))
                for i, box in enumerate(boxes)]
    outers = dask.compute(*[dask.delayed(_bounds)(c, tuple(box)) for c, box in zip(contexts, boxes)])
    arounds = [list(dask.persist(*[dask.delayed(_near)(parts[j], outer, tuple(box)) for j in others(i, outer)]))
               for i, (box, outer) in enumerate(zip(boxes, outers))]
    opts = (tolerance, True, through, keep_angle, alpha, geographic)
    rounds = _core._Rounds()
    while True:
        levels, round = rounds.levels, rounds.round
        runs = dask.persist(*[dask.delayed(_smooth_part)(p, c, a, nodes, levels, opts, i, round)
                              for i, (p, c, a) in enumerate(zip(parts, contexts, arounds))])
        ended = dask.compute(*[r[1] for r in runs])
        if not rounds.finish([_aligned(e) for e in ended]):
            return dd.from_delayed([r[0] for r in runs], meta=d._meta, verify_meta=False)
