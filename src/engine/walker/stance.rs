//! The walker's phases on the ground (KLAW 1989 §4, §4.2; spec §4, §7): the heel strike, the stance
//! solve (unknowns τ1, p; end conditions θ1*, w*), the previous stance leg completing its stance
//! through double support to toe-off, and this step's stance leg to its heel-off.
use nalgebra::{Vector2, Vector3};
use std::f64::consts::PI;

use super::{StepPlan, Walker};
use crate::control::shooting::{self, Memory2, Start2};
use crate::control::stance::{StanceRun, StanceSetup, StanceState, TerminalStance};
use crate::control::swing::SwingState;
use crate::dynamics::impact::{self, ImpactReport};
use crate::engine::error::SimulationError;
use crate::engine::report::SolveRecord;
use crate::engine::startup::{tables, with_fallback};
use crate::engine::trials::Trials;
use crate::kinematics::pelvis::Side;
use crate::kinematics::stance_leg::{KneeCurve, StanceLeg};
use crate::plan::StepConstraints;

/// The hip joints of a step, hung from its stance run's hip and moved by the determinants of
/// gait.
pub(super) struct HipJoints<'a> {
    pub plan: &'a StepPlan,
    pub stance: &'a StanceRun,
    pub setup: &'a StanceSetup,
}

impl HipJoints<'_> {
    /// The hip joint of `leg` at step time τ: world (x, y) and lateral offset from its ankle.
    pub fn at(&self, leg: Side, tau: f64) -> ([f64; 2], f64) {
        let det = &self.plan.det;
        let h = self.stance.hip_position(self.setup, tau);
        let p = self.plan.pelvis(tau);
        let o = det.engine_offset(leg, self.plan.side, &p);
        (
            [self.plan.x0 + h[0] + o[0], h[1] + o[1]],
            det.lateral_offset(leg, &p, o),
        )
    }
}

/// The hind leg at toe-off: the leg, its state as the swing's initial state (θ3, θ4 and their
/// rates), and the foot's ankle dorsiflexion θ5 and toe angle θ6.
pub(super) struct ToeOff {
    pub hind_leg: StanceLeg,
    pub state: SwingState,
    pub theta5: f64,
    pub theta6: f64,
}

impl Walker {
    /// The heel strike that starts the step (spec §7): the previous step's constraints, the
    /// stance's initial state about the new pivot after the impulse, and the impact's report.
    pub(super) fn heel_strike(
        &self,
        plan: &StepPlan,
    ) -> (StepConstraints, StanceState, ImpactReport) {
        let c = plan.c;
        // pre-impact posture and rates about the new pivot
        let (prev_c, q, hip_v, trunk_rate) = match &self.prev {
            // first step [ours]: the heel-strike posture of the step's own lead, hip moving
            // horizontally at v
            None => (
                c,
                Vector3::new(c.lead.1, c.lead.0, self.attrs.trunk_lean),
                [plan.gait.velocity, 0.0],
                0.0,
            ),
            Some((pc, y_end)) => {
                let q_old = Vector3::new(y_end[0], y_end[1], y_end[2]);
                let qd_old = Vector3::new(y_end[3], y_end[4], y_end[5]);
                let v = self.stance_model.hip_velocity(&q_old, &qd_old);
                (
                    *pc,
                    Vector3::new(pc.lead.1, pc.lead.0, y_end[2]),
                    v,
                    y_end[5],
                )
            }
        };
        let qd_minus = impact::rates_about_pivot(&q, hip_v, trunk_rate);
        let (qd, impact) = impact::heel_strike(&self.stance_model, &q, &qd_minus, plan.impulse);
        let y0 = StanceState::from([q[0], q[1], q[2], qd[0], qd[1], qd[2]]);
        (prev_c, y0, impact)
    }

