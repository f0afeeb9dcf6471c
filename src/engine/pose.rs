//! A step at one instant (KLAW 1989 §4.2, spec §5, §7): the stance state, the pelvis's
//! determinants and both legs' poses, from which the figure and the engine's state frames are
//! drawn; and the swing foot's ankle and toe rule.
use nalgebra::Vector3;
use std::f64::consts::PI;

use crate::control::stance::StanceState;
use crate::control::swing;
use crate::engine::report::StateFrame;
use crate::engine::step::Step;
use crate::kinematics::GeometryError;
use crate::kinematics::foot::{Foot, FootPoints};
use crate::kinematics::pelvis::{Determinants, PelvisMotion, Side, fold_height};
use crate::kinematics::stance_leg::{LegPose, leg_points, leg_points_sc};
use crate::plan::StepConstraints;

/// \[ours\] Fraction of swing1 at which the swing ankle is back at neutral
/// ([`Step::swing_foot_angles`]): a modelling constant, not one of the attribute table's 28.
const ANKLE_NEUTRAL: f64 = 0.8;

/// The swing leg at one instant: subphase, in-plane angles, and points (x relative to the
/// stance ankle, world heights; the hip joint's lateral offset from the ankle `dz`).
#[derive(Clone, Copy, Debug)]
pub struct SwingPose {
    pub(crate) phase: &'static str,
    pub(crate) theta3: f64,
    /// θ4: the knee's flexion (rad; spec §1).
    pub theta4: f64,
    /// (sin, cos) of θ3 and of θ3 + θ4, as [`leg_points`] (or the hind leg's pose) computed
    /// them.
    pub(crate) sin_cos: [(f64, f64); 2],
    pub(crate) dz: f64,
    pub(crate) knee: [f64; 2],
    pub(crate) ankle: [f64; 2],
    /// The foot's heel, metatarsal joint and toe tip.
    pub foot: FootPoints,
}

/// A step at one instant: what the figure hangs from, evaluated once ([`Step::at`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Instant {
    /// Step time τ (s).
    pub tau: f64,
    /// The stance state and whether the knee is locked.
    pub state: StanceState,
    pub locked: bool,
    /// The dynamic hip, the pelvis centre (x relative to the stance ankle): [`Step::hip`].
    pub centre: [f64; 2],
    /// The determinants: [`Step::pelvis`].
    pub pelvis: PelvisMotion,
    /// [`Determinants::hip_offset`] of the right and the left hip joint.
    pub hip_offsets: [[f64; 3]; 2],
    /// [`Determinants::centre_shift`]: the pelvis centre relative to the dynamic hip.
    pub shift: [f64; 3],
    /// [`Determinants::ankle_z`] of the right and the left ankle.
    pub ankle_z: [f64; 2],
}

impl Instant {
    fn index(side: Side) -> usize {
        match side {
            Side::Right => 0,
            Side::Left => 1,
        }
    }

    /// The hip joint of `leg` relative to the pelvis centre (m, world axes).
    pub fn hip_offset(&self, leg: Side) -> [f64; 3] {
        self.hip_offsets[Self::index(leg)]
    }

    /// [`Step::hip_joint`]: the hip joint of `leg` (x relative to the stance ankle, world y)
    /// and [`Determinants::lateral_offset`] from that leg's ankle.
    pub fn hip_joint(&self, leg: Side) -> ([f64; 2], f64) {
        let o = self.hip_offset(leg);
        let d = self.shift;
        (
            [self.centre[0] + d[0] + o[0], self.centre[1] + d[1] + o[1]],
            self.pelvis.lateral + d[2] + o[2] - self.ankle_z[Self::index(leg)],
        )
    }

    /// The pelvis centre (x relative to the stance ankle, world y, world z).
    pub fn pelvis_centre(&self) -> [f64; 3] {
        let d = self.shift;
        [
            self.centre[0] + d[0],
            self.centre[1] + d[1],
            self.pelvis.lateral + d[2],
        ]
    }
}

impl Step {
    /// The dynamic hip, the pelvis centre (x relative to the stance ankle), at step time τ.
    pub fn hip(&self, tau: f64) -> [f64; 2] {
        self.stance.hip_position(&self.stance_setup, tau)
    }

    /// The pelvis's determinants at step time τ.
    pub(crate) fn pelvis(&self, tau: f64) -> PelvisMotion {
        self.determinants
            .at(self.side, tau, self.constraints.timing.t_step)
    }

    /// The hip joint of `leg` (x relative to the stance ankle, world y) and its lateral offset
    /// from that leg's ankle, at step time τ.
    pub fn hip_joint(&self, leg: Side, tau: f64) -> ([f64; 2], f64) {
        self.at(tau).hip_joint(leg)
    }

