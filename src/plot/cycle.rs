//! Joint angle curves over the gait cycle (`klaw plot`, issue item 9): hip flexion, knee
//! flexion, ankle dorsiflexion, pelvic list, pelvic rotation and pelvis height against 0–100 %
//! of the gait cycle, averaged over the steady cycles, with the published normal ranges of
//! `models/gait-norms.toml` (the data of `gait-norms.md`) shaded over their cycle windows.
//!
//! Phase: the right leg's curves and the pelvis run from right heel strike (0 %) to the next
//! right heel strike (100 %); the left leg's curves from left heel strike to the next left heel
//! strike, so that both legs are read against the same norms ("gait cycle % starts at heel
//! strike of the same leg"): for a symmetric walk the two lie on top of each other. Right solid,
//! left dashed.
//!
//! PNG or SVG by the extension, 1500 × 1000 px, written whole or not at all; text needs the font
//! of [`crate::plot`] and is left out without one.
use std::path::Path;

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use serde::Deserialize;

use crate::engine::walker::Walk;
use crate::error::{Error, Result};
use crate::export::{CycleCurves, average_cycles, cycle_average};
use crate::figure::skeleton::{self, Clinical, Side};
use crate::model::body::Body;
use crate::plan::gait::Gait;
use crate::plot::{self, Drawn, FONT, FigureFormat, TITLE_SIZE, msg};

/// The bundled norm table (`models/gait-norms.toml`).
pub const NORMS_TABLE: &str = include_str!("../../models/gait-norms.toml");
/// Figure size in pixels (width, height).
pub const CYCLE_FIGURE_SIZE: (u32, u32) = (1500, 1000);
/// Frame rate at which the walk is sampled before the cycles are averaged (frames/s of walk
/// time): 200 frames/s puts ≥ 2 frames on every 1 % of a cycle slower than 0.5 s.
pub const CYCLE_FPS: f64 = 200.0;
/// The first `CYCLE_SKIP` cycles of each leg are left out: they start from the engine's initial
/// conditions.
pub const CYCLE_SKIP: usize = 1;
/// Fill of a norm band (value ranges over their windows).
pub const BAND_COLOR: RGBColor = RGBColor(196, 230, 188);
/// Fill of a peak-to-peak norm, anchored at the curve's minimum.
pub const EXCURSION_BAND_COLOR: RGBColor = RGBColor(253, 218, 168);
/// The right leg's curves (solid).
pub const RIGHT_COLOR: RGBColor = RGBColor(31, 119, 180);
/// The left leg's curves (dashed).
pub const LEFT_COLOR: RGBColor = RGBColor(214, 39, 40);
/// The pelvis' curves (solid, right cycle).
pub const PELVIS_COLOR: RGBColor = RGBColor(30, 30, 30);
/// The values are shown to 0.1 (° or cm) and compared with the norms at that resolution.
pub const CHECK_RESOLUTION: f64 = 0.1;
const LABEL_SIZE: i32 = 15;
const NOTE_SIZE: i32 = 14;
const LEGEND_H: u32 = 34;

/// A panel of the figure, and the curve it shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Panel {
    HipFlexion,
    KneeFlexion,
    AnkleDorsiflexion,
    PelvisList,
    PelvisRotation,
    PelvisHeight,
}

impl Panel {
    /// The panels in figure order (left to right, top to bottom).
    pub const ALL: [Panel; 6] = [
        Panel::HipFlexion,
        Panel::KneeFlexion,
        Panel::AnkleDorsiflexion,
        Panel::PelvisList,
        Panel::PelvisRotation,
        Panel::PelvisHeight,
    ];

