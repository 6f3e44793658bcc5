"""The plugin QGIS loads: it registers the Processing provider and nothing
else (no menus, no toolbar: the algorithms are in the Processing Toolbox, the
modeler, batch mode and ``qgis_process``)."""

from qgis.core import QgsApplication

from .provider import BzsplineProvider


class BzsplinePlugin:
    """Registers :class:`BzsplineProvider` with QGIS's Processing registry."""

    def __init__(self, iface):
        self.iface = iface
        self.provider = None

    def initProcessing(self):  # noqa: N802 (QGIS's name)
        """Called by QGIS (also by ``qgis_process``, thanks to
        ``hasProcessingProvider=yes`` in metadata.txt)."""
        if self.provider is None:
            self.provider = BzsplineProvider()
            QgsApplication.processingRegistry().addProvider(self.provider)

    def initGui(self):  # noqa: N802
        self.initProcessing()

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
