//! A poulaine against its curve model (Pronost et al. §3.2, their Figure 3; `klaw poulaine fit
//! --plot`): both ankles relative to the pelvis centre, in a sagittal view (x forward to the
//! right, y up) and a frontal view seen from behind (z to the right, y up), one scale on both
//! axes of each; the samples as dots, the model as a line, the four characteristic points
//! marked and numbered (1 highest, 2 most forward, 3 under the pelvis, 4 most backward). The
//! right ankle in blue, the left in red.
//!
//! PNG or SVG by the file's extension, 1400 × 700 px, written whole or not at all.
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::error::Result;
use crate::plot::{
    self, Chart, Draw, DrawError, FONT, LEFT_COLOR, Png, RIGHT_COLOR, TITLE_SIZE, builder, msg,
    padded, titled,
};

/// The figure's size (px).
pub const SIZE_PX: (u32, u32) = (1400, 700);

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

/// Write the figure of the right and left ankles' poulaines (`legs`) to `path` (module doc);
/// `title` heads it. Errors: an extension other than .png or .svg, drawing, writing.
pub fn write(path: &Path, legs: &[AnklePoulaine; 2], title: &str) -> Result<()> {
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

/// A view: its name, the horizontal coordinate's index and label.
const VIEWS: [(&str, usize, &str); 2] = [
    ("sagittal (from the right)", 0, "x forward (m)"),
    ("frontal (from behind)", 2, "z right (m)"),
];

impl Draw for PoulaineFigure<'_> {
    type Output = ();
    fn draw<DB: DrawingBackend>(
        &mut self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), DrawError> {
        root.fill(&WHITE).map_err(msg)?;
        let area = titled(root, self.title, TITLE_SIZE, self.text)?;
        let panels = area.split_evenly((1, 2));
        for (panel, &(name, u, u_label)) in panels.iter().zip(&VIEWS) {
            let panel = titled(panel, name, 18, self.text)?;
            let mut chart = view_chart(&panel, self.legs, u, u_label, self.text)?;
            for (leg, color) in self.legs.iter().zip([RIGHT_COLOR, LEFT_COLOR]) {
                draw_leg(&mut chart, leg, u, color, self.text)?;
            }
            if self.text {
                chart
                    .configure_series_labels()
                    .background_style(WHITE.mix(0.8))
                    .border_style(BLACK)
                    .label_font((FONT, 14))
                    .position(SeriesLabelPosition::UpperMiddle)
                    .draw()
                    .map_err(msg)?;
            }
        }
        Ok(())
    }
}

/// The chart of one view, one scale on both axes, over every sample and model point.
fn view_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    legs: &[AnklePoulaine; 2],
    u: usize,
    u_label: &str,
    text: bool,
) -> std::result::Result<Chart<'a, DB>, DrawError> {
    let all = || legs.iter().flat_map(|l| l.samples.iter().chain(&l.model));
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
    let side = if color == RIGHT_COLOR {
        "right"
    } else {
        "left"
    };
    let dots = chart
        .draw_series(
            leg.samples
                .iter()
                .map(|p| Circle::new(at(p), 2, color.mix(0.6).filled())),
        )
        .map_err(msg)?;
    if text {
        dots.label(format!("{side}: samples"))
            .legend(move |(x, y)| Circle::new((x + 10, y), 2, color.filled()));
    }
    let mut line: Vec<(f64, f64)> = leg.model.iter().map(at).collect();
    line.extend(line.first().copied());
    let curve = chart
        .draw_series(std::iter::once(PathElement::new(
            line,
            color.stroke_width(2),
        )))
        .map_err(msg)?;
    if text {
        curve
            .label(format!("{side}: model (4 Hermite segments)"))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2)));
    }
    chart
        .draw_series(leg.points.iter().enumerate().map(|(k, p)| {
            EmptyElement::at(at(p))
                + Rectangle::new([(-5, -5), (5, 5)], BLACK.filled())
                + Text::new(format!("{}", k + 1), (7, -18), (FONT, 16).into_font())
        }))
        .map_err(msg)?;
    Ok(())
}
