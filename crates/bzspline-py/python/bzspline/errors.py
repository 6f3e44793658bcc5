"""The exceptions bzspline raises beyond Python's own, each a ``ValueError``
carrying where the fault is, so that code can act on it without reading the
message."""

__all__ = ["GeometryError"]


class GeometryError(ValueError):
    """A geometry that cannot be smoothed (a coordinate that is not finite, a
    curve that cannot be built).

    Attributes
    ----------
    index : int
        The geometry's position in the array given (in its partition, for a
        dask series).
    member : int or None
        The line or polygon within a multi-geometry (0 for a single one).
    ring : int or None
        The ring of a polygon (0 the shell); None for a line.
    coordinate : int or None
        The position within the geometry, counted over its lines and rings.
    partition : int or None
        For a dask series, the partition.
    label : object or None
        For a dask series, the geometry's index label; None for a geometry of
        a neighbouring partition that the partition held.
    """

    def __init__(self, message, index, member=None, ring=None, coordinate=None, partition=None,
                 label=None):
        super().__init__(message)
        self.index = index
        self.member = member
        self.ring = ring
        self.coordinate = coordinate
        self.partition = partition
        self.label = label

    def __reduce__(self):
        return (_rebuild, (type(self), self.args[0], self.__dict__))


def _rebuild(cls, message, fields):
    e = cls.__new__(cls)
    ValueError.__init__(e, message)
    e.__dict__.update(fields)
    return e
