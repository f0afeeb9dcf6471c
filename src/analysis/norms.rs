//! The published normal ranges of adult walking (`models/gait-norms.toml`, the rows of
//! `gait-norms.md`: Inman, Ralston & Todd 1981; Murray 1964; Winter; Perry; Whittle), the
//! speed-dependent ranges of Schwartz, Rozumalski & Trost 2008 (`[norm.by_speed]`, evaluated at
//! the walk's dimensionless speed, [`WalkSpeed`]) and the check of an averaged gait cycle against
//! them (issue items 9 and 16): each norm is measured on every curve of its panel ([`check`])
//! and compared at the resolution the values are shown to (0.1 ° or cm, `CHECK_RESOLUTION`).
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::cycle::{CYCLE_SKIP, GaitCycle, Panel};
use super::extent;
use crate::engine::walker::Walk;
use crate::figure::skeleton::Side;
use crate::model::{GRAVITY, InputError};
use crate::numerics::sampled::piecewise_linear;

/// The bundled norm table (`models/gait-norms.toml`).
pub(crate) const NORMS_TABLE: &str = include_str!("../../models/gait-norms.toml");
/// The values are shown to 0.1 (° or cm) and compared with the norms at that resolution.
pub(crate) const CHECK_RESOLUTION: f64 = 0.1;

/// A walk's speed as the speed-dependent norms read it: the velocity and the leg length l1
/// (hip joint to ankle, the leg of the engine's Froude limit), whose dimensionless speed
/// v / √(g l1) is Hof's (1996) scaling that Schwartz et al. 2008 bin their speeds by
/// (docs/realism.md, "Speed dependence").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WalkSpeed {
    /// Velocity (m/s).
    pub velocity: f64,
    /// Leg length l1 (m).
    pub leg_length: f64,
}

impl WalkSpeed {
    /// The speed of the cycles [`GaitCycle::from_walk`] averages: the time-weighted mean of the
    /// gait velocity over the steps after the first `CYCLE_SKIP` cycles (the whole walk when it
    /// has no more), and the body's l1.
    pub fn of_walk(walk: &Walk) -> WalkSpeed {
        let steady = walk.steps.get(2 * CYCLE_SKIP..).filter(|s| !s.is_empty());
        let steps = steady.unwrap_or(&walk.steps);
        let (mut distance, mut time) = (0.0, 0.0);
        for s in steps {
            distance += s.constraints.gait.velocity * s.constraints.timing.t_step;
            time += s.constraints.timing.t_step;
        }
        WalkSpeed {
            velocity: distance / time,
            leg_length: walk.body.l1,
        }
    }

    /// The dimensionless speed v̂ = v / √(g l1).
    pub fn dimensionless(&self) -> f64 {
        self.velocity / (GRAVITY * self.leg_length).sqrt()
    }
}

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
#[derive(Clone, Debug, PartialEq)]
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
    pub at: Option<f64>,
    /// The normal range, in `unit`: fixed, or by the walk's speed.
    pub range: NormRange,
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

/// The speed a [`BySpeed`] table lists its rows by: the source's own.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
pub enum SpeedScale {
    /// v̂ = v / √(g l1), Hof's (1996) scaling (Schwartz et al. 2008 bin their speeds by it).
    #[default]
    #[serde(rename = "v/sqrt(g l1)")]
    Dimensionless,
    /// The velocity in m/s, for sources that give no leg lengths to scale by.
    #[serde(rename = "m/s")]
    MetresPerSecond,
}

impl SpeedScale {
    /// A walk's speed on this scale.
    pub fn of(self, speed: WalkSpeed) -> f64 {
        match self {
            SpeedScale::Dimensionless => speed.dimensionless(),
            SpeedScale::MetresPerSecond => speed.velocity,
        }
    }

    /// `v/√(g l1) 0.48` or `1.20 m/s`.
    pub fn describe(self, value: f64) -> String {
        match self {
            SpeedScale::Dimensionless => format!("v/√(g l1) {value:.2}"),
            SpeedScale::MetresPerSecond => format!("{value:.2} m/s"),
        }
    }
}

/// A range given at listed speeds (`[norm.by_speed]`): the mean and SD of the quantity at
/// the listed speeds (dimensionless v̂ = v / √(g l1), or m/s: `scale`), each linear in the
/// speed between them and held at the end values out to `span`, the speeds the source's
/// subjects walked at; the range is mean ± `sd_multiple` SD. Outside `span` the source says
/// nothing, and neither does the norm.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BySpeed {
    /// The source in a few words, for a figure's legend, e.g. `Schwartz et al. 2008 (children)`.
    pub cite: String,
    /// The scale of `speed` and `span`: v̂ unless the row says `scale = "m/s"`.
    #[serde(default)]
    pub scale: SpeedScale,
    /// The listed speeds, increasing.
    pub speed: Vec<f64>,
    /// [slowest, fastest] speed the norm holds for.
    pub span: [f64; 2],
    /// The quantity's mean at each listed speed, in the norm's unit.
    pub mean: Vec<f64>,
    /// Its standard deviation at each listed speed, in the norm's unit.
    pub sd: Vec<f64>,
    /// The range's half-width in SDs.
    pub sd_multiple: f64,
}

