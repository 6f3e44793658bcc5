"""bzspline for QGIS: a Processing provider over the bzspline Python package.

QGIS calls :func:`classFactory` when it loads the plugin.
"""


def classFactory(iface):  # noqa: N802 (the name QGIS calls)
    """The plugin object QGIS keeps while the plugin is loaded."""
    from .plugin import BzsplinePlugin

    return BzsplinePlugin(iface)
