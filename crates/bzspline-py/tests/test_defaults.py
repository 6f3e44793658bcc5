"""Python and the command agree when every default is taken: the same points
give the same curve, bit for bit (the command and the server's protocol are
compared in crates/bzspline-cli/tests/cli.rs)."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import bzspline

ROOT = pathlib.Path(__file__).resolve().parents[3]


def command():
    given = os.environ.get("BZSPLINE_BIN")
    for p in [given, ROOT / "target/debug/bzspline", ROOT / "target/release/bzspline"]:
        if p and pathlib.Path(p).is_file():
            return str(p)
    pytest.skip("no bzspline binary (cargo build -p bzspline-cli, or set BZSPLINE_BIN)")


def fit(args, table):
    out = subprocess.run([command(), "fit", "--input-format", "csv", *args], input=table,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


PTS = [[0, 0], [1, 0], [1, 1], [0, 1], [3, 5]]
TABLE = "x,y\n" + "".join(f"{x},{y}\n" for x, y in PTS)


def test_a_curve_with_defaults_is_the_commands():
    c = bzspline.Curve(PTS)
    got = fit(["--curve"], TABLE)
    assert c.knots[-1] == 3 + np.sqrt(5)  # centripetal, as everywhere
    assert np.array_equal(c.knots, np.array(got["knots"]))
    assert np.array_equal(c.segments, np.array(got["segments"]))


def test_a_closed_curve_and_a_spline_with_defaults_are_the_commands():
    c = bzspline.Curve(PTS, closed=True)
    got = fit(["--closed"], TABLE)
    assert np.array_equal(c.knots, np.array(got["knots"]))
    assert np.array_equal(c.segments, np.array(got["segments"]))
    x, y = [0.0, 1.0, 2.0, 4.0], [0.0, 2.0, 1.0, 3.0]
    s = bzspline.Spline(x, y)
    got = fit([], "x,y\n" + "".join(f"{a},{b}\n" for a, b in zip(x, y)))
    assert np.array_equal(s.knot_values, np.array(got["knot_values"]))
    assert np.array_equal(s.segments, np.array(got["segments"]))


def test_each_geometry_on_its_own_is_the_commands_independent():
    # `coverage=False` and `bzspline smooth --independent` mean the same thing:
    # every geometry smoothed as a coverage of its own, with its own default
    # tolerance; the same positions, bit for bit.
    import shapely
    from shapely.geometry import shape

    import bzspline.geo

    path = ROOT / "crates/bzspline-cli/tests/fixtures/mosaic.geojson"
    features = json.loads(path.read_text())["features"]
    geoms = np.array([shape(f["geometry"]) for f in features], dtype=object)
    ours = bzspline.geo.smooth(geoms, coverage=False)
    out = subprocess.run([command(), "smooth", str(path), "--independent"],
                         capture_output=True, text=True, check=True)
    theirs = [shape(f["geometry"]) for f in json.loads(out.stdout)["features"]]
    assert len(theirs) == len(ours)
    for a, b in zip(ours, theirs):
        assert np.array_equal(shapely.get_coordinates(a), shapely.get_coordinates(b))
    # And differently from one coverage: the shared borders part.
    assert not all(np.array_equal(shapely.get_coordinates(a), shapely.get_coordinates(b))
                   for a, b in zip(ours, bzspline.geo.smooth(geoms)))


def test_keep_angle_with_z_keeps_the_corners_as_the_command_does():
    # The same line through the command and Python: right-angled corners, z
    # rising along it; the turning angle is planar, z is carried along.
    import shapely
    from shapely.geometry import shape

    import bzspline.geo

    path = ROOT / "crates/bzspline-cli/tests/fixtures/z_corners.geojson"
    line = shape(json.loads(path.read_text()))
    with pytest.warns(UserWarning, match="z"):
        ours = bzspline.geo.smooth(line, keep_angle=30)
    out = subprocess.run([command(), "smooth", str(path), "--keep-angle", "30"],
                         capture_output=True, text=True, check=True)
    theirs = np.array(json.loads(out.stdout)["coordinates"], dtype=float)
    got = shapely.get_coordinates(ours, include_z=True)
    assert np.array_equal(got, theirs)
    for corner in shapely.get_coordinates(line, include_z=True):
        assert (got == corner).all(axis=1).any(), corner
    with pytest.warns(UserWarning):
        cut = shapely.get_coordinates(bzspline.geo.smooth(line), include_z=True)
    assert not (cut == [1.0, 1.0, 3.0]).all(axis=1).any()


def test_metres_on_longitude_and_latitude_are_the_commands(tmp_path):
    # `tolerance="500m"` and `snap="2m"` on geometries in EPSG:4326 mean what
    # `bzspline smooth --tolerance 500m --snap 2m` means on GeoJSON (RFC 7946:
    # longitude and latitude): smoothing on the ellipsoid; the same positions.
    import shapely
    from shapely.geometry import mapping, shape

    import bzspline.geo

    path = ROOT / "crates/bzspline-cli/tests/fixtures/mosaic.geojson"
    doc = json.loads(path.read_text())
    # Moved north, where a degree of longitude is a quarter of a degree of
    # latitude on the ground, and across the antimeridian.
    geoms = shapely.transform(np.array([shape(f["geometry"]) for f in doc["features"]], dtype=object),
                              lambda c: c * [1.0, 0.5] + [178.5, 74.0])
    for f, g in zip(doc["features"], geoms):
        f["geometry"] = mapping(g)
    moved = tmp_path / "north.geojson"
    moved.write_text(json.dumps(doc))
    ours = bzspline.geo.smooth(geoms, tolerance="500m", snap="2m", crs="EPSG:4326")
    out = subprocess.run([command(), "smooth", str(moved), "--tolerance", "500m", "--snap", "2m"],
                         capture_output=True, text=True, check=True)
    theirs = [shape(f["geometry"]) for f in json.loads(out.stdout)["features"]]
    assert len(theirs) == len(ours)
    for a, b in zip(ours, theirs):
        assert np.array_equal(shapely.get_coordinates(a), shapely.get_coordinates(b))
    # Not what the same number in degrees gives.
    plain = bzspline.geo.smooth(geoms, tolerance=500 / 111_195, snap=2 / 111_195)
    assert not all(np.array_equal(shapely.get_coordinates(a), shapely.get_coordinates(b))
                   for a, b in zip(ours, plain))
