//! Stick-figure animation of a walk (`klaw animate`, issue item 10): an animated GIF, one frame
//! per 1/fps s of walk time, each with two views of the figure of [`crate::figure`]:
//! - side view: x forward to the right, y up, the viewer on the figure's right side (+z); the
//!   camera follows the pelvis, ticks on the ground every 0.25 m (`GROUND_TICK_M`) show the
//!   progression;
//! - front view: the walker coming towards the viewer, so its right side (+z) is on the left of
//!   the picture (horizontal axis −z), y up; the camera stays on the walk's plane z = 0.
//!
//! A scenario's animation ([`write_scenario_gif`], `klaw scenario --animate`, issue 15) has a
//! third view beside these, from above (module `top`; axes of [`crate::plot::floor`]: x across,
//! −z up): the whole scenario's floor, the footprints placed so far, the pelvis path, and the
//! figure with an arrow along its gaze. There the front view's camera follows the pelvis's z.
//!
//! Both views have one scale (px per m) on both axes. The figure: each leg hip–knee–ankle–heel–
//! metatarsal joint–toe tip (and ankle–metatarsal joint, closing the foot), the pelvis line
//! between the hip joints, the spine from the pelvis centre to the shoulder line, neck and head
//! (in the head's frame: a neck rotation turns them about their own axis, which neither view
//! shows), the arms shoulder–elbow–wrist–hand tip (segment frames from
//! [`crate::figure::skeleton::Skeleton`], dimensions from [`Body::figure`]). The right side is
//! blue, the left red, the trunk grey; in
//! the side view the far (left) limbs are drawn first and paler. Every foot point (heel,
//! metatarsal joint, toe tip) within 1 mm of the ground (`CONTACT_TOLERANCE_M`) gets a black
//! dot in every view.
//!
//! The GIF is written by plotters' [`BitMapBackend::gif`] frame by frame into a temporary file
//! next to the target, renamed over it when complete: written whole or not at all. Text (the
//! walk's parameters, the time) needs the font of [`crate::plot`] and is left out without one.
use std::io::Read;
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::engine::walker::Walk;
use crate::error::{Error, Result};
use crate::export::ExportError;
use crate::figure::skeleton::Skeleton;
use crate::figure::{Landmarks, LegPoints};
use crate::model::InputError;
use crate::model::body::Body;
use crate::plot::{self, Chart, DrawError, LEFT_COLOR, RIGHT_COLOR, msg};
use crate::scenario::Motion;

pub use crate::plot::ViewMap;

mod text;
mod top;

pub use text::{MAX_LINES, MIN_FONT_PX, TextBlock};

/// A foot point this close to the ground (m) is drawn as a contact.
pub(crate) const CONTACT_TOLERANCE_M: f64 = 1e-3;
/// Spacing of the ground ticks of the side view (m).
pub(crate) const GROUND_TICK_M: f64 = 0.25;
/// Frame rate range (frames/s): GIF delays are whole hundredths of a second.
pub(crate) const FPS_RANGE: (f64, f64) = (1.0, 100.0);
/// Image width range (px).
pub(crate) const WIDTH_RANGE: (u32, u32) = (200, 4000);
/// Image height range (px).
pub(crate) const HEIGHT_RANGE: (u32, u32) = (100, 4000);
/// At most this many frames (a GIF of more would take long to write and be too large to show).
pub(crate) const MAX_FRAMES: usize = 20_000;
/// Colour of the contact dots.
pub(crate) const CONTACT_COLOR: RGBColor = RGBColor(0, 0, 0);
/// Pelvis, spine, shoulders, neck and head.
pub(crate) const TRUNK_COLOR: RGBColor = RGBColor(95, 95, 95);
const GROUND_COLOR: RGBColor = RGBColor(140, 140, 140);
const CONTACT_RADIUS: i32 = 4;
const MARGIN: u32 = 8;
/// The most of a frame's height the text above the figure may take.
const TEXT_SHARE: f64 = 0.45;

/// The animation's frame rate and image size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnimationOptions {
    /// Frames per second of walk time, also the playback rate.
    pub fps: f64,
    /// Width and height in pixels.
    pub size: (u32, u32),
}

