//! The gait-cycle figure (`klaw plot`, issue items 9 and 16): the curves of a [`GaitCycle`] —
//! hip flexion, knee flexion, ankle dorsiflexion, pelvic list, pelvic rotation and pelvis height
//! against 0–100 % of the gait cycle, averaged over the steady cycles — with the published
//! normal ranges of [`crate::analysis::norms`] shaded over their cycle windows (the
//! speed-dependent ones at the walk's speed, light blue with a blue edge, under and over the
//! fixed ones) and each panel's norm checks noted above its curves. Each leg's curves start at its own heel strike (the phase of
//! [`crate::analysis::cycle`]); right solid, left dashed.
//!
//! A range norm (peak to peak: a range of motion, an excursion) says nothing about where the
//! curve lies, only how far it spans: it is drawn beside the panel, right of the plotting area,
//! not over the cycle. Per curve a bracket from the curve's minimum to its maximum, and next to
//! it per range norm a bar from min + low to min + high, with a dotted stem down to the minimum
//! they are measured from: the curve's range is normal when the bracket's top lies level with
//! the bar.
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
/// Fill of a fixed peak-to-peak norm's bar beside the panel, [min + low, min + high] of the
/// curve (a speed-dependent one is filled with [`SPEED_BAND_COLOR`] and edged).
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
/// The range marks beside a panel: the gap before each curve's bracket, the gap from it to the
/// bars, a bar's width and the gap after each bar (px).
const RANGE_GAP: i32 = 10;
const BRACKET_GAP: i32 = 5;
const BAR_W: i32 = 10;
const BAR_GAP: i32 = 4;
/// The panels' right margin without range marks (px).
const PANEL_MARGIN_RIGHT: i32 = 18;
/// The stems and the baseline of the range marks.
const RANGE_STEM_COLOR: RGBColor = RGBColor(90, 90, 90);

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

/// Where a range norm (peak to peak) was drawn beside its panel, for one curve: the bracket of
/// the curve's own range and the bar of the norm's, in the figure's pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct RangePixels {
    /// The panel.
    pub panel: Panel,
    /// The norm's name.
    pub name: String,
    /// The curve's leg (`None`: the pelvis).
    pub side: Option<Side>,
    /// The bracket: its column and its rows (top, bottom) at the curve's maximum and minimum.
    pub bracket: (i32, (i32, i32)),
    /// The bar: its columns (left, right) and rows (top, bottom) at min + high and min + low.
    pub bar: ((i32, i32), (i32, i32)),
    /// The curve's extent (min, max) and the norm's range (low, high) drawn, in the panel's unit.
    pub values: ((f64, f64), (f64, f64)),
}

/// What a written figure shows: the norm checks and where each panel was drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleFigure {
    /// Every norm's check on every curve of its panel.
    pub checks: Vec<NormCheck>,
    /// The panels, in [`Panel::ALL`]'s order.
    pub panels: Vec<PanelPixels>,
    /// The range norms drawn beside the panels, per curve.
    pub ranges: Vec<RangePixels>,
    /// The legend's texts' boxes (left, top, right, bottom) in the figure's pixels.
    pub legend: Vec<(i32, i32, i32, i32)>,
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
        legend: Vec::new(),
    };
    render(&mut figure, path, format)
}

fn render(figure: &mut CycleDrawing, path: &Path, format: FigureFormat) -> Result<CycleFigure> {
    let (panels, ranges) = plot::write_figure(
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
        ranges,
        legend: figure.legend.clone(),
    })
}

struct CycleDrawing<'a> {
    cycle: &'a GaitCycle,
    norms: &'a NormTable,
    speed: WalkSpeed,
    checks: Vec<NormCheck>,
    subtitle: &'a str,
    text: bool,
    /// The legend's text boxes, once drawn.
    legend: Vec<(i32, i32, i32, i32)>,
}

