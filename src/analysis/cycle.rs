//! Gait-cycle normalized curves (issue items 8 and 9): values resampled on 0, 1, …, 100 % of the
//! gait cycle and averaged over the steady-state cycles; the clinical angles of every frame
//! ([`cycle_average`], written by `klaw walk --cycle-out`) and the curves of the gait-cycle
//! figure ([`GaitCycle`], drawn by `klaw plot`).
//!
//! Steady state: the cycles between consecutive heel strikes of one leg, less the first `skip` of
//! them (`skip` = 1 drops the first cycle, which starts from the engine's initial conditions), and
//! only those the frames cover completely (first frame at or before the cycle's heel strike, last
//! frame at or after the next one). Each cycle is sampled at t = t_HS + p/100 · (t_HS' − t_HS) by
//! linear interpolation between the two frames around t; the curves are the means over the
//! cycles, sample by sample.
//!
//! Phase of [`GaitCycle`]: the right leg's curves and the pelvis run from right heel strike (0 %)
//! to the next right heel strike (100 %); the left leg's curves from left heel strike to the next
//! left heel strike, so that both legs are read against the same norms ("gait cycle % starts at
//! heel strike of the same leg"): for a symmetric walk the two lie on top of each other.
use serde::Deserialize;

use crate::engine::walker::Walk;
use crate::figure::FigureError;
use crate::figure::clinical::{self, Clinical, angle_columns};
use crate::figure::skeleton::Side;

/// Frame rate at which the walk is sampled before the cycles are averaged (frames/s of walk
/// time): 200 frames/s puts ≥ 2 frames on every 1 % of a cycle slower than 0.5 s.
pub(crate) const CYCLE_FPS: f64 = 200.0;
/// The first `CYCLE_SKIP` cycles of each leg are left out: they start from the engine's initial
/// conditions.
pub(crate) const CYCLE_SKIP: usize = 1;

/// The fewest steps of a walk with a steady cycle (after the `CYCLE_SKIP` skipped) of the right
/// leg, which strikes first (`both_legs` false), or of both legs: a leg's cycle runs between two
/// of its heel strikes, at the starts of every other step, and the walk ends with a heel strike.
pub fn min_steps(both_legs: bool) -> usize {
    2 * CYCLE_SKIP + if both_legs { 4 } else { 3 }
}

/// Cycle-normalized curves: 101 rows (0…100 %) of the column values.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleCurves {
    /// Column names (from [`angle_columns`] for [`cycle_average`]).
    pub columns: Vec<String>,
    /// `rows[p][k]`: column k at p % of the cycle (rad for angles).
    pub rows: Vec<Vec<f64>>,
    /// How many cycles were averaged.
    pub cycles: usize,
}

/// Frames that cannot be averaged over the gait cycle.
#[derive(Debug, thiserror::Error)]
pub enum CycleError {
    /// A frame of the walk cannot be built.
    #[error(transparent)]
    Frame(#[from] FigureError),
    /// Not one time per frame.
    #[error("{times} frame times for {frames} frames")]
    FrameCount {
        /// The frame times given.
        times: usize,
        /// The frames given.
        frames: usize,
    },
    /// A frame with another number of values than the first.
    #[error("frame {frame} has {values} values, frame 0 has {width}")]
    FrameWidth {
        /// The frame's index, from 0.
        frame: usize,
        /// Its number of values.
        values: usize,
        /// The first frame's number of values.
        width: usize,
    },
    /// Frame times not finite and strictly increasing.
    #[error("frame times must be finite and strictly increasing")]
    Times,
    /// Right heel strike times not finite and strictly increasing.
    #[error("right heel strike times must be finite and strictly increasing")]
    HeelStrikes,
    /// No frame was given.
    #[error("no frames to average")]
    NoFrames,
    /// No cycle between two heel strikes, after the first `skip`, lies within the frames'
    /// times [`t_first`, `t_last`] (s).
    #[error(
        "no complete steady-state gait cycle: {strikes} right heel strikes give {} cycles, the \
         first {skip} skipped as the start-up, and the frames cover {t_first} … {t_last} s; \
         walk more steps: a steady cycle of a leg needs {} of its heel strikes, i.e. at least {} \
         steps for the right leg (which strikes first) and {} for both legs",
        strikes.saturating_sub(1), skip + 2, 2 * skip + 3, 2 * skip + 4
    )]
    NoSteadyCycle {
        /// The right heel strikes given.
        strikes: usize,
        /// The cycles skipped as the start-up.
        skip: usize,
        /// The first frame's time (in s).
        t_first: f64,
        /// The last frame's time (in s).
        t_last: f64,
    },
}

