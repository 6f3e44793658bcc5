"""The algorithms that smooth lines and polygons: *Smooth coverage* (the
layer as one coverage, every shared border smoothed once) and *Smooth lines
or polygons independently* (each feature on its own). Both call
``bzspline.geo.smooth``, whose options and defaults they are."""

from qgis.core import (
    QgsFeatureRequest,
    QgsProcessing,
    QgsProcessingAlgorithm,
    QgsProcessingException,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterNumber,
    QgsWkbTypes,
)

from . import layers
from .provider import HERE, package_problem

HELP_OPTIONS = """
<p><b>Tolerance</b>: the largest distance between the smooth curve and the output line (0: the
default, 1e-4 of the diagonal of the layer's extent), in the unit chosen. Metres and kilometres on a
longitude/latitude layer smooth on the WGS 84 ellipsoid (the same ground distance at every latitude,
across the antimeridian); on a projected layer they become the layer's units. Degrees only on
longitude/latitude layers.</p>
<p><b>Shape parameter alpha</b>: where the curve touches each leg between two vertices, from 1/3 to
2/3 (0.5: the middle).</p>
<p><b>Pass through every vertex</b>: the interpolating variant, which keeps every input vertex
(by default the curve cuts the corners and touches the legs).</p>
<p><b>Keep corners sharper than</b> (degrees, 0: none): vertices where a line turns by more
are kept as corners.</p>
<p><b>Snap distance</b> (in the tolerance's unit, 0: none): positions closer than this are merged
first, so that borders digitised twice with small differences become one.</p>
<p>Features without a geometry pass through unchanged. M values are dropped; geometries with Z are
smoothed in space, one line or ring at a time.</p>
"""


class SmoothBase(QgsProcessingAlgorithm):
    """The parameters, reading, smoothing and writing both algorithms share."""

    INPUT = "INPUT"
    TOLERANCE = "TOLERANCE"
    UNIT = "TOLERANCE_UNIT"
    ALPHA = "ALPHA"
    THROUGH = "THROUGH"
    KEEP_ANGLE = "KEEP_ANGLE"
    SNAP = "SNAP"
    OUTPUT = "OUTPUT"

    #: Smooth the whole layer as one coverage.
    coverage = True

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

    def extra_parameters(self):
        """Parameters one algorithm adds."""

    def initAlgorithm(self, config=None):  # noqa: N802
        try:
            from bzspline import ALPHA_MAX, ALPHA_MIN
        except ImportError:  # the algorithm says how to install it
            ALPHA_MIN, ALPHA_MAX = 0.0, 1.0
        self.addParameter(QgsProcessingParameterFeatureSource(
            self.INPUT, "Input layer", [QgsProcessing.TypeVectorLine, QgsProcessing.TypeVectorPolygon]))
        self.addParameter(QgsProcessingParameterNumber(
            self.TOLERANCE, "Tolerance (0: 1e-4 of the extent's diagonal)",
            QgsProcessingParameterNumber.Double, 0.0, minValue=0.0))
        self.addParameter(QgsProcessingParameterEnum(
            self.UNIT, "Unit of the tolerance and snap distance", layers.UNIT_NAMES, defaultValue=0))
        self.addParameter(QgsProcessingParameterNumber(
            self.ALPHA, "Shape parameter alpha", QgsProcessingParameterNumber.Double, 0.5,
            minValue=ALPHA_MIN, maxValue=ALPHA_MAX))
        self.addParameter(QgsProcessingParameterBoolean(
            self.THROUGH, "Pass through every vertex", defaultValue=False))
        self.addParameter(QgsProcessingParameterNumber(
            self.KEEP_ANGLE, "Keep corners sharper than (degrees, 0: none)",
            QgsProcessingParameterNumber.Double, 0.0, minValue=0.0, maxValue=180.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.SNAP, "Snap distance (0: none)", QgsProcessingParameterNumber.Double, 0.0, minValue=0.0))
        self.extra_parameters()
        self.addParameter(QgsProcessingParameterFeatureSink(self.OUTPUT, "Smoothed"))

    def per_feature(self, parameters, context):
        return not self.coverage

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

        # Invalid polygons are smoothed with a warning (below), not refused
        # by QGIS's check of the input.
        context.setInvalidGeometryCheck(QgsFeatureRequest.GeometryNoCheck)
        source = self.parameterAsSource(parameters, self.INPUT, context)
        if source is None:
            raise QgsProcessingException(self.invalidSourceError(parameters, self.INPUT))
        kind = QgsWkbTypes.geometryType(source.wkbType())
        if kind not in (QgsWkbTypes.LineGeometry, QgsWkbTypes.PolygonGeometry):
            raise QgsProcessingException(
                f"{source.sourceName()}: a {QgsWkbTypes.displayString(source.wkbType())} layer; "
                "only lines and polygons are smoothed (Spline through points takes points)")
        unit = self.parameterAsEnum(parameters, self.UNIT, context)
        tolerance = layers.distance(self.parameterAsDouble(parameters, self.TOLERANCE, context), unit)
        snap = layers.distance(self.parameterAsDouble(parameters, self.SNAP, context), unit)
        layers.check_units(source.sourceCrs(), tolerance, snap)
        keep = self.parameterAsDouble(parameters, self.KEEP_ANGLE, context) or None
        alpha = self.parameterAsDouble(parameters, self.ALPHA, context)
        through = self.parameterAsBool(parameters, self.THROUGH, context)
        coverage = not self.per_feature(parameters, context)

        ids, attrs, geoms = layers.read(source, feedback)
        missing = int((shapely.is_missing(geoms) | shapely.is_empty(geoms)).sum())
        if missing:
            feedback.pushWarning(f"{missing} features have no geometry: they are written unchanged")
        if kind == QgsWkbTypes.PolygonGeometry:
            present = ~shapely.is_missing(geoms)
            invalid = np.flatnonzero(present & ~shapely.is_valid(geoms))
            if len(invalid):
                named = ", ".join(str(ids[i]) for i in invalid[:10]) + (", ..." if len(invalid) > 10 else "")
                feedback.pushWarning(
                    f"{len(invalid)} input polygons are not valid (feature ids {named}; "
                    f"{shapely.is_valid_reason(geoms[invalid[0]])}): they are smoothed as they are, "
                    "and their outputs may not be valid either")
        layers.check(feedback, 30)
        feedback.pushInfo(f"Smoothing {len(geoms)} features "
                          + ("as one coverage" if coverage else "one by one") + " ...")
        with layers.package_messages(feedback, ids):
            out = bzspline.geo.smooth(
                geoms, tolerance=tolerance, coverage=coverage, through=through, keep_angle=keep,
                alpha=alpha, snap=snap, crs=layers.crs_text(source.sourceCrs()))
        layers.check(feedback, 80)
        if kind == QgsWkbTypes.PolygonGeometry:
            was = ~shapely.is_missing(geoms) & shapely.is_valid(geoms)
            broken = np.flatnonzero(was & ~shapely.is_valid(out))
            if len(broken):
                feedback.reportError(f"{len(broken)} valid polygons came out invalid "
                                     f"(feature ids {', '.join(str(ids[i]) for i in broken[:10])})")
        wkb_type = QgsWkbTypes.dropM(source.wkbType())
        dest = layers.write(self, parameters, context, self.OUTPUT, source.fields(), wkb_type,
                            source.sourceCrs(), list(zip(attrs, out)), feedback)
        return {self.OUTPUT: dest}


