//! OpenSim storage (`.mot` / `.sto`, issue item 7): tab-separated, header `Coordinates`,
//! `version=1`, `nRows`, `nColumns`, `inDegrees=yes`, `endheader`, then `time` and the model's
//! coordinates, one row per frame.
//!
//! Coordinate names, axes and signs were read from the models' `.osim` files (the evidence is in
//! `docs/export.md`). Both models' ground, pelvis and segment frames have x forward, y up, z right,
//! as the klaw world frame, and their joints compose rotations in the order of their
//! `SpatialTransform` (rotation1 · rotation2 · rotation3):
//! - `ground_pelvis`: `pelvis_tilt` about z, `pelvis_list` about x, `pelvis_rotation` about y, so
//!   the three are the exact `zxy_angles` of the pelvis frame. About +z a positive tilt lifts
//!   the front of the pelvis: `pelvis_tilt` is + for a posterior tilt (≈ −clinical tilt); about +x
//!   a positive list lowers the right side (≈ −clinical list); `pelvis_rotation` + turns the right
//!   side forward (= clinical).
//! - `pelvis_tx/ty/tz`: the model's pelvis origin, which sits ahead of and above the hip-joint
//!   midpoint by the model's hip-joint offset (scaled by body height, see [`OpenSimModel`]).
//! - hips (flexion z, adduction x / −x on the left, rotation y / −y on the left): the clinical hip
//!   angles exactly.
//! - `knee_angle_*`: gait2392 about +z, range −120°…10°, so −knee flexion; Rajagopal 2015 +
//!   knee flexion.
//! - `ankle_angle_*` (oblique axis close to +z): dorsiflexion positive; `subtalar_angle_*`
//!   (oblique, close to +x on the right and −x on the left): inversion positive; `mtp_angle_*`
//!   (close to +z): dorsiflexion positive. These three axes are oblique in the models and are
//!   about klaw's orthogonal axes here: the values agree with the model to first order only.
//! - `back`: `lumbar_extension` about z, `lumbar_bending` about x, `lumbar_rotation` about y:
//!   the exact `zxy_angles` of the thorax in the pelvis (+ extension, + bending to the right,
//!   positive rotation with the right shoulder forward).
//! - Rajagopal 2015 arms (`acromial`: `arm_flex` z, `arm_add` x, `arm_rot` y; `elbow_flex` about
//!   an axis close to +z): shoulder flexion, adduction (= −abduction), internal rotation and
//!   elbow flexion.
//! - Neither model has a neck: the head is part of the torso body above `back`, so
//!   [`crate::figure::Landmarks::neck_rotation`] is not written.
use std::io::{self, Write};

use glam::DVec3;

use super::number::push_f64;
use super::{ExportError, FrameData, RowWriter};
use crate::figure::clinical::Clinical;
use crate::figure::euler::{nearest_turn, zxy_angles};
use crate::figure::skeleton::{Side, Skeleton};
use crate::model::body::Body;

/// The OpenSim model whose coordinates a `.mot` / `.sto` file holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum OpenSimModel {
    /// gait2392 (and gait2354): legs, pelvis and back; no arms. Knee negative in flexion.
    #[default]
    Gait2392,
    /// Rajagopal 2015 ("full body"): gait2392's leg and back names plus the arms; knee positive in
    /// flexion.
    Rajagopal2015,
}

impl OpenSimModel {
    /// The model's pelvis origin relative to the midpoint of its hip joints, pelvis frame (m), at
    /// the model's own size: gait2392's hip joints are at (−0.0707, −0.0661, ±0.0835) in the
    /// pelvis; Rajagopal 2015's at (−0.056276, −0.07849, ±0.07726).
    pub(crate) fn pelvis_origin_from_hips(self) -> DVec3 {
        match self {
            OpenSimModel::Gait2392 => DVec3::new(0.0707, 0.0661, 0.0),
            OpenSimModel::Rajagopal2015 => DVec3::new(0.056276, 0.07849, 0.0),
        }
    }

    /// Body height the model's dimensions describe (m): gait2392 1.8 m, Rajagopal 2015 1.7 m.
    /// The pelvis offset is scaled by H / this.
    pub(crate) fn reference_height(self) -> f64 {
        match self {
            OpenSimModel::Gait2392 => 1.8,
            OpenSimModel::Rajagopal2015 => 1.7,
        }
    }

    pub(crate) fn knee_sign(self) -> f64 {
        match self {
            OpenSimModel::Gait2392 => -1.0,
            OpenSimModel::Rajagopal2015 => 1.0,
        }
    }

    fn has_arms(self) -> bool {
        self == OpenSimModel::Rajagopal2015
    }
}

/// One model coordinate of a frame.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Coordinate {
    pub name: &'static str,
    /// rad for rotations, m for translations.
    pub value: f64,
    pub is_rotation: bool,
}

/// The leg coordinates of the right and the left side, in file column order.
const LEG_COORDINATES: [[&str; 7]; 2] = [
    [
        "hip_flexion_r",
        "hip_adduction_r",
        "hip_rotation_r",
        "knee_angle_r",
        "ankle_angle_r",
        "subtalar_angle_r",
        "mtp_angle_r",
    ],
    [
        "hip_flexion_l",
        "hip_adduction_l",
        "hip_rotation_l",
        "knee_angle_l",
        "ankle_angle_l",
        "subtalar_angle_l",
        "mtp_angle_l",
    ],
];

