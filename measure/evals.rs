//! Cost and accuracy figures of the engine (docs/engine.md, "What was measured"):
//! right-hand-side evaluations and shooting trials per step of the default walk, the same over
//! the 60-walk grid of tests/walk.rs with the worst end-condition and step-length errors, and the
//! residual noise of the stance shooting (the deviation of r(τ1 + δ) from its secant line).
//! `cargo run --release --example evals`
use klaw::control::stance::StanceRun;
use klaw::engine::walker as walk;
use klaw::*;

fn gait(body: &Body, v: f64) -> Gait {
    GaitRequest {
        velocity: Some(v),
        ..Default::default()
    }
    .complete(body, &Attributes::default())
    .unwrap()
}

fn main() {
    let attrs = Attributes::default();
    let body = Body::standard(1.8, 80.0).unwrap();
    let w = walk::simulate(body, attrs.clone(), &[gait(&body, 1.4); 10]).unwrap();
    println!(
        "default walk: step, RHS evaluations, trials per solve (stance, swing1, swing2, swing3)"
    );
    let mut total = 0;
    for s in &w.steps {
        let r = &s.report;
        total += r.rhs_evaluations;
        let it: Vec<usize> = r.solves.iter().map(|so| so.report.iterations).collect();
        println!("  {} {:6} {:?}", s.index, r.rhs_evaluations, it);
    }
    let rhythmic: u64 = w.steps[3..].iter().map(|s| s.report.rhs_evaluations).sum();
    let rtrials: usize = w.steps[3..]
        .iter()
        .flat_map(|s| s.report.solves.iter().map(|so| so.report.iterations))
        .sum();
    println!(
        "  total {total}; steps 3-9: {:.0} evaluations per step, {:.2} trials per step, {:.0} evaluations per trial",
        rhythmic as f64 / 7.0,
        rtrials as f64 / 7.0,
        rhythmic as f64 / rtrials as f64
    );

    // residual noise of the stance at step 5: r(τ1 + k δ) − the line through k = ±K
    let s = &w.steps[5];
    let y0 = s.stance.segments[0].0.y0;
    let (tau1, p) = (s.stance.tau1, s.stance.p);
    for rel in [1e-6, 1e-4] {
        let d = rel * tau1.abs();
        let r = |k: f64| {
            StanceRun::simulate(&s.stance_setup, y0, tau1 + k * d, p)
                .unwrap()
                .residual
        };
        let (ra, rb) = (r(-5.0), r(5.0));
        let mut noise: f64 = 0.0;
        for k in -5..=5 {
            let k = k as f64;
            let line = ra + (rb - ra) * ((k + 5.0) / 10.0);
            noise = noise.max((r(k) - line).amax());
        }
        println!("stance residual noise (step 5, δτ1 = {rel:e} τ1): {noise:.1e}");
    }

    let exact = w
        .steps
        .iter()
        .map(|s| exact_residual(s, &body, &attrs))
        .fold([0.0; 4], max4);
    println!(
        "  residuals of the exact dynamics (re-integrated at 1e-12; stance, swing1-3): {:.1e} {:.1e} {:.1e} {:.1e}",
        exact[0], exact[1], exact[2], exact[3]
    );

    // one trial of each phase of step 5, with the step sequence chosen afresh
    {
        use klaw::control::stance::StanceRun;
        use klaw::control::swing::SwingTrial;
        let s = &w.steps[5];
        let y0 = s.stance.segments[0].0.y0;
        let run = StanceRun::simulate(&s.stance_setup, y0, s.stance.tau1, s.stance.p).unwrap();
        let t = s.constraints.timing;
        let path = klaw::control::stance::HipPath::new(
            &s.stance,
            &s.stance_setup,
            t.t_ds,
            t.t_step,
            &|tau| s.swing_offset(tau),
        );
        let setup = swing_setup(s, &body, &attrs, &path);
        let mut line = format!(
            "  evaluations per trial at step 5: stance {}",
            run.evaluations
        );
        for (sub, seg) in &s.swing {
            let tr = SwingTrial::simulate(&setup, *sub, seg.t0, seg.y0).unwrap();
            line += &format!(
                ", {} {} ({:.3} s)",
                sub.name(),
                tr.evaluations,
                seg.t1 - seg.t0
            );
        }
        println!("{line}; stance {:.3} s", t.t_step);
    }

    // the same for swing1 (hip magnitude A)
    use klaw::control::stance::HipPath;
    use klaw::control::swing::{Subphase, SwingSetup, SwingTrial};
    let t = s.constraints.timing;
    let path = HipPath::new(&s.stance, &s.stance_setup, t.t_ds, t.t_step, &|tau| {
        s.swing_offset(tau)
    });
    // swing1 reads the timing, θ3*, the hip and its knee damper from the setup
    let setup = SwingSetup::new(
        klaw::dynamics::SwingModel::new(&body),
        &path,
        0.0,
        &s.constraints,
        &attrs,
        &klaw::engine::parameters::EngineParameters::default().servos,
    );
    let (sub, seg) = &s.swing[0];
    let Subphase::Swing1 { hip, knee } = *sub else {
        unreachable!()
    };
    for rel in [1e-6, 1e-4] {
        let d = rel * hip.abs();
        let r = |k: f64| {
            let tr = SwingTrial::simulate(
                &setup,
                Subphase::Swing1 {
                    hip: hip + k * d,
                    knee,
                },
                seg.t0,
                seg.y0,
            )
            .unwrap();
            (tr.residual, tr.evaluations)
        };
        let ((ra, ev), (rb, _)) = (r(-5.0), r(5.0));
        let mut noise: f64 = 0.0;
        for k in -5..=5 {
            let k = k as f64;
            let line = ra + (rb - ra) * ((k + 5.0) / 10.0);
            noise = noise.max((r(k).0 - line).amax());
        }
        println!(
            "swing1 residual noise (step 5, δA = {rel:e} A): {noise:.1e} ({ev} evaluations per trial)"
        );
    }

    let (mut evals, mut trials, mut maxit, mut end_err, mut sl_err) =
        (0u64, 0usize, 0, 0.0f64, 0.0f64);
    let mut exact = [0.0; 4];
    let mut heel_v = f64::NEG_INFINITY;
    let mut late = Vec::new();
    let t0 = std::time::Instant::now();
    let (mut refused, mut walked, mut steps) = (0, 0, 0);
    for hi in 0..4 {
        let h = 1.5 + 0.15 * hi as f64;
        for vi in 0..15 {
            let v = 0.6 + 0.1 * vi as f64;
            let body = Body::standard(h, 23.0 * h * h).unwrap();
            // beyond the body's walk–run transition: refused before any work, not a walk
            let request = GaitRequest {
                velocity: Some(v),
                ..Default::default()
            };
            let Ok(g) = request.complete(&body, &attrs) else {
                refused += 1;
                continue;
            };
            match walk::simulate(body, attrs.clone(), &[g; 10]) {
                Ok(w) => {
                    walked += 1;
                    for s in &w.steps {
                        steps += 1;
                        exact = max4(exact, exact_residual(s, &body, &attrs));
                        let r = &s.report;
                        heel_v = heel_v.max(r.heel_contact_velocity);
                        evals += r.rhs_evaluations;
                        end_err = end_err.max(r.end_condition_error);
                        sl_err = sl_err.max(
                            (r.achieved.step_length - r.target.step_length).abs()
                                / r.target.step_length,
                        );
                        for so in &r.solves {
                            trials += so.report.iterations;
                            maxit = maxit.max(so.report.iterations);
                            if s.index >= 3 {
                                late.push(so.report.iterations);
                            }
                        }
                    }
                }
                Err(e) => println!("v {v:.1} H {h:.2}: {e}"),
            }
        }
    }
    late.sort_unstable();
    println!("grid: highest heel contact velocity {heel_v:.3e} m/s (the bound: <= 0)");
    let mean = late.iter().sum::<usize>() as f64 / late.len() as f64;
    println!(
        "grid ({walked} walks x 10 steps; {refused} points past the walk–run transition refused): \
         {:.0} evaluations per step, {:.2} trials per step, {:.0} per trial; \
         max {maxit} trials per solve, steps >= 3 mean {mean:.2} p95 {}; worst end condition {end_err:.1e}, \
         worst step length {:.3} %; residuals of the exact dynamics {:.1e} {:.1e} {:.1e} {:.1e}; {:.2} s",
        evals as f64 / steps as f64,
        trials as f64 / steps as f64,
        evals as f64 / trials as f64,
        late[(95 * late.len()).div_ceil(100) - 1],
        100.0 * sl_err,
        exact[0],
        exact[1],
        exact[2],
        exact[3],
        t0.elapsed().as_secs_f64()
    );
}

