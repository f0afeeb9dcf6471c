//! The pelvis's list and rotation by walking speed \[ours\]: the attributes `pelvic_list` and
//! `pelvic_rotation` are the amplitudes at the style's preferred speed (`preferred_velocity`)
//! and below it, and a faster walk, at dimensionless speed v̂ = v / √(g l1), scales them by the
//! ratio of measured means, mean(v̂) / mean(v̂_pref), of Schwartz, Rozumalski & Trost 2008
//! (J Biomech 41:1639, supplementary workbook: children at five speed categories;
//! `models/pelvis-speed.toml` names the cells). gait-norms.md: rotation "more at higher speed";
//! KLAW 1989 §2.1 keeps both fixed (`pelvis_speed_law` = 0). Below the preferred speed the
//! amplitudes stay the attributes': the children's list falls there, but the adult ranges
//! (±4–5°) hold from 1.2 m/s, and no adult data by speed were at hand (docs/realism.md).
use std::path::Path;

use serde::Deserialize;

use crate::model::attributes::Attributes;
use crate::model::{GRAVITY, InputError};
use crate::numerics::sampled::piecewise_linear;

const TABLE: &str = include_str!("../../models/pelvis-speed.toml");

/// The measured means the amplitudes follow, at increasing dimensionless speeds.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PelvisSpeedLaw {
    /// Dimensionless speeds v̂ of the rows, strictly increasing.
    pub speed: Vec<f64>,
    /// Mean pelvic list, stance side up, at each speed (deg).
    pub list: Vec<f64>,
    /// Mean pelvic rotation range, peak to peak, at each speed (deg).
    pub rotation: Vec<f64>,
}

impl Default for PelvisSpeedLaw {
    /// The bundled `models/pelvis-speed.toml`.
    fn default() -> Self {
        Self::parse(TABLE, Path::new("models/pelvis-speed.toml"))
            .expect("models/pelvis-speed.toml parses (tested)")
    }
}

