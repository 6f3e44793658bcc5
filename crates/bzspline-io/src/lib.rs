//! The formats of [bzspline](https://github.com/bzspline/bzspline): what the
//! `bzspline` command, its editor server, the fuzz targets and the language
//! bindings read and write, defined once.
//!
//! - [`input`]: control points from CSV/TSV tables (named columns, dates),
//!   JSON arrays and `fit` objects, GeoJSON (every geometry checked first) and
//!   the paper's examples, each point knowing the file and line it came from.
//! - [`model`]: a fit (a spline y(x) or a curve) and its JSON and SVG forms,
//!   numbers written by the one formatter ([`bzspline::text::Shortest`]).
//! - [`distance`]: distances with units (`50m`, `2km`, `0.001deg`) and what
//!   they mean for geographic, projected or unknown coordinates.
//! - [`options`]: the options every entry point takes, parsed once (alphas
//!   as decimals or fractions).
//! - [`time`]: ISO 8601 dates and date-times as numbers and back.
//! - [`topojson`]: TopoJSON Topologies in (quantized or not) and out.
//! - [`layer`]: a GIS layer's features and schema (fields, CRS), shared by
//!   the file formats below so that a layer read from one is written to
//!   another.
//! - [`features`]: a layer's features held compactly (geo-types, values
//!   in the fields' order), and the features a layer writer takes.
//! - [`files`]: which reader and writer a layer file's format selects.
//! - [`wkt1`]: a CRS given as PROJJSON written as the WKT 1 of a `.prj`.
//! - `shp` (feature `shapefile`): ESRI Shapefiles in and out.
//! - `gpkg` (feature `geopackage`): GeoPackage feature layers in and out.
//! - `fgb` (feature `flatgeobuf`): FlatGeobuf files in and out.
//! - `geoparquet` (feature `geoparquet`): GeoParquet files in and out.
//! - [`smooth`]: a GeoJSON document smoothed as one coverage or ring by ring.
//! - [`api`]: the editor's `POST /api/fit` request and response.
//!
//! Errors are [`anyhow::Error`]s of one line that start with the source's
//! name (`pts.csv:4: ...`, `map.geojson: feature 2, coordinates[1]: ...`).

pub mod api;
pub mod distance;
pub mod features;
#[cfg(feature = "flatgeobuf")]
pub mod fgb;
pub mod files;
#[cfg(any(feature = "geopackage", feature = "flatgeobuf", feature = "geoparquet"))]
pub mod geom;
#[cfg(feature = "geoparquet")]
pub mod geoparquet;
#[cfg(feature = "geopackage")]
pub mod gpkg;
pub mod input;
pub mod layer;
pub mod model;
pub mod options;
#[cfg(feature = "shapefile")]
pub mod shp;
pub mod smooth;
pub mod time;
pub mod topojson;
pub mod wkt1;
