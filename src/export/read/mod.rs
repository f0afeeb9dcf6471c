//! Motion files read back into clinical frames for the quality criteria (`klaw evaluate`,
//! `docs/criteria.md`): klaw's frame CSV ([`frame_csv`], a measured walk in the same columns)
//! and OpenSim storage ([`storage`], `.mot` / `.sto` with gait2392's or Rajagopal 2015's
//! coordinate names). The readers are the inverses of the writers beside them, whose column and
//! coordinate definitions they share (as the BVH parser does), so they live with the exports.
//!
//! Every number must parse and be finite, the times increase strictly, the rows have the
//! header's width; otherwise [`InputError::Malformed`] names the file, the line and what was
//! expected. Needed: the time and the paper's eleven angles (pelvis tilt, list, rotation; hip
//! flexion, adduction, rotation and knee flexion of each leg). Optional: the step index (the
//! heel strikes; without it they are found from the kinematics), the pelvis position (without
//! it no C3 and no pelvis-height norm), the lumbar angles (without them 0: the trunk follows the
//! pelvis), the ankle dorsiflexion (without it no ankle norm). Other columns are not read.
pub mod frame_csv;
pub mod report;
pub mod storage;

use std::path::Path;

use crate::analysis::criteria::heel_strikes::{self, HeelStrikes};
use crate::analysis::criteria::{CriteriaFrames, CriteriaParameters};
use crate::error::{Error, Result};
use crate::figure::clinical::Clinical;
use crate::model::InputError;
use crate::model::body::Body;

/// Why a motion file cannot be read (the reason of an [`InputError::Malformed`]).
#[derive(Debug, thiserror::Error)]
pub enum MotionFileError {
    /// A path whose extension names no motion format read here.
    #[error(
        "unrecognised extension: a motion file is klaw's frame CSV (.csv) or OpenSim storage \
         (.mot, .sto)"
    )]
    Extension,
    /// A needed column absent from the header.
    #[error("line {line}: no column `{name}`; the file needs {needed}")]
    MissingColumn {
        /// The header's line.
        line: usize,
        /// The column.
        name: String,
        /// Every needed column.
        needed: String,
    },
    /// A column named twice.
    #[error("line {line}: column `{name}` appears twice")]
    RepeatedColumn {
        /// The header's line.
        line: usize,
        /// The column.
        name: String,
    },
    /// A row of another width than the header.
    #[error("line {line}: {found} values where the header names {expected} columns")]
    RowWidth {
        /// The row's line.
        line: usize,
        /// Its values.
        found: usize,
        /// The header's columns.
        expected: usize,
    },
    /// A cell that is not a finite number.
    #[error("line {line}: {column} `{cell}` is not a finite number")]
    NotANumber {
        /// The row's line.
        line: usize,
        /// The cell's column.
        column: String,
        /// The cell's text.
        cell: String,
    },
    /// A step index that is not a whole number ≥ 0.
    #[error("line {line}: step `{cell}` is not a whole number ≥ 0")]
    Step {
        /// The row's line.
        line: usize,
        /// The cell's text.
        cell: String,
    },
    /// A time not after the previous row's.
    #[error("line {line}: time {time} s does not follow the previous row's {previous} s")]
    Time {
        /// The row's line.
        line: usize,
        /// Its time (s).
        time: f64,
        /// The previous row's (s).
        previous: f64,
    },
    /// No data row.
    #[error("no rows after the header")]
    NoRows,
    /// An OpenSim header that cannot be read.
    #[error("line {line}: {reason}")]
    Header {
        /// The line.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// A CSV the reader cannot parse.
    #[error(transparent)]
    Csv(#[from] csv::Error),
}

/// A motion file read for the criteria.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionFile {
    /// The frames and heel strikes.
    pub motion: CriteriaFrames,
    /// What the file is, in words: `klaw frame CSV`, `OpenSim storage (gait2392)`.
    pub format: String,
    /// Where the heel strikes come from, in words.
    pub heel_strikes_from: &'static str,
    /// The optional quantities the file lacks and what that leaves out, in words.
    pub absent: Vec<&'static str>,
    /// The number of steps the `step` column counts (the largest index + 1), if it has one.
    pub steps: Option<usize>,
}

/// The frames of a file before the heel strikes are found, and what it lacks.
pub(crate) struct Frames {
    pub frames: Vec<Clinical>,
    pub format: String,
    pub has_steps: bool,
    pub absent: Vec<&'static str>,
}

/// Read `path` (klaw's frame CSV or OpenSim storage, by the extension) for the criteria of
/// `body`: its frames, and its heel strikes from the `step` column when there is one, else from
/// the kinematics (`analysis::criteria::heel_strikes`). Errors: reading the file
/// ([`Error::Io`]), a malformed file ([`InputError::Malformed`] with a [`MotionFileError`]).
pub fn read_motion(
    path: &Path,
    body: &Body,
    parameters: &CriteriaParameters,
) -> Result<MotionFile> {
    let malformed = |e: MotionFileError| Error::from(InputError::malformed("motion file", path, e));
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let parse = match ext.as_deref() {
        Some("csv") => frame_csv::parse,
        Some("mot" | "sto") => |text: &str, body: &Body| storage::parse(text, body),
        _ => return Err(malformed(MotionFileError::Extension)),
    };
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        action: "reading",
        path: path.to_path_buf(),
        source,
    })?;
    let f = parse(&text, body).map_err(malformed)?;
    let (heel_strikes, from): (HeelStrikes, _) = if f.has_steps {
        (
            heel_strikes::from_steps(&f.frames),
            "the step column (to the frame)",
        )
    } else {
        let h = heel_strikes::from_kinematics(&f.frames, body, parameters.heel_strike_window);
        (
            h,
            "the kinematics (the ankle's foremost position ahead of the pelvis)",
        )
    };
    let steps = f
        .has_steps
        .then(|| f.frames.iter().map(|c| c.step + 1).max().unwrap_or(0));
    Ok(MotionFile {
        motion: CriteriaFrames {
            frames: f.frames,
            heel_strikes,
        },
        format: f.format,
        heel_strikes_from: from,
        absent: f.absent,
        steps,
    })
}

