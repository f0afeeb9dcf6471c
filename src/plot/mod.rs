//! Figures of walks and sweeps: the walk figure ([`walk`], `klaw walk --plot`), the gait-cycle
//! figure ([`cycle`], `klaw plot`), sweep heat maps ([`heat_map`], `klaw plot-sweep`), the
//! stick-figure animation ([`animation`], `klaw animate`) and a scenario's footprints seen from
//! above ([`footprints`], `klaw scenario --footprints`), a poulaine against its model
//! ([`poulaine`], `klaw poulaine fit --plot`); here what they share: the font, the
//! colours, the file format by extension, charts with one scale on both axes and the writing of
//! a drawn figure.
//!
//! PNG (rendered in memory, encoded here) or SVG, chosen by the file's extension, written
//! atomically through `write_atomic`. Text needs a TrueType font: it is read at run time from
//! the file named by `KLAW_FONT` or else from the usual DejaVu Sans locations; without one the
//! figures are drawn without any text (no titles, tick labels or legends) rather than failing.
pub mod animation;
pub mod cycle;
pub mod error;
pub mod floor;
pub mod footprints;
pub mod heat_map;
pub mod overlay;
pub mod poulaine;
pub mod walk;

pub use error::DrawError;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ColorType, ImageEncoder, ImageError};

use crate::error::{Error, Result};
use crate::model::InputError;
use crate::model::body::Body;
use crate::plan::gait::Gait;

/// Environment variable naming the TrueType font to use instead of the default locations.
pub const FONT_ENV: &str = "KLAW_FONT";
/// Where the font is looked for when `KLAW_FONT` is not set (Debian/Ubuntu, Arch, Fedora).
pub(crate) const FONT_CANDIDATES: &[&str] = &[
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
];

pub(crate) const FONT: &str = "sans-serif";
pub(crate) const TITLE_SIZE: i32 = 22;
/// The right side's curves and segments, in every figure.
pub(crate) const RIGHT_COLOR: RGBColor = RGBColor(31, 119, 180);
/// The left side's curves and segments, in every figure.
pub(crate) const LEFT_COLOR: RGBColor = RGBColor(214, 39, 40);

/// The file format of a figure, from its path's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FigureFormat {
    /// `.png`: a raster image.
    Png,
    /// `.svg`: a vector image.
    Svg,
}

/// `.png` or `.svg` (any case); anything else is an input error naming the path.
pub fn figure_format(path: &Path) -> Result<FigureFormat, InputError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(FigureFormat::Png),
        Some("svg") => Ok(FigureFormat::Svg),
        _ => Err(InputError::malformed(
            "plot path",
            path,
            "the extension must be .png or .svg",
        )),
    }
}

