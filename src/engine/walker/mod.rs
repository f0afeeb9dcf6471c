//! The step loop (KLAW 1989 Figure 1, top to bottom): plan the step constraints, strike the heel,
//! shoot the stance, complete the hind leg through double support, find the stance leg's
//! heel-off, shoot the swing subphases, integrate the work, measure the step, and carry the
//! state and the warm starts to the next step.
mod stance;
mod swing;

use crate::control::shooting::{Memory1, Memory2, SolveError, SolveOptions, SolveReport};
use crate::control::stance::{StanceRun, StanceState};
use crate::control::swing::{Subphase, SwingSetup, SwingTrial};
use crate::dynamics::{StanceModel, SwingModel};
use crate::engine::error::{Invariant, SimulationError};
use crate::engine::parameters::EngineParameters;
use crate::engine::report::{Repairs, SolveRecord, StepReport};
use crate::engine::startup::Startup;
use crate::engine::work::{self, Work};
use crate::kinematics::GeometryError;
use crate::kinematics::foot::Foot;
use crate::kinematics::pelvis::{Determinants, PelvisMotion, Side};
use crate::kinematics::stance_leg::StanceLeg;
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::model::pelvis_speed::PelvisSpeedLaw;
use crate::numerics::ode::Segment;
use crate::plan::StepConstraints;
use crate::plan::gait::Gait;

use std::sync::OnceLock;

// the step records, the walk and the swing hip's velocity at the walker's paths, where the
// rest of the crate reads them
pub use crate::engine::step::{Step, Walk};
pub use swing::swing_hip_vy_end;

/// Walks step after step, carrying the state and the warm starts.
pub struct Walker {
    pub(crate) body: Body,
    pub(crate) attrs: Attributes,
    /// The tolerances and limits (today's values, [`EngineParameters::default`]).
    pub(super) parameters: EngineParameters,
    pub(super) stance_model: StanceModel,
    pub(super) swing_model: SwingModel,
    /// The last step's constraints and end state.
    pub(super) prev: Option<(StepConstraints, StanceState)>,
    pub(super) determinants: Determinants,
    /// The last step's stance leg: this step's hind leg.
    pub(super) prev_leg: Option<StanceLeg>,
    pub(super) stance_memory: Option<Memory2>,
    pub(super) swing1_memory: Option<Memory2>,
    pub(super) swing2_memory: Option<Memory1>,
    pub(super) swing3_memory: Option<Memory2>,
    /// The step sequences of the last step's kept trials (stance; swing1, swing2, swing3):
    /// the next step's first trials follow them ([`crate::numerics::ode::integrate_on`])
    /// instead of choosing their own.
    pub(super) stance_mesh: Option<StanceRun>,
    pub(super) swing_meshes: [Option<Segment<4>>; 3],
    t: f64,
    x_ankle: f64,
    index: usize,
    /// Right-hand-side evaluations of the current step, over all trials.
    pub(super) evaluations: u64,
    /// The retries' worth of change the steps from the second on start from.
    kept: Kept,
    /// Start the first steps' solves from the fitted guesses (`engine::startup`).
    startup_guesses: bool,
}

/// The solves' memories for the next step's warm starts: stance, swing1, swing2, swing3.
pub type Memories = (
    Option<Memory2>,
    Option<Memory2>,
    Option<Memory1>,
    Option<Memory2>,
);

/// What the phases of one step share: its constraints, side and determinants, where and when
/// it starts, how its solves start, and its heel-strike impulse.
pub(super) struct StepPlan {
    pub index: usize,
    pub gait: Gait,
    pub c: StepConstraints,
    /// The stance side.
    pub side: Side,
    /// The determinants of gait, with the step's pelvic list.
    pub det: Determinants,
    /// Time of the heel strike (s) and global x of the stance ankle (m).
    pub t0: f64,
    pub x0: f64,
    pub startup: Startup,
    /// The fraction of the new leg's axial velocity the heel-strike impulse removes
    /// ([`impact::heel_strike`](crate::dynamics::impact::heel_strike)).
    pub impulse: f64,
    /// κ_TO: the knee flexion the hind leg reaches at toe-off in this step's double support
    /// (rad).
    pub toe_off_knee: f64,
}

