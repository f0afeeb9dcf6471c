//! Biomechanical quality criteria of any walk (Pronost, Dumont, Nicolas & Multon 2006, §6.2,
//! eqs. 7–11; issue 18, `docs/criteria.md`), from a sequence of frames of clinical angles and a
//! [`Body`]: a klaw walk ([`CriteriaFrames::from_walk`]), a file (`input::motion_file`) or the angles
//! of an inverse-kinematics solve.
//!
//! Over each gait cycle, heel strike to the next heel strike of the same foot (both included),
//! the walk is resampled at `rate` = 60 frames/s (the paper's capture rate) from the cycle's heel
//! strike on, by local degree-5 Lagrange interpolation between the frames
//! (`numerics::sampled`), and:
//! - C1, the total jerk ([`jerk`]): Σ over the cycle's frames of the squared third derivatives
//!   of the paper's eleven angles ([`segments::DOFS`]), averaged over the eleven, rad² s⁻⁶
//!   (eq. 8 as Table 1's values fit it), and the mean squared jerk (1/T) ∫ θ⃛² dt, which does
//!   not grow with the frame count;
//! - C2, the cyclicity (eq. 9): ‖θ(end) − θ(start)‖ of the eleven angles at the two heel strikes,
//!   rad;
//! - C3, the mechanical power per unit mass ([`energy`], eqs. 10–11 and Willems et al. 1995),
//!   where the frames give the pelvis position.
//!
//! The first `skip` cycles of each foot are left out (a klaw walk's first cycle starts from the
//! engine's initial conditions), as in `analysis::cycle`.
pub mod compare;
pub mod energy;
pub mod heel_strikes;
pub mod jerk;
pub mod segments;

use serde::Serialize;

pub use compare::mean_shifted_rms;
pub use energy::Power;
pub use heel_strikes::HeelStrikes;

use crate::engine::walker::Walk;
use crate::figure::FigureError;
use crate::figure::clinical::{self, Clinical};
use crate::figure::skeleton::Side;
use crate::model::body::Body;
use crate::numerics::sampled::lagrange;
use segments::{DOFS, POSE, POSE_NAMES, Segments, pose};

/// The paper's Table 1, mean of its seven subjects: C1 (rad² s⁻⁶), C2 (rad), C3 (W/kg).
pub const PAPER_TABLE_1: [f64; 3] = [7.2e7, 0.02, 6.1];

/// The criteria's parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CriteriaParameters {
    /// Frame rate of the resampled cycles (frames/s): 60, the paper's capture rate (§3.1).
    pub rate: f64,
    /// Cycles of each foot left out at the start of the walk.
    pub skip: usize,
    /// Heel strikes found from the kinematics ([`heel_strikes::from_kinematics`]) are the
    /// ankle's foremost positions at least this far apart (s): less than any step's duration
    /// (≥ 0.33 s at klaw's fastest 182 steps/min).
    pub heel_strike_window: f64,
}

impl Default for CriteriaParameters {
    fn default() -> Self {
        CriteriaParameters {
            rate: 60.0,
            skip: 1,
            heel_strike_window: 0.3,
        }
    }
}

/// A walk's motion as the criteria read it.
#[derive(Clone, Debug, PartialEq)]
pub struct CriteriaFrames {
    /// The frames, time increasing: the pelvis centre (NaN where not known, then C3 is not
    /// computed) and the clinical angles (rad; the eleven of [`segments::DOFS`] finite).
    pub frames: Vec<Clinical>,
    /// The heel strikes of each foot.
    pub heel_strikes: HeelStrikes,
}

impl CriteriaFrames {
    /// A klaw walk's motion: its frames at `fps` and its heel strikes, exactly: the starts of its
    /// steps (even steps on the right foot, odd ones on the left) and the walk's end, the heel
    /// strike that ends its last step.
    pub fn from_walk(walk: &Walk, fps: f64) -> Result<CriteriaFrames, FigureError> {
        let frames = crate::figure::frames(walk, fps)
            .map(|lm| lm.and_then(|lm| clinical::clinical(&lm, &walk.body)))
            .collect::<Result<Vec<_>, _>>()?;
        let strikes: Vec<f64> = walk
            .steps
            .iter()
            .map(|s| s.t_start)
            .chain(std::iter::once(walk.duration()))
            .collect();
        let starts = |parity: usize| strikes.iter().skip(parity).step_by(2).copied().collect();
        Ok(CriteriaFrames {
            frames,
            heel_strikes: HeelStrikes {
                right: starts(0),
                left: starts(1),
            },
        })
    }

    /// The frame times.
    pub fn times(&self) -> Vec<f64> {
        self.frames.iter().map(|f| f.time).collect()
    }
}

