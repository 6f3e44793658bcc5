//! Python bindings: the extension module `bzspline._core`, which the
//! pure-Python package `bzspline` re-exports. No mathematics here: every
//! number comes from the `bzspline` crate; the modules convert arrays
//! ([`args`]), wrap the spline ([`spline`]) and the curve ([`curve`]) and
//! smooth geometries ([`geo`]), mapping errors to Python exceptions and
//! releasing the GIL around the work, which large inputs spread over the
//! cores ([`threads`]).

mod alloc;
mod args;
mod curve;
mod geo;
mod spare;
mod spline;
mod threads;

#[global_allocator]
static ALLOCATOR: alloc::HugePages = alloc::HugePages;

use pyo3::prelude::*;

pub(crate) use args::guard;
use curve::{smoothing_curve, Curve};
use spline::{_spline_from_parts, smoothing_spline, Spline};

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ALPHA_MIN", bzspline::ALPHA_MIN)?;
    m.add("ALPHA_MAX", bzspline::ALPHA_MAX)?;
    m.add("ROBUST_MIN_POINTS", bzspline::ROBUST_MIN_POINTS)?;
    m.add_class::<Spline>()?;
    m.add_class::<Curve>()?;
    m.add_function(wrap_pyfunction!(_spline_from_parts, m)?)?;
    m.add_function(wrap_pyfunction!(smoothing_spline, m)?)?;
    m.add_function(wrap_pyfunction!(smoothing_curve, m)?)?;
    m.add_function(wrap_pyfunction!(geo::_smooth_ragged, m)?)?;
    m.add_function(wrap_pyfunction!(geo::_default_tolerance, m)?)?;
    m.add_function(wrap_pyfunction!(geo::_nodes_of, m)?)?;
    m.add_function(wrap_pyfunction!(geo::_meetings, m)?)?;
    m.add_function(wrap_pyfunction!(geo::_across, m)?)?;
    m.add_class::<geo::Rounds>()?;
    m.add_function(wrap_pyfunction!(geo::_context_of, m)?)?;
    m.add_function(wrap_pyfunction!(geo::_around_of, m)?)?;
    m.add_function(wrap_pyfunction!(geo::_outer, m)?)?;
    m.add_function(wrap_pyfunction!(geo::_smooth_spans, m)?)?;
    m.add_function(wrap_pyfunction!(geo::_distances, m)?)?;
    Ok(())
}