/// What one try of a step varies ([`Walker::step`]).
#[derive(Clone, Copy, Debug)]
struct Attempt {
    /// The pelvic list (rad).
    list: f64,
    /// The heel-strike impulse fraction.
    impulse: f64,
    /// The bounce's margin below the straight leg's reach (fraction of the bounce).
    reach_margin: f64,
    /// The toe-off knee κ_TO (rad).
    toe_off_knee: f64,
}

/// The retries' worth of change the steps from the second on start from: the most any of them
/// needed ([`Walker::step`]).
#[derive(Clone, Copy, Debug, Default)]
struct Kept {
    /// Tenths (1 / `list_retries`) of the attributes' pelvic list left out.
    list_lowered: usize,
    /// Hundredths (`reach_margin_step`) of the bounce added to `reach_margin`.
    reach_raised: usize,
    /// `toe_off_knee_step`s taken off the toe-off knee.
    knee_lowered: usize,
}

/// The least toe-off knee (rad): the bundled attribute table's least `toe_off_knee`.
fn toe_off_knee_floor() -> f64 {
    static FLOOR: OnceLock<f64> = OnceLock::new();
    *FLOOR.get_or_init(|| {
        let table = crate::model::attributes::AttributeTable::builtin();
        table.0["toe_off_knee"].min.to_radians()
    })
}

impl StepPlan {
    /// The pelvis's determinants at step time τ.
    pub fn pelvis(&self, tau: f64) -> PelvisMotion {
        self.det.at(self.side, tau, self.c.timing.t_step)
    }

    /// A failed solve of `phase` as the step's error.
    pub fn integration(&self, phase: &'static str) -> impl Fn(SolveError) -> SimulationError {
        let step = self.index;
        move |source| SimulationError::Integration {
            step,
            phase,
            source,
        }
    }

    /// A pose the stance leg cannot take in `phase` as the step's error.
    pub fn invariant(&self, phase: &'static str) -> impl Fn(GeometryError) -> SimulationError {
        let step = self.index;
        move |e| SimulationError::Invariant {
            step,
            phase,
            source: Invariant::Geometry(e),
        }
    }

    /// The record of `phase`'s solve, or the step's error if it did not converge.
    pub fn converged(
        &self,
        phase: &'static str,
        report: SolveReport,
    ) -> Result<SolveRecord, SimulationError> {
        if report.converged {
            Ok(SolveRecord { phase, report })
        } else {
            Err(SimulationError::NotConverged {
                step: self.index,
                phase,
                residual: report.residual,
                iterations: report.iterations,
            })
        }
    }
}

/// `attrs` for a walk of `gaits` by `body`: the pelvic list and rotation at the gaits' mean
/// velocity ([`PelvisSpeedLaw::scale`]), the same in every step, so that the pelvis hands over
/// smoothly when the speed changes; the walk records these.
pub fn walk_attributes(body: &Body, attrs: &Attributes, gaits: &[Gait]) -> Attributes {
    static LAW: OnceLock<PelvisSpeedLaw> = OnceLock::new();
    if gaits.is_empty() {
        return attrs.clone();
    }
    // the first velocity plus the mean difference: exactly the velocity of a steady walk
    let v0 = gaits[0].velocity;
    let v = v0 + gaits.iter().map(|g| g.velocity - v0).sum::<f64>() / gaits.len() as f64;
    LAW.get_or_init(PelvisSpeedLaw::default)
        .scale(attrs, v, body.l1)
}

/// Simulate one step per entry of `gaits` (parameters may change from step to step), with the
/// walk's attributes ([`walk_attributes`]).
pub fn simulate(body: Body, attrs: Attributes, gaits: &[Gait]) -> Result<Walk, SimulationError> {
    simulate_with(body, attrs, gaits, EngineParameters::default())
}