/// Rajagopal 2015's arm coordinates of the right and the left side, in file column order.
const ARM_COORDINATES: [[&str; 4]; 2] = [
    ["arm_flex_r", "arm_add_r", "arm_rot_r", "elbow_flex_r"],
    ["arm_flex_l", "arm_add_l", "arm_rot_l", "elbow_flex_l"],
];

/// The model coordinates of one frame, in file column order (without `time`), appended to
/// `out`.
pub(crate) fn coordinates(
    model: OpenSimModel,
    skeleton: &Skeleton,
    clinical: &Clinical,
    height: f64,
    out: &mut Vec<Coordinate>,
) {
    let mut rot = |name: &'static str, value: f64| {
        out.push(Coordinate {
            name,
            value,
            is_rotation: true,
        })
    };
    let [tilt, list, rotation] = zxy_angles(&skeleton.pelvis.axes);
    rot("pelvis_tilt", tilt);
    rot("pelvis_list", list);
    rot(
        "pelvis_rotation",
        nearest_turn(rotation, clinical.pelvis_rotation),
    );
    let origin = skeleton
        .pelvis
        .point(model.pelvis_origin_from_hips() * (height / model.reference_height()));
    for (name, v) in ["pelvis_tx", "pelvis_ty", "pelvis_tz"]
        .into_iter()
        .zip(origin.to_array())
    {
        out.push(Coordinate {
            name,
            value: v,
            is_rotation: false,
        });
    }
    let mut rot = |name: &'static str, value: f64| {
        out.push(Coordinate {
            name,
            value,
            is_rotation: true,
        })
    };
    for (side, names) in [Side::Right, Side::Left].into_iter().zip(LEG_COORDINATES) {
        let leg = clinical.leg(side);
        let values = [
            leg.hip.flexion,
            leg.hip.adduction,
            leg.hip.rotation,
            model.knee_sign() * leg.knee.flexion,
            leg.ankle.flexion,
            leg.ankle.adduction,
            leg.mtp.flexion,
        ];
        for (name, v) in names.into_iter().zip(values) {
            rot(name, v);
        }
    }
    let [ext, bend, lrot] = zxy_angles(&(skeleton.pelvis.axes.transpose() * skeleton.thorax.axes));
    rot("lumbar_extension", ext);
    rot("lumbar_bending", bend);
    rot("lumbar_rotation", lrot);
    if model.has_arms() {
        for (side, names) in [Side::Right, Side::Left].into_iter().zip(ARM_COORDINATES) {
            let arm = clinical.arm(side);
            let values = [
                arm.shoulder.flexion,
                arm.shoulder.adduction,
                arm.shoulder.rotation,
                arm.elbow.flexion,
            ];
            for (name, v) in names.into_iter().zip(values) {
                rot(name, v);
            }
        }
    }
}

/// The `.mot` / `.sto` writer.
pub(crate) struct Storage {
    model: OpenSimModel,
    height: f64,
    /// The coordinates' names, from the first row.
    names: Vec<&'static str>,
    /// A frame's coordinates, kept across the rows.
    coords: Vec<Coordinate>,
}

impl Storage {
    pub(crate) fn new(model: OpenSimModel, body: &Body) -> Self {
        Storage {
            model,
            height: body.height,
            names: Vec::new(),
            coords: Vec::with_capacity(40),
        }
    }
}

impl RowWriter for Storage {
    fn row(&mut self, out: &mut Vec<u8>, frame: &FrameData) -> Result<(), ExportError> {
        self.coords.clear();
        let clinical = frame.clinical();
        coordinates(
            self.model,
            &frame.skeleton,
            clinical,
            self.height,
            &mut self.coords,
        );
        if self.names.is_empty() {
            self.names = self.coords.iter().map(|c| c.name).collect();
        }
        push_f64(out, frame.landmarks.time);
        for c in &self.coords {
            let v = if c.is_rotation {
                c.value.to_degrees()
            } else {
                c.value
            };
            out.push(b'\t');
            push_f64(out, v);
        }
        out.push(b'\n');
        Ok(())
    }

    fn header(&self, out: &mut dyn Write, rows: usize) -> io::Result<()> {
        writeln!(out, "Coordinates")?;
        writeln!(out, "version=1")?;
        writeln!(out, "nRows={rows}")?;
        writeln!(out, "nColumns={}", self.names.len() + 1)?;
        writeln!(out, "inDegrees=yes")?;
        writeln!(out)?;
        writeln!(
            out,
            "Units are S.I. units (second, meters, Newtons, ...); angles in degrees."
        )?;
        writeln!(
            out,
            "Written by klaw for the OpenSim model {:?}.",
            self.model
        )?;
        writeln!(out)?;
        writeln!(out, "endheader")?;
        write!(out, "time")?;
        for n in &self.names {
            write!(out, "\t{n}")?;
        }
        writeln!(out)
    }
}
