//! The command's allocator: mimalloc, set to hand large freed blocks back to
//! the system at once.
//!
//! mimalloc in place of the system allocator: smoothing a large coverage
//! frees the read phase's many small allocations and then asks for large
//! arrays; glibc keeps the freed holes resident, mimalloc reuses them
//! (BENCHMARKS.md, peak memory of `smooth`). Its version 2 (the crate's
//! `v2`) hands freed pages back to the system after 10 ms where version 3
//! waits a second: each step of `smooth` frees what the next no longer
//! needs, and with version 3 the command's peak on 10^6 polygons was 15-24 %
//! higher.
//!
//! Blocks of several MiB (the arrays of a coverage's steps) come from
//! mimalloc's arenas, which it purges ten times later than its pages, and
//! only when it next allocates from them: the arrays a step frees then
//! stayed resident under the next step's, which put 10-40 MB on the
//! command's peak on 10^6 polygons. With the arenas' delay set to none,
//! they are handed back when freed.
#![allow(unsafe_code)]

use std::ffi::c_long;

use libmimalloc_sys::{mi_option_get, mi_option_set, mi_option_t};

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// mimalloc 2's `mi_option_arena_purge_mult` (the multiple of the pages'
/// purge delay that arenas wait), which libmimalloc-sys does not name.
const ARENA_PURGE_MULT: mi_option_t = 24;

/// Its default: the option is set only when it reads so, so that the index
/// names it (and `MIMALLOC_ARENA_PURGE_MULT` in the environment wins).
const ARENA_PURGE_MULT_DEFAULT: c_long = 10;

/// Makes mimalloc purge freed arena blocks at once.
pub fn hand_back_at_once() {
    // SAFETY: both functions take any option index (an unknown one is
    // ignored and reads 0) and may be called at any time, from any thread.
    unsafe {
        if mi_option_get(ARENA_PURGE_MULT) == ARENA_PURGE_MULT_DEFAULT {
            mi_option_set(ARENA_PURGE_MULT, 0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_index_names_the_arena_option_and_it_is_set_to_none() {
        // SAFETY: as in `hand_back_at_once`.
        let get = || unsafe { mi_option_get(ARENA_PURGE_MULT) };
        // An index past mimalloc's options would read 0 (run without
        // MIMALLOC_ARENA_PURGE_MULT set).
        assert_eq!(get(), ARENA_PURGE_MULT_DEFAULT);
        hand_back_at_once();
        assert_eq!(get(), 0);
    }
}
