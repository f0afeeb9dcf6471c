//! A scenario's footprints seen from above (`klaw scenario --footprints`, issue 15): every
//! footprint as a foot outline ([`crate::plot::floor`]) in its side's colour, numbered by its
//! index; the path of the pelvis centre over the floor; the gaze (the head's heading) as an
//! arrow from the pelvis path at the start, after every metre of the path (`GAZE_SPACING_M`,
//! about a stride) and wherever it has turned by 60° (`GAZE_TURN_DEG`) since the last arrow, so
//! that standing, stepping aside and turning on the spot pile no arrows up. One scale on both
//! axes, in metres: x to the right and −z up (the top view of [`crate::plot::floor`]), the
//! vertical axis labelled in z, which grows downwards.
//!
//! The numbers: a foot put down again where it stood (a pivot in a turn) gets one label with
//! all its indices ("12, 15, 17"). Each label goes beside its foot on the outward side (the
//! left foot's left, the right foot's right), or, where that place is taken, at the nearest
//! place around the foot that overlaps no other label, footprint or gaze arrow, with a thin
//! leader line to the foot when it had to move away.
//!
//! PNG or SVG by the file's extension, 1400 px wide and as high as the floor's extent needs
//! (500–1400 px), written whole or not at all.
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::Result;
use crate::figure::Landmarks;
use crate::figure::skeleton::{Side, Skeleton};
use crate::model::body::Body;
use crate::plot::floor::{self, heading_vector, side_color};
use crate::plot::{
    self, Chart, Draw, DrawError, EqualScale, FONT, FigureFormat, Png, TITLE_SIZE, ViewMap,
    builder, frame_border, msg, titled,
};
use crate::scenario::{Footprint, Motion};

/// A gaze arrow after this much of the pelvis's way from the last one (m; about a stride).
pub const GAZE_SPACING_M: f64 = 1.0;
/// A gaze arrow wherever the gaze has turned this far from the last one (°).
pub const GAZE_TURN_DEG: f64 = 60.0;
/// Footprints of one foot this close (m) are one place: one label.
pub const SAME_PLACE_M: f64 = 0.03;
/// The figure's width (px).
pub const WIDTH_PX: u32 = 1400;
/// The figure's height range (px): as much as the floor's extent needs at the width's scale.
pub const HEIGHT_RANGE_PX: (u32, u32) = (500, 1400);
/// Length of a gaze arrow (m).
const GAZE_ARROW_M: f64 = 0.3;
/// Room around the footprints and the path (m).
const PAD_M: f64 = 0.25;
const PATH_COLOR: RGBColor = RGBColor(110, 110, 110);
/// Room kept around a label (px).
const LABEL_PAD_PX: i32 = 2;
/// The label's search: the gap from the foot's edge to the first place tried, the step outwards
/// and the farthest (px).
const LABEL_GAP_PX: f64 = 6.0;
const LABEL_STEP_PX: f64 = 7.0;
const LABEL_REACH_PX: f64 = 160.0;
/// … or this far (m), whichever is farther.
const LABEL_REACH_M: f64 = 0.4;
/// A label farther than this from its first place gets a leader line (px).
const LEADER_PX: f64 = 12.0;
const LABEL_FONT: i32 = 14;
/// The legend's row (px).
const LEGEND_ROW_PX: u32 = 30;

/// A step number's label: the footprints it names, its text and where it was drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct StepLabel {
    /// The indices of the footprints at this place (one, or a foot put down again in place).
    pub indices: Vec<usize>,
    /// The text: the indices, comma-separated.
    pub text: String,
    /// The label's box (left, top, right, bottom) in the figure's pixels.
    pub bbox: (i32, i32, i32, i32),
    /// Whether a leader line joins it to its foot (it moved away from its first place).
    pub leader: bool,
}

/// What the footprint figure drew: the chart's map from top-view coordinates to pixels, the
/// step numbers, the gaze arrows (top-view point and heading, rad).
#[derive(Clone, Debug, PartialEq)]
pub struct FootprintLayout {
    /// The chart's map from top-view coordinates (m) to pixels.
    pub map: ViewMap,
    /// The step numbers' labels (empty without text).
    pub labels: Vec<StepLabel>,
    /// The gaze arrows: their top-view start on the pelvis path and heading (rad, + left).
    pub gaze: Vec<((f64, f64), f64)>,
}

