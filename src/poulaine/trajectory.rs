//! A poulaine as sampled (Pronost et al. §3): both ankles relative to the pelvis centre over one
//! gait cycle, in the frame that follows the walking direction and does not turn with the
//! pelvis (klaw's axes: x forward, y up, z to the right; the paper's x, y, z are klaw's x, −z,
//! y). Extracted from any walk's frames, or read from a CSV file of measured data (the layout is
//! in `docs/ik.md`).
use std::path::Path;

use crate::figure::Landmarks;
use crate::ik::Ankles;
use crate::model::InputError;
use crate::poulaine::error::PoulaineError;
use crate::simulation::Walk;

/// One gait cycle of both ankles relative to the pelvis centre (m), sampled at `time`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Trajectory {
    /// The sample times from the cycle's start (s): 0 first, strictly increasing, below
    /// `period`.
    pub time: Vec<f64>,
    /// The cycle's duration T (s): the sample after the last is the first, at T.
    pub period: f64,
    /// The right ankle (x forward, y up, z right).
    pub right: Vec<[f64; 3]>,
    /// The left ankle.
    pub left: Vec<[f64; 3]>,
    /// The pelvis's forward speed at each sample (m/s), where known: the "speed profile" that
    /// comes with a poulaine (§3.1); a klaw walk's, or the CSV's optional last column.
    pub pelvis_speed: Option<Vec<f64>>,
}

/// The CSV header of a poulaine file.
pub const CSV_HEADER: [&str; 7] = [
    "time_s",
    "right_x_m",
    "right_y_m",
    "right_z_m",
    "left_x_m",
    "left_y_m",
    "left_z_m",
];

/// The CSV's optional last column: the pelvis's forward speed.
pub const SPEED_COLUMN: &str = "pelvis_speed_m_s";

/// The rate a walk's poulaine is sampled at unless asked otherwise: the paper's capture, a
/// Vicon 370 "sampled at 60Hz" (Pronost et al. §4).
pub const CAPTURE_RATE: f64 = 60.0;

/// The figure of `walk`'s last complete gait cycle, right heel strike to right heel strike (a
/// walk's even steps start on the right), at N = round(T · fps) uniform instants
/// t₀ + i T / N; and t₀ and T. Err: a walk of fewer than 2 steps, or a rate out of [10, 1000].
pub fn cycle_frames(walk: &Walk, fps: f64) -> crate::Result<(Vec<Landmarks>, f64, f64)> {
    InputError::check_range("poulaine frame rate", fps, 10.0, 1000.0, "frames/s")?;
    let steps = &walk.engine().steps;
    if steps.len() < 2 {
        let reason = format!("{} step: a gait cycle needs 2", steps.len());
        return Err(InputError::bad_value("steps", reason).into());
    }
    let first = 2 * ((steps.len() - 2) / 2);
    let t0 = steps[first].t_start;
    let t1 = steps.get(first + 2).map_or(walk.duration(), |s| s.t_start);
    let period = t1 - t0;
    let n = (period * fps).round().max(8.0) as usize;
    let frames = (0..n)
        .map(|i| walk.figure_at(t0 + i as f64 * period / n as f64))
        .collect::<crate::Result<Vec<_>>>()?;
    Ok((frames, t0, period))
}

impl Trajectory {
    /// The poulaine of `walk`'s last complete gait cycle ([`cycle_frames`]) and those frames,
    /// with the pelvis's forward speed at each sample (central differences of its position
    /// over ±0.1 ms).
    pub fn from_walk(walk: &Walk, fps: f64) -> crate::Result<(Self, Vec<Landmarks>)> {
        let (frames, t0, period) = cycle_frames(walk, fps)?;
        let mut t = Self::from_frames(&frames, t0, t0 + period)?;
        let h = 1e-4;
        let speed = frames
            .iter()
            .map(|f| {
                let at = |t: f64| walk.figure_at(t).map(|lm| lm.pelvis[0]);
                Ok((at(f.time + h)? - at(f.time - h)?) / (2.0 * h))
            })
            .collect::<crate::Result<Vec<f64>>>()?;
        t.pelvis_speed = Some(speed);
        Ok((t, frames))
    }