impl AnimationOptions {
    /// Check the frame rate against 1–100 frames/s (`FPS_RANGE`) and the size against 200–4000
    /// px wide and 100–4000 px high (`WIDTH_RANGE`, `HEIGHT_RANGE`) ([`InputError::OutOfRange`]
    /// / [`InputError::NotFinite`]).
    pub fn new(fps: f64, size: (u32, u32)) -> Result<AnimationOptions, InputError> {
        InputError::check_range("fps", fps, FPS_RANGE.0, FPS_RANGE.1, "frames/s")?;
        let (w, h) = size;
        InputError::check_range(
            "width",
            f64::from(w),
            f64::from(WIDTH_RANGE.0),
            f64::from(WIDTH_RANGE.1),
            "px",
        )?;
        InputError::check_range(
            "height of the image",
            f64::from(h),
            f64::from(HEIGHT_RANGE.0),
            f64::from(HEIGHT_RANGE.1),
            "px",
        )?;
        Ok(AnimationOptions { fps, size })
    }

    /// The display time of a frame in milliseconds, as plotters takes it (it rounds to
    /// hundredths of a second).
    pub(crate) fn frame_delay_ms(&self) -> u32 {
        (1000.0 / self.fps).round() as u32
    }
}

impl Default for AnimationOptions {
    /// 25 frames/s, 900 × 450 px.
    fn default() -> Self {
        AnimationOptions {
            fps: 25.0,
            size: (900, 450),
        }
    }
}

/// Parse `WIDTHxHEIGHT` (e.g. `900x450`); errors are [`InputError::BadValue`] for `size`.
pub fn parse_size(text: &str) -> Result<(u32, u32), InputError> {
    let bad = || {
        let reason = format!("`{text}` is not WIDTHxHEIGHT in pixels, e.g. 900x450");
        InputError::bad_value("size", reason)
    };
    let (w, h) = text.trim().split_once(['x', 'X', '×']).ok_or_else(bad)?;
    // parsed signed, so that a negative size gets its range rather than "not WIDTHxHEIGHT"
    let w = w.trim().parse::<i64>().map_err(|_| bad())?;
    let h = h.trim().parse::<i64>().map_err(|_| bad())?;
    let (wr, hr) = (WIDTH_RANGE, HEIGHT_RANGE);
    InputError::check_range("width", w as f64, wr.0.into(), wr.1.into(), "px")?;
    InputError::check_range(
        "height of the image",
        h as f64,
        hr.0.into(),
        hr.1.into(),
        "px",
    )?;
    Ok((w as u32, h as u32))
}

/// The animation's path must end in `.gif` (any case); else [`InputError::Malformed`].
pub fn check_path(path: &Path) -> Result<(), InputError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if ext.as_deref() == Some("gif") {
        Ok(())
    } else {
        Err(InputError::malformed(
            "animation path",
            path,
            "the extension must be .gif",
        ))
    }
}

/// Where one frame's views were drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameViews {
    /// The side view (x across, y up).
    pub side: ViewMap,
    /// The front view (−z across, y up).
    pub front: ViewMap,
    /// The top view of a scenario (x across, −z up; [`crate::plot::floor`]).
    pub top: Option<ViewMap>,
    /// The text drawn (empty without a font): the header across the image, then each view's
    /// caption (side, front, top).
    pub text: Vec<TextBlock>,
    /// Each view's column (left, right) in pixels: side, front (and top).
    pub columns: Vec<(i32, i32)>,
}

/// What was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// GIF frames written.
    pub frames: usize,
    /// Each frame's view maps.
    pub views: Vec<FrameViews>,
}

/// Refuse an animation of a walk lasting `duration` s at `fps` frames/s with more frames than a
/// GIF of klaw holds (20 000): known before the walk is simulated (its duration is Σ 60 / sf).
pub fn check_frame_count(duration: f64, fps: f64) -> Result<(), InputError> {
    let expected = duration * fps + 1.0;
    InputError::check_range(
        "frame count (duration · fps + 1)",
        expected.floor(),
        1.0,
        MAX_FRAMES as f64,
        "frames",
    )?;
    Ok(())
}