/// Write the footprint figure of `motion` (the scenario run by `body`) to `path`, PNG or SVG by
/// its extension (see the module doc); `title` names the scenario. Returns the chart's map from
/// top-view coordinates to pixels, the labels and the gaze arrows drawn. Errors: an extension other than .png or .svg
/// ([`crate::model::InputError::Malformed`]), a frame the skeleton cannot be built from
/// ([`crate::Error::Figure`]), drawing ([`crate::Error::Draw`]) or writing ([`crate::Error::Io`]).
pub fn write(path: &Path, motion: &Motion, body: &Body, title: &str) -> Result<FootprintLayout> {
    let format = plot::figure_format(path)?;
    write_as(path, format, motion, body, title, plot::text_available())
}

/// [`write`] in `format`, with the text switched on or off (off needs no font).
pub(crate) fn write_as(
    path: &Path,
    format: FigureFormat,
    motion: &Motion,
    body: &Body,
    title: &str,
    text: bool,
) -> Result<FootprintLayout> {
    let gaze = gaze_samples(&motion.frames, body)?;
    let extent = floor::extent(&motion.footprints, &motion.frames, body, PAD_M);
    let size = figure_size(extent);
    let duration = motion.frames.last().map_or(0.0, |f| f.time);
    let mut figure = FootprintFigure {
        motion,
        body,
        title: format!(
            "{title}: top view, {} footprints in {duration:.1} s",
            motion.footprints.len()
        ),
        gaze,
        extent,
        text,
    };
    plot::write_figure(&mut figure, path, format, size, Png::Small, "the figure")
}

/// The figure's size: `WIDTH_PX` wide and the height that shows `extent` at the width's scale,
/// within `HEIGHT_RANGE_PX`.
fn figure_size(((u_lo, u_hi), (v_lo, v_hi)): ((f64, f64), (f64, f64))) -> (u32, u32) {
    // the plotting area is the image less the margins, label areas, the title and the legend's
    // row (about 210 px high and 90 px wide)
    let pw = f64::from(WIDTH_PX - 90);
    let ph = pw * (v_hi - v_lo) / (u_hi - u_lo).max(1e-9);
    let h = (ph + 210.0).clamp(f64::from(HEIGHT_RANGE_PX.0), f64::from(HEIGHT_RANGE_PX.1));
    (WIDTH_PX, h as u32)
}

