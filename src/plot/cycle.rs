//! The gait-cycle figure (`klaw plot`, issue items 9 and 16): the curves of a [`GaitCycle`] —
//! hip flexion, knee flexion, ankle dorsiflexion, pelvic list, pelvic rotation and pelvis height
//! against 0–100 % of the gait cycle, averaged over the steady cycles — with the published
//! normal ranges of [`crate::analysis::norms`] shaded over their cycle windows (the
//! speed-dependent ones at the walk's speed, light blue with a blue edge, under and over the
//! fixed ones) and each panel's norm checks noted above its curves. Each leg's curves start at its own heel strike (the phase of
//! [`crate::analysis::cycle`]); right solid, left dashed.
//!
//! PNG or SVG by the extension, 1500 × 1000 px, written whole or not at all; text needs the font
//! of [`crate::plot`] and is left out without one.
use std::path::Path;

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use crate::analysis::cycle::{GaitCycle, Panel, PanelCurve};
use crate::analysis::extent;
use crate::analysis::norms::{
    BySpeed, Measure, Norm, NormCheck, NormRange, NormTable, WalkSpeed, check,
};
use crate::error::Result;
use crate::figure::skeleton::Side;
use crate::plot::{
    self, Chart, Draw, DrawError, Drawn, FONT, FigureFormat, LEFT_COLOR, Png, RIGHT_COLOR,
    TITLE_SIZE, msg, titled,
};

/// Figure size in pixels (width, height).
pub const CYCLE_FIGURE_SIZE: (u32, u32) = (1500, 1000);
/// Fill of a norm band (value ranges over their windows).
pub const BAND_COLOR: RGBColor = RGBColor(196, 230, 188);
/// Fill of a peak-to-peak norm, anchored at the curve's minimum.
pub const EXCURSION_BAND_COLOR: RGBColor = RGBColor(253, 218, 168);
/// Fill of a speed-dependent norm at the walk's speed (drawn under the fixed bands).
pub const SPEED_BAND_COLOR: RGBColor = RGBColor(204, 224, 247);
/// Edge of a speed-dependent norm (drawn over the fixed bands).
pub const SPEED_EDGE_COLOR: RGBColor = RGBColor(40, 96, 196);
/// The pelvis' curves (solid, right cycle).
pub(crate) const PELVIS_COLOR: RGBColor = RGBColor(30, 30, 30);
const LABEL_SIZE: i32 = 15;
const NOTE_SIZE: i32 = 13;
const LEGEND_ROW_H: u32 = 30;

/// A panel's title.
fn title(panel: Panel) -> &'static str {
    match panel {
        Panel::HipFlexion => "Hip flexion",
        Panel::KneeFlexion => "Knee flexion",
        Panel::AnkleDorsiflexion => "Ankle dorsiflexion",
        Panel::PelvisList => "Pelvic list (obliquity)",
        Panel::PelvisRotation => "Pelvic rotation (transverse)",
        Panel::PelvisHeight => "Pelvis height",
    }
}

/// A panel's vertical axis label, with the unit and the sign convention.
fn y_label(panel: Panel) -> &'static str {
    match panel {
        Panel::HipFlexion => "flexion + / extension − (°)",
        Panel::KneeFlexion => "flexion + (°)",
        Panel::AnkleDorsiflexion => "dorsiflexion + / plantarflexion − (°)",
        Panel::PelvisList => "right side up + (°)",
        Panel::PelvisRotation => "right side forward + (°)",
        Panel::PelvisHeight => "pelvis centre above the ground (cm)",
    }
}

/// Where a panel's plotting area lies in the figure: the pixels of its corners (0 %, y_hi) (left,
/// top) and (100 %, y_lo) (right, bottom), and the value range [y_lo, y_hi] of its vertical
/// axis, in the panel's unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PanelPixels {
    /// The panel.
    pub panel: Panel,
    /// Pixel of the plotting area's left top corner (0 %, y_hi).
    pub left_top: (i32, i32),
    /// Pixel of the plotting area's right bottom corner (100 %, y_lo).
    pub right_bottom: (i32, i32),
    /// The vertical axis's range (y_lo, y_hi), in the panel's unit.
    pub y_range: (f64, f64),
}

/// What a written figure shows: the norm checks and where each panel was drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleFigure {
    /// Every norm's check on every curve of its panel.
    pub checks: Vec<NormCheck>,
    /// The panels, in [`Panel::ALL`]'s order.
    pub panels: Vec<PanelPixels>,
}