impl CycleDrawing<'_> {
    /// The legend's entries: the curves, the bands, the toe-off lines, the speed-dependent
    /// bands (when the table has any) and the range marks (when any is drawn).
    fn legend_entries(&self) -> Vec<(Sample, String)> {
        let mut out: Vec<(Sample, String)> = [
            (Sample::Right, "right leg, from right heel strike"),
            (Sample::Left, "left leg, from left heel strike"),
            (Sample::Pelvis, "pelvis (right cycle)"),
            (Sample::Band, "normal range (gait-norms.md) over its window"),
            (Sample::ToeOff, "toe-off"),
        ]
        .into_iter()
        .map(|(s, t)| (s, t.to_string()))
        .collect();
        if let Some(line) = self.speed_legend() {
            out.push((Sample::SpeedBand, line));
        }
        if self.norms.norms.iter().any(drawn_beside) {
            out.push((
                Sample::Range,
                "right of a panel: the curve's range, min to max (bracket), and its normal range \
                 above the curve's min (bar)"
                    .into(),
            ));
        }
        out
    }

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
    type Output = (Vec<PanelPixels>, Vec<RangePixels>);

    /// The title, the legend and the panels in a 2 × 3 grid.
    fn draw<DB: DrawingBackend>(
        &mut self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<Self::Output, DrawError> {
        root.fill(&WHITE).map_err(msg)?;
        let (r, l) = self.cycle.cycles;
        let title = format!(
            "Gait cycle, mean of {r} right / {l} left steady cycles: {}",
            self.subtitle
        );
        let body = titled(root, &title, TITLE_SIZE, self.text)?;
        let entries = self.legend_entries();
        let (w, _) = body.dim_in_pixel();
        let layout = if self.text {
            legend_layout(&body, &entries, w as i32)?
        } else {
            Vec::new()
        };
        let rows = layout.last().map_or(1, |l| l.0 + 1) as u32;
        let (legend, grid) = body.split_vertically(rows * LEGEND_ROW_H);
        self.legend = if self.text {
            draw_legend(&legend, &entries, &layout)?
        } else {
            Vec::new()
        };
        let (mut panels, mut ranges) = (Vec::new(), Vec::new());
        for (area, panel) in grid.split_evenly((2, 3)).iter().zip(Panel::ALL) {
            let (pixels, marks) = draw_panel(area, panel, self)?;
            panels.push(pixels);
            ranges.extend(marks);
        }
        Ok((panels, ranges))
    }
}

/// Whether a norm is a range drawn beside its panel: peak to peak, with windows (an empty list
/// is only checked).
fn drawn_beside(norm: &Norm) -> bool {
    norm.measure == Measure::PeakToPeak && !norm.windows.is_empty()
}

/// A legend entry's sample, drawn left of its text.
#[derive(Clone, Copy)]
enum Sample {
    Right,
    Left,
    Pelvis,
    Band,
    ToeOff,
    SpeedBand,
    /// A range mark: a bracket and a bar.
    Range,
}

impl Sample {
    /// The room the sample takes before its text (px).
    fn width(self) -> i32 {
        match self {
            Sample::ToeOff => 24,
            Sample::Range => 12 + BAR_W + 6,
            _ => 36,
        }
    }