/// Whether a font was found, so that figures carry text (loaded once per process).
pub fn text_available() -> bool {
    static READY: OnceLock<bool> = OnceLock::new();
    *READY.get_or_init(|| {
        let candidates: Vec<PathBuf> = match std::env::var_os(FONT_ENV) {
            Some(p) => vec![PathBuf::from(p)],
            None => FONT_CANDIDATES.iter().map(PathBuf::from).collect(),
        };
        candidates.iter().any(|p| match std::fs::read(p) {
            // plotters keeps registered fonts for the life of the process
            Ok(bytes) => {
                register_font(FONT, FontStyle::Normal, Box::leak(bytes.into_boxed_slice())).is_ok()
            }
            Err(_) => false,
        })
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

pub(crate) type Drawn = std::result::Result<(), DrawError>;
/// A chart with both axes in f64.
pub(crate) type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A plotters error as a [`DrawError`].
pub(crate) fn msg<E: std::fmt::Display>(e: E) -> DrawError {
    DrawError(e.to_string())
}

/// `area` with `title` above it in `size` px when there is text, else `area` itself.
pub(crate) fn titled<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    size: i32,
    text: bool,
) -> std::result::Result<DrawingArea<DB, Shift>, DrawError> {
    if text {
        area.titled(title, (FONT, size)).map_err(msg)
    } else {
        Ok(area.clone())
    }
}

/// A figure that draws itself on any plotters backend (the bitmap of a PNG, or SVG).
pub(crate) trait Draw {
    /// What drawing reports (e.g. where the panels were put).
    type Output;
    fn draw<DB: DrawingBackend>(
        &mut self,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<Self::Output, DrawError>;
}

/// [lo, hi] widened by `frac` of its span on each side, and to at least `min_span`.
pub(crate) fn padded((lo, hi): (f64, f64), frac: f64, min_span: f64) -> (f64, f64) {
    let pad = (hi - lo) * frac;
    let (lo, hi) = (lo - pad, hi + pad);
    if hi - lo < min_span {
        let mid = 0.5 * (lo + hi);
        (mid - 0.5 * min_span, mid + 0.5 * min_span)
    } else {
        (lo, hi)
    }
}

/// A chart builder with the figures' margins; label areas only when there is text.
pub(crate) fn builder<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    text: bool,
) -> ChartBuilder<'a, 'b, DB> {
    let mut b = ChartBuilder::on(area);
    b.margin(12);
    if text {
        b.x_label_area_size(48).y_label_area_size(64);
    }
    b
}

/// The outline of the plotting area (drawn instead of the axes when there is no text).
pub(crate) fn frame_border<DB: DrawingBackend>(chart: &Chart<'_, DB>) -> Drawn {
    let (w, h) = chart.plotting_area().dim_in_pixel();
    let area = chart.plotting_area().strip_coord_spec();
    area.draw(&Rectangle::new(
        [(0, 0), (w as i32 - 1, h as i32 - 1)],
        BLACK.stroke_width(1),
    ))
    .map_err(msg)
}

/// The ranges of a chart with one scale on both axes (see [`equal_scale`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EqualScale {
    /// The horizontal range shown.
    pub x: (f64, f64),
    /// The vertical range shown.
    pub y: (f64, f64),
    /// Pixels per unit (metre), both axes.
    pub scale: f64,
}

/// The largest scale (px per unit, one for both axes) at which the extent `x` × `y` fits in a
/// plotting area of `pw` × `ph` px, and the ranges that fill the area at it, centred on the
/// extent (the axis with room to spare is widened on both sides). A span of 0 (or less) asks
/// for nothing along that axis: the other fixes the scale.
pub fn equal_scale(x: (f64, f64), y: (f64, f64), (pw, ph): (u32, u32)) -> EqualScale {
    let (pw, ph) = (f64::from(pw.max(1)), f64::from(ph.max(1)));
    let fit = |px: f64, (lo, hi): (f64, f64)| {
        if hi > lo {
            px / (hi - lo)
        } else {
            f64::INFINITY
        }
    };
    let scale = fit(pw, x).min(fit(ph, y));
    // two empty spans: one metre across the narrower side
    let scale = if scale.is_finite() { scale } else { pw.min(ph) };
    let around = |(lo, hi): (f64, f64), px: f64| {
        let (mid, half) = (0.5 * (lo + hi), 0.5 * px / scale);
        (mid - half, mid + half)
    };
    EqualScale {
        x: around(x, pw),
        y: around(y, ph),
        scale,
    }
}

/// A chart's world-to-pixel map: pixel = (px0 + scale · (u − u0), py0 − scale · (v − v0)), u
/// the chart's horizontal coordinate (x in a side view, −z in a front view, x in a top view), v
/// its vertical one (y, or −z in a top view).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewMap {
    pub(crate) u0: f64,
    pub(crate) v0: f64,
    pub(crate) px0: f64,
    pub(crate) py0: f64,
    /// Pixels per metre, both axes.
    pub(crate) scale: f64,
}

impl ViewMap {
    /// The pixel of view coordinates (u, v).
    pub fn pixel(&self, u: f64, v: f64) -> (i32, i32) {
        (
            (self.px0 + self.scale * (u - self.u0)).round() as i32,
            (self.py0 - self.scale * (v - self.v0)).round() as i32,
        )
    }

    /// Pixels per metre, both axes.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The map of a chart built over `fit`'s ranges, read off two corners as plotters places
    /// them (backend coordinates: the whole image's pixels).
    pub(crate) fn of_chart<DB: DrawingBackend>(chart: &Chart<'_, DB>, fit: &EqualScale) -> Self {
        let ((u_lo, u_hi), (v_lo, v_hi)) = (fit.x, fit.y);
        let (x0, y0) = chart.backend_coord(&(u_lo, v_lo));
        let (x1, y1) = chart.backend_coord(&(u_hi, v_hi));
        let sx = f64::from(x1 - x0) / (u_hi - u_lo);
        let sy = f64::from(y0 - y1) / (v_hi - v_lo);
        ViewMap {
            u0: u_lo,
            v0: v_lo,
            px0: f64::from(x0),
            py0: f64::from(y0),
            scale: 0.5 * (sx + sy),
        }
    }
}

