//! Generates the start-up guesses of `src/walk.rs` ([ours]; they only save shooting trials):
//! the seven unknowns (τ1, p, A, B, C, D0, D1) of steps 0, 1 and 2 over the grid of
//! `tests/walk.rs` (v 0.6–2.0 m/s × H 1.5–1.95 m, M = 23 H², default attributes), in body units
//! (torques / (M l1), lengths / l1), fitted by least squares as c0 + c1 F + c2 F² in the Froude
//! speed F = v / √(g l1): the step-0 values (`STEP0`) and the changes from step 0 to 1 and 1 to 2
//! (`CHANGES`); and the default walk's Jacobians at the end of its step-0 solves (`COLD_*`).
//! Prints the Rust constants, with the fits' largest residuals as comments. The walks start
//! every solve plainly (`Walker::without_startup_guesses`), so the output does not depend on the
//! constants it replaces: a rerun prints the same digits.
//!
//! `cargo run --release --example startup_fit`
use klaw::control::swing::Subphase;
use klaw::engine::walker::Walker;
use klaw::model::GRAVITY;
use klaw::{Attributes, Body, GaitRequest};
use nalgebra::{Matrix3, Vector3};

fn unknowns(step: &klaw::engine::walker::Step, body: &Body) -> [f64; 7] {
    let torque = body.mass * body.l1;
    let mut out = [
        step.stance.tau1 / torque,
        step.stance.p / body.l1,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ];
    for (sub, _) in &step.swing {
        match *sub {
            Subphase::Swing1 { hip, knee } => (out[2], out[3]) = (hip / torque, knee / torque),
            Subphase::Swing2 { knee, .. } => out[4] = knee / torque,
            Subphase::Swing3 { hip, ramp } => (out[5], out[6]) = (hip / torque, ramp / torque),
        }
    }
    out
}

/// Least-squares quadratic through (x, y): coefficients and the largest residual.
fn quadratic(points: &[(f64, f64)]) -> ([f64; 3], f64) {
    let (mut a, mut b) = (Matrix3::zeros(), Vector3::zeros());
    for &(x, y) in points {
        let row = Vector3::new(1.0, x, x * x);
        a += row * row.transpose();
        b += row * y;
    }
    let c = a.lu().solve(&b).expect("distinct speeds");
    let worst = points
        .iter()
        .map(|&(x, y)| (y - (c[0] + x * (c[1] + x * c[2]))).abs())
        .fold(0.0, f64::max);
    ([c[0], c[1], c[2]], worst)
}

fn main() {
    let attrs = Attributes::default();
    let names = ["τ1", "p", "A", "B", "C", "D0", "D1"];
    // per grid point: F and the unknowns of steps 0, 1, 2
    let mut rows: Vec<(f64, [[f64; 7]; 3])> = Vec::new();
    for h in [1.5, 1.65, 1.8, 1.95] {
        for i in 0..15 {
            let v = 0.6 + 0.1 * i as f64;
            let body = Body::standard(h, 23.0 * h * h).expect("grid body");
            let gait = GaitRequest {
                velocity: Some(v),
                ..Default::default()
            }
            .complete(&body, &attrs)
            .expect("grid gait");
            let mut walker = Walker::new(body, attrs.clone()).without_startup_guesses();
            let steps: Vec<_> = (0..3)
                .map(|_| walker.step(gait).expect("grid walks converge"))
                .collect();
            let u = [0, 1, 2].map(|k| unknowns(&steps[k], &body));
            rows.push((v / (GRAVITY * body.l1).sqrt(), u));
        }
    }
    let print = |name: &str, end: &str, value: &dyn Fn(&[[f64; 7]; 3], usize) -> f64| {
        println!("    // {name}");
        println!("    [");
        for (k, unknown) in names.iter().enumerate() {
            let pts: Vec<_> = rows.iter().map(|(f, u)| (*f, value(u, k))).collect();
            let (c, worst) = quadratic(&pts);
            println!(
                "        [{:.5e}, {:.5e}, {:.5e}], // {unknown}: largest residual {worst:.2e}",
                c[0], c[1], c[2]
            );
        }
        println!("    ]{end}");
    };
    println!("const STEP0: [[f64; 3]; 7] =");
    print("step 0", ";", &|u, k| u[0][k]);
    println!("const CHANGES: [[[f64; 3]; 7]; 2] = [");
    print("step 0 to 1", ",", &|u, k| u[1][k] - u[0][k]);
    print("step 1 to 2", ",", &|u, k| u[2][k] - u[1][k]);
    println!("];");

    // the default walk's Jacobians after step 0, in body units (residual units: stance θ1 in
    // rad and w in l1, swings in rad)
    let body = Body::standard(1.8, 80.0).expect("default body");
    let gait = GaitRequest {
        velocity: Some(1.4),
        ..Default::default()
    }
    .complete(&body, &attrs)
    .expect("default gait");
    let mut walker = Walker::new(body, attrs).without_startup_guesses();
    walker.step(gait).expect("the default walk converges");
    let (stance, swing1, swing2, swing3) = walker.memories();
    let (torque, l1) = (body.mass * body.l1, body.l1);
    let jacobian =
        |name: &str, m: Option<klaw::control::shooting::Memory2>, x: [f64; 2], r: [f64; 2]| {
            let j = m.expect("step 0 solved").jacobian;
            let e = |i: usize, k: usize| j[(i, k)] * x[k] / r[i];
            println!(
                "const {name}: [[f64; 2]; 2] = [[{:.5e}, {:.5e}], [{:.5e}, {:.5e}]];",
                e(0, 0),
                e(0, 1),
                e(1, 0),
                e(1, 1)
            );
        };
    jacobian("COLD_STANCE", stance, [torque, l1], [1.0, l1]);
    jacobian("COLD_SWING1", swing1, [torque; 2], [1.0; 2]);
    println!(
        "const COLD_SWING2_SLOPE: f64 = {:.5e};",
        swing2.expect("step 0 solved").slope * torque
    );
    jacobian("COLD_SWING3", swing3, [torque; 2], [1.0; 2]);
}