/// Average `values` (one row per frame, at `times`) over the steady-state cycles delimited by
/// `right_heel_strikes` (see the module doc). Errors ([`CycleError`]): times or strikes not
/// finite and strictly increasing, rows of unequal length, no complete cycle after skipping
/// `skip`.
pub fn average_cycles(
    times: &[f64],
    values: &[Vec<f64>],
    right_heel_strikes: &[f64],
    skip: usize,
) -> Result<Vec<Vec<f64>>, CycleError> {
    average(times, values, right_heel_strikes, skip).map(|(rows, _)| rows)
}

/// [`average_cycles`], and how many cycles were averaged.
fn average(
    times: &[f64],
    values: &[Vec<f64>],
    right_heel_strikes: &[f64],
    skip: usize,
) -> Result<(Vec<Vec<f64>>, usize), CycleError> {
    let cycles = steady_cycles(times, values, right_heel_strikes, skip)?;
    let sample = |t: f64, k: usize| -> f64 {
        // the last frame at or before t (t is inside [t_first, t_last])
        let i = times.partition_point(|&x| x <= t).saturating_sub(1);
        if i + 1 >= times.len() {
            return values[i][k];
        }
        let (t0, t1) = (times[i], times[i + 1]);
        let u = (t - t0) / (t1 - t0);
        values[i][k] + u * (values[i + 1][k] - values[i][k])
    };
    let width = values.first().map_or(0, Vec::len);
    let mut rows = vec![vec![0.0; width]; 101];
    for &(a, b) in &cycles {
        for (p, row) in rows.iter_mut().enumerate() {
            let t = a + (b - a) * p as f64 / 100.0;
            for (k, cell) in row.iter_mut().enumerate() {
                *cell += sample(t, k);
            }
        }
    }
    let n = cycles.len() as f64;
    for row in &mut rows {
        for cell in row.iter_mut() {
            *cell /= n;
        }
    }
    Ok((rows, cycles.len()))
}

/// The checked input of [`average_cycles`] and its steady-state cycles (start, end), at least one.
fn steady_cycles(
    times: &[f64],
    values: &[Vec<f64>],
    right_heel_strikes: &[f64],
    skip: usize,
) -> Result<Vec<(f64, f64)>, CycleError> {
    if times.len() != values.len() {
        return Err(CycleError::FrameCount {
            times: times.len(),
            frames: values.len(),
        });
    }
    let width = values.first().map_or(0, Vec::len);
    if let Some(i) = values.iter().position(|v| v.len() != width) {
        return Err(CycleError::FrameWidth {
            frame: i,
            values: values[i].len(),
            width,
        });
    }
    let increasing =
        |xs: &[f64]| xs.iter().all(|x| x.is_finite()) && xs.windows(2).all(|w| w[0] < w[1]);
    if !increasing(times) {
        return Err(CycleError::Times);
    }
    if !increasing(right_heel_strikes) {
        return Err(CycleError::HeelStrikes);
    }
    let (Some(&t_first), Some(&t_last)) = (times.first(), times.last()) else {
        return Err(CycleError::NoFrames);
    };
    let cycles: Vec<(f64, f64)> = right_heel_strikes
        .windows(2)
        .skip(skip)
        .map(|w| (w[0], w[1]))
        .filter(|&(a, b)| a >= t_first && b <= t_last)
        .collect();
    if cycles.is_empty() {
        return Err(CycleError::NoSteadyCycle {
            strikes: right_heel_strikes.len(),
            skip,
            t_first,
            t_last,
        });
    }
    Ok(cycles)
}

