"""The plugin as QGIS loads it: the ZIP built by qgis/build.py, unpacked
into a plugins folder, loads in a fresh QGIS (its own process), registers
the provider with its four algorithms and runs one; the algorithms carry
help; without the package they say how to install it."""

import os
import subprocess
import sys
import textwrap
import zipfile

from conftest import ROOT, provider

NAMES = {"smoothcoverage", "smoothindependently", "splinethroughpoints", "smoothtrack"}


def test_the_provider_lists_every_algorithm_with_help():
    algs = {a.name(): a for a in provider().algorithms()}
    assert set(algs) == NAMES
    for a in algs.values():
        assert len(a.shortHelpString()) > 200
        assert a.canExecute() == (True, "")


def test_the_zip_installs_and_qgis_loads_it(tmp_path):
    zipped = tmp_path / "bzspline_processing.zip"
    subprocess.run([sys.executable, str(ROOT / "qgis/build.py"), "-o", str(zipped)], check=True)
    with zipfile.ZipFile(zipped) as z:
        names = z.namelist()
        for need in ("metadata.txt", "icon.svg", "__init__.py", "README.md", "LICENSE"):
            assert f"bzspline_processing/{need}" in names
        assert not [n for n in names if "__pycache__" in n or n.endswith(".pyc")]
        z.extractall(tmp_path / "plugins")
    script = textwrap.dedent(f"""
        import sys
        from qgis.core import QgsApplication, QgsVectorLayer
        QgsApplication.setPrefixPath("/usr", True)
        app = QgsApplication([], False)
        app.initQgis()
        sys.path.append("/usr/share/qgis/python/plugins")
        import qgis.utils
        from processing.core.Processing import Processing
        Processing.initialize()
        import processing
        sys.path.insert(0, {str(tmp_path / "plugins")!r})
        qgis.utils.plugin_paths = [{str(tmp_path / "plugins")!r}]
        assert qgis.utils.loadPlugin("bzspline_processing")
        assert qgis.utils.startProcessingPlugin("bzspline_processing")
        import bzspline_processing
        assert bzspline_processing.__file__.startswith({str(tmp_path)!r})
        p = QgsApplication.processingRegistry().providerById("bzspline")
        print(sorted(a.name() for a in p.algorithms()))
        layer = QgsVectorLayer("Polygon?crs=EPSG:3857", "x", "memory")
        from qgis.core import QgsFeature, QgsGeometry
        f = QgsFeature()
        f.setGeometry(QgsGeometry.fromWkt("POLYGON((0 0, 10 0, 10 10, 0 10, 0 0))"))
        layer.dataProvider().addFeatures([f])
        out = processing.run("bzspline:smoothcoverage", {{"INPUT": layer, "OUTPUT": "memory:"}})["OUTPUT"]
        print(out.featureCount(), len(list(list(out.getFeatures())[0].geometry().vertices())) > 5)
        qgis.utils.unloadPlugin("bzspline_processing")
        print(QgsApplication.processingRegistry().providerById("bzspline") is None)
        app.exitQgis()
    """)
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.strip().splitlines()[-3:]
    assert lines == [str(sorted(NAMES)), "1 True", "True"], done.stdout


def test_without_the_package_the_algorithms_say_how_to_install_it(monkeypatch):
    from bzspline_processing import provider as module

    monkeypatch.setitem(sys.modules, "bzspline.geo", None)
    message = module.package_problem()
    assert "pip install" in message and "OSGeo4W" in message and "numpy" in message
    alg = provider().algorithm("smoothcoverage").create()
    ok, why = alg.canExecute()
    assert not ok and why == message


def test_a_shapely_on_another_geos_than_the_loaded_one_is_refused():
    from bzspline_processing.provider import MIXED_GEOS, geos_problem, global_geos, package_problem

    assert geos_problem((3, 11, 1), (3, 11, 2)) is None
    assert geos_problem((3, 13, 1), None) is None
    assert geos_problem((3, 13, 1), (3, 11, 1)) == ("3.13.1", "3.11.1")
    assert "--no-binary shapely" in MIXED_GEOS
    # Python loads QGIS's modules privately: no GEOS is global here, and
    # whichever shapely this is, it answers with its own.
    assert global_geos() is None
    assert package_problem() is None
