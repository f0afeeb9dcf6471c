//! The walking engine's bounds (issue: walking engine), checked on whole walks.
mod common;

use common::{
    body_of_height, body_of_height_in, default_attributes, default_body, fine_grid, gait, grid,
    grid_of, walk,
};
use klaw::engine::report::StepReport;
use klaw::{GaitRequest, Simulation};

/// Every per-step bound of the issue that does not depend on the speed range.
fn check_step(s: &StepReport, label: &str) {
    let who = format!("{label} step {}", s.index);
    assert!(
        s.end_condition_error <= 1e-6,
        "{who}: end conditions off by {:e}",
        s.end_condition_error
    );
    assert!(
        s.heel_height_at_strike.abs() <= 1e-4,
        "{who}: heel {:e} m off the ground",
        s.heel_height_at_strike
    );
    let sl_err = (s.achieved.step_length - s.target.step_length).abs() / s.target.step_length;
    assert!(
        sl_err <= 0.005,
        "{who}: step length off by {:.3} %",
        100.0 * sl_err
    );
    assert!(
        (s.achieved.duration - 60.0 / s.target.step_frequency).abs() < 1e-12,
        "{who}: duration"
    );
    for so in &s.solves {
        assert!(
            so.report.converged && so.report.residual <= 1e-6,
            "{who}: {so:?}"
        );
        assert!(so.report.iterations <= 25, "{who}: {so:?}");
    }
    assert!(
        s.hip_min_margin >= -1e-6,
        "{who}: hip {:e} m below its heel-strike height",
        -s.hip_min_margin
    );
    assert!(
        (s.hip_excursion - s.bounce_reference).abs() <= 0.01,
        "{who}: hip excursion {:.4} m vs reference {:.4} m",
        s.hip_excursion,
        s.bounce_reference
    );
    assert!(
        s.min_foot_height >= -1e-6,
        "{who}: swing foot {:e} m under the ground",
        -s.min_foot_height
    );
    assert!(
        s.min_toe_clearance
            > klaw::engine::parameters::EngineParameters::default().toe_clearance_min,
        "{who}: no toe clearance in mid swing"
    );
    assert!(
        s.heel_contact_velocity <= 0.0,
        "{who}: heel scrapes up at contact"
    );
}

/// Iteration statistics over the solves of steps with index ≥ 3 (warm starts): p95 ≤ 10, mean ≤ 6.
fn check_warm_iterations(iterations: &mut [usize]) {
    iterations.sort_unstable();
    let n = iterations.len();
    assert!(n > 0);
    let mean = iterations.iter().sum::<usize>() as f64 / n as f64;
    let p95 = iterations[(95 * n).div_ceil(100) - 1];
    assert!(mean <= 6.0, "mean iterations {mean}");
    assert!(p95 <= 10, "95th percentile of iterations {p95}");
}

#[test]
fn default_walk_meets_every_bound() {
    let body = default_body();
    let g = gait(&body, 1.4);
    let w = walk(body, 1.4, 10).unwrap();
    let report = w.report();
    assert_eq!(report.steps.len(), 10);
    let mut late = Vec::new();
    for s in &report.steps {
        check_step(s, "1.4 m/s");
        // v in [1.2, 1.4], H ≥ 1.65: the hip rises 3–6 cm
        assert!(
            (0.03..=0.06).contains(&s.hip_excursion),
            "step {}: excursion {}",
            s.index,
            s.hip_excursion
        );
        if s.index >= 3 {
            late.extend(s.solves.iter().map(|so| so.report.iterations));
        }
    }
    check_warm_iterations(&mut late);
    // spec §7: the hip speed surviving each impact lies between the point-mass bounds for a hip
    // velocity at θ1* and 2θ1* from the new leg's normal: the impulse removes the fraction ρ of
    // the axial part, so the ratio is √(1 − ρ (2 − ρ) sin² α) (cos α for the plastic ρ = 1;
    // tests/dynamics.rs shows the trunk can push it below for a velocity across the old leg,
    // but not in a walk, where the hip moves nearly horizontally)
    let attrs = default_attributes();
    let c = klaw::StepConstraints::new(&body, &attrs, g).unwrap();
    let rho = attrs.heel_strike_impulse;
    let ratio = |alpha: f64| (1.0 - rho * (2.0 - rho) * alpha.sin().powi(2)).sqrt();
    for s in &report.steps {
        let r = s.impact_speed_ratio;
        assert!(
            r > ratio(2.0 * c.theta1) && r < ratio(c.theta1),
            "step {}: ratio {r}",
            s.index
        );
    }
    // the walk lasts 10 t_step and covers 10 sl: from sf = √(15000·1.4/1.8) by hand
    let sf = (15000.0_f64 * 1.4 / 1.8).sqrt();
    assert!((w.duration() - 10.0 * 60.0 / sf).abs() < 1e-9);
    let frames = w.frames(100.0);
    assert_eq!(frames.len(), (w.duration() * 100.0).floor() as usize + 1);
    let last = frames.last().unwrap();
    assert!((last.stance_ankle_x_m - 9.0 * g.step_length).abs() < 1e-9);
    // the hip moves forward in every frame; the swing foot never under the ground
    for pair in frames.windows(2) {
        assert!(
            pair[1].hip_x_m > pair[0].hip_x_m,
            "hip goes back at t = {}",
            pair[1].time_s
        );
    }
    for f in &frames {
        assert!(
            f.swing_toe_y_m >= -1e-6 && f.swing_heel_y_m >= -1e-6,
            "foot under the ground at {}",
            f.time_s
        );
    }
}

