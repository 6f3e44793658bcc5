//! The extension's allocator: the system's, asking Linux for transparent
//! huge pages on every block of 4 MiB or more, as numpy does for its arrays.
//!
//! A spline of a million knots writes 56 MB of fresh memory while it is
//! built; on 4 KiB pages that is 14,000 page faults, which cost more than the
//! arithmetic. With `madvise(MADV_HUGEPAGE)` the kernel maps the block in
//! 2 MiB pages where it can (the default `madvise` mode of transparent huge
//! pages); elsewhere the advice is ignored and nothing changes.

// A global allocator is unsafe code by definition; this module is the only
// place in the workspace that holds any.
#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};

/// Blocks this large get the advice (numpy's threshold).
const HUGE: usize = 4 << 20;

pub struct HugePages;

#[cfg(target_os = "linux")]
fn advise(p: *mut u8, size: usize) {
    if p.is_null() || size < HUGE {
        return;
    }
    const PAGE: usize = 4096;
    let start = (p as usize).next_multiple_of(PAGE);
    let end = (p as usize + size) & !(PAGE - 1);
    if end > start {
        // SAFETY: the range lies inside the block just allocated; the advice
        // changes how it is backed, not its contents.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise(_: *mut u8, _: usize) {}

// SAFETY: every call goes to `System`; `advise` only adds advice on memory
// `System` just returned.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        advise(p, layout.size());
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc_zeroed(layout) };
        advise(p, layout.size());
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) }
    }

    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let q = unsafe { System.realloc(p, layout, new_size) };
        advise(q, new_size);
        q
    }
}
