//! The per-mode contributions of issue 9's mode bars do not allocate (a
//! counting global allocator; its own test binary, one test, so that no other
//! thread allocates meanwhile).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;
static ALLOCS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn mode_contributions_do_not_allocate() {
    let text = std::fs::read_to_string("presets/three_points.ron").unwrap();
    let scene = tirecontact::Scene::parse(&text, "three_points").unwrap();
    let mut sim = tirecontact::Simulation::new(&scene).unwrap();
    let mut c = vec![0.0; sim.num_modes()];
    for _ in 0..2000 {
        sim.step().unwrap();
    }
    let before = ALLOCS.load(Ordering::Relaxed);
    let mut sum = 0.0;
    for _ in 0..1000 {
        sim.step().unwrap();
        for i in 0..3 {
            sim.mode_displacement_m(i, &mut c);
            sum += c.iter().sum::<f64>();
        }
    }
    let allocs = ALLOCS.load(Ordering::Relaxed) - before;
    assert_eq!(allocs, 0, "{allocs} allocations");
    assert!(sum.is_finite());
}
