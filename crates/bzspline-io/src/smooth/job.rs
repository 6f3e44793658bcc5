//! One smoothing job over whole documents: what `bzspline smooth` does to a
//! GeoJSON or TopoJSON document, a line of newline-delimited GeoJSON or a
//! table, and what the JavaScript package's `smooth` does to the same
//! document, by the same code. A [`Job`] chooses between one coverage, a
//! coverage for each geometry and (for z) ring by ring, writes GeoJSON or TopoJSON, and keeps the totals and
//! notes for a summary.

use anyhow::{anyhow, Context, Result};
use bzspline_geo::{SmoothOptions, Stats};
use geojson::{Feature, GeoJson, Geometry, GeometryValue, Position};
use serde_json::Value;

use super::collection::Collection;
use super::document::{Document, SmoothedTopology};
use super::{chains, coverage, default_tolerance, each_position, independent, positions};
use crate::distance::{Distance, Space, Unit};
use crate::features::{Features, Shape};
use crate::input::{self, Limits, Points};
use crate::layer::Crs;
use crate::topojson;

/// What a smoothed document is written as.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Output {
    /// A GeoJSON document (newline-delimited for newline-delimited input).
    #[default]
    Geojson,
    /// A TopoJSON Topology with the smoothed arcs.
    Topojson,
    /// An ESRI Shapefile: the job gives the GeoJSON features, which
    /// [`crate::files::write`] writes as the layer's files (as for the
    /// formats below).
    Shapefile,
    /// A GeoPackage of one layer.
    Geopackage,
    /// A FlatGeobuf file.
    Flatgeobuf,
    /// A GeoParquet file (WKB geometries).
    Geoparquet,
}

impl Output {
    /// The output a file name's extension names (`.topojson`, `.shp`,
    /// `.gpkg`, `.fgb`, `.parquet`, `.geoparquet`), GeoJSON for any other.
    #[must_use]
    pub fn of_path(path: &std::path::Path) -> Output {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("topojson") => Output::Topojson,
            Some("shp") => Output::Shapefile,
            Some("gpkg") => Output::Geopackage,
            Some("fgb") => Output::Flatgeobuf,
            Some("parquet" | "geoparquet") => Output::Geoparquet,
            _ => Output::Geojson,
        }
    }

    /// What the output is called in messages.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Output::Geopackage => "a GeoPackage",
            Output::Flatgeobuf => "a FlatGeobuf file",
            Output::Geoparquet => "a GeoParquet file",
            Output::Shapefile => "a Shapefile",
            Output::Geojson => "GeoJSON",
            Output::Topojson => "TopoJSON",
        }
    }

    /// The extension of a file of this output.
    #[must_use]
    pub fn extension(self) -> &'static str {
        match self {
            Output::Geopackage => "gpkg",
            Output::Flatgeobuf => "fgb",
            Output::Geoparquet => "parquet",
            Output::Shapefile => "shp",
            Output::Geojson => "geojson",
            Output::Topojson => "topojson",
        }
    }
}

/// Everything a job is asked to do.
#[derive(Debug, Clone, Default)]
pub struct Settings {
    /// The smoothing options (alpha, parametrisation, tolerance, keep-angle,
    /// through).
    pub options: SmoothOptions,
    /// Every feature's geometry on its own (a coverage of its own), not the
    /// document as one coverage.
    pub independent: bool,
    /// Join positions within this distance (and positions to edges) before
    /// building the coverage.
    pub snap: Option<f64>,
    /// The one object of a TopoJSON input written as GeoJSON (all of them
    /// when `None`).
    pub object: Option<String>,
    /// GeoJSON or TopoJSON out.
    pub output: Output,
    /// The name of the object a GeoJSON input becomes in TopoJSON output
    /// (`collection` when empty).
    pub object_name: String,
    /// Input limits.
    pub limits: Limits,
    /// The unit of `options.tolerance` ([`Unit::Data`]: the data's own).
    pub tolerance_unit: Unit,
    /// The unit of `snap`.
    pub snap_unit: Unit,
}

impl Settings {
    /// Checks the settings as a whole: every number in its range
    /// ([`SmoothOptions::validate`], [`bzspline_geo::check_snap`]), and no
    /// combination that cannot be
    /// done: every geometry on its own (`independent`) with a snap distance
    /// or TopoJSON output, which need one topology for the document.
    ///
    /// # Errors
    ///
    /// A sentence naming the option (as the command spells it) at fault.
    pub fn check(&self) -> Result<(), String> {
        self.options.validate().map_err(|e| e.to_string())?;
        if let Some(d) = self.snap {
            bzspline_geo::check_snap(d).map_err(|e| e.to_string())?;
        }
        if self.independent {
            if self.snap.is_some() {
                return Err(
                    "independent smooths every geometry on its own and takes no snap distance"
                        .into(),
                );
            }
            if self.output == Output::Topojson {
                return Err(
                    "--independent smooths every geometry on its own and has no topology to write as TopoJSON"
                        .into(),
                );
            }
        }
        Ok(())
    }
}