/// Animate `walk`: its figure at `options.fps` ([`crate::figure::frames`]), then [`write_gif`].
/// `title` names the walk (e.g. [`crate::plot::parameters_title`]).
pub fn animate_walk(
    walk: &Walk,
    title: &str,
    path: &Path,
    options: &AnimationOptions,
) -> Result<Summary> {
    check_path(path)?;
    check_frame_count(walk.duration(), options.fps)?;
    let frames = crate::figure::frames(walk, options.fps);
    let frames = frames.collect::<Result<Vec<Landmarks>, _>>()?;
    write_gif(&frames, &walk.body, title, path, options)
}

/// Write `frames` (the figure at successive instants, 1/fps apart) as an animated GIF to `path`
/// (see the module doc). Errors: a path not ending in .gif ([`InputError::Malformed`]), no
/// frames or more than 20 000 (`MAX_FRAMES`) ([`ExportError::FrameCount`]), a frame the skeleton cannot
/// be built from ([`Error::Figure`]), drawing ([`Error::Draw`]) or writing ([`Error::Io`],
/// action "writing"). On error no file is left and an existing `path` is untouched.
pub fn write_gif(
    frames: &[Landmarks],
    body: &Body,
    title: &str,
    path: &Path,
    options: &AnimationOptions,
) -> Result<Summary> {
    write_frames(frames, None, body, title, path, options)
}

/// [`write_gif`] of a scenario's frames with a third view, from above: the floor over the whole
/// scenario's extent, the footprints placed so far, the pelvis path, and the figure seen from
/// above with its gaze (module doc). The same errors as [`write_gif`].
pub fn write_scenario_gif(
    motion: &Motion,
    body: &Body,
    title: &str,
    path: &Path,
    options: &AnimationOptions,
) -> Result<Summary> {
    let floor = top::Floor::new(motion, body);
    write_frames(&motion.frames, Some(&floor), body, title, path, options)
}

/// [`write_gif`], with the top view of `floor` when there is one.
fn write_frames(
    frames: &[Landmarks],
    floor: Option<&top::Floor>,
    body: &Body,
    title: &str,
    path: &Path,
    options: &AnimationOptions,
) -> Result<Summary> {
    check_path(path)?;
    let options = AnimationOptions::new(options.fps, options.size)?;
    if frames.is_empty() || frames.len() > MAX_FRAMES {
        return Err(ExportError::FrameCount {
            path: path.to_path_buf(),
            frames: frames.len(),
            max: MAX_FRAMES,
        }
        .into());
    }
    // every skeleton first: a bad frame fails before any drawing
    let skeletons = frames
        .iter()
        .map(|lm| Skeleton::new(lm, body))
        .collect::<Result<Vec<_>, _>>()?;
    let text = plot::text_available();
    let fail = |source| Error::Draw {
        path: path.to_path_buf(),
        what: "the animation",
        source,
    };
    let file = crate::export::file::AtomicFile::create(path)?;
    let mut views = Vec::with_capacity(frames.len());
    {
        let backend = BitMapBackend::gif(file.temp_path(), options.size, options.frame_delay_ms())
            .map_err(|e| fail(msg(e)))?;
        let root = backend.into_drawing_area();
        for (lm, sk) in frames.iter().zip(&skeletons) {
            let drawn = draw_frame(&root, lm, sk, body, title, text, floor);
            views.push(drawn.map_err(fail)?);
            root.present().map_err(|e| fail(msg(e)))?;
        }
        // dropping the backend writes the GIF trailer (errors there are not reported: checked
        // below)
    }
    let complete = gif_is_complete(file.temp_path()).map_err(|e| file.error(e))?;
    if !complete {
        return Err(fail(msg(
            "the GIF has no trailer: the file was not completed",
        )));
    }
    file.commit()?;
    Ok(Summary {
        frames: frames.len(),
        views,
    })
}

/// Whether the file ends with the GIF trailer byte (0x3B).
fn gif_is_complete(path: &Path) -> std::io::Result<bool> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)?.read_to_end(&mut bytes)?;
    Ok(bytes.starts_with(b"GIF8") && bytes.last() == Some(&0x3B))
}