    /// Draw the sample with its left end at `x`, centred on row `y`.
    fn draw<DB: DrawingBackend>(self, area: &DrawingArea<DB, Shift>, (x, y): (i32, i32)) -> Drawn {
        let line =
            |color: RGBColor| PathElement::new(vec![(x, y), (x + 30, y)], color.stroke_width(2));
        match self {
            Sample::Right => area.draw(&line(RIGHT_COLOR)),
            Sample::Pelvis => area.draw(&line(PELVIS_COLOR)),
            Sample::Left => area.draw(&DashedPathElement::new(
                vec![(x, y), (x + 30, y)],
                7,
                4,
                LEFT_COLOR.stroke_width(2),
            )),
            Sample::Band => area.draw(&Rectangle::new(
                [(x, y - 8), (x + 30, y + 8)],
                BAND_COLOR.filled(),
            )),
            Sample::SpeedBand => {
                let corners = [(x, y - 8), (x + 30, y + 8)];
                area.draw(&Rectangle::new(corners, SPEED_BAND_COLOR.filled()))
                    .and_then(|_| {
                        area.draw(&Rectangle::new(corners, SPEED_EDGE_COLOR.stroke_width(2)))
                    })
            }
            Sample::ToeOff => area.draw(&DashedPathElement::new(
                vec![(x + 15, y - 10), (x + 15, y + 10)],
                3,
                3,
                RGBColor(90, 90, 90).stroke_width(1),
            )),
            Sample::Range => area
                .draw(&PathElement::new(
                    vec![(x, y - 9), (x + 5, y - 9), (x + 5, y + 9), (x, y + 9)],
                    PELVIS_COLOR.stroke_width(2),
                ))
                .and_then(|_| {
                    area.draw(&Rectangle::new(
                        [(x + 12, y - 9), (x + 11 + BAR_W, y + 4)],
                        EXCURSION_BAND_COLOR.filled(),
                    ))
                })
                .and_then(|_| {
                    area.draw(&PathElement::new(
                        vec![(x + 5, y + 9), (x + 12 + BAR_W / 2, y + 9)],
                        RANGE_STEM_COLOR.stroke_width(1),
                    ))
                })
                .and_then(|_| {
                    area.draw(&DashedPathElement::new(
                        vec![(x + 12 + BAR_W / 2, y + 4), (x + 12 + BAR_W / 2, y + 9)],
                        2,
                        2,
                        RANGE_STEM_COLOR.stroke_width(1),
                    ))
                }),
        }
        .map_err(msg)
    }
}

/// The legend's left edge, the gap after an entry and the room kept at the right edge (px).
const LEGEND_LEFT: i32 = 20;
const LEGEND_GAP: i32 = 22;
const LEGEND_RIGHT: i32 = 10;

/// The legend's entries laid out in rows across `width` px: each entry's row and left end, and
/// its text's width.
fn legend_layout<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(Sample, String)],
    width: i32,
) -> std::result::Result<Vec<(usize, i32, i32)>, DrawError> {
    let style = legend_style();
    let (mut row, mut x) = (0, LEGEND_LEFT);
    let mut out = Vec::with_capacity(entries.len());
    for (sample, text) in entries {
        let (tw, _) = area.estimate_text_size(text, &style).map_err(msg)?;
        let need = sample.width() + tw as i32;
        if x > LEGEND_LEFT && x + need > width - LEGEND_RIGHT {
            row += 1;
            x = LEGEND_LEFT;
        }
        out.push((row, x, tw as i32));
        x += need + LEGEND_GAP;
    }
    Ok(out)
}

/// The legend: every entry's sample and text where `layout` puts it; the texts' boxes (left,
/// top, right, bottom) in the figure's pixels.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(Sample, String)],
    layout: &[(usize, i32, i32)],
) -> std::result::Result<Vec<(i32, i32, i32, i32)>, DrawError> {
    let style = legend_style();
    let (bx, by) = area.get_base_pixel();
    let mut boxes = Vec::with_capacity(entries.len());
    for ((sample, text), &(row, x, tw)) in entries.iter().zip(layout) {
        let y = row as i32 * LEGEND_ROW_H as i32 + LEGEND_ROW_H as i32 / 2;
        sample.draw(area, (x, y))?;
        let tx = x + sample.width();
        area.draw(&Text::new(text.clone(), (tx, y), style.clone()))
            .map_err(msg)?;
        let half = LABEL_SIZE / 2 + 2;
        boxes.push((bx + tx, by + y - half, bx + tx + tw, by + y + half));
    }
    Ok(boxes)
}

/// The legend's text style: left-aligned, vertically centred.
fn legend_style() -> TextStyle<'static> {
    TextStyle::from((FONT, LABEL_SIZE)).pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Left,
        plotters::style::text_anchor::VPos::Center,
    ))
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