/// A smoothing job: settings, and the totals over what it smoothed.
#[derive(Debug)]
pub struct Job {
    settings: Settings,
    /// Where positions with z sent a document ring by ring.
    z_at: Option<String>,
    /// Positions cut to x, y, z (more than 3 numbers), and where the first was.
    cut: (usize, Option<String>),
    total: Stats,
    features: usize,
    /// The space of the layer being smoothed, when its file states it.
    space: Option<Space>,
}

impl Job {
    /// A job with nothing smoothed yet.
    pub fn new(settings: Settings) -> Self {
        Job {
            settings,
            z_at: None,
            cut: (0, None),
            total: Stats::default(),
            features: 0,
            space: None,
        }
    }

    /// The settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// Smooths a whole document (GeoJSON or a TopoJSON Topology) read from
    /// `name`.
    ///
    /// # Errors
    ///
    /// `name: ...` for a document that is not GeoJSON or TopoJSON, `name:
    /// feature i, ...: ...` for a geometry that cannot be smoothed.
    pub fn document(&mut self, name: &str, value: Value) -> Result<Value> {
        self.smooth_document(name, value)?.into_value()
    }

    /// As [`Job::document`], giving a TopoJSON Topology smoothed on its own
    /// arcs as the Topology and its arcs, to be written a feature at a time
    /// ([`SmoothedTopology::write`]) rather than as one JSON value.
    ///
    /// # Errors
    ///
    /// As [`Job::document`].
    pub fn smooth_document(&mut self, name: &str, value: Value) -> Result<Document> {
        if topojson::is_topology(&value) {
            self.topology(name, value)
        } else {
            let doc = self.checked(name, value)?;
            self.geojson(doc, name, true).map(Document::Value)
        }
    }

    /// Smooths the features of a layer file read from `name` whose
    /// coordinate system is `crs` (none stated: `None`), which says what a
    /// distance in metres or degrees is. Features in the plane are smoothed
    /// where they are (`Ok(None)`: every geometry replaced, unless the
    /// output is TopoJSON); others (positions with z) become the GeoJSON
    /// document given back.
    ///
    /// # Errors
    ///
    /// As [`Job::document`], and a distance that cannot be measured in the
    /// layer's coordinates.
    pub fn layer(
        &mut self,
        name: &str,
        features: &mut Features,
        crs: Option<&Crs>,
    ) -> Result<Option<Value>> {
        let space = match crs {
            None => Space::Unknown("the file states no coordinate system".into()),
            Some(c) => Space::of_crs(Some(c)),
        };
        if self.settings.output != Output::Topojson && features.is_plane() {
            return self.plane(name, features, space).map(|()| None);
        }
        self.space = Some(space);
        let out = self.document(name, features.to_value());
        self.space = None;
        out.map(Some)
    }

    /// Smooths features in the plane where they are, as one coverage or
    /// each geometry on its own.
    fn plane(&mut self, name: &str, features: &mut Features, space: Space) -> Result<()> {
        self.features += features.len();
        let (lib, snap) = self.resolved(name, || space)?;
        let shapes = features.take_shapes();
        let empty =
            || geo_types::Geometry::GeometryCollection(geo_types::GeometryCollection(vec![]));
        let had: Vec<bool> = shapes.iter().map(|s| !matches!(s, Shape::Null)).collect();
        let none = empty();
        self.check_longest(
            name,
            shapes.iter().map(|s| match s {
                Shape::Plane(g) => &**g,
                _ => &none,
            }),
        )?;
        // Taken one at a time: a coverage lets go of each geometry's
        // positions as soon as it holds them.
        let geoms = shapes.into_iter().map(|s| match s {
            Shape::Plane(g) => *g,
            _ => empty(),
        });
        if self.settings.independent {
            let out = self.smooth_each(name, geoms.collect(), &lib)?;
            let shapes = out
                .into_iter()
                .zip(had)
                .map(|(g, had)| match had {
                    true => Shape::Plane(Box::new(g)),
                    false => Shape::Null,
                })
                .collect();
            features.put_shapes(shapes);
        } else {
            let (assembled, stats) = self.smooth_assembled(name, geoms, &lib, snap)?;
            self.total += &stats;
            features.put_assembled(assembled, had);
        }
        Ok(())
    }

