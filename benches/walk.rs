//! Criterion benchmarks of the walking simulation (H = 1.8 m, M = 80 kg, v = 1.4 m/s):
//! `one_step` (a fresh 1-step walk), `walk_10_steps` (simulation only) and
//! `walk_10_steps_with_frames` (simulation, then frames sampled at 100 frames/s).
//! Short measurement windows keep `cargo bench` to well under two minutes on two cores.
use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use klaw::walk::simulate;
use klaw::{AttributeTable, Attributes, Body, Gait, GaitRequest};

const HEIGHT: f64 = 1.8;
const MASS: f64 = 80.0;
const VELOCITY: f64 = 1.4;
const FPS: f64 = 100.0;

fn setup() -> (Body, Attributes, Gait) {
    let body = Body::standard(HEIGHT, MASS).expect("the default body is valid");
    let attrs = AttributeTable::builtin().defaults();
    let gait = GaitRequest {
        velocity: Some(VELOCITY),
        ..GaitRequest::default()
    }
    .complete(&body, &attrs)
    .expect("the default gait is valid");
    (body, attrs, gait)
}

fn one_step(c: &mut Criterion) {
    let (body, attrs, gait) = setup();
    let one = [gait];
    c.bench_function("one_step", |b| {
        b.iter(|| simulate(black_box(body), attrs.clone(), black_box(&one)).expect("walks"))
    });
}

fn ten_steps(c: &mut Criterion) {
    let (body, attrs, gait) = setup();
    let ten = [gait; 10];
    c.bench_function("walk_10_steps", |b| {
        b.iter(|| simulate(black_box(body), attrs.clone(), black_box(&ten)).expect("walks"))
    });
    c.bench_function("walk_10_steps_with_frames", |b| {
        b.iter(|| {
            let walk = simulate(black_box(body), attrs.clone(), black_box(&ten)).expect("walks");
            walk.frames(black_box(FPS))
        })
    });
}

fn config(measurement_s: u64) -> Criterion {
    Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(measurement_s))
}

// a 10-step walk takes ≈ 25 ms: criterion's 20 linear samples need 210 of them (≈ 5.5 s), so
// those benchmarks get a longer window than the 5 ms single step
criterion_group! {
    name = short;
    config = config(5);
    targets = one_step
}
criterion_group! {
    name = long;
    config = config(8);
    targets = ten_steps
}
criterion_main!(short, long);