impl BySpeed {
    /// Why the table is unusable, if it is: speeds finite and strictly increasing (at least
    /// one), `span` holding them, one finite mean and one finite positive SD per speed, a finite
    /// positive `sd_multiple`.
    fn fault(&self) -> Option<String> {
        let n = self.speed.len();
        let finite = |xs: &[f64]| xs.iter().all(|x| x.is_finite());
        if n == 0 || !finite(&self.speed) || self.speed.windows(2).any(|w| w[0] >= w[1]) {
            return Some("by_speed: speed must be finite and strictly increasing".into());
        }
        if !(finite(&self.span)
            && self.span[0] <= self.speed[0]
            && self.speed[n - 1] <= self.span[1])
        {
            return Some(format!(
                "by_speed: span {:?} must be finite and hold the speeds {}…{}",
                self.span,
                self.speed[0],
                self.speed[n - 1]
            ));
        }
        if self.mean.len() != n || self.sd.len() != n {
            return Some(format!(
                "by_speed: {} speeds need as many means and SDs, not {} and {}",
                n,
                self.mean.len(),
                self.sd.len()
            ));
        }
        if !finite(&self.mean) || !self.sd.iter().all(|s| s.is_finite() && *s > 0.0) {
            return Some("by_speed: means must be finite and SDs finite and > 0".into());
        }
        if !(self.sd_multiple.is_finite() && self.sd_multiple > 0.0) {
            return Some("by_speed: sd_multiple must be finite and > 0".into());
        }
        None
    }

    /// [low, high] at speed `v` on the table's `scale`, or `None` outside `span` (or for a
    /// speed that is not a number). The span's ends hold to 1e-9 of their size: a walk asked
    /// at 1.6 m/s measures its speed as a sum over steps, a few ulps away.
    pub fn range(&self, v: f64) -> Option<(f64, f64)> {
        let slack = 1e-9 * self.span[1].abs().max(1.0);
        if !(self.span[0] - slack..=self.span[1] + slack).contains(&v) {
            return None;
        }
        let mean = piecewise_linear(&self.speed, &self.mean, v);
        let half = self.sd_multiple * piecewise_linear(&self.speed, &self.sd, v);
        Some((mean - half, mean + half))
    }
}

/// A norm's range: the same at every speed, or by the walk's speed.
#[derive(Clone, Debug, PartialEq)]
pub enum NormRange {
    /// [low, high] at every speed.
    Fixed {
        /// Lower end, in the norm's unit.
        low: f64,
        /// Upper end, in the norm's unit.
        high: f64,
    },
    /// By the walk's dimensionless speed.
    BySpeed(BySpeed),
}

impl NormRange {
    /// The speed table of a speed-dependent range.
    pub fn by_speed(&self) -> Option<&BySpeed> {
        match self {
            NormRange::BySpeed(b) => Some(b),
            NormRange::Fixed { .. } => None,
        }
    }

    /// [low, high] for a walk at `speed`; `None` for a speed-dependent range outside its span.
    pub fn at(&self, speed: WalkSpeed) -> Option<(f64, f64)> {
        match self {
            NormRange::Fixed { low, high } => Some((*low, *high)),
            NormRange::BySpeed(b) => b.range(b.scale.of(speed)),
        }
    }
}

/// A row as written: `low` and `high`, or `[norm.by_speed]`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NormRow {
    panel: Panel,
    name: String,
    label: String,
    measure: Measure,
    #[serde(default)]
    at: Option<f64>,
    #[serde(default)]
    low: Option<f64>,
    #[serde(default)]
    high: Option<f64>,
    #[serde(default)]
    by_speed: Option<BySpeed>,
    unit: String,
    windows: Vec<[f64; 2]>,
    window_source: String,
    source: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NormFile {
    norm: Vec<NormRow>,
}