    /// The document `text` read one feature at a time when it is a
    /// FeatureCollection in the plane ([`Collection::read`]) and the output
    /// is not TopoJSON, for [`Job::collection`]; `None` for a document
    /// [`Job::document`] must take.
    #[must_use]
    pub fn read_collection(&self, text: &str) -> Option<Collection> {
        if self.settings.output == Output::Topojson {
            return None;
        }
        Collection::read(text)
    }

    /// [`Job::read_collection`] from a reader ([`Collection::read_from`]),
    /// the text never held whole.
    #[must_use]
    pub fn read_collection_from(&self, reader: impl std::io::BufRead) -> Option<Collection> {
        if self.settings.output == Output::Topojson {
            return None;
        }
        Collection::read_from(reader)
    }

    /// [`Job::read_collection_from`] the file at `path`, through a 64 KiB
    /// buffer, when it opens and is within the settings' `max_bytes`;
    /// `None` otherwise, for the whole text to be read and say what is wrong.
    #[must_use]
    pub fn read_collection_file(&self, path: &std::path::Path) -> Option<Collection> {
        let file = std::fs::File::open(path).ok()?;
        let size = file.metadata().ok()?.len();
        if size > self.settings.limits.max_bytes {
            return None;
        }
        self.read_collection_from(std::io::BufReader::with_capacity(1 << 16, file))
    }

    /// Smooths a FeatureCollection read from `name` by
    /// [`Job::read_collection`] where it is: what [`Job::document`] gives
    /// for its text.
    ///
    /// # Errors
    ///
    /// As [`Job::document`] for a geometry that cannot be smoothed.
    pub fn collection(&mut self, name: &str, c: &mut Collection) -> Result<()> {
        self.features += c.len();
        let geoms = c.take_geometries();
        let (lib, snap) = self.resolved(name, || {
            Space::of_lonlat_bounds(coverage::bounds(&geoms), "it")
        })?;
        self.check_longest(name, &geoms)?;
        if self.settings.independent {
            let out = self.smooth_each(name, geoms, &lib)?;
            c.put_geometries(out);
        } else {
            let (assembled, stats) = self.smooth_assembled(name, geoms, &lib, snap)?;
            self.total += &stats;
            c.put_assembled(assembled);
        }
        Ok(())
    }

