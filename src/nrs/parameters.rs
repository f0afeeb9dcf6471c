//! The constants of non-rhythmic stepping and their defaults, from `models/nrs.toml`.
use std::path::Path;

use serde::Deserialize;

use crate::model::InputError;

const TABLE: &str = include_str!("../../models/nrs.toml");

/// The NRS attribute defaults and method constants (angles in rad; `models/nrs.toml` documents
/// each and gives its source).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NrsParameters {
    /// ν: the lateral region's width (§4).
    pub region_angle: f64,
    /// The width of a region boundary (§4).
    pub boundary_tolerance: f64,
    /// The largest angle between a foot direction and the stance foot's still called parallel.
    pub parallel_tolerance: f64,
    /// The swing ankle's peak rise for swhf = 1 (m, eq. 3).
    pub swing_height: f64,
    /// swhf's default.
    pub swing_height_factor: f64,
    /// swhf's largest value.
    pub swing_height_factor_max: f64,
    /// θ_HSM+^SW's default.
    pub strike_swing: f64,
    /// θ_HSM+^ST's default.
    pub strike_stance: f64,
    /// θ_TOM^SW's default for a lateral step.
    pub lateral_toe_off_swing: f64,
    /// The ankles' largest dorsiflexion in an NRS⁻ (the heel rises or the foot plantarflexes).
    pub ankle_dorsiflexion_max: f64,
    /// The ankles' largest eversion in an NRS (a knee's plane turns from the foot's heading).
    pub ankle_eversion_max: f64,
    /// The largest turn of one turnaround (§6).
    pub turn_max: f64,
    /// δ's default (s).
    pub turn_step_duration: f64,
    /// When a turnaround's flat foot leaves the floor (normalized time of its step).
    pub turn_lift_off: f64,
    /// When the swing foot of a start from standing leaves the floor (normalized time).
    pub start_toe_off: f64,
    /// How long the walk runs past its last heel strike before the stop takes over (s).
    pub stop_handover: f64,
    /// The neck's share of the gaze twist (§5.4).
    pub neck_share: f64,
    /// The knees' flexion in quiet standing.
    pub stand_knee: f64,
    /// An NRS⁻'s shortest duration (s).
    pub duration_min: f64,
    /// An NRS⁻'s longest duration (s).
    pub duration_max: f64,
    /// Scenario events: a foot touches the floor while its lowest point is within this height
    /// of it (m).
    pub contact_height: f64,
    /// Intervals of the uniform tables over normalized time.
    pub table_intervals: usize,
}

impl Default for NrsParameters {
    /// The bundled `models/nrs.toml`.
    fn default() -> Self {
        Self::parse(TABLE, Path::new("models/nrs.toml")).expect("models/nrs.toml parses (tested)")
    }
}

impl NrsParameters {
    /// Parse a table in `models/nrs.toml`'s layout (degrees), converting its angles to rad.
    pub fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        let mut p: NrsParameters = toml::from_str(text)
            .map_err(|e| InputError::malformed("NRS table", path, Box::new(e)))?;
        for a in [
            &mut p.region_angle,
            &mut p.boundary_tolerance,
            &mut p.parallel_tolerance,
            &mut p.strike_swing,
            &mut p.strike_stance,
            &mut p.lateral_toe_off_swing,
            &mut p.ankle_dorsiflexion_max,
            &mut p.ankle_eversion_max,
            &mut p.turn_max,
            &mut p.stand_knee,
        ] {
            *a = a.to_radians();
        }
        if !(p.table_intervals >= 8 && p.region_angle > 0.0 && p.region_angle < 3.0) {
            return Err(InputError::malformed(
                "NRS table",
                path,
                "table_intervals must be at least 8 and region_angle in (0°, 172°)",
            ));
        }
        Ok(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bundled_table_parses_with_the_papers_values() {
        let p = NrsParameters::default();
        assert!((p.region_angle - 60f64.to_radians()).abs() < 1e-15);
        assert!((p.turn_max - 100f64.to_radians()).abs() < 1e-15);
        assert!((p.neck_share - 2.0 / 3.0).abs() < 1e-15);
        assert_eq!(p.swing_height, 0.05);
    }

    #[test]
    fn an_unknown_name_is_refused() {
        let text = format!("{TABLE}\nsurprise = 1.0\n");
        assert!(NrsParameters::parse(&text, Path::new("x.toml")).is_err());
    }
}