/// [`simulate`] with the engine's model constants `parameters` (e.g. a user's
/// `models/engine.toml`, [`EngineParameters::parse`]).
pub fn simulate_with(
    body: Body,
    attrs: Attributes,
    gaits: &[Gait],
    parameters: EngineParameters,
) -> Result<Walk, SimulationError> {
    let attrs = walk_attributes(&body, &attrs, gaits);
    let mut walker = Walker::new(body, attrs.clone()).with_parameters(parameters);
    let steps = gaits
        .iter()
        .map(|g| walker.step(*g))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Walk { body, attrs, steps })
}

impl Walker {
    /// A walker for `body` and `attrs` at the first step, with the engine's parameters
    /// ([`EngineParameters::default`]) and the start-up guesses on. The attributes are used as
    /// given: [`simulate`] passes the walk's ([`walk_attributes`], the pelvis at the walk's
    /// speed).
    pub fn new(body: Body, attrs: Attributes) -> Self {
        let determinants = Determinants::new(&attrs, body.l0);
        Walker {
            stance_model: StanceModel::new(&body),
            swing_model: SwingModel::new(&body),
            body,
            attrs,
            parameters: EngineParameters::default(),
            prev: None,
            determinants,
            prev_leg: None,
            stance_memory: None,
            swing1_memory: None,
            swing2_memory: None,
            swing3_memory: None,
            stance_mesh: None,
            swing_meshes: [None, None, None],
            t: 0.0,
            x_ankle: 0.0,
            index: 0,
            evaluations: 0,
            kept: Kept::default(),
            startup_guesses: true,
        }
    }

    /// The same walker with the tolerances and limits `parameters`.
    pub fn with_parameters(mut self, parameters: EngineParameters) -> Self {
        self.parameters = parameters;
        self
    }

    /// The same walker with every solve started plainly (body-scaled constants, zero torques,
    /// difference Jacobians) instead of from the fitted start-up guesses: what
    /// `measure/startup_fit.rs` fits, so that its output does not depend on its last output.
    pub fn without_startup_guesses(mut self) -> Self {
        self.startup_guesses = false;
        self
    }

    /// What the last step's solves leave for the next one's warm starts (stance, swing1,
    /// swing2, swing3): `measure/startup_fit.rs` reads the cold Jacobians from it.
    pub fn memories(&self) -> Memories {
        (
            self.stance_memory,
            self.swing1_memory,
            self.swing2_memory,
            self.swing3_memory,
        )
    }

