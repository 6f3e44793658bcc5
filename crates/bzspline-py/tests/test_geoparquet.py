"""GeoParquet files as geopandas and pyarrow write and read them, judged by
them: the command reads what geopandas writes (in longitude and latitude
and in a projected CRS) and smooths it exactly as it smooths the same
features as GeoJSON; geopandas reads what the command writes with its
columns, types and CRS, and the file's `geo` metadata is what GeoParquet
1.1 asks for."""

import json
import pathlib
import subprocess

import numpy as np
import pytest

geopandas = pytest.importorskip("geopandas")
pq = pytest.importorskip("pyarrow.parquet")
shapely = pytest.importorskip("shapely")

from test_defaults import ROOT, command  # noqa: E402

COUNTRIES = ROOT / "crates/bzspline-cli/tests/fixtures/countries.geojson"


def layer():
    """The countries with columns of several types."""
    doc = json.loads(COUNTRIES.read_text())
    gdf = geopandas.GeoDataFrame.from_features(doc["features"], crs="EPSG:4326")
    gdf["rank"] = np.arange(len(gdf), dtype="int64")
    gdf["share"] = np.linspace(0.25, 0.75, len(gdf))
    gdf["big"] = gdf["rank"] % 2 == 0
    return gdf


def smooth(*args):
    out = subprocess.run([command(), "smooth", *args], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out.stdout


def exactly(a, b):
    return all(shapely.equals_exact(x, y, tolerance=0) for x, y in zip(a, b))


@pytest.mark.parametrize("crs", ["EPSG:4326", "EPSG:3857"])
def test_what_geopandas_writes_is_smoothed_as_its_geojson(tmp_path, crs):
    gdf = layer().to_crs(crs)
    src = tmp_path / "in.parquet"
    gdf.to_parquet(src)
    geojson = tmp_path / "in.geojson"
    geojson.write_text(gdf.to_json(drop_id=True))
    tol = "0.01" if crs == "EPSG:4326" else "1000"
    from_parquet = json.loads(smooth(str(src), "--tolerance", tol))
    from_geojson = json.loads(smooth(str(geojson), "--tolerance", tol))
    a = [shapely.geometry.shape(f["geometry"]) for f in from_parquet["features"]]
    b = [shapely.geometry.shape(f["geometry"]) for f in from_geojson["features"]]
    assert len(a) == len(gdf) and exactly(a, b)
    assert [f["properties"]["name"] for f in from_parquet["features"]] == list(gdf["name"])
    # Written as GeoParquet: geopandas reads the columns, types and CRS.
    out = tmp_path / "out.parquet"
    smooth(str(src), "--tolerance", tol, "-o", str(out))
    back = geopandas.read_parquet(out)
    assert back.crs == gdf.crs
    assert list(back.columns) == ["geometry", "name", "rank", "share", "big"]
    for c in ["name", "rank", "share", "big"]:
        assert back[c].dtype == gdf[c].dtype, c
        assert back[c].tolist() == gdf[c].tolist(), c
    assert exactly(back.geometry, a)
    assert back.geometry.is_valid.all()


def test_the_geo_metadata_is_geoparquets(tmp_path):
    src = tmp_path / "in.geojson"
    src.write_text(COUNTRIES.read_text())
    out = tmp_path / "out.parquet"
    smooth(str(src), "--tolerance", "0.05", "-o", str(out))
    meta = pq.read_schema(out).metadata
    geo = json.loads(meta[b"geo"])
    assert geo["version"] == "1.1.0" and geo["primary_column"] == "geometry"
    col = geo["columns"]["geometry"]
    assert col["encoding"] == "WKB"
    assert "crs" not in col  # OGC:CRS84, GeoJSON's coordinates
    back = geopandas.read_parquet(out)
    assert sorted(col["geometry_types"]) == sorted(set(back.geom_type))
    assert np.allclose(col["bbox"], back.total_bounds, rtol=0, atol=0)
    assert back.crs.to_string() == "OGC:CRS84"


def test_a_parquet_file_without_geo_metadata_is_refused(tmp_path):
    pa = pytest.importorskip("pyarrow")
    plain = tmp_path / "plain.parquet"
    pq.write_table(pa.table({"a": [1, 2]}), plain)
    out = subprocess.run([command(), "smooth", str(plain), "-o", str(tmp_path / "o.parquet")],
                         capture_output=True, text=True)
    assert out.returncode == 1
    assert "plain.parquet" in out.stderr and "not a GeoParquet file" in out.stderr
    assert not (tmp_path / "o.parquet").exists()


def test_a_multi_column_projected_layer_keeps_its_crs_through_other_formats(tmp_path):
    gdf = layer().to_crs("EPSG:32633")
    src = tmp_path / "utm.parquet"
    gdf.to_parquet(src)
    gpkg = tmp_path / "utm.gpkg"
    smooth(str(src), "--tolerance", "5km", "-o", str(gpkg))
    back = tmp_path / "back.parquet"
    smooth(str(gpkg), "--tolerance", "5km", "-o", str(back))
    got = geopandas.read_parquet(back)
    assert got.crs.to_epsg() == 32633
    assert len(got) == len(gdf)
