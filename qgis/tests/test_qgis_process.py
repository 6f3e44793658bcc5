"""The algorithms run by ``qgis_process``, the way scripts and servers run
them: inside a QGIS executable, whose GEOS answers shapely's calls on Linux.
Its output is the same as ``processing.run``'s in this Python."""

import os
import shutil
import subprocess

import pytest
import shapely
from conftest import ROOT, features, run

# Debian's wrapper adds options of its own that 3.22's qgis_process refuses.
QGIS_PROCESS = shutil.which("qgis_process.bin") or shutil.which("qgis_process")


def qgis_geos():
    from qgis.core import Qgis

    return (Qgis.geosVersionMajor(), Qgis.geosVersionMinor())


def good_site():
    """Site-packages where shapely is built against QGIS's GEOS, as a QGIS
    executable needs: BZSPLINE_QGIS_SITE, or this Python's own where its
    shapely is."""
    import site

    given = os.environ.get("BZSPLINE_QGIS_SITE")
    if given:
        return [given]
    if tuple(shapely.geos_version[:2]) == qgis_geos():
        return site.getsitepackages()
    pytest.skip(f"shapely here is on GEOS {shapely.geos_version}, QGIS on {qgis_geos()}: "
                "set BZSPLINE_QGIS_SITE to site-packages with shapely built with --no-binary shapely")


def qgis_process(tmp_path, *args, site=None, check=True):
    """Runs ``qgis_process`` with the plugin from this clone and the packages
    of ``site`` (default: ``good_site()``); returns the completed process."""
    if QGIS_PROCESS is None:
        pytest.skip("no qgis_process: install Debian's qgis package")
    plugins = tmp_path / "plugins"
    plugins.mkdir(exist_ok=True)
    link = plugins / "bzspline_processing"
    if not link.exists():
        link.symlink_to(ROOT / "qgis" / "bzspline_processing")
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", QGIS_PLUGINPATH=str(plugins), HOME=str(tmp_path),
               PYTHONPATH=os.pathsep.join(site or good_site()))
    subprocess.run([QGIS_PROCESS, "plugins", "enable", "bzspline_processing"], env=env, capture_output=True,
                   text=True, timeout=300)
    done = subprocess.run([QGIS_PROCESS, *args], env=env, capture_output=True, text=True, timeout=600)
    done.output = done.stdout + done.stderr
    if check:
        assert done.returncode == 0, done.output
    return done


def test_a_shapely_wheel_on_another_geos_is_refused_with_the_way_out(atlas, tmp_path):
    import site

    if tuple(shapely.geos_version[:2]) == qgis_geos():
        pytest.skip("this shapely is on QGIS's GEOS")
    done = qgis_process(tmp_path, "run", "bzspline:smoothcoverage", "--", f"INPUT={atlas / 'states.geojson'}",
                        f"OUTPUT={tmp_path / 'out.gpkg'}", site=site.getsitepackages(), check=False)
    assert done.returncode != 0
    assert "was built with GEOS" in done.output and "--no-binary shapely" in done.output, done.output
    assert not (tmp_path / "out.gpkg").exists()


def test_the_provider_lists_its_algorithms(tmp_path):
    out = qgis_process(tmp_path, "list").output
    for name in ("smoothcoverage", "smoothindependently", "splinethroughpoints", "smoothtrack"):
        assert f"bzspline:{name}" in out


def test_smooth_coverage_in_qgis_process_is_processing_run_s(atlas, tmp_path):
    src = atlas / "states.geojson"
    there = tmp_path / "there.gpkg"
    # The form the plugin's README gives.
    out = qgis_process(tmp_path, "run", "bzspline:smoothcoverage", "--", f"INPUT={src}", "TOLERANCE=500",
                       "TOLERANCE_UNIT=0", f"OUTPUT={there}").output
    assert "geometries with M" not in out, out
    here = run("smoothcoverage", INPUT=str(src), TOLERANCE=500, TOLERANCE_UNIT=0,
               OUTPUT=str(tmp_path / "here.gpkg"))["OUTPUT"]
    a, b = features(there), features(here)
    assert len(a) == len(b) == 56
    given = [g for _, g in features(src)]
    for (pa, ga), (pb, gb), g in zip(a, b, given):
        assert pa == pb
        # Valid stays valid (us-atlas's Delaware and Oregon are not).
        assert shapely.is_valid(ga) or not shapely.is_valid(g), pa
        assert shapely.equals_exact(ga, gb, 0.0), pa


def test_a_track_in_qgis_process(tmp_path):
    # A noisy track written as a GeoJSON point layer with times.
    import json

    import numpy as np

    rng = np.random.default_rng(3)
    t = np.arange(60.0)
    # Longitude and latitude (GeoJSON's): a circle of 0.1 degrees near Kyiv.
    pts = np.c_[30.5 + 0.1 * np.cos(t / 20), 50.4 + 0.1 * np.sin(t / 20)] + rng.normal(0, 0.001, (60, 2))
    doc = {"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"t": float(s)}, "geometry": {"type": "Point", "coordinates": list(p)}}
        for s, p in zip(t, pts)]}
    src = tmp_path / "track.geojson"
    src.write_text(json.dumps(doc))
    there = tmp_path / "track.gpkg"
    out = qgis_process(tmp_path, "run", "bzspline:smoothtrack", "--", f"INPUT={src}", "TIME_FIELD=t",
                       f"OUTPUT={there}").output
    assert "chosen by GCV" in out, out
    [(attrs, line)] = features(there)
    assert attrs["points"] == 60 and attrs["lam"] > 0
    assert line.geom_type == "LineString" and len(line.coords) > 60
    # Smoothing pulls the line towards the circle the noise was added to.
    def off(xy):
        return np.abs(np.hypot(*(np.asarray(xy) - [30.5, 50.4]).T) - 0.1).mean()

    assert off(line.coords) < off(pts)