/// The pelvis's floor point and the gaze's heading at every frame.
fn gaze_samples(frames: &[Landmarks], body: &Body) -> Result<Vec<((f64, f64), f64)>> {
    let all = frames
        .iter()
        .map(|lm| {
            let sk = Skeleton::new(lm, body)?;
            Ok((floor::pelvis_point(lm), floor::gaze_heading(&sk)))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(gaze_arrows(&all))
}

/// The samples (top-view point, heading) that get an arrow: the first, then each that lies
/// [`GAZE_SPACING_M`] from the last arrow's point or has turned [`GAZE_TURN_DEG`] from its
/// heading.
pub(crate) fn gaze_arrows(samples: &[((f64, f64), f64)]) -> Vec<((f64, f64), f64)> {
    let mut out: Vec<((f64, f64), f64)> = Vec::new();
    for &(p, d) in samples {
        let due = match out.last() {
            None => true,
            Some(&(q, e)) => {
                let turned = (d - e).sin().atan2((d - e).cos()).abs().to_degrees();
                // (to rounding: a turn of exactly 60° counts)
                (p.0 - q.0).hypot(p.1 - q.1) >= GAZE_SPACING_M - 1e-9
                    || turned >= GAZE_TURN_DEG - 1e-9
            }
        };
        if due && p.0.is_finite() && p.1.is_finite() && d.is_finite() {
            out.push((p, d));
        }
    }
    out
}

struct FootprintFigure<'a> {
    motion: &'a Motion,
    body: &'a Body,
    title: String,
    gaze: Vec<((f64, f64), f64)>,
    extent: ((f64, f64), (f64, f64)),
    text: bool,
}

impl Draw for FootprintFigure<'_> {
    type Output = FootprintLayout;
    fn draw<DB: DrawingBackend>(
        &mut self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<FootprintLayout, DrawError> {
        root.fill(&WHITE).map_err(msg)?;
        let area = titled(root, &self.title, TITLE_SIZE, self.text)?;
        // the legend in a row of its own, over no footprint or label
        let area = if self.text {
            let (row, rest) = area.split_vertically(LEGEND_ROW_PX);
            legend(&row)?;
            rest
        } else {
            area
        };
        let (mut chart, fit) = floor_chart(&area, self.text, self.extent)?;
        let map = ViewMap::of_chart(&chart, &fit);
        let path: Vec<(f64, f64)> = self.motion.frames.iter().map(floor::pelvis_point).collect();
        chart
            .draw_series(std::iter::once(PathElement::new(
                path,
                PATH_COLOR.stroke_width(2),
            )))
            .map_err(msg)?;
        floor::draw_footprints(&mut chart, &self.motion.footprints, self.body, 1.0)?;
        chart
            .draw_series(self.gaze.iter().map(|&(at, d)| {
                PathElement::new(
                    floor::arrow(at, d, GAZE_ARROW_M),
                    floor::GAZE_COLOR.stroke_width(2),
                )
            }))
            .map_err(msg)?;
        let mut labels_drawn = Vec::new();
        if self.text {
            let (xr, yr) = chart.plotting_area().get_pixel_range();
            let within = (xr.start, yr.start, xr.end - 1, yr.end - 1);
            labels_drawn = labels(root, &map, within, self.motion, self.body, &self.gaze)?;
        } else {
            frame_border(&chart)?;
        }
        Ok(FootprintLayout {
            map,
            labels: labels_drawn,
            gaze: self.gaze.clone(),
        })
    }
}

/// The chart over `extent` (top-view u, v ranges) at one scale on both axes, with its mesh:
/// x across, z down (the v axis labelled −v).
fn floor_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    text: bool,
    (u, v): ((f64, f64), (f64, f64)),
) -> std::result::Result<(Chart<'a, DB>, EqualScale), DrawError> {
    let mut b = builder(area, text);
    let plot_px = {
        let probe = b.build_cartesian_2d(0.0..1.0, 0.0..1.0).map_err(msg)?;
        probe.plotting_area().dim_in_pixel()
    };
    let fit = plot::equal_scale(u, v, plot_px);
    let mut chart = b
        .build_cartesian_2d(fit.x.0..fit.x.1, fit.y.0..fit.y.1)
        .map_err(msg)?;
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(RGBColor(240, 240, 240));
    let z_label = |v: &f64| format!("{:.1}", -v + 0.0);
    if text {
        mesh.x_desc("x (m)")
            .y_desc("z (m), the start's left up")
            .y_label_formatter(&z_label)
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17));
    }
    mesh.draw().map_err(msg)?;
    Ok((chart, fit))
}