/// The grid over the whole valid range (`common::grid`: v from 0.4 m/s to the walk–run
/// transition, H 1.2–2.2 m), M = 23 H², 10 steps each: every walk converges and meets every
/// bound.
#[test]
fn grid_meets_every_bound() {
    grid_bounds(&grid());
}

/// The same over the 0.1 m/s × 0.1 m box (192 walks; `cargo test --release --test walk --
/// --ignored`): what the README's convergence map shows.
#[test]
#[ignore]
fn fine_grid_meets_every_bound() {
    grid_bounds(&fine_grid());
}

/// The bodies of de Leva's tables (other proportions than Winter's: docs/bodies.md) walk their
/// own valid range with every bound held: H 1.2, 1.7, 2.2 m × v 0.4, 0.8, 1.2, 1.6 m/s and each
/// body's walk–run limit (its own leg length), 14 walks a table. (De Leva's woman of H 1.2 m
/// from 1.6 m/s to her limit touched the floor with her toe in the start step's swing until the
/// start step's hind leg mirrored a steady one: docs/coverage.md.)
#[test]
fn de_leva_bodies_meet_every_bound() {
    for table in ["deleva-male", "deleva-female"] {
        grid_bounds_in(table, &grid_of(table, 0.4, &[1.2, 1.7, 2.2]));
    }
}

/// The start step's swing leaves toe-off as a steady step's does: its hind leg mirrors the
/// step's own stance leg one step earlier, so that the knee's rate at toe-off is within
/// 0.1 rad/s + 5 % of the third step's (from a knee of κ_hs at heel strike it was 9.6 against
/// 4.1 rad/s at 1.4 m/s, 23 against −0.3 rad/s for de Leva's woman of 1.2 m at 1.6 m/s).
#[test]
fn the_start_step_leaves_toe_off_as_a_steady_step() {
    for (table, v, h) in [
        ("winter", 1.4, 1.8),
        ("deleva-female", 1.6, 1.2),
        ("winter", 0.6, 2.0),
    ] {
        let w = walk(body_of_height_in(table, h), v, 3).unwrap();
        let rate = |k: usize| {
            let seg = &w.steps[k].swing[0].1;
            seg.state(seg.t0)[3]
        };
        let (first, steady) = (rate(0), rate(2));
        assert!(
            (first - steady).abs() <= 0.1 + 0.05 * steady.abs(),
            "{table} v {v} H {h}: knee rate at toe-off {first} vs {steady} rad/s"
        );
    }
}

fn grid_bounds(grid: &[(f64, f64)]) {
    grid_bounds_in("winter", grid)
}

fn grid_bounds_in(table: &str, grid: &[(f64, f64)]) {
    let mut late = Vec::new();
    for &(v, h) in grid {
        let label = format!("{table} v {v:.4} H {h:.2}");
        let body = body_of_height_in(table, h);
        let w = walk(body, v, 10).unwrap_or_else(|e| panic!("{label}: {e}"));
        for s in &w.report().steps {
            check_step(s, &label);
            if (1.2..=1.4 + 1e-9).contains(&v) && h >= 1.65 {
                assert!(
                    (0.03..=0.06).contains(&s.hip_excursion),
                    "{label}: {}",
                    s.hip_excursion
                );
            }
            if s.index >= 3 {
                late.extend(s.solves.iter().map(|so| so.report.iterations));
            }
        }
    }
    check_warm_iterations(&mut late);
}

