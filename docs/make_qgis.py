#!/usr/bin/env python3
"""Draws docs/qgis.png with QGIS's own renderer: US counties around Richmond,
Virginia (us-atlas), smoothed by QGIS's Smooth (native:smoothgeometry, 3
iterations) and by the plugin's Smooth coverage (500 m), side by side.
Counties are filled with translucent colours over white: where two smoothed
counties overlap the colour darkens, where they part the white shows.

Run with QGIS's Python (bzspline and shapely 2 installed into it):

    export BZSPLINE_ATLAS=$(bash bench/atlas.sh)
    QT_QPA_PLATFORM=offscreen python3 docs/make_qgis.py
"""

import os
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "qgis"))

from qgis.core import (  # noqa: E402
    QgsApplication,
    QgsFillSymbol,
    QgsMapRendererParallelJob,
    QgsMapSettings,
    QgsProperty,
    QgsRectangle,
    QgsSingleSymbolRenderer,
    QgsSymbolLayer,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QSize, Qt  # noqa: E402
from qgis.PyQt.QtGui import QColor, QFont, QImage, QPainter  # noqa: E402

QgsApplication.setPrefixPath("/usr", True)
app = QgsApplication([], False)
app.initQgis()
sys.path.append("/usr/share/qgis/python/plugins")
import processing  # noqa: E402
from processing.core.Processing import Processing  # noqa: E402

Processing.initialize()
from bzspline_processing.provider import BzsplineProvider  # noqa: E402

provider = BzsplineProvider()
QgsApplication.processingRegistry().addProvider(provider)

EXTENT = QgsRectangle(-77.75, 37.05, -77.05, 37.60)
SIZE = 640


def styled(layer):
    symbol = QgsFillSymbol.createSimple({"outline_color": "40,40,40,255", "outline_width": "0.15"})
    symbol.symbolLayer(0).setDataDefinedProperty(
        QgsSymbolLayer.PropertyFillColor,
        QgsProperty.fromExpression("color_hsla((to_int(\"id\") * 137) % 360, 65, 55, 120)"))
    layer.setRenderer(QgsSingleSymbolRenderer(symbol))
    return layer


def render(layer):
    settings = QgsMapSettings()
    settings.setLayers([styled(layer)])
    settings.setDestinationCrs(layer.crs())
    settings.setExtent(EXTENT)
    settings.setOutputSize(QSize(SIZE, SIZE))
    settings.setBackgroundColor(QColor("white"))
    job = QgsMapRendererParallelJob(settings)
    job.start()
    job.waitForFinished()
    return job.renderedImage()


def main():
    folder = pathlib.Path(os.environ.get("BZSPLINE_ATLAS", ROOT / "bench/atlas/data"))
    counties = str(folder / "counties.geojson")
    qgis = processing.run("native:smoothgeometry", {"INPUT": counties, "ITERATIONS": 3,
                                                    "OUTPUT": "memory:"})["OUTPUT"]
    ours = processing.run("bzspline:smoothcoverage", {"INPUT": counties, "TOLERANCE": 500.0,
                                                      "OUTPUT": "memory:"})["OUTPUT"]
    panels = [("QGIS Smooth, 3 iterations", render(qgis)), ("bzspline Smooth coverage, 500 m", render(ours))]
    title = 36
    out = QImage(SIZE * 2 + 10, SIZE + title, QImage.Format_ARGB32)
    out.fill(QColor("white"))
    p = QPainter(out)
    p.setFont(QFont("DejaVu Sans", 14))
    for i, (label, image) in enumerate(panels):
        x = i * (SIZE + 10)
        p.drawText(x, 0, SIZE, title, Qt.AlignCenter, label)
        p.drawImage(x, title, image)
    p.end()
    out.save(str(ROOT / "docs/qgis.png"))
    print(ROOT / "docs/qgis.png")


if __name__ == "__main__":
    main()