/// The legend's row, centred: the pelvis path, the gaze, the feet.
fn legend<DB: DrawingBackend>(row: &DrawingArea<DB, Shift>) -> std::result::Result<(), DrawError> {
    let style = TextStyle::from((FONT, 15)).pos(Pos::new(HPos::Left, VPos::Center));
    let gaze =
        format!("gaze: at the start, every {GAZE_SPACING_M} m, at every {GAZE_TURN_DEG}° of turn");
    let entries = [
        ("pelvis path", 0),
        (gaze.as_str(), 1),
        ("left foot", 2),
        ("right foot", 3),
        (
            "step number (a foot put down again in place: \"12, 15, 17\")",
            4,
        ),
    ];
    let (w, h) = row.dim_in_pixel();
    let y = h as i32 / 2;
    let widths = entries
        .iter()
        .map(|(t, _)| {
            let (tw, _) = row.estimate_text_size(t, &style).map_err(msg)?;
            Ok(30 + tw as i32)
        })
        .collect::<std::result::Result<Vec<i32>, DrawError>>()?;
    let gap = 28;
    let total: i32 = widths.iter().sum::<i32>() + gap * (widths.len() as i32 - 1);
    let mut x = ((w as i32 - total) / 2).max(8);
    for ((text, kind), width) in entries.iter().zip(widths) {
        match kind {
            0 => row.draw(&PathElement::new(
                vec![(x, y), (x + 22, y)],
                PATH_COLOR.stroke_width(2),
            )),
            1 => row.draw(&PathElement::new(
                vec![
                    (x, y),
                    (x + 22, y),
                    (x + 16, y - 4),
                    (x + 22, y),
                    (x + 16, y + 4),
                ],
                floor::GAZE_COLOR.stroke_width(2),
            )),
            2 | 3 => {
                let side = if *kind == 2 { Side::Left } else { Side::Right };
                let color = side_color(side);
                row.draw(&Rectangle::new(
                    [(x, y - 5), (x + 22, y + 5)],
                    color.mix(0.18).filled(),
                ))
                .and_then(|_| {
                    row.draw(&Rectangle::new(
                        [(x, y - 5), (x + 22, y + 5)],
                        color.stroke_width(2),
                    ))
                })
            }
            _ => row.draw(&Text::new(
                "7".to_string(),
                (x + 8, y),
                TextStyle::from((FONT, LABEL_FONT)).pos(Pos::new(HPos::Center, VPos::Center)),
            )),
        }
        .map_err(msg)?;
        row.draw(&Text::new(text.to_string(), (x + 30, y), style.clone()))
            .map_err(msg)?;
        x += width + gap;
    }
    Ok(())
}

/// A pixel box (left, top, right, bottom).
type PxBox = (i32, i32, i32, i32);

fn overlaps(a: PxBox, b: PxBox) -> bool {
    a.0 <= b.2 && b.0 <= a.2 && a.1 <= b.3 && b.1 <= a.3
}

/// The pixels along a gaze arrow (every 2 px of its strokes), each as a box of its own: an
/// arrow across a label's place is in the way, its bounding box is not.
fn arrow_points(map: &ViewMap, at: (f64, f64), direction: f64) -> Vec<PxBox> {
    let points: Vec<(i32, i32)> = floor::arrow(at, direction, GAZE_ARROW_M)
        .into_iter()
        .map(|(u, v)| map.pixel(u, v))
        .collect();
    points
        .windows(2)
        .flat_map(|w| {
            let ((x0, y0), (x1, y1)) = (w[0], w[1]);
            let n = ((x1 - x0).abs().max((y1 - y0).abs()) / 2).max(1);
            (0..=n).map(move |k| {
                let x = x0 + (x1 - x0) * k / n;
                let y = y0 + (y1 - y0) * k / n;
                (x - 1, y - 1, x + 1, y + 1)
            })
        })
        .collect()
}

/// The pixel box around top-view `points` on `map`.
fn pixel_box(map: &ViewMap, points: impl IntoIterator<Item = (f64, f64)>) -> PxBox {
    points.into_iter().fold(
        (i32::MAX, i32::MAX, i32::MIN, i32::MIN),
        |(l, t, r, b), (u, v)| {
            let (x, y) = map.pixel(u, v);
            (l.min(x), t.min(y), r.max(x), b.max(y))
        },
    )
}

/// The footprints grouped by place: a foot put down within [`SAME_PLACE_M`] of one of its
/// earlier prints joins that print's group; in the order of their first prints.
pub(crate) fn places(footprints: &[Footprint]) -> Vec<Vec<&Footprint>> {
    let mut groups: Vec<Vec<&Footprint>> = Vec::new();
    for f in footprints {
        let same = groups.iter_mut().find(|g| {
            let first = g[0];
            first.side == f.side
                && (first.ankle[0] - f.ankle[0]).hypot(first.ankle[1] - f.ankle[1]) <= SAME_PLACE_M
        });
        match same {
            Some(g) => g.push(f),
            None => groups.push(vec![f]),
        }
    }
    groups
}