/// A schedule that accelerates from 1.0 to 1.6 m/s over 6 steps meets every step's targets.
#[test]
fn accelerating_schedule_meets_every_target() {
    let schedule = (0..6)
        .map(|i| GaitRequest {
            velocity: Some(1.0 + 0.12 * i as f64),
            ..GaitRequest::default()
        })
        .collect();
    let w = Simulation::new(default_body())
        .schedule(schedule)
        .run()
        .unwrap();
    for (s, g) in w.report().steps.iter().zip(w.gaits()) {
        check_step(s, "schedule");
        assert!((s.target.velocity - g.velocity).abs() < 1e-12);
        assert!(
            (s.achieved.velocity - g.velocity).abs() / g.velocity <= 0.005,
            "{s:?}"
        );
    }
}

/// The tabulated hip acceleration the swing reads agrees with the stance dynamics between the
/// grid points: to 5e-6 m/s² (2e-6 of the ≈ 3 m/s² hip accelerations; measured 3.1e-6 with the
/// quintic every 3 ms and a cut at the reference's heel-off since PITCH_BULGE, 1.4e-5 without
/// the cut; 1.3e-6 before it; 8.1e-6 every 4 ms since the hip's lead moved heel-off near mid-stance,
/// 7e-7 before; 7e-6 with the cubic every 1 ms before that).
#[test]
fn hip_path_interpolates_the_stance_hip() {
    use klaw::control::stance::HipPath;
    let w = walk(default_body(), 1.4, 3).unwrap();
    let s = &w.steps[2];
    let t = s.constraints.timing;
    // with an offset whose acceleration is known: (0.01 sin 9t, 0.02 cos 7t)
    let offset = |t: f64| [0.01 * (9.0 * t).sin(), 0.02 * (7.0 * t).cos()];
    let path = HipPath::new(&s.stance, &s.stance_setup, t.t_ds, t.t_step, &offset);
    let mut worst: f64 = 0.0;
    for k in 0..997 {
        let tau = t.t_ds + (t.t_step - t.t_ds) * (k as f64 + 0.37) / 997.0;
        let mut exact = s.stance.hip(&s.stance_setup, tau)[2];
        exact[0] -= 0.81 * (9.0 * tau).sin();
        exact[1] -= 0.98 * (7.0 * tau).cos();
        let got = path.acceleration(tau);
        worst = worst
            .max((exact[0] - got[0]).abs())
            .max((exact[1] - got[1]).abs());
    }
    assert!(worst < 5e-6, "worst hip acceleration error {worst:e} m/s²");
}