/// Draw the cycle figure to `path` (PNG or SVG by its extension), the speed-dependent norms
/// taken at the walk's `speed` ([`WalkSpeed::of_walk`]). `subtitle` names the walk (see
/// [`crate::plot::parameters_title`]). Errors: a bad extension
/// ([`crate::model::InputError::Malformed`], before anything is drawn), drawing
/// ([`crate::Error::Draw`]) or writing ([`crate::Error::Io`] with action "writing"; no file is
/// left).
pub fn write_cycle_figure(
    cycle: &GaitCycle,
    norms: &NormTable,
    speed: WalkSpeed,
    subtitle: &str,
    path: &Path,
) -> Result<CycleFigure> {
    let format = plot::figure_format(path)?;
    let mut figure = CycleDrawing {
        cycle,
        norms,
        speed,
        checks: check(cycle, norms, speed),
        subtitle,
        text: plot::text_available(),
    };
    render(&mut figure, path, format)
}

fn render(figure: &mut CycleDrawing, path: &Path, format: FigureFormat) -> Result<CycleFigure> {
    let panels = plot::write_figure(
        figure,
        path,
        format,
        CYCLE_FIGURE_SIZE,
        Png::Small,
        "the gait-cycle figure",
    )?;
    Ok(CycleFigure {
        checks: figure.checks.clone(),
        panels,
    })
}

struct CycleDrawing<'a> {
    cycle: &'a GaitCycle,
    norms: &'a NormTable,
    speed: WalkSpeed,
    checks: Vec<NormCheck>,
    subtitle: &'a str,
    text: bool,
}

impl CycleDrawing<'_> {
    /// The legend's line on the speed-dependent norms, if the table has any: the speed they are
    /// taken at and their sources (`cite`).
    fn speed_legend(&self) -> Option<String> {
        let norms = &self.norms.norms;
        let rows: Vec<&BySpeed> = norms.iter().filter_map(|n| n.range.by_speed()).collect();
        let first = rows.first()?;
        let mut cites: Vec<&str> = rows.iter().map(|b| b.cite.as_str()).collect();
        cites.dedup();
        let k = if rows.iter().all(|b| b.sd_multiple == first.sd_multiple) {
            first.sd_multiple.to_string()
        } else {
            "k".to_string()
        };
        Some(format!(
            "normal range at this walk's speed, v/√(g·l1) = {:.3} ({:.2} m/s): mean ± {k} SD of {}",
            self.speed.dimensionless(),
            self.speed.velocity,
            cites.join("; ")
        ))
    }
}

impl Draw for CycleDrawing<'_> {
    type Output = Vec<PanelPixels>;

    /// The title, the legend and the panels in a 2 × 3 grid.
    fn draw<DB: DrawingBackend>(
        &mut self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<Vec<PanelPixels>, DrawError> {
        root.fill(&WHITE).map_err(msg)?;
        let (r, l) = self.cycle.cycles;
        let title = format!(
            "Gait cycle, mean of {r} right / {l} left steady cycles: {}",
            self.subtitle
        );
        let body = titled(root, &title, TITLE_SIZE, self.text)?;
        let speed_line = self.speed_legend();
        let rows = if speed_line.is_some() { 2 } else { 1 };
        let (legend, grid) = body.split_vertically(rows * LEGEND_ROW_H);
        if self.text {
            let (first, second) = legend.split_vertically(LEGEND_ROW_H);
            draw_legend(&first)?;
            if let Some(line) = speed_line {
                draw_speed_legend(&second, &line)?;
            }
        }
        let mut out = Vec::new();
        for (area, panel) in grid.split_evenly((2, 3)).iter().zip(Panel::ALL) {
            out.push(draw_panel(area, panel, self)?);
        }
        Ok(out)
    }
}

/// One row of samples of the legend: line styles and fills, each followed by its text.
fn draw_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>) -> Drawn {
    let (_, h) = area.dim_in_pixel();
    let y = h as i32 / 2;
    let style = legend_style();
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

/// The legend's text style: left-aligned, vertically centred.
fn legend_style() -> TextStyle<'static> {
    TextStyle::from((FONT, LABEL_SIZE)).pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Left,
        plotters::style::text_anchor::VPos::Center,
    ))
}

