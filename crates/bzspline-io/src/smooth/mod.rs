//! A GeoJSON document smoothed: as one coverage ([`coverage`], the default:
//! shared borders smoothed once, valid polygons kept valid) or every line and
//! ring on its own ([`independent`]; also for positions with z).

pub mod coverage;
pub mod independent;