/// `Step::measure` samples and refines around the sampled minima and maxima: every extreme it
/// reports is at least as extreme as dense sampling finds (4 000 samples per phase; to 1e-12 m:
/// where the foot rests on its floor the heights are rounding noise of 1e-16 m), on the default
/// walk and at the grid's corners (v 0.4 m/s and the walk–run limit at H 1.2 and 2.2 m); the mid-swing clearance as well (its least is at an end of
/// mid swing or at a refined local minimum: 400 samples alone missed a 50 nm touch at 0.6 m/s,
/// H 1.8 m, that the refined search finds).
#[test]
fn measured_extremes_are_at_least_those_of_dense_sampling() {
    use klaw::kinematics::foot::Foot;
    for (v, h) in [
        (1.4, 1.8),
        (0.4, 1.2),
        (1.6847, 1.2),
        (0.4, 2.2),
        (2.2812, 2.2),
    ] {
        let body = if h == 1.8 {
            default_body()
        } else {
            body_of_height(h)
        };
        let w = walk(body, v, 4).unwrap();
        let foot = Foot::new(&body);
        for s in &w.steps {
            let r = &s.report;
            let t = s.constraints.timing;
            const N: usize = 4000;
            let (mut y_min, mut y_max) = (f64::INFINITY, f64::NEG_INFINITY);
            let (mut lowest, mut mid, mut knee) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY);
            for k in 0..=N {
                let f = k as f64 / N as f64;
                let y = s.hip(f * t.t_step)[1];
                y_min = y_min.min(y);
                y_max = y_max.max(y);
                let p = s.swing_pose(t.t_ds + f * t.t_swing, &foot);
                lowest = lowest.min(p.foot.lowest());
                if (0.25..=0.75).contains(&f) {
                    mid = mid.min(p.foot.lowest());
                }
                knee = knee.max(p.theta4);
            }
            let sy = &s.stance_setup;
            let who = format!("v {v} H {h} step {}", s.index);
            // (to round-off: a search's extreme and a dense sample can meet at the same point)
            assert!(
                r.hip_min_margin <= y_min - sy.y_start.min(sy.y_end) + 1e-12,
                "{who}: hip lowest"
            );
            assert!(
                r.hip_excursion >= y_max - sy.y_end - 1e-12,
                "{who}: hip highest"
            );
            assert!(r.min_foot_height <= lowest + 1e-12, "{who}: foot lowest");
            assert!(
                r.min_toe_clearance <= mid + 1e-12,
                "{who}: mid-swing clearance"
            );
            // (the knee's search stops within ≈ 1e-11 rad of its peak: 7e-12 under a dense
            // sample at 1.6847 m/s, H 1.2 m)
            assert!(
                r.peak_swing_knee_flexion >= knee - 1e-10,
                "{who}: knee peak {} vs {knee}",
                r.peak_swing_knee_flexion
            );
            // and not beyond what the motion reaches (the dense samples' spacing bounds it)
            assert!(lowest - r.min_foot_height < 1e-4, "{who}: foot lowest");
            assert!(mid - r.min_toe_clearance < 1e-4, "{who}: clearance");
            assert!(r.peak_swing_knee_flexion - knee < 1e-4, "{who}: knee");
        }
    }
}

/// The walker runs with the parameters it is given: a solve tolerance 100 times looser (the
/// walk's own promise, 1e-6) spends fewer trials over the walk, and a limit of one
/// trial per solve cannot walk the first step, whose warm starts are only guesses.
#[test]
fn the_walker_runs_with_its_parameters() {
    use klaw::engine::parameters::EngineParameters;
    use klaw::engine::walker::Walker;
    let body = default_body();
    let g = gait(&body, 1.4);
    let trials = |parameters: EngineParameters| {
        let mut w = Walker::new(body, default_attributes()).with_parameters(parameters);
        let mut spent = 0;
        for _ in 0..6 {
            let step = w.step(g).unwrap();
            for s in &step.report.solves {
                assert!(s.report.converged);
                spent += s.report.iterations;
            }
        }
        spent
    };
    let default = EngineParameters::default();
    let loose = EngineParameters {
        solve_tolerance: 1e-6,
        waypoint_tolerance: 1e-6,
        ..default
    };
    assert!(
        trials(loose) < trials(default),
        "{} vs {}",
        trials(loose),
        trials(default)
    );
    let one = EngineParameters {
        max_iterations: 1,
        ..default
    };
    let mut w = Walker::new(body, default_attributes()).with_parameters(one);
    assert!(w.step(g).is_err());
}

/// The integrator's limits and the hip table's grid reach the integrations through the
/// walker's parameters: five integrator steps per integration cannot walk a stance (≈ 140
/// steps), and a hip table four times coarser moves the swing knee's measured peak flexion, though
/// by less than 1e-6 rad (the toe clearance, measured here before the hip's lead, now sits on the
/// clearance rule's floor in both).
#[test]
fn the_integrator_limits_come_from_the_parameters() {
    use klaw::engine::parameters::EngineParameters;
    use klaw::engine::walker::Walker;
    use klaw::numerics::ode::Tolerance;
    let body = default_body();
    let g = gait(&body, 1.4);
    let default = EngineParameters::default();
    let few = EngineParameters {
        ode: Tolerance {
            max_steps: 5,
            ..default.ode
        },
        ..default
    };
    let mut w = Walker::new(body, default_attributes()).with_parameters(few);
    let err = w.step(g).unwrap_err().to_string();
    assert!(err.contains("more than 5 steps"), "{err}");
    let knee_peak = |parameters: EngineParameters| {
        let mut w = Walker::new(body, default_attributes()).with_parameters(parameters);
        w.step(g).unwrap().report.peak_swing_knee_flexion
    };
    let coarse = EngineParameters {
        hip_path_step: 4.0 * default.hip_path_step,
        ..default
    };
    let (a, b) = (knee_peak(default), knee_peak(coarse));
    assert!(a != b && (a - b).abs() < 1e-6, "{a} vs {b}");
}