/// A table of numbers read from a file: column names, rows and their lines (from 1).
pub(crate) struct Table {
    pub names: Vec<String>,
    pub header_line: usize,
    pub rows: Vec<Vec<f64>>,
    pub lines: Vec<usize>,
}

impl Table {
    /// Check the names (none twice) and the rows (width, finite numbers, increasing time in
    /// column `time`); `cells` are the rows' texts.
    pub(crate) fn new(
        names: Vec<String>,
        header_line: usize,
        cells: Vec<(usize, Vec<String>)>,
        time: &str,
    ) -> Result<Table, MotionFileError> {
        for (i, n) in names.iter().enumerate() {
            if names[..i].contains(n) {
                return Err(MotionFileError::RepeatedColumn {
                    line: header_line,
                    name: n.clone(),
                });
            }
        }
        let t = names.iter().position(|n| n == time);
        let mut rows = Vec::with_capacity(cells.len());
        let mut lines = Vec::with_capacity(cells.len());
        for (line, row) in cells {
            if row.len() != names.len() {
                return Err(MotionFileError::RowWidth {
                    line,
                    found: row.len(),
                    expected: names.len(),
                });
            }
            let values = row
                .iter()
                .zip(&names)
                .map(|(cell, name)| {
                    cell.trim()
                        .parse::<f64>()
                        .ok()
                        .filter(|v| v.is_finite())
                        .ok_or_else(|| MotionFileError::NotANumber {
                            line,
                            column: name.clone(),
                            cell: cell.trim().to_string(),
                        })
                })
                .collect::<Result<Vec<f64>, _>>()?;
            if let Some(t) = t
                && let Some(previous) = rows.last().map(|r: &Vec<f64>| r[t])
                && values[t] <= previous
            {
                return Err(MotionFileError::Time {
                    line,
                    time: values[t],
                    previous,
                });
            }
            rows.push(values);
            lines.push(line);
        }
        if rows.is_empty() {
            return Err(MotionFileError::NoRows);
        }
        Ok(Table {
            names,
            header_line,
            rows,
            lines,
        })
    }

    /// The index of column `name`, if any.
    pub(crate) fn column(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// The indices of `needed`, or [`MotionFileError::MissingColumn`] for the first absent.
    pub(crate) fn needed(&self, needed: &[String]) -> Result<Vec<usize>, MotionFileError> {
        needed
            .iter()
            .map(|name| {
                self.column(name)
                    .ok_or_else(|| MotionFileError::MissingColumn {
                        line: self.header_line,
                        name: name.clone(),
                        needed: needed.join(", "),
                    })
            })
            .collect()
    }
}

/// Set the angle `name` (a column of `figure::clinical::angle_columns`, one of the pose's or an
/// ankle's dorsiflexion) of `c` to `v` (rad).
pub(crate) fn set_angle(c: &mut Clinical, name: &str, v: f64) {
    let (leg, base) = match name.rsplit_once('_') {
        Some((base, "r")) => (Some(&mut c.right), base),
        Some((base, "l")) => (Some(&mut c.left), base),
        _ => (None, name),
    };
    match (leg, base) {
        (Some(leg), "hip_flexion") => leg.hip.flexion = v,
        (Some(leg), "hip_adduction") => leg.hip.adduction = v,
        (Some(leg), "hip_rotation") => leg.hip.rotation = v,
        (Some(leg), "knee_flexion") => leg.knee.flexion = v,
        (Some(leg), "ankle_dorsiflexion") => leg.ankle.flexion = v,
        (None, "pelvis_tilt") => c.pelvis_tilt = v,
        (None, "pelvis_list") => c.pelvis_list = v,
        (None, "pelvis_rotation") => c.pelvis_rotation = v,
        (None, "lumbar_extension") => c.lumbar_extension = v,
        (None, "lumbar_bending") => c.lumbar_bending = v,
        (None, "lumbar_rotation") => c.lumbar_rotation = v,
        _ => unreachable!("not an angle the criteria read: {name}"),
    }
}

/// What a file without the pelvis position, the lumbar angles or the ankles lacks, in words.
pub(crate) fn absent(position: bool, lumbar: bool, ankles: bool) -> Vec<&'static str> {
    [
        (
            position,
            "the pelvis position: no C3 (power) and no pelvis-height norm",
        ),
        (
            lumbar,
            "the lumbar angles: taken as 0 (the trunk follows the pelvis)",
        ),
        (
            ankles,
            "the ankle dorsiflexion: no ankle norm, no ankle RMS",
        ),
    ]
    .into_iter()
    .filter(|(has, _)| !has)
    .map(|(_, what)| what)
    .collect()
}
