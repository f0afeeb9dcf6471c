//! Criterion benchmarks of non-rhythmic stepping (issue 15, item 1; H = 1.8 m, M = 80 kg, from
//! quiet standing):
//! - `nrs_advance`: one pose of a forward step (`NrsStep::advance`, t stepping through [0, 1]);
//!   the target is ≤ 1 µs a pose;
//! - `nrs_initialize_forward`: one forward step of 0.55 m precomputed (the engine's walking step
//!   of the same length simulated, the tables built);
//! - `nrs_initialize_lateral`: one lateral step of 0.4 m (no walking step);
//! - `scenario_table`: the table example (`examples/scenarios/table.toml`, 15.8 s of motion) run
//!   and sampled at 100 frames/s (`scenario::run`), to set against its duration.
//!
//! Run: `cargo bench --bench nrs -- --warm-up-time 1 --measurement-time 3`.
use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group};
use klaw::model::attributes::AttributeTable;
use klaw::model::body::Body;
use klaw::nrs::state::WalkerState;
use klaw::nrs::step::NrsStep;
use klaw::nrs::{Side, StepSpecs};

fn specs(side: Side, goal: [f64; 2], heading: f64) -> StepSpecs {
    StepSpecs {
        foot_position: goal,
        foot_direction: heading,
        side,
        swing_height_factor: 1.0,
        gaze_direction: None,
        foot_angles: None,
    }
}

fn standing() -> WalkerState {
    let body = Body::standard(1.8, 80.0).expect("a valid body");
    WalkerState::standing(body, AttributeTable::builtin().defaults(), [0.0, 0.0], 0.0)
}

fn nrs(c: &mut Criterion) {
    let s = standing();
    let forward = specs(Side::Right, [0.55, s.feet[0].flat[1]], 0.1);
    let lateral = specs(Side::Left, [0.0, s.feet[0].flat[1] - 0.4], 0.0);
    let step = NrsStep::initialize(&s, &forward, None).expect("a forward step");
    let mut i = 0u32;
    c.bench_function("nrs_advance", |b| {
        b.iter(|| {
            i = (i + 1) % 1000;
            black_box(&step).advance(black_box(i as f64 / 999.0))
        })
    });
    c.bench_function("nrs_initialize_forward", |b| {
        b.iter(|| NrsStep::initialize(black_box(&s), black_box(&forward), None).expect("steps"))
    });
    c.bench_function("nrs_initialize_lateral", |b| {
        b.iter(|| NrsStep::initialize(black_box(&s), black_box(&lateral), None).expect("steps"))
    });
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenarios/table.toml");
    let table = klaw::scenario::read_scenario(std::path::Path::new(path)).expect("the example");
    c.bench_function("scenario_table", |b| {
        b.iter(|| klaw::scenario::run(black_box(&table), 100.0).expect("runs"))
    });
}

criterion_group! {
    name = steps;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = nrs
}

/// `criterion_main!(steps)` with the CLI's memory policy first
/// ([`klaw::memory::keep_freed_memory`]), as `benches/walk.rs`.
fn main() {
    klaw::memory::keep_freed_memory();
    steps();
    Criterion::default().configure_from_args().final_summary();
}
