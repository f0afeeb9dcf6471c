//! The constants of the generalization and their defaults, from `models/generalize.toml`: the α
//! slopes of eqs. 5, 6, 21 and 24, and the tolerances of reading a measured walk and of posing.
use std::path::Path;

use serde::Deserialize;

use crate::model::InputError;

const TABLE: &str = include_str!("../../models/generalize.toml");

/// The generalization's constants (angles in rad; `models/generalize.toml` documents each).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeneralizeParameters {
    /// α1: knee flexion at heel strike per leg length of step length (eq. 5).
    pub alpha1: f64,
    /// α2: the foot's toes-up angle at heel strike per leg length (eq. 6).
    pub alpha2: f64,
    /// α3: the foot's heel-up angle at toe-off per leg length (eq. 21).
    pub alpha3: f64,
    /// α4: the toes' angle at toe-off per leg length (eq. 24).
    pub alpha4: f64,
    /// A foot point touches the floor within this height of it (m).
    pub contact_height: f64,
    /// A measured toe tip leaves the floor when its forward speed rises through this (m/s).
    pub lift_speed: f64,
    /// A foot is flat, or its toes down, within this angle of the floor (rad).
    pub flat_angle: f64,
    /// The largest relative difference of a measured segment's length from its median.
    pub length_tolerance: f64,
    /// The fewest frames of a measured step.
    pub min_frames_per_step: usize,
    /// Samples per unit of normalized time of an extracted timed sequence to start from.
    pub samples_per_step: usize,
    /// An extracted angle sequence reproduces its prototype to this (rad) between samples.
    pub sample_angle: f64,
    /// An extracted position sequence reproduces its prototype to this (m) between samples.
    pub sample_length: f64,
    /// How far below the floor a posed foot point may be (m).
    pub floor_tolerance: f64,
    /// The most the hip may come down from the walk data's H to let the legs reach (m).
    pub hip_drop_max: f64,
    /// Instants of a step checked before it is walked.
    pub check_samples: usize,
    /// The farthest a swing foot point may move while on the floor (within `floor_tolerance`)
    /// before its heel strike or after its toe-off (m).
    pub slide_max: f64,
}

impl Default for GeneralizeParameters {
    fn default() -> Self {
        Self::parse(TABLE, Path::new("models/generalize.toml"))
            .expect("the bundled generalization table parses (tested)")
    }
}

impl GeneralizeParameters {
    /// The α slopes α1…α4.
    pub fn alphas(&self) -> [f64; 4] {
        [self.alpha1, self.alpha2, self.alpha3, self.alpha4]
    }

    /// Read and check the model file `path` (the layout of `models/generalize.toml`;
    /// [`Self::parse`]'s rules).
    pub fn read(path: &Path) -> Result<Self, InputError> {
        Self::parse(
            &crate::model::file::read_text("generalization model", path)?,
            path,
        )
    }

    /// Parse a table in `models/generalize.toml`'s layout (angles in degrees), every key of it
    /// and no other, converting its angles to rad; `path` names the source in errors. Each
    /// value must lie in its range, in the file's units: alpha1…alpha4 [−170, 170] °/leg length,
    /// contact_height [0, 0.1] m, lift_speed [0, 10] m/s, flat_angle [0, 17]°,
    /// length_tolerance [0, 0.5], min_frames_per_step [3, 1e6], samples_per_step [2, 1e5],
    /// sample_angle [1e-7, 5.7]°, sample_length [1e-9, 0.01] m, floor_tolerance [0, 0.01] m,
    /// hip_drop_max [0, 0.5] m, check_samples [2, 1e6], slide_max [0, 0.05] m.
    pub fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        let bad = |reason: String| InputError::malformed("generalization model", path, reason);
        let mut p: GeneralizeParameters = crate::model::file::parse_toml(text).map_err(bad)?;
        let slope = "°/leg length";
        for (name, v, lo, hi, unit) in [
            ("alpha1", p.alpha1, -170.0, 170.0, slope),
            ("alpha2", p.alpha2, -170.0, 170.0, slope),
            ("alpha3", p.alpha3, -170.0, 170.0, slope),
            ("alpha4", p.alpha4, -170.0, 170.0, slope),
            ("contact_height", p.contact_height, 0.0, 0.1, "m"),
            ("lift_speed", p.lift_speed, 0.0, 10.0, "m/s"),
            ("flat_angle", p.flat_angle, 0.0, 17.0, "°"),
            ("length_tolerance", p.length_tolerance, 0.0, 0.5, ""),
            (
                "min_frames_per_step",
                p.min_frames_per_step as f64,
                3.0,
                1e6,
                "",
            ),
            ("samples_per_step", p.samples_per_step as f64, 2.0, 1e5, ""),
            ("sample_angle", p.sample_angle, 1e-7, 5.7, "°"),
            ("sample_length", p.sample_length, 1e-9, 0.01, "m"),
            ("floor_tolerance", p.floor_tolerance, 0.0, 0.01, "m"),
            ("hip_drop_max", p.hip_drop_max, 0.0, 0.5, "m"),
            ("check_samples", p.check_samples as f64, 2.0, 1e6, ""),
            ("slide_max", p.slide_max, 0.0, 0.05, "m"),
        ] {
            InputError::check_range(name, v, lo, hi, unit).map_err(|e| bad(e.to_string()))?;
        }
        for a in [
            &mut p.alpha1,
            &mut p.alpha2,
            &mut p.alpha3,
            &mut p.alpha4,
            &mut p.flat_angle,
            &mut p.sample_angle,
        ] {
            *a = a.to_radians();
        }
        Ok(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bundled table parses, in radians; a value out of range names itself.
    #[test]
    fn the_bundled_table_parses_and_bad_values_are_named() {
        let p = GeneralizeParameters::default();
        assert!((p.flat_angle - 2f64.to_radians()).abs() < 1e-15);
        assert_eq!(p.alpha1, 0.0);
        let bad = TABLE.replace("contact_height = 0.001", "contact_height = -1");
        let e = GeneralizeParameters::parse(&bad, Path::new("g.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("g.toml: contact_height = -1 m is out of range: valid range is [0, 0.1] m"),
            "{e}"
        );
        let bad = TABLE.replace("alpha2 = 22.31", "alpha2 = 200");
        let e = GeneralizeParameters::parse(&bad, Path::new("g.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("alpha2 = 200 °/leg length is out of range"),
            "{e}"
        );
        let e = GeneralizeParameters::parse("alpha1 = 0", Path::new("g.toml")).unwrap_err();
        assert!(matches!(e, InputError::Malformed { .. }));
    }
}
