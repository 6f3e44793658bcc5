//! The threads a construction spreads a large system over (from 131,073
//! points on, the `bzspline` crate solves it in chunks side by side): one
//! pool per process, made again in a child after `fork`, whose copy of the
//! parent's pool has no threads, so that `multiprocessing` and dask's process
//! workers never wait on a pool that is not there. `RAYON_NUM_THREADS` sets
//! its size (default: the cores this process may use). The result does not
//! depend on the number of threads, bit for bit.

use rayon::{ThreadPool, ThreadPoolBuilder};
use std::sync::{Arc, Mutex, PoisonError};

/// The process that made the pool, and the pool.
static POOL: Mutex<Option<(u32, Arc<ThreadPool>)>> = Mutex::new(None);

/// Runs `op` with this process's pool as the current pool (on the calling
/// thread alone if no pool can be made).
pub(crate) fn install<R: Send>(op: impl FnOnce() -> R + Send) -> R {
    match pool() {
        Some(p) => p.install(op),
        None => op(),
    }
}

fn pool() -> Option<Arc<ThreadPool>> {
    let pid = std::process::id();
    let mut slot = POOL.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some((owner, p)) = slot.as_ref() {
        if *owner == pid {
            return Some(Arc::clone(p));
        }
    }
    // A pool inherited over fork: its threads stayed in the parent. It is
    // forgotten, not dropped, since dropping it would signal threads that
    // are not there.
    if let Some(inherited) = slot.take() {
        std::mem::forget(inherited);
    }
    let p = Arc::new(
        ThreadPoolBuilder::new()
            .thread_name(|i| format!("bzspline-{i}"))
            .build()
            .ok()?,
    );
    *slot = Some((pid, Arc::clone(&p)));
    Some(p)
}
