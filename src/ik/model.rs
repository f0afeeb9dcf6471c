//! The data of the secondary tasks (Pronost et al. eq. 4–6): joint limits, the rest posture, the
//! weights, ξ and the segment inertias, from `models/ik.toml` and `models/rom.toml` (each value's
//! source is in the files).
use std::path::Path;

use glam::DMat3;
use serde::Deserialize;

use crate::ik::chain::{Angles, DOF, PELVIS_LIST, PELVIS_ROTATION, PELVIS_TILT, leg_offset};
use crate::kinematics::pelvis::Side;
use crate::model::InputError;
use crate::model::body::Body;
use crate::model::rom::RangesOfMotion;

const TABLE: &str = include_str!("../../models/ik.toml");

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PelvisLimits {
    tilt: [f64; 2],
    list: [f64; 2],
    rotation: [f64; 2],
}

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Rest {
    pelvis_tilt: f64,
    pelvis_list: f64,
    pelvis_rotation: f64,
    hip_flexion: f64,
    hip_adduction: f64,
    hip_rotation: f64,
    knee_flexion: f64,
}

/// The weights of the secondary tasks and ξ.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Weights {
    /// w_limits, of f1 (eq. 4).
    pub limits: f64,
    /// w_energy, of f2 (eq. 5).
    pub energy: f64,
    /// w_rest, of f3 (eq. 6).
    pub rest: f64,
    /// w_energy when f3 pulls towards a per-phase reference posture instead of the rest
    /// posture (a database entry's angles; docs/ik.md).
    pub energy_with_reference: f64,
    /// ξ of eq. 4 (1/rad).
    pub xi: f64,
}

/// Radii of gyration as fractions of a segment's length (de Leva 1996).
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Inertia {
    thigh_longitudinal: f64,
    shank_longitudinal: f64,
    pelvis_mass: f64,
    pelvis_length: f64,
    pelvis_sagittal: f64,
    pelvis_transverse: f64,
    pelvis_longitudinal: f64,
}

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    pelvis_limits: PelvisLimits,
    rest: Rest,
    weights: Weights,
    inertia: Inertia,
}

/// The secondary tasks' data for one body (rad, kg m²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IkModel {
    /// Lower joint limits `blow` (eq. 4).
    pub lower: Angles,
    /// Upper joint limits `bup` (eq. 4).
    pub upper: Angles,
    /// The rest posture θ_r (eq. 6).
    pub rest: Angles,
    /// The weights and ξ.
    pub weights: Weights,
    /// The segments' inertia tensors about their centres of mass in their own axes (x forward,
    /// y along the segment, z to the right): pelvis, thigh, shank (eq. 5's I_b).
    pub inertia: [DMat3; 3],
}

impl IkModel {
    /// The bundled `models/ik.toml` and `models/rom.toml` for `body`.
    pub fn new(body: &Body) -> Self {
        Self::parse(TABLE, Path::new("models/ik.toml"), body)
            .expect("models/ik.toml parses (tested)")
    }