/// Every place's step numbers (see the module doc), inside `within` (the plotting area's pixel
/// box): beside the foot on its outward side where that is free, else at the nearest free place
/// around it (rings every `LABEL_STEP_PX`, the outward directions first), with a leader line.
fn labels<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    map: &ViewMap,
    within: PxBox,
    motion: &Motion,
    body: &Body,
    gaze: &[((f64, f64), f64)],
) -> std::result::Result<Vec<StepLabel>, DrawError> {
    let style = (FONT, LABEL_FONT)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Center));
    let length = body.l8 + body.ankle_to_metatarsal_horizontal() + body.l13;
    let breadth = floor::FOOT_BREADTH_PER_LENGTH * length;
    // what a label must not cover: the footprints and the gaze arrows
    let marks: Vec<PxBox> = motion
        .footprints
        .iter()
        .map(|f| pixel_box(map, floor::foot_outline(body, f.side, f.ankle, f.direction)))
        .chain(gaze.iter().flat_map(|&(at, d)| arrow_points(map, at, d)))
        .collect();
    let mut placed: Vec<PxBox> = Vec::new();
    let mut out = Vec::new();
    for group in places(&motion.footprints) {
        let f = group[0];
        let indices: Vec<usize> = group.iter().map(|f| f.index).collect();
        let text = indices
            .iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(", ");
        let (w, h) = root.estimate_text_size(&text, &style).map_err(msg)?;
        let (hw, hh) = (w as i32 / 2 + LABEL_PAD_PX, h as i32 / 2 + LABEL_PAD_PX);
        // the foot's middle and its outward side (the left foot's left), in pixels
        let (a_u, a_v) = floor::top(f.ankle[0], f.ankle[1]);
        let (fu, fv) = heading_vector(f.direction);
        let mid = 0.5 * length - body.l8;
        let (cx, cy) = map.pixel(a_u + mid * fu, a_v + mid * fv);
        let out_sign = -f.side.sign();
        // in pixels y grows downwards: the top view's (u, v) turns into (u, −v)
        let outward = (-fv * out_sign, -fu * out_sign);
        let first = 0.5 * breadth * map.scale() + LABEL_GAP_PX;
        let fits = |x: i32, y: i32, obstacles: &[&[PxBox]]| {
            let b = (x - hw, y - hh, x + hw, y + hh);
            let inside = b.0 >= within.0 && b.1 >= within.1 && b.2 <= within.2 && b.3 <= within.3;
            inside
                && !obstacles
                    .iter()
                    .flat_map(|o| o.iter())
                    .any(|&t| overlaps(b, t))
        };
        // rings around the foot's middle, every LABEL_STEP_PX outwards; on each, sixteen
        // directions from the outward side (0, +1, −1, +2, −2, … sixteenths of a turn); the
        // centre past the foot's half breadth and the label's own half extent that way
        let search = |obstacles: &[&[PxBox]]| {
            let mut r = 0.0;
            while r <= LABEL_REACH_PX.max(LABEL_REACH_M * map.scale()) {
                for k in 0..16 {
                    let step = (k + 1) / 2;
                    let turn = if k % 2 == 1 { step } else { -step } as f64;
                    let a = turn * std::f64::consts::PI / 8.0;
                    let (c, s) = (a.cos(), a.sin());
                    let (dx, dy) = (outward.0 * c - outward.1 * s, outward.0 * s + outward.1 * c);
                    let half = (f64::from(hw) * dx.abs()).max(f64::from(hh) * dy.abs());
                    let d = first + half + r;
                    let (x, y) = (cx + (d * dx).round() as i32, cy + (d * dy).round() as i32);
                    if fits(x, y, obstacles) {
                        return Some((x, y, r > LEADER_PX || k > 2));
                    }
                }
                r += LABEL_STEP_PX;
            }
            None
        };
        // clear of everything; else clear of the other labels at least (over a foot); else the
        // first place
        let (x, y, leader) = search(&[&marks, &placed])
            .or_else(|| search(&[&placed]))
            .unwrap_or_else(|| {
                let half = f64::from(hw).max(f64::from(hh));
                let d = first + half;
                (
                    cx + (d * outward.0).round() as i32,
                    cy + (d * outward.1).round() as i32,
                    false,
                )
            });
        if leader {
            root.draw(&PathElement::new(
                vec![(cx, cy), (x, y)],
                RGBColor(120, 120, 120).stroke_width(1),
            ))
            .map_err(msg)?;
        }
        let bbox = (x - hw, y - hh, x + hw, y + hh);
        root.draw(&Rectangle::new(
            [(bbox.0 + 1, bbox.1 + 1), (bbox.2 - 1, bbox.3 - 1)],
            WHITE.mix(0.8).filled(),
        ))
        .map_err(msg)?;
        root.draw(&Text::new(text.clone(), (x, y), style.clone()))
            .map_err(msg)?;
        placed.push(bbox);
        out.push(StepLabel {
            indices,
            text,
            bbox,
            leader,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_chart_draws_a_metre_as_many_pixels_across_as_up() {
        // plotters' own placement of the chart's points, not the map read off it: a 1 m square
        // at the extent's corner is a square in pixels (to the pixel rounding)
        for (extent, size) in [
            (((0.0, 5.6), (-1.3, 0.5)), (1400, 600)),
            (((-1.0, 1.0), (-2.0, 2.0)), (700, 900)),
        ] {
            let mut pixels = vec![0u8; size.0 as usize * size.1 as usize * 3];
            let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
            let (chart, fit) = floor_chart(&root, false, extent).unwrap();
            let (u, v) = (extent.0.0, extent.1.0);
            let (x0, y0) = chart.backend_coord(&(u, v));
            let (x1, _) = chart.backend_coord(&(u + 1.0, v));
            let (_, y1) = chart.backend_coord(&(u, v + 1.0));
            let (across, up) = (x1 - x0, y0 - y1);
            assert!((across - up).abs() <= 1, "{across} px across, {up} px up");
            assert!((f64::from(across) - fit.scale).abs() <= 1.0);
        }
    }

    #[test]
    fn gaze_arrows_at_a_metre_or_a_turn() {
        let at = |u: f64, deg: f64| ((u, 0.0), deg.to_radians());
        // standing for 2 s (100 frames), one arrow
        let still: Vec<_> = (0..100).map(|_| at(0.0, 0.0)).collect();
        assert_eq!(gaze_arrows(&still).len(), 1);
        // turning on the spot through 180°: 0, 60, 120, 180
        let turn: Vec<_> = (0..=180).map(|k| at(0.0, f64::from(k))).collect();
        let arrows = gaze_arrows(&turn);
        let degrees: Vec<i64> = arrows
            .iter()
            .map(|a| a.1.to_degrees().round() as i64)
            .collect();
        assert_eq!(degrees, [0, 60, 120, 180]);
        // walking 3 m straight in 1 cm steps: 0, 1, 2, 3 m
        let walk: Vec<_> = (0..=300).map(|k| at(f64::from(k) / 100.0, 0.0)).collect();
        let us: Vec<f64> = gaze_arrows(&walk).iter().map(|a| a.0.0).collect();
        assert_eq!(us.len(), 4);
        for (u, want) in us.iter().zip([0.0, 1.0, 2.0, 3.0]) {
            assert!((u - want).abs() < 0.011, "{us:?}");
        }
    }

    #[test]
    fn the_height_follows_the_extent() {
        // a long narrow floor gets the least height, a square one the most
        assert_eq!(figure_size(((0.0, 10.0), (0.0, 1.0))).1, HEIGHT_RANGE_PX.0);
        assert_eq!(figure_size(((0.0, 2.0), (0.0, 2.0))).1, HEIGHT_RANGE_PX.1);
        // between the two, the plotting area keeps the extent's proportions
        let (w, h) = figure_size(((0.0, 4.0), (0.0, 2.0)));
        assert_eq!(w, WIDTH_PX);
        assert_eq!(h, ((f64::from(WIDTH_PX - 90) / 2.0) + 210.0) as u32);
    }
}