/// A view's chart over `area` with one scale on both axes, showing the extent `u` × `v` whole
/// and centred (the side and front views pass an empty `u` span: their height fixes the scale).
fn view_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    u: (f64, f64),
    v: (f64, f64),
) -> std::result::Result<(Chart<'a, DB>, ViewMap), DrawError> {
    let (w, h) = area.dim_in_pixel();
    let plot_px = (
        w.saturating_sub(2 * MARGIN).max(2),
        h.saturating_sub(2 * MARGIN).max(2),
    );
    let fit = plot::equal_scale(u, v, plot_px);
    let chart = ChartBuilder::on(area)
        .margin(MARGIN)
        .build_cartesian_2d(fit.x.0..fit.x.1, fit.y.0..fit.y.1)
        .map_err(msg)?;
    let map = ViewMap::of_chart(&chart, &fit);
    Ok((chart, map))
}

/// The figure's segments as polylines of 3-D points, each with its colour and side.
fn segments(lm: &Landmarks, sk: &Skeleton, body: &Body) -> Vec<(Limb, Vec<[f64; 3]>)> {
    let leg = |l: &LegPoints| {
        vec![
            vec![l.hip, l.knee, l.ankle, l.heel, l.mtp, l.toe],
            vec![l.ankle, l.mtp],
        ]
    };
    let f = &body.figure;
    let t = |u: [f64; 3]| sk.thorax.point(glam::DVec3::from_array(u)).to_array();
    let head = |u: [f64; 3]| sk.head.point(glam::DVec3::from_array(u)).to_array();
    let arm = |a: &crate::figure::skeleton::ArmFrames| {
        vec![
            a.upper_arm.origin.to_array(),
            a.forearm.origin.to_array(),
            a.hand.origin.to_array(),
            a.hand.point(glam::DVec3::new(0.0, -f.hand, 0.0)).to_array(),
        ]
    };
    let mut out = Vec::new();
    for p in leg(&lm.left) {
        out.push((Limb::Left, p));
    }
    out.push((Limb::Left, arm(&sk.left_arm)));
    out.push((Limb::Trunk, vec![lm.right.hip, lm.left.hip]));
    out.push((Limb::Trunk, vec![lm.pelvis, t([0.0, f.spine, 0.0])]));
    out.push((
        Limb::Trunk,
        vec![
            t([0.0, f.spine, f.shoulder_width / 2.0]),
            t([0.0, f.spine, -f.shoulder_width / 2.0]),
        ],
    ));
    out.push((
        Limb::Trunk,
        vec![head([0.0, 0.0, 0.0]), head([0.0, f.neck, 0.0])],
    ));
    for p in leg(&lm.right) {
        out.push((Limb::Right, p));
    }
    out.push((Limb::Right, arm(&sk.right_arm)));
    out
}

#[derive(Clone, Copy, PartialEq)]
enum Limb {
    Right,
    Left,
    Trunk,
}

/// The foot points on the ground.
fn contacts(lm: &Landmarks) -> Vec<[f64; 3]> {
    [&lm.right, &lm.left]
        .into_iter()
        .flat_map(|l| [l.heel, l.mtp, l.toe])
        .filter(|p| p[1].abs() < CONTACT_TOLERANCE_M)
        .collect()
}