/// The legend's second row: a speed band's sample and `line`.
fn draw_speed_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, line: &str) -> Drawn {
    let (_, h) = area.dim_in_pixel();
    let (x, y) = (20, h as i32 / 2);
    let sample = [(x, y - 8), (x + 30, y + 8)];
    area.draw(&Rectangle::new(sample, SPEED_BAND_COLOR.filled()))
        .map_err(msg)?;
    area.draw(&Rectangle::new(sample, SPEED_EDGE_COLOR.stroke_width(2)))
        .map_err(msg)?;
    area.draw(&Text::new(line.to_string(), (x + 36, y), legend_style()))
        .map_err(msg)
}

/// A norm's band over one window, in the panel's unit: cycle % [x0, x1], values [y0, y1].
#[derive(Clone, Copy)]
struct Band {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    fill: RGBColor,
    /// A speed-dependent norm's (filled under the fixed bands, edged over them).
    speed: bool,
}

/// The bands of a norm whose range is [low, high] on a panel.
fn bands(norm: &Norm, (low, high): (f64, f64), curves: &[&PanelCurve]) -> Vec<Band> {
    let base = match norm.measure {
        Measure::PeakToPeak => {
            // anchored at the lowest curve of the panel
            let lo = curves
                .iter()
                .filter_map(|c| extent(c.values.iter().copied()))
                .map(|r| r.0)
                .fold(f64::INFINITY, f64::min);
            if !lo.is_finite() {
                return Vec::new();
            }
            lo
        }
        _ => 0.0,
    };
    let speed = norm.range.by_speed().is_some();
    let fill = match (speed, norm.measure) {
        (true, _) => SPEED_BAND_COLOR,
        (false, Measure::PeakToPeak) => EXCURSION_BAND_COLOR,
        (false, _) => BAND_COLOR,
    };
    norm.windows
        .iter()
        .map(|w| Band {
            x0: w[0],
            x1: w[1],
            y0: base + low,
            y1: base + high,
            fill,
            speed,
        })
        .collect()
}

/// A panel's vertical extent: the curves' and bands' [lo, hi] and its span (≥ 1), and the axis
/// range [y_lo, y_hi] around them with room above for the notes.
#[derive(Clone, Copy)]
struct PanelRange {
    lo: f64,
    hi: f64,
    span: f64,
    y_lo: f64,
    y_hi: f64,
}

impl PanelRange {
    fn new(curves: &[&PanelCurve], bands: &[Band], note_lines: usize) -> PanelRange {
        let ys = curves
            .iter()
            .flat_map(|c| c.values.iter().copied())
            .chain(bands.iter().flat_map(|b| [b.y0, b.y1]));
        let (lo, hi) = extent(ys).unwrap_or((0.0, 1.0));
        let span = (hi - lo).max(1.0);
        PanelRange {
            lo,
            hi,
            span,
            y_lo: lo - 0.06 * span,
            y_hi: hi + span * (0.06 + 0.075 * note_lines as f64),
        }
    }
}

/// One panel: its norms' bands, the toe-off lines, the zero line, the curves and the notes.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: Panel,
    figure: &CycleDrawing,
) -> std::result::Result<PanelPixels, DrawError> {
    let text = figure.text;
    let area = titled(area, title(panel), 19, text)?;
    let curves: Vec<&PanelCurve> = figure.cycle.panel_curves(panel).collect();
    let panel_norms: Vec<&Norm> = figure
        .norms
        .norms
        .iter()
        .filter(|n| n.panel == panel)
        .collect();
    let ranges: Vec<Option<(f64, f64)>> = panel_norms
        .iter()
        .map(|n| n.range.at(figure.speed))
        .collect();
    let all_bands: Vec<Band> = panel_norms
        .iter()
        .zip(&ranges)
        .filter_map(|(n, r)| r.map(|r| bands(n, r, &curves)))
        .flatten()
        .collect();
    let notes: Vec<String> = panel_norms
        .iter()
        .zip(&ranges)
        .map(|(n, &r)| {
            let checks = figure
                .checks
                .iter()
                .filter(|c| c.panel == panel && c.name == n.name);
            note(n, r, checks)
        })
        .collect();
    let range = PanelRange::new(&curves, &all_bands, if text { notes.len() } else { 0 });
    let mut chart = panel_chart(&area, panel, range, text)?;
    draw_marks(&mut chart, panel, figure.cycle, &all_bands, range)?;
    draw_curves(&mut chart, &curves)?;
    if text {
        draw_notes(&mut chart, &notes, range.y_hi)?;
    }
    Ok(PanelPixels {
        panel,
        left_top: chart.backend_coord(&(0.0, range.y_hi)),
        right_bottom: chart.backend_coord(&(100.0, range.y_lo)),
        y_range: (range.y_lo, range.y_hi),
    })
}

