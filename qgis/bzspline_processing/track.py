"""*Smooth noisy track*: points with a time (GPS fixes), optionally grouped
into tracks, to one smoothed line per track: ``bzspline.smoothing_curve``
with the points' times as the parameter and the smoothing weight chosen by
generalised cross-validation, flattened to the tolerance. Tracks in
longitude and latitude are smoothed in metres, in an azimuthal equidistant
projection centred on each track, and brought back."""

import math

from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsField,
    QgsFields,
    QgsPointXY,
    QgsProcessing,
    QgsProcessingAlgorithm,
    QgsProcessingException,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterField,
    QgsProcessingParameterNumber,
    QgsWkbTypes,
)
from qgis.PyQt.QtCore import QDateTime, Qt, QVariant

from . import layers
from .points import sortable
from .provider import HERE, package_problem


def seconds(value):
    """A time field's value as seconds (dates and times since 1970, numbers
    as they are), ``None`` for NULL or text that is no ISO 8601 time."""
    if value is None or (hasattr(value, "isNull") and value.isNull()):
        return None
    if isinstance(value, QDateTime):
        return value.toMSecsSinceEpoch() / 1000.0
    if hasattr(value, "toPyDate") and not hasattr(value, "toPyDateTime"):  # QDate
        return QDateTime(value).toMSecsSinceEpoch() / 1000.0
    if isinstance(value, str):
        t = QDateTime.fromString(value.strip(), Qt.ISODate)
        return t.toMSecsSinceEpoch() / 1000.0 if t.isValid() else None
    try:
        v = float(value)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


