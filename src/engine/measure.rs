//! The measurements of a step (spec §4, §5, §10): its end-condition errors, what it achieved,
//! the hip's excursion and lowest point, the swing foot's clearance, the knee's peak flexion and
//! the heel's landing velocity; and the invariants a converged step must meet.
//!
//! The extremes are the [`minima`] of uniform samples refined by Brent's search down to 1e-5 of
//! the interval: at a smooth minimum the value's error is f″ δ² / 2, with δ = 1e-5 of a 0.4 s
//! swing 1e-8 m for the foot (f″ ≈ 10 m/s²) and 1e-6 rad for the knee (≈ 500 rad/s²);
//! `tests/walk.rs` checks them against dense sampling.
use crate::engine::error::{Invariant, SimulationError};
use crate::engine::parameters::EngineParameters;
use crate::engine::report::Achieved;
use crate::engine::step::Step;
use crate::kinematics::foot::Foot;
use crate::numerics::minimise::{least_in, minima};

impl Step {
    /// Fill the report: end conditions, step length achieved, hip excursion, foot clearance.
    pub(super) fn measure(&mut self, foot: &Foot, p: &EngineParameters) {
        let c = self.constraints;
        let t = c.timing;
        let y_end = self.stance.segments.last().expect("converged").0.y1;
        let sw_end = self.swing.last().expect("converged").1.y1;
        let end_error = [
            y_end[1] - c.theta1,
            y_end[0] - c.w,
            sw_end[0] - c.theta3,
            sw_end[1] - c.theta4,
        ]
        .iter()
        .fold(0.0_f64, |m, e| m.max(e.abs()));
        let strike = self.swing_pose(t.t_step, foot);
        // the heel's contact velocity: a backward difference over 1e-6 s
        let dt = 1e-6;
        let before = self.swing_pose(t.t_step - dt, foot);
        let step_length = strike.foot.heel[0] + foot.l8;
        // hip: its highest and lowest points through the stance
        let hip_y = |tau: f64| self.hip(tau)[1];
        let (y_min, _) = least_in(
            &minima(hip_y, 0.0, t.t_step, p.coarse_samples),
            0.0,
            t.t_step,
        );
        let (y_max, _) = least_in(
            &minima(|tau| -hip_y(tau), 0.0, t.t_step, p.coarse_samples),
            0.0,
            t.t_step,
        );
        let y_max = -y_max;
        let s = &self.stance_setup;
        // swing foot: lowest point over the swing, and in mid swing; the knee's peak flexion
        let (t_off, t_swing) = (t.t_ds, t.t_swing);
        let foot_y = |tau: f64| self.swing_pose(tau, foot).foot.lowest();
        let swing_end = t_off + t_swing;
        let (mid_lo, mid_hi) = (t_off + 0.25 * t_swing, t_off + 0.75 * t_swing);
        // the least over mid swing is at one of its ends or at a local minimum inside
        let mut heights = minima(foot_y, t_off, swing_end, p.foot_samples);
        heights.extend([(mid_lo, foot_y(mid_lo)), (mid_hi, foot_y(mid_hi))]);
        let (mid, _) = least_in(&heights, mid_lo, mid_hi);
        let (lowest, lowest_at) = least_in(&heights, t_off, swing_end);
        let knee = |tau: f64| {
            let i = self
                .swing
                .partition_point(|(_, s)| s.t1 < tau)
                .min(self.swing.len() - 1);
            self.swing[i].1.state(tau)[1]
        };
        let (knee_peak, _) = least_in(
            &minima(|tau| -knee(tau), t_off, swing_end, p.coarse_samples),
            t_off,
            swing_end,
        );
        let knee_peak = -knee_peak;
        self.lowest_at = (lowest_at - t_off) / t_swing;
        let r = &mut self.report;
        r.solves = self.solves.clone();
        r.achieved = Achieved {
            velocity: step_length / t.t_step,
            step_length,
            duration: t.t_step,
        };
        r.end_condition_error = end_error;
        r.heel_height_at_strike = strike.foot.heel[1];
        r.heel_contact_velocity = (strike.foot.heel[1] - before.foot.heel[1]) / dt;
        r.hip_excursion = y_max - s.y_end;
        r.hip_min_margin = y_min - s.y_start.min(s.y_end);
        r.min_foot_height = lowest;
        r.min_toe_clearance = mid;
        r.peak_swing_knee_flexion = knee_peak;
    }

    /// Invariants of a converged step (spec §4, §5, §10): the hip never below its heel-strike height,
    /// no point of the swing foot under the ground, the toe clear of it in mid swing.
    pub(super) fn check_invariants(&self, p: &EngineParameters) -> Result<(), SimulationError> {
        let r = &self.report;
        let fail = |phase: &'static str, source: Invariant| {
            Err(SimulationError::Invariant {
                step: self.index,
                phase,
                source,
            })
        };
        if r.hip_min_margin < -p.invariant_slack {
            return fail(
                "stance",
                Invariant::HipDrops {
                    depth: -r.hip_min_margin,
                },
            );
        }
        // a positive clearance, by more than the 1e-6 m to which the feet are placed (spec §5):
        // where the toe-clearance rule cannot lift the toe it rests on the ground, at ±1e-16 m
        // of rounding, and that walk must not pass or fail by the sign of the rounding
        if r.min_toe_clearance <= p.toe_clearance_min {
            return fail(
                "swing",
                Invariant::ToeTouches {
                    clearance: r.min_toe_clearance,
                },
            );
        }
        if r.min_foot_height < -p.invariant_slack {
            return fail(
                "swing",
                Invariant::FootUnderGround {
                    depth: -r.min_foot_height,
                    at: self.lowest_at,
                },
            );
        }
        Ok(())
    }
}
