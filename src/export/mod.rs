//! Motion export (issue items 7 and 8): clinical-angle CSV, OpenSim storage (`.mot` / `.sto`) and
//! BVH, written from a stream of [`Landmarks`]; gait-cycle normalized curves. Axes, signs and
//! the import recipes are in `docs/export.md`. The walk's other files have a writer each: the
//! engine-state CSV ([`state`]), the gait events ([`events`]) and the JSON report ([`report`]).
//!
//! Every motion writer streams: rows go to an unnamed file in the target's directory while the
//! frames are converted (`spool`). When the header could go first (no row count in it, or the
//! count known beforehand), that file becomes the target; otherwise the header (which needs the
//! row count) and the rows are written to the target by `file::write_atomic`. Any error, in a
//! frame or in the file system, leaves no file (and an existing target untouched); every file of
//! the crate is written through [`file`](mod@file) or a spool renamed over the target.
pub mod bvh;
pub(crate) mod csv;
pub mod cycle;
pub mod error;
pub mod events;
pub mod file;
pub(crate) mod number;
pub mod opensim;
pub mod read;
pub mod report;
mod rows;
mod spool;
pub mod state;
pub mod walk_data;

use std::cell::OnceCell;
use std::io::{self, Write};
use std::path::Path;

pub use cycle::write_cycle_csv;
pub use error::ExportError;
pub use events::{write_events_csv, write_rows_csv};
pub use opensim::OpenSimModel;
pub use report::write_report_json;
pub use state::write_frames_csv;
pub use walk_data::write_walk_data;

use crate::error::{Error, Result};
use crate::figure::Landmarks;
use crate::figure::clinical::Clinical;
use crate::figure::euler::nearest_turn;
use crate::figure::skeleton::Skeleton;
use crate::model::InputError;
use crate::model::body::Body;

/// Lowest frame rate of the frame samplers and exports (frames/s), as the command line allows.
pub const MIN_FPS: f64 = 0.001;
/// Highest frame rate of the frame samplers and exports (frames/s), as the command line allows.
pub const MAX_FPS: f64 = 10_000.0;

/// The export file formats, chosen by the file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `.csv`: one row per frame, clinical angles in degrees.
    Csv,
    /// `.mot`: OpenSim motion (storage) file.
    Mot,
    /// `.sto`: OpenSim storage file, the same content as `.mot`.
    Sto,
    /// `.bvh`: Biovision hierarchy, Y up, metres.
    Bvh,
}

impl Format {
    /// The format named by `path`'s extension (case-insensitive): `.csv`, `.mot`, `.sto`, `.bvh`.
    pub fn from_path(path: &Path) -> Result<Format, ExportError> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("csv") => Ok(Format::Csv),
            Some("mot") => Ok(Format::Mot),
            Some("sto") => Ok(Format::Sto),
            Some("bvh") => Ok(Format::Bvh),
            _ => Err(ExportError::UnknownFormat {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// Choices that only some formats use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// BVH: keep the root over the origin in the walking direction of an unplaced walk: its
    /// translation along the world x axis is dropped (height and sideways sway remain). A walk
    /// placed with a heading (`figure::Placement`) keeps its other horizontal motion; export it
    /// unplaced for an in-place clip (`docs/export.md`).
    pub in_place: bool,
    /// `.mot` / `.sto`: the OpenSim model whose coordinates are written.
    pub opensim_model: OpenSimModel,
}

/// One frame as the writers see it: the landmarks, their segment frames and (made when first
/// asked for: BVH does not use them) clinical angles, the pelvis rotation continuous with the
/// landmarks' heading (not wrapped at ±180°).
pub(crate) struct FrameData<'a> {
    pub index: usize,
    pub landmarks: &'a Landmarks,
    pub skeleton: Skeleton,
    clinical: OnceCell<Clinical>,
}

impl FrameData<'_> {
    /// The frame's clinical angles.
    pub fn clinical(&self) -> &Clinical {
        self.clinical.get_or_init(|| {
            let mut c = self
                .skeleton
                .clinical(self.landmarks.time, self.landmarks.step);
            // the landmarks' heading is continuous; the decomposition's lies in (−π, π]
            c.pelvis_rotation = nearest_turn(c.pelvis_rotation, self.landmarks.pelvis_rotation);
            c
        })
    }
}

/// A format's row and header writers.
pub(crate) trait RowWriter {
    /// Whether the header holds the row count (`.mot`'s `nRows`, BVH's `Frames:`).
    fn counts_rows(&self) -> bool {
        true
    }
    /// Append one frame's row, with its line end, to `out` (numbers by [`number`]). An error is a
    /// frame the format cannot represent.
    fn row(&mut self, out: &mut Vec<u8>, frame: &FrameData) -> Result<(), ExportError>;
    /// Write everything before the rows, knowing how many rows there are.
    fn header(&self, out: &mut dyn Write, rows: usize) -> io::Result<()>;
}

/// Write `frames` to `path` in `format`: `.csv` (clinical angles, one row per frame), `.mot` /
/// `.sto` (OpenSim coordinates of `options.opensim_model`), `.bvh` (frame time 1/`fps`, root
/// in place if `options.in_place`). The frames' times must increase strictly (for BVH: one frame
/// every 1/fps); `body` gives the segment lengths. Written whole or not at all.
pub fn write<I>(
    path: &Path,
    format: Format,
    body: &Body,
    fps: f64,
    frames: I,
    options: &Options,
) -> Result<()>
where
    I: IntoIterator<Item = Landmarks>,
{
    let frames = frames.into_iter().map(Ok::<_, Error>);
    try_write(path, format, body, fps, frames, options)
}

/// [`write`](fn@write) for frames that may fail to be made (e.g. `figure::frames`): the first
/// error is returned and no file is written.
pub fn try_write<I, E>(
    path: &Path,
    format: Format,
    body: &Body,
    fps: f64,
    frames: I,
    options: &Options,
) -> Result<()>
where
    I: IntoIterator<Item = Result<Landmarks, E>>,
    Error: From<E>,
{
    InputError::check_range("fps", fps, 1e-3, 1e6, "frames/s")?;
    match format {
        Format::Csv => rows::run(path, body, frames, csv::FrameCsv::new()),
        Format::Mot | Format::Sto => rows::run(
            path,
            body,
            frames,
            opensim::Storage::new(options.opensim_model, body),
        ),
        Format::Bvh => rows::run(
            path,
            body,
            frames,
            bvh::BvhWriter::new(body, fps, options.in_place),
        ),
    }
}
