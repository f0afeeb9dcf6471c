//! `NrsStep::advance` allocates nothing (issue 15, item 1): a counting global allocator (this
//! test binary's own, so it counts nothing of the other tests) sees no allocation during
//! 10 000 calls after `initialize`.
use std::alloc::{GlobalAlloc, Layout, System};
use std::hint::black_box;
use std::sync::atomic::{AtomicUsize, Ordering};

use klaw::model::attributes::AttributeTable;
use klaw::model::body::Body;
use klaw::nrs::state::WalkerState;
use klaw::nrs::step::NrsStep;
use klaw::nrs::{Side, StepSpecs};

/// The system allocator, counting allocations and reallocations.
struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn step(side: Side, goal: [f64; 2], heading: f64) -> NrsStep {
    let body = Body::standard(1.8, 80.0).unwrap();
    let s = WalkerState::standing(body, AttributeTable::builtin().defaults(), [0.0, 0.0], 0.0);
    let specs = StepSpecs {
        foot_position: goal,
        foot_direction: heading,
        side,
        swing_height_factor: 1.0,
        gaze_direction: None,
        foot_angles: None,
    };
    NrsStep::initialize(&s, &specs, None).unwrap()
}

/// The counter counts (a Vec allocates), and 10 000 `advance` calls of a forward and of a
/// lateral step, over all of t ∈ [0, 1] and beyond its ends, allocate 0 times.
#[test]
fn advance_allocates_nothing() {
    let steps = [
        step(Side::Right, [0.55, 0.05], 0.2),
        step(Side::Left, [0.0, -0.4], -0.3),
    ];
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    black_box(vec![1u8; 16]);
    assert!(
        ALLOCATIONS.load(Ordering::SeqCst) > before,
        "the counter counts"
    );
    let mut sum = 0.0;
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    for i in 0..10_000 {
        let t = -0.01 + 1.02 * i as f64 / 9_999.0;
        let lm = black_box(&steps[i % 2]).advance(black_box(t));
        sum += lm.pelvis[1];
    }
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    assert!(sum.is_finite());
    assert_eq!(
        after - before,
        0,
        "advance allocated {} times",
        after - before
    );
}