    /// The stance state, the dynamic hip and the pelvis at step time τ, each evaluated once.
    pub(crate) fn at(&self, tau: f64) -> Instant {
        let (state, locked) = self.stance.state(tau);
        let centre = self
            .stance_setup
            .model
            .hip(&Vector3::new(state[0], state[1], state[2]));
        let pelvis = self.pelvis(tau);
        let right = self.determinants.hip_offset(Side::Right, &pelvis);
        let shift = self.determinants.centre_shift(self.side, &pelvis);
        Instant {
            tau,
            state,
            locked,
            centre,
            pelvis,
            // hip_offset(Left) is hip_offset(Right) with the half width negated: exactly −right
            hip_offsets: [right, right.map(|x| -x)],
            shift,
            ankle_z: [
                self.determinants.ankle_z(Side::Right),
                self.determinants.ankle_z(Side::Left),
            ],
        }
    }

    /// The swing-side hip joint relative to the pelvis centre in the swing leg's plane, at step
    /// time τ: the offset the swing dynamics hang from.
    pub fn swing_offset(&self, tau: f64) -> [f64; 2] {
        swing_hip_offset(
            &self.determinants,
            self.side,
            &self.constraints,
            &self.pelvis(tau),
        )
    }

    /// The stance leg's pose at step time τ (x relative to the stance ankle).
    pub(crate) fn stance_pose(&self, tau: f64) -> Result<LegPose, GeometryError> {
        self.stance_pose_at(&self.at(tau))
    }

    /// [`Self::stance_pose`] at an instant of this step.
    pub(crate) fn stance_pose_at(&self, now: &Instant) -> Result<LegPose, GeometryError> {
        let (h, dz) = now.hip_joint(self.side);
        let mut p =
            self.stance_leg
                .pose([h[0] + self.x_ankle, h[1]], dz, self.t_start + now.tau)?;
        shift_pose(&mut p, -self.x_ankle);
        Ok(p)
    }

    /// The swing foot's ankle dorsiflexion θ5 and toe angle θ6 at step time τ ≥ t_ds (spec §5
    /// \[ours\]): θ5 linear from its toe-off value to 0 over the first 80 % of swing1 (the spec
    /// says all of swing1; the toe needs the neutral ankle earlier), then to δ_hs at heel strike
    /// on a smoothstep; θ6 back to 0 on a half-cosine (no toe velocity jump at toe-off).
    pub(crate) fn swing_foot_angles(&self, tau: f64) -> (f64, f64) {
        let t = self.constraints.timing;
        let t1 = t.t_ds + swing::SWING1_END * t.t_swing;
        if tau < t1 {
            let s = ((tau - t.t_ds) / (ANKLE_NEUTRAL * (t1 - t.t_ds))).clamp(0.0, 1.0);
            (
                self.theta5_off * (1.0 - s),
                self.theta6_off * 0.5 * (1.0 + crate::numerics::trig::sin_cos(PI * s).1),
            )
        } else {
            let s = ((tau - t1) / (t.t_step - t1)).clamp(0.0, 1.0);
            (
                self.constraints.ankle * crate::numerics::smooth::smoothstep(s),
                0.0,
            )
        }
    }

    /// The swing (or, in double support, hind) leg at step time τ.
    pub fn swing_pose(&self, tau: f64, foot: &Foot) -> SwingPose {
        self.swing_pose_at(&self.at(tau), foot)
    }

    /// [`Self::swing_pose`] at an instant of this step.
    pub(crate) fn swing_pose_at(&self, now: &Instant, foot: &Foot) -> SwingPose {
        let tau = now.tau;
        let t = self.constraints.timing;
        let (hip, dz) = now.hip_joint(self.side.other());
        let (l3, l4) = (self.stance_leg.l3, self.stance_leg.l4);
        if tau < t.t_ds
            && let Ok(mut p) =
                self.hind_leg
                    .pose([hip[0] + self.x_ankle, hip[1]], dz, self.t_start + tau)
        {
            shift_pose(&mut p, -self.x_ankle);
            let (knee, _) = leg_points_sc(hip, dz, p.sin_cos, l3, l4);
            return SwingPose {
                phase: "double_support",
                theta3: p.theta3,
                theta4: p.theta4,
                sin_cos: p.sin_cos,
                dz,
                knee,
                ankle: p.ankle,
                foot: p.foot,
            };
        }
        let i = self
            .swing
            .partition_point(|(_, s)| s.t1 < tau)
            .min(self.swing.len() - 1);
        let (sub, seg) = &self.swing[i];
        let y = seg.state(tau);
        let (knee, ankle, sin_cos) = leg_points(hip, dz, y[0], y[1], l3, l4);
        let (theta5, theta6) = self.swing_foot_angles(tau);
        // [ours] the ankle dorsiflexes beyond its rule when the rule would put the toe below a
        // floor rising from 0 at toe-off to the toe-clearance attribute at mid swing and back to
        // 0 at heel strike: the foot's mass is in the shank, so this is kinematic only
        let t = self.constraints.timing;
        let s = ((tau - t.t_ds) / t.t_swing).clamp(0.0, 1.0);
        let floor = crate::kinematics::foot::swing_floor(self.toe_clearance, s);
        let (_, foot_points) = foot.clear_pitch(y[0] + y[1] - theta5, ankle, theta6, floor);
        SwingPose {
            phase: sub.name(),
            theta3: y[0],
            theta4: y[1],
            sin_cos,
            dz,
            knee,
            ankle,
            foot: foot_points,
        }
    }