/// The swing setup of `step`, as `Walker::step` builds it.
fn swing_setup<'a>(
    step: &'a walk::Step,
    body: &Body,
    attrs: &Attributes,
    path: &'a klaw::control::stance::HipPath,
) -> klaw::control::swing::SwingSetup<'a> {
    // the swing-side hip's vertical velocity at heel strike, as the walk computes it
    let hip_vy_end = walk::swing_hip_vy_end(&step.stance, &step.stance_setup, &|tau| {
        step.swing_offset(tau)
    });
    klaw::control::swing::SwingSetup::new(
        klaw::dynamics::SwingModel::new(body),
        path,
        hip_vy_end,
        &step.constraints,
        attrs,
        &klaw::engine::parameters::EngineParameters::default().servos,
    )
}

/// The end-condition residuals of a converged step's phases when its magnitudes are integrated
/// again at tolerance 1e-12: how far the exact dynamics are from meeting the end conditions.
fn exact_residual(step: &walk::Step, body: &Body, attrs: &Attributes) -> [f64; 4] {
    use klaw::control::stance::{HipPath, StanceRun};
    use klaw::control::swing::SwingTrial;
    const REFERENCE: f64 = 1e-12;
    let y0 = step.stance.segments[0].0.y0;
    let mut worst = [0.0; 4];
    worst[0] = StanceRun::simulate_with(
        &step.stance_setup,
        y0,
        step.stance.tau1,
        step.stance.p,
        REFERENCE,
    )
    .unwrap()
    .residual
    .amax();
    let t = step.constraints.timing;
    let path = HipPath::new(&step.stance, &step.stance_setup, t.t_ds, t.t_step, &|tau| {
        step.swing_offset(tau)
    });
    let setup = swing_setup(step, body, attrs, &path);
    for (i, (sub, seg)) in step.swing.iter().enumerate() {
        let tr = SwingTrial::simulate_with(&setup, *sub, seg.t0, seg.y0, REFERENCE).unwrap();
        worst[i + 1] = tr.residual.amax();
    }
    worst
}

fn max4(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0].max(b[0]),
        a[1].max(b[1]),
        a[2].max(b[2]),
        a[3].max(b[3]),
    ]
}
