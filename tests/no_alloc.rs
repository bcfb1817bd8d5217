//! Zero heap allocations per step once a simulation is built, for both
//! contact schemes and through located impacts and releases (a counting
//! global allocator; this file is its own test binary). Only allocations
//! made by the measuring thread while its flag is up are counted, so the
//! test harness's other threads cannot make it fail.

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
fn allocations_in(f: impl FnOnce()) -> usize {
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

#[test]
fn steps_do_not_allocate() {
    // "Compliant": tread springs (override the scheme; landings and
    // releases located in the step as the "Located" scheme's are)
    for scheme in ["Located", "Paper", "Compliant"] {
        let text = std::fs::read_to_string("presets/three_points.ron")
            .unwrap()
            .replace(
                "contact_scheme: Located",
                &if scheme == "Compliant" {
                    "contact: Compliant(stiffness_n_m: [3e6])".to_string()
                } else {
                    format!("contact_scheme: {scheme}")
                },
            );
        let scene = tirecontact::Scene::parse(&text, "three_points").unwrap();
        let mut sim = tirecontact::Simulation::new(&scene).unwrap();
        // warm up: the first event sizes the scratch tables
        for _ in 0..5000 {
            sim.step().unwrap();
        }
        let events_before = sim.stats().events;
        let allocs = allocations_in(|| {
            for _ in 0..20000 {
                sim.step().unwrap();
            }
        });
        let events = sim.stats().events - events_before;
        assert_eq!(
            allocs, 0,
            "{scheme}: {allocs} allocations in 20000 steps ({events} events)"
        );
        if scheme == "Located" {
            assert!(
                events > 50,
                "the window must contain located events: {events}"
            );
        }
        if scheme == "Compliant" {
            assert!(
                events > 20,
                "the window must contain located landings and releases: {events}"
            );
        }
    }
}
