"""*Spline through points*: a point layer, ordered by a field and optionally
grouped by another, to one smooth line per group, open or closed, through
``bzspline.geo.smooth`` of the polyline through the points."""

from qgis.core import (
    QgsField,
    QgsFields,
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
from qgis.PyQt.QtCore import QVariant

from . import layers
from .provider import HERE, package_problem


def sortable(value):
    """A field's value as a sort key (dates and times as Python's), ``None``
    for NULL."""
    if value is None or (hasattr(value, "isNull") and value.isNull()):
        return None
    for convert in ("toPyDateTime", "toPyDate", "toPyTime"):
        if hasattr(value, convert):
            return getattr(value, convert)()
    return value


def grouped(source, order_field, group_field, feedback):
    """The points of ``source`` by group (insertion order of the groups):
    ``{group: [(order key, feature id, (x, y[, z])), ...]}``, sorted by the
    order key (the feature order without an order field), each group's
    field value as the layer holds it, and the count of features without a
    point, which are skipped. A NULL order value is an error naming the
    feature."""
    groups, labels, skipped = {}, {}, 0
    total = max(source.featureCount(), 1)
    for i, f in enumerate(source.getFeatures()):
        if i % 1000 == 0:
            layers.check(feedback, 40.0 * i / total)
        g = f.geometry()
        if g is None or g.isNull() or g.isEmpty():
            skipped += 1
            continue
        key = i if order_field is None else sortable(f[order_field])
        if key is None:
            raise QgsProcessingException(f"feature {f.id()}: its {order_field} is NULL, so it has no place "
                                         "in the order")
        group = None if group_field is None else sortable(f[group_field])
        labels.setdefault(group, None if group_field is None else f[group_field])
        for v in g.constGet().vertices():
            p = (v.x(), v.y(), v.z()) if v.is3D() else (v.x(), v.y())
            groups.setdefault(group, []).append((key, f.id(), p))
    for pts in groups.values():
        try:
            pts.sort(key=lambda r: r[0])
        except TypeError as e:
            raise QgsProcessingException(f"the values of {order_field} cannot be ordered: {e}") from None
    return groups, labels, skipped


class SplineThroughPoints(QgsProcessingAlgorithm):
    INPUT = "INPUT"
    ORDER = "ORDER_FIELD"
    GROUP = "GROUP_FIELD"
    CLOSED = "CLOSED"
    THROUGH = "THROUGH"
    ALPHA = "ALPHA"
    TOLERANCE = "TOLERANCE"
    UNIT = "TOLERANCE_UNIT"
    OUTPUT = "OUTPUT"

    def name(self):
        return "splinethroughpoints"

    def displayName(self):  # noqa: N802
        return "Spline through points"

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
        return ("<p>Draws a smooth line through the points of a layer, in the order of a field "
                "(the features' order without one), one line per value of the group field: the "
                "Bezier-type spline of Stelia, Potapenko and Sirenko, C1, each piece inside the "
                "hull of its points.</p>"
                "<p><b>Pass through every point</b> (the default): the interpolating variant; "
                "unticked, the curve starts and ends at the end points and touches every leg "
                "between two points, cutting the corners. <b>Closed</b>: the last point joins the "
                "first smoothly.</p>"
                "<p><b>Tolerance</b>: the largest distance between the curve and the output line "
                "(0: 1e-4 of the points' extent), in the unit chosen; metres on a longitude/latitude "
                "layer are measured on the WGS 84 ellipsoid.</p>"
                "<p>Multipoint features give their points in order. Features without geometry are "
                "skipped (counted in the log); a group of fewer than two distinct points is "
                "skipped with a warning.</p>")

    def initAlgorithm(self, config=None):  # noqa: N802
        try:
            from bzspline import ALPHA_MAX, ALPHA_MIN
        except ImportError:
            ALPHA_MIN, ALPHA_MAX = 0.0, 1.0
        self.addParameter(QgsProcessingParameterFeatureSource(
            self.INPUT, "Point layer", [QgsProcessing.TypeVectorPoint]))
        self.addParameter(QgsProcessingParameterField(
            self.ORDER, "Order by", parentLayerParameterName=self.INPUT, optional=True))
        self.addParameter(QgsProcessingParameterField(
            self.GROUP, "One line per value of", parentLayerParameterName=self.INPUT, optional=True))
        self.addParameter(QgsProcessingParameterBoolean(self.CLOSED, "Closed", defaultValue=False))
        self.addParameter(QgsProcessingParameterBoolean(
            self.THROUGH, "Pass through every point", defaultValue=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.ALPHA, "Shape parameter alpha", QgsProcessingParameterNumber.Double, 0.5,
            minValue=ALPHA_MIN, maxValue=ALPHA_MAX))
        self.addParameter(QgsProcessingParameterNumber(
            self.TOLERANCE, "Tolerance (0: 1e-4 of the extent's diagonal)",
            QgsProcessingParameterNumber.Double, 0.0, minValue=0.0))
        self.addParameter(QgsProcessingParameterEnum(
            self.UNIT, "Unit of the tolerance", layers.UNIT_NAMES, defaultValue=0))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, "Spline", QgsProcessing.TypeVectorLine))

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
        import shapely

        import bzspline.geo

        source = self.parameterAsSource(parameters, self.INPUT, context)
        if source is None:
            raise QgsProcessingException(self.invalidSourceError(parameters, self.INPUT))
        if QgsWkbTypes.geometryType(source.wkbType()) != QgsWkbTypes.PointGeometry:
            raise QgsProcessingException(f"{source.sourceName()}: not a point layer")
        order = self.parameterAsString(parameters, self.ORDER, context) or None
        group = self.parameterAsString(parameters, self.GROUP, context) or None
        closed = self.parameterAsBool(parameters, self.CLOSED, context)
        through = self.parameterAsBool(parameters, self.THROUGH, context)
        alpha = self.parameterAsDouble(parameters, self.ALPHA, context)
        unit = self.parameterAsEnum(parameters, self.UNIT, context)
        tolerance = layers.distance(self.parameterAsDouble(parameters, self.TOLERANCE, context), unit)

        layers.check_units(source.sourceCrs(), tolerance)
        groups, labels, skipped = grouped(source, order, group, feedback)
        if skipped:
            feedback.pushWarning(f"{skipped} features have no point: skipped")
        keys, lines, counts, firsts = [], [], [], []
        for key, pts in groups.items():
            coords = [p for _, _, p in pts]
            # Repeated points make no leg: one of each run is kept.
            distinct = [c for k, c in enumerate(coords) if k == 0 or c != coords[k - 1]]
            if closed and len(distinct) > 1 and distinct[0] == distinct[-1]:
                distinct.pop()
            if len(distinct) < 2 or (closed and len(distinct) < 3):
                feedback.pushWarning(f"group {key!r}: {len(distinct)} distinct points, too few for a "
                                     f"{'closed' if closed else 'open'} spline: skipped")
                continue
            ring = distinct + [distinct[0]] if closed else distinct
            # A closed spline is the ring of a polygon to the package.
            lines.append(shapely.Polygon(ring) if closed else shapely.LineString(ring))
            keys.append(labels[key])
            counts.append(len(distinct))
            firsts.append(pts[0][1])
        layers.check(feedback, 50)
        with layers.package_messages(feedback, firsts, what="the line starting at feature"):
            out = bzspline.geo.smooth(np.array(lines, dtype=object), tolerance=tolerance, coverage=False,
                                      through=through, alpha=alpha, crs=layers.crs_text(source.sourceCrs()))
        out = [shapely.LineString(g.exterior.coords) if closed else g for g in out]
        layers.check(feedback, 80)

        fields = QgsFields()
        if group is not None:
            fields.append(source.fields().field(group))
        fields.append(QgsField("points", QVariant.Int))
        z = any(shapely.has_z(np.array(out, dtype=object))) if out else False
        wkb_type = QgsWkbTypes.LineStringZ if z else QgsWkbTypes.LineString
        rows = [(([k] if group is not None else []) + [n], g) for k, n, g in zip(keys, counts, out)]
        dest = layers.write(self, parameters, context, self.OUTPUT, fields, wkb_type, source.sourceCrs(),
                            rows, feedback)
        feedback.pushInfo(f"{len(rows)} lines written")
        return {self.OUTPUT: dest}

    def createInstance(self):  # noqa: N802
        return SplineThroughPoints()