/// Frames or heel strikes the criteria cannot be computed from.
#[derive(Debug, thiserror::Error)]
pub enum CriteriaError {
    /// Frame times not finite and strictly increasing.
    #[error("frame {frame}: the frame times must be finite and strictly increasing")]
    Times {
        /// The first frame (from 0) whose time is not finite or not after the one before.
        frame: usize,
    },
    /// One of the eleven angles not finite.
    #[error("frame {frame}: {name} is {value}: the eleven angles of the criteria must be finite")]
    NotFinite {
        /// The frame, from 0.
        frame: usize,
        /// The angle's name.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// Heel strike times not finite and strictly increasing.
    #[error("the {side} heel strikes must be finite and strictly increasing")]
    HeelStrikes {
        /// `right` or `left`.
        side: &'static str,
    },
    /// A parameter out of its range.
    #[error("criteria parameter {name} = {value}: {rule}")]
    Parameter {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        rule: &'static str,
    },
    /// No complete cycle left once the first `skip` of each foot are left out.
    #[error(
        "no complete gait cycle: {right} right and {left} left heel strikes within the frames' \
         {t_first} … {t_last} s, the first {skip} cycle(s) of each foot left out; a cycle runs \
         from a heel strike to the next of the same foot and needs both inside the frames"
    )]
    NoCycle {
        /// Right heel strikes.
        right: usize,
        /// Left heel strikes.
        left: usize,
        /// Cycles of each foot left out.
        skip: usize,
        /// First frame's time (s).
        t_first: f64,
        /// Last frame's time (s).
        t_last: f64,
    },
}

/// A gait cycle: heel strike to the next heel strike of the same foot.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Cycle {
    /// The foot.
    pub side: Side,
    /// Its heel strike (s).
    pub start: f64,
    /// Its next heel strike (s).
    pub end: f64,
}

/// The criteria of one cycle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CycleCriteria {
    /// The cycle.
    pub cycle: Cycle,
    /// Its frames at the criteria's rate, t_start + k / rate ≤ t_end.
    pub frames: usize,
    /// C1, Σ over the frames of θ⃛², mean over the eleven angles (rad² s⁻⁶).
    pub total_jerk: f64,
    /// (1/T) ∫ θ⃛² dt over the cycle, mean over the eleven angles (rad² s⁻⁶).
    pub mean_squared_jerk: f64,
    /// C2, ‖θ(end) − θ(start)‖ (rad).
    pub cyclicity: f64,
    /// C3 and the other powers (W/kg), where the pelvis position is known.
    pub power: Option<Power>,
}

/// The criteria of a walk: every steady cycle's and their means.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Criteria {
    /// The parameters used.
    pub parameters: CriteriaParameters,
    /// The steady cycles, in time order.
    pub cycles: Vec<CycleCriteria>,
    /// The means over the cycles.
    pub mean: Means,
}

/// The criteria averaged over the steady cycles.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Means {
    /// The cycles averaged.
    pub cycles: usize,
    /// C1 (rad² s⁻⁶).
    pub total_jerk: f64,
    /// The mean squared jerk (rad² s⁻⁶).
    pub mean_squared_jerk: f64,
    /// C2 (rad).
    pub cyclicity: f64,
    /// C3 and the other powers (W/kg), when every cycle has them.
    pub power: Option<Power>,
}

/// The walk's complete cycles after the first `skip` of each foot, in time order.
pub fn cycles(motion: &CriteriaFrames, skip: usize) -> Result<Vec<Cycle>, CriteriaError> {
    let times = motion.times();
    check_frames(motion, &times)?;
    let (t_first, t_last) = (times[0], times[times.len() - 1]);
    let h = &motion.heel_strikes;
    let mut out = Vec::new();
    for (side, strikes) in [(Side::Right, &h.right), (Side::Left, &h.left)] {
        if !strikes.iter().all(|t| t.is_finite()) || strikes.windows(2).any(|w| w[0] >= w[1]) {
            return Err(CriteriaError::HeelStrikes {
                side: if side == Side::Right { "right" } else { "left" },
            });
        }
        out.extend(
            strikes
                .windows(2)
                .skip(skip)
                .filter(|w| w[0] >= t_first && w[1] <= t_last)
                .map(|w| Cycle {
                    side,
                    start: w[0],
                    end: w[1],
                }),
        );
    }
    if out.is_empty() {
        let inside = |s: &[f64]| s.iter().filter(|&&t| t >= t_first && t <= t_last).count();
        return Err(CriteriaError::NoCycle {
            right: inside(&h.right),
            left: inside(&h.left),
            skip,
            t_first,
            t_last,
        });
    }
    out.sort_by(|a, b| a.start.total_cmp(&b.start));
    Ok(out)
}