    /// The stance of a step from the previous step's constraints `prev` to the plan's
    /// (spec §4): the leg axis and trunk servos from the engine's constants, the terminal stance of the
    /// virtual leg with the plan's pelvic list.
    pub(super) fn stance_setup(&self, prev: &StepConstraints, plan: &StepPlan) -> StanceSetup {
        let (a, c) = (&self.attrs, &plan.c);
        let m = self.stance_model;
        let b = &self.body;
        let y_mid = 0.5 * (prev.hip[1] + c.hip[1]) + c.bounce;
        let servos = &self.parameters.servos;
        let ww = 2.0 * PI * servos.leg_frequency;
        let w2 = 2.0 * PI * servos.trunk_frequency;
        let j2 = m.trunk_inertia();
        StanceSetup {
            model: m,
            l1: self.body.l1,
            k_w: m.m2 * ww * ww,
            d_w: 2.0 * servos.damping_ratio * m.m2 * ww,
            k_2: j2 * w2 * w2,
            d_2: 2.0 * servos.trunk_damping_ratio * j2 * w2,
            theta2_ref: a.trunk_lean,
            t_step: c.timing.t_step,
            torque_off: self.parameters.torque_off,
            theta1_start: -prev.lead.0,
            theta1_end: c.theta1,
            w_end: c.w,
            y_start: prev.hip[1],
            y_end: c.hip[1],
            bounce: c.bounce,
            terminal: TerminalStance::new(
                y_mid,
                &plan.det,
                (c.theta1, c.w),
                (b.l3, b.l4, b.l9, b.ankle_to_metatarsal_horizontal()),
                a.heel_off_dorsiflexion,
                self.parameters.stance_reference,
            ),
        }
    }

    /// The stance solve (KLAW 1989 §4.1, spec §6): the leg torque τ1 and the position actuator's p that
    /// bring the stance from `y0` to θ1*, w* at heel strike (Broyden), its kept trial densified.
    pub(super) fn solve_stance(
        &mut self,
        plan: &StepPlan,
        setup: &StanceSetup,
        y0: StanceState,
    ) -> Result<(StanceRun, SolveRecord), SimulationError> {
        let (torque, l1) = (self.torque_unit(), self.body.l1);
        // the plain cold start (the fallback): a body-scaled step-0 solution of the default walk
        let (start, fallback) = plan.startup.start2(
            self.stance_memory,
            [0, 1],
            [torque, l1],
            (tables().cold_stance, [1.0, l1]),
            Start2::Cold {
                x0: Vector2::new(2.0 * torque, 0.0055 * l1),
                h: Vector2::new(0.01 * torque, 1e-3),
            },
        );
        let trials = Trials::new(self.stance_mesh.take());
        let tol = self.parameters.ode;
        let residual = |x: Vector2<f64>| {
            trials.run(|mesh| StanceRun::simulate_on(setup, y0, x[0], x[1], tol, mesh))
        };
        let options = self.options(self.parameters.solve_tolerance);
        let solved = with_fallback(start, fallback, |start| {
            shooting::solve2(residual, start, &options).map(|(x, r, m)| ((x, m), r))
        });
        let (best, evaluations) = trials.finish();
        self.evaluations += evaluations;
        let ((x, memory), report) = solved.map_err(plan.integration("stance"))?;
        let mut stance = best.expect("at least one trial ran");
        self.evaluations += u64::from(stance.densify(setup));
        let record = plan.converged("stance", report)?;
        debug_assert!(stance.tau1 == x[0] && stance.p == x[1]);
        self.stance_memory = Some(memory);
        if plan.index >= 3 {
            self.share_step_ratio(&memory);
        }
        self.stance_mesh = Some(stance.clone());
        Ok((stance, record))
    }

    /// \[ours\] The swings' warm starts extrapolate with the stance's step ratio: the walk
    /// approaches its limit cycle with one ratio for all seven unknowns (λ ≈ −0.04 to −0.15 over
    /// the grid), which the stance's history shows from step 2 on while the swings' own start
    /// with the first step's (+0.03 to +0.4 for swing1's A at step 2).
    fn share_step_ratio(&mut self, stance: &Memory2) {
        let ratio = shooting::step_ratio(
            stance.x.into(),
            [stance.earlier[0].into(), stance.earlier[1].into()],
        );
        for m in [&mut self.swing1_memory, &mut self.swing3_memory]
            .into_iter()
            .flatten()
        {
            m.ratio = ratio;
        }
        if let Some(m) = self.swing2_memory.as_mut() {
            m.ratio = ratio;
        }
    }