    /// Simulate the next step with gait `gait`, trying it again where a failure has a mend
    /// \[ours\]:
    /// - the stance hip falling under y_hs in the loading response
    ///   ([`SimulationError::is_loading_failure`]): a stronger heel-strike impulse;
    /// - the flat stance foot out of the straight leg's reach
    ///   ([`SimulationError::is_reach_failure`]): the bounce's reach margin raised by
    ///   [`EngineParameters::reach_margin_step`] at a time ([`EngineParameters::reach_retries`]);
    ///   where the reach cuts the bounce, less list only lets the bounce rise again;
    /// - the rolling hind foot out of the hip's reach in double support
    ///   ([`SimulationError::is_toe_off_failure`]): the toe-off knee κ_TO lowered by
    ///   [`EngineParameters::toe_off_knee_step`] at a time ([`EngineParameters::toe_off_retries`],
    ///   never under the attribute's least value): a straighter trailing knee reaches further,
    ///   as long steps at a slow cadence need;
    /// - a failure less pelvic list can mend ([`SimulationError::is_list_failure`]: the swing
    ///   foot under the ground, no convergence of the swing, the stance hip under its
    ///   heel-strike height, the flat foot out of reach once the margin's retries are spent):
    ///   the list lowered by a tenth of the attribute's at a time, down to none
    ///   ([`EngineParameters::list_retries`]). The list lowers the swing hip by (l0/2) sin L at
    ///   mid step, ≈ 5 mm, which the fastest walks of short bodies (v = 2 m/s at H = 1.5 m)
    ///   cannot spare, and raises the stance hip joint by as much above the pelvis centre at
    ///   mid-stance, which the slowest walks of tall ones (0.4 m/s at H ≥ 1.7 m, height budget
    ///   E ≈ 14 mm) cannot.
    ///
    /// The later steps start from the list, margin and toe-off knee the step walked with, so
    /// that the steady steps are the same on both sides; the first step, from the start-up
    /// posture, changes its own only. The list used is in the step's `determinants`.
    pub fn step(&mut self, gait: Gait) -> Result<Step, SimulationError> {
        let saved = self.memories();
        let first = self.index == 0;
        let p = self.parameters;
        let mut kept = self.kept;
        let mut impulse = self.attrs.heel_strike_impulse;
        let mut impulse_raised = 0;
        let knee_floor = toe_off_knee_floor();
        self.evaluations = 0;
        loop {
            let knee = self.attrs.toe_off_knee - kept.knee_lowered as f64 * p.toe_off_knee_step;
            let attempt = Attempt {
                list: self.attrs.pelvic_list
                    * (1.0 - kept.list_lowered as f64 / p.list_retries.max(1) as f64),
                impulse,
                reach_margin: p.reach_margin + kept.reach_raised as f64 * p.reach_margin_step,
                toe_off_knee: knee.max(knee_floor),
            };
            match self.step_with(gait, attempt) {
                Err(e) if e.is_loading_failure() && impulse < 1.0 => {
                    impulse_raised += 1;
                    impulse = if impulse < 0.5 {
                        0.5 * (1.0 + impulse)
                    } else {
                        1.0
                    };
                }
                Err(e) if kept.reach_raised < p.reach_retries && e.is_reach_failure() => {
                    kept.reach_raised += 1;
                }
                Err(e)
                    if kept.knee_lowered < p.toe_off_retries
                        && knee > knee_floor
                        && e.is_toe_off_failure() =>
                {
                    kept.knee_lowered += 1;
                }
                Err(e) if kept.list_lowered < p.list_retries && e.is_list_failure() => {
                    kept.list_lowered += 1;
                }
                result => {
                    if !first {
                        self.kept = kept;
                    }
                    let repairs = Repairs {
                        impulse: impulse_raised,
                        reach: kept.reach_raised as u32,
                        toe_off_knee: kept.knee_lowered as u32,
                        list: kept.list_lowered as u32,
                    };
                    return result.map(|mut step| {
                        step.report.repairs = repairs;
                        step
                    });
                }
            }
            self.restore(saved);
        }
    }

    /// Put back the solves' memories of before a failed try of a step.
    fn restore(&mut self, saved: Memories) {
        (
            self.stance_memory,
            self.swing1_memory,
            self.swing2_memory,
            self.swing3_memory,
        ) = saved;
    }