impl PelvisSpeedLaw {
    /// Parse and check a table in `models/pelvis-speed.toml`'s layout: speeds finite and
    /// strictly increasing, one finite positive mean per speed in each column.
    pub fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        const WHAT: &str = "pelvis speed table";
        let bad = |why: String| InputError::malformed(WHAT, path, why);
        let law: PelvisSpeedLaw =
            toml::from_str(text).map_err(|e| InputError::malformed(WHAT, path, Box::new(e)))?;
        let n = law.speed.len();
        if n == 0
            || !law.speed.iter().all(|v| v.is_finite())
            || law.speed.windows(2).any(|w| w[0] >= w[1])
        {
            return Err(bad("speed must be finite and strictly increasing".into()));
        }
        for (name, column) in [("list", &law.list), ("rotation", &law.rotation)] {
            if column.len() != n || !column.iter().all(|m| m.is_finite() && *m > 0.0) {
                return Err(bad(format!(
                    "{name} needs {n} finite positive means, one per speed"
                )));
            }
        }
        Ok(law)
    }

    /// The factors (list, rotation) at dimensionless speed `v_hat` for amplitudes given at
    /// `anchor`: mean(v̂) / mean(anchor) above the anchor, 1 up to it; each mean linear in v̂
    /// between the rows and held beyond the first and last.
    pub fn factors(&self, v_hat: f64, anchor: f64) -> (f64, f64) {
        let v_hat = v_hat.max(anchor);
        let ratio = |column: &[f64]| {
            piecewise_linear(&self.speed, column, v_hat)
                / piecewise_linear(&self.speed, column, anchor)
        };
        (ratio(&self.list), ratio(&self.rotation))
    }

    /// `attrs` for a walk at velocity `v` (m/s) of a body with leg length `l1` (m): the list
    /// and rotation scaled by 1 + g (f − 1), f [`Self::factors`] at v / √(g l1) for amplitudes
    /// given at `preferred_velocity` / √(g l1), and g the attribute `pelvis_speed_law` (0 keeps
    /// the attributes' amplitudes, KLAW 1989).
    pub fn scale(&self, attrs: &Attributes, v: f64, l1: f64) -> Attributes {
        let unit = (GRAVITY * l1).sqrt();
        let (list, rotation) = self.factors(v / unit, attrs.preferred_velocity / unit);
        let g = attrs.pelvis_speed_law;
        Attributes {
            pelvic_list: attrs.pelvic_list * (1.0 + g * (list - 1.0)),
            pelvic_rotation: attrs.pelvic_rotation * (1.0 + g * (rotation - 1.0)),
            ..attrs.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law() -> PelvisSpeedLaw {
        PelvisSpeedLaw::default()
    }

    /// At the anchor both factors are 1; at a listed speed each is the ratio of the table's own
    /// means, read from the file's text independently of the parser's columns.
    #[test]
    fn factors_are_ratios_of_the_table_means() {
        let l = law();
        let (a, b) = l.factors(0.5, 0.5);
        assert!((a - 1.0).abs() < 1e-15 && (b - 1.0).abs() < 1e-15);
        // the fourth row (the fast category) against the third (free)
        let (list, rot) = l.factors(0.560, 0.429);
        assert!((list - 5.54 / 4.40).abs() < 1e-12, "{list}");
        assert!((rot - 15.22 / 11.98).abs() < 1e-12, "{rot}");
    }

    /// Midway between two rows the mean is the average of theirs; beyond the last row it
    /// holds; up to the anchor both factors are 1.
    #[test]
    fn factors_are_linear_between_rows_and_held_beyond() {
        let l = law();
        let mid = 0.5 * (0.560 + 0.694);
        let (list, _) = l.factors(mid, 0.429);
        assert!((list - 0.5 * (5.54 + 6.37) / 4.40).abs() < 1e-12, "{list}");
        let (_, rot) = l.factors(0.694, 0.5 * (0.429 + 0.560));
        assert!(
            (rot - 18.65 / (0.5 * (11.98 + 15.22))).abs() < 1e-12,
            "{rot}"
        );
        assert_eq!(l.factors(0.9, 0.429), l.factors(0.694, 0.429));
        assert_eq!(l.factors(0.01, 0.429), (1.0, 1.0));
        assert_eq!(l.factors(0.3, 0.429), (1.0, 1.0));
    }

    /// The gain blends from the attributes' own amplitudes (0) to the law's (1), the anchor is
    /// the preferred velocity, and nothing but the list and the rotation changes.
    #[test]
    fn the_gain_blends_the_scaling_from_the_preferred_speed() {
        let l = law();
        let attrs = Attributes::default();
        let l1 = 0.8676;
        let unit = (GRAVITY * l1).sqrt();
        let (v, v_pref) = (0.694 * unit, attrs.preferred_velocity);
        let pref_list = piecewise_linear(&l.speed, &l.list, v_pref / unit);
        let pref_rot = piecewise_linear(&l.speed, &l.rotation, v_pref / unit);
        let off = l.scale(
            &Attributes {
                pelvis_speed_law: 0.0,
                ..attrs.clone()
            },
            v,
            l1,
        );
        assert_eq!(off.pelvic_list, attrs.pelvic_list);
        assert_eq!(off.pelvic_rotation, attrs.pelvic_rotation);
        let on = l.scale(&attrs, v, l1);
        assert_eq!(attrs.pelvis_speed_law, 1.0);
        assert!((on.pelvic_list / attrs.pelvic_list - 6.37 / pref_list).abs() < 1e-9);
        assert!((on.pelvic_rotation / attrs.pelvic_rotation - 18.65 / pref_rot).abs() < 1e-9);
        let at_pref = l.scale(&attrs, v_pref, l1);
        assert_eq!(at_pref.pelvic_list, attrs.pelvic_list);
        let half = l.scale(
            &Attributes {
                pelvis_speed_law: 0.5,
                ..attrs.clone()
            },
            v,
            l1,
        );
        let expect = attrs.pelvic_list * 0.5 * (1.0 + 6.37 / pref_list);
        assert!((half.pelvic_list - expect).abs() < 1e-12);
        let rest = Attributes {
            pelvic_list: attrs.pelvic_list,
            pelvic_rotation: attrs.pelvic_rotation,
            ..on
        };
        assert_eq!(rest, attrs);
    }

    /// A malformed table is refused naming what is wrong.
    #[test]
    fn malformed_tables_are_refused() {
        let p = Path::new("t.toml");
        let e = PelvisSpeedLaw::parse("speed = [0.2, 0.1]\nlist = [1, 2]\nrotation = [1, 2]", p)
            .unwrap_err();
        assert!(e.to_string().contains("strictly increasing"), "{e}");
        let e = PelvisSpeedLaw::parse("speed = [0.1, 0.2]\nlist = [1]\nrotation = [1, 2]", p)
            .unwrap_err();
        assert!(e.to_string().contains("list needs 2"), "{e}");
    }
}
