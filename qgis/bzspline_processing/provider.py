"""The Processing provider "bzspline": its algorithms, and whether the Python
packages they call can be imported into QGIS's Python."""

import os

from qgis.core import Qgis, QgsMessageLog, QgsProcessingProvider
from qgis.PyQt.QtGui import QIcon

HERE = os.path.dirname(__file__)

INSTALL = (
    "The bzspline plugin needs the Python packages bzspline and shapely (2 or later) in QGIS's "
    "Python, which cannot import them ({error}). Install them into that Python, keeping its numpy, "
    "from a clone of bzspline (github.com/bzspline/bzspline; building needs Rust): on Linux, "
    "python3 -m pip install --user \"shapely>=2\" ./crates/bzspline-py; on Windows, the same "
    "with python in the OSGeo4W Shell; on macOS, with QGIS's own python3 "
    "(/Applications/QGIS.app/Contents/MacOS/bin/python3). Then restart QGIS. The plugin's "
    "README.md gives the details."
)


def package_problem():
    """``None`` when bzspline and shapely 2 import, else the message that
    says how to install them."""
    try:
        import shapely

        import bzspline.geo  # noqa: F401

        if int(shapely.__version__.split(".")[0]) < 2:
            raise ImportError(f"shapely {shapely.__version__} is older than 2")
    except Exception as e:  # ImportError, or a broken build's own error
        return INSTALL.format(error=f"{type(e).__name__}: {e}")
    return None


class BzsplineProvider(QgsProcessingProvider):
    """The algorithms, in the Processing Toolbox under "bzspline"."""

    def __init__(self):
        super().__init__()
        self.problem = package_problem()

    def loadAlgorithms(self):  # noqa: N802 (QGIS's name)
        from .points import SplineThroughPoints
        from .smooth import SmoothCoverage, SmoothIndependently
        from .track import SmoothTrack

        if self.problem is not None:
            QgsMessageLog.logMessage(self.problem, "bzspline", Qgis.Warning)
        for alg in (SmoothCoverage(), SmoothIndependently(), SplineThroughPoints(), SmoothTrack()):
            self.addAlgorithm(alg)

    def id(self):
        return "bzspline"

    def name(self):
        return "bzspline"

    def longName(self):  # noqa: N802
        try:
            import bzspline

            return f"bzspline {bzspline.__version__}"
        except Exception:
            return "bzspline (its Python package is not installed)"

    def icon(self):
        return QIcon(os.path.join(HERE, "icon.svg"))

    def svgIconPath(self):  # noqa: N802
        return os.path.join(HERE, "icon.svg")