/// The clinical angles of [`angle_columns`] averaged over the steady-state cycles.
pub fn cycle_average(
    frames: &[Clinical],
    right_heel_strikes: &[f64],
    skip: usize,
) -> Result<CycleCurves, CycleError> {
    let columns = angle_columns();
    let times: Vec<f64> = frames.iter().map(|c| c.time).collect();
    let values: Vec<Vec<f64>> = frames
        .iter()
        .map(|c| columns.iter().map(|col| (col.get)(c)).collect())
        .collect();
    let (rows, cycles) = average(&times, &values, right_heel_strikes, skip)?;
    Ok(CycleCurves {
        columns: columns.into_iter().map(|c| c.name).collect(),
        rows,
        cycles,
    })
}

/// A curve of the gait cycle, and the panel of the figure that shows it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Panel {
    /// Hip flexion, + flexion (deg; spec §1).
    HipFlexion,
    /// Knee flexion, + flexion (deg).
    KneeFlexion,
    /// Ankle dorsiflexion, + dorsiflexion (deg).
    AnkleDorsiflexion,
    /// Pelvic list (obliquity), + with the right side up (deg).
    PelvisList,
    /// Pelvic rotation, + with the right side forward (deg).
    PelvisRotation,
    /// Height of the pelvis centre above the ground (cm).
    PelvisHeight,
}

impl Panel {
    /// The panels in figure order (left to right, top to bottom).
    pub const ALL: [Panel; 6] = [
        Panel::HipFlexion,
        Panel::KneeFlexion,
        Panel::AnkleDorsiflexion,
        Panel::PelvisList,
        Panel::PelvisRotation,
        Panel::PelvisHeight,
    ];

    /// The unit of the panel's values and norms: `deg` or `cm`.
    pub(crate) fn unit(self) -> &'static str {
        match self {
            Panel::PelvisHeight => "cm",
            _ => "deg",
        }
    }

    /// Whether the panel has a curve per leg (else one curve, of the pelvis).
    pub fn per_leg(self) -> bool {
        matches!(
            self,
            Panel::HipFlexion | Panel::KneeFlexion | Panel::AnkleDorsiflexion
        )
    }

    /// The curve's value in a frame, in rad or m (the leg's own for a leg panel): the columns of
    /// [`angle_columns`] of the same names, and the pelvis centre's height
    /// ([`Clinical::pelvis`], the landmarks' `pelvis[1]`).
    fn value(self, c: &Clinical, side: Side) -> f64 {
        match self {
            Panel::HipFlexion => c.leg(side).hip.flexion,
            Panel::KneeFlexion => c.leg(side).knee.flexion,
            Panel::AnkleDorsiflexion => c.leg(side).ankle.flexion,
            Panel::PelvisList => c.pelvis_list,
            Panel::PelvisRotation => c.pelvis_rotation,
            Panel::PelvisHeight => c.pelvis[1],
        }
    }

    /// An averaged [`Panel::value`] in the panel's unit.
    fn in_unit(self, v: f64) -> f64 {
        match self {
            Panel::PelvisHeight => 100.0 * v,
            _ => v.to_degrees(),
        }
    }
}

/// One curve of the figure: 101 samples, 0…100 % of its cycle, in its panel's unit.
#[derive(Clone, Debug, PartialEq)]
pub struct PanelCurve {
    /// The panel that shows the curve.
    pub panel: Panel,
    /// The leg (its own cycle), or `None` for the pelvis (the right cycle).
    pub side: Option<Side>,
    /// The 101 averaged samples at 0, 1, …, 100 % of the cycle, in the panel's unit.
    pub values: Vec<f64>,
}

/// The averaged gait cycle of a walk: the curves of every panel.
#[derive(Clone, Debug, PartialEq)]
pub struct GaitCycle {
    /// The curves, panel by panel in [`Panel::ALL`]'s order, the right leg's before the left's.
    pub curves: Vec<PanelCurve>,
    /// How many cycles were averaged (right, left).
    pub cycles: (usize, usize),
    /// Toe-off of each leg in % of its own cycle (mean over the averaged cycles), if known.
    pub toe_off_pct: [Option<f64>; 2],
}

