//! Once a body's node tables are built, an evaluation allocates nothing (fixed rules, every
//! method path used by the default engine), counted by a wrapping global allocator.

mod interaction_support;

use interaction_support::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use surfgrav_interaction::{Body, InteractionOptions};
use surfgrav_potentials::{Ellipsoid as SolidEllipsoid, UniformDisk};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
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
        let cold = ALLOCATIONS.load(Ordering::Relaxed);
        let first = e.interact(a, &pose_a, b, pose_b).unwrap();
        // The first evaluation builds tables: the counter sees it.
        assert!(ALLOCATIONS.load(Ordering::Relaxed) > cold);
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        let again = e.interact(a, &pose_a, b, pose_b).unwrap();
        let after = ALLOCATIONS.load(Ordering::Relaxed);
        assert_eq!(
            after - before,
            0,
            "{} allocations in a warm evaluation",
            after - before
        );
        assert_eq!(first, again);
    }
}
