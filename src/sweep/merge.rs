//! Merging sweep outputs, typically the shards of one sweep, into one file in point order: a
//! k-way merge of the sorted files, byte-identical to the output of the unsharded sweep.
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::io::Write;
use std::path::{Path, PathBuf};

use super::output::{RowReader, malformed};
use crate::error::Result;
use crate::export::file::AtomicFile;
use crate::model::InputError;
use crate::sweep::RowFormat;

/// What a merge did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MergeStats {
    /// Rows written.
    pub rows: usize,
    /// Rows found in more than one input (identical; written once).
    pub duplicates: usize,
    /// Points missing between 0 and the largest point found, and the first few of them.
    pub missing: usize,
    /// The first (at most 10) missing points.
    pub first_missing: Vec<usize>,
    /// Inputs whose last line was cut off (not merged).
    pub cut_off: Vec<PathBuf>,
}

/// Join sweep outputs (typically the shards of one sweep) into `out`, rows in point order,
/// written whole or not at all. All files must have the format of `out` (by extension) and the
/// same columns. A point found in several inputs must have the same row in each (a duplicate is
/// written once and counted); different rows for one point are an error. Points missing below
/// the largest point found are an error unless `allow_missing` (then counted). Points after the
/// largest one cannot be detected: the files do not record the sweep's size.
pub fn merge(out: &Path, inputs: &[PathBuf], allow_missing: bool) -> Result<MergeStats> {
    let format = RowFormat::from_path(out)?;
    if inputs.is_empty() {
        return Err(InputError::bad_value("merge", "no input files").into());
    }
    let mut heads = Heads::open(out, inputs, format)?;
    let mut file = AtomicFile::create(out)?;
    let mut stats = MergeStats::default();
    if format == RowFormat::Csv
        && let Some(c) = heads.readers.iter().find_map(RowReader::columns)
    {
        let line = format.header_line(c);
        file.writer()
            .write_all(line.as_bytes())
            .map_err(|e| file.error(e))?;
    }
    heads.merge_into(&mut file, &mut stats)?;
    stats.cut_off = heads
        .readers
        .iter()
        .filter(|r| r.cut_off)
        .map(|r| r.path.clone())
        .collect();
    if stats.missing > 0 && !allow_missing {
        let list: Vec<String> = stats.first_missing.iter().map(|p| p.to_string()).collect();
        let reason = format!(
            "{} points are missing (first: {}): is a shard missing or unfinished? \
             (--allow-missing writes the rows anyway)",
            stats.missing,
            list.join(", ")
        );
        return Err(InputError::malformed("merge of sweep outputs", out, reason).into());
    }
    file.commit()?;
    Ok(stats)
}

/// The inputs of a merge, read in step: the next row of each, and a heap of their points.
struct Heads<'a> {
    paths: &'a [PathBuf],
    readers: Vec<RowReader>,
    /// (point, input) of every input's next row, smallest first.
    heap: BinaryHeap<Reverse<(usize, usize)>>,
    /// Every input's next row.
    lines: Vec<Option<String>>,
    /// The first columns known, and the input they came from.
    columns: Option<(Vec<String>, usize)>,
}

impl<'a> Heads<'a> {
    /// Open every input (each must have the format of `out`), then read the first row of each.
    fn open(out: &Path, paths: &'a [PathBuf], format: RowFormat) -> Result<Heads<'a>> {
        let mut readers = Vec::with_capacity(paths.len());
        for path in paths {
            if RowFormat::from_path(path)? != format {
                return Err(malformed(
                    path,
                    format!("its format differs from the output's ({})", out.display()),
                ));
            }
            readers.push(RowReader::open(path, format)?);
        }
        let mut heads = Heads {
            paths,
            lines: vec![None; readers.len()],
            readers,
            heap: BinaryHeap::new(),
            columns: None,
        };
        for i in 0..heads.readers.len() {
            heads.pull(i)?;
            // (an empty JSON Lines file is a shard without rows; a CSV one has its header)
            if format == RowFormat::Csv && heads.readers[i].columns().is_none() {
                let reason = "no header line: not a sweep output";
                return Err(malformed(&heads.paths[i], reason.to_string()));
            }
        }
        if heads.heap.is_empty() {
            let reason = "no rows in any input: nothing to merge";
            return Err(malformed(&paths[0], reason.to_string()));
        }
        Ok(heads)
    }

    /// Read input `i`'s next row; its columns must be those of the other inputs.
    fn pull(&mut self, i: usize) -> Result<()> {
        if let Some((p, line)) = self.readers[i].next_row()? {
            self.heap.push(Reverse((p, i)));
            self.lines[i] = Some(line);
        }
        if let Some(c) = self.readers[i].columns() {
            match &self.columns {
                None => self.columns = Some((c.to_vec(), i)),
                Some((first, j)) if first.as_slice() != c => {
                    return Err(malformed(
                        &self.paths[i],
                        format!(
                            "its columns differ from those of {}: not the same sweep",
                            self.paths[*j].display()
                        ),
                    ));
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Write the rows in point order, a point found in several inputs once (its rows must be
    /// the same); count the duplicates and the points missing below the largest.
    fn merge_into(&mut self, file: &mut AtomicFile, stats: &mut MergeStats) -> Result<()> {
        let mut previous: Option<(usize, String, usize)> = None;
        while let Some(Reverse((p, i))) = self.heap.pop() {
            let line = self.lines[i].take().unwrap_or_default();
            match &previous {
                Some((q, text, j)) if *q == p => {
                    if *text != line {
                        return Err(malformed(
                            &self.paths[i],
                            format!(
                                "point {p} differs from its row in {}: not the same sweep",
                                self.paths[*j].display()
                            ),
                        ));
                    }
                    stats.duplicates += 1;
                }
                _ => {
                    let from = previous.as_ref().map_or(0, |(q, _, _)| q + 1);
                    for m in from..p {
                        stats.missing += 1;
                        if stats.first_missing.len() < 10 {
                            stats.first_missing.push(m);
                        }
                    }
                    file.writer()
                        .write_all(line.as_bytes())
                        .map_err(|e| file.error(e))?;
                    stats.rows += 1;
                    previous = Some((p, line, i));
                }
            }
            self.pull(i)?;
        }
        Ok(())
    }
}
