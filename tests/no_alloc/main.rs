//! Zero heap allocations where the solver promises none: per step once a
//! simulation is built, and in the per-mode contributions of the mode bars.
//! A counting global allocator (so this is a test binary of its own) counts
//! only the allocations made by the measuring thread while its flag is up,
//! so the harness's other threads and tests running in parallel cannot
//! make a test fail.

mod modes;
mod recorders;
mod steps;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    /// Up while this thread measures: its allocations are counted.
    static MEASURING: Cell<bool> = const { Cell::new(false) };
    /// This thread's count (per thread: tests run in parallel).
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

fn count() {
    // `try_with`: no panic while the thread-locals are being torn down
    if MEASURING.try_with(Cell::get).unwrap_or(false) {
        let _ = ALLOCS.try_with(|n| n.set(n.get() + 1));
    }
}

/// Allocations made by this thread while `f` runs.
pub fn allocations_in(f: impl FnOnce()) -> usize {
    let before = ALLOCS.with(Cell::get);
    MEASURING.with(|m| m.set(true));
    f();
    MEASURING.with(|m| m.set(false));
    ALLOCS.with(Cell::get) - before
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[test]
fn the_counter_sees_an_allocation_of_this_thread_only() {
    // the check can fail: a Vec made while measuring is counted ...
    let n = allocations_in(|| {
        let v: Vec<u64> = std::hint::black_box(vec![1, 2, 3]);
        drop(v);
    });
    assert_eq!(n, 1);
    // ... one made by another thread at the same time is not
    let n = allocations_in(|| {
        std::thread::scope(|s| {
            let h = s.spawn(|| std::hint::black_box(vec![0u8; 64]).len());
            assert_eq!(h.join().unwrap_or(0), 64);
        })
    });
    // (spawning may allocate on this thread: only the worker's Vec must be excluded)
    let spawn_only = allocations_in(|| {
        std::thread::scope(|s| {
            let h = s.spawn(|| 64usize);
            assert_eq!(h.join().unwrap_or(0), 64);
        })
    });
    assert_eq!(n, spawn_only, "another thread's allocation was counted");
}

#[global_allocator]
static GLOBAL: Counting = Counting;
