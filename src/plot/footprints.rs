//! A scenario's footprints seen from above (`klaw scenario --footprints`, issue 15): every
//! footprint as a foot outline ([`crate::plot::floor`]) in its side's colour, numbered by its
//! index; the path of the pelvis centre over the floor; the gaze (the head's heading) as an
//! arrow from the pelvis path every 0.5 s (`GAZE_INTERVAL_S`). One scale on both axes, in
//! metres: x to the right and −z up (the top view of [`crate::plot::floor`]), the vertical axis
//! labelled in z, which grows downwards.
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

/// The gaze is drawn this often (s of scenario time).
pub const GAZE_INTERVAL_S: f64 = 0.5;
/// The figure's width (px).
pub const WIDTH_PX: u32 = 1400;
/// The figure's height range (px): as much as the floor's extent needs at the width's scale.
pub const HEIGHT_RANGE_PX: (u32, u32) = (500, 1400);
/// Length of a gaze arrow (m).
const GAZE_ARROW_M: f64 = 0.3;
/// Room around the footprints and the path (m).
const PAD_M: f64 = 0.25;
const PATH_COLOR: RGBColor = RGBColor(110, 110, 110);
/// Labels closer than this (px) to one already placed move down a line.
const LABEL_CLEARANCE_PX: i32 = 15;

/// Write the footprint figure of `motion` (the scenario run by `body`) to `path`, PNG or SVG by
/// its extension (see the module doc); `title` names the scenario. Returns the chart's map from
/// top-view coordinates to pixels. Errors: an extension other than .png or .svg
/// ([`crate::model::InputError::Malformed`]), a frame the skeleton cannot be built from
/// ([`crate::Error::Figure`]), drawing ([`crate::Error::Draw`]) or writing ([`crate::Error::Io`]).
pub fn write(path: &Path, motion: &Motion, body: &Body, title: &str) -> Result<ViewMap> {
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
) -> Result<ViewMap> {
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
    // the plotting area is the image less the margins, label areas and the title (about 180 px
    // high and 90 px wide)
    let pw = f64::from(WIDTH_PX - 90);
    let ph = pw * (v_hi - v_lo) / (u_hi - u_lo).max(1e-9);
    let h = (ph + 180.0).clamp(f64::from(HEIGHT_RANGE_PX.0), f64::from(HEIGHT_RANGE_PX.1));
    (WIDTH_PX, h as u32)
}

/// The pelvis's floor point and the gaze's heading at the first frame at or after every multiple
/// of [`GAZE_INTERVAL_S`].
fn gaze_samples(frames: &[Landmarks], body: &Body) -> Result<Vec<((f64, f64), f64)>> {
    let mut out = Vec::new();
    let mut next = f64::NEG_INFINITY;
    for lm in frames {
        if lm.time + 1e-9 >= next {
            let sk = Skeleton::new(lm, body)?;
            out.push((floor::pelvis_point(lm), floor::gaze_heading(&sk)));
            next = (lm.time / GAZE_INTERVAL_S + 1e-9).floor() * GAZE_INTERVAL_S + GAZE_INTERVAL_S;
        }
    }
    Ok(out)
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
    type Output = ViewMap;
    fn draw<DB: DrawingBackend>(
        &mut self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<ViewMap, DrawError> {
        root.fill(&WHITE).map_err(msg)?;
        let area = titled(root, &self.title, TITLE_SIZE, self.text)?;
        let (mut chart, fit) = floor_chart(&area, self.text, self.extent)?;
        let map = ViewMap::of_chart(&chart, &fit);
        let path: Vec<(f64, f64)> = self.motion.frames.iter().map(floor::pelvis_point).collect();
        let series = chart
            .draw_series(std::iter::once(PathElement::new(
                path,
                PATH_COLOR.stroke_width(2),
            )))
            .map_err(msg)?;
        if self.text {
            series.label("pelvis path").legend(|(x, y)| {
                PathElement::new([(x, y), (x + 20, y)], PATH_COLOR.stroke_width(2))
            });
        }
        floor::draw_footprints(&mut chart, &self.motion.footprints, self.body, 1.0)?;
        let series = chart
            .draw_series(self.gaze.iter().map(|&(at, d)| {
                PathElement::new(
                    floor::arrow(at, d, GAZE_ARROW_M),
                    floor::GAZE_COLOR.stroke_width(2),
                )
            }))
            .map_err(msg)?;
        if self.text {
            series
                .label(format!("gaze every {GAZE_INTERVAL_S} s"))
                .legend(|(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], floor::GAZE_COLOR.stroke_width(2))
                });
            legend(&mut chart)?;
            labels(root, &map, &self.motion.footprints, self.body)?;
        } else {
            frame_border(&chart)?;
        }
        Ok(map)
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

/// The feet's entries in the legend, and the legend.
fn legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
) -> std::result::Result<(), DrawError> {
    for (side, name) in [(Side::Left, "left foot"), (Side::Right, "right foot")] {
        let color = side_color(side);
        chart
            .draw_series(std::iter::once(PathElement::new(
                Vec::<(f64, f64)>::new(),
                color.stroke_width(2),
            )))
            .map_err(msg)?
            .label(name)
            .legend(move |(x, y)| {
                Rectangle::new([(x, y - 5), (x + 20, y + 5)], color.mix(0.5).filled())
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font((FONT, 15))
        .draw()
        .map_err(msg)
}

/// Every footprint's index, just beyond its toe; a label that would sit on one already placed
/// moves down until it is clear.
fn labels<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    map: &ViewMap,
    footprints: &[Footprint],
    body: &Body,
) -> std::result::Result<(), DrawError> {
    let ahead = body.ankle_to_metatarsal_horizontal() + body.l13 + 0.06;
    let style = (FONT, 14)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Center));
    let mut placed: Vec<(i32, i32)> = Vec::with_capacity(footprints.len());
    for f in footprints {
        let (u, v) = floor::top(f.ankle[0], f.ankle[1]);
        let (du, dv) = heading_vector(f.direction);
        let (x, mut y) = map.pixel(u + ahead * du, v + ahead * dv);
        while placed.iter().any(|&(px, py)| {
            (px - x).abs() < 2 * LABEL_CLEARANCE_PX && (py - y).abs() < LABEL_CLEARANCE_PX
        }) {
            y += LABEL_CLEARANCE_PX;
        }
        placed.push((x, y));
        root.draw(&Text::new(f.index.to_string(), (x, y), style.clone()))
            .map_err(msg)?;
    }
    Ok(())
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
    fn the_height_follows_the_extent() {
        // a long narrow floor gets the least height, a square one the most
        assert_eq!(figure_size(((0.0, 10.0), (0.0, 1.0))).1, HEIGHT_RANGE_PX.0);
        assert_eq!(figure_size(((0.0, 2.0), (0.0, 2.0))).1, HEIGHT_RANGE_PX.1);
        // between the two, the plotting area keeps the extent's proportions
        let (w, h) = figure_size(((0.0, 4.0), (0.0, 2.0)));
        assert_eq!(w, WIDTH_PX);
        assert_eq!(h, ((f64::from(WIDTH_PX - 90) / 2.0) + 180.0) as u32);
    }
}