impl NormRow {
    /// The checked norm (see [`NormTable::parse`]), or why not.
    fn check(self) -> Result<Norm, String> {
        let range = match (self.low, self.high, self.by_speed) {
            (Some(low), Some(high), None) if low.is_finite() && high.is_finite() && low < high => {
                NormRange::Fixed { low, high }
            }
            (Some(_), Some(_), None) => {
                return Err("low and high must be finite with low < high".into());
            }
            (None, None, Some(b)) => match b.fault() {
                Some(fault) => return Err(fault),
                None => NormRange::BySpeed(b),
            },
            (None, None, None) => return Err("a range needs low and high, or by_speed".into()),
            _ => return Err("give low and high, or by_speed, not parts of both".into()),
        };
        if self.unit != self.panel.unit() {
            return Err(format!(
                "unit `{}`: the panel's values are in {}",
                self.unit,
                self.panel.unit()
            ));
        }
        let in_cycle = |p: f64| (0.0..=100.0).contains(&p);
        if self
            .windows
            .iter()
            .any(|w| !(in_cycle(w[0]) && in_cycle(w[1]) && w[0] < w[1]))
        {
            return Err("windows must lie in [0, 100] % with start < end".into());
        }
        // the lowest low: a fixed low, or a by-speed low at a listed speed (linear between them)
        let lowest = match &range {
            NormRange::Fixed { low, .. } => *low,
            NormRange::BySpeed(b) => b
                .speed
                .iter()
                .filter_map(|&v| b.range(v))
                .map(|r| r.0)
                .fold(f64::INFINITY, f64::min),
        };
        match (self.measure, self.at) {
            (Measure::At, Some(p)) if in_cycle(p) => {}
            (Measure::At, _) => return Err("measure \"at\" needs `at` in [0, 100] %".into()),
            (_, Some(_)) => return Err("`at` is only for measure \"at\"".into()),
            (Measure::Max | Measure::Min, None) if self.windows.is_empty() => {
                return Err("max / min need the windows to search".into());
            }
            (Measure::PeakToPeak, None) if lowest < 0.0 => {
                return Err("a peak-to-peak range cannot be negative".into());
            }
            _ => {}
        }
        Ok(Norm {
            panel: self.panel,
            name: self.name,
            label: self.label,
            measure: self.measure,
            at: self.at,
            range,
            unit: self.unit,
            windows: self.windows,
            window_source: self.window_source,
            source: self.source,
        })
    }
}

/// The norms a figure is checked against.
#[derive(Clone, Debug, PartialEq)]
pub struct NormTable {
    /// The norms, in the table's order.
    pub norms: Vec<Norm>,
}

impl NormTable {
    /// Parse and check a norm table: a fixed range (finite `low < high`) or a `by_speed` one
    /// ([`BySpeed`]: speeds increasing inside `span`, a mean and a positive SD at each), the
    /// panel's unit, windows inside [0, 100] with start < end, `at` in [0, 100] given exactly
    /// for `measure = "at"`, windows for max / min, no negative peak-to-peak range. Errors are
    /// [`InputError::Malformed`] naming `path` and the row.
    pub fn parse(text: &str, path: &Path) -> Result<NormTable, InputError> {
        let file: NormFile =
            toml::from_str(text).map_err(|e| InputError::malformed("norm table", path, e))?;
        let norms = file
            .norm
            .into_iter()
            .enumerate()
            .map(|(i, row)| {
                let name = row.name.clone();
                row.check().map_err(|reason| {
                    let reason = format!("norm {} ({name}): {reason}", i + 1);
                    InputError::malformed("norm table", path, reason)
                })
            })
            .collect::<Result<Vec<Norm>, InputError>>()?;
        Ok(NormTable { norms })
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
    /// The speed a speed-dependent range was evaluated at, on its table's scale (`None` for a
    /// fixed range).
    pub speed: Option<(f64, SpeedScale)>,
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

    /// One line for people: `knee peak swing flexion, right: 61.2° at 72 % (norm 55…65°): inside`;
    /// a speed-dependent norm's range to 0.1 with the speed it holds at, `(norm 55.9…65.7° at
    /// v/√(g l1) 0.48)` or `(norm 3.2…4.6 cm at 1.20 m/s)`.
    pub fn describe(&self) -> String {
        let unit = if self.unit == "deg" { "°" } else { " cm" };
        let side = match self.side {
            Some(s) => format!(", {}", if s == Side::Right { "right" } else { "left" }),
            None => String::new(),
        };
        let at = self
            .at_pct
            .map_or(String::new(), |p| format!(" at {p:.0} %"));
        let norm = match self.speed {
            Some((v, scale)) => format!(
                "{:.1}…{:.1}{unit} at {}",
                self.low,
                self.high,
                scale.describe(v)
            ),
            None => format!("{}…{}{unit}", self.low, self.high),
        };
        format!(
            "{}{side}: {:.1}{unit}{at} (norm {norm}): {}",
            self.name,
            self.value,
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

/// Measure every norm on every curve of its panel, each range taken at the walk's `speed`; a
/// speed-dependent norm whose span does not hold the speed is left out.
pub fn check(cycle: &GaitCycle, norms: &NormTable, speed: WalkSpeed) -> Vec<NormCheck> {
    let mut out = Vec::new();
    for n in &norms.norms {
        let Some((low, high)) = n.range.at(speed) else {
            continue;
        };
        let evaluated_at = n.range.by_speed().map(|b| (b.scale.of(speed), b.scale));
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
                low,
                high,
                speed: evaluated_at,
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
