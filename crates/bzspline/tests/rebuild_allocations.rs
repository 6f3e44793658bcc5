//! What a rebuild in place allocates, counted by a global allocator that
//! wraps the system's: `Spline::rebuild` and `CurveBuilder::build_into` keep
//! their documented promises (nothing below 65,537 knots; only the chunked
//! solve's small plan and rows above).
//!
//! One test in this file, so that no other test's allocations are counted.

// A global allocator is unsafe code by definition; this one only counts.
#![allow(unsafe_code)]

use bzspline::{Alphas, CurveBuilder, Param, Spline};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

/// The system's allocator, counting allocations and their bytes.
struct Counting;

static CALLS: AtomicUsize = AtomicUsize::new(0);
static BYTES: AtomicUsize = AtomicUsize::new(0);
static LARGEST: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// This thread's allocations alone: the thread pool's own threads
    /// allocate now and then for themselves (crossbeam's epochs), whatever
    /// the calling thread does.
    static HERE: Cell<usize> = const { Cell::new(0) };
}

fn count(size: usize) {
    HERE.with(|c| c.set(c.get() + 1));
    CALLS.fetch_add(1, Relaxed);
    BYTES.fetch_add(size, Relaxed);
    LARGEST.fetch_max(size, Relaxed);
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count(layout.size());
        // SAFETY: the caller's contract is passed on unchanged.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count(layout.size());
        // SAFETY: as above.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count(new_size);
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Calls, bytes and the largest request of the allocations of every thread
/// while `f` runs.
fn counted(f: impl FnOnce()) -> (usize, usize, usize) {
    let (calls, bytes) = (CALLS.load(Relaxed), BYTES.load(Relaxed));
    LARGEST.store(0, Relaxed);
    f();
    (
        CALLS.load(Relaxed) - calls,
        BYTES.load(Relaxed) - bytes,
        LARGEST.load(Relaxed),
    )
}

/// The allocations `f` makes on this thread (where a build below 65,537
/// knots runs whole).
fn counted_here(f: impl FnOnce()) -> usize {
    let before = HERE.with(Cell::get);
    f();
    HERE.with(Cell::get) - before
}

/// Knots of uneven widths and values from a small generator.
fn data(n: usize, seed: u64) -> (Vec<f64>, Vec<f64>) {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut x = 0.0;
    let knots = (0..n)
        .map(|_| {
            x += 0.05 + next();
            x
        })
        .collect();
    let values = (0..n).map(|_| 10.0 * next() - 5.0).collect();
    (knots, values)
}

#[test]
fn rebuilds_in_place_allocate_what_their_docs_say() {
    // Up to 65,536 knots: nothing, for a spline and for a planar curve on
    // uniform parameters; the same size or smaller. Such a build runs whole
    // on the calling thread: its allocations are counted there.
    for (n, smaller) in [(1_000, 700), (65_536, 40_000)] {
        let (k, v) = data(n, 1);
        let (k2, v2) = data(n, 2);
        let mut s = Spline::new(&k, &v).expect("valid data");
        // Once, for what the first call sets up once a process (the thread
        // pool with the `rayon` feature).
        s.rebuild(&k, &v, Alphas::Uniform(0.5)).expect("valid data");
        for (knots, values) in [(&k2[..], &v2[..]), (&k[..smaller], &v[..smaller])] {
            let got = counted_here(|| {
                s.rebuild(knots, values, Alphas::Uniform(0.4))
                    .expect("valid data");
            });
            assert_eq!(got, 0, "spline of {} knots", knots.len());
        }
        let points: Vec<f64> = k.iter().zip(&v).flat_map(|(&x, &y)| [x, y]).collect();
        let mut c = CurveBuilder::new(&points, 2)
            .param(Param::Uniform)
            .build()
            .expect("valid points");
        let moved: Vec<f64> = points.iter().map(|p| p * 0.5 + 1.0).collect();
        let got = counted_here(|| {
            CurveBuilder::new(&moved, 2)
                .param(Param::Uniform)
                .build_into(&mut c)
                .expect("valid points");
        });
        assert_eq!(got, 0, "curve of {n} points");
    }
    // From 65,537 knots: the chunks' plan and overlapping rows only, under
    // 100 kB for a million knots (80 kB measured on two threads, 40 kB on
    // one), none of them near the size of an output.
    let n = 1_000_000;
    let (k, v) = data(n, 3);
    let (k2, v2) = data(n, 4);
    let mut s = Spline::new(&k, &v).expect("valid data");
    let got = counted(|| {
        s.rebuild(&k2, &v2, Alphas::Uniform(0.6))
            .expect("valid data");
    });
    assert!(
        got.1 <= 200_000 && got.2 <= 64 * 1024,
        "spline of {n} knots: {got:?}"
    );
    let fresh = Spline::build(&k2, &v2, Alphas::Uniform(0.6)).expect("valid data");
    assert!(s == fresh, "the rebuild differs from a fresh build");
}