    /// Double support (spec §7): the previous step's stance leg completes its stance to toe-off
    /// at t_ds, the knee reaching the plan's κ_TO; θ̇3 at toe-off by a 4th-order central
    /// difference. The first step's hind leg mirrors this step's `stance_leg` one step earlier.
    pub(super) fn double_support(
        &self,
        plan: &StepPlan,
        hips: &HipJoints,
        stance_leg: &StanceLeg,
    ) -> Result<ToeOff, SimulationError> {
        let (t, t0) = (plan.c.timing, plan.t0);
        let kappa_to = plan.toe_off_knee;
        let mut hind = self
            .prev_leg
            .unwrap_or_else(|| self.first_hind_leg(plan, stance_leg));
        let hind_side = plan.side.other();
        let invariant = plan.invariant("double_support");
        hind.continue_to_toe_off(|tw| hips.at(hind_side, tw - t0), t0, t0 + t.t_ds, kappa_to)
            .map_err(&invariant)?;
        let hind_pose = |tau: f64| {
            let (h, dz) = hips.at(hind_side, tau);
            hind.pose(h, dz, t0 + tau)
        };
        let off = hind_pose(t.t_ds).map_err(&invariant)?;
        let h = 1e-4 * t.t_ds;
        let theta3_at = |tau: f64| hind_pose(tau).map(|p| p.theta3).map_err(&invariant);
        let d3 = (-theta3_at(t.t_ds + 2.0 * h)? + 8.0 * theta3_at(t.t_ds + h)?
            - 8.0 * theta3_at(t.t_ds - h)?
            + theta3_at(t.t_ds - 2.0 * h)?)
            / (12.0 * h);
        let knee_rate = hind.knee_curve(t0 + t.t_ds).map_or(0.0, |k| k.1);
        Ok(ToeOff {
            hind_leg: hind,
            state: SwingState::from([off.theta3, off.theta4, d3, knee_rate]),
            theta5: off.theta3 + off.theta4 - off.pitch,
            theta6: off.theta6,
        })
    }

    /// \[ours\] The first step's hind leg: a foot flat at −sl whose knee follows the plan of
    /// this step's own stance leg `mirror` one step earlier (its heel-off, knee and rate there,
    /// and κ_TO at this step's toe-off), as the hind leg of a steady gait would; with no heel-off
    /// in `mirror`, its heel is already off at the heel strike with the knee at κ_hs. (Starting
    /// from κ_hs at the heel strike instead handed the swing a knee flexing at 2.4–5.5 times the
    /// steady rate at toe-off, and the start step's toe went 13–16 mm under the floor at
    /// 1.6–1.7 m/s in de Leva's female bodies: docs/coverage.md.)
    fn first_hind_leg(&self, plan: &StepPlan, mirror: &StanceLeg) -> StanceLeg {
        let (t, t0) = (plan.c.timing, plan.t0);
        let mut leg = StanceLeg::new(
            &self.body,
            plan.x0 - plan.gait.step_length,
            t0 - t.t_step,
            0.0,
            self.attrs.foot_flat_time * t.t_cycle,
            self.attrs.heel_off_dorsiflexion,
            self.attrs.metatarsal_limit,
        );
        leg.heel_off = Some(match mirror.heel_off {
            Some(k) => KneeCurve {
                t0: k.t0 - t.t_step,
                t_to: t0 + t.t_ds,
                ..k
            },
            None => KneeCurve::new(
                t0,
                self.attrs.heel_strike_knee,
                0.0,
                t0 + t.t_ds,
                plan.toe_off_knee,
            ),
        });
        leg
    }

    /// This step's stance leg from its heel strike (the sole at the previous step's
    /// `sole_angle`) to its heel-off, planned to reach κ_TO at the next toe-off (spec §7).
    pub(super) fn heel_off(
        &self,
        plan: &StepPlan,
        hips: &HipJoints,
        sole_angle: f64,
    ) -> Result<StanceLeg, SimulationError> {
        let (t, t0) = (plan.c.timing, plan.t0);
        let mut leg = StanceLeg::new(
            &self.body,
            plan.x0,
            t0,
            sole_angle,
            self.attrs.foot_flat_time * t.t_cycle,
            self.attrs.heel_off_dorsiflexion,
            self.attrs.metatarsal_limit,
        );
        leg.find_heel_off(
            |tw| hips.at(plan.side, tw - t0),
            t0,
            t0 + t.t_step,
            t0 + t.t_step + t.t_ds,
            self.attrs.toe_off_knee,
        )
        .map_err(plan.invariant("stance"))?;
        Ok(leg)
    }
}