/// One GIF frame: the side view (two thirds of the width) and the front view, or with a
/// `floor` the side, front and top views (`top::PANELS`), each with its lines of text above the
/// figure.
fn draw_frame<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    lm: &Landmarks,
    sk: &Skeleton,
    body: &Body,
    title: &str,
    text: bool,
    floor: Option<&top::Floor>,
) -> std::result::Result<FrameViews, DrawError> {
    root.fill(&WHITE).map_err(msg)?;
    let (w, h) = root.dim_in_pixel();
    let widths: Vec<u32> = match floor {
        None => vec![w * 2 / 3, w - w * 2 / 3],
        Some(_) => top::panel_widths(w),
    };
    let f = &body.figure;
    // the header across the image and each view's caption, above the figure
    let font_px = (h / 30).clamp(12, 16) as i32;
    let (mut header, mut captions, header_text) = if text {
        let (header_text, header, captions) =
            text::frame_text(root, lm, title, w, &widths, font_px)?;
        (Some(header), captions, header_text)
    } else {
        (None, Vec::new(), String::new())
    };
    let ph = f64::from(h.saturating_sub(2 * MARGIN));
    let text_px = |header: &Option<text::TextBlock>, captions: &[text::TextBlock]| {
        let captions = captions.iter().map(text::TextBlock::height).max();
        match header {
            None => 0.0,
            Some(b) => f64::from(MARGIN as i32 + 4 + b.height() + captions.unwrap_or(0) + 6),
        }
    };
    // a low frame keeps the figure: the captions go, then the header's second line
    if text_px(&header, &captions) > TEXT_SHARE * ph {
        captions.clear();
    }
    if text_px(&header, &captions) > TEXT_SHARE * ph {
        header = Some(text::fit(root, &header_text, w, font_px, 1)?);
    }
    let header_px = header.as_ref().map_or(0, |b| b.height() + 2);
    let text_px = text_px(&header, &captions);
    // the head's top; the vertical range leaves text_px above it
    let top = (lm.pelvis[1] + f.spine + f.neck + f.head).max(body.height) + 0.05;
    let headroom = if ph > text_px + 40.0 {
        text_px * (top + 0.12) / (ph - text_px)
    } else {
        0.0
    };
    let scene = Scene {
        segments: segments(lm, sk, body),
        contacts: contacts(lm),
        head_centre: sk
            .head
            .point(glam::DVec3::new(0.0, f.neck + f.head / 2.0, 0.0))
            .to_array(),
        head: f.head,
        gaze: plot::floor::gaze_heading(sk),
        time: lm.time,
        pelvis_x: lm.pelvis[0],
        // a scenario's figure leaves the plane z = 0: the front view follows it
        front_u: if floor.is_some() { -lm.pelvis[2] } else { 0.0 },
        v_range: (-0.12, top + headroom),
        text_px: text_px as u32,
    };
    let (side_area, rest) = root.split_horizontally(widths[0]);
    let (front_area, top_area) = rest.split_horizontally(widths[1]);
    let side = draw_view(&side_area, &scene, View::Side)?;
    let front = draw_view(&front_area, &scene, View::Front)?;
    let top = match floor {
        Some(floor) => Some(draw_view(&top_area, &scene, View::Top(floor))?),
        None => None,
    };
    // the text over the views
    let y = MARGIN as i32 + 2;
    let mut blocks = Vec::new();
    if let Some(header) = header.as_mut() {
        text::draw(root, header, (text::left_px(), y))?;
        blocks.push(header.clone());
    }
    let areas = [&side_area, &front_area, &top_area];
    for (block, area) in captions.iter_mut().zip(areas) {
        text::draw(area, block, (text::left_px(), y + header_px))?;
        blocks.push(block.clone());
    }
    let mut left = 0;
    let columns = widths
        .iter()
        .map(|&px| {
            let column = (left, left + px as i32 - 1);
            left += px as i32;
            column
        })
        .collect();
    Ok(FrameViews {
        side,
        front,
        top,
        text: blocks,
        columns,
    })
}

/// What the views of a frame show, in world coordinates (m).
struct Scene {
    segments: Vec<(Limb, Vec<[f64; 3]>)>,
    contacts: Vec<[f64; 3]>,
    head_centre: [f64; 3],
    /// The head's diameter.
    head: f64,
    /// The head's heading (rad, + left).
    gaze: f64,
    /// The frame's time (s).
    time: f64,
    pelvis_x: f64,
    /// The horizontal centre of the front view (m of −z).
    front_u: f64,
    /// The vertical range of the side and front views.
    v_range: (f64, f64),
    /// The height of the text above the views (px).
    text_px: u32,
}

/// Which view of the figure a panel shows.
#[derive(Clone, Copy)]
enum View<'a> {
    /// x across, y up.
    Side,
    /// −z across, y up.
    Front,
    /// From above, over this floor: x across, −z up.
    Top(&'a top::Floor<'a>),
}

