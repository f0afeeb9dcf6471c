//! A poulaine against its curve model (Pronost et al. §3.2, their Figure 3; `klaw poulaine fit
//! --plot`): both ankles relative to the pelvis centre. A symmetric walk's two ankles trace the
//! same sagittal loop, so the sagittal view (x forward to the right, y up) has a panel per ankle,
//! the right above the left at one scale; the frontal view seen from behind (z to the right, y
//! up), where the ankles lie apart, shows both. One scale on both axes of each panel; the
//! samples as dots, the model as a line, the four characteristic points marked and numbered (1
//! highest, 2 most forward, 3 under the pelvis, 4 most backward). The right ankle in blue, the
//! left in red; the legend in a row of its own under the title, over no curve.
//!
//! PNG or SVG by the file's extension, 1500 × 900 px, written whole or not at all.
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::Result;
use crate::plot::{
    self, Chart, Draw, DrawError, FONT, LEFT_COLOR, Png, RIGHT_COLOR, TITLE_SIZE, builder, msg,
    padded, titled,
};

/// The figure's size (px).
pub const SIZE_PX: (u32, u32) = (1500, 900);
/// The sagittal panels' share of the width.
const SAGITTAL_WIDTH: f64 = 0.66;
const LEGEND_ROW_PX: u32 = 30;

/// One ankle's poulaine and model (m, klaw's axes: x forward, y up, z right).
#[derive(Clone, Debug, PartialEq)]
pub struct AnklePoulaine {
    /// The samples.
    pub samples: Vec<[f64; 3]>,
    /// The model, densely sampled over its cycle.
    pub model: Vec<[f64; 3]>,
    /// The characteristic points 1–4 (the model's knots).
    pub points: [[f64; 3]; 4],
}

/// Where the figure's panels were drawn: each plotting area's (left, top, right, bottom) pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoulaineLayout {
    /// The sagittal panels: the right ankle's, the left's.
    pub sagittal: [(i32, i32, i32, i32); 2],
    /// The frontal panel, both ankles.
    pub frontal: (i32, i32, i32, i32),
}

/// Write the figure of the right and left ankles' poulaines (`legs`) to `path` (module doc);
/// `title` heads it. Returns where the panels were drawn. Errors: an extension other than .png
/// or .svg, drawing, writing.
pub fn write(path: &Path, legs: &[AnklePoulaine; 2], title: &str) -> Result<PoulaineLayout> {
    let format = plot::figure_format(path)?;
    let mut figure = PoulaineFigure {
        legs,
        title,
        text: plot::text_available(),
    };
    plot::write_figure(&mut figure, path, format, SIZE_PX, Png::Small, "the figure")
}

struct PoulaineFigure<'a> {
    legs: &'a [AnklePoulaine; 2],
    title: &'a str,
    text: bool,
}

/// The legs' colours and names, right then left.
const LEGS: [(RGBColor, &str); 2] = [(RIGHT_COLOR, "right"), (LEFT_COLOR, "left")];

impl Draw for PoulaineFigure<'_> {
    type Output = PoulaineLayout;
    fn draw<DB: DrawingBackend>(
        &mut self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<PoulaineLayout, DrawError> {
        root.fill(&WHITE).map_err(msg)?;
        let area = titled(root, self.title, TITLE_SIZE, self.text)?;
        let area = if self.text {
            let (legend, rest) = area.split_vertically(LEGEND_ROW_PX);
            draw_legend(&legend)?;
            rest
        } else {
            area
        };
        let (w, _) = area.dim_in_pixel();
        let (sagittal, frontal) =
            area.split_horizontally((f64::from(w) * SAGITTAL_WIDTH).round() as u32);
        let sagittal_areas = sagittal.split_evenly((2, 1));
        let everything = || self.legs.iter();
        let mut out = [(0, 0, 0, 0); 2];
        for (k, (panel, leg)) in sagittal_areas.iter().zip(self.legs).enumerate() {
            let (color, side) = LEGS[k];
            let name = format!("{side} ankle, sagittal (from the right)");
            let panel = titled(panel, &name, 18, self.text)?;
            // both sagittal panels over both ankles' extent: one scale, comparable
            let mut chart = view_chart(&panel, everything(), 0, "x forward (m)", self.text)?;
            draw_leg(&mut chart, leg, 0, color, self.text)?;
            out[k] = plotting_box(&chart);
        }
        let panel = titled(
            &frontal,
            "both ankles, frontal (from behind)",
            18,
            self.text,
        )?;
        let mut chart = view_chart(&panel, everything(), 2, "z right (m)", self.text)?;
        for (leg, (color, _)) in self.legs.iter().zip(LEGS) {
            draw_leg(&mut chart, leg, 2, color, self.text)?;
        }
        Ok(PoulaineLayout {
            sagittal: out,
            frontal: plotting_box(&chart),
        })
    }
}

