//! The top view of a scenario's animation: the floor from above ([`crate::plot::floor`]) over
//! the whole scenario's extent (the camera does not move), the pelvis path of the whole
//! scenario, faint, the footprints placed by the frame's time, and the figure's gaze.
use plotters::prelude::*;

use crate::model::body::Body;
use crate::plot::floor;
use crate::plot::{Chart, DrawError, Drawn, msg};
use crate::scenario::{Footprint, Motion};

/// The widths of the side, front and top views, as fractions of the image's.
pub(super) const PANELS: [f64; 3] = [0.36, 0.18, 0.46];
/// Room around the footprints and the path (m).
const PAD_M: f64 = 0.3;
/// The gaze arrow's length (m).
const GAZE_ARROW_M: f64 = 0.35;
/// The footprints' opacity (the figure is drawn over them).
const FOOTPRINT_OPACITY: f64 = 0.6;
/// Two footprints this close in time (s) are placed together.
const TIME_TOLERANCE_S: f64 = 1e-6;
const PATH_COLOR: RGBColor = RGBColor(190, 190, 190);

/// What the top view shows of the whole scenario.
pub(crate) struct Floor<'a> {
    footprints: &'a [Footprint],
    body: &'a Body,
    /// The pelvis centre's floor path, top-view coordinates.
    path: Vec<(f64, f64)>,
    /// The view's u and v ranges (m).
    pub(super) extent: ((f64, f64), (f64, f64)),
}

impl<'a> Floor<'a> {
    pub(crate) fn new(motion: &'a Motion, body: &'a Body) -> Self {
        Floor {
            footprints: &motion.footprints,
            body,
            path: motion.frames.iter().map(floor::pelvis_point).collect(),
            extent: floor::extent(&motion.footprints, &motion.frames, body, PAD_M),
        }
    }
}

/// The side, front and top views' widths (px) in an image `w` px wide.
pub(super) fn panel_widths(w: u32) -> Vec<u32> {
    let side = (f64::from(w) * PANELS[0]) as u32;
    let front = (f64::from(w) * PANELS[1]) as u32;
    vec![side, front, w.saturating_sub(side + front)]
}

/// The top view's caption.
pub(super) const TEXT: &str = "top, the start's left up: footprints so far, pelvis path, gaze";

/// The pelvis path and the footprints placed by `time`.
pub(super) fn draw_floor<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    floor: &Floor,
    time: f64,
) -> Drawn {
    chart
        .draw_series(std::iter::once(PathElement::new(
            floor.path.clone(),
            PATH_COLOR.stroke_width(1),
        )))
        .map_err(msg)?;
    let placed = floor
        .footprints
        .iter()
        .take_while(|f| f.time <= time + TIME_TOLERANCE_S)
        .count();
    floor::draw_footprints(
        chart,
        &floor.footprints[..placed],
        floor.body,
        FOOTPRINT_OPACITY,
    )
}

/// The gaze: an arrow from the head along its heading `gaze` (rad, + left).
pub(super) fn draw_gaze<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    head: (f64, f64),
    gaze: f64,
) -> std::result::Result<(), DrawError> {
    chart
        .draw_series(std::iter::once(PathElement::new(
            floor::arrow(head, gaze, GAZE_ARROW_M),
            floor::GAZE_COLOR.stroke_width(2),
        )))
        .map_err(msg)?;
    Ok(())
}
