//! The text above the animation's views: a header across the whole image (what is walked, the
//! time, the step) and a short caption over each view, each at most two lines: a block that
//! does not fit in two lines at the frame's font size is set smaller (down to `MIN_FONT_PX`),
//! and at the smallest size its second line is cut with "…". In a frame too low for that much
//! text above the figure the captions are left out, then the header is cut to one line.
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{MARGIN, top};
use crate::figure::Landmarks;
use crate::plot::{DrawError, FONT, msg};

/// The most lines of any block of text.
pub const MAX_LINES: usize = 2;
/// The smallest font a block is set in (px).
pub const MIN_FONT_PX: i32 = 9;
/// The room left of and right of a block's text (px).
const SIDE_PX: u32 = MARGIN + 6;

/// A block of text set to fit its width: its lines and font size.
#[derive(Clone, Debug, PartialEq)]
pub struct TextBlock {
    /// The lines, at most [`MAX_LINES`].
    pub lines: Vec<String>,
    /// The font size (px).
    pub font_px: i32,
    /// Where it was drawn: (left, top, right, bottom) of its lines' text in the image's pixels.
    pub bbox: (i32, i32, i32, i32),
}

impl TextBlock {
    /// The height of a line (px).
    pub(super) fn line_px(&self) -> i32 {
        line_px(self.font_px)
    }

    /// The block's height (px): its lines.
    pub(super) fn height(&self) -> i32 {
        self.lines.len() as i32 * self.line_px()
    }
}

fn line_px(font_px: i32) -> i32 {
    font_px + font_px / 4 + 2
}

/// The frame's header's text (across the image, `width` px) and the header and each view's
/// caption (side, front and, with three `widths`, top) set at `font_px` or smaller to fit; the
/// boxes are not yet placed.
pub(super) fn frame_text<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    lm: &Landmarks,
    title: &str,
    width: u32,
    widths: &[u32],
    font_px: i32,
) -> std::result::Result<(String, TextBlock, Vec<TextBlock>), DrawError> {
    let stance = if lm.step.is_multiple_of(2) {
        "right"
    } else {
        "left"
    };
    let header = format!(
        "{title}: t = {:.2} s, step {} ({stance} stance)",
        lm.time,
        lm.step + 1
    );
    // a scenario's figure turns: its right is on the left only while it faces +x
    let front = if widths.len() > 2 {
        "front, from +x: +z on the left"
    } else {
        "front: the walker's right on the left"
    };
    let captions = ["side; dots: feet on the ground", front, top::TEXT];
    let block = fit(root, &header, width, font_px, MAX_LINES)?;
    let captions = widths
        .iter()
        .zip(captions)
        .map(|(&px, text)| fit(root, text, px, font_px, MAX_LINES))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok((header, block, captions))
}

/// `text` set in a column `width` px wide (less the side room): at `font_px` if it wraps into
/// at most `max_lines` lines, else at the largest smaller size that does, down to
/// [`MIN_FONT_PX`], where the last line is cut to fit with "…".
pub(super) fn fit<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    width: u32,
    font_px: i32,
    max_lines: usize,
) -> std::result::Result<TextBlock, DrawError> {
    let room = width.saturating_sub(2 * SIDE_PX).max(1);
    let block = |font_px: i32, lines: Vec<String>| TextBlock {
        lines,
        font_px,
        bbox: (0, 0, 0, 0),
    };
    let smallest = MIN_FONT_PX.min(font_px);
    for size in (smallest..=font_px).rev() {
        let style = TextStyle::from((FONT, size));
        let lines = wrap(area, text, room, &style)?;
        let fits = lines.len() <= max_lines
            && lines
                .iter()
                .map(|l| area.estimate_text_size(l, &style).map(|s| s.0 <= room))
                .collect::<Result<Vec<bool>, _>>()
                .map_err(msg)?
                .into_iter()
                .all(|f| f);
        if fits {
            return Ok(block(size, lines));
        }
    }
    // the smallest size: the first lines as wrapped, the rest cut into the last line
    let style = TextStyle::from((FONT, smallest));
    let mut lines = wrap(area, text, room, &style)?;
    let rest = lines.split_off(max_lines.min(lines.len()).saturating_sub(1));
    let mut out = Vec::with_capacity(max_lines);
    for line in lines {
        out.push(cut(area, &line, room, &style, false)?);
    }
    out.push(cut(area, &rest.join(" "), room, &style, rest.len() > 1)?);
    Ok(block(smallest, out))
}

/// `line` cut to `width` px with "…" when it is too long (or `more` follows it).
fn cut<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    line: &str,
    width: u32,
    style: &TextStyle,
    more: bool,
) -> std::result::Result<String, DrawError> {
    let size = |s: &str| area.estimate_text_size(s, style).map(|s| s.0).map_err(msg);
    if !more && size(line)? <= width {
        return Ok(line.to_string());
    }
    let chars: Vec<char> = line.chars().collect();
    for n in (0..=chars.len()).rev() {
        let candidate = format!("{}…", chars[..n].iter().collect::<String>().trim_end());
        if size(&candidate)? <= width || n == 0 {
            return Ok(candidate);
        }
    }
    Ok("…".to_string())
}

/// `text` broken at spaces so that each line fits in `width` pixels (a word longer than that
/// stays whole).
fn wrap<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    width: u32,
    style: &TextStyle,
) -> std::result::Result<Vec<String>, DrawError> {
    let mut out = Vec::new();
    let mut current = String::new();
    for word in text.split(' ') {
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
    Ok(out)
}

/// Draw `block` with its first line's top at `(x, y)` on `area` (whose top left is the image's
/// `origin`); its box is filled in.
pub(super) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    block: &mut TextBlock,
    (x, y): (i32, i32),
) -> std::result::Result<(), DrawError> {
    let style = TextStyle::from((FONT, block.font_px)).color(&BLACK);
    let (ox, oy) = area.get_base_pixel();
    let mut right = x;
    for (i, line) in block.lines.iter().enumerate() {
        let at = (x, y + block.line_px() * i as i32);
        area.draw(&Text::new(line.clone(), at, style.clone()))
            .map_err(msg)?;
        let (tw, _) = area.estimate_text_size(line, &style).map_err(msg)?;
        right = right.max(x + tw as i32);
    }
    block.bbox = (ox + x, oy + y, ox + right, oy + y + block.height());
    Ok(())
}

/// The left room of a block in its column (px).
pub(super) fn left_px() -> i32 {
    SIDE_PX as i32
}