/// Finite, strictly increasing times (at least one) and finite angles of the eleven.
fn check_frames(motion: &CriteriaFrames, times: &[f64]) -> Result<(), CriteriaError> {
    if times.is_empty() {
        return Err(CriteriaError::Times { frame: 0 });
    }
    if let Some(k) =
        (0..times.len()).find(|&k| !times[k].is_finite() || (k > 0 && times[k] <= times[k - 1]))
    {
        return Err(CriteriaError::Times { frame: k });
    }
    for (k, f) in motion.frames.iter().enumerate() {
        let p = pose(f);
        if let Some(&i) = DOFS.iter().find(|&&i| !p[i].is_finite()) {
            return Err(CriteriaError::NotFinite {
                frame: k,
                name: POSE_NAMES[i],
                value: p[i],
            });
        }
    }
    Ok(())
}

/// The criteria of `motion` for `body` (module doc).
pub fn evaluate(
    motion: &CriteriaFrames,
    body: &Body,
    parameters: &CriteriaParameters,
) -> Result<Criteria, CriteriaError> {
    let rate = parameters.rate;
    if !(rate.is_finite() && rate > 0.0) {
        return Err(CriteriaError::Parameter {
            name: "rate",
            value: rate,
            rule: "a finite number of frames/s > 0",
        });
    }
    let cycles = cycles(motion, parameters.skip)?;
    let times = motion.times();
    let poses: Vec<[f64; POSE]> = motion.frames.iter().map(pose).collect();
    let columns: Vec<Vec<f64>> = (0..POSE)
        .map(|i| poses.iter().map(|p| p[i]).collect())
        .collect();
    let at = |t: f64| -> [f64; POSE] { std::array::from_fn(|i| lagrange(&times, &columns[i], t)) };
    let positioned = poses.iter().all(|p| p[..3].iter().all(|x| x.is_finite()));
    let segments = Segments::new(body);
    let (t_first, t_last) = (times[0], times[times.len() - 1]);
    let h = 1.0 / rate;
    let out: Vec<CycleCriteria> = cycles
        .into_iter()
        .map(|cycle| {
            // the cycle's frames k = 0..=n, and up to two more on either side inside the frames
            // (for the derivatives' central differences)
            let n = ((cycle.end - cycle.start) * rate + 1e-9).floor() as i64;
            let grid: Vec<(i64, f64)> = (-2..=n + 2)
                .map(|k| (k, cycle.start + k as f64 * h))
                .filter(|&(_, t)| t >= t_first - 1e-12 && t <= t_last + 1e-12)
                .collect();
            let first = grid.iter().position(|&(k, _)| k == 0).unwrap_or(0);
            let inside = first..first + n as usize + 1;
            let grid_poses: Vec<[f64; POSE]> = grid.iter().map(|&(_, t)| at(t)).collect();
            let (total_jerk, mean_squared_jerk) = jerk::total_jerk(&grid_poses, h, inside.clone());
            let (a, b) = (at(cycle.start), at(cycle.end));
            let cyclicity = DOFS
                .iter()
                .map(|&i| (b[i] - a[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            let power = positioned.then(|| {
                let e = energy::energies(&grid_poses, h, &segments);
                energy::power(&e[inside], h, body.mass)
            });
            CycleCriteria {
                cycle,
                frames: n as usize + 1,
                total_jerk,
                mean_squared_jerk,
                cyclicity,
                power,
            }
        })
        .collect();
    let mean = mean_of(&out);
    Ok(Criteria {
        parameters: *parameters,
        cycles: out,
        mean,
    })
}

/// The means over `cycles` (at least one).
fn mean_of(cycles: &[CycleCriteria]) -> Means {
    let n = cycles.len() as f64;
    let mean = |f: &dyn Fn(&CycleCriteria) -> f64| cycles.iter().map(f).sum::<f64>() / n;
    let power = cycles
        .iter()
        .map(|c| c.power)
        .collect::<Option<Vec<Power>>>()
        .map(|p| {
            let m = |f: fn(&Power) -> f64| p.iter().map(f).sum::<f64>() / n;
            Power {
                literal: m(|p| p.literal),
                mechanical: m(|p| p.mechanical),
                internal: m(|p| p.internal),
                external: m(|p| p.external),
            }
        });
    Means {
        cycles: cycles.len(),
        total_jerk: mean(&|c| c.total_jerk),
        mean_squared_jerk: mean(&|c| c.mean_squared_jerk),
        cyclicity: mean(&|c| c.cyclicity),
        power,
    }
}