    /// The cycle of `frames` from the walk time `start` (inclusive) to `end` (exclusive, the
    /// next cycle's start): ankle − pelvis centre of each frame, for a walk along the world's
    /// x axis (klaw's walks; a placed walk must be turned back first).
    pub fn from_frames(frames: &[Landmarks], start: f64, end: f64) -> Result<Self, PoulaineError> {
        let eps = 1e-9;
        let kept: Vec<&Landmarks> = frames
            .iter()
            .filter(|f| f.time >= start - eps && f.time < end - eps)
            .collect();
        if kept.len() < 8 {
            return Err(PoulaineError::TooFewSamples {
                samples: kept.len(),
                min: 8,
            });
        }
        let rel = |a: [f64; 3], p: [f64; 3]| [a[0] - p[0], a[1] - p[1], a[2] - p[2]];
        let t0 = kept[0].time;
        let t = Trajectory {
            time: kept.iter().map(|f| f.time - t0).collect(),
            period: end - t0,
            right: kept.iter().map(|f| rel(f.right.ankle, f.pelvis)).collect(),
            left: kept.iter().map(|f| rel(f.left.ankle, f.pelvis)).collect(),
            pelvis_speed: None,
        };
        t.check(Path::new("(frames)"))?;
        Ok(t)
    }

