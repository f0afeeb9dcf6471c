//! How well the inverse kinematics recovers a walk's angles from its poulaine (Pronost et al.
//! §6.2, Table 2): the chain's angles solved on the poulaine against the walk's own clinical
//! angles at the same instants, per angle the RMS difference after removing each trajectory's
//! mean (eq. 7: the captured trajectory "shifted to θᵢ mean value";
//! [`crate::analysis::criteria::mean_shifted_rms`]).
use serde::Serialize;

use crate::analysis::criteria::mean_shifted_rms;
use crate::figure::Landmarks;
use crate::figure::clinical::{Clinical, clinical};
use crate::ik::chain::{Angles, DOF, NAMES};
use crate::ik::{Ik, IkError};
use crate::model::body::Body;
use crate::poulaine::trajectory::Trajectory;

/// Table 2 of the paper: the mean RMS errors (rad) of pelvis tilt, obliquity, rotation, hip
/// flexion, abduction, rotation and knee flexion over its seven subjects (left leg).
pub const TABLE2: [(&str, f64); 7] = [
    ("pelvis_tilt", 0.03),
    ("pelvis_list", 0.01),
    ("pelvis_rotation", 0.01),
    ("hip_flexion", 0.05),
    ("hip_adduction", 0.04),
    ("hip_rotation", 0.03),
    ("knee_flexion", 0.02),
];

/// The chain's 11 angles of a frame's clinical angles.
pub fn chain_angles(c: &Clinical) -> Angles {
    Angles::from_row_slice(&[
        c.pelvis_tilt,
        c.pelvis_list,
        c.pelvis_rotation,
        c.right.hip.flexion,
        c.right.hip.adduction,
        c.right.hip.rotation,
        c.right.knee.flexion,
        c.left.hip.flexion,
        c.left.hip.adduction,
        c.left.hip.rotation,
        c.left.knee.flexion,
    ])
}

/// The chain's angles of each frame.
pub fn frames_angles(frames: &[Landmarks], body: &Body) -> crate::Result<Vec<Angles>> {
    frames
        .iter()
        .map(|f| Ok(chain_angles(&clinical(f, body)?)))
        .collect()
}

/// The recovery of one walk.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Recovery {
    /// Eq. 7 per angle, in the order of the chain's [`NAMES`] (rad).
    pub rms: [f64; DOF],
    /// The IK's angles, one per sample.
    #[serde(skip)]
    pub angles: Vec<Angles>,
    /// The largest ankle error left by the closed loop (m).
    pub residual: f64,
    /// Whether every angle stayed within its joint limits.
    pub within_limits: bool,
}

impl Recovery {
    /// Eq. 7 of a Table 2 angle, the mean of the two legs for the hip and knee angles.
    pub fn table2(&self, name: &str) -> f64 {
        let at = |n: &str| NAMES.iter().position(|m| *m == n).expect("a chain angle");
        if name.starts_with("pelvis") {
            self.rms[at(name)]
        } else {
            0.5 * (self.rms[at(&format!("{name}_r"))] + self.rms[at(&format!("{name}_l"))])
        }
    }
}

/// Solve `poulaine` (uniform samples, one cycle) and compare with `truth`, the walk's angles
/// at the same instants.
pub fn recover(ik: &Ik, poulaine: &Trajectory, truth: &[Angles]) -> Result<Recovery, IkError> {
    recover_referenced(ik, poulaine, truth, None)
}

/// [`recover`] with a reference posture per sample in f3 ([`Ik::solve_referenced`]).
pub fn recover_referenced(
    ik: &Ik,
    poulaine: &Trajectory,
    truth: &[Angles],
    reference: Option<&[Angles]>,
) -> Result<Recovery, IkError> {
    let dt = poulaine.uniform_step().ok_or_else(|| {
        crate::model::InputError::bad_value("poulaine", "its samples are not uniform in time")
    })?;
    let sol = ik.solve_referenced(&poulaine.targets(), dt, true, reference)?;
    let angles: Vec<Angles> = sol.frames.iter().map(|f| f.theta).collect();
    let mut rms = [0.0; DOF];
    for (k, r) in rms.iter_mut().enumerate() {
        let a: Vec<f64> = angles.iter().map(|t| t[k]).collect();
        let b: Vec<f64> = truth.iter().map(|t| t[k]).collect();
        *r = mean_shifted_rms(&a, &b);
    }
    Ok(Recovery {
        rms,
        residual: sol.frames.iter().map(|f| f.residual).fold(0.0, f64::max),
        within_limits: angles.iter().all(|a| ik.model.within_limits(a)),
        angles,
    })
}
