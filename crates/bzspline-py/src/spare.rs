//! The memory of the last large spline that Python dropped, kept for the
//! next spline built of about its size.
//!
//! A new spline of a million knots must clear its 48 MB of pieces, knots and
//! values before the sweeps write them (safe Rust never hands out memory it
//! has not written), and that clearing costs about a quarter of the build. A spline
//! rebuilt in the memory of another ([`bzspline::Spline::rebuild`]) writes
//! over memory that is already its own: the build of a loop that drops each
//! spline before making the next costs what a rebuild costs. One spline is
//! kept, of [`MIN_KNOTS`] to [`MAX_KNOTS`] knots, and it is used only for a spline of
//! at least half its knots and at most its own, so that it never holds more
//! than twice the memory of the spline it becomes.

use std::sync::{Arc, LazyLock, Mutex, PoisonError};

/// Smaller splines are not kept: clearing them costs little.
const MIN_KNOTS: usize = 1 << 16;

/// Larger ones are not kept either (about 200 MB): their memory goes back
/// as the allocator's rules say.
const MAX_KNOTS: usize = 1 << 22;

/// The kept spline.
static SPARE: Mutex<Option<bzspline::Spline>> = Mutex::new(None);

/// A spline of two knots, to stand in a dropped object for the spline kept.
static STAND_IN: LazyLock<Option<Arc<bzspline::Spline>>> = LazyLock::new(|| {
    bzspline::Spline::new(&[0.0, 1.0], &[0.0, 0.0])
        .ok()
        .map(Arc::new)
});

/// Keeps the spline `slot` holds, when it is large and nothing else holds
/// it, and leaves a small stand-in in its place.
pub(crate) fn keep(slot: &mut Arc<bzspline::Spline>) {
    let n = slot.knots().len();
    if !(MIN_KNOTS..=MAX_KNOTS).contains(&n) || Arc::strong_count(slot) != 1 {
        return;
    }
    let Some(stand_in) = STAND_IN.as_ref() else {
        return;
    };
    let taken = std::mem::replace(slot, Arc::clone(stand_in));
    if let Ok(s) = Arc::try_unwrap(taken) {
        *SPARE.lock().unwrap_or_else(PoisonError::into_inner) = Some(s);
    }
}

/// The spline [`bzspline::Spline::build`] returns for the same arguments,
/// built in the kept spline's memory when that fits.
pub(crate) fn build(
    knots: &[f64],
    values: &[f64],
    alphas: bzspline::Alphas<'_>,
) -> Result<bzspline::Spline, bzspline::Error> {
    let n = knots.len();
    let fits = |s: &bzspline::Spline| (n..=2 * n).contains(&s.knots().len());
    let spare = {
        let mut slot = SPARE.lock().unwrap_or_else(PoisonError::into_inner);
        slot.take_if(|s| fits(s))
    };
    let Some(mut s) = spare else {
        return bzspline::Spline::build(knots, values, alphas);
    };
    match s.rebuild(knots, values, alphas) {
        Ok(()) => Ok(s),
        Err(e) => {
            // Unchanged: kept for the next.
            *SPARE.lock().unwrap_or_else(PoisonError::into_inner) = Some(s);
            Err(e)
        }
    }
}