impl View<'_> {
    /// The view coordinates (u, v) of a world point.
    fn project(self, p: [f64; 3]) -> (f64, f64) {
        match self {
            View::Side => (p[0], p[1]),
            View::Front => (-p[2], p[1]),
            View::Top(_) => plot::floor::top(p[0], p[2]),
        }
    }
}

/// One view of `scene` on `area`: the ground (with moving ticks in the side view) or the
/// floor from above, the segments, the head, the contacts.
fn draw_view<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    scene: &Scene,
    view: View,
) -> std::result::Result<ViewMap, DrawError> {
    let chart_area = match view {
        // the floor's extent is fixed: the text goes above it
        View::Top(_) => area.split_vertically(scene.text_px).1,
        _ => area.clone(),
    };
    let (mut chart, map) = match view {
        View::Side | View::Front => {
            let u_mid = if matches!(view, View::Side) {
                scene.pelvis_x
            } else {
                scene.front_u
            };
            let (chart, map) = view_chart(&chart_area, (u_mid, u_mid), scene.v_range)?;
            let (u_lo, u_hi) = (map.u0, map.u0 + 2.0 * (u_mid - map.u0));
            ground(chart, map, (u_lo, u_hi), matches!(view, View::Side))?
        }
        View::Top(floor) => {
            let (mut chart, map) = view_chart(&chart_area, floor.extent.0, floor.extent.1)?;
            top::draw_floor(&mut chart, floor, scene.time)?;
            (chart, map)
        }
    };
    figure(&mut chart, scene, view, &map)?;
    Ok(map)
}

/// The ground line over `u_lo..u_hi`, and in the side view ticks below it that move with the
/// walk.
fn ground<'a, DB: DrawingBackend>(
    mut chart: Chart<'a, DB>,
    map: ViewMap,
    (u_lo, u_hi): (f64, f64),
    ticks: bool,
) -> std::result::Result<(Chart<'a, DB>, ViewMap), DrawError> {
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(u_lo, 0.0), (u_hi, 0.0)],
            GROUND_COLOR.stroke_width(1),
        )))
        .map_err(msg)?;
    if ticks {
        let first = (u_lo / GROUND_TICK_M).ceil() as i64;
        let last = (u_hi / GROUND_TICK_M).floor() as i64;
        chart
            .draw_series((first..=last).map(|k| {
                let u = k as f64 * GROUND_TICK_M;
                PathElement::new(vec![(u, 0.0), (u, -0.05)], GROUND_COLOR.stroke_width(1))
            }))
            .map_err(msg)?;
    }
    Ok((chart, map))
}

/// The figure in `view`: the segments (the far, left limbs paler in the side view), the head,
/// the contacts, and from above the gaze.
fn figure<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    scene: &Scene,
    view: View,
    map: &ViewMap,
) -> std::result::Result<(), DrawError> {
    for (limb, points) in &scene.segments {
        let color = match limb {
            Limb::Right => RIGHT_COLOR.to_rgba(),
            Limb::Left if matches!(view, View::Side) => LEFT_COLOR.mix(0.55),
            Limb::Left => LEFT_COLOR.to_rgba(),
            Limb::Trunk => TRUNK_COLOR.to_rgba(),
        };
        let pts: Vec<(f64, f64)> = points.iter().map(|&p| view.project(p)).collect();
        chart
            .draw_series(std::iter::once(PathElement::new(
                pts,
                color.stroke_width(3),
            )))
            .map_err(msg)?;
    }
    let head = view.project(scene.head_centre);
    let radius = (map.scale * scene.head / 2.0).round().max(2.0) as i32;
    chart
        .draw_series(std::iter::once(Circle::new(
            head,
            radius,
            TRUNK_COLOR.stroke_width(3),
        )))
        .map_err(msg)?;
    if let View::Top(_) = view {
        top::draw_gaze(chart, head, scene.gaze)?;
    }
    chart
        .draw_series(
            scene
                .contacts
                .iter()
                .map(|&p| Circle::new(view.project(p), CONTACT_RADIUS, CONTACT_COLOR.filled())),
        )
        .map_err(msg)?;
    Ok(())
}
