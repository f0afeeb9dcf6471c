//! The data of the secondary tasks (Pronost et al. eq. 4–6): joint limits, the rest posture, the
//! weights, ξ and the segment inertias, from `models/ik.toml` and `models/rom.toml` (each value's
//! source is in the files).
use std::path::Path;

use glam::DMat3;
use serde::Deserialize;

use crate::ik::chain::{Angles, DOF, PELVIS_LIST, PELVIS_ROTATION, PELVIS_TILT, leg_offset};
use crate::kinematics::pelvis::Side;
use crate::model::body::Body;
use crate::model::rom::RangesOfMotion;
use crate::model::{InputError, Shown};

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

/// The hips' and knees' limits when a model file gives its own (degrees, both legs alike).
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LegLimits {
    hip_flexion: [f64; 2],
    hip_adduction: [f64; 2],
    hip_rotation: [f64; 2],
    knee_flexion: [f64; 2],
}

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    pelvis_limits: PelvisLimits,
    /// Optional: `models/rom.toml`'s ranges when absent.
    #[serde(default)]
    leg_limits: Option<LegLimits>,
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

    /// Read and check the model file `path` (the layout of `models/ik.toml`) for `body`
    /// ([`IkModel::parse`]'s rules).
    pub fn read(path: &Path, body: &Body) -> Result<Self, InputError> {
        let text = crate::model::file::read_text("inverse-kinematics model", path)?;
        Self::parse(&text, path, body)
    }

    /// Parse a table in `models/ik.toml`'s layout (degrees) for `body`: every key of it and no
    /// other, and optionally `[leg_limits]` (`hip_flexion`, `hip_adduction`, `hip_rotation`,
    /// `knee_flexion`, each `[lo, hi]`, both legs alike), without which the hips' and knees'
    /// limits are `models/rom.toml`'s. Every limit must be finite and ordered with the rest
    /// posture inside, the weights and ξ finite and ≥ 0, the radii and fractions in (0, 1).
    pub fn parse(text: &str, path: &Path, body: &Body) -> Result<Self, InputError> {
        let bad = |reason: String| InputError::malformed("inverse-kinematics model", path, reason);
        let t: Table = crate::model::file::parse_toml(text).map_err(bad)?;
        let rom = RangesOfMotion::default();
        let deg = |r: [f64; 2]| [r[0].to_radians(), r[1].to_radians()];
        let leg: [(&str, [f64; 2], f64); 4] = match t.leg_limits {
            Some(l) => [
                (
                    "leg_limits.hip_flexion",
                    deg(l.hip_flexion),
                    t.rest.hip_flexion,
                ),
                (
                    "leg_limits.hip_adduction",
                    deg(l.hip_adduction),
                    t.rest.hip_adduction,
                ),
                (
                    "leg_limits.hip_rotation",
                    deg(l.hip_rotation),
                    t.rest.hip_rotation,
                ),
                (
                    "leg_limits.knee_flexion",
                    deg(l.knee_flexion),
                    t.rest.knee_flexion,
                ),
            ],
            None => [
                (
                    "models/rom.toml's hip_flexion",
                    rom.hip_flexion,
                    t.rest.hip_flexion,
                ),
                (
                    "models/rom.toml's hip_adduction",
                    rom.hip_adduction,
                    t.rest.hip_adduction,
                ),
                (
                    "models/rom.toml's hip_rotation",
                    rom.hip_rotation,
                    t.rest.hip_rotation,
                ),
                (
                    "models/rom.toml's knee_flexion",
                    rom.knee_flexion,
                    t.rest.knee_flexion,
                ),
            ]
            .map(|(k, r, v)| (k, [r.lo, r.hi], v)),
        };
        let p = t.pelvis_limits;
        let r = &t.rest;
        let pelvis = [
            ("pelvis_limits.tilt", deg(p.tilt), r.pelvis_tilt),
            ("pelvis_limits.list", deg(p.list), r.pelvis_list),
            ("pelvis_limits.rotation", deg(p.rotation), r.pelvis_rotation),
        ];
        let rest_key = |limits: &str| {
            let joint = limits.rsplit(['.', ' ']).next().unwrap_or(limits);
            match limits.starts_with("pelvis") {
                true => format!("rest.pelvis_{joint}"),
                false => format!("rest.{joint}"),
            }
        };
        for (key, [lo, hi], rest) in pelvis.iter().chain(&leg) {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(bad(format!(
                    "{key} = [{}°, {}°]: the lower limit must be below the upper, both finite",
                    Shown(lo.to_degrees()),
                    Shown(hi.to_degrees())
                )));
            }
            let v = rest.to_radians();
            if !(*lo..=*hi).contains(&v) {
                return Err(bad(format!(
                    "{} = {}° lies outside its limits {key} = [{}°, {}°]",
                    rest_key(key),
                    Shown(*rest),
                    Shown(lo.to_degrees()),
                    Shown(hi.to_degrees())
                )));
            }
        }
        let (mut lower, mut upper, mut rest) = (Angles::zeros(), Angles::zeros(), Angles::zeros());
        for (i, (_, [lo, hi], r)) in [PELVIS_TILT, PELVIS_LIST, PELVIS_ROTATION]
            .iter()
            .zip(pelvis)
        {
            lower[*i] = lo;
            upper[*i] = hi;
            rest[*i] = r.to_radians();
        }
        for side in [Side::Right, Side::Left] {
            let o = leg_offset(side);
            for (k, (_, [lo, hi], r)) in leg.iter().enumerate() {
                lower[o + k] = *lo;
                upper[o + k] = *hi;
                rest[o + k] = r.to_radians();
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
                return Err(bad(format!("{name} = {} must be finite and ≥ 0", Shown(v))));
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
                return Err(bad(format!("{name} = {} must lie in (0, 1)", Shown(v))));
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
        assert!(
            e.to_string().contains(
                "rest.knee_flexion = -5° lies outside its limits models/rom.toml's knee_flexion = [0°, 135°]"
            ),
            "{e}"
        );
        let e = IkModel::parse(&TABLE.replace("xi = 20.0", "xi = -1.0"), p, &b).unwrap_err();
        assert!(e.to_string().contains("weights.xi"), "{e}");
        let e = IkModel::parse(
            &TABLE.replace("tilt = [-80.0, 25.0]", "tilt = [25.0, -80.0]"),
            p,
            &b,
        )
        .unwrap_err();
        assert!(
            e.to_string().contains("pelvis_limits.tilt = [25°, -80°]"),
            "{e}"
        );
        let e = IkModel::parse(&format!("{TABLE}\n[extra]\n"), p, &b).unwrap_err();
        assert!(e.to_string().contains("unknown field `extra`"), "{e}");
    }

    /// `[leg_limits]` replaces models/rom.toml's ranges, for both legs; the rest posture must
    /// lie inside them.
    #[test]
    fn a_file_gives_its_own_leg_limits() {
        let b = body();
        let p = Path::new("x.toml");
        let limits = "\n[leg_limits]\nhip_flexion = [-20.0, 100.0]\nhip_adduction = [-30.0, 20.0]\n\
                      hip_rotation = [-40.0, 40.0]\nknee_flexion = [0.0, 120.0]\n";
        let m = IkModel::parse(&format!("{TABLE}{limits}"), p, &b).unwrap();
        for side in [Side::Right, Side::Left] {
            let o = leg_offset(side);
            assert!((m.upper[o] - 100f64.to_radians()).abs() < 1e-15);
            assert!((m.lower[o + 1] + 30f64.to_radians()).abs() < 1e-15);
            assert!((m.upper[o + 3] - 120f64.to_radians()).abs() < 1e-15);
        }
        let tight = limits.replace(
            "knee_flexion = [0.0, 120.0]",
            "knee_flexion = [10.0, 120.0]",
        );
        let e = IkModel::parse(&format!("{TABLE}{tight}"), p, &b).unwrap_err();
        assert!(
            e.to_string()
                .contains("rest.knee_flexion = 5° lies outside its limits leg_limits.knee_flexion = [10°, 120°]"),
            "{e}"
        );
        let partial = "\n[leg_limits]\nhip_flexion = [-20.0, 100.0]\n";
        let e = IkModel::parse(&format!("{TABLE}{partial}"), p, &b).unwrap_err();
        assert!(
            e.to_string()
                .contains("missing field `hip_adduction` in [leg_limits]"),
            "{e}"
        );
    }
}