/// A panel's chart, 0–100 % across, and its mesh.
fn panel_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    panel: Panel,
    range: PanelRange,
    text: bool,
) -> std::result::Result<Chart<'a, DB>, DrawError> {
    let mut b = ChartBuilder::on(area);
    b.margin(10).margin_right(18);
    if text {
        b.x_label_area_size(42).y_label_area_size(58);
    }
    let mut chart = b
        .build_cartesian_2d(0.0..100.0, range.y_lo..range.y_hi)
        .map_err(msg)?;
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
            .y_desc(y_label(panel))
            .label_style((FONT, LABEL_SIZE))
            .axis_desc_style((FONT, LABEL_SIZE + 1));
    }
    mesh.draw().map_err(msg)?;
    Ok(chart)
}

/// Under the curves: the norm bands, each leg's toe-off (leg panels), the zero line when the
/// range crosses it (angles).
fn draw_marks<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    panel: Panel,
    cycle: &GaitCycle,
    bands: &[Band],
    range: PanelRange,
) -> Drawn {
    // speed-dependent fills, then the fixed bands over them, then the speed bands' edges
    let corners = |b: &Band| [(b.x0, b.y1), (b.x1, b.y0)];
    for speed in [true, false] {
        chart
            .draw_series(
                bands
                    .iter()
                    .filter(|b| b.speed == speed)
                    .map(|b| Rectangle::new(corners(b), b.fill.filled())),
            )
            .map_err(msg)?;
    }
    chart
        .draw_series(
            bands
                .iter()
                .filter(|b| b.speed)
                .map(|b| Rectangle::new(corners(b), SPEED_EDGE_COLOR.stroke_width(2))),
        )
        .map_err(msg)?;
    if panel.per_leg() {
        for (k, color) in [RIGHT_COLOR, LEFT_COLOR].into_iter().enumerate() {
            if let Some(p) = cycle.toe_off_pct[k] {
                chart
                    .draw_series(std::iter::once(DashedPathElement::new(
                        vec![(p, range.y_lo), (p, range.hi + 0.03 * range.span)],
                        3,
                        3,
                        color.mix(0.6).stroke_width(1),
                    )))
                    .map_err(msg)?;
            }
        }
    }
    if range.lo < 0.0 && range.hi > 0.0 && panel != Panel::PelvisHeight {
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(0.0, 0.0), (100.0, 0.0)],
                RGBColor(150, 150, 150).stroke_width(1),
            )))
            .map_err(msg)?;
    }
    Ok(())
}

/// The curves: right solid, left dashed, the pelvis solid.
fn draw_curves<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, curves: &[&PanelCurve]) -> Drawn {
    for c in curves {
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
    Ok(())
}

/// The notes in the headroom, top left, a line each (red when a value is outside its norm).
fn draw_notes<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, notes: &[String], y_hi: f64) -> Drawn {
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
    Ok(())
}

/// A panel's note on one norm whose range here is `range` (`None`: a speed-dependent norm
/// outside its span): `swing peak 55…65°: R 61.2 L 61.0 inside`, a speed-dependent range to 0.1.
fn note<'a>(
    norm: &Norm,
    range: Option<(f64, f64)>,
    checks: impl Iterator<Item = &'a NormCheck>,
) -> String {
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
    let range = match (range, &norm.range) {
        (None, _) => return format!("{}: no norm at this speed", norm.label),
        (Some((low, high)), NormRange::BySpeed(_)) => {
            format!("{}…{}{unit}", tenths(low), tenths(high))
        }
        (Some((low, high)), NormRange::Fixed { .. }) => format!("{low}…{high}{unit}"),
    };
    format!(
        "{} {range}: {shown} {}",
        norm.label,
        if values.is_empty() {
            "not measured"
        } else if all_inside {
            "inside"
        } else {
            "OUTSIDE"
        }
    )
}

/// `x` to 0.1, without a minus sign on a value that shows as zero.
fn tenths(x: f64) -> String {
    let s = format!("{x:.1}");
    if s == "-0.0" { "0.0".to_string() } else { s }
}