    /// Refuses a line or ring longer than the settings allow among the
    /// geometries of `name`, geometry i feature i.
    fn check_longest<'a>(
        &self,
        name: &str,
        geoms: impl IntoIterator<Item = &'a geo_types::Geometry<f64>>,
    ) -> Result<()> {
        coverage::check_longest(geoms, self.settings.limits.max_points, &feature_of(name))
    }

    /// Smooths geometries in the plane, geometry i feature i of `name`
    /// (checked by [`Job::check_longest`]), each on its own
    /// (`--independent`), adding to the totals.
    fn smooth_each(
        &mut self,
        name: &str,
        geoms: Vec<geo_types::Geometry<f64>>,
        lib: &SmoothOptions,
    ) -> Result<Vec<geo_types::Geometry<f64>>> {
        let (out, stats) = coverage::smooth_apart(geoms, lib, name, &feature_of(name))?;
        self.total += &stats;
        Ok(out)
    }

    /// Smooths geometries in the plane as one coverage, geometry i feature
    /// i of `name` (checked by [`Job::check_longest`]), each smoothed
    /// geometry put together as it is written.
    fn smooth_assembled(
        &self,
        name: &str,
        geoms: impl IntoIterator<Item = geo_types::Geometry<f64>>,
        lib: &SmoothOptions,
        snap: Option<f64>,
    ) -> Result<(bzspline_geo::Assembled, Stats)> {
        coverage::smooth_into_assembled(geoms, lib, snap, name, &feature_of(name))
    }

    /// The options and snap distance for data in `space` (found by `space`
    /// when a distance has a unit): distances with units resolved.
    fn resolved(
        &self,
        where_: &str,
        space: impl FnOnce() -> Space,
    ) -> Result<(SmoothOptions, Option<f64>)> {
        let s = &self.settings;
        let mut opts = s.options.clone();
        if s.tolerance_unit == Unit::Data && s.snap_unit == Unit::Data {
            return Ok((opts, s.snap));
        }
        let space = self.space.clone().unwrap_or_else(space);
        if let Some(t) = opts.tolerance {
            let d = Distance {
                value: t,
                unit: s.tolerance_unit,
            };
            let (v, frame) = space
                .resolve(d)
                .map_err(|e| anyhow!("{where_}: the tolerance {e}"))?;
            opts.tolerance = Some(v);
            opts.frame = frame;
        }
        let snap = match s.snap {
            Some(v) => Some(
                space
                    .resolve_snap(Distance {
                        value: v,
                        unit: s.snap_unit,
                    })
                    .map_err(|e| anyhow!("{where_}: the snap distance {e}"))?,
            ),
            None => None,
        };
        Ok((opts, snap))
    }

    /// Smooths the text of one line of newline-delimited GeoJSON (RFC 8142
    /// record separators accepted); `None` for a blank line. `here` is
    /// `FILE:LINE`.
    ///
    /// # Errors
    ///
    /// `here: invalid JSON: ...` and the errors of [`Job::document`].
    pub fn line(&mut self, here: &str, text: &str) -> Result<Option<Value>> {
        let text = text.trim_matches(|c: char| c.is_whitespace() || c == '\u{1e}');
        if text.is_empty() {
            return Ok(None);
        }
        let value: Value =
            serde_json::from_str(text).map_err(|e| anyhow!("{here}: invalid JSON: {e}"))?;
        let doc = self.checked(here, value)?;
        self.geojson(doc, here, false).map(Some)
    }

    /// Smooths a table of points as one LineString (its rows are the
    /// vertices), a Feature with the table's name as property `source`.
    ///
    /// # Errors
    ///
    /// A table of other than 2 or 3 columns; the errors of [`Job::document`].
    pub fn table(&mut self, points: &Points) -> Result<Value> {
        input::check_columns(points, &[2, 3], "2 or 3 coordinates")?;
        let line: Vec<Position> = points.rows().map(|r| Position::from(r.to_vec())).collect();
        let mut feature = Feature::from(Geometry::new(GeometryValue::LineString {
            coordinates: line,
        }));
        feature.set_property("source", points.source.clone());
        self.space = Some(Space::Unknown("a table states no coordinate system".into()));
        let out = self.geojson(GeoJson::Feature(feature), &points.source, false);
        self.space = None;
        out
    }

    /// The notes for standard error once the output is written: positions
    /// cut to x, y, z, and a document smoothed ring by ring for its z.
    pub fn notes(&self) -> Vec<String> {
        let mut notes = Vec::new();
        if let (n @ 1.., Some(at)) = &self.cut {
            notes.push(input::cut_note(at, *n));
        }
        if let Some(at) = &self.z_at {
            notes.push(format!(
                "{at}: positions with z: smoothed ring by ring (the coverage's topology is planar)"
            ));
        }
        notes
    }

    /// The totals over everything smoothed so far.
    pub fn stats(&self) -> &Stats {
        &self.total
    }

    /// A GeoJSON document checked ([`input::to_geojson`]) and converted;
    /// positions cut to x, y, z are counted for the note.
    fn checked(&mut self, where_: &str, value: Value) -> Result<GeoJson> {
        let (doc, cut) = input::to_geojson(where_, value)?;
        if cut > 0 {
            self.cut.0 += cut;
            self.cut.1.get_or_insert_with(|| where_.to_owned());
        }
        Ok(doc)
    }

    /// Smooths one GeoJSON document and gives the output document.
    fn geojson(&mut self, doc: GeoJson, where_: &str, number_single: bool) -> Result<Value> {
        self.features += match &doc {
            GeoJson::FeatureCollection(fc) => fc.features.len(),
            _ => 1,
        };
        let z = coverage::document_has_z(&doc);
        let (lib, snap) = self.resolved(where_, || {
            let mut b = [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ];
            each_position(&doc, &mut |p| {
                if p.len() >= 2 {
                    b = [
                        b[0].min(p[0]),
                        b[1].min(p[1]),
                        b[2].max(p[0]),
                        b[3].max(p[1]),
                    ];
                }
            });
            Space::of_lonlat_bounds(b, "it")
        })?;
        let lib = &lib;
        if z {
            // Curves in space, ring by ring: the coverage's topology is planar.
            if !self.settings.independent && number_single && self.z_at.is_none() {
                self.z_at = Some(where_.to_owned());
            }
            let tolerance = lib
                .tolerance
                .unwrap_or_else(|| lib.default_tolerance_from(default_tolerance(&doc)));
            let opts = lib.clone().tolerance(tolerance);
            let max = self.settings.limits.max_points;
            let positions_in = positions(&doc);
            let (rings, lines) = chains(&doc);
            let out = independent::smooth_document(doc, &opts, max, where_, number_single)?;
            let mut s = Stats::default();
            s.rings = rings;
            s.lines = lines;
            s.positions_in = positions_in;
            s.positions_out = positions(&out);
            s.tolerance = tolerance;
            self.total += &s;
            return serde_json::to_value(&out).context("formatting GeoJSON");
        }
        if self.settings.independent {
            let limit = self.settings.limits.max_points;
            let (out, s) = coverage::smooth_each(doc, lib, limit, where_, number_single)?;
            self.total += &s;
            return serde_json::to_value(&out).context("formatting GeoJSON");
        }
        let s = coverage::smooth_document(
            doc,
            lib,
            snap,
            self.settings.limits.max_points,
            where_,
            number_single,
        )?;
        self.total += &s.stats;
        match self.settings.output {
            Output::Topojson => Ok(topojson::from_features(
                self.object_name(),
                &coverage::features(&s.doc),
                s.coverage.topology(),
                &s.arcs,
            )),
            _ => serde_json::to_value(&s.doc).context("formatting GeoJSON"),
        }
    }

    fn object_name(&self) -> &str {
        match self.settings.object_name.as_str() {
            "" => "collection",
            name => name,
        }
    }

    /// Smooths a TopoJSON Topology on its own arcs (or, with a snap distance
    /// or ring by ring, as the GeoJSON of its objects).
    fn topology(&mut self, name: &str, value: Value) -> Result<Document> {
        let topo = topojson::read(name, value)?;
        let object = self.settings.object.clone();
        if self.settings.independent || self.settings.snap.is_some() {
            let fc = topo
                .to_geojson(topo.topology.arcs(), object.as_deref())
                .map_err(|e| anyhow!("{name}: {e}"))?;
            let doc = self.checked(name, fc)?;
            return self.geojson(doc, name, true).map(Document::Value);
        }
        let (lib, _) = self.resolved(name, || {
            let mut b = [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ];
            for c in topo.topology.arcs().iter().flatten() {
                b = [b[0].min(c.x), b[1].min(c.y), b[2].max(c.x), b[3].max(c.y)];
            }
            Space::of_lonlat_bounds(b, "it")
        })?;
        let s = topo
            .topology
            .smooth(&lib)
            .map_err(|e| anyhow!("{name}: {}", topo.describe(&e)))?;
        self.features += topo.features;
        self.total += &s.stats;
        let out = SmoothedTopology {
            doc: topo,
            arcs: s.arcs,
            object,
            output: self.settings.output,
            name: name.to_owned(),
        };
        if out.output != Output::Topojson {
            // An object that is not there is named now, not when written.
            out.features()?;
        }
        Ok(Document::Topology(Box::new(out)))
    }

    /// The summary `bzspline smooth` prints on standard error.
    pub fn summary(&self) -> String {
        let t = &self.total;
        let mut s = format!(
            "smooth: {} features, {} rings, {} lines",
            self.features, t.rings, t.lines
        );
        if t.arcs > 0 {
            s += &format!(
                "; {} arcs ({} shared, {} not, {} closed)",
                t.arcs,
                t.shared_arcs,
                t.arcs - t.shared_arcs,
                t.closed_arcs
            );
        }
        let tolerance = match (self.settings.options.tolerance, self.settings.independent) {
            (Some(t), _) => Distance {
                value: t,
                unit: self.settings.tolerance_unit,
            }
            .to_string(),
            (None, false) => format!(
                "{} (the default: 1e-4 of the extent's diagonal)",
                t.tolerance
            ),
            (None, true) => "each geometry's default (1e-4 of its extent's diagonal)".to_owned(),
        };
        s += &format!(
            "\n  positions {} -> {}; tolerance {tolerance}\n",
            t.positions_in, t.positions_out,
        );
        if !self.settings.independent {
            s += &format!(
                "  refined {} legs ({} kept as original edges) in {} rounds; {} pairs of edges already met in the input (left as they were)\n",
                t.refined_legs, t.straight_legs, t.rounds, t.input_conflicts
            );
        }
        if t.area_in > 0.0 {
            s += &format!(
                "  polygon area {:+.4} %\n",
                100.0 * (t.area_out - t.area_in) / t.area_in
            );
        }
        s
    }
}

/// How errors name geometry i of `name`: its feature i.
fn feature_of(name: &str) -> impl Fn(usize) -> String + '_ {
    move |i| format!("{name}: feature {i}")
}
