//! The extension's allocator: the system's, asking Linux for transparent
//! huge pages on every block of 4 MiB or more, as numpy does for its arrays,
//! and keeping a few freed blocks of that size for the next ones.
//!
//! A spline of a million knots writes 56 MB of fresh memory while it is
//! built; on 4 KiB pages that is 14,000 page faults, which cost more than the
//! arithmetic. With `madvise(MADV_HUGEPAGE)` the kernel maps the block in
//! 2 MiB pages where it can (the default `madvise` mode of transparent huge
//! pages); elsewhere the advice is ignored and nothing changes. Even so, the
//! C library hands blocks above 32 MiB straight back to the kernel when they
//! are freed, and the next spline's blocks arrive as new pages that the
//! kernel clears first: as long again as the construction itself. So freed
//! blocks of 4 MiB or more are kept (at most [`SLOTS`] of them and [`KEEP`]
//! bytes together) and handed out again for a request they hold without
//! wasting more than half of them.

// A global allocator is unsafe code by definition; this module is the only
// place in the workspace that holds any.
#![allow(unsafe_code)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::Mutex;

/// Blocks this large get the advice (numpy's threshold) and are kept.
const HUGE: usize = 4 << 20;

/// At most this many freed blocks are kept...
const SLOTS: usize = 16;

/// ...holding at most this many bytes together.
const KEEP: usize = 512 << 20;

/// Freed blocks kept for reuse: each its address, and the size (at most
/// what it holds) and alignment it was last allocated with.
struct Kept {
    blocks: [(usize, usize, usize); SLOTS],
    len: usize,
    bytes: usize,
}

impl Kept {
    const fn new() -> Self {
        Kept {
            blocks: [(0, 0, 0); SLOTS],
            len: 0,
            bytes: 0,
        }
    }

    /// The smallest kept block of alignment `align` that holds `size` bytes
    /// with at most half of it left over, taken out.
    fn take(&mut self, size: usize, align: usize) -> Option<usize> {
        let fits = |&(_, s, a): &(usize, usize, usize)| a == align && s >= size && s / 2 <= size;
        let (i, &(addr, s, _)) = self.blocks[..self.len]
            .iter()
            .enumerate()
            .filter(|(_, b)| fits(b))
            .min_by_key(|(_, &(_, s, _))| s)?;
        self.len -= 1;
        self.blocks[i] = self.blocks[self.len];
        self.bytes -= s;
        Some(addr)
    }

    /// Keeps the block at `addr` of `size` bytes and alignment `align`;
    /// `false` when there is no room (the caller frees it).
    fn put(&mut self, addr: usize, size: usize, align: usize) -> bool {
        if self.len == SLOTS || self.bytes + size > KEEP {
            return false;
        }
        self.blocks[self.len] = (addr, size, align);
        self.len += 1;
        self.bytes += size;
        true
    }
}

static KEPT: Mutex<Kept> = Mutex::new(Kept::new());

/// Runs `f` on the kept blocks unless another thread holds them (it never
/// waits: a child forked while a thread of its parent held them finds them
/// held for ever, and only stops reusing blocks).
fn with_kept<R>(f: impl FnOnce(&mut Kept) -> Option<R>) -> Option<R> {
    let mut kept = KEPT.try_lock().ok()?;
    f(&mut kept)
}

/// Whether a block of this layout is kept when freed and may be reused.
fn keepable(layout: Layout) -> bool {
    layout.size() >= HUGE
}

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

// SAFETY: every block comes from `System` and goes back to it. A kept block
// is one `System` returned and that was freed to us but not yet to
// `System`; it is handed out again only for a layout of the alignment it was
// allocated with and of at most the size, so it is valid for that layout,
// and `System` may later free or reallocate it under that layout: neither
// depends on the size given beyond copying at most that many bytes.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if keepable(layout) {
            if let Some(addr) = with_kept(|k| k.take(layout.size(), layout.align())) {
                return addr as *mut u8;
            }
        }
        let p = unsafe { System.alloc(layout) };
        advise(p, layout.size());
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if keepable(layout) {
            if let Some(addr) = with_kept(|k| k.take(layout.size(), layout.align())) {
                let p = addr as *mut u8;
                // SAFETY: the kept block holds at least `layout.size()` bytes.
                unsafe { p.write_bytes(0, layout.size()) };
                return p;
            }
        }
        let p = unsafe { System.alloc_zeroed(layout) };
        advise(p, layout.size());
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        if keepable(layout)
            && with_kept(|k| {
                k.put(p as usize, layout.size(), layout.align())
                    .then_some(())
            })
            .is_some()
        {
            return;
        }
        unsafe { System.dealloc(p, layout) }
    }

    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let q = unsafe { System.realloc(p, layout, new_size) };
        advise(q, new_size);
        q
    }
}
