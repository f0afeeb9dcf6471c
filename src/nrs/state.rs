//! The figure between two actions: both feet on the floor, the pelvis and upper body, and the
//! centre site's velocity; what an NRS, a turnaround or a walk starts from and leaves behind.
use crate::figure::{ArmAngles, Landmarks};
use crate::kinematics::foot::Foot;
use crate::kinematics::leg::reach;
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::nrs::NrsError;
use crate::nrs::parameters::NrsParameters;
use crate::nrs::pose::{Planted, Upper, direction, figure, right_of};
use crate::nrs::specs::Side;

/// The arms hanging at rest: shoulder flexion 0, abduction 5°, elbow 20° (the walk's arm rule
/// with no swing, [`crate::figure::landmarks`]).
pub(crate) fn hanging_arm() -> ArmAngles {
    ArmAngles {
        shoulder_flexion: 0.0,
        shoulder_abduction: 5f64.to_radians(),
        elbow_flexion: 20f64.to_radians(),
    }
}

/// One walker: its body, attributes and NRS constants, where its feet stand, its pelvis and
/// upper body, and when. Several walkers are independent values.
#[derive(Clone, Debug)]
pub struct WalkerState {
    /// The body.
    pub body: Body,
    /// The locomotion attributes.
    pub attrs: Attributes,
    /// The NRS constants.
    pub params: NrsParameters,
    /// Time (s).
    pub time: f64,
    /// Index of the step (walking or NRS) the figure is at.
    pub step: usize,
    /// The right and the left foot.
    pub feet: [Planted; 2],
    /// The pelvis and upper body.
    pub upper: Upper,
    /// The centre site's velocity (m/s, world).
    pub velocity: [f64; 3],
}

impl WalkerState {
    /// Quiet standing: feet flat, side by side the attributes' step width apart, their ankles'
    /// midpoint at floor point `at`, facing `facing`; knees flexed by `stand_knee`, pelvis
    /// above the ankles' midpoint, tilt and trunk as the walk's at its lean reference, arms
    /// hanging, at rest.
    pub fn standing(body: Body, attrs: Attributes, at: [f64; 2], facing: f64) -> Self {
        Self::standing_with(body, attrs, NrsParameters::default(), at, facing)
    }

    /// [`Self::standing`] with the NRS constants `params` (a model file's, `--nrs-model`)
    /// instead of `models/nrs.toml`'s.
    pub fn standing_with(
        body: Body,
        attrs: Attributes,
        params: NrsParameters,
        at: [f64; 2],
        facing: f64,
    ) -> Self {
        let w = attrs.step_width / 2.0;
        let r = right_of(facing);
        let foot = |s: f64| Planted {
            flat: [at[0] + s * w * r[0], at[1] + s * w * r[1]],
            heading: facing,
            pitch: 0.0,
        };
        let l = reach(body.l3, body.l4, params.stand_knee.cos());
        let dz = body.l0 / 2.0 - w;
        let upper = Upper {
            centre: [at[0], body.l9 + (l * l - dz * dz).sqrt(), at[1]],
            heading: facing,
            tilt: attrs.pelvis_tilt,
            list: 0.0,
            lumbar_extension: attrs.pelvis_tilt - attrs.trunk_lean,
            lumbar_bending: 0.0,
            lumbar_rotation: 0.0,
            neck_rotation: 0.0,
            arms: [hanging_arm(); 2],
        };
        WalkerState {
            body,
            attrs,
            params,
            time: 0.0,
            step: 0,
            feet: [foot(1.0), foot(-1.0)],
            upper,
            velocity: [0.0; 3],
        }
    }

    /// The foot of `side`.
    pub fn foot(&self, side: Side) -> &Planted {
        match side {
            Side::Right => &self.feet[0],
            Side::Left => &self.feet[1],
        }
    }

    /// The gaze's heading: the pelvis's, turned by the lumbar and the neck rotations.
    pub fn gaze(&self) -> f64 {
        self.upper.heading + self.upper.lumbar_rotation + self.upper.neck_rotation
    }

    /// The figure in this state.
    pub fn figure(&self) -> Result<Landmarks, NrsError> {
        self.figure_with(&self.upper, self.time)
    }

    /// The figure with these feet and the pelvis and upper body `upper`, at `time`.
    pub fn figure_with(&self, upper: &Upper, time: f64) -> Result<Landmarks, NrsError> {
        let foot = Foot::new(&self.body);
        let lim = self.attrs.metatarsal_limit;
        let [r, l] = self.feet.map(|f| f.pose(&foot, lim));
        let max = self.params.ankle_eversion_max;
        figure(upper, [&r, &l], (&self.body, &foot), max, time, self.step).map_err(
            |(side, distance)| NrsError::Goal {
                position: self.foot(side).flat,
                side: side.name(),
                reason: crate::nrs::GoalReason::Unreachable {
                    leg: side.name(),
                    distance,
                    length: self.body.l1,
                    t: 0.0,
                },
            },
        )
    }

    /// The feet's midpoint (flat ankles) and the direction ahead of the pelvis.
    pub fn ahead(&self) -> [f64; 2] {
        direction(self.upper.heading)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::attributes::AttributeTable;

    /// Standing: the legs reach the feet with the standing knee, the soles are on the floor and
    /// the pelvis is above the ankles' midpoint.
    #[test]
    fn quiet_standing_is_a_valid_figure() {
        let body = Body::standard(1.75, 70.0).unwrap();
        let attrs = AttributeTable::builtin().defaults();
        let s = WalkerState::standing(body, attrs, [1.0, -2.0], 0.7);
        let lm = s.figure().unwrap();
        for leg in [lm.right, lm.left] {
            for p in [leg.heel, leg.mtp] {
                assert!(p[1].abs() < 1e-12, "the sole is on the floor");
            }
            let d = |a: [f64; 3], b: [f64; 3]| {
                ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
            };
            let want = reach(body.l3, body.l4, s.params.stand_knee.cos());
            assert!((d(leg.hip, leg.ankle) - want).abs() < 1e-9);
        }
        assert!((lm.pelvis[0] - 1.0).abs() < 1e-12 && (lm.pelvis[2] + 2.0).abs() < 1e-12);
        // the right foot is to the right of the heading
        let r = right_of(0.7);
        let v = [
            lm.right.ankle[0] - lm.left.ankle[0],
            lm.right.ankle[2] - lm.left.ankle[2],
        ];
        assert!(v[0] * r[0] + v[1] * r[1] > 0.0);
    }
}