/// A chart's plotting area in the figure's pixels (left, top, right, bottom).
fn plotting_box<DB: DrawingBackend>(chart: &Chart<'_, DB>) -> (i32, i32, i32, i32) {
    let (x, y) = chart.plotting_area().get_pixel_range();
    (x.start, y.start, x.end - 1, y.end - 1)
}

/// The legend's row: the ankles' colours, the samples, the model, the characteristic points.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
) -> std::result::Result<(), DrawError> {
    let (_, h) = area.dim_in_pixel();
    let y = h as i32 / 2;
    let style = TextStyle::from((FONT, 15)).pos(Pos::new(HPos::Left, VPos::Center));
    let mut x = 20;
    let label = |x: &mut i32, s: &str| -> std::result::Result<(), DrawError> {
        area.draw(&Text::new(s.to_string(), (*x, y), style.clone()))
            .map_err(msg)?;
        let (tw, _) = area.estimate_text_size(s, &style).map_err(msg)?;
        *x += tw as i32 + 24;
        Ok(())
    };
    for (color, side) in LEGS {
        area.draw(&Circle::new((x + 4, y), 3, color.mix(0.6).filled()))
            .map_err(msg)?;
        area.draw(&PathElement::new(
            vec![(x + 12, y), (x + 36, y)],
            color.stroke_width(2),
        ))
        .map_err(msg)?;
        x += 42;
        label(
            &mut x,
            &format!("{side} ankle: samples (dots), model (line)"),
        )?;
    }
    area.draw(&Rectangle::new(
        [(x, y - 5), (x + 10, y + 5)],
        BLACK.filled(),
    ))
    .map_err(msg)?;
    x += 16;
    label(
        &mut x,
        "characteristic points: 1 highest, 2 most forward, 3 under the pelvis, 4 most backward \
         (model: 4 Hermite segments)",
    )
}

/// The chart of one view, one scale on both axes, over every sample and model point.
fn view_chart<'a, 'l, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    legs: impl Iterator<Item = &'l AnklePoulaine> + Clone,
    u: usize,
    u_label: &str,
    text: bool,
) -> std::result::Result<Chart<'a, DB>, DrawError> {
    let all = || legs.clone().flat_map(|l| l.samples.iter().chain(&l.model));
    let range = |i: usize| {
        let lo = all().map(|p| p[i]).fold(f64::INFINITY, f64::min);
        let hi = all().map(|p| p[i]).fold(f64::NEG_INFINITY, f64::max);
        padded((lo, hi), 0.08, 0.05)
    };
    let mut b = builder(area, text);
    let plot_px = {
        let probe = b.build_cartesian_2d(0.0..1.0, 0.0..1.0).map_err(msg)?;
        probe.plotting_area().dim_in_pixel()
    };
    let fit = plot::equal_scale(range(u), range(1), plot_px);
    let mut chart = b
        .build_cartesian_2d(fit.x.0..fit.x.1, fit.y.0..fit.y.1)
        .map_err(msg)?;
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(RGBColor(240, 240, 240));
    if text {
        mesh.x_desc(u_label)
            .y_desc("y up from the pelvis centre (m)")
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 16));
    }
    mesh.draw().map_err(msg)?;
    Ok(chart)
}

/// One ankle in one view: samples, model, numbered points.
fn draw_leg<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    leg: &AnklePoulaine,
    u: usize,
    color: RGBColor,
    text: bool,
) -> std::result::Result<(), DrawError> {
    let at = |p: &[f64; 3]| (p[u], p[1]);
    chart
        .draw_series(
            leg.samples
                .iter()
                .map(|p| Circle::new(at(p), 2, color.mix(0.6).filled())),
        )
        .map_err(msg)?;
    let mut line: Vec<(f64, f64)> = leg.model.iter().map(at).collect();
    line.extend(line.first().copied());
    chart
        .draw_series(std::iter::once(PathElement::new(
            line,
            color.stroke_width(2),
        )))
        .map_err(msg)?;
    chart
        .draw_series(
            leg.points.iter().map(|p| {
                EmptyElement::at(at(p)) + Rectangle::new([(-5, -5), (5, 5)], BLACK.filled())
            }),
        )
        .map_err(msg)?;
    if text {
        chart
            .draw_series(leg.points.iter().enumerate().map(|(k, p)| {
                EmptyElement::at(at(p))
                    + Text::new(format!("{}", k + 1), (7, -18), (FONT, 16).into_font())
            }))
            .map_err(msg)?;
    }
    Ok(())
}
