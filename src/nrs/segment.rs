//! One tabulated step: the channels of an NRS over normalized time, and the figure they pose.
use crate::figure::{ArmAngles, Landmarks};
use crate::kinematics::foot::Foot;
use crate::nrs::curves::Table;
use crate::nrs::pose::{FootPose, Planted, Upper, figure};
use crate::nrs::specs::Side;
use crate::nrs::{GoalReason, NrsError};

/// Channels of a step's table: centre (3), pelvis heading, tilt, list, lumbar extension,
/// bending, rotation, neck rotation, the arms (6), stance pitch, swing ankle (3), swing
/// heading, pitch, θ6.
pub(crate) const K: usize = 23;

/// One tabulated step: the channels over normalized time and the foot that stands.
#[derive(Clone, Debug)]
pub(crate) struct Segment {
    pub table: Table<K>,
    pub stance: Side,
    pub stance_foot: Planted,
    /// The swing foot until TOM (normalized time `toe_off`): it rolls on the floor, posed from
    /// its pitch exactly rather than from the table's interpolated ankle.
    pub swing_foot: Planted,
    pub toe_off: f64,
    pub duration: f64,
    pub t0: f64,
    pub step: usize,
    pub foot: Foot,
    pub body: crate::model::body::Body,
    pub theta6_max: f64,
    /// The ankles' largest eversion ([`crate::nrs::pose::knee_heading`]).
    pub eversion_max: f64,
}

impl Segment {
    /// The feet and the upper body at t from one row of the table.
    pub(crate) fn parts(&self, row: &[f64; K], t: f64) -> (Upper, FootPose, FootPose) {
        let arm = |i: usize| ArmAngles {
            shoulder_flexion: row[i],
            shoulder_abduction: row[i + 1],
            elbow_flexion: row[i + 2],
        };
        let upper = Upper {
            centre: [row[0], row[1], row[2]],
            heading: row[3],
            tilt: row[4],
            list: row[5],
            lumbar_extension: row[6],
            lumbar_bending: row[7],
            lumbar_rotation: row[8],
            neck_rotation: row[9],
            arms: [arm(10), arm(13)],
        };
        let stance = Planted {
            pitch: row[16],
            ..self.stance_foot
        }
        .pose(&self.foot, self.theta6_max);
        let swing = if t <= self.toe_off {
            Planted {
                pitch: row[21],
                ..self.swing_foot
            }
            .pose(&self.foot, self.theta6_max)
        } else {
            FootPose {
                ankle: [row[17], row[18], row[19]],
                heading: row[20],
                pitch: row[21],
                theta6: row[22],
            }
        };
        (upper, stance, swing)
    }

    /// The figure at normalized time t, or the leg that cannot reach and its hip–ankle distance.
    pub fn pose(&self, t: f64) -> Result<Landmarks, (Side, f64)> {
        let (upper, stance, swing) = self.parts(&self.table.at(t), t);
        let feet = match self.stance {
            Side::Right => [&stance, &swing],
            Side::Left => [&swing, &stance],
        };
        let time = self.t0 + t.clamp(0.0, 1.0) * self.duration;
        let shape = (&self.body, &self.foot);
        figure(&upper, feet, shape, self.eversion_max, time, self.step)
    }

    /// Every row of the table is reachable by both legs, or the error naming the leg and the
    /// instant (the goal `goal` of the stepping leg): at the `n` rows and the midpoints between
    /// them (a rolling foot's ankle moves on an arc, the table's centre on the chord).
    pub(crate) fn check_reach(&self, goal: [f64; 2], n: usize) -> Result<(), NrsError> {
        for i in 0..=2 * n {
            let t = i as f64 / (2 * n) as f64;
            if let Err((side, distance)) = self.pose(t) {
                return Err(NrsError::Goal {
                    position: goal,
                    side: self.stance.other().name(),
                    reason: GoalReason::Unreachable {
                        leg: side.name(),
                        distance,
                        length: self.body.l1,
                        t,
                    },
                });
            }
        }
        Ok(())
    }
}