class SmoothCoverage(SmoothBase):
    """A polygon or line layer smoothed as one coverage."""

    PER_FEATURE = "PER_FEATURE"

    def name(self):
        return "smoothcoverage"

    def displayName(self):  # noqa: N802
        return "Smooth coverage"

    def shortHelpString(self):  # noqa: N802
        return ("<p>Smooths a polygon or line layer as one coverage with the Bezier-type spline of "
                "Stelia, Potapenko and Sirenko: every border two features share (or a line shares "
                "with a polygon) is smoothed once, the same way for both, so no gaps or overlaps "
                "open between neighbours, and valid polygons stay valid (where curves would cross, "
                "they are refined). Each piece of curve lies inside the hull of its vertices.</p>"
                + HELP_OPTIONS
                + "<p><b>Each feature on its own</b>: smooth every feature as a coverage of its own "
                "(as <i>Smooth lines or polygons independently</i>).</p>")

    def extra_parameters(self):
        self.addParameter(QgsProcessingParameterBoolean(
            self.PER_FEATURE, "Each feature on its own (borders no longer shared)", defaultValue=False))

    def per_feature(self, parameters, context):
        return self.parameterAsBool(parameters, self.PER_FEATURE, context)

    def createInstance(self):  # noqa: N802
        return SmoothCoverage()


class SmoothIndependently(SmoothBase):
    """Every line or polygon smoothed on its own."""

    coverage = False

    def name(self):
        return "smoothindependently"

    def displayName(self):  # noqa: N802
        return "Smooth lines or polygons independently"

    def shortHelpString(self):  # noqa: N802
        return ("<p>Smooths every line and polygon of the layer on its own with the Bezier-type "
                "spline of Stelia, Potapenko and Sirenko, each with its own default tolerance. "
                "Borders neighbours share are smoothed separately and may part: use <i>Smooth "
                "coverage</i> to keep them shared.</p>" + HELP_OPTIONS)

    def createInstance(self):  # noqa: N802
        return SmoothIndependently()
