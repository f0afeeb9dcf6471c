//! The constants of non-rhythmic stepping and their defaults, from `models/nrs.toml`.
use std::path::Path;

use serde::Deserialize;

use crate::model::{InputError, Shown};

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

/// A closed or open end of a parameter's range.
#[derive(Clone, Copy)]
enum End {
    Closed(f64),
    Open(f64),
}

impl End {
    fn admits_above(self, v: f64) -> bool {
        match self {
            End::Closed(lo) => v >= lo,
            End::Open(lo) => v > lo,
        }
    }

    fn admits_below(self, v: f64) -> bool {
        match self {
            End::Closed(hi) => v <= hi,
            End::Open(hi) => v < hi,
        }
    }
}

/// `key = v unit` if `v` is finite and inside (lo, hi) with their ends; else the rule in words.
fn check(key: &str, v: f64, lo: End, hi: End, unit: &str) -> Result<(), String> {
    if v.is_finite() && lo.admits_above(v) && hi.admits_below(v) {
        return Ok(());
    }
    let (open, lo) = match lo {
        End::Closed(x) => ('[', x),
        End::Open(x) => ('(', x),
    };
    let (close, hi) = match hi {
        End::Closed(x) => (']', x),
        End::Open(x) => (')', x),
    };
    Err(format!(
        "{key} = {}{unit} must lie in {open}{}, {}{close}{unit}",
        Shown(v),
        Shown(lo),
        Shown(hi)
    ))
}

impl NrsParameters {
    /// Read and check the model file `path` (the layout of `models/nrs.toml`; [`Self::parse`]'s
    /// rules).
    pub fn read(path: &Path) -> Result<Self, InputError> {
        Self::parse(&crate::model::file::read_text("NRS model", path)?, path)
    }

    /// Parse a table in `models/nrs.toml`'s layout (degrees), every key of it and no other,
    /// converting its angles to rad. Each value must lie in its range, in the file's units:
    /// region_angle (0, 172)°, boundary_tolerance [0, 45]°, parallel_tolerance [0, 90]°,
    /// swing_height (0, 0.5] m, swing_height_factor_max (0, 10], swing_height_factor [0,
    /// swing_height_factor_max], the three foot angles [−60, 60]°, ankle_dorsiflexion_max (0,
    /// 60]°, ankle_eversion_max (0, 45]°, turn_max (0, 180]°, duration_min (0, 60] s,
    /// duration_max (duration_min, 60] s, turn_step_duration [duration_min, duration_max] s,
    /// turn_lift_off and start_toe_off (0, 1), stop_handover [0, 0.5] s, neck_share [0, 1],
    /// stand_knee [0, 60]°, contact_height (0, 0.1] m, table_intervals [8, 100000].
    pub fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        let bad = |reason: String| InputError::malformed("NRS model", path, reason);
        let mut p: NrsParameters = crate::model::file::parse_toml(text).map_err(bad)?;
        use End::{Closed, Open};
        for (key, v, lo, hi, unit) in [
            ("region_angle", p.region_angle, Open(0.0), Open(172.0), "°"),
            (
                "boundary_tolerance",
                p.boundary_tolerance,
                Closed(0.0),
                Closed(45.0),
                "°",
            ),
            (
                "parallel_tolerance",
                p.parallel_tolerance,
                Closed(0.0),
                Closed(90.0),
                "°",
            ),
            ("swing_height", p.swing_height, Open(0.0), Closed(0.5), " m"),
            (
                "swing_height_factor_max",
                p.swing_height_factor_max,
                Open(0.0),
                Closed(10.0),
                "",
            ),
            (
                "swing_height_factor",
                p.swing_height_factor,
                Closed(0.0),
                Closed(p.swing_height_factor_max),
                "",
            ),
            (
                "strike_swing",
                p.strike_swing,
                Closed(-60.0),
                Closed(60.0),
                "°",
            ),
            (
                "strike_stance",
                p.strike_stance,
                Closed(-60.0),
                Closed(60.0),
                "°",
            ),
            (
                "lateral_toe_off_swing",
                p.lateral_toe_off_swing,
                Closed(-60.0),
                Closed(60.0),
                "°",
            ),
            (
                "ankle_dorsiflexion_max",
                p.ankle_dorsiflexion_max,
                Open(0.0),
                Closed(60.0),
                "°",
            ),
            (
                "ankle_eversion_max",
                p.ankle_eversion_max,
                Open(0.0),
                Closed(45.0),
                "°",
            ),
            ("turn_max", p.turn_max, Open(0.0), Closed(180.0), "°"),
            (
                "duration_min",
                p.duration_min,
                Open(0.0),
                Closed(60.0),
                " s",
            ),
            (
                "duration_max",
                p.duration_max,
                Open(p.duration_min),
                Closed(60.0),
                " s",
            ),
            (
                "turn_step_duration",
                p.turn_step_duration,
                Closed(p.duration_min),
                Closed(p.duration_max),
                " s",
            ),
            ("turn_lift_off", p.turn_lift_off, Open(0.0), Open(1.0), ""),
            ("start_toe_off", p.start_toe_off, Open(0.0), Open(1.0), ""),
            (
                "stop_handover",
                p.stop_handover,
                Closed(0.0),
                Closed(0.5),
                " s",
            ),
            ("neck_share", p.neck_share, Closed(0.0), Closed(1.0), ""),
            ("stand_knee", p.stand_knee, Closed(0.0), Closed(60.0), "°"),
            (
                "contact_height",
                p.contact_height,
                Open(0.0),
                Closed(0.1),
                " m",
            ),
            (
                "table_intervals",
                p.table_intervals as f64,
                Closed(8.0),
                Closed(100_000.0),
                "",
            ),
        ] {
            check(key, v, lo, hi, unit).map_err(bad)?;
        }
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
        let e = NrsParameters::parse(&text, Path::new("x.toml")).unwrap_err();
        assert!(e.to_string().contains("unknown field `surprise`"), "{e}");
    }

    /// A value outside its range is named with the range, in the file's units.
    #[test]
    fn values_out_of_range_are_named() {
        for (from, to, expect) in [
            (
                "region_angle = 60.0",
                "region_angle = 180.0",
                "region_angle = 180° must lie in (0, 172)°",
            ),
            (
                "swing_height = 0.05",
                "swing_height = -0.05",
                "swing_height = -0.05 m must lie in (0, 0.5] m",
            ),
            (
                "swing_height_factor = 1.0",
                "swing_height_factor = 5.0",
                "swing_height_factor = 5 must lie in [0, 4]",
            ),
            (
                "duration_max = 3.0",
                "duration_max = 0.2",
                "duration_max = 0.2 s must lie in (0.3, 60] s",
            ),
            (
                "turn_step_duration = 0.6",
                "turn_step_duration = 4",
                "turn_step_duration = 4 s must lie in [0.3, 3] s",
            ),
            (
                "neck_share = 0.6666666666666666",
                "neck_share = 1.5",
                "neck_share = 1.5 must lie in [0, 1]",
            ),
            (
                "table_intervals = 256",
                "table_intervals = 4",
                "table_intervals = 4 must lie in [8, 100000]",
            ),
        ] {
            assert!(TABLE.contains(from), "{from}");
            let e = NrsParameters::parse(&TABLE.replace(from, to), Path::new("n.toml"))
                .unwrap_err()
                .to_string();
            assert!(e.contains(expect), "{to}: {e}");
        }
    }
}
