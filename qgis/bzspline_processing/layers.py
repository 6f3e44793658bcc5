"""Between QGIS and the bzspline package: features read into shapely
geometries (with their ids and attributes), distances with a unit written as
the package takes them, the package's errors and warnings turned into
Processing's, and an output layer written only once everything is computed,
so that a failure or a cancellation never leaves half a layer."""

import warnings
from contextlib import contextmanager

from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsFeature,
    QgsFeatureSink,
    QgsGeometry,
    QgsProcessingException,
    QgsWkbTypes,
)

# The choices of every "unit" parameter and the suffix the package reads
# (bzspline_io::distance: a bare number is in the layer's own units).
UNITS = [("metres", "m"), ("kilometres", "km"), ("layer units", ""), ("degrees", "deg")]
UNIT_NAMES = [name for name, _ in UNITS]


class Canceled(Exception):
    """The user canceled; nothing is written."""


def distance(value, unit):
    """A distance as ``bzspline.geo.smooth`` takes it: ``None`` for 0 (the
    package's default), a number in the layer's units, or text with a unit
    (``"50m"``), which the package measures in the layer's CRS."""
    if value is None or value == 0:
        return None
    suffix = UNITS[unit][1]
    return float(value) if suffix == "" else f"{float(value)!r}{suffix}"


def check_units(crs, *distances):
    """Refuses a distance with a unit on a layer without a CRS, in the
    words of QGIS (the package would ask for its ``crs=`` argument)."""
    if (crs is None or not crs.isValid()) and any(isinstance(d, str) for d in distances):
        raise QgsProcessingException("the layer has no CRS, so a distance in metres or degrees cannot be "
                                     "measured: set the layer's CRS, or give the distance in layer units")


def crs_text(crs):
    """A layer's CRS as the package reads it (WKT), ``None`` when it has none."""
    if crs is None or not crs.isValid():
        return None
    return crs.toWkt(QgsCoordinateReferenceSystem.WKT1_GDAL)


def check(feedback, share=None):
    """Raises :class:`Canceled` when the user canceled; sets the progress."""
    if feedback.isCanceled():
        raise Canceled()
    if share is not None:
        feedback.setProgress(share)


def read(source, feedback, start=0.0, end=30.0):
    """Every feature of ``source``: ids, attribute lists and shapely
    geometries (``None`` for a null geometry), in the source's order."""
    import numpy as np
    import shapely

    ids, attrs, wkbs = [], [], []
    total = max(source.featureCount(), 1)
    for i, f in enumerate(source.getFeatures()):
        if i % 1000 == 0:
            check(feedback, start + (end - start) * i / total)
        ids.append(f.id())
        attrs.append(f.attributes())
        g = f.geometry()
        wkbs.append(None if g is None or g.isNull() else bytes(g.asWkb()))
    geoms = shapely.from_wkb(np.array(wkbs, dtype=object))
    return ids, attrs, geoms


def to_qgis(geom, wkb_type):
    """A shapely geometry as a QgsGeometry of the output layer's type (single
    parts made multi where the layer is multi)."""
    import shapely

    if geom is None:
        return QgsGeometry()
    g = QgsGeometry()
    # The dimension given: inside QGIS (the desktop and qgis_process) a
    # shapely wheel's GEOS calls can reach the GEOS QGIS loaded, which may be
    # older than 3.12 and refuses shapely's default of 4 (for M values).
    g.fromWkb(shapely.to_wkb(geom, output_dimension=3))
    if QgsWkbTypes.isMultiType(wkb_type) and not g.isMultipart():
        g.convertToMultiType()
    return g


def write(alg, parameters, context, name, fields, wkb_type, crs, rows, feedback, start=80.0):
    """Creates the sink of parameter ``name`` and writes ``rows`` (attribute
    list, shapely geometry) to it; returns the sink's id. Called only when
    every row is known."""
    sink, dest = alg.parameterAsSink(parameters, name, context, fields, wkb_type, crs)
    if sink is None:
        raise QgsProcessingException(alg.invalidSinkError(parameters, name))
    total = max(len(rows), 1)
    for i, (attributes, geom) in enumerate(rows):
        f = QgsFeature(fields)
        f.setAttributes(attributes)
        f.setGeometry(to_qgis(geom, wkb_type))
        if not sink.addFeature(f, QgsFeatureSink.FastInsert):
            raise QgsProcessingException(f"could not write feature {i} to the output: {sink.lastError()}")
        if i % 1000 == 0:
            feedback.setProgress(start + (100.0 - start) * i / total)
    feedback.setProgress(100.0)
    return dest


@contextmanager
def package_messages(feedback, ids, what="feature"):
    """Runs a call into the package: its warnings go to the log, its errors
    become a QgsProcessingException naming the feature by id (``ids`` maps
    the package's geometry index to it)."""
    from bzspline.errors import GeometryError

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            yield
        except GeometryError as e:
            at = ids[e.index] if ids is not None and 0 <= e.index < len(ids) else e.index
            rest = str(e).split(":", 1)[-1].strip()
            where = "".join(f", {k} {v}" for k, v in (("member", e.member), ("ring", e.ring),
                                                      ("coordinate", e.coordinate)) if v is not None)
            raise QgsProcessingException(f"{what} {at}{where}: {rest}") from None
        except (ValueError, TypeError) as e:
            raise QgsProcessingException(str(e)) from None
    for w in caught:
        feedback.pushWarning(str(w.message))
