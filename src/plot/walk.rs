//! The figure of a walk (`klaw walk --plot`), drawn from its frames: a side view of stick-figure
//! legs over the ground (equal aspect ratio, metres), the hip height and the joint angles θ1..θ4
//! (KLAW 1989 §4.2, spec §4) against time.
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::analysis::extent;
use crate::engine::report::StateFrame;
use crate::error::Result;
use crate::plot::{
    self, Chart, Draw, DrawError, Drawn, FONT, FigureFormat, LEFT_COLOR, Png, RIGHT_COLOR,
    TITLE_SIZE, builder, frame_border, msg, padded, titled,
};

/// Figure size in pixels (width, height).
pub const FIGURE_SIZE: (u32, u32) = (1600, 1000);
/// Stick figures are drawn this often (s of walk time).
pub(crate) const FIGURE_INTERVAL_S: f64 = 0.1;
/// The figure shows at most this many steps, the walk's first: a longer walk would shrink the
/// stick figures to nothing and fill the time plots solid, and the frames it holds stay
/// bounded however long the walk.
pub const FIGURE_STEPS: usize = 12;

const HIP_PATH: RGBColor = RGBColor(150, 150, 150);
const STEP_LINE: RGBColor = RGBColor(215, 215, 215);
const THETA_COLORS: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
];
const THETA_LABELS: [&str; 4] = [
    "θ1 stance leg (from vertical)",
    "θ2 upper body (from vertical)",
    "θ3 swing thigh (from vertical)",
    "θ4 swing knee flexion",
];

/// Write the figure of a walk of `steps` steps to `path` (PNG or SVG by its extension, 1600 ×
/// 1000 px) from its `frames`: the side view on top, hip height (bottom left) and θ1..θ4
/// (bottom right) against time, over the first [`FIGURE_STEPS`] steps of the frames (the title
/// says so when the walk has more). The file is written whole or not at all; rendering and
/// writing failures are `Error::Io { action: "writing" }`.
pub fn walk_figure(frames: &[StateFrame], steps: usize, path: &Path) -> Result<()> {
    let format = plot::figure_format(path)?;
    render_figure(frames, steps, path, format, plot::text_available())
}

/// `walk_figure` with the text switched on or off (off needs no font).
fn render_figure(
    frames: &[StateFrame],
    steps: usize,
    path: &Path,
    format: FigureFormat,
    text: bool,
) -> Result<()> {
    let mut figure = WalkFigure {
        frames: shown_frames(frames),
        steps,
        text,
    };
    plot::write_figure(
        &mut figure,
        path,
        format,
        FIGURE_SIZE,
        Png::Default,
        "the figure",
    )
}

struct WalkFigure<'a> {
    frames: &'a [StateFrame],
    /// The walk's steps, shown or not.
    steps: usize,
    text: bool,
}

impl Draw for WalkFigure<'_> {
    type Output = ();
    fn draw<DB: DrawingBackend>(&mut self, root: &DrawingArea<DB, Shift>) -> Drawn {
        draw(root, self.frames, self.steps, self.text)
    }
}

/// A named, coloured curve in pieces (each piece a polyline of finite points).
type Series<'a> = (&'a str, RGBColor, Vec<Vec<(f64, f64)>>);

fn finite(points: impl IntoIterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    points
        .into_iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect()
}

fn side_color(side: &str) -> RGBColor {
    if side == "left" {
        LEFT_COLOR
    } else {
        RIGHT_COLOR
    }
}

fn other_side_color(side: &str) -> RGBColor {
    if side == "left" {
        RIGHT_COLOR
    } else {
        LEFT_COLOR
    }
}

/// The frames at which stick figures are drawn: the first at or after each multiple of the
/// interval, and the last frame.
fn figure_frames(frames: &[StateFrame]) -> Vec<&StateFrame> {
    let mut picked: Vec<&StateFrame> = Vec::new();
    let mut next = f64::NEG_INFINITY;
    for f in frames {
        if f.time_s >= next - 1e-9 {
            picked.push(f);
            next = ((f.time_s + 1e-9) / FIGURE_INTERVAL_S).floor() * FIGURE_INTERVAL_S
                + FIGURE_INTERVAL_S;
        }
    }
    if let (Some(last), Some(p)) = (frames.last(), picked.last())
        && !std::ptr::eq(last, *p)
    {
        picked.push(last);
    }
    picked
}