    /// The engine's state frame at world time t.
    pub(crate) fn frame(&self, t: f64, foot: &Foot) -> StateFrame {
        let tau = (t - self.t_start).clamp(0.0, self.constraints.timing.t_step);
        let now = self.at(tau);
        let (y, locked, hip) = (now.state, now.locked, now.centre);
        let sw = self.swing_pose_at(&now, foot);
        let x0 = self.x_ankle;
        StateFrame {
            time_s: t,
            step: self.index,
            phase: sw.phase,
            stance_side: if self.index.is_multiple_of(2) {
                "right"
            } else {
                "left"
            },
            stance_mode: if locked { "locked" } else { "telescopic" },
            w_m: y[0],
            theta1_deg: y[1].to_degrees(),
            theta2_deg: y[2].to_degrees(),
            theta3_deg: sw.theta3.to_degrees(),
            theta4_deg: sw.theta4.to_degrees(),
            hip_x_m: x0 + hip[0],
            hip_y_m: hip[1],
            stance_ankle_x_m: x0,
            stance_ankle_y_m: self.stance_setup.model.l9,
            swing_knee_x_m: x0 + sw.knee[0],
            swing_knee_y_m: sw.knee[1],
            swing_ankle_x_m: x0 + sw.ankle[0],
            swing_ankle_y_m: sw.ankle[1],
            swing_heel_x_m: x0 + sw.foot.heel[0],
            swing_heel_y_m: sw.foot.heel[1],
            swing_toe_x_m: x0 + sw.foot.toe[0],
            swing_toe_y_m: sw.foot.toe[1],
        }
    }
}

/// Move a pose's x coordinates by `dx`.
fn shift_pose(p: &mut LegPose, dx: f64) {
    for q in [
        &mut p.knee,
        &mut p.ankle,
        &mut p.foot.heel,
        &mut p.foot.meta,
        &mut p.foot.toe,
    ] {
        q[0] += dx;
    }
}

/// The swing-side hip joint relative to the dynamic hip, in the swing leg's plane (spec §7):
/// the determinants' offset, raised by the fold of the leg's lateral offset (with the striking
/// leg's in-plane drop, exact at heel strike).
pub(super) fn swing_hip_offset(
    det: &Determinants,
    stance: Side,
    c: &StepConstraints,
    p: &PelvisMotion,
) -> [f64; 2] {
    let leg = stance.other();
    let o = det.engine_offset(leg, stance, p);
    let dz = det.lateral_offset(leg, p, o);
    [o[0], o[1] + fold_height(c.fold_length, dz)]
}

#[cfg(test)]
mod tests {
    use crate::engine::walker::simulate;
    use crate::kinematics::foot::{Foot, FootPoints, swing_floor};
    use crate::model::attributes::AttributeTable;
    use crate::model::body::Body;
    use crate::plan::gait::GaitRequest;

    /// The swing ankle leaves its rule (spec §7) only as far as the toe needs: over a steady
    /// step's swing, wherever the foot's pitch differs from the rule's, the rule would put the
    /// foot's lowest front point (metatarsal joint or toe tip) under the floor rising to
    /// `toe_clearance` at mid swing, and the pitch used puts it on that floor; elsewhere it is
    /// above. The bump of the swing ankle after 75 % of the cycle is this and nothing more.
    #[test]
    fn the_swing_ankle_leaves_its_rule_only_to_clear_the_floor() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let attrs = AttributeTable::builtin().defaults();
        let gait = GaitRequest {
            velocity: Some(1.4),
            ..Default::default()
        }
        .complete(&body, &attrs)
        .unwrap();
        let walk = simulate(body, attrs, &[gait; 4]).unwrap();
        let foot = Foot::new(&body);
        let low = |p: &FootPoints| p.meta[1].min(p.toe[1]);
        let step = &walk.steps[2];
        let t = step.constraints.timing;
        let mut raised = 0;
        for i in 1..400 {
            let tau = t.t_ds + t.t_swing * i as f64 / 400.0;
            let pose = step.swing_pose_at(&step.at(tau), &foot);
            let (theta5, theta6) = step.swing_foot_angles(tau);
            let rule = foot.points(pose.ankle, pose.theta3 + pose.theta4 - theta5, theta6);
            let floor = swing_floor(step.toe_clearance, (tau - t.t_ds) / t.t_swing);
            if (pose.foot.toe[1] - rule.toe[1]).abs() > 1e-12 {
                raised += 1;
                assert!(low(&rule) < floor, "τ {tau}: {rule:?}");
                assert!((low(&pose.foot) - floor).abs() < 1e-9, "τ {tau}: {pose:?}");
            } else {
                assert!(low(&pose.foot) >= floor - 1e-9, "τ {tau}: {pose:?}");
            }
        }
        assert!(raised > 20, "{raised}");
    }
}
