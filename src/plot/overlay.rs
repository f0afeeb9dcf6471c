//! Two walks' gait cycles over each other (issue 17: the kinematic walk mode against the dynamic
//! one): hip flexion, knee flexion and ankle dorsiflexion of the right leg against 0–100 % of
//! its cycle, the first walk solid, the second dashed. The legend is a row of its own under the
//! title, so that it covers no curve.
//!
//! PNG or SVG by the extension, 1500 × 600 px, written whole or not at all; text needs the font
//! of [`crate::plot`] and is left out without one.
use std::path::Path;

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::analysis::cycle::{GaitCycle, Panel};
use crate::error::Result;
use crate::figure::skeleton::Side;
use crate::plot::{
    self, Draw, DrawError, FONT, FigureFormat, LEFT_COLOR, Png, RIGHT_COLOR, TITLE_SIZE, msg,
    titled,
};

/// Figure size in pixels (width, height).
pub const OVERLAY_FIGURE_SIZE: (u32, u32) = (1500, 600);
const PANELS: [(Panel, &str); 3] = [
    (Panel::HipFlexion, "Hip flexion (°)"),
    (Panel::KneeFlexion, "Knee flexion (°)"),
    (Panel::AnkleDorsiflexion, "Ankle dorsiflexion (°)"),
];

/// The legend's row height (px).
const LEGEND_ROW_PX: u32 = 30;

/// Where an overlay figure was drawn (the figure's pixels, boxes as (left, top, right, bottom)).
#[derive(Clone, Debug, PartialEq)]
pub struct OverlayLayout {
    /// The plotting area of each panel: hip, knee, ankle.
    pub panels: [(i32, i32, i32, i32); 3],
    /// Every drawn point of each panel's curves (first walk's, then second's), in pixels.
    pub curves: [Vec<(i32, i32)>; 3],
    /// The legend's entries' boxes (sample and text), empty without text.
    pub legend: Vec<(i32, i32, i32, i32)>,
}

/// Draw the right leg's hip, knee and ankle curves of `first` (solid) and `second` (dashed),
/// each named by its label, under `title`, to `path` (PNG or SVG by its extension); returns
/// where it drew. Errors: a bad extension ([`crate::model::InputError::Malformed`], before
/// anything is drawn), drawing ([`crate::Error::Draw`]) or writing ([`crate::Error::Io`]; no
/// file is left).
pub fn write_overlay(
    first: (&str, &GaitCycle),
    second: (&str, &GaitCycle),
    title: &str,
    path: &Path,
) -> Result<OverlayLayout> {
    let format = plot::figure_format(path)?;
    render([first, second], title, path, format, plot::text_available())
}

/// [`write_overlay`] in `format`, with text or without.
fn render(
    walks: [(&str, &GaitCycle); 2],
    title: &str,
    path: &Path,
    format: FigureFormat,
    text: bool,
) -> Result<OverlayLayout> {
    let mut figure = Overlay { walks, title, text };
    plot::write_figure(
        &mut figure,
        path,
        format,
        OVERLAY_FIGURE_SIZE,
        Png::Small,
        "the overlay figure",
    )
}

struct Overlay<'a> {
    walks: [(&'a str, &'a GaitCycle); 2],
    title: &'a str,
    text: bool,
}

/// The right leg's curve of `panel` as (%, value) points.
fn points(cycle: &GaitCycle, panel: Panel) -> Vec<(f64, f64)> {
    cycle
        .curves
        .iter()
        .find(|c| c.panel == panel && c.side == Some(Side::Right))
        .map(|c| {
            let n = (c.values.len().max(2) - 1) as f64;
            c.values
                .iter()
                .enumerate()
                .map(|(i, &v)| (i as f64 * 100.0 / n, v))
                .filter(|(_, v)| v.is_finite())
                .collect()
        })
        .unwrap_or_default()
}

impl Draw for Overlay<'_> {
    type Output = OverlayLayout;

    fn draw<DB: DrawingBackend>(
        &mut self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<OverlayLayout, DrawError> {
        root.fill(&WHITE).map_err(msg)?;
        let area = titled(root, self.title, TITLE_SIZE, self.text)?;
        let (area, legend) = if self.text {
            let (row, rest) = area.split_vertically(LEGEND_ROW_PX);
            (rest, self.legend(&row)?)
        } else {
            (area, Vec::new())
        };
        let mut panels = [(0, 0, 0, 0); 3];
        let mut curves: [Vec<(i32, i32)>; 3] = Default::default();
        for (k, (area, &(panel, name))) in area.split_evenly((1, 3)).iter().zip(&PANELS).enumerate()
        {
            (panels[k], curves[k]) = self.panel(area, panel, name)?;
        }
        Ok(OverlayLayout {
            panels,
            curves,
            legend,
        })
    }
}

