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
    /// The poulaine of `walk`'s last complete gait cycle ([`cycle_frames`]) and those frames.
    pub fn from_walk(walk: &Walk, fps: f64) -> crate::Result<(Self, Vec<Landmarks>)> {
        let (frames, t0, period) = cycle_frames(walk, fps)?;
        Ok((Self::from_frames(&frames, t0, t0 + period)?, frames))
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
        };
        t.check(Path::new("(frames)"))?;
        Ok(t)
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
        if self.time[0].abs() > 1e-9 {
            return Err(bad(format!("the first time is {} s, not 0", self.time[0])));
        }
        for (i, w) in self.time.windows(2).enumerate() {
            if !(w[1] > w[0]) {
                return Err(bad(format!(
                    "row {}: the times must increase strictly",
                    i + 2
                )));
            }
        }
        if !(self.time[n - 1] < self.period) {
            return Err(bad(format!(
                "the last time {} s is not below the period {} s",
                self.time[n - 1],
                self.period
            )));
        }
        let finite = |p: &[f64; 3]| p.iter().all(|v| v.is_finite());
        if let Some(i) = (0..n).find(|&i| !finite(&self.right[i]) || !finite(&self.left[i])) {
            return Err(bad(format!("row {}: a coordinate is not finite", i + 1)));
        }
        Ok(())
    }
}