/// Times at which a new step starts (heel strikes).
fn step_starts(frames: &[StateFrame]) -> Vec<f64> {
    frames
        .windows(2)
        .filter(|w| w[1].step != w[0].step)
        .map(|w| w[1].time_s)
        .collect()
}

/// The frames the figure shows: those of their first [`FIGURE_STEPS`] steps.
fn shown_frames(frames: &[StateFrame]) -> &[StateFrame] {
    match frames.first() {
        Some(first) => {
            let n = frames.partition_point(|f| f.step < first.step + FIGURE_STEPS);
            &frames[..n.max(1)]
        }
        None => frames,
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frames: &[StateFrame],
    steps: usize,
    text: bool,
) -> Drawn {
    root.fill(&WHITE).map_err(msg)?;
    let (w, _) = root.dim_in_pixel();
    let title = side_title(frames, steps);
    let extent = side_extent(frames);
    let top_h = side_view_height(root, &title, extent, text)?;
    let (top, bottom) = root.split_vertically(top_h);
    let (left, right) = bottom.split_horizontally(w / 2);
    side_view(&top, frames, text, &title, extent)?;
    let starts = step_starts(frames);
    let hip = vec![finite(frames.iter().map(|f| (f.time_s, f.hip_y_m)))];
    time_plot(
        &left,
        "Hip height",
        "hip height (m)",
        &[("hip", RGBColor(0, 0, 0), hip)],
        2,
        &starts,
        text,
    )?;
    time_plot(
        &right,
        "Joint angles",
        "angle (°)",
        &angle_series(frames),
        0,
        &starts,
        text,
    )
}

/// The height of the side view: what its equal-aspect figures need (30–56 % of the figure), the
/// time plots take the rest. The space around the plotting area is measured on a trial split.
fn side_view_height<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    ((x_lo, x_hi), (y_lo, y_hi)): ((f64, f64), (f64, f64)),
    text: bool,
) -> std::result::Result<u32, DrawError> {
    let (_, h) = root.dim_in_pixel();
    let title_h = if text {
        let (_, th) = root
            .estimate_text_size(title, &TextStyle::from((FONT, TITLE_SIZE)))
            .map_err(msg)?;
        th + 2 * (th / 2).min(5)
    } else {
        0
    };
    let (max_top, min_top) = (h * 56 / 100, h * 30 / 100);
    let trial = root.split_vertically(max_top).0;
    let trial = trial.split_vertically(title_h.min(max_top)).1;
    let (pw, ph) = builder(&trial, text)
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)
        .map_err(msg)?
        .plotting_area()
        .dim_in_pixel();
    let needed = f64::from(pw) * (y_hi - y_lo) / (x_hi - x_lo);
    Ok((needed.ceil() as u32 + (max_top - ph.min(max_top))).clamp(min_top, max_top))
}

/// θ1..θ4 against time. The angles jump at a heel strike, where the legs exchange roles: one
/// curve per step.
fn angle_series(frames: &[StateFrame]) -> Vec<Series<'static>> {
    (0..4)
        .map(|k| {
            let pieces = frames
                .chunk_by(|a, b| a.step == b.step)
                .map(|step| {
                    finite(step.iter().map(|f| {
                        let a = [f.theta1_deg, f.theta2_deg, f.theta3_deg, f.theta4_deg];
                        (f.time_s, a[k])
                    }))
                })
                .collect();
            (THETA_LABELS[k], THETA_COLORS[k], pieces)
        })
        .collect()
}

fn side_title(frames: &[StateFrame], steps: usize) -> String {
    match (frames.first(), frames.last()) {
        (Some(a), Some(b)) => {
            let shown = b.step + 1 - a.step.min(b.step);
            let what = if shown < steps {
                format!("steps 1–{shown} of {steps} shown,")
            } else {
                format!("{shown} step{}", if shown == 1 { "" } else { "s" })
            };
            format!(
                "Side view: {what} in {:.2} s, hip advances {:.2} m. Legs every {} s \
                 (blue right, red left), grey hip path, dots at stance ankles",
                b.time_s - a.time_s,
                b.hip_x_m - a.hip_x_m,
                FIGURE_INTERVAL_S
            )
        }
        _ => "Side view (no frames)".to_string(),
    }
}

