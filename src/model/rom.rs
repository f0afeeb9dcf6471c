//! The normal ranges of motion of the lower-limb joints, from `models/rom.toml` (AAOS 1965,
//! "Joint Motion: Method of Measuring and Recording"; the file quotes the table it uses), in the
//! clinical signs of [`crate::figure::clinical`].
use std::path::Path;

use serde::Deserialize;

use crate::model::InputError;

const TABLE: &str = include_str!("../../models/rom.toml");

/// One joint angle's normal range (rad): `lo ≤ angle ≤ hi`.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Range {
    /// The lower end (rad; degrees in the file).
    pub lo: f64,
    /// The upper end (rad; degrees in the file).
    pub hi: f64,
}

impl Range {
    /// Whether `angle` (rad) lies in the range.
    pub fn contains(&self, angle: f64) -> bool {
        (self.lo..=self.hi).contains(&angle)
    }
}

/// The normal ranges of motion of one leg's joints (clinical signs).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RangesOfMotion {
    /// Hip flexion (+) and extension (−).
    pub hip_flexion: Range,
    /// Hip adduction (+) and abduction (−).
    pub hip_adduction: Range,
    /// Hip internal (+) and external (−) rotation.
    pub hip_rotation: Range,
    /// Knee flexion.
    pub knee_flexion: Range,
    /// Ankle dorsiflexion (+) and plantar flexion (−).
    pub ankle_flexion: Range,
    /// Foot inversion (+) and eversion (−).
    pub ankle_inversion: Range,
    /// Metatarsophalangeal dorsiflexion (+, toes up) and plantar flexion (−).
    pub mtp_flexion: Range,
}

impl Default for RangesOfMotion {
    /// The bundled `models/rom.toml`.
    fn default() -> Self {
        Self::parse(TABLE, Path::new("models/rom.toml")).expect("models/rom.toml parses (tested)")
    }
}

impl RangesOfMotion {
    /// Parse a table in `models/rom.toml`'s layout (degrees), converting to rad; every range
    /// must have lo < hi.
    pub fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        let mut r: RangesOfMotion = toml::from_str(text)
            .map_err(|e| InputError::malformed("range-of-motion table", path, Box::new(e)))?;
        for (name, range) in r.ranges_mut() {
            if !(range.lo.is_finite() && range.hi.is_finite() && range.lo < range.hi) {
                return Err(InputError::malformed(
                    "range-of-motion table",
                    path,
                    format!("{name}: lo must be below hi (finite degrees)"),
                ));
            }
            range.lo = range.lo.to_radians();
            range.hi = range.hi.to_radians();
        }
        Ok(r)
    }

    /// Every range with its name.
    pub fn ranges(&self) -> [(&'static str, Range); 7] {
        [
            ("hip_flexion", self.hip_flexion),
            ("hip_adduction", self.hip_adduction),
            ("hip_rotation", self.hip_rotation),
            ("knee_flexion", self.knee_flexion),
            ("ankle_flexion", self.ankle_flexion),
            ("ankle_inversion", self.ankle_inversion),
            ("mtp_flexion", self.mtp_flexion),
        ]
    }

    fn ranges_mut(&mut self) -> [(&'static str, &mut Range); 7] {
        [
            ("hip_flexion", &mut self.hip_flexion),
            ("hip_adduction", &mut self.hip_adduction),
            ("hip_rotation", &mut self.hip_rotation),
            ("knee_flexion", &mut self.knee_flexion),
            ("ankle_flexion", &mut self.ankle_flexion),
            ("ankle_inversion", &mut self.ankle_inversion),
            ("mtp_flexion", &mut self.mtp_flexion),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bundled file parses, every range has lo < hi, and two of AAOS 1965's values come
    /// through in rad (hip flexion 120°, ankle plantar flexion 50°).
    #[test]
    fn the_bundled_table_parses_and_every_range_is_ordered() {
        let r = RangesOfMotion::default();
        for (name, range) in r.ranges() {
            assert!(range.lo < range.hi, "{name}");
        }
        assert!((r.hip_flexion.hi - 120f64.to_radians()).abs() < 1e-15);
        assert!((r.ankle_flexion.lo + 50f64.to_radians()).abs() < 1e-15);
    }

    #[test]
    fn a_reversed_range_and_an_unknown_name_are_refused() {
        let bad = TABLE.replace("lo = -30.0\nhi = 120.0", "lo = 120.0\nhi = -30.0");
        assert_ne!(bad, TABLE);
        let e = RangesOfMotion::parse(&bad, Path::new("x.toml")).unwrap_err();
        assert!(e.to_string().contains("hip_flexion"), "{e}");
        let extra = format!("{TABLE}\n[elbow]\nlo = 0.0\nhi = 1.0\n");
        assert!(RangesOfMotion::parse(&extra, Path::new("x.toml")).is_err());
    }
}