/// The hip's lead at heel strike (the default: `hip_lead_slope` 0.595, `heel_off_dorsiflexion` 8°,
/// docs/realism.md) walks with every bound held where the whole lead up to the walk–run
/// transition failed (docs/coverage.md): Winter's body of 1.2 m at its limit (the virtual leg's
/// reference under y_hs before heel strike), de Leva's woman of 1.4 m at 1.75 m/s and of 1.7 m
/// at 1.86 m/s and at her limit (the swing toe on the floor, the hip under y_hs), de Leva's man
/// of 1.3 m at 1.77 m/s; it fades from Froude 0.4 (`hip_lead_froude`). Kept whole (neither
/// fade applied: the step is 1.2 leg lengths at the first of them) it failed there, the virtual
/// leg's reference under y_hs before heel strike, until the heel rose mid-way in terminal
/// stance (`PITCH_BULGE`, docs/realism.md); now it walks there too.
#[test]
fn the_hip_lead_walks_up_to_the_walk_run_transition() {
    let lead = klaw::Attributes {
        hip_lead_slope: 0.595,
        heel_off_dorsiflexion: 8f64.to_radians(),
        ..default_attributes()
    };
    let walk_with = |attrs: &klaw::Attributes, table: &str, v: Option<f64>, h: f64| {
        let body = body_of_height_in(table, h);
        let v = v.unwrap_or_else(|| klaw::plan::gait::velocity_limit(&body, attrs));
        let w = Simulation::new(body)
            .attributes(attrs.clone())
            .velocity(v)
            .steps(10)
            .run();
        (w, format!("{table} v {v:.4} H {h}"))
    };
    for (table, v, h) in [
        ("winter", None, 1.2),
        ("deleva-female", Some(1.75), 1.4),
        ("deleva-female", Some(1.86), 1.7),
        ("deleva-female", None, 1.7),
        ("deleva-male", Some(1.77), 1.3),
    ] {
        let (w, label) = walk_with(&lead, table, v, h);
        let w = w.unwrap_or_else(|e| panic!("{label}: {e}"));
        for s in &w.report().steps {
            check_step(s, &label);
        }
    }
    let whole = klaw::Attributes {
        hip_lead_froude: 0.5,
        hip_lead_step_from: 9.0,
        hip_lead_step_to: 10.0,
        ..lead
    };
    let (w, label) = walk_with(&whole, "winter", None, 1.2);
    let w = w.unwrap_or_else(|e| panic!("{label}: {e}"));
    for s in &w.report().steps {
        check_step(s, &label);
    }
}

/// The default body's steps at 1.8 m/s, walked with the engine's parameters `p`: per step, the
/// pelvic list (deg) and the bounce reference (m) of its report.
fn fast_steps(p: klaw::engine::parameters::EngineParameters) -> Vec<(f64, f64)> {
    use klaw::engine::walker::{Walker, walk_attributes};
    let sim = Simulation::default().velocity(1.8).steps(10);
    let prepared = sim.prepare().unwrap();
    let body = *prepared.body();
    let attrs = walk_attributes(&body, prepared.attributes(), prepared.gaits());
    let mut walker = Walker::new(body, attrs).with_parameters(p);
    prepared
        .gaits()
        .iter()
        .map(|g| {
            let r = walker.step(*g).unwrap().report;
            (r.pelvic_list.to_degrees(), r.bounce_reference)
        })
        .collect()
}