    /// Read a poulaine CSV file (`docs/ik.md`): lines starting with `#` skipped (comments: a
    /// measured poulaine's source), the header [`CSV_HEADER`], optionally followed by
    /// [`SPEED_COLUMN`], one row per sample of one cycle, uniform in time from 0; the period
    /// is the number of rows × the step.
    pub fn read_csv(path: &Path) -> crate::Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|source| crate::Error::Io {
            action: "reading",
            path: path.to_path_buf(),
            source,
        })?;
        Ok(Self::parse_csv(&text, path)?)
    }

    /// [`Self::read_csv`] of the text of `path`.
    pub fn parse_csv(text: &str, path: &Path) -> Result<Self, PoulaineError> {
        let bad = |reason: String| PoulaineError::Malformed {
            path: path.to_path_buf(),
            reason,
        };
        let mut reader = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        let header = reader
            .headers()
            .map_err(|e| bad(format!("not a CSV file: {e}")))?
            .clone();
        let with_speed = header.len() == CSV_HEADER.len() + 1;
        let names: Vec<&str> = CSV_HEADER
            .iter()
            .copied()
            .chain(with_speed.then_some(SPEED_COLUMN))
            .collect();
        if header.iter().ne(names.iter().copied()) {
            return Err(bad(format!(
                "the header must be {}[,{SPEED_COLUMN}]",
                CSV_HEADER.join(",")
            )));
        }
        let mut rows: Vec<[f64; 8]> = Vec::new();
        for (i, record) in reader.records().enumerate() {
            let record = record.map_err(|e| bad(format!("row {}: {e}", i + 2)))?;
            let mut row = [0.0; 8];
            for (k, field) in record.iter().enumerate() {
                row[k] = field.trim().parse().map_err(|_| {
                    bad(format!(
                        "row {}, column {}: `{field}` is not a number",
                        i + 2,
                        names[k]
                    ))
                })?;
            }
            rows.push(row);
        }
        if rows.len() < 2 {
            return Err(PoulaineError::TooFewSamples {
                samples: rows.len(),
                min: 8,
            });
        }
        let step = rows[1][0] - rows[0][0];
        let t = Trajectory {
            time: rows.iter().map(|r| r[0]).collect(),
            period: step * rows.len() as f64,
            right: rows.iter().map(|r| [r[1], r[2], r[3]]).collect(),
            left: rows.iter().map(|r| [r[4], r[5], r[6]]).collect(),
            pelvis_speed: with_speed.then(|| rows.iter().map(|r| r[7]).collect()),
        };
        t.check(path)?;
        if t.uniform_step().is_none() {
            return Err(bad(
                "the samples must be uniform in time (one step between every two rows)".into(),
            ));
        }
        Ok(t)
    }

    /// Write the poulaine as CSV ([`Self::read_csv`]'s layout, the speed column where the
    /// pelvis's speed is known), whole or not at all.
    pub fn write_csv(&self, path: &Path) -> crate::Result<()> {
        // the fields name the columns: CSV_HEADER
        #[derive(serde::Serialize)]
        struct Row {
            time_s: f64,
            right_x_m: f64,
            right_y_m: f64,
            right_z_m: f64,
            left_x_m: f64,
            left_y_m: f64,
            left_z_m: f64,
            #[serde(skip_serializing_if = "Option::is_none")]
            pelvis_speed_m_s: Option<f64>,
        }
        let rows: Vec<Row> = (0..self.time.len())
            .map(|i| {
                let (r, l) = (self.right[i], self.left[i]);
                Row {
                    time_s: self.time[i],
                    right_x_m: r[0],
                    right_y_m: r[1],
                    right_z_m: r[2],
                    left_x_m: l[0],
                    left_y_m: l[1],
                    left_z_m: l[2],
                    pelvis_speed_m_s: self.pelvis_speed.as_ref().map(|s| s[i]),
                }
            })
            .collect();
        crate::export::write_rows_csv(path, &CSV_HEADER, &rows)
    }

    /// The walking speed: the mean of the pelvis's speed over the cycle's samples where it is
    /// known (exact but for the rule's error: the mean of a periodic function at uniform samples
    /// over a whole period), else [`Self::ankle_speed`].
    pub fn speed(&self) -> f64 {
        match &self.pelvis_speed {
            Some(s) => s.iter().sum::<f64>() / s.len() as f64,
            None => self.ankle_speed(),
        }
    }

    /// The walking speed from the ankles alone: the supporting foot stands still, so its ankle
    /// moves back relative to the pelvis at the body's speed; v is the slope of x against time
    /// (least squares) over the middle half of each ankle's support (most forward to most
    /// backward sample), the mean of both ankles. The pelvis is slowest in mid-stance, so this
    /// reads low (5–8 % on klaw's walks, `docs/ik.md`).
    pub fn ankle_speed(&self) -> f64 {
        let one = |leg: &[[f64; 3]]| {
            let n = leg.len();
            let arg = |sign: f64| {
                (0..n).fold(0, |b, i| {
                    if sign * leg[i][0] > sign * leg[b][0] {
                        i
                    } else {
                        b
                    }
                })
            };
            let (f, b) = (arg(1.0), arg(-1.0));
            let span = (b + n - f) % n;
            let pts: Vec<(f64, f64)> = (span / 4..=3 * span / 4)
                .map(|k| {
                    let i = f + k;
                    let t = self.time[i % n] + if i >= n { self.period } else { 0.0 };
                    (t, leg[i % n][0])
                })
                .collect();
            let m = pts.len() as f64;
            let (mt, mx) = pts
                .iter()
                .fold((0.0, 0.0), |(a, b), p| (a + p.0 / m, b + p.1 / m));
            let (sxy, sxx) = pts.iter().fold((0.0, 0.0), |(a, b), p| {
                (a + (p.0 - mt) * (p.1 - mx), b + (p.0 - mt) * (p.0 - mt))
            });
            -sxy / sxx
        };
        0.5 * (one(&self.right) + one(&self.left))
    }

    /// The ankles' trace length along x over the cycle (max x − min x), the mean of both (m):
    /// the samples' counterpart of the model's [`crate::poulaine::Axes::trace`].
    pub fn trace(&self) -> f64 {
        let range = |leg: &[[f64; 3]]| {
            let (lo, hi) = leg
                .iter()
                .fold((f64::MAX, f64::MIN), |(l, h), p| (l.min(p[0]), h.max(p[0])));
            hi - lo
        };
        0.5 * (range(&self.right) + range(&self.left))
    }

    /// Half the feet's spacing in support (m): each ankle's mean |z| over its samples from its
    /// most forward to its most backward, the mean of both; the samples' counterpart of the
    /// model's [`crate::poulaine::Axes::spacing`].
    pub fn spacing(&self) -> f64 {
        let one = |leg: &[[f64; 3]]| {
            let n = leg.len();
            let by_x = |a: &usize, b: &usize| leg[*a][0].total_cmp(&leg[*b][0]);
            let front = (0..n).max_by(by_x).expect("samples");
            let back = (0..n).min_by(by_x).expect("samples");
            let count = (back + n - front) % n + 1;
            (0..count)
                .map(|j| leg[(front + j) % n][2].abs())
                .sum::<f64>()
                / count as f64
        };
        0.5 * (one(&self.right) + one(&self.left))
    }

    /// The ankle targets of the inverse kinematics, one per sample.
    pub fn targets(&self) -> Vec<Ankles> {
        self.right
            .iter()
            .zip(&self.left)
            .map(|(r, l)| Ankles::new(r[0], r[1], r[2], l[0], l[1], l[2]))
            .collect()
    }

    /// Whether the samples are uniform in time (within 1e-6 of the mean step, the step from
    /// the last sample to the period included): the inverse kinematics needs one frame period.
    pub fn uniform_step(&self) -> Option<f64> {
        let n = self.time.len();
        let dt = self.period / n as f64;
        let ok = self
            .time
            .iter()
            .enumerate()
            .all(|(i, &t)| (t - i as f64 * dt).abs() <= 1e-6 * self.period.max(1.0));
        ok.then_some(dt)
    }

    /// Check the layout: equal lengths, at least 8 samples, times from 0 strictly increasing
    /// below the period, every value finite.
    pub fn check(&self, path: &Path) -> Result<(), PoulaineError> {
        let bad = |reason: String| PoulaineError::Malformed {
            path: path.to_path_buf(),
            reason,
        };
        let n = self.time.len();
        if n < 8 {
            return Err(PoulaineError::TooFewSamples { samples: n, min: 8 });
        }
        if self.right.len() != n || self.left.len() != n {
            return Err(bad("the ankles and the times have different lengths".into()));
        }
        if !(self.period.is_finite() && self.period > 0.0) {
            return Err(bad(format!(
                "the period {} s must be positive",
                self.period
            )));
        }
        if let Some(i) = self.time.iter().position(|t| !t.is_finite()) {
            return Err(bad(format!("row {}: the time is not finite", i + 1)));
        }
        if self.time[0].abs() > 1e-9 {
            return Err(bad(format!("the first time is {} s, not 0", self.time[0])));
        }
        for (i, w) in self.time.windows(2).enumerate() {
            if w[1].is_nan() || w[1] <= w[0] {
                return Err(bad(format!(
                    "row {}: the times must increase strictly",
                    i + 2
                )));
            }
        }
        if self.time[n - 1].is_nan() || self.time[n - 1] >= self.period {
            return Err(bad(format!(
                "the last time {} s is not below the period {} s",
                self.time[n - 1],
                self.period
            )));
        }
        if let Some(s) = &self.pelvis_speed {
            if s.len() != n {
                return Err(bad(
                    "the pelvis speeds and the times have different lengths".into(),
                ));
            }
            if let Some(i) = s.iter().position(|v| !v.is_finite()) {
                return Err(bad(format!(
                    "row {}: the pelvis speed is not finite",
                    i + 1
                )));
            }
        }
        let finite = |p: &[f64; 3]| p.iter().all(|v| v.is_finite());
        if let Some(i) = (0..n).find(|&i| !finite(&self.right[i]) || !finite(&self.left[i])) {
            return Err(bad(format!("row {}: a coordinate is not finite", i + 1)));
        }
        Ok(())
    }
}
