//! Kinematic completion of the hind leg's stance during double support (spec §5 "initial
//! conditions at toe-off" and §7 heel-off / meta-off). The hind foot rolls over its metatarsal
//! joint, then its toe tip; the knee flexion follows a prescribed curve κ(t) from κ0 at the
//! opposite heel strike to κ_TO at toe-off, and the one unknown foot pitch p solves
//! |hip − ankle(p)| = a(κ) (a: hip–ankle distance for knee flexion κ).
//!
//! Stand-in until the virtual leg exists [ours, spec §5 allows it]: κ0 = κ_hs and
//! κ(t) = κ0 + (κ_TO − κ0)(t/t_ds)² (the knee is still flexing at toe-off, as in human gait).
//! The virtual leg of the whole-body issue replaces κ0 by the stance leg's own knee at the
//! opposite heel strike, which makes the knee continuous through the stance.
use argmin::core::{CostFunction, Executor};
use argmin::solver::brent::BrentRoot;

use crate::body::Body;
use crate::kinematics::foot::{Foot, FootPoints};

/// A leg pose in the sagittal plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LegPose {
    pub knee: [f64; 2],
    pub ankle: [f64; 2],
    pub foot: FootPoints,
    /// Thigh from the downward vertical (knee ahead −), rad.
    pub theta3: f64,
    /// Knee flexion, rad.
    pub theta4: f64,
    /// Foot pitch (heel up +) and toe dorsiflexion θ6, rad.
    pub pitch: f64,
    pub theta6: f64,
}

/// The hind leg of one double support.
#[derive(Clone, Copy, Debug)]
pub struct HindLeg {
    pub foot: Foot,
    pub l3: f64,
    pub l4: f64,
    /// x of the metatarsal joint on the ground (flat-foot position).
    pub meta_x: f64,
    pub kappa0: f64,
    pub kappa_to: f64,
    pub t_ds: f64,
    pub theta6_max: f64,
}

struct PitchResidual<'a> {
    leg: &'a HindLeg,
    hip: [f64; 2],
    a: f64,
}

impl CostFunction for PitchResidual<'_> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, p: &f64) -> Result<f64, argmin::core::Error> {
        let (ankle, _) = self
            .leg
            .foot
            .rolling_ankle(self.leg.meta_x, *p, self.leg.theta6_max);
        Ok((self.hip[0] - ankle[0]).hypot(self.hip[1] - ankle[1]) - self.a)
    }
}

/// Bracket of the foot pitch (rad): from slightly toe-up to far beyond any toe-off pitch.
const PITCH_BRACKET: (f64, f64) = (-0.5, 1.8);

impl HindLeg {
    pub fn new(
        body: &Body,
        meta_x: f64,
        kappa0: f64,
        kappa_to: f64,
        t_ds: f64,
        theta6_max: f64,
    ) -> Self {
        HindLeg {
            foot: Foot::new(body),
            l3: body.l3,
            l4: body.l4,
            meta_x,
            kappa0,
            kappa_to,
            t_ds,
            theta6_max,
        }
    }

    /// Prescribed knee flexion and its rate at time t of the double support.
    pub fn knee(&self, t: f64) -> (f64, f64) {
        let s = t / self.t_ds;
        let d = self.kappa_to - self.kappa0;
        (self.kappa0 + d * s * s, 2.0 * d * s / self.t_ds)
    }

    /// The pose for a hip at `hip` at time t.
    pub fn pose(&self, hip: [f64; 2], t: f64) -> Result<LegPose, String> {
        let (kappa, _) = self.knee(t);
        let a =
            (self.l3 * self.l3 + self.l4 * self.l4 + 2.0 * self.l3 * self.l4 * kappa.cos()).sqrt();
        let problem = PitchResidual { leg: self, hip, a };
        let (lo, hi) = PITCH_BRACKET;
        let (flo, fhi) = (
            problem.cost(&lo).unwrap_or(f64::NAN),
            problem.cost(&hi).unwrap_or(f64::NAN),
        );
        if flo * fhi >= 0.0 || flo.is_nan() || fhi.is_nan() {
            return Err(format!(
                "the hind foot cannot roll to reach the hip: hip–ankle distance {:.4} m is out of reach for knee flexion {:.1}°",
                a,
                kappa.to_degrees()
            ));
        }
        let solver = BrentRoot::new(lo, hi, 1e-13);
        let res = Executor::new(problem, solver)
            .configure(|s| s.param(0.3).max_iters(100))
            .run()
            .map_err(|e| e.to_string())?;
        let p = res.state.best_param.unwrap_or(f64::NAN);
        let (ankle, theta6) = self.foot.rolling_ankle(self.meta_x, p, self.theta6_max);
        // thigh = hip–ankle line angle minus β, the angle between thigh and line (knee ahead)
        let line = (hip[0] - ankle[0]).atan2(hip[1] - ankle[1]);
        let beta = (self.l4 * kappa.sin() / a).clamp(-1.0, 1.0).asin();
        let theta3 = line - beta;
        let knee = [
            hip[0] - self.l3 * theta3.sin(),
            hip[1] - self.l3 * theta3.cos(),
        ];
        Ok(LegPose {
            knee,
            ankle,
            foot: self.foot.points(ankle, p, theta6),
            theta3,
            theta4: kappa,
            pitch: p,
            theta6,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pose closes the chain: |hip − knee| = l3, |knee − ankle| = l4, the knee angle is κ(t),
    /// and the foot's pivot stays on the ground.
    #[test]
    fn pose_closes_the_leg_chain() {
        let b = Body::standard(1.8, 80.0).unwrap();
        let leg = HindLeg::new(
            &b,
            -0.78 + 0.1444,
            4f64.to_radians(),
            40f64.to_radians(),
            0.13,
            35f64.to_radians(),
        );
        for i in 0..=10 {
            let t = 0.013 * i as f64;
            let hip = [-0.39 + 1.4 * t, 0.877 + 0.05 * t];
            let pose = leg.pose(hip, t).unwrap();
            let d = |u: [f64; 2], v: [f64; 2]| (u[0] - v[0]).hypot(u[1] - v[1]);
            assert!((d(hip, pose.knee) - b.l3).abs() < 1e-9, "t {t}");
            assert!((d(pose.knee, pose.ankle) - b.l4).abs() < 1e-9, "t {t}");
            let thigh = [pose.knee[0] - hip[0], pose.knee[1] - hip[1]];
            let shank = [pose.ankle[0] - pose.knee[0], pose.ankle[1] - pose.knee[1]];
            let flex = (thigh[0] * shank[1] - thigh[1] * shank[0])
                .atan2(thigh[0] * shank[0] + thigh[1] * shank[1]);
            assert!((flex.abs() - leg.knee(t).0).abs() < 1e-9, "t {t}: {flex}");
            assert!(pose.foot.lowest() > -1e-12);
            assert!(pose.pitch > 0.0, "heel is off the ground in double support");
        }
    }
}