/// The side view's data ranges (m), padded, the ground always in view.
fn side_extent(frames: &[StateFrame]) -> ((f64, f64), (f64, f64)) {
    let xs = frames.iter().flat_map(|f| {
        [
            f.hip_x_m,
            f.stance_ankle_x_m,
            f.swing_knee_x_m,
            f.swing_ankle_x_m,
            f.swing_heel_x_m,
            f.swing_toe_x_m,
        ]
    });
    let ys = frames.iter().flat_map(|f| {
        [
            f.hip_y_m,
            f.stance_ankle_y_m,
            f.swing_knee_y_m,
            f.swing_ankle_y_m,
            f.swing_heel_y_m,
            f.swing_toe_y_m,
        ]
    });
    let (x_lo, x_hi) = padded(extent(xs).unwrap_or((0.0, 1.0)), 0.03, 0.5);
    let (y_lo, y_hi) = extent(ys).unwrap_or((0.0, 1.0));
    // the ground is always in view, with a margin under the lowest point
    let (y_lo, y_hi) = (y_lo.min(0.0) - 0.08, y_hi.max(0.5) + 0.08);
    ((x_lo, x_hi), (y_lo, y_hi))
}

fn side_view<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    frames: &[StateFrame],
    text: bool,
    title: &str,
    extent: ((f64, f64), (f64, f64)),
) -> Drawn {
    let area = titled(area, title, TITLE_SIZE, text)?;
    let (mut chart, (x_lo, x_hi)) = equal_aspect_chart(&area, text, extent)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(x_lo, 0.0), (x_hi, 0.0)],
            BLACK.stroke_width(2),
        )))
        .map_err(msg)?;
    let hip_path = finite(frames.iter().map(|f| (f.hip_x_m, f.hip_y_m)));
    chart
        .draw_series(LineSeries::new(hip_path, HIP_PATH.stroke_width(1)))
        .map_err(msg)?;
    stance_ankles(&mut chart, frames)?;
    stick_figures(&mut chart, frames)?;
    if !text {
        frame_border(&chart)?;
    }
    Ok(())
}

/// The side view's chart and its mesh: one scale (px per m) on both axes, the smaller of the two
/// that fit; the horizontal range it shows.
fn equal_aspect_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    text: bool,
    ((x_lo, x_hi), (y_lo, y_hi)): ((f64, f64), (f64, f64)),
) -> std::result::Result<(Chart<'a, DB>, (f64, f64)), DrawError> {
    let mut b = builder(area, text);
    let (pw, ph) = {
        let probe = b.build_cartesian_2d(0.0..1.0, 0.0..1.0).map_err(msg)?;
        probe.plotting_area().dim_in_pixel()
    };
    let fit = plot::equal_scale((x_lo, x_hi), (y_lo, y_hi), (pw, ph));
    let x_range = fit.x.0..fit.x.1;
    // extra height goes above the figures: the ground stays near the bottom
    let y_range = y_lo..(y_lo + fit.y.1 - fit.y.0);
    let mut chart = b
        .build_cartesian_2d(x_range.clone(), y_range)
        .map_err(msg)?;
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(RGBColor(240, 240, 240));
    if text {
        mesh.x_desc("x, forward (m)")
            .y_desc("height (m)")
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17));
    }
    mesh.draw().map_err(msg)?;
    Ok((chart, (x_range.start, x_range.end)))
}

/// The stance ankles, one mark per step, coloured by side.
fn stance_ankles<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, frames: &[StateFrame]) -> Drawn {
    let mut ankles: Vec<(f64, f64, RGBColor)> = Vec::new();
    for f in frames {
        let p = (f.stance_ankle_x_m, f.stance_ankle_y_m);
        if ankles.last().is_none_or(|a| (a.0, a.1) != p) {
            ankles.push((p.0, p.1, side_color(f.stance_side)));
        }
    }
    chart
        .draw_series(
            ankles
                .iter()
                .filter(|a| a.0.is_finite() && a.1.is_finite())
                .map(|&(x, y, c)| Circle::new((x, y), 5, c.filled())),
        )
        .map_err(msg)?;
    Ok(())
}