/// A step whose flat stance foot falls out of the straight leg's reach is walked again with
/// the bounce's reach margin raised by `reach_margin_step` at a time, and the later steps keep
/// it; only then would the list be lowered. At 1.8 m/s the default body's steady step falls
/// short at `REACH_MARGIN` (the hip overshoots its reference): with the reach retry every step
/// keeps the whole list (±4.87°, the speed law's) and the later steps bounce lower, by the cut
/// of one more hundredth, (top − ȳ) (1/(1 + m) − 1/(1 + m + 0.01)); without it the list is
/// lowered by tenths of it (`list_retries` = 10) to the most that walks, and the later steps
/// keep that list, so that the steady pelvis is the same on both sides (a blunt mend here: the
/// reach cut lets the bounce rise by as much as the lower list lowers the hip joint, and the
/// steps lower it by a tenth, then by three). The figure's pelvis lists as the report says.
#[test]
fn a_step_out_of_the_legs_reach_bounces_lower_else_lists_less() {
    use klaw::engine::parameters::EngineParameters;
    let p = EngineParameters::default();
    assert_eq!((p.list_retries, p.reach_retries), (10, 5));
    let walk = Simulation::default().velocity(1.8).steps(10).run().unwrap();
    let full = walk.attributes().pelvic_list.to_degrees();
    assert!((full - 4.866).abs() < 0.01, "{full}");
    let raised = fast_steps(p);
    assert!(
        raised.iter().all(|(l, _)| (l - full).abs() < 1e-9),
        "{raised:?}"
    );
    let first = raised.iter().position(|(_, b)| *b < raised[0].1 - 1e-6);
    let first = first.expect("a step with a raised margin");
    assert!(first >= 1, "{raised:?}");
    for (_, b) in &raised[first..] {
        assert!((b - raised[first].1).abs() < 1e-12, "{raised:?}");
    }
    // one more hundredth: the steady steps' top − ȳ from the step before's cut at REACH_MARGIN
    let want = raised[first - 1].1 * 1.07 / 1.08;
    assert!((raised[first].1 / want - 1.0).abs() < 1e-4, "{raised:?}");
    let lowered = fast_steps(EngineParameters {
        reach_retries: 0,
        ..p
    });
    let rungs: Vec<f64> = lowered.iter().map(|(l, _)| l / full * 10.0).collect();
    for (k, f) in rungs.iter().enumerate() {
        assert!((f - f.round()).abs() < 1e-6, "step {k}: {lowered:?}");
    }
    let rungs: Vec<i64> = rungs.iter().map(|f| f.round() as i64).collect();
    let first_lowered = rungs.iter().position(|&r| r < 10).expect("a lowered step");
    assert!(first_lowered >= 1, "{rungs:?}");
    assert!(rungs.windows(2).all(|w| w[1] <= w[0]), "{rungs:?}");
    // the figure's pelvis lists as the report says, in every step
    let mut peaks = [0.0f64; 10];
    for c in walk.clinical_angles(1000.0).unwrap() {
        let p = &mut peaks[c.step.min(9)];
        *p = p.max(c.pelvis_list.abs().to_degrees());
    }
    for (step, peak) in walk.report().steps.iter().zip(&peaks) {
        assert!(
            (step.pelvic_list.to_degrees() - peak).abs() < 1e-3,
            "{peak}"
        );
    }
}

/// A step whose rolling hind foot cannot reach the hip in double support with the toe-off knee
/// κ_TO is walked again with κ_TO lowered by `toe_off_knee_step` (5°) at a time, and the later
/// steps keep it: a long step at a slow cadence (H 1.8 m, sl 0.8 m at 1.0 m/s, 75 steps/min,
/// 0.92 leg lengths) fails in its second step's double support at 40° and walks at 35°, the
/// swing starting from the knee the hind leg reached. The least is the attribute's 20°.
#[test]
fn a_hind_foot_out_of_reach_toes_off_with_a_straighter_knee() {
    use klaw::engine::parameters::EngineParameters;
    use klaw::engine::walker::{Walker, walk_attributes};
    let p = EngineParameters::default();
    assert_eq!(p.toe_off_retries, 4);
    assert!((p.toe_off_knee_step - 5f64.to_radians()).abs() < 1e-15);
    let sim = Simulation::new(klaw::Body::standard(1.8, 80.0).unwrap())
        .gait(GaitRequest {
            velocity: Some(1.0),
            step_length: Some(0.8),
            ..Default::default()
        })
        .steps(10);
    let prepared = sim.prepare().unwrap();
    let body = *prepared.body();
    let attrs = walk_attributes(&body, prepared.attributes(), prepared.gaits());
    assert!((attrs.toe_off_knee.to_degrees() - 40.0).abs() < 1e-12);
    let walk = |p: EngineParameters| {
        let mut walker = Walker::new(body, attrs.clone()).with_parameters(p);
        prepared
            .gaits()
            .iter()
            .map(|g| walker.step(*g))
            .collect::<Result<Vec<_>, _>>()
    };
    let e = walk(EngineParameters {
        toe_off_retries: 0,
        ..p
    })
    .unwrap_err();
    assert!(e.is_toe_off_failure(), "{e}");
    assert!(e.to_string().contains("step 1, double_support"), "{e}");
    let steps = walk(p).unwrap();
    let knees: Vec<f64> = steps
        .iter()
        .map(|s| s.swing[0].1.y0[1].to_degrees())
        .collect();
    assert!((knees[0] - 40.0).abs() < 1e-9, "{knees:?}");
    for k in &knees[1..] {
        assert!((k - 35.0).abs() < 1e-9, "{knees:?}");
    }
    for s in &steps {
        check_step(&s.report, "sl 0.8 m at 1.0 m/s");
    }
}