    /// Parse a table in `models/ik.toml`'s layout (degrees) for `body`; the hips' and knees'
    /// limits are `models/rom.toml`'s. Every limit must be ordered with the rest posture inside,
    /// the weights and ξ finite and ≥ 0, the radii positive.
    pub fn parse(text: &str, path: &Path, body: &Body) -> Result<Self, InputError> {
        let bad = |reason: String| InputError::malformed("inverse-kinematics table", path, reason);
        let t: Table = toml::from_str(text)
            .map_err(|e| InputError::malformed("inverse-kinematics table", path, Box::new(e)))?;
        let rom = RangesOfMotion::default();
        let (mut lower, mut upper, mut rest) = (Angles::zeros(), Angles::zeros(), Angles::zeros());
        let p = t.pelvis_limits;
        for (i, [lo, hi], r) in [
            (PELVIS_TILT, p.tilt, t.rest.pelvis_tilt),
            (PELVIS_LIST, p.list, t.rest.pelvis_list),
            (PELVIS_ROTATION, p.rotation, t.rest.pelvis_rotation),
        ] {
            lower[i] = lo.to_radians();
            upper[i] = hi.to_radians();
            rest[i] = r.to_radians();
        }
        for side in [Side::Right, Side::Left] {
            let o = leg_offset(side);
            let r = &t.rest;
            for (k, range, value) in [
                (0, rom.hip_flexion, r.hip_flexion),
                (1, rom.hip_adduction, r.hip_adduction),
                (2, rom.hip_rotation, r.hip_rotation),
                (3, rom.knee_flexion, r.knee_flexion),
            ] {
                lower[o + k] = range.lo;
                upper[o + k] = range.hi;
                rest[o + k] = value.to_radians();
            }
        }
        for i in 0..DOF {
            let name = crate::ik::chain::NAMES[i];
            if !(lower[i].is_finite() && upper[i].is_finite() && lower[i] < upper[i]) {
                return Err(bad(format!(
                    "{name}: the lower limit must be below the upper"
                )));
            }
            if !(lower[i]..=upper[i]).contains(&rest[i]) {
                return Err(bad(format!(
                    "{name}: the rest posture {:.2}° lies outside its limits [{:.1}°, {:.1}°]",
                    rest[i].to_degrees(),
                    lower[i].to_degrees(),
                    upper[i].to_degrees()
                )));
            }
        }
        let w = t.weights;
        for (name, v) in [
            ("weights.limits", w.limits),
            ("weights.energy", w.energy),
            ("weights.rest", w.rest),
            ("weights.energy_with_reference", w.energy_with_reference),
            ("weights.xi", w.xi),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(bad(format!("{name} = {v} must be finite and ≥ 0")));
            }
        }
        let i = t.inertia;
        for (name, v) in [
            ("inertia.thigh_longitudinal", i.thigh_longitudinal),
            ("inertia.shank_longitudinal", i.shank_longitudinal),
            ("inertia.pelvis_mass", i.pelvis_mass),
            ("inertia.pelvis_length", i.pelvis_length),
            ("inertia.pelvis_sagittal", i.pelvis_sagittal),
            ("inertia.pelvis_transverse", i.pelvis_transverse),
            ("inertia.pelvis_longitudinal", i.pelvis_longitudinal),
        ] {
            if !(v.is_finite() && v > 0.0 && v < 1.0) {
                return Err(bad(format!("{name} = {v} must lie in (0, 1)")));
            }
        }
        let diag = |x: f64, y: f64, z: f64| DMat3::from_diagonal(glam::DVec3::new(x, y, z));
        let pm = i.pelvis_mass * body.mass;
        let pl = i.pelvis_length * body.height;
        let moment = |m: f64, r: f64, l: f64| m * (r * l).powi(2);
        let inertia = [
            diag(
                moment(pm, i.pelvis_sagittal, pl),
                moment(pm, i.pelvis_longitudinal, pl),
                moment(pm, i.pelvis_transverse, pl),
            ),
            diag(
                body.i3,
                moment(body.m3, i.thigh_longitudinal, body.l3),
                body.i3,
            ),
            diag(
                body.i4,
                moment(body.m4, i.shank_longitudinal, body.l4),
                body.i4,
            ),
        ];
        Ok(IkModel {
            lower,
            upper,
            rest,
            weights: w,
            inertia,
        })
    }

    /// The model with other weights.
    pub fn with_weights(self, weights: Weights) -> Self {
        IkModel { weights, ..self }
    }

    /// Whether every angle of θ lies within its limits.
    pub fn within_limits(&self, theta: &Angles) -> bool {
        (0..DOF).all(|i| (self.lower[i]..=self.upper[i]).contains(&theta[i]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> Body {
        Body::standard(1.8, 80.0).unwrap()
    }

    /// The bundled table parses; AAOS's hip flexion and knee range come through from rom.toml,
    /// the rest posture lies inside the limits, the pelvis's inertia is de Leva's, by hand.
    #[test]
    fn the_bundled_table_parses() {
        let b = body();
        let m = IkModel::new(&b);
        assert!((m.upper[3] - 120f64.to_radians()).abs() < 1e-15);
        assert_eq!(m.lower[6], 0.0);
        assert!((m.upper[10] - 135f64.to_radians()).abs() < 1e-15);
        assert!(m.within_limits(&m.rest));
        // 0.1117 × 80 kg × (0.587 × 0.0837 × 1.8 m)² about the vertical
        let expect = 0.1117 * 80.0 * (0.587f64 * 0.0837 * 1.8).powi(2);
        assert!((m.inertia[0].y_axis.y - expect).abs() < 1e-12);
        assert!((m.inertia[1].x_axis.x - b.i3).abs() < 1e-15);
    }

    #[test]
    fn bad_tables_are_refused_naming_the_value() {
        let b = body();
        let p = Path::new("x.toml");
        let e = IkModel::parse(
            &TABLE.replace("knee_flexion = 5.0", "knee_flexion = -5.0"),
            p,
            &b,
        )
        .unwrap_err();
        assert!(e.to_string().contains("knee_flexion_r"), "{e}");
        let e = IkModel::parse(&TABLE.replace("xi = 20.0", "xi = -1.0"), p, &b).unwrap_err();
        assert!(e.to_string().contains("weights.xi"), "{e}");
        let e = IkModel::parse(
            &TABLE.replace("tilt = [-80.0, 25.0]", "tilt = [25.0, -80.0]"),
            p,
            &b,
        )
        .unwrap_err();
        assert!(e.to_string().contains("pelvis_tilt"), "{e}");
        assert!(IkModel::parse(&format!("{TABLE}\n[extra]\n"), p, &b).is_err());
    }
}