class SmoothTrack(QgsProcessingAlgorithm):
    INPUT = "INPUT"
    TIME = "TIME_FIELD"
    GROUP = "GROUP_FIELD"
    TOLERANCE = "TOLERANCE"
    UNIT = "TOLERANCE_UNIT"
    ROBUST = "ROBUST"
    OUTPUT = "OUTPUT"

    def name(self):
        return "smoothtrack"

    def displayName(self):  # noqa: N802
        return "Smooth noisy track"

    def group(self):
        return ""

    def groupId(self):  # noqa: N802
        return ""

    def icon(self):
        from qgis.PyQt.QtGui import QIcon

        return QIcon(f"{HERE}/icon.svg")

    def canExecute(self):  # noqa: N802
        problem = package_problem()
        return (problem is None, problem or "")

    def shortHelpString(self):  # noqa: N802
        return ("<p>Smooths noisy positions with a time (GPS fixes) into one line per track: the "
                "smoothing spline of bzspline, with the times as the curve's parameter and the "
                "smoothing weight chosen by generalised cross-validation (GCV), reported in the log "
                "and in the output's <i>lam</i> field (with <i>gcv</i>, the criterion, and "
                "<i>dof</i>, the fit's degrees of freedom).</p>"
                "<p><b>Time</b>: a date/time, date or number field, or ISO 8601 text. Points are "
                "taken in time order; two points of a track at the same time are an error.</p>"
                "<p><b>One track per value of</b>: optional, one line for each value.</p>"
                "<p><b>Tolerance</b>: the largest distance between the smoothed curve and the "
                "output line (0: 1e-4 of the track's extent). On a longitude/latitude layer each "
                "track is smoothed in metres, in an azimuthal equidistant projection centred on "
                "it, so give metres or kilometres.</p>"
                "<p><b>Ignore jumps</b>: a robust fit for fixes with gross errors (a jump of the "
                "receiver, a reflection): the fit is weighted again by its residuals (Tukey's "
                "biweight on six median absolute residuals, as lowess does), the smoothing weight "
                "chosen again each time, so that a jump does not pull the line. The output's "
                "<i>outliers</i> field counts the fixes it set aside (weight 0).</p>"
                "<p>Features without geometry or time are skipped (counted in the log).</p>")

    def initAlgorithm(self, config=None):  # noqa: N802
        self.addParameter(QgsProcessingParameterFeatureSource(
            self.INPUT, "Points of the track", [QgsProcessing.TypeVectorPoint]))
        self.addParameter(QgsProcessingParameterField(
            self.TIME, "Time", parentLayerParameterName=self.INPUT))
        self.addParameter(QgsProcessingParameterField(
            self.GROUP, "One track per value of", parentLayerParameterName=self.INPUT, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.TOLERANCE, "Tolerance (0: 1e-4 of the extent's diagonal)",
            QgsProcessingParameterNumber.Double, 0.0, minValue=0.0))
        self.addParameter(QgsProcessingParameterEnum(
            self.UNIT, "Unit of the tolerance", layers.UNIT_NAMES, defaultValue=0))
        self.addParameter(QgsProcessingParameterBoolean(
            self.ROBUST, "Ignore jumps (robust fit)", defaultValue=False))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, "Smoothed track", QgsProcessing.TypeVectorLine))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        # qgis_process runs an algorithm without asking canExecute.
        problem = package_problem()
        if problem is not None:
            raise QgsProcessingException(problem)
        try:
            return self.process(parameters, context, feedback)
        except layers.Canceled:
            feedback.pushInfo("Canceled: nothing was written.")
            return {}

    def process(self, parameters, context, feedback):
        import numpy as np

        import bzspline

        source = self.parameterAsSource(parameters, self.INPUT, context)
        if source is None:
            raise QgsProcessingException(self.invalidSourceError(parameters, self.INPUT))
        if QgsWkbTypes.geometryType(source.wkbType()) != QgsWkbTypes.PointGeometry:
            raise QgsProcessingException(f"{source.sourceName()}: not a point layer")
        time_field = self.parameterAsString(parameters, self.TIME, context)
        group = self.parameterAsString(parameters, self.GROUP, context) or None
        unit = self.parameterAsEnum(parameters, self.UNIT, context)
        tolerance = layers.distance(self.parameterAsDouble(parameters, self.TOLERANCE, context), unit)
        robust = self.parameterAsBool(parameters, self.ROBUST, context)
        crs = source.sourceCrs()
        geographic = crs.isValid() and crs.isGeographic()
        if geographic and tolerance is not None and layers.UNITS[unit][1] in ("", "deg"):
            raise QgsProcessingException("a longitude/latitude track is smoothed in metres: give the "
                                         "tolerance in metres or kilometres")

        tracks, labels, skipped = {}, {}, 0
        total = max(source.featureCount(), 1)
        for i, f in enumerate(source.getFeatures()):
            if i % 1000 == 0:
                layers.check(feedback, 30.0 * i / total)
            g, t = f.geometry(), seconds(f[time_field])
            if g is None or g.isNull() or g.isEmpty() or t is None:
                skipped += 1
                continue
            key = None if group is None else sortable(f[group])
            labels.setdefault(key, None if group is None else f[group])
            for v in g.constGet().vertices():
                tracks.setdefault(key, []).append((t, f.id(), v.x(), v.y()))
        if skipped:
            feedback.pushWarning(f"{skipped} features without a point or a time: skipped")

        rows = []
        for n, (key, fixes) in enumerate(tracks.items()):
            layers.check(feedback, 30 + 50 * n / max(len(tracks), 1))
            fixes.sort(key=lambda r: r[0])
            name = "the track" if group is None else f"track {labels[key]!r}"
            for a, b in zip(fixes, fixes[1:]):
                if a[0] == b[0]:
                    raise QgsProcessingException(f"{name}: features {a[1]} and {b[1]} have the same time")
            t = np.array([r[0] for r in fixes])
            xy = np.array([[r[2], r[3]] for r in fixes])
            frame = crs
            if geographic:
                lon, lat = np.median(xy[:, 0]), np.median(xy[:, 1])
                frame = QgsCoordinateReferenceSystem.fromProj(
                    f"+proj=aeqd +lat_0={lat} +lon_0={lon} +datum=WGS84 +units=m +no_defs")
                there = QgsCoordinateTransform(crs, frame, context.transformContext())
                xy = np.array([[p.x(), p.y()] for p in (there.transform(QgsPointXY(*c)) for c in xy)])
            fewest = bzspline.ROBUST_MIN_POINTS if robust else 3
            if len(t) < fewest:
                feedback.pushWarning(f"{name}: {len(t)} points, too few to smooth"
                                     f"{' robustly' if robust else ''}: skipped")
                continue
            try:
                curve = bzspline.smoothing_curve(xy, param=t - t[0], robust=robust)
                lo, hi = xy.min(axis=0), xy.max(axis=0)
                tol = bzspline.geo.tolerance(tolerance, crs=layers.crs_text(frame), bounds=(*lo, *hi))
                line = curve.flatten(tol)
            except ValueError as e:
                raise QgsProcessingException(f"{name}: {e}") from None
            if geographic:
                back = QgsCoordinateTransform(frame, crs, context.transformContext())
                line = np.array([[p.x(), p.y()] for p in (back.transform(QgsPointXY(*c)) for c in line)])
            feedback.pushInfo(f"{name}: {len(t)} points, smoothing weight {curve.lam:.6g} chosen by GCV "
                              f"(GCV {curve.gcv:.6g}, {curve.dof:.2f} degrees of freedom)")
            attributes = ([labels[key]] if group is not None else []) + [len(t), curve.lam, curve.gcv, curve.dof]
            if robust:
                outliers = int(np.count_nonzero(curve.robustness == 0))
                if outliers:
                    ids = [fixes[j][1] for j in np.flatnonzero(curve.robustness == 0)[:10]]
                    feedback.pushInfo(f"{name}: {outliers} fixes set aside as jumps (features "
                                      f"{', '.join(map(str, ids))}{', ...' if outliers > 10 else ''})")
                attributes.append(outliers)
            import shapely

            rows.append((attributes, shapely.LineString(line)))
        fields = QgsFields()
        if group is not None:
            fields.append(source.fields().field(group))
        fields.append(QgsField("points", QVariant.Int))
        for name in ("lam", "gcv", "dof"):
            fields.append(QgsField(name, QVariant.Double))
        if robust:
            fields.append(QgsField("outliers", QVariant.Int))
        dest = layers.write(self, parameters, context, self.OUTPUT, fields, QgsWkbTypes.LineString, crs, rows,
                            feedback)
        return {self.OUTPUT: dest}

    def createInstance(self):  # noqa: N802
        return SmoothTrack()