/// The engine's model constants come from models/engine.toml and govern the walk: a stiffer
/// leg servo (f_w 5 → 8 Hz, parsed from an edited copy of the bundled file) tracks the hip's
/// reference more closely, so the steps' hip excursions change; the bundled file parsed again
/// walks exactly the default walker's steps.
#[test]
fn the_engines_constants_change_the_walk() {
    use klaw::engine::parameters::{BUILTIN_TABLE, EngineParameters};
    use klaw::engine::walker::Walker;
    let path = std::path::Path::new("engine.toml");
    let body = default_body();
    let g = gait(&body, 1.2);
    let excursions = |p: EngineParameters| -> Vec<f64> {
        let mut w = Walker::new(body, default_attributes()).with_parameters(p);
        (0..4)
            .map(|_| w.step(g).unwrap().report.hip_excursion)
            .collect()
    };
    let bundled = excursions(EngineParameters::parse(BUILTIN_TABLE, path).unwrap());
    let default = {
        let mut w = Walker::new(body, default_attributes());
        (0..4)
            .map(|_| w.step(g).unwrap().report.hip_excursion)
            .collect::<Vec<_>>()
    };
    assert_eq!(bundled, default);
    let stiff = BUILTIN_TABLE.replace("leg_frequency = 5.0", "leg_frequency = 8.0");
    assert_ne!(stiff, BUILTIN_TABLE);
    let changed = excursions(EngineParameters::parse(&stiff, path).unwrap());
    let largest = changed
        .iter()
        .zip(&default)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(largest > 1e-5, "excursions {changed:?} against {default:?}");
}

/// The step report counts the fallbacks each step walked with: at 1.8 m/s (where the default
/// body's flat foot falls out of the straight leg's reach at the bundled margin) exactly the
/// steps whose bounce the raised margin cut report a reach repair, and nothing else; with the
/// reach fallback off, exactly the steps that walk with less than the whole list report list
/// repairs, in tenths equal to the list they left out; the default walk's plan walks as made.
#[test]
fn the_step_report_counts_the_fallbacks_it_walked_with() {
    use klaw::engine::parameters::EngineParameters;
    use klaw::engine::walker::{Walker, walk_attributes};
    let run = |p: EngineParameters| {
        let body = default_body();
        let prepared = Simulation::new(body)
            .velocity(1.8)
            .steps(10)
            .prepare()
            .unwrap();
        let attrs = walk_attributes(&body, &default_attributes(), prepared.gaits());
        let full = attrs.pelvic_list;
        let mut walker = Walker::new(body, attrs).with_parameters(p);
        let reports: Vec<_> = prepared
            .gaits()
            .iter()
            .map(|g| walker.step(*g).unwrap().report)
            .collect();
        (full, reports)
    };
    let (_, raised) = run(EngineParameters::default());
    let top = raised[1].bounce_reference;
    for r in &raised[1..] {
        let cut = r.bounce_reference < top - 1e-6;
        assert_eq!(
            r.repairs.reach > 0,
            cut,
            "step {}: {:?}",
            r.index,
            r.repairs
        );
        assert_eq!((r.repairs.list, r.repairs.toe_off_knee), (0, 0));
    }
    assert!(raised.iter().any(|r| r.repairs.any()));
    let (full, lowered) = run(EngineParameters {
        reach_retries: 0,
        ..EngineParameters::default()
    });
    for r in &lowered {
        let left_out = (1.0 - r.pelvic_list / full) * 10.0;
        assert!(
            (left_out - r.repairs.list as f64).abs() < 1e-9,
            "{left_out} {:?}",
            r.repairs
        );
    }
    assert!(lowered.iter().any(|r| r.repairs.list > 0));
    let default = Simulation::default().steps(10).run().unwrap();
    assert!(default.report().steps.iter().all(|s| !s.repairs.any()));
}
