//! The engine's tolerances and limits: what the walker's shooting solves converge to and may
//! spend, how its measurements sample a step, and what a step's invariants allow (spec §4, §5;
//! the decisions behind each value: docs/engine.md, "Decisions" and "Engine").

use crate::numerics::ode::Tolerance;

/// The tolerances and limits of a walker: [`crate::engine::walker::Walker`] runs with the
/// `Default`, today's values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EngineParameters {
    /// Shooting tolerance of the stance's and swing3's end conditions (rad or m): 100× inside
    /// the 1e-6 the walk promises, and small enough for the heel-contact check, which
    /// differences the heel height over 1e-6 s.
    pub solve_tolerance: f64,
    /// \[ours\] Shooting tolerance of swing1's and swing2's end conditions (rad): 10× inside the
    /// 1e-6 the walk promises, since they are waypoints: the next subphase starts from the state
    /// they reach, swing3 meets the heel strike's conditions at `solve_tolerance` whatever it
    /// is, and swing2's error is the knee's jump where it locks.
    pub waypoint_tolerance: f64,
    /// Trial integrations allowed per solve (count): about twice the most any solve of the
    /// grid of `tests/walk.rs` needs (13).
    pub max_iterations: usize,
    /// Integrator tolerance of every shooting trial (relative and absolute, 1) and the
    /// integrator's limits (event location, steps, frozen mesh): the ODE integrator's own,
    /// [`Tolerance::default`], its step tolerance set by the accuracy of the end conditions.
    pub ode: Tolerance,
    /// \[ours\] How much looser swing2 integrates than the other phases (factor on
    /// `ode.step`): [`crate::control::swing`]'s default, 100, since swing2's stiff servos damp
    /// the local errors away.
    pub swing2_tolerance_scale: f64,
    /// Largest grid step of the stance hip's acceleration table the swing reads (s): 3 ms, its quintic
    /// interpolation 1.3e-6 m/s² from the stance dynamics (docs/engine.md, "Engine").
    pub hip_path_step: f64,
    /// The least mid-swing toe clearance a step may have (m): the feet's placement precision.
    pub toe_clearance_min: f64,
    /// How far the hip may drop below its heel-strike height and the swing foot go under the
    /// ground (m): the 1e-6 the walk promises.
    pub invariant_slack: f64,
    /// Uniform samples of the hip height and of the swing knee per interval in the step's
    /// measurements (count): each sampled local extreme is then refined by Brent's search.
    pub coarse_samples: usize,
    /// Uniform samples of the swing foot's height (count): narrow dips (the toe under the
    /// ground for 1 % of the swing while the heel rests on its floor) need them denser.
    pub foot_samples: usize,
    /// Least Gauss–Legendre panels per integration segment in the work of the step's report
    /// (count): one per integrator step (≈ 140 in a stance, ≈ 200 in a swing) is within 0.5 %
    /// of 8000 per segment (`tests/work.rs`).
    pub work_panels: usize,
    /// How many times a step that less pelvic list can mend is tried again, each time with the
    /// list lowered by 1 / `list_retries` of the attribute's, the last time with none (count;
    /// 10: 90, 80, …, 0 %; 0: never). Halving instead (50 %, 25 %, …) gave up 2.7° of a 5.4°
    /// list where 4.3° walks; fifths gave up 20 % of a 4.87° list where 10 % less walks
    /// (1.8 m/s, H 1.8 m; docs/realism.md).
    pub list_retries: usize,
    /// How many times a step whose flat foot falls out of the straight leg's reach is tried
    /// again before its list is lowered, each time with the bounce's reach margin
    /// (`REACH_MARGIN`, a fraction of the bounce) larger by `reach_margin_step` (count; 0:
    /// never): where the reach cuts the bounce, less list only lets the bounce rise again.
    pub reach_retries: usize,
    /// The reach margin's growth per retry (fraction of the bounce).
    pub reach_margin_step: f64,
    /// How many times a step whose rolling hind foot cannot reach the hip in double support is
    /// tried again, each time with the toe-off knee κ_TO lowered by `toe_off_knee_step`, never
    /// under the attribute's least value (count; 0: never): a straighter trailing knee reaches
    /// further, as long steps at a slow cadence need.
    pub toe_off_retries: usize,
    /// The toe-off knee's fall per retry (rad).
    pub toe_off_knee_step: f64,
}

impl Default for EngineParameters {
    fn default() -> Self {
        EngineParameters {
            solve_tolerance: 1e-8,
            waypoint_tolerance: 1e-7,
            max_iterations: 25,
            ode: Tolerance::default(),
            swing2_tolerance_scale: crate::control::swing::SWING2_TOLERANCE_SCALE,
            hip_path_step: crate::control::stance::HIP_PATH_STEP,
            toe_clearance_min: 1e-6,
            invariant_slack: 1e-6,
            coarse_samples: 32,
            foot_samples: 100,
            work_panels: 1,
            list_retries: 10,
            reach_retries: 5,
            reach_margin_step: 0.01,
            toe_off_retries: 4,
            toe_off_knee_step: 5f64.to_radians(),
        }
    }
}
