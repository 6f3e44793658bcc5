//! What smoothing a whole document gives: a JSON value, or a TopoJSON
//! Topology with its smoothed arcs, written from them a feature (or a
//! position) at a time, so that a large output is never held as a tree of
//! JSON values (about 100 bytes a position).

use anyhow::{anyhow, Result};
use bzspline_geo::Arcs;
use serde_json::Value;

use super::job::Output;
use crate::topojson::{GeojsonFeatures, TopoDoc};

/// A smoothed document ([`super::job::Job::smooth_document`]).
pub enum Document {
    /// A GeoJSON or TopoJSON value.
    Value(Value),
    /// A Topology smoothed on its own arcs.
    Topology(Box<SmoothedTopology>),
}

/// A TopoJSON Topology smoothed on its own arcs, for output as TopoJSON or
/// as the GeoJSON features of its objects (or of one).
pub struct SmoothedTopology {
    pub(super) doc: TopoDoc,
    pub(super) arcs: Arcs,
    pub(super) object: Option<String>,
    pub(super) output: Output,
    pub(super) name: String,
}

impl SmoothedTopology {
    /// The output as GeoJSON features, for a layer file.
    ///
    /// # Errors
    ///
    /// An object asked for that the Topology lacks (checked when it was
    /// smoothed).
    pub fn features(&self) -> Result<GeojsonFeatures<'_>> {
        self.doc
            .geojson_features(&self.arcs, self.object.as_deref())
            .map_err(|e| anyhow!("{}: {e}", self.name))
    }

    /// Writes the output, compact: the Topology with the smoothed arcs when
    /// the output is TopoJSON, else the GeoJSON FeatureCollection of its
    /// objects; the same text as [`SmoothedTopology::into_value`] written
    /// whole.
    ///
    /// # Errors
    ///
    /// Write errors of `w`, and those of [`SmoothedTopology::features`].
    pub fn write(&self, w: impl std::io::Write) -> Result<()> {
        match self.output {
            Output::Topojson => self.doc.write_topojson(&self.arcs, w)?,
            _ => self.features()?.write_geojson(w)?,
        }
        Ok(())
    }

    /// The output as one JSON value.
    ///
    /// # Errors
    ///
    /// As [`SmoothedTopology::features`].
    pub fn into_value(self) -> Result<Value> {
        match self.output {
            Output::Topojson => Ok(self.doc.to_topojson(&self.arcs)),
            _ => self
                .doc
                .to_geojson(&self.arcs, self.object.as_deref())
                .map_err(|e| anyhow!("{}: {e}", self.name)),
        }
    }
}

impl Document {
    /// The document as one JSON value.
    ///
    /// # Errors
    ///
    /// As [`SmoothedTopology::into_value`].
    pub fn into_value(self) -> Result<Value> {
        match self {
            Document::Value(v) => Ok(v),
            Document::Topology(t) => t.into_value(),
        }
    }
}
