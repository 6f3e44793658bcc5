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
    "with the GEOS headers (libgeos-dev), python3 -m pip install --user --no-binary shapely "
    "\"shapely>=2\" ./crates/bzspline-py; on Windows, python -m pip install \"shapely>=2\" "
    "./crates/bzspline-py in the OSGeo4W Shell; on macOS, the same with QGIS's own python3 "
    "(/Applications/QGIS.app/Contents/MacOS/bin/python3). Then restart QGIS. The plugin's "
    "README.md gives the details."
)

# A GEOS that the QGIS executable has loaded (on Linux it links it, so its
# symbols are global) answers the calls of every library loaded after it:
# a shapely wheel's calls reach that GEOS, not the one built into the wheel,
# and where their versions differ give wrong answers (a 2D polygon with M,
# WKB refused). Python hosting QGIS's modules loads them privately.
MIXED_GEOS = (
    "shapely {shapely} was built with GEOS {theirs}, but QGIS runs GEOS {ours}, which answers "
    "shapely's calls inside QGIS and can give wrong answers. Install shapely built against "
    "QGIS's GEOS (with the GEOS headers, libgeos-dev): python3 -m pip install --user "
    "--force-reinstall --no-binary shapely \"shapely>=2\". Then restart QGIS."
)


def global_geos():
    """The version (major, minor, patch) of the GEOS whose symbols this
    process holds globally, or ``None`` where there is none (or no way to
    tell)."""
    import ctypes

    try:
        version = ctypes.CDLL(None).GEOSversion
        version.restype = ctypes.c_char_p
        text = version().decode()
        return tuple(int(p) for p in text.split("-")[0].split(".")[:3])
    except Exception:  # no such symbol, no global namespace (Windows), odd text
        return None


def geos_problem(shapely_geos, loaded):
    """``None`` unless a globally loaded GEOS (``loaded``) differs from
    shapely's own in major or minor version; else both versions as text."""
    if loaded is None or tuple(shapely_geos[:2]) == tuple(loaded[:2]):
        return None
    return (".".join(map(str, shapely_geos)), ".".join(map(str, loaded)))


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
    mixed = geos_problem(shapely.geos_version, global_geos())
    if mixed:
        theirs, ours = mixed
        return MIXED_GEOS.format(shapely=shapely.__version__, theirs=theirs, ours=ours)
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