impl GaitCycle {
    /// Average clinical frames over the steady cycles of each leg (see the module doc): the right
    /// leg and the pelvis between right heel strikes, the left leg between left heel strikes,
    /// the first `skip` cycles of each left out.
    pub fn from_clinical(
        frames: &[Clinical],
        right_heel_strikes: &[f64],
        left_heel_strikes: &[f64],
        skip: usize,
    ) -> Result<GaitCycle, CycleError> {
        let times: Vec<f64> = frames.iter().map(|c| c.time).collect();
        let averaged = |side: Side, strikes: &[f64]| {
            let values: Vec<Vec<f64>> = frames
                .iter()
                .map(|c| Panel::ALL.map(|p| p.value(c, side)).to_vec())
                .collect();
            average(&times, &values, strikes, skip)
        };
        let (right, right_cycles) = averaged(Side::Right, right_heel_strikes)?;
        let (left, left_cycles) = averaged(Side::Left, left_heel_strikes)?;
        let mut curves = Vec::new();
        for (k, panel) in Panel::ALL.into_iter().enumerate() {
            let curve = |rows: &[Vec<f64>], side| PanelCurve {
                panel,
                side,
                values: rows.iter().map(|r| panel.in_unit(r[k])).collect(),
            };
            if panel.per_leg() {
                curves.push(curve(&right, Some(Side::Right)));
                curves.push(curve(&left, Some(Side::Left)));
            } else {
                curves.push(curve(&right, None));
            }
        }
        Ok(GaitCycle {
            curves,
            cycles: (right_cycles, left_cycles),
            toe_off_pct: [None, None],
        })
    }

    /// The walk's averaged cycle: frames at 200 frames/s (`CYCLE_FPS`), clinical angles, heel
    /// strikes at the starts of the steps (even steps right, odd steps left), the first cycle of
    /// each leg skipped (`CYCLE_SKIP`);
    /// toe-off from the walk's gait events. Errors: a frame the skeleton cannot be built from, no
    /// complete steady cycle of a leg ([`CycleError`]: walk more steps).
    pub fn from_walk(walk: &Walk) -> Result<GaitCycle, CycleError> {
        let frames = crate::figure::frames(walk, CYCLE_FPS)
            .map(|lm| lm.and_then(|lm| clinical::clinical(&lm, &walk.body)))
            .collect::<Result<Vec<Clinical>, FigureError>>()?;
        let strikes = |parity: usize| -> Vec<f64> {
            walk.steps
                .iter()
                .enumerate()
                .filter(|(i, _)| i % 2 == parity)
                .map(|(_, s)| s.t_start)
                .collect()
        };
        let (right, left) = (strikes(0), strikes(1));
        let mut cycle = Self::from_clinical(&frames, &right, &left, CYCLE_SKIP)?;
        let last = frames.last().map_or(f64::NEG_INFINITY, |f| f.time);
        let events = crate::analysis::events::events(walk);
        for (k, (strikes, side)) in [(&right, "right"), (&left, "left")].into_iter().enumerate() {
            let pcts: Vec<f64> = strikes
                .windows(2)
                .skip(CYCLE_SKIP)
                .filter(|w| w[1] <= last)
                .filter_map(|w| {
                    events
                        .iter()
                        .find(|e| {
                            e.side == side && e.event == "TO" && e.time_s > w[0] && e.time_s < w[1]
                        })
                        .map(|e| 100.0 * (e.time_s - w[0]) / (w[1] - w[0]))
                })
                .collect();
            if !pcts.is_empty() {
                cycle.toe_off_pct[k] = Some(pcts.iter().sum::<f64>() / pcts.len() as f64);
            }
        }
        Ok(cycle)
    }

    /// The curves of one panel.
    pub(crate) fn panel_curves(&self, panel: Panel) -> impl Iterator<Item = &PanelCurve> {
        self.curves.iter().filter(move |c| c.panel == panel)
    }
}
