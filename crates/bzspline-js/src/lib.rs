//! The WebAssembly modules of the `bzspline` npm package, one per entry: with
//! the `curves` feature (the default; the `bzspline` entry) the method's
//! splines and curves ([`spline`], [`curve`]) and the Bezier pieces the d3
//! curves draw ([`paths`]); with `smoothing` (`bzspline/smoothing`) the
//! smoothing fits ([`smoothing`]); with `geo` (`bzspline/geo`) map smoothing
//! ([`geo`]).
//!
//! wasm-bindgen generates the JavaScript glue; the package's own modules
//! (`js/`) load it and add the d3 curve factories. Errors reach JavaScript as
//! `RangeError` (a value out of range, naming the index, as the library
//! words it) or `TypeError` (an argument of the wrong kind).

mod args;
#[cfg(feature = "curves")]
pub mod curve;
#[cfg(feature = "geo")]
pub mod geo;
#[cfg(feature = "curves")]
pub mod paths;
#[cfg(feature = "smoothing")]
pub mod smoothing;
#[cfg(feature = "curves")]
pub mod spline;

#[cfg(feature = "curves")]
pub use curve::Curve;
#[cfg(feature = "curves")]
pub use spline::Spline;

/// The bytes of memory the WebAssembly module holds (its linear memory,
/// which grows and never shrinks): for checking that objects are released.
#[wasm_bindgen::prelude::wasm_bindgen(js_name = memoryBytes)]
pub fn memory_bytes() -> f64 {
    #[cfg(target_arch = "wasm32")]
    {
        (core::arch::wasm32::memory_size(0) * 65536) as f64
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        0.0
    }
}
