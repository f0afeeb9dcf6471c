//! Criterion benchmarks of the walking simulation (H = 1.8 m, M = 80 kg, v = 1.4 m/s), the
//! walks run through the library's `Simulation` builder:
//! - `one_step`: a fresh 1-step walk (cold shooting start);
//! - `walk_10_steps`: simulation only;
//! - `walk_10_steps_with_frames`: simulation, then the engine's state frames sampled at
//!   100 frames/s;
//! - `walk_10_steps_frames_csv`: the same, then the frames written as CSV to a temporary file;
//! - `sweep_1000_walks` (group `sweep`): 1 000 walks of 10 steps, v = 0.6…1.99 m/s (250 values)
//!   × H = 1.5, 1.65, 1.8, 1.95 m (M = 23 H²), on the rayon pool (all cores), as `klaw sweep`
//!   runs them (`engine::walker::simulate` per point; the sweep's summary rows are not built).
//!
//! Short measurement windows keep the first group to about half a minute on two cores; the sweep
//! (≈ 1 s a run) takes its minimum of 10 samples, ≈ 30 s: skip it with
//! `cargo bench --bench walk -- 'walk_|one_step'` (criterion takes one filter, a regular
//! expression), or run it alone with `-- sweep`. Measured figures: docs/engine.md, "Engine".
use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group};
use klaw::engine::walker::simulate;
use klaw::{AttributeTable, Attributes, Body, Gait, GaitRequest, Simulation};
use rayon::prelude::*;

const FPS: f64 = 100.0;

fn gait(body: &Body, attrs: &Attributes, v: f64) -> Gait {
    GaitRequest {
        velocity: Some(v),
        ..GaitRequest::default()
    }
    .complete(body, attrs)
    .expect("the gait is valid")
}

fn one_step(c: &mut Criterion) {
    let one = Simulation::default().steps(1);
    c.bench_function("one_step", |b| {
        b.iter(|| black_box(&one).run().expect("walks"))
    });
}

fn ten_steps(c: &mut Criterion) {
    let ten = Simulation::default();
    c.bench_function("walk_10_steps", |b| {
        b.iter(|| black_box(&ten).run().expect("walks"))
    });
    c.bench_function("walk_10_steps_with_frames", |b| {
        b.iter(|| {
            let walk = black_box(&ten).run().expect("walks");
            walk.state_frames(black_box(FPS)).expect("valid fps")
        })
    });
    let dir = tempfile::tempdir().expect("a temporary directory");
    let path = dir.path().join("walk.csv");
    c.bench_function("walk_10_steps_frames_csv", |b| {
        b.iter(|| {
            let walk = black_box(&ten).run().expect("walks");
            walk.write_state(&path, FPS).expect("writes")
        })
    });
}

fn sweep(c: &mut Criterion) {
    let attrs = AttributeTable::builtin().defaults();
    let points: Vec<(Body, Gait)> = [1.5, 1.65, 1.8, 1.95]
        .iter()
        .flat_map(|&h| {
            let body = Body::standard(h, 23.0 * h * h).expect("a valid body");
            let attrs = &attrs;
            (0..250).map(move |i| (body, gait(&body, attrs, 0.6 + 0.0056 * i as f64)))
        })
        .collect();
    assert_eq!(points.len(), 1000);
    c.bench_function("sweep_1000_walks", |b| {
        b.iter(|| {
            points
                .par_iter()
                .map(|(body, g)| {
                    let walk = simulate(*body, attrs.clone(), &[*g; 10]).expect("walks");
                    walk.duration()
                })
                .sum::<f64>()
        })
    });
}

fn config(measurement_s: u64) -> Criterion {
    Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(measurement_s))
}

criterion_group! {
    name = walks;
    config = config(4);
    targets = one_step, ten_steps
}
criterion_group! {
    name = sweeps;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(30));
    targets = sweep
}
/// `criterion_main!(walks, sweeps)` with the CLI's memory policy first
/// ([`klaw::memory::keep_freed_memory`]), so the benches measure what `klaw bench` does.
fn main() {
    klaw::memory::keep_freed_memory();
    walks();
    sweeps();
    Criterion::default().configure_from_args().final_summary();
}
