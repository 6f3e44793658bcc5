//! GIS layer files by format: the reader and the writer that a file's
//! format selects (ESRI Shapefile, GeoPackage, FlatGeobuf, GeoParquet),
//! each behind its cargo feature, so that the command and the bindings
//! choose in one place and a layer read from one format can be written to
//! another.

use std::path::Path;

use anyhow::{bail, Result};
use serde_json::Value;

use crate::features::Source;
use crate::input::InputFormat;
use crate::layer::{Layer, Schema};
use crate::smooth::job::Output;

/// Whether a format is a layer file read by [`read`] (rather than a text
/// document).
#[must_use]
pub fn is_layer(format: InputFormat) -> bool {
    matches!(
        format,
        InputFormat::Shapefile
            | InputFormat::Geopackage
            | InputFormat::Flatgeobuf
            | InputFormat::Geoparquet
    )
}

/// Whether an output is a layer file written by [`write()`].
#[must_use]
pub fn writes_layer(output: Output) -> bool {
    matches!(
        output,
        Output::Shapefile | Output::Geopackage | Output::Flatgeobuf | Output::Geoparquet
    )
}

/// What a format is called in messages.
#[must_use]
pub fn format_name(format: InputFormat) -> &'static str {
    match format {
        InputFormat::Shapefile => "a Shapefile",
        InputFormat::Geopackage => "a GeoPackage",
        InputFormat::Flatgeobuf => "a FlatGeobuf file",
        InputFormat::Geoparquet => "a GeoParquet file",
        InputFormat::Csv | InputFormat::Tsv => "a table",
        InputFormat::Json => "JSON",
        InputFormat::Geojson | InputFormat::Geojsonseq => "GeoJSON",
        InputFormat::Topojson => "TopoJSON",
    }
}

/// Reads the layer file at `path` in `format` (`layer` chooses a
/// GeoPackage's layer), no file larger than `max_bytes`.
///
/// # Errors
///
/// A format this build does not read (its cargo feature), `layer` for a
/// format without layers, and the format's reader's errors.
#[allow(unused_variables)]
pub fn read(
    path: &Path,
    format: InputFormat,
    layer: Option<&str>,
    max_bytes: u64,
) -> Result<Layer> {
    let name = path.display();
    if let (Some(l), false) = (layer, format == InputFormat::Geopackage) {
        bail!(
            "{name}: --layer {l:?} chooses a layer of a GeoPackage; this is {}",
            format_name(format)
        );
    }
    match format {
        #[cfg(feature = "shapefile")]
        InputFormat::Shapefile => crate::shp::read(path, max_bytes),
        #[cfg(feature = "geopackage")]
        InputFormat::Geopackage => crate::gpkg::read(path, layer, max_bytes),
        #[cfg(feature = "flatgeobuf")]
        InputFormat::Flatgeobuf => crate::fgb::read(path, max_bytes),
        #[cfg(feature = "geoparquet")]
        InputFormat::Geoparquet => crate::geoparquet::read(path, max_bytes),
        f if is_layer(f) => bail!(
            "{name}: this build reads no {} (a cargo feature of bzspline-io)",
            &format_name(f)[2..]
        ),
        f => bail!("{name}: {} is not a layer file", format_name(f)),
    }
}

/// A document as a FeatureCollection: a Feature as the collection of it, a
/// geometry as the collection of a feature without properties.
#[must_use]
pub fn as_collection(doc: &Value) -> std::borrow::Cow<'_, Value> {
    use std::borrow::Cow;
    match doc["type"].as_str() {
        Some("FeatureCollection") | None => Cow::Borrowed(doc),
        Some("Feature") => {
            Cow::Owned(serde_json::json!({"type": "FeatureCollection", "features": [doc]}))
        }
        Some(_) => Cow::Owned(
            serde_json::json!({"type": "FeatureCollection", "features": [
                {"type": "Feature", "properties": {}, "geometry": doc}
            ]}),
        ),
    }
}

/// Writes a GeoJSON document (a FeatureCollection, or a Feature or geometry
/// as a layer of one feature) as the layer file `path` in `output`'s
/// format, as [`write()`].
///
/// # Errors
///
/// A document that is not GeoJSON (a TopoJSON Topology), and [`write()`]'s.
pub fn write_document(
    path: &Path,
    output: Output,
    doc: &Value,
    schema: Option<&Schema>,
) -> Result<()> {
    let fc = as_collection(doc);
    let Some(features) = crate::features::of_collection(&fc) else {
        bail!(
            "{}: only GeoJSON features can be written as {}",
            path.display(),
            output.name()
        );
    };
    write(path, output, features, schema)
}

/// Writes features as the layer file `path` in `output`'s format, with
/// `schema` (the layer read) when given; every file is complete before it
/// replaces what was at `path`.
///
/// # Errors
///
/// A format this build does not write, and the format's writer's errors.
#[allow(unused_variables)]
pub fn write(
    path: &Path,
    output: Output,
    features: &dyn Source,
    schema: Option<&Schema>,
) -> Result<()> {
    let name = path.display();
    match output {
        #[cfg(feature = "shapefile")]
        Output::Shapefile => crate::shp::write_file(path, features, schema),
        #[cfg(feature = "geopackage")]
        Output::Geopackage => crate::gpkg::write(path, features, schema),
        #[cfg(feature = "flatgeobuf")]
        Output::Flatgeobuf => crate::fgb::write(path, features, schema),
        #[cfg(feature = "geoparquet")]
        Output::Geoparquet => crate::geoparquet::write(path, features, schema),
        o => bail!("{name}: this build writes no {o:?} (a cargo feature of bzspline-io)"),
    }
}
