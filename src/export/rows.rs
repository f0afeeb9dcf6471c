//! A motion file written as its frames come: the caller's thread makes the frames (for `klaw
//! walk`, simulates the walk), a second thread turns them into rows and writes them, so the two
//! overlap (what this saves: `docs/engine.md`, "Output speed"). Frames travel in batches through
//! a bounded queue, so memory stays bounded whatever the walk's length.
//!
//! Errors are those of the first frame that fails, as if one thread did everything: frames reach
//! the writer in order, and a frame the caller's iterator fails to make comes after every frame
//! the writer was given.
use std::cell::OnceCell;
use std::path::Path;
use std::sync::mpsc;

use super::file::write_error;
use super::spool::Spool;
use super::{ExportError, FrameData, RowWriter};
use crate::error::{Error, Result};
use crate::figure::Landmarks;
use crate::figure::skeleton::Skeleton;
use crate::model::body::Body;

/// Frames per message to the writer thread.
const BATCH: usize = 64;

/// Batches on their way to the writer thread at most.
const QUEUE: usize = 4;

/// Write `frames` to `path` with `writer` (see the module doc). The rows stream into a spool in
/// the target's directory. The header goes first when it can: for a format without a row count,
/// or when the frames' size hint gives the count (an exact upper bound, as the walk's stream and
/// `figure::frames` give); if that count is then met, the spool is the file. Otherwise the header
/// is written to the target and the rows copied behind it.
pub(super) fn run<I, E, W>(path: &Path, body: &Body, frames: I, writer: W) -> Result<()>
where
    I: IntoIterator<Item = Result<Landmarks, E>>,
    Error: From<E>,
    W: RowWriter + Send,
{
    let frames = frames.into_iter();
    let count = frames.size_hint().1;
    let header_first = !writer.counts_rows() || count.is_some();
    let mut rows = Rows {
        path,
        body,
        spool: Spool::create(path, header_first)?,
        writer,
        count,
        header_first,
        header: Vec::new(),
        row: Vec::new(),
        rows: 0,
        last_time: f64::NEG_INFINITY,
    };
    std::thread::scope(|scope| {
        let (send, receive) = mpsc::sync_channel::<Vec<Landmarks>>(QUEUE);
        let worker = scope.spawn(move || -> Result<Rows<'_, W>> {
            for batch in receive {
                for lm in &batch {
                    rows.push(lm)?;
                }
            }
            Ok(rows)
        });
        let made = send_frames(frames, &send);
        drop(send);
        let written = worker
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        // the writer's error is of an earlier frame than the iterator's
        written?.finish(made)
    })
}

/// Send `frames` in batches until they end, one fails (its error is returned, after the frames
/// before it are sent) or the writer stops (it failed: its error is the one to report).
fn send_frames<I, E>(frames: I, send: &mpsc::SyncSender<Vec<Landmarks>>) -> Result<()>
where
    I: Iterator<Item = Result<Landmarks, E>>,
    Error: From<E>,
{
    let mut batch = Vec::with_capacity(BATCH);
    for lm in frames {
        match lm {
            Ok(lm) => batch.push(lm),
            Err(e) => {
                // the frames before it are written first: one of them may fail before it
                let _ = send.send(batch);
                return Err(e.into());
            }
        }
        if batch.len() == BATCH {
            let full = std::mem::replace(&mut batch, Vec::with_capacity(BATCH));
            if send.send(full).is_err() {
                return Ok(());
            }
        }
    }
    if !batch.is_empty() {
        // an error here is the writer's, returned by it
        let _ = send.send(batch);
    }
    Ok(())
}

/// The writer thread's state: the rows written so far and where they go.
struct Rows<'a, W> {
    path: &'a Path,
    body: &'a Body,
    spool: Spool,
    writer: W,
    /// The row count the frames' size hint gave.
    count: Option<usize>,
    /// The header is written before the first row.
    header_first: bool,
    /// The header written first.
    header: Vec<u8>,
    /// One row, in a buffer kept across the rows.
    row: Vec<u8>,
    rows: usize,
    last_time: f64,
}

impl<W: RowWriter> Rows<'_, W> {
    /// Write the next frame's row (and, before the first, the header if it goes first).
    fn push(&mut self, lm: &Landmarks) -> Result<()> {
        let frame = frame_data(self.rows, lm, self.body, &mut self.last_time)?;
        self.row.clear();
        self.writer.row(&mut self.row, &frame)?;
        if self.rows == 0 && self.header_first {
            // after the first row is made: a header may name its columns (`.mot`); a format
            // without a row count ignores it
            self.writer
                .header(&mut self.header, self.count.unwrap_or(0))
                .map_err(|e| write_error(self.path, e))?;
            self.spool.write(&self.header)?;
        }
        self.spool.write(&self.row)?;
        self.rows += 1;
        Ok(())
    }

    /// After the last row: `made` is how making the frames ended (an error is the one to report,
    /// and no file is written); the file is finished from the spool.
    fn finish(mut self, made: Result<()>) -> Result<()> {
        made?;
        if self.rows == 0 {
            return Err(ExportError::NoFrames {
                path: self.path.to_path_buf(),
            }
            .into());
        }
        if self.header_first && (!self.writer.counts_rows() || self.count == Some(self.rows)) {
            return self.spool.into_target();
        }
        let skip = self.header.len() as u64;
        self.header.clear();
        self.writer
            .header(&mut self.header, self.rows)
            .map_err(|e| write_error(self.path, e))?;
        self.spool.copy_behind(&self.header, skip)
    }
}

/// Frame `index` as the writers see it; its time must follow `last_time` (then its own).
fn frame_data<'a>(
    index: usize,
    lm: &'a Landmarks,
    body: &Body,
    last_time: &mut f64,
) -> Result<FrameData<'a>> {
    let skeleton = Skeleton::new(lm, body)?;
    if lm.time <= *last_time {
        return Err(ExportError::OutOfOrder {
            frame: index,
            time: lm.time,
            previous: *last_time,
        }
        .into());
    }
    *last_time = lm.time;
    Ok(FrameData {
        index,
        landmarks: lm,
        skeleton,
        clinical: OnceCell::new(),
    })
}