/// How a PNG is encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Png {
    /// The encoder's default compression and filter.
    Default,
    /// The best compression and adaptive filters: slower, and the file about a third of the size
    /// (for figures committed to the repository).
    Small,
}

/// Draw `figure` on `size` pixels and write it to `path` in `format`, whole or not at all. A
/// drawing failure is [`Error::Draw`] naming `what`.
pub(crate) fn write_figure<F: Draw>(
    figure: &mut F,
    path: &Path,
    format: FigureFormat,
    size: (u32, u32),
    png: Png,
    what: &'static str,
) -> Result<F::Output> {
    let fail = |source| Error::Draw {
        path: path.to_path_buf(),
        what,
        source,
    };
    match format {
        FigureFormat::Png => {
            let mut pixels = vec![0u8; size.0 as usize * size.1 as usize * 3];
            let drawn = {
                let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
                let drawn = figure.draw(&root).map_err(fail)?;
                root.present().map_err(|e| fail(msg(e)))?;
                drawn
            };
            write_png(path, &pixels, size, png)?;
            Ok(drawn)
        }
        FigureFormat::Svg => {
            let mut svg = String::new();
            let drawn = {
                let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
                let drawn = figure.draw(&root).map_err(fail)?;
                root.present().map_err(|e| fail(msg(e)))?;
                drawn
            };
            crate::export::file::write_atomic(path, |out| out.write_all(svg.as_bytes()))?;
            Ok(drawn)
        }
    }
}

/// Encode an RGB buffer as PNG and write it atomically.
fn write_png(path: &Path, pixels: &[u8], (w, h): (u32, u32), png: Png) -> Result<()> {
    let (compression, filter) = match png {
        Png::Default => (CompressionType::default(), FilterType::default()),
        Png::Small => (CompressionType::Best, FilterType::Adaptive),
    };
    crate::export::file::write_atomic(path, |out| {
        PngEncoder::new_with_quality(out, compression, filter)
            .write_image(pixels, w, h, ColorType::Rgb8)
            .map_err(|e| match e {
                ImageError::IoError(e) => e,
                other => std::io::Error::other(other),
            })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_scale_fits_the_extent_at_one_scale() {
        // a 4 m × 1 m extent in 800 × 400 px: the width binds at 200 px/m, the height shows 2 m
        let fit = equal_scale((0.0, 4.0), (-0.5, 0.5), (800, 400));
        assert!((fit.scale - 200.0).abs() < 1e-12);
        assert!((fit.x.0 - 0.0).abs() < 1e-12 && (fit.x.1 - 4.0).abs() < 1e-12);
        assert!((fit.y.0 + 1.0).abs() < 1e-12 && (fit.y.1 - 1.0).abs() < 1e-12);
        // both ranges at that scale fill the area exactly
        for (range, px) in [(fit.x, 800.0), (fit.y, 400.0)] {
            assert!(((range.1 - range.0) * fit.scale - px).abs() < 1e-9);
        }
        // a zero span leaves the scale to the other axis
        let fit = equal_scale((3.0, 3.0), (0.0, 2.0), (600, 400));
        assert!((fit.scale - 200.0).abs() < 1e-12);
        assert!((fit.x.0 - 1.5).abs() < 1e-12 && (fit.x.1 - 4.5).abs() < 1e-12);
    }

    #[test]
    fn extension_chooses_the_format() {
        assert_eq!(
            figure_format(Path::new("a/w.png")).unwrap(),
            FigureFormat::Png
        );
        assert_eq!(
            figure_format(Path::new("w.SVG")).unwrap(),
            FigureFormat::Svg
        );
        for bad in ["w", "w.jpg", "png"] {
            let e = figure_format(Path::new(bad)).unwrap_err();
            assert!(matches!(e, InputError::Malformed { .. }), "{e}");
            assert!(e.to_string().contains(".png or .svg"), "{e}");
        }
    }
}
