//! The published normal ranges of adult walking (`models/gait-norms.toml`, the rows of
//! `gait-norms.md`: Inman, Ralston & Todd 1981; Murray 1964; Winter; Perry; Whittle) and the
//! check of an averaged gait cycle against them (issue item 9): each norm is measured on every
//! curve of its panel ([`check`]) and compared at the resolution the values are shown to
//! (0.1 ° or cm, `CHECK_RESOLUTION`).
use std::path::Path;

use serde::Deserialize;

use super::cycle::{GaitCycle, Panel};
use super::extent;
use crate::figure::skeleton::Side;
use crate::model::InputError;

/// The bundled norm table (`models/gait-norms.toml`).
pub(crate) const NORMS_TABLE: &str = include_str!("../../models/gait-norms.toml");
/// The values are shown to 0.1 (° or cm) and compared with the norms at that resolution.
pub(crate) const CHECK_RESOLUTION: f64 = 0.1;

/// How a curve is compared with a norm's range.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Measure {
    /// The value at `at` % of the cycle.
    At,
    /// The largest value inside the windows.
    Max,
    /// The smallest value inside the windows.
    Min,
    /// max − min over the whole cycle.
    PeakToPeak,
}

/// One published normal range (a row of `models/gait-norms.toml`; its header documents the
/// fields).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Norm {
    /// The curve it applies to.
    pub panel: Panel,
    /// What the published table calls it, e.g. `hip flexion at heel strike`.
    pub name: String,
    /// Short name for the panel's note.
    pub label: String,
    /// How the curve is compared with the range [low, high].
    pub measure: Measure,
    /// Cycle % for [`Measure::At`].
    #[serde(default)]
    pub at: Option<f64>,
    /// Lower end of the normal range, in `unit`.
    pub low: f64,
    /// Upper end of the normal range, in `unit`.
    pub high: f64,
    /// `deg` or `cm`: the panel's unit.
    pub unit: String,
    /// Cycle-% intervals [start, end] where the band is shaded (and, for max / min, searched).
    pub windows: Vec<[f64; 2]>,
    /// Where the windows come from: `table` (the published timing, widened by 5 % either side)
    /// or `chosen`, with the reason.
    pub window_source: String,
    /// The line of the published table (`gait-norms.md`) the range is read from.
    pub source: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NormFile {
    norm: Vec<Norm>,
}

/// The norms a figure is checked against.
#[derive(Clone, Debug, PartialEq)]
pub struct NormTable {
    /// The norms, in the table's order.
    pub norms: Vec<Norm>,
}

impl NormTable {
    /// Parse and check a norm table: finite `low < high`, the panel's unit, windows inside
    /// [0, 100] with start < end, `at` in [0, 100] given exactly for `measure = "at"`, windows
    /// for max / min. Errors are [`InputError::Malformed`] naming `path` and the row.
    pub fn parse(text: &str, path: &Path) -> Result<NormTable, InputError> {
        let file: NormFile =
            toml::from_str(text).map_err(|e| InputError::malformed("norm table", path, e))?;
        for (i, n) in file.norm.iter().enumerate() {
            let row = |reason: &str| {
                let reason = format!("norm {} ({}): {reason}", i + 1, n.name);
                InputError::malformed("norm table", path, reason)
            };
            if !(n.low.is_finite() && n.high.is_finite() && n.low < n.high) {
                return Err(row("low and high must be finite with low < high"));
            }
            if n.unit != n.panel.unit() {
                return Err(row(&format!(
                    "unit `{}`: the panel's values are in {}",
                    n.unit,
                    n.panel.unit()
                )));
            }
            let in_cycle = |p: f64| (0.0..=100.0).contains(&p);
            if n.windows
                .iter()
                .any(|w| !(in_cycle(w[0]) && in_cycle(w[1]) && w[0] < w[1]))
            {
                return Err(row("windows must lie in [0, 100] % with start < end"));
            }
            match (n.measure, n.at) {
                (Measure::At, Some(p)) if in_cycle(p) => {}
                (Measure::At, _) => return Err(row("measure \"at\" needs `at` in [0, 100] %")),
                (_, Some(_)) => return Err(row("`at` is only for measure \"at\"")),
                (Measure::Max | Measure::Min, None) if n.windows.is_empty() => {
                    return Err(row("max / min need the windows to search"));
                }
                (Measure::PeakToPeak, None) if n.low < 0.0 => {
                    return Err(row("a peak-to-peak range cannot be negative"));
                }
                _ => {}
            }
        }
        Ok(NormTable { norms: file.norm })
    }

    /// The bundled table (`models/gait-norms.toml`).
    pub fn builtin() -> NormTable {
        Self::parse(NORMS_TABLE, Path::new("models/gait-norms.toml"))
            .expect("the bundled norm table parses (tested)")
    }
}

/// A norm's measure on one curve.
#[derive(Clone, Debug, PartialEq)]
pub struct NormCheck {
    /// The norm's panel.
    pub panel: Panel,
    /// The norm's name.
    pub name: String,
    /// The curve's leg, `None` for the pelvis.
    pub side: Option<Side>,
    /// The norm's measure.
    pub measure: Measure,
    /// The measured value, in the norm's unit.
    pub value: f64,
    /// Where in the cycle (%) it was measured (none for peak to peak).
    pub at_pct: Option<f64>,
    /// The norm's range [low, high], in `unit`.
    pub low: f64,
    /// Upper end of the norm's range, in `unit`.
    pub high: f64,
    /// `deg` or `cm`.
    pub unit: String,
}