/// The bands of a norm of values (not a range) whose range is [low, high] on a panel.
fn bands(norm: &Norm, (low, high): (f64, f64)) -> Vec<Band> {
    if norm.measure == Measure::PeakToPeak {
        return Vec::new();
    }
    let speed = norm.range.by_speed().is_some();
    let fill = if speed { SPEED_BAND_COLOR } else { BAND_COLOR };
    norm.windows
        .iter()
        .map(|w| Band {
            x0: w[0],
            x1: w[1],
            y0: low,
            y1: high,
            fill,
            speed,
        })
        .collect()
}

/// One range norm's bar beside a curve: [low, high] above the curve's minimum.
struct RangeBar {
    name: String,
    low: f64,
    high: f64,
    speed: bool,
}

/// A curve's range marks beside the panel: its extent and the bars of the range norms.
struct RangeGroup {
    side: Option<Side>,
    extent: (f64, f64),
    bars: Vec<RangeBar>,
}

impl RangeGroup {
    /// The marks' width (px): the gap, the bracket, the bars.
    fn width(&self) -> i32 {
        RANGE_GAP + 2 + BRACKET_GAP + self.bars.len() as i32 * (BAR_W + BAR_GAP)
    }

    /// The values the panel's axis must show: the curve's and the bars' ends.
    fn values(&self) -> impl Iterator<Item = f64> + '_ {
        let min = self.extent.0;
        [self.extent.0, self.extent.1].into_iter().chain(
            self.bars
                .iter()
                .flat_map(move |b| [min + b.low, min + b.high]),
        )
    }
}