    /// The panel's title.
    pub fn title(self) -> &'static str {
        match self {
            Panel::HipFlexion => "Hip flexion",
            Panel::KneeFlexion => "Knee flexion",
            Panel::AnkleDorsiflexion => "Ankle dorsiflexion",
            Panel::PelvisList => "Pelvic list (obliquity)",
            Panel::PelvisRotation => "Pelvic rotation (transverse)",
            Panel::PelvisHeight => "Pelvis height",
        }
    }

    /// The vertical axis label, with the unit and the sign convention.
    pub fn y_label(self) -> &'static str {
        match self {
            Panel::HipFlexion => "flexion + / extension − (°)",
            Panel::KneeFlexion => "flexion + (°)",
            Panel::AnkleDorsiflexion => "dorsiflexion + / plantarflexion − (°)",
            Panel::PelvisList => "right side up + (°)",
            Panel::PelvisRotation => "right side forward + (°)",
            Panel::PelvisHeight => "pelvis centre above the ground (cm)",
        }
    }

    /// The unit of the panel's values and norms: `deg` or `cm`.
    pub fn unit(self) -> &'static str {
        match self {
            Panel::PelvisHeight => "cm",
            _ => "deg",
        }
    }

    /// Whether the panel has a curve per leg (else one curve, of the pelvis).
    pub fn per_leg(self) -> bool {
        matches!(
            self,
            Panel::HipFlexion | Panel::KneeFlexion | Panel::AnkleDorsiflexion
        )
    }

    /// The column of [`crate::export::angle_columns`] the curve is read from (none for height).
    fn column(self, side: Side) -> Option<String> {
        let s = side.suffix();
        match self {
            Panel::HipFlexion => Some(format!("hip_flexion_{s}")),
            Panel::KneeFlexion => Some(format!("knee_flexion_{s}")),
            Panel::AnkleDorsiflexion => Some(format!("ankle_dorsiflexion_{s}")),
            Panel::PelvisList => Some("pelvis_list".into()),
            Panel::PelvisRotation => Some("pelvis_rotation".into()),
            Panel::PelvisHeight => None,
        }
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
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Norm {
    pub panel: Panel,
    pub name: String,
    /// Short name for the panel's note.
    pub label: String,
    pub measure: Measure,
    /// Cycle % for [`Measure::At`].
    #[serde(default)]
    pub at: Option<f64>,
    pub low: f64,
    pub high: f64,
    pub unit: String,
    /// Cycle-% intervals [start, end] where the band is shaded (and, for max / min, searched).
    pub windows: Vec<[f64; 2]>,
    pub window_source: String,
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
    pub norms: Vec<Norm>,
}

impl NormTable {
    /// Parse and check a norm table: finite `low < high`, the panel's unit, windows inside
    /// [0, 100] with start < end, `at` in [0, 100] given exactly for `measure = "at"`, windows
    /// for max / min. Errors are [`Error::Malformed`] naming `path` and the row.
    pub fn parse(text: &str, path: &Path) -> Result<NormTable> {
        let bad = |reason: String| Error::Malformed {
            what: "norm table",
            path: path.to_path_buf(),
            reason,
        };
        let file: NormFile = toml::from_str(text).map_err(|e| bad(e.to_string()))?;
        for (i, n) in file.norm.iter().enumerate() {
            let row = |reason: &str| bad(format!("norm {} ({}): {reason}", i + 1, n.name));
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

/// One curve of the figure: 101 samples, 0…100 % of its cycle, in its panel's unit.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    pub panel: Panel,
    /// The leg (its own cycle), or `None` for the pelvis (the right cycle).
    pub side: Option<Side>,
    pub values: Vec<f64>,
}

/// The averaged gait cycle of a walk: the curves of every panel.
#[derive(Clone, Debug, PartialEq)]
pub struct GaitCycle {
    pub curves: Vec<Curve>,
    /// How many cycles were averaged (right, left).
    pub cycles: (usize, usize),
    /// Toe-off of each leg in % of its own cycle (mean over the averaged cycles), if known.
    pub toe_off_pct: [Option<f64>; 2],
}

fn export_error(what: String) -> Error {
    Error::Export { what }
}

impl GaitCycle {
    /// Average clinical frames over the steady cycles of each leg (see
    /// [`crate::export::cycle_average`]): the right leg and the pelvis between right heel strikes,
    /// the left leg between left heel strikes, the first `skip` cycles of each left out. The
    /// pelvis height is the pelvis centre's y ([`Clinical::pelvis`], the landmarks' `pelvis[1]`)
    /// averaged the same way.
    pub fn from_clinical(
        frames: &[Clinical],
        right_heel_strikes: &[f64],
        left_heel_strikes: &[f64],
        skip: usize,
    ) -> Result<GaitCycle> {
        let right = cycle_average(frames, right_heel_strikes, skip)?;
        let left = cycle_average(frames, left_heel_strikes, skip)?;
        let times: Vec<f64> = frames.iter().map(|c| c.time).collect();
        let heights: Vec<Vec<f64>> = frames.iter().map(|c| vec![c.pelvis[1]]).collect();
        let height = average_cycles(&times, &heights, right_heel_strikes, skip)?;
        let column = |curves: &CycleCurves, name: &str| -> Result<Vec<f64>> {
            let k = curves
                .columns
                .iter()
                .position(|c| c == name)
                .ok_or_else(|| export_error(format!("no column {name} in the cycle curves")))?;
            Ok(curves.rows.iter().map(|r| r[k].to_degrees()).collect())
        };
        let mut curves = Vec::new();
        for panel in Panel::ALL {
            if panel == Panel::PelvisHeight {
                curves.push(Curve {
                    panel,
                    side: None,
                    values: height.iter().map(|r| 100.0 * r[0]).collect(),
                });
            } else if panel.per_leg() {
                for (side, avg) in [(Side::Right, &right), (Side::Left, &left)] {
                    let name = panel.column(side).expect("a leg panel has a column");
                    curves.push(Curve {
                        panel,
                        side: Some(side),
                        values: column(avg, &name)?,
                    });
                }
            } else {
                let name = panel
                    .column(Side::Right)
                    .expect("a pelvis angle has a column");
                curves.push(Curve {
                    panel,
                    side: None,
                    values: column(&right, &name)?,
                });
            }
        }
        Ok(GaitCycle {
            curves,
            cycles: (right.cycles, left.cycles),
            toe_off_pct: [None, None],
        })
    }

    /// The walk's averaged cycle: frames at [`CYCLE_FPS`], clinical angles, heel strikes at the
    /// starts of the steps (even steps right, odd steps left), [`CYCLE_SKIP`] cycles skipped;
    /// toe-off from the walk's gait events. Errors: a frame the skeleton cannot be built from, no
    /// complete steady cycle of a leg ([`Error::Export`]: walk more steps).
    pub fn from_walk(walk: &Walk) -> Result<GaitCycle> {
        let frames = crate::figure::frames(walk, CYCLE_FPS)
            .map(|lm| lm.and_then(|lm| skeleton::clinical(&lm, &walk.body)))
            .collect::<Result<Vec<Clinical>>>()?;
        let strikes = |parity: usize| -> Vec<f64> {
            walk.steps
                .iter()
                .enumerate()
                .filter(|(i, _)| i % 2 == parity)
                .map(|(_, s)| s.t_start)
                .collect()
        };
        let (right, left) = (strikes(0), strikes(1));
        let mut cycle = Self::from_clinical(&frames, &right, &left, CYCLE_SKIP)?;
        let last = frames.last().map_or(f64::NEG_INFINITY, |f| f.time);
        let events = crate::analysis::events::events(walk);
        for (k, (strikes, side)) in [(&right, "right"), (&left, "left")].into_iter().enumerate() {
            let pcts: Vec<f64> = strikes
                .windows(2)
                .skip(CYCLE_SKIP)
                .filter(|w| w[1] <= last)
                .filter_map(|w| {
                    events
                        .iter()
                        .find(|e| {
                            e.side == side && e.event == "TO" && e.time_s > w[0] && e.time_s < w[1]
                        })
                        .map(|e| 100.0 * (e.time_s - w[0]) / (w[1] - w[0]))
                })
                .collect();
            if !pcts.is_empty() {
                cycle.toe_off_pct[k] = Some(pcts.iter().sum::<f64>() / pcts.len() as f64);
            }
        }
        Ok(cycle)
    }

    /// The curves of one panel.
    pub fn panel_curves(&self, panel: Panel) -> impl Iterator<Item = &Curve> {
        self.curves.iter().filter(move |c| c.panel == panel)
    }
}

/// A norm's measure on one curve.
#[derive(Clone, Debug, PartialEq)]
pub struct NormCheck {
    pub panel: Panel,
    pub name: String,
    /// The curve's leg, `None` for the pelvis.
    pub side: Option<Side>,
    pub measure: Measure,
    /// The measured value, in the norm's unit.
    pub value: f64,
    /// Where in the cycle (%) it was measured (none for peak to peak).
    pub at_pct: Option<f64>,
    pub low: f64,
    pub high: f64,
    pub unit: String,
}

impl NormCheck {
    /// Whether the value lies in [low, high], compared as it is shown: to
    /// [`CHECK_RESOLUTION`] (a peak of 3.9999° against a norm of 4–5° is inside).
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
                Measure::PeakToPeak => match range(&c.values) {
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

/// Smallest and largest finite value.
fn range(values: &[f64]) -> Option<(f64, f64)> {
    values
        .iter()
        .filter(|v| v.is_finite())
        .fold(None, |acc, &v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// The title line of a walk's parameters: `v 1.40 m/s, sl 0.778 m, sf 108.0 steps/min, H 1.80 m,
/// M 80 kg, style normal`; a walk whose steps ask for different gaits shows the range of each.
pub fn parameters_title(gaits: &[Gait], body: &Body, style: &str) -> String {
    let span = |f: fn(&Gait) -> f64, decimals: usize| {
        let (lo, hi) = gaits
            .iter()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, v| {
                (a.0.min(v), a.1.max(v))
            });
        if !lo.is_finite() {
            "?".to_string()
        } else if hi - lo < 1e-9 {
            format!("{lo:.decimals$}")
        } else {
            format!("{lo:.decimals$}–{hi:.decimals$}")
        }
    };
    format!(
        "v {} m/s, sl {} m, sf {} steps/min, H {:.2} m, M {:.0} kg, style {style}",
        span(|g| g.velocity, 2),
        span(|g| g.step_length, 3),
        span(|g| g.step_frequency, 1),
        body.height,
        body.mass
    )
}

/// Where a panel's plotting area lies in the figure: the pixels of its corners (0 %, y_hi) (left,
/// top) and (100 %, y_lo) (right, bottom), and the value range [y_lo, y_hi] of its vertical
/// axis, in the panel's unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PanelPixels {
    pub panel: Panel,
    pub left_top: (i32, i32),
    pub right_bottom: (i32, i32),
    pub y_range: (f64, f64),
}

/// What a written figure shows: the norm checks and where each panel was drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleFigure {
    pub checks: Vec<NormCheck>,
    pub panels: Vec<PanelPixels>,
}

/// Draw the cycle figure to `path` (PNG or SVG by its extension). `subtitle` names the walk
/// (see [`parameters_title`]). Errors: a bad extension ([`Error::Malformed`], before anything
/// is drawn), drawing or writing ([`Error::Io`] with action "writing"; no file is left).
pub fn write_cycle_figure(
    cycle: &GaitCycle,
    norms: &NormTable,
    subtitle: &str,
    path: &Path,
) -> Result<CycleFigure> {
    let format = plot::figure_format(path)?;
    render(cycle, norms, subtitle, path, format, plot::text_available())
}

fn render(
    cycle: &GaitCycle,
    norms: &NormTable,
    subtitle: &str,
    path: &Path,
    format: FigureFormat,
    text: bool,
) -> Result<CycleFigure> {
    let fail = |reason: String| Error::Io {
        action: "writing",
        path: path.to_path_buf(),
        source: std::io::Error::other(format!("drawing the gait-cycle figure: {reason}")),
    };
    let checks = check(cycle, norms);
    let (w, h) = CYCLE_FIGURE_SIZE;
    let panels = match format {
        FigureFormat::Png => {
            let mut pixels = vec![0u8; w as usize * h as usize * 3];
            let panels = {
                let root =
                    BitMapBackend::with_buffer(&mut pixels, CYCLE_FIGURE_SIZE).into_drawing_area();
                let panels = draw(&root, cycle, norms, &checks, subtitle, text).map_err(fail)?;
                root.present().map_err(|e| fail(e.to_string()))?;
                panels
            };
            plot::write_png_small(path, &pixels, CYCLE_FIGURE_SIZE)?;
            panels
        }
        FigureFormat::Svg => {
            let mut svg = String::new();
            let panels = {
                let root = SVGBackend::with_string(&mut svg, CYCLE_FIGURE_SIZE).into_drawing_area();
                let panels = draw(&root, cycle, norms, &checks, subtitle, text).map_err(fail)?;
                root.present().map_err(|e| fail(e.to_string()))?;
                panels
            };
            crate::export::file::write_atomic(path, |out| out.write_all(svg.as_bytes()))?;
            panels
        }
    };
    Ok(CycleFigure { checks, panels })
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    cycle: &GaitCycle,
    norms: &NormTable,
    checks: &[NormCheck],
    subtitle: &str,
    text: bool,
) -> std::result::Result<Vec<PanelPixels>, String> {
    root.fill(&WHITE).map_err(msg)?;
    let body = if text {
        let (r, l) = cycle.cycles;
        let title = format!("Gait cycle, mean of {r} right / {l} left steady cycles: {subtitle}",);
        root.titled(&title, (FONT, TITLE_SIZE)).map_err(msg)?
    } else {
        root.clone()
    };
    let (legend, grid) = body.split_vertically(LEGEND_H);
    if text {
        draw_legend(&legend)?;
    }
    let mut out = Vec::new();
    for (area, panel) in grid.split_evenly((2, 3)).iter().zip(Panel::ALL) {
        out.push(draw_panel(area, panel, cycle, norms, checks, text)?);
    }
    Ok(out)
}

/// One row of samples of the legend: line styles and fills, each followed by its text.
fn draw_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>) -> Drawn {
    let (_, h) = area.dim_in_pixel();
    let y = h as i32 / 2;
    let style = TextStyle::from((FONT, LABEL_SIZE)).pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Left,
        plotters::style::text_anchor::VPos::Center,
    ));
    let mut x = 20;
    let label = |x: &mut i32, s: &str| -> Drawn {
        area.draw(&Text::new(s.to_string(), (*x, y), style.clone()))
            .map_err(msg)?;
        let (tw, _) = area.estimate_text_size(s, &style).map_err(msg)?;
        *x += tw as i32 + 22;
        Ok(())
    };
    area.draw(&PathElement::new(
        vec![(x, y), (x + 30, y)],
        RIGHT_COLOR.stroke_width(2),
    ))
    .map_err(msg)?;
    x += 36;
    label(&mut x, "right leg, from right heel strike")?;
    area.draw(&DashedPathElement::new(
        vec![(x, y), (x + 30, y)],
        7,
        4,
        LEFT_COLOR.stroke_width(2),
    ))
    .map_err(msg)?;
    x += 36;
    label(&mut x, "left leg, from left heel strike")?;
    area.draw(&PathElement::new(
        vec![(x, y), (x + 30, y)],
        PELVIS_COLOR.stroke_width(2),
    ))
    .map_err(msg)?;
    x += 36;
    label(&mut x, "pelvis (right cycle)")?;
    area.draw(&Rectangle::new(
        [(x, y - 8), (x + 30, y + 8)],
        BAND_COLOR.filled(),
    ))
    .map_err(msg)?;
    x += 36;
    label(&mut x, "normal range (gait-norms.md) over its window")?;
    area.draw(&Rectangle::new(
        [(x, y - 8), (x + 30, y + 8)],
        EXCURSION_BAND_COLOR.filled(),
    ))
    .map_err(msg)?;
    x += 36;
    label(&mut x, "excursion norm above the curve's minimum")?;
    area.draw(&DashedPathElement::new(
        vec![(x + 15, y - 10), (x + 15, y + 10)],
        3,
        3,
        RGBColor(90, 90, 90).stroke_width(1),
    ))
    .map_err(msg)?;
    x += 24;
    label(&mut x, "toe-off")
}

/// The band of a norm on a panel, in the panel's unit: (x0, x1, y0, y1, colour) per window.
fn bands(norm: &Norm, curves: &[&Curve]) -> Vec<(f64, f64, f64, f64, RGBColor)> {
    let (low, high, color) = match norm.measure {
        Measure::PeakToPeak => {
            // anchored at the lowest curve of the panel
            let lo = curves
                .iter()
                .filter_map(|c| range(&c.values))
                .map(|r| r.0)
                .fold(f64::INFINITY, f64::min);
            if !lo.is_finite() {
                return Vec::new();
            }
            (lo + norm.low, lo + norm.high, EXCURSION_BAND_COLOR)
        }
        _ => (norm.low, norm.high, BAND_COLOR),
    };
    norm.windows
        .iter()
        .map(|w| (w[0], w[1], low, high, color))
        .collect()
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: Panel,
    cycle: &GaitCycle,
    norms: &NormTable,
    checks: &[NormCheck],
    text: bool,
) -> std::result::Result<PanelPixels, String> {
    let area = if text {
        area.titled(panel.title(), (FONT, 19)).map_err(msg)?
    } else {
        area.clone()
    };
    let curves: Vec<&Curve> = cycle.panel_curves(panel).collect();
    let panel_norms: Vec<&Norm> = norms.norms.iter().filter(|n| n.panel == panel).collect();
    let all_bands: Vec<_> = panel_norms.iter().flat_map(|n| bands(n, &curves)).collect();
    let notes: Vec<String> = panel_norms
        .iter()
        .map(|n| {
            note(
                n,
                checks
                    .iter()
                    .filter(|c| c.panel == panel && c.name == n.name),
            )
        })
        .collect();
    // the vertical range holds the curves and the bands, with room above for the notes
    let ys = curves
        .iter()
        .flat_map(|c| c.values.iter().copied())
        .chain(all_bands.iter().flat_map(|b| [b.2, b.3]));
    let (lo, hi) = range(&ys.collect::<Vec<f64>>()).unwrap_or((0.0, 1.0));
    let span = (hi - lo).max(1.0);
    let y_lo = lo - 0.06 * span;
    let lines = if text { notes.len() as f64 } else { 0.0 };
    let y_hi = hi + span * (0.06 + 0.075 * lines);

    let mut b = ChartBuilder::on(&area);
    b.margin(10).margin_right(18);
    if text {
        b.x_label_area_size(42).y_label_area_size(58);
    }
    let mut chart = b.build_cartesian_2d(0.0..100.0, y_lo..y_hi).map_err(msg)?;
    let tick = |v: &f64| {
        let s = format!("{v:.1}");
        s.strip_suffix(".0").map_or(s.clone(), str::to_string)
    };
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(RGBColor(238, 238, 238))
        .bold_line_style(RGBColor(215, 215, 215))
        .x_label_formatter(&tick)
        .y_label_formatter(&tick);
    if text {
        mesh.x_desc("gait cycle (%)")
            .y_desc(panel.y_label())
            .label_style((FONT, LABEL_SIZE))
            .axis_desc_style((FONT, LABEL_SIZE + 1));
    }
    mesh.draw().map_err(msg)?;

    chart
        .draw_series(
            all_bands
                .iter()
                .map(|&(x0, x1, y0, y1, c)| Rectangle::new([(x0, y1), (x1, y0)], c.filled())),
        )
        .map_err(msg)?;
    if panel.per_leg() {
        for (k, color) in [RIGHT_COLOR, LEFT_COLOR].into_iter().enumerate() {
            if let Some(p) = cycle.toe_off_pct[k] {
                chart
                    .draw_series(std::iter::once(DashedPathElement::new(
                        vec![(p, y_lo), (p, hi + 0.03 * span)],
                        3,
                        3,
                        color.mix(0.6).stroke_width(1),
                    )))
                    .map_err(msg)?;
            }
        }
    }
    if lo < 0.0 && hi > 0.0 && panel != Panel::PelvisHeight {
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(0.0, 0.0), (100.0, 0.0)],
                RGBColor(150, 150, 150).stroke_width(1),
            )))
            .map_err(msg)?;
    }
    for c in &curves {
        let points: Vec<(f64, f64)> = c
            .values
            .iter()
            .enumerate()
            .map(|(p, &v)| (p as f64 * 100.0 / (c.values.len().max(2) - 1) as f64, v))
            .filter(|(_, v)| v.is_finite())
            .collect();
        match c.side {
            Some(Side::Left) => chart
                .draw_series(DashedLineSeries::new(
                    points,
                    9,
                    5,
                    LEFT_COLOR.stroke_width(2),
                ))
                .map(|_| ()),
            Some(Side::Right) => chart
                .draw_series(LineSeries::new(points, RIGHT_COLOR.stroke_width(2)))
                .map(|_| ()),
            None => chart
                .draw_series(LineSeries::new(points, PELVIS_COLOR.stroke_width(2)))
                .map(|_| ()),
        }
        .map_err(msg)?;
    }
    if text {
        // the notes in the headroom, top left, a line each
        chart
            .draw_series(notes.iter().enumerate().map(|(i, line)| {
                let color = if line.ends_with("OUTSIDE") {
                    RGBColor(180, 20, 20)
                } else {
                    RGBColor(20, 20, 20)
                };
                EmptyElement::at((0.0, y_hi))
                    + Text::new(
                        line.clone(),
                        (6, 5 + i as i32 * (NOTE_SIZE + 5)),
                        (FONT, NOTE_SIZE).into_font().color(&color),
                    )
            }))
            .map_err(msg)?;
    }
    Ok(PanelPixels {
        panel,
        left_top: chart.backend_coord(&(0.0, y_hi)),
        right_bottom: chart.backend_coord(&(100.0, y_lo)),
        y_range: (y_lo, y_hi),
    })
}