impl Overlay<'_> {
    /// The legend's row, centred: the first walk's solid line and label, the second's dashed.
    fn legend<DB: DrawingBackend>(
        &self,
        row: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<Vec<(i32, i32, i32, i32)>, DrawError> {
        let style = TextStyle::from((FONT, 16)).pos(Pos::new(HPos::Left, VPos::Center));
        let (w, h) = row.dim_in_pixel();
        let y = h as i32 / 2;
        let [(a, _), (b, _)] = self.walks;
        let width = |t: &str| -> std::result::Result<i32, DrawError> {
            let (tw, _) = row.estimate_text_size(t, &style).map_err(msg)?;
            Ok(36 + tw as i32)
        };
        let (wa, wb) = (width(a)?, width(b)?);
        let gap = 40;
        let mut x = (w as i32 - (wa + gap + wb)) / 2;
        let (bx, by) = row.get_base_pixel();
        let mut boxes = Vec::new();
        for (k, (label, width)) in [(a, wa), (b, wb)].into_iter().enumerate() {
            let line = vec![(x, y), (x + 28, y)];
            if k == 0 {
                row.draw(&PathElement::new(line, RIGHT_COLOR.stroke_width(2)))
            } else {
                row.draw(&DashedPathElement::new(
                    line,
                    9,
                    5,
                    LEFT_COLOR.stroke_width(2),
                ))
            }
            .map_err(msg)?;
            row.draw(&Text::new(label.to_string(), (x + 36, y), style.clone()))
                .map_err(msg)?;
            boxes.push((bx + x, by + y - 10, bx + x + width, by + y + 10));
            x += width + gap;
        }
        Ok(boxes)
    }

    /// One panel; its plotting area and its curves' pixels.
    #[allow(clippy::type_complexity)]
    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        panel: Panel,
        name: &str,
    ) -> std::result::Result<((i32, i32, i32, i32), Vec<(i32, i32)>), DrawError> {
        let curves = self.walks.map(|(_, c)| points(c, panel));
        let values = curves.iter().flatten().map(|p| p.1);
        let lo = values.clone().fold(f64::INFINITY, f64::min);
        let hi = values.fold(f64::NEG_INFINITY, f64::max);
        let (lo, hi) = plot::padded((lo, hi), 0.08, 5.0);
        let mut builder = plot::builder(area, self.text);
        // room right of the axis for the last tick's label ("100")
        builder.margin_right(24);
        if self.text {
            builder.caption(name, (FONT, 18));
        }
        let mut chart = builder
            .build_cartesian_2d(0.0..100.0, lo..hi)
            .map_err(msg)?;
        if self.text {
            let tick = |v: &f64| {
                let s = format!("{v:.1}");
                s.strip_suffix(".0").map_or(s.clone(), str::to_string)
            };
            chart
                .configure_mesh()
                .x_desc("% of the gait cycle (right heel strike to right heel strike)")
                .x_label_formatter(&tick)
                .y_label_formatter(&tick)
                .label_style((FONT, 14))
                .draw()
                .map_err(msg)?;
        } else {
            plot::frame_border(&chart)?;
        }
        let [pa, pb] = curves;
        let pixels: Vec<(i32, i32)> = pa
            .iter()
            .chain(&pb)
            .map(|p| chart.backend_coord(p))
            .collect();
        chart
            .draw_series(LineSeries::new(pa, RIGHT_COLOR.stroke_width(2)))
            .map_err(msg)?;
        chart
            .draw_series(DashedLineSeries::new(pb, 9, 5, LEFT_COLOR.stroke_width(2)))
            .map_err(msg)?;
        let (x, y) = chart.plotting_area().get_pixel_range();
        Ok(((x.start, y.start, x.end - 1, y.end - 1), pixels))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::cycle::PanelCurve;

    fn cycle(shift: f64) -> GaitCycle {
        GaitCycle {
            curves: PANELS
                .iter()
                .map(|&(panel, _)| PanelCurve {
                    panel,
                    side: Some(Side::Right),
                    values: (0..=100).map(|i| shift + (i as f64 * 0.06).sin()).collect(),
                })
                .collect(),
            cycles: (1, 1),
            toe_off_pct: [None, None],
        }
    }

    /// The right leg's curve of a panel at 0…100 %; a PNG and an SVG are written, a bad
    /// extension refused with nothing written.
    #[test]
    fn overlays_are_written_and_a_bad_extension_refused() {
        let c = cycle(1.0);
        let p = points(&c, Panel::KneeFlexion);
        assert_eq!(p.len(), 101);
        assert_eq!(p[100].0, 100.0);
        assert!((p[50].1 - (1.0 + 3f64.sin())).abs() < 1e-12);
        assert!(points(&c, Panel::PelvisList).is_empty());
        let dir = tempfile::tempdir().unwrap();
        // without text: this test binary registers no font (plot::walk's tests rely on it)
        for (name, format) in [("o.png", FigureFormat::Png), ("o.svg", FigureFormat::Svg)] {
            let p = dir.path().join(name);
            render([("a", &c), ("b", &cycle(0.0))], "t", &p, format, false).unwrap();
            assert!(std::fs::metadata(&p).unwrap().len() > 1000);
        }
        let bad = dir.path().join("o.jpg");
        assert!(write_overlay(("a", &c), ("b", &c), "t", &bad).is_err());
        assert!(!bad.exists());
    }
}