/// The legs every [`FIGURE_INTERVAL_S`]: stance leg hip–ankle, swing leg hip–knee–ankle–heel–
/// toe–ankle, a dot at the hip.
fn stick_figures<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, frames: &[StateFrame]) -> Drawn {
    for f in figure_frames(frames) {
        let stance = finite([
            (f.hip_x_m, f.hip_y_m),
            (f.stance_ankle_x_m, f.stance_ankle_y_m),
        ]);
        let swing = finite([
            (f.hip_x_m, f.hip_y_m),
            (f.swing_knee_x_m, f.swing_knee_y_m),
            (f.swing_ankle_x_m, f.swing_ankle_y_m),
            (f.swing_heel_x_m, f.swing_heel_y_m),
            (f.swing_toe_x_m, f.swing_toe_y_m),
            (f.swing_ankle_x_m, f.swing_ankle_y_m),
        ]);
        let stance_style = side_color(f.stance_side).mix(0.7).stroke_width(2);
        let swing_style = other_side_color(f.stance_side).mix(0.7).stroke_width(2);
        chart
            .draw_series([
                PathElement::new(stance, stance_style),
                PathElement::new(swing, swing_style),
            ])
            .map_err(msg)?;
        if f.hip_x_m.is_finite() && f.hip_y_m.is_finite() {
            chart
                .draw_series(std::iter::once(Circle::new(
                    (f.hip_x_m, f.hip_y_m),
                    3,
                    BLACK.filled(),
                )))
                .map_err(msg)?;
        }
    }
    Ok(())
}

/// The time and value ranges of a time plot, with headroom for the legend (one row per series)
/// above the curves when there is one.
fn time_ranges(series: &[Series], legend: bool) -> ((f64, f64), (f64, f64)) {
    let points = || series.iter().flat_map(|s| s.2.iter().flatten());
    let t = padded(
        extent(points().map(|p| p.0)).unwrap_or((0.0, 1.0)),
        0.0,
        0.1,
    );
    let (y_lo, mut y_hi) = padded(
        extent(points().map(|p| p.1)).unwrap_or((0.0, 1.0)),
        0.08,
        0.02,
    );
    if legend {
        y_hi += (y_hi - y_lo) * 0.09 * series.len() as f64;
    }
    (t, (y_lo, y_hi))
}

/// The decimals that tell apart the ticks of an axis spanning `span` (about ten ticks), at least
/// `least`: a 4.5 cm range of hip heights in metres needs three.
fn tick_decimals(span: f64, least: usize) -> usize {
    let tick = span / 10.0;
    let needed = if tick > 0.0 {
        (-tick.log10().floor()).max(0.0) as usize
    } else {
        0
    };
    least.max(needed)
}

