//! Integration segments that end where the forces jump: the stance's first segment ends where
//! the leg torque switches off (0.4 t_step), the swing's pieces end at the hip path's breaks.
//! The integrator's last stages are evaluated at the segment's end, and must see the forces of
//! the segment (their limit from inside), not the values past the jump. Each segment's end
//! state is compared with an independent integration (ode_solvers' Dopri5 at 1e-12) of the
//! segment's own forces, with t held inside the segment. The engine's phases are integrated
//! again here at 1e-8, the tolerance the bounds were measured at (the walk's own tolerance is
//! looser, `ode::TOLERANCE`).
mod common;

use nalgebra::SVector;
use ode_solvers::{Dopri5, OutputType, System};

use klaw::control::stance::{HipPath, StanceForces, StanceRun};
use klaw::control::swing::{Subphase, SwingForces, SwingSetup};
use klaw::dynamics::SwingModel;
use klaw::engine::walker::{Step, Walk, swing_hip_vy_end};
use klaw::numerics::ode::Phase;
use klaw::{Attributes, Body};

/// The integrator tolerance of the checks (the bounds below were measured at it).
const TOLERANCE: f64 = 1e-8;

/// The step's converged stance integrated again at [`TOLERANCE`].
fn stance_again(step: &Step) -> StanceRun {
    let s = &step.stance;
    StanceRun::simulate_with(
        &step.stance_setup,
        s.segments[0].0.y0,
        s.tau1,
        s.p,
        TOLERANCE,
    )
    .unwrap()
}

fn steps(n: usize) -> (Body, Attributes, Vec<Step>) {
    let Walk { body, attrs, steps } = common::default_walk(n);
    (body, attrs, steps)
}

/// A phase evaluated at `t` clamped to `hi`: the forces of the segment that ends at `hi`.
struct Inside<'a, P, const K: usize>(&'a P, f64);

impl<P: Phase<N, K>, const N: usize, const K: usize> System<f64, SVector<f64, N>>
    for Inside<'_, P, K>
{
    fn system(&self, t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        *dy = self.0.rhs(t.min(self.1), y);
    }
}

/// The end state at `hi` of `phase` from (t0, y0) with t held below `hi`, by ode_solvers'
/// Dopri5 at 1e-12.
fn end_state<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    hi: f64,
    t0: f64,
    y0: SVector<f64, N>,
) -> SVector<f64, N> {
    // sparse output: ode_solvers 0.6.2's dense output extrapolates its last point
    // (tests/dynamics.rs)
    let mut s = Dopri5::from_param(
        Inside::<P, K>(phase, hi),
        t0,
        hi,
        hi - t0,
        y0,
        1e-12,
        1e-12,
        0.9,
        0.04,
        0.2,
        10.0,
        hi - t0,
        0.0,
        1_000_000,
        1000,
        OutputType::Sparse,
    );
    s.integrate().unwrap();
    *s.y_out().last().unwrap()
}

/// Each stance segment ends with its own forces, in the default walk and with the plastic
/// heel-strike impulse (heel_strike_impulse = 1), whose hip, launched upwards, unloads the leg
/// just after heel strike: there a segment surely ends where the leg force's clamp lets go.
#[test]
fn stance_segments_end_with_their_own_forces() {
    let (body, mut attrs, steps) = steps(6);
    attrs.heel_strike_impulse = 1.0;
    let plastic = klaw::Simulation::new(body)
        .attributes(attrs)
        .velocity(1.4)
        .steps(6)
        .run()
        .unwrap()
        .into_engine()
        .steps;
    for (step, clamps) in [
        (&steps[0], false),
        (&steps[5], false),
        (&plastic[0], true),
        (&plastic[5], true),
    ] {
        let setup = &step.stance_setup;
        let t_off = setup.torque_off * setup.t_step;
        let run = stance_again(step);
        let segments = &run.segments;
        // one segment ends at the torque's switch; with the plastic impulse one before it where
        // the leg force's clamp lets go (the unloaded leg after the heel strike), telescopic
        let at_switch = segments.iter().position(|(s, _)| s.t1 == t_off).unwrap();
        let forces = |locked| StanceForces::new(setup, run.tau1, run.p, locked);
        let weight = body.mass * 9.81;
        let at_clamp = segments.iter().position(|(s, l)| {
            !l && s.t1 < t_off && forces(false).leg_force(s.t1, &s.y1).abs() < 1e-6 * weight
        });
        assert!(at_clamp.is_some() || !clamps, "step {}", step.index);
        assert!(at_clamp.is_none_or(|c| c < at_switch));
        for (i, (seg, locked)) in segments.iter().enumerate() {
            // t enters the forces through the switch and the position actuator's blend (0
            // before t_step / 2, C¹ there): held just before the segment's end
            let reference = end_state(&forces(*locked), seg.t1 * (1.0 - 1e-15), seg.t0, seg.y0);
            let err = (seg.y1 - reference).amax();
            // measured ≤ 5e-9 (tolerance 1e-8); with the torque off at the last stages 2.9e-8
            // at step 0, with the clamp's kink inside the integrator's steps 3.8e-8 at step 5
            assert!(err < 2e-8, "step {}, segment {i}: {err:.2e}", step.index);
        }
    }
}

#[test]
fn swing_pieces_end_with_their_own_hip_acceleration() {
    let (body, attrs, steps) = steps(6);
    let mut checked = 0;
    for step in [&steps[0], &steps[5]] {
        let t = step.constraints.timing;
        let offset = |tau: f64| step.swing_offset(tau);
        let stance = stance_again(step);
        let path = HipPath::new(&stance, &step.stance_setup, t.t_ds, t.t_step, &offset);
        let breaks: Vec<f64> = path.breaks().collect();
        assert!(!breaks.is_empty());
        // at a break the next piece starts; the piece before it ends with its own values
        for (i, &b) in breaks.iter().enumerate() {
            assert_eq!(path.piece(b), i + 1);
            let left = path.acceleration(b * (1.0 - 1e-15));
            let end = path.acceleration_on(i, b);
            assert!((left[0] - end[0]).abs() + (left[1] - end[1]).abs() < 1e-6);
        }
        let hip_vy_end = swing_hip_vy_end(&stance, &step.stance_setup, &offset);
        let setup = SwingSetup::new(
            SwingModel::new(&body),
            &path,
            hip_vy_end,
            &step.constraints,
            &attrs,
            &klaw::engine::parameters::EngineParameters::default().servos,
        );
        // swing1 integrated again by the engine, piece by piece: each piece's end state against
        // the reference integration of that piece with t held inside it
        let (sub, seg) = &step.swing[0];
        assert!(matches!(sub, Subphase::Swing1 { .. }));
        let trial = klaw::control::swing::SwingTrial::simulate_with(
            &setup, *sub, seg.t0, seg.y0, TOLERANCE,
        )
        .unwrap();
        let forces = SwingForces {
            setup: &setup,
            sub: *sub,
            piece: None,
        };
        let mut t0 = seg.t0;
        for &b in breaks.iter().filter(|&&b| b > seg.t0 && b < seg.t1) {
            let reference = end_state(&forces, b * (1.0 - 1e-15), t0, trial.segment.state(t0));
            let err = (trial.segment.state(b) - reference).amax();
            // measured 7e-9 and 2.6e-8 at step 0 (tolerance 1e-8); with the next piece's
            // acceleration at the last stages 6.9e-8 in the first piece
            assert!(
                err < 5e-8,
                "step {}, piece ending at {b}: {err:.2e}",
                step.index
            );
            t0 = b;
            checked += 1;
        }
    }
    assert!(checked >= 2);
}