    /// One try of a step, phase after phase.
    fn step_with(&mut self, gait: Gait, attempt: Attempt) -> Result<Step, SimulationError> {
        let plan = self.plan(gait, attempt)?;
        let (prev_c, y0, impact) = self.heel_strike(&plan);
        let setup = self.stance_setup(&prev_c, &plan);
        let (stance, stance_solve) = self.solve_stance(&plan, &setup, y0)?;
        let hips = stance::HipJoints {
            plan: &plan,
            stance: &stance,
            setup: &setup,
        };
        let stance_leg = self.heel_off(&plan, &hips, prev_c.sole_angle)?;
        let toe_off = self.double_support(&plan, &hips, &stance_leg)?;
        let (hip_path, hip_vy_end) =
            swing::hip_path(&plan, &stance, &setup, self.parameters.hip_path_step);
        let sw = SwingSetup::new(
            self.swing_model,
            &hip_path,
            hip_vy_end,
            &plan.c,
            &self.attrs,
            &self.parameters.servos,
        );
        let [mesh1, mesh2, mesh3] = std::mem::take(&mut self.swing_meshes);
        let (s1, swing1) = self.swing1(&plan, &sw, toe_off.state, mesh1)?;
        let (s2, swing2) = self.swing2(&plan, &sw, s1.segment.y1, mesh2)?;
        let (s3, swing3) = self.swing3(&plan, &sw, s2.segment.y1, mesh3)?;
        self.swing_meshes = [&s1, &s2, &s3].map(|s| Some(s.segment.clone()));
        let work = self.work(&sw, &setup, &stance, [&s1, &s2, &s3]);
        let impact = (impact.speed_ratio, plan.impulse);
        let report =
            StepReport::unmeasured(plan.index, &gait, &plan.c, impact, plan.det.list, work);
        let step = Step {
            index: plan.index,
            t_start: plan.t0,
            x_ankle: plan.x0,
            constraints: plan.c,
            stance_setup: setup,
            stance,
            solves: vec![stance_solve, swing1, swing2, swing3],
            side: plan.side,
            determinants: plan.det,
            stance_leg,
            hind_leg: toe_off.hind_leg,
            swing: [s1, s2, s3].map(|s| (s.sub, s.segment)).into(),
            theta5_off: toe_off.theta5,
            theta6_off: toe_off.theta6,
            toe_clearance: self.attrs.toe_clearance,
            lowest_at: 0.0,
            report,
        };
        self.finish(step, gait)
    }

    /// The step's constraints (the high level, KLAW 1989 §3, spec §3), side, determinants and start.
    fn plan(&self, gait: Gait, attempt: Attempt) -> Result<StepPlan, SimulationError> {
        let det = Determinants {
            list: attempt.list,
            ..self.determinants
        };
        let c = StepConstraints::new(&self.body, &self.attrs, gait)?;
        let y_start = self.prev.as_ref().map_or(c.hip[1], |(p, _)| p.hip[1]);
        let c = c.within_reach(&self.body, &det, y_start, attempt.reach_margin);
        let index = self.index;
        Ok(StepPlan {
            index,
            gait,
            c,
            side: Side::of_step(index),
            det,
            t0: self.t,
            x0: self.x_ankle,
            startup: Startup {
                enabled: self.startup_guesses,
                index,
                froude: gait.velocity / (crate::model::GRAVITY * self.body.l1).sqrt(),
            },
            impulse: attempt.impulse,
            toe_off_knee: attempt.toe_off_knee,
        })
    }

    /// The unit of the solves' torques: M l1 (N m).
    pub(super) fn torque_unit(&self) -> f64 {
        self.body.mass * self.body.l1
    }

    /// The shooting options of a solve to tolerance `tol`.
    pub(super) fn options(&self, tol: f64) -> SolveOptions {
        SolveOptions {
            tol,
            max_iterations: self.parameters.max_iterations,
        }
    }

    /// Mechanical work of the actuators over the step: the stance's and the swing's
    /// (`engine::work`).
    fn work(
        &self,
        sw: &SwingSetup,
        setup: &crate::control::stance::StanceSetup,
        stance: &StanceRun,
        swing: [&SwingTrial; 3],
    ) -> Work {
        let panels = self.parameters.work_panels;
        let subphases: [(Subphase, &Segment<4>); 3] = swing.map(|s| (s.sub, &s.segment));
        work::stance_work(setup, stance, panels) + work::swing_work(sw, &subphases, panels)
    }

    /// Measure the step, check its invariants, and carry its end to the next step.
    fn finish(&mut self, mut step: Step, gait: Gait) -> Result<Step, SimulationError> {
        step.measure(&Foot::new(&self.body), &self.parameters);
        step.report.rhs_evaluations = self.evaluations;
        step.check_invariants(&self.parameters)?;
        let y_end = step
            .stance
            .segments
            .last()
            .expect("a converged run has segments")
            .0
            .y1;
        self.prev = Some((step.constraints, y_end));
        self.prev_leg = Some(step.stance_leg);
        self.t += step.constraints.timing.t_step;
        self.x_ankle += gait.step_length;
        self.index += 1;
        Ok(step)
    }
}