/// A panel of curves against time, light vertical lines at the heel strikes.
fn time_plot<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    y_desc: &str,
    series: &[Series],
    y_decimals: usize,
    step_starts: &[f64],
    text: bool,
) -> Drawn {
    let area = titled(area, title, TITLE_SIZE, text)?;
    let legend = text && series.len() > 1;
    let ((t_lo, t_hi), (y_lo, y_hi)) = time_ranges(series, legend);
    let mut chart = builder(&area, text)
        .build_cartesian_2d(t_lo..t_hi, y_lo..y_hi)
        .map_err(msg)?;
    let decimals = tick_decimals(y_hi - y_lo, y_decimals);
    let y_label = |v: &f64| format!("{v:.decimals$}");
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(RGBColor(240, 240, 240));
    if text {
        mesh.x_desc("time (s)")
            .y_desc(y_desc)
            .y_label_formatter(&y_label)
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17));
    }
    mesh.draw().map_err(msg)?;
    chart
        .draw_series(
            step_starts
                .iter()
                .filter(|t| t.is_finite())
                .map(|&t| PathElement::new(vec![(t, y_lo), (t, y_hi)], STEP_LINE.stroke_width(1))),
        )
        .map_err(msg)?;
    for (name, color, pieces) in series {
        let color = *color;
        let anno = chart
            .draw_series(
                pieces
                    .iter()
                    .map(|p| PathElement::new(p.clone(), color.stroke_width(2))),
            )
            .map_err(msg)?;
        if legend {
            anno.label(*name).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(3))
            });
        }
    }
    if legend {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font((FONT, 15))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(msg)?;
    }
    if !text {
        frame_border(&chart)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    /// Ticks about a tenth of the span apart, each label distinct: a 0.045 m span ticks every
    /// 0.005 m (three decimals), a 120° span every 10–20° (none), never fewer than asked.
    #[test]
    fn tick_labels_tell_the_ticks_apart() {
        assert_eq!(tick_decimals(0.045, 2), 3);
        assert_eq!(tick_decimals(120.0, 0), 0);
        assert_eq!(tick_decimals(120.0, 1), 1);
        assert_eq!(tick_decimals(0.5, 2), 2);
        for span in [0.0031, 0.045, 0.7, 13.0] {
            let d = tick_decimals(span, 0);
            let (a, b) = (1.0, 1.0 + span / 10.0);
            assert_ne!(format!("{a:.d$}"), format!("{b:.d$}"), "{span}");
        }
    }

    fn frame(t: f64, step: usize) -> StateFrame {
        StateFrame {
            time_s: t,
            step,
            stance_side: if step.is_multiple_of(2) {
                "right"
            } else {
                "left"
            },
            hip_x_m: t,
            hip_y_m: 0.95,
            stance_ankle_x_m: 0.7 * step as f64,
            stance_ankle_y_m: 0.08,
            swing_knee_x_m: t + 0.1,
            swing_knee_y_m: 0.5,
            swing_ankle_x_m: t,
            swing_ankle_y_m: 0.1,
            swing_heel_x_m: t - 0.05,
            swing_heel_y_m: 0.02,
            swing_toe_x_m: t + 0.15,
            swing_toe_y_m: 0.02,
            ..StateFrame::default()
        }
    }

    #[test]
    fn figure_frames_every_interval_and_the_last() {
        let frames: Vec<StateFrame> = (0..=100).map(|k| frame(k as f64 / 100.0, 0)).collect();
        let t: Vec<f64> = figure_frames(&frames).iter().map(|f| f.time_s).collect();
        assert_eq!(t.len(), 11, "{t:?}");
        for (k, t) in t.iter().enumerate() {
            assert!((t - k as f64 * 0.1).abs() < 1e-9, "{t}");
        }
        // frames sparser than the interval: every frame, once
        let sparse: Vec<StateFrame> = (0..=4).map(|k| frame(k as f64 * 0.25, 0)).collect();
        assert_eq!(figure_frames(&sparse).len(), 5);
        assert!(figure_frames(&[]).is_empty());
    }

    #[test]
    fn figure_title_tells_when_only_the_first_steps_are_shown() {
        let frames: Vec<StateFrame> = (0..=400).map(|k| frame(k as f64 / 20.0, k / 20)).collect();
        let shown = shown_frames(&frames);
        assert_eq!(shown.last().unwrap().step, FIGURE_STEPS - 1);
        let t = side_title(shown, 21);
        assert!(
            t.starts_with("Side view: steps 1–12 of 21 shown, in"),
            "{t}"
        );
        let t = side_title(&frames[..20], 1);
        assert!(t.starts_with("Side view: 1 step in"), "{t}");
    }

    /// Without a font the figure is still drawn: no text at all is laid out. (This test binary
    /// never registers a font: nothing here calls `text_available`.)
    #[test]
    fn figure_without_text_needs_no_font() {
        let dir = tempfile::tempdir().unwrap();
        let frames: Vec<StateFrame> = (0..=120).map(|k| frame(k as f64 / 100.0, k / 60)).collect();
        for (name, format) in [("w.png", FigureFormat::Png), ("w.svg", FigureFormat::Svg)] {
            let p = dir.path().join(name);
            render_figure(&frames, 2, &p, format, false).unwrap();
            assert!(std::fs::metadata(&p).unwrap().len() > 1000);
        }
        // with text but no font registered, plotters fails: a drawing error, and no file
        let p = dir.path().join("t.png");
        let e = render_figure(&frames, 2, &p, FigureFormat::Png, true).unwrap_err();
        assert!(matches!(e, Error::Draw { .. }), "{e}");
        assert!(!p.exists());
        // degenerate input: no frames, one frame
        render_figure(&[], 0, &dir.path().join("e.png"), FigureFormat::Png, false).unwrap();
        render_figure(
            &frames[..1],
            1,
            &dir.path().join("o.svg"),
            FigureFormat::Svg,
            false,
        )
        .unwrap();
    }
}