impl NormCheck {
    /// Whether the value lies in [low, high], compared as it is shown: to
    /// 0.1 ° or cm, `CHECK_RESOLUTION` (a peak of 3.9999° against a norm of 4–5° is inside).
    pub fn inside(&self) -> bool {
        let half = 0.5 * CHECK_RESOLUTION;
        self.value >= self.low - half && self.value <= self.high + half
    }

    /// One line for people: `knee peak swing flexion, right: 61.2° at 72 % (norm 55…65°): inside`.
    pub fn describe(&self) -> String {
        let unit = if self.unit == "deg" { "°" } else { " cm" };
        let side = match self.side {
            Some(s) => format!(", {}", if s == Side::Right { "right" } else { "left" }),
            None => String::new(),
        };
        let at = self
            .at_pct
            .map_or(String::new(), |p| format!(" at {p:.0} %"));
        format!(
            "{}{side}: {:.1}{unit}{at} (norm {}…{}{unit}): {}",
            self.name,
            self.value,
            self.low,
            self.high,
            if self.inside() { "inside" } else { "OUTSIDE" }
        )
    }
}

/// The value of a 101-sample curve at `p` % (linear interpolation).
fn at_pct(values: &[f64], p: f64) -> f64 {
    let x = p.clamp(0.0, 100.0);
    let i = (x.floor() as usize).min(values.len().saturating_sub(2));
    let u = x - i as f64;
    values[i] + u * (values[i + 1] - values[i])
}

/// Measure every norm on every curve of its panel.
pub fn check(cycle: &GaitCycle, norms: &NormTable) -> Vec<NormCheck> {
    let mut out = Vec::new();
    for n in &norms.norms {
        for c in cycle.panel_curves(n.panel) {
            if c.values.len() < 2 {
                continue;
            }
            let in_window = |p: usize| {
                n.windows
                    .iter()
                    .any(|w| (p as f64) >= w[0] && (p as f64) <= w[1])
            };
            let extreme = |better: fn(f64, f64) -> bool| {
                c.values
                    .iter()
                    .enumerate()
                    .filter(|(p, v)| in_window(*p) && v.is_finite())
                    .fold(None, |acc: Option<(usize, f64)>, (p, &v)| match acc {
                        Some((_, best)) if !better(v, best) => acc,
                        _ => Some((p, v)),
                    })
            };
            let (value, at) = match n.measure {
                Measure::At => {
                    let p = n.at.unwrap_or(0.0);
                    (at_pct(&c.values, p), Some(p))
                }
                Measure::Max => match extreme(|a, b| a > b) {
                    Some((p, v)) => (v, Some(p as f64)),
                    None => continue,
                },
                Measure::Min => match extreme(|a, b| a < b) {
                    Some((p, v)) => (v, Some(p as f64)),
                    None => continue,
                },
                Measure::PeakToPeak => match extent(c.values.iter().copied()) {
                    Some((lo, hi)) => (hi - lo, None),
                    None => continue,
                },
            };
            out.push(NormCheck {
                panel: n.panel,
                name: n.name.clone(),
                side: c.side,
                measure: n.measure,
                value,
                at_pct: at,
                low: n.low,
                high: n.high,
                unit: n.unit.clone(),
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bundled_table_parses_and_has_every_panel() {
        let t = NormTable::builtin();
        for p in Panel::ALL {
            assert!(t.norms.iter().any(|n| n.panel == p), "{p:?}");
        }
    }

    #[test]
    fn bad_rows_are_malformed_errors() {
        let row = |extra: &str| {
            format!(
                "[[norm]]\npanel = \"knee_flexion\"\nname = \"x\"\nlabel = \"x\"\nunit = \"deg\"\n\
                 window_source = \"\"\nsource = \"\"\n{extra}"
            )
        };
        let bad = [
            "measure = \"max\"\nlow = 5.0\nhigh = 1.0\nwindows = [[0.0, 10.0]]",
            "measure = \"max\"\nlow = 1.0\nhigh = 5.0\nwindows = [[10.0, 5.0]]",
            "measure = \"max\"\nlow = 1.0\nhigh = 5.0\nwindows = [[0.0, 101.0]]",
            "measure = \"max\"\nlow = 1.0\nhigh = 5.0\nwindows = []",
            "measure = \"at\"\nlow = 1.0\nhigh = 5.0\nwindows = []",
            "measure = \"min\"\nat = 3.0\nlow = 1.0\nhigh = 5.0\nwindows = [[0.0, 1.0]]",
            "measure = \"sometimes\"\nlow = 1.0\nhigh = 5.0\nwindows = []",
        ];
        for b in bad {
            let e = NormTable::parse(&row(b), Path::new("n.toml")).unwrap_err();
            assert!(matches!(e, InputError::Malformed { .. }), "{b}: {e}");
        }
        let cm = row("measure = \"max\"\nlow = 1.0\nhigh = 5.0\nwindows = [[0.0, 1.0]]")
            .replace("\"deg\"", "\"cm\"");
        assert!(NormTable::parse(&cm, Path::new("n.toml")).is_err());
        let good = row("measure = \"at\"\nat = 0.0\nlow = 1.0\nhigh = 5.0\nwindows = []");
        assert_eq!(
            NormTable::parse(&good, Path::new("n.toml"))
                .unwrap()
                .norms
                .len(),
            1
        );
    }

    #[test]
    fn interpolation_between_samples() {
        let v: Vec<f64> = (0..=100).map(|p| (p * p) as f64).collect();
        assert_eq!(at_pct(&v, 0.0), 0.0);
        assert_eq!(at_pct(&v, 100.0), 10000.0);
        assert!((at_pct(&v, 10.5) - 110.5).abs() < 1e-12);
    }
}