/// A panel's note on one norm: `swing peak 55…65°: R 61.2 L 61.0 inside`.
fn note<'a>(norm: &Norm, checks: impl Iterator<Item = &'a NormCheck>) -> String {
    let unit = if norm.unit == "deg" { "°" } else { " cm" };
    let mut values = Vec::new();
    let mut all_inside = true;
    for c in checks {
        let side = match c.side {
            Some(Side::Right) => "R ",
            Some(Side::Left) => "L ",
            None => "",
        };
        let at = c.at_pct.filter(|_| c.measure != Measure::At);
        let at = at.map_or(String::new(), |p| format!(" @{p:.0}%"));
        values.push(format!("{side}{:.1}{at}", c.value));
        all_inside &= c.inside();
    }
    // both legs alike: one value
    let shown = match values.as_slice() {
        [r, l] if r.strip_prefix("R ") == l.strip_prefix("L ") => {
            format!("R = L {}", r.trim_start_matches("R "))
        }
        _ => values.join(", "),
    };
    format!(
        "{} {}…{}{unit}: {shown} {}",
        norm.label,
        norm.low,
        norm.high,
        if values.is_empty() {
            "not measured"
        } else if all_inside {
            "inside"
        } else {
            "OUTSIDE"
        }
    )
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
            assert!(matches!(e, Error::Malformed { .. }), "{b}: {e}");
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
