//! Once a body's node tables are built, an evaluation allocates nothing (fixed rules, every
//! method path used by the default engine), counted by a wrapping global allocator. The count
//! is per thread (the evaluations here run on the test's thread): the test harness's own
//! threads allocate at times of their own, which a process-wide counter saw as a flaky
//! "4 allocations in a warm evaluation" under load.

mod interaction_support;

use interaction_support::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use surfgrav_interaction::{Body, InteractionOptions};
use surfgrav_potentials::{Ellipsoid as SolidEllipsoid, UniformDisk};

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Allocations made so far by the calling thread.
fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // `try_with`: a thread being torn down has no slot any more; it is not counted.
        let _ = ALLOCATIONS.try_with(|count| count.set(count.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn warm_evaluations_do_not_allocate() {
    let pairs = [
        (
            paper_spheroid(),
            paper_spheroid(),
            pose([3.0, 0.0, 0.0], [0.0; 3]),
        ),
        (
            Body::ellipsoid(SolidEllipsoid::new(1.0, 0.6, 0.3, 1.0).unwrap()).unwrap(),
            Body::disk(UniformDisk::new(0.7, 1.0).unwrap()).unwrap(),
            pose([1.5, 1.2, 0.4], [0.3, 0.2, 0.1]),
        ),
    ];
    let mut e = engine(InteractionOptions::default());
    for (a, b, pose_b) in &pairs {
        let pose_a = pose([0.1, 0.0, 0.0], [0.0, 0.1, 0.0]);
        let cold = allocations();
        let first = e.interact(a, &pose_a, b, pose_b).unwrap();
        // The first evaluation builds tables: the counter sees it.
        assert!(allocations() > cold);
        let before = allocations();
        let again = e.interact(a, &pose_a, b, pose_b).unwrap();
        let after = allocations();
        assert_eq!(
            after - before,
            0,
            "{} allocations in a warm evaluation",
            after - before
        );
        assert_eq!(first, again);
    }
}
