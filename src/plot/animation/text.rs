//! The lines of text above the animation's views, wrapped to their widths.
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{MARGIN, top};
use crate::figure::Landmarks;
use crate::plot::{DrawError, msg};

/// The lines of text of each view (side, front and, with three `widths`, top), wrapped to their
/// widths in pixels.
pub(super) fn frame_text<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    lm: &Landmarks,
    title: &str,
    widths: &[u32],
    style: &TextStyle,
) -> std::result::Result<Vec<Vec<String>>, DrawError> {
    let stance = if lm.step.is_multiple_of(2) {
        "right"
    } else {
        "left"
    };
    let side = vec![
        format!("side view: {title}"),
        format!(
            "t = {:.2} s, step {} ({stance} stance); dots: feet on the ground",
            lm.time,
            lm.step + 1
        ),
    ];
    // a scenario's figure turns: its right is on the left only while it faces +x
    let front = if widths.len() > 2 {
        "front view, from +x: +z (the start's right) on the left"
    } else {
        "front view: walker's right on the left"
    };
    let front = vec![front.to_string()];
    let texts = [side, front, top::text()];
    widths
        .iter()
        .zip(texts.iter())
        .map(|(&px, lines)| wrap(root, lines, px.saturating_sub(2 * MARGIN + 12), style))
        .collect()
}

/// `lines` broken at spaces so that each fits in `width` pixels (a word longer than that stays
/// whole).
fn wrap<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    lines: &[String],
    width: u32,
    style: &TextStyle,
) -> std::result::Result<Vec<String>, DrawError> {
    let mut out = Vec::new();
    for line in lines {
        let mut current = String::new();
        for word in line.split(' ') {
            let candidate = if current.is_empty() {
                word.to_string()
            } else {
                format!("{current} {word}")
            };
            let (tw, _) = area.estimate_text_size(&candidate, style).map_err(msg)?;
            if tw > width && !current.is_empty() {
                out.push(std::mem::replace(&mut current, word.to_string()));
            } else {
                current = candidate;
            }
        }
        out.push(current);
    }
    Ok(out)
}
