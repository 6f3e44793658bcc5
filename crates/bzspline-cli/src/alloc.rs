//! The command's allocator: mimalloc, set to hand freed memory back to the
//! system at once.
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
//! Freed memory is handed back at once, not after those 10 ms: mimalloc
//! purges only when it next allocates or frees, and a step that computes for
//! a second or two without either kept the previous step's freed pages
//! resident under its own (its arenas, which hold the blocks of several MiB,
//! wait ten times longer still). On 10^6 polygons that put 5-40 MB on the
//! command's peak, varying from run to run; handing back at once costs about
//! a second of system time there (of 20).
#![allow(unsafe_code)]

use std::ffi::c_long;

use libmimalloc_sys::{mi_option_get, mi_option_set, mi_option_t};

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// mimalloc 2's options set, which libmimalloc-sys does not name: each
/// index, its default, and the value set. An option is set only when it
/// reads its default, so that the index names it (and a value set in the
/// environment, `MIMALLOC_PURGE_DELAY` or `MIMALLOC_ARENA_PURGE_MULT`, wins).
const SET: [(mi_option_t, c_long, c_long); 2] = [
    // `mi_option_purge_delay`: milliseconds before freed pages are purged.
    (15, 10, 0),
    // `mi_option_arena_purge_mult`: the arenas' multiple of that delay.
    (24, 10, 0),
];

/// Makes mimalloc hand freed memory back to the system at once.
pub fn hand_back_at_once() {
    for (option, default, value) in SET {
        // SAFETY: both functions take any option index (an unknown one is
        // ignored and reads 0) and may be called at any time, from any
        // thread.
        unsafe {
            if mi_option_get(option) == default {
                mi_option_set(option, value);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_indices_name_the_options_and_they_are_set() {
        // SAFETY: as in `hand_back_at_once`.
        let get = |option| unsafe { mi_option_get(option) };
        // An index past mimalloc's options would read 0 (run without the
        // options set in the environment).
        for (option, default, _) in SET {
            assert_eq!(get(option), default, "option {option}");
        }
        hand_back_at_once();
        for (option, _, value) in SET {
            assert_eq!(get(option), value, "option {option}");
        }
    }
}