/// Per curve of the panel, the range norms drawn beside it (`ranges`: each norm's [low, high]
/// here, `None` outside its speed span).
fn range_groups(
    norms: &[&Norm],
    ranges: &[Option<(f64, f64)>],
    curves: &[&PanelCurve],
) -> Vec<RangeGroup> {
    curves
        .iter()
        .filter_map(|c| {
            let extent = extent(c.values.iter().copied())?;
            let bars: Vec<RangeBar> = norms
                .iter()
                .zip(ranges)
                .filter(|(n, _)| drawn_beside(n))
                .filter_map(|(n, r)| {
                    r.map(|(low, high)| RangeBar {
                        name: n.name.clone(),
                        low,
                        high,
                        speed: n.range.by_speed().is_some(),
                    })
                })
                .collect();
            (!bars.is_empty()).then_some(RangeGroup {
                side: c.side,
                extent,
                bars,
            })
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
    fn new(
        curves: &[&PanelCurve],
        bands: &[Band],
        groups: &[RangeGroup],
        note_lines: usize,
    ) -> PanelRange {
        let ys = curves
            .iter()
            .flat_map(|c| c.values.iter().copied())
            .chain(bands.iter().flat_map(|b| [b.y0, b.y1]))
            .chain(groups.iter().flat_map(RangeGroup::values));
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

/// One panel: its norms' bands, the toe-off lines, the zero line, the curves, the range marks
/// beside it and the notes.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: Panel,
    figure: &CycleDrawing,
) -> std::result::Result<(PanelPixels, Vec<RangePixels>), DrawError> {
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
        .filter_map(|(n, r)| r.map(|r| bands(n, r)))
        .flatten()
        .collect();
    let groups = range_groups(&panel_norms, &ranges, &curves);
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
    let note_lines = if text { notes.len() } else { 0 };
    let range = PanelRange::new(&curves, &all_bands, &groups, note_lines);
    let beside: i32 = groups.iter().map(RangeGroup::width).sum();
    let mut chart = panel_chart(&area, panel, range, text, PANEL_MARGIN_RIGHT + beside)?;
    draw_marks(&mut chart, panel, figure.cycle, &all_bands, range)?;
    draw_curves(&mut chart, &curves)?;
    if text {
        draw_notes(&mut chart, &notes, range.y_hi)?;
    }
    let marks = draw_ranges(&area, &chart, panel, &groups)?;
    let pixels = PanelPixels {
        panel,
        left_top: chart.backend_coord(&(0.0, range.y_hi)),
        right_bottom: chart.backend_coord(&(100.0, range.y_lo)),
        y_range: (range.y_lo, range.y_hi),
    };
    Ok((pixels, marks))
}

/// The range marks right of the plotting area, per curve: a bracket from the curve's minimum to
/// its maximum in the curve's colour, then per range norm a bar from min + low to min + high
/// (light blue, edged, for a norm by speed), a dotted stem from each bar down to the minimum, a
/// line along the minimum from the bracket to the stems and a dotted one along the maximum
/// across the bars.
fn draw_ranges<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &Chart<'_, DB>,
    panel: Panel,
    groups: &[RangeGroup],
) -> std::result::Result<Vec<RangePixels>, DrawError> {
    // the chart's rows are the figure's; the area draws in its own pixels
    let (bx, by) = area.get_base_pixel();
    let row = |v: f64| chart.backend_coord(&(100.0, v)).1;
    let draw =
        |e: &dyn Fn((i32, i32)) -> (i32, i32), points: Vec<(i32, i32)>, style: ShapeStyle| {
            let points: Vec<(i32, i32)> = points.into_iter().map(e).collect();
            area.draw(&PathElement::new(points, style)).map_err(msg)
        };
    let local = |(x, y): (i32, i32)| (x - bx, y - by);
    let mut x = chart.backend_coord(&(100.0, 0.0)).0;
    let mut out = Vec::new();
    for g in groups {
        let color = match g.side {
            Some(Side::Right) => RIGHT_COLOR,
            Some(Side::Left) => LEFT_COLOR,
            None => PELVIS_COLOR,
        };
        x += RANGE_GAP;
        let bracket_x = x;
        let (top, bottom) = (row(g.extent.1), row(g.extent.0));
        let bracket = vec![
            (bracket_x - 4, top),
            (bracket_x, top),
            (bracket_x, bottom),
            (bracket_x - 4, bottom),
        ];
        draw(&local, bracket, color.stroke_width(2))?;
        x += 2 + BRACKET_GAP;
        let min = g.extent.0;
        for bar in &g.bars {
            let (l, r) = (x, x + BAR_W - 1);
            let (t, b) = (row(min + bar.high), row(min + bar.low));
            let fill = if bar.speed {
                SPEED_BAND_COLOR
            } else {
                EXCURSION_BAND_COLOR
            };
            area.draw(&Rectangle::new(
                [local((l, t)), local((r, b))],
                fill.filled(),
            ))
            .map_err(msg)?;
            if bar.speed {
                area.draw(&Rectangle::new(
                    [local((l, t)), local((r, b))],
                    SPEED_EDGE_COLOR.stroke_width(1),
                ))
                .map_err(msg)?;
            }
            let stem = (l + r) / 2;
            if b < bottom {
                area.draw(&DashedPathElement::new(
                    vec![local((stem, b)), local((stem, bottom))],
                    2,
                    2,
                    RANGE_STEM_COLOR.stroke_width(1),
                ))
                .map_err(msg)?;
            }
            out.push(RangePixels {
                panel,
                name: bar.name.clone(),
                side: g.side,
                bracket: (bracket_x, (top, bottom)),
                bar: ((l, r), (t, b)),
                values: (g.extent, (bar.low, bar.high)),
            });
            x = r + 1 + BAR_GAP;
        }
        let end = x - BAR_GAP - 1;
        draw(
            &local,
            vec![(bracket_x, bottom), (end, bottom)],
            RANGE_STEM_COLOR.stroke_width(1),
        )?;
        // the curve's maximum carried across the bars, to read against them
        area.draw(&DashedPathElement::new(
            vec![local((bracket_x + 2, top)), local((end, top))],
            2,
            2,
            RANGE_STEM_COLOR.stroke_width(1),
        ))
        .map_err(msg)?;
    }
    Ok(out)
}

/// A panel's chart, 0–100 % across, and its mesh.
fn panel_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    panel: Panel,
    range: PanelRange,
    text: bool,
    margin_right: i32,
) -> std::result::Result<Chart<'a, DB>, DrawError> {
    let mut b = ChartBuilder::on(area);
    b.margin(10).margin_right(margin_right);
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
