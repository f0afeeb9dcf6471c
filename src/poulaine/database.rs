//! The database of modelled poulaines and the poulaine it gives for a new walker (Pronost et al.
//! §4): each axis taken from the poulaine nearest in the parameter that characterizes it, then
//! corrected to fit the request exactly.
//!
//! The parameters, each as a fraction of the walker's leg length l (hip to ankle, l3 + l4) so
//! that walkers of every size share one database:
//! - x: the ankle's trace length along x over the cycle, its x at its most forward point
//!   less its x at its most backward (characteristic points 2 and 4: the samples' max x −
//!   min x; the cubic between may overshoot them), the paper's "step length" parameter;
//! - y: half the feet's spacing in support, the ankle's mean |z| from its most forward to its
//!   most backward point;
//! - z: the stance, the pelvis-to-ankle height where the ankle passes under the pelvis in
//!   support (characteristic point 3).
//!
//! The corrections, per ankle, in units of l: x scaled by x*/x_e (points and tangents), z
//! (lateral) shifted outwards by y* − y_e, y (vertical) shifted down by z* − z_e; then × the new
//! walker's l, and the sampled targets clamped to the leg's reach ([`clamp_to_reach`]).
use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::ik::chain::{Angles, DOF};
use crate::model::GRAVITY;
use crate::poulaine::curve::{Component, LegCurve, Speed};
use crate::poulaine::error::PoulaineError;
use crate::poulaine::fit::{FitError, Model};
use crate::poulaine::trajectory::Trajectory;

/// A poulaine's three parameters, fractions of the leg length (module doc).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axes {
    /// x: the trace length along x.
    pub trace: f64,
    /// y: half the feet's spacing in support.
    pub spacing: f64,
    /// z: the pelvis-to-ankle height under the pelvis in support.
    pub stance: f64,
}

impl Axes {
    /// The parameters of `model` for a walker of leg length `leg` (m): the mean of the two
    /// ankles'.
    pub fn of(model: &Model, leg: f64) -> Self {
        let one = |c: &LegCurve| {
            // support: the x component's knots 2 (most forward) to 4 (most backward)
            let [_, front, under, back] = c.x.phase;
            let span = (back - front).rem_euclid(1.0);
            let k = 64;
            let spacing = (0..=k)
                .map(|i| c.z.at(front + span * i as f64 / k as f64).abs())
                .sum::<f64>()
                / (k + 1) as f64;
            Axes {
                trace: (c.x.value[1] - c.x.value[3]) / leg,
                spacing: spacing / leg,
                stance: -c.y.at(under) / leg,
            }
        };
        let (r, l) = (one(&model.right), one(&model.left));
        Axes {
            trace: (r.trace + l.trace) / 2.0,
            spacing: (r.spacing + l.spacing) / 2.0,
            stance: (r.stance + l.stance) / 2.0,
        }
    }
}

/// One modelled poulaine and what it was recorded from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    /// A name, unique in its database.
    pub label: String,
    /// Where it comes from: `synthetic` (a klaw walk) or `measured` (a motion capture).
    pub source: String,
    /// The walker's leg length l, hip to ankle (m).
    pub leg_length: f64,
    /// The walker's height (m), if known.
    pub height: Option<f64>,
    /// The walk's step length (m).
    pub step_length: f64,
    /// The walk's speed (m/s), if known.
    pub velocity: Option<f64>,
    /// The inputs of a synthetic walk that set its stance and feet (klaw attributes, in their
    /// file units), or anything a measured one records.
    #[serde(default)]
    pub attributes: BTreeMap<String, f64>,
    /// The model.
    pub model: Model,
    /// The model's error on the samples it was fitted to.
    pub fit_error: FitError,
    /// The parameters (computed from the model; checked on reading).
    pub axes: Axes,
    /// The walk's chain angles (rad, in the order of [`crate::ik::chain::NAMES`]) at uniform
    /// phases of its cycle from the model's phase 0, a per-phase reference posture for the IK's
    /// f3 (eq. 6; docs/ik.md, "The database's angles as reference"); empty when the entry has
    /// none (a measured poulaine).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub angles: Vec<[f64; DOF]>,
}

/// A database of poulaines.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Database {
    /// What it holds and how it was made.
    pub description: String,
    /// The poulaines.
    pub entries: Vec<Entry>,
}

/// The poulaine asked of the database: its three parameters (fractions of the leg length).
pub type Query = Axes;

/// f3's reference posture per sample from a database's angles ([`Database::reference`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    /// One posture per sample of the poulaine.
    pub angles: Vec<Angles>,
    /// The entries blended.
    pub blend: Vec<Blended>,
}

/// One entry of a [`Reference`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blended {
    /// The entry's index.
    pub entry: usize,
    /// Its weight; the weights sum to 1.
    pub weight: f64,
    /// The entry's phase read at the poulaine's phase 0 (cycles; 0 unless aligned).
    pub shift: f64,
}

/// The entries chosen for each axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Selection {
    /// The entry giving x.
    pub x: usize,
    /// The entry giving the lateral coordinate (klaw's z, the paper's y).
    pub y: usize,
    /// The entry giving the vertical coordinate (klaw's y, the paper's z).
    pub z: usize,
}

impl Entry {
    /// An entry for `model` (fitted with `fit_error`) of a walker of leg length `leg_length`.
    pub fn new(
        label: String,
        source: &str,
        leg_length: f64,
        step_length: f64,
        model: Model,
        fit_error: FitError,
    ) -> Self {
        Entry {
            label,
            source: source.to_string(),
            leg_length,
            height: None,
            step_length,
            velocity: None,
            attributes: BTreeMap::new(),
            axes: Axes::of(&model, leg_length),
            model,
            fit_error,
            angles: Vec::new(),
        }
    }
}

impl Database {
    /// Read a database file (JSON, the layout of `docs/ik.md`), checking every entry: a valid
    /// model, a positive leg length, parameters that are the model's, unique labels.
    pub fn read(path: &Path) -> crate::Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|source| crate::Error::Io {
            action: "reading",
            path: path.to_path_buf(),
            source,
        })?;
        Ok(Self::parse(&text, path)?)
    }

    /// [`Self::read`] of the text of `path`.
    pub fn parse(text: &str, path: &Path) -> Result<Self, PoulaineError> {
        let bad = |reason: String| PoulaineError::Malformed {
            path: path.to_path_buf(),
            reason,
        };
        let db: Database =
            serde_json::from_str(text).map_err(|e| bad(format!("not a poulaine database: {e}")))?;
        if db.entries.is_empty() {
            return Err(bad("the database has no entry".into()));
        }
        let mut labels = std::collections::BTreeSet::new();
        for (i, e) in db.entries.iter().enumerate() {
            let at = |what: String| bad(format!("entry {i} ({}): {what}", e.label));
            if !labels.insert(e.label.as_str()) {
                return Err(at("the label is used twice".into()));
            }
            if !(e.leg_length.is_finite() && (0.3..=1.5).contains(&e.leg_length)) {
                return Err(at(format!(
                    "leg_length {} m is out of [0.3, 1.5] m",
                    e.leg_length
                )));
            }
            if !(e.model.period.is_finite() && e.model.period > 0.0) {
                return Err(at(format!(
                    "the period {} s must be positive",
                    e.model.period
                )));
            }
            let valid = [&e.model.right, &e.model.left]
                .iter()
                .flat_map(|c| c.components())
                .all(Component::is_valid);
            if !valid {
                return Err(at("a curve's knots are not distinct phases in [0, 1) in cyclic order, or a value is not finite".into()));
            }
            if ![&e.model.right, &e.model.left]
                .iter()
                .all(|c| c.speed.is_valid())
            {
                return Err(at(format!(
                    "a speed profile must run from 0 to 1 nondecreasing, {} steps per interval",
                    crate::poulaine::curve::SPEED_STEPS
                )));
            }
            if e.angles.len() == 1 || e.angles.iter().flatten().any(|v| !v.is_finite()) {
                return Err(at(format!(
                    "its angles must be none or at least 2 samples of finite values ({} given)",
                    e.angles.len()
                )));
            }
            let axes = Axes::of(&e.model, e.leg_length);
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-6 * a.abs().max(1.0);
            if !(close(axes.trace, e.axes.trace)
                && close(axes.spacing, e.axes.spacing)
                && close(axes.stance, e.axes.stance))
            {
                return Err(at(format!(
                    "its axes {:?} are not its model's {axes:?}",
                    e.axes
                )));
            }
        }
        Ok(db)
    }

    /// The entry nearest `target` in the parameter `key`.
    fn nearest(&self, key: impl Fn(&Axes) -> f64, target: f64) -> usize {
        (0..self.entries.len())
            .min_by(|&a, &b| {
                let d = |i: usize| (key(&self.entries[i].axes) - target).abs();
                d(a).total_cmp(&d(b))
            })
            .expect("a database has entries")
    }

    /// The nearest entry per axis (§4).
    pub fn select(&self, q: &Query) -> Selection {
        Selection {
            x: self.nearest(|a| a.trace, q.trace),
            y: self.nearest(|a| a.spacing, q.spacing),
            z: self.nearest(|a| a.stance, q.stance),
        }
    }

    /// The trace length (fraction of the leg) that goes with step length `step` (m) for a
    /// walker of leg length `leg` (m): the database's trace per step length at the entry nearest
    /// in step length per leg length.
    pub fn trace_for_step(&self, step: f64, leg: f64) -> f64 {
        let target = step / leg;
        let e = self
            .entries
            .iter()
            .min_by(|a, b| {
                let d = |e: &Entry| (e.step_length / e.leg_length - target).abs();
                d(a).total_cmp(&d(b))
            })
            .expect("a database has entries");
        target * e.axes.trace / (e.step_length / e.leg_length)
    }

    /// The poulaine for a walker of leg length `leg` (m) and cycle `period` (s) that meets `q`
    /// exactly: the selection's axes scaled to the leg, x scaled to the trace length, \[ours\]
    /// the vertical and lateral coordinates moved onto the x entry's characteristic points
    /// ([`Component::retimed`]: a poulaine's coordinates share their knots, and the entries'
    /// points fall at different phases), then shifted by what the combined curve still lacks
    /// (its support phases are the x entry's, so the shift is measured on the combination, not
    /// on the y or z entry alone); the speed along it the database's average profile per ankle
    /// (§3.2, [`Speed::mean`]). Not clamped: sample it and [`clamp_to_reach`].
    pub fn poulaine(&self, q: &Query, leg: f64, period: f64) -> (Model, Selection) {
        let s = self.select(q);
        let (ex, ey, ez) = (&self.entries[s.x], &self.entries[s.y], &self.entries[s.z]);
        let scale = |c: &Component, k: f64, shift: f64| Component {
            phase: c.phase,
            value: c.value.map(|v| k * v + shift),
            slope: c.slope.map(|m| k * m),
        };
        let kx = q.trace / ex.axes.trace * leg / ex.leg_length;
        let average = |pick: fn(&Model) -> &LegCurve| {
            Speed::mean(self.entries.iter().map(|e| &pick(&e.model).speed))
        };
        let combine = |lateral: f64, down: f64| {
            let leg_curve = |side: f64, pick: fn(&Model) -> &LegCurve| {
                let x = pick(&ex.model).x;
                let y = scale(&pick(&ez.model).y, leg / ez.leg_length, -down * leg);
                let z = scale(
                    &pick(&ey.model).z,
                    leg / ey.leg_length,
                    side * lateral * leg,
                );
                LegCurve {
                    speed: average(pick),
                    x: scale(&x, kx, 0.0),
                    y: y.retimed(x.phase),
                    z: z.retimed(x.phase),
                }
            };
            Model {
                period,
                right: leg_curve(1.0, |m| &m.right),
                left: leg_curve(-1.0, |m| &m.left),
            }
        };
        let raw = Axes::of(&combine(0.0, 0.0), leg);
        (combine(q.spacing - raw.spacing, q.stance - raw.stance), s)
    }

    /// The per-phase reference posture of f3 (eq. 6) for `poulaine` (uniform samples of one
    /// cycle) of a walker of leg length `leg` (m) \[ours: the paper's f3 pulls towards one rest
    /// posture; its database held no angles\]: the angles of the two entries nearest below and
    /// above the poulaine in the blending coordinate, linear in it between them, each linear
    /// between its samples, read at the poulaine's phase: both cycles from their right heel
    /// strike (klaw's poulaines and synthetic entries start there), or with `align`, shifted by
    /// the [`alignment`] of the ankles' paths (a poulaine that starts elsewhere). Beyond the
    /// database, the nearest entry's. The coordinate is the dimensionless speed v / √(g l)
    /// (Alexander's dynamic similarity: walkers of different sizes at one v / √(g l) move their
    /// joints alike), the poulaine's [`Trajectory::speed`] against each entry's walking speed,
    /// when every entry with angles knows its speed; else the trace per leg
    /// ([`Trajectory::trace`] / `leg` against [`Axes::trace`]). Of entries equally near (a
    /// database's walks that differ in step width only), the one nearest in half the feet's
    /// spacing ([`Trajectory::spacing`] / `leg` against [`Axes::spacing`]). `None` when no entry
    /// carries angles.
    pub fn reference(&self, poulaine: &Trajectory, leg: f64, align: bool) -> Option<Reference> {
        let n = poulaine.time.len();
        let with: Vec<usize> = (0..self.entries.len())
            .filter(|&i| !self.entries[i].angles.is_empty())
            .collect();
        let by_speed = with.iter().all(|&i| self.entries[i].velocity.is_some());
        let froude = |v: f64, l: f64| v / (GRAVITY * l).sqrt();
        let x = if by_speed {
            froude(poulaine.speed(), leg)
        } else {
            poulaine.trace() / leg
        };
        let t = |i: usize| {
            let e = &self.entries[i];
            match e.velocity {
                Some(v) if by_speed => froude(v, e.leg_length),
                _ => e.axes.trace,
            }
        };
        let spacing = poulaine.spacing() / leg;
        let apart = |i: usize| {
            let e = &self.entries[i];
            ((t(i) - x).abs(), (e.axes.spacing - spacing).abs())
        };
        let nearest = |side: f64| {
            with.iter()
                .copied()
                .filter(|&i| side * (t(i) - x) >= 0.0)
                .min_by(|&a, &b| {
                    let ((ta, sa), (tb, sb)) = (apart(a), apart(b));
                    ta.total_cmp(&tb).then(sa.total_cmp(&sb))
                })
        };
        let weights = match (nearest(-1.0), nearest(1.0)) {
            (Some(lo), Some(hi)) if t(hi) > t(lo) => {
                let w = (x - t(lo)) / (t(hi) - t(lo));
                vec![(lo, 1.0 - w), (hi, w)]
            }
            (Some(i), _) | (None, Some(i)) => vec![(i, 1.0)],
            (None, None) => return None,
        };
        let mut angles = vec![Angles::zeros(); n];
        let mut blend = Vec::new();
        for (entry, weight) in weights {
            let e = &self.entries[entry];
            let shift = if align { alignment(e, poulaine) } else { 0.0 };
            let own: Vec<Angles> = e.angles.iter().map(|a| Angles::from(*a)).collect();
            for (i, sum) in angles.iter_mut().enumerate() {
                *sum += at_phase(&own, i as f64 / n as f64 + shift) * weight;
            }
            blend.push(Blended {
                entry,
                weight,
                shift,
            });
        }
        Some(Reference { angles, blend })
    }

    /// The database without the entry labelled `label` (leave-one-out).
    pub fn without(&self, label: &str) -> Self {
        Database {
            description: self.description.clone(),
            entries: self
                .entries
                .iter()
                .filter(|e| e.label != label)
                .cloned()
                .collect(),
        }
    }
}

/// The phase shift s (cycles, in [−½, ½)) that puts `entry`'s cycle in phase with
/// `poulaine` (uniform samples from its phase 0): the s on a grid of 1/1000 cycle that
/// minimizes Σᵢ Σ_c (ĉᵢ − ĉₑ(i/n + s))² over the forward and vertical coordinates c of both
/// ankles, each less its mean over its range (max − min), c_e the entry's model. A measured
/// poulaine may start anywhere in its cycle; klaw's start at the right heel strike.
pub fn alignment(entry: &Entry, poulaine: &Trajectory) -> f64 {
    const GRID: usize = 1000;
    let n = poulaine.time.len();
    let normalized = |v: Vec<f64>| {
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let (lo, hi) = v
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), &a| (l.min(a), h.max(a)));
        v.into_iter()
            .map(|a| (a - mean) / (hi - lo).max(1e-9))
            .collect::<Vec<f64>>()
    };
    let signals: Vec<(Vec<f64>, Vec<f64>)> = [
        (&poulaine.right, &entry.model.right),
        (&poulaine.left, &entry.model.left),
    ]
    .into_iter()
    .flat_map(|(samples, curve)| {
        [0, 1].map(|c| {
            let own = normalized(samples.iter().map(|p| p[c]).collect());
            let model = (0..GRID).map(|k| curve.at(k as f64 / GRID as f64)[c]);
            (own, normalized(model.collect()))
        })
    })
    .collect();
    let cost = |s: usize| {
        let mut sum = 0.0;
        for (own, model) in &signals {
            for (i, a) in own.iter().enumerate() {
                let u = (i as f64 / n as f64 * GRID as f64).round() as usize + s;
                sum += (a - model[u % GRID]).powi(2);
            }
        }
        sum
    };
    let best = (0..GRID)
        .min_by(|&a, &b| cost(a).total_cmp(&cost(b)))
        .expect("a grid");
    let s = best as f64 / GRID as f64;
    if s >= 0.5 { s - 1.0 } else { s }
}

/// `angles`, samples of one cycle at uniform phases from 0, at `phase` (cycles, any real):
/// linear between samples, cyclic.
fn at_phase(angles: &[Angles], phase: f64) -> Angles {
    let m = angles.len();
    let u = phase.rem_euclid(1.0) * m as f64;
    let (k, f) = (u.floor() as usize % m, u.fract());
    angles[k] * (1.0 - f) + angles[(k + 1) % m] * f
}

/// `angles`, samples of one cycle at uniform phases from 0, at `n` uniform phases: linear
/// between samples, cyclic (the last sample is followed by the first).
pub fn resample(angles: &[Angles], n: usize) -> Vec<Angles> {
    (0..n)
        .map(|i| at_phase(angles, i as f64 / n as f64))
        .collect()
}

/// Clamp each ankle of `t` to at most `reach` (m) from its hip at the pelvis's rest position,
/// (0, 0, ±`half_width`): pulled in along the hip–ankle line. Returns how many samples moved.
pub fn clamp_to_reach(t: &mut Trajectory, half_width: f64, reach: f64) -> usize {
    let mut moved = 0;
    for (side, leg) in [(1.0, &mut t.right), (-1.0, &mut t.left)] {
        for p in leg.iter_mut() {
            let d = [p[0], p[1], p[2] - side * half_width];
            let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if r > reach {
                let k = reach / r;
                *p = [d[0] * k, d[1] * k, side * half_width + d[2] * k];
                moved += 1;
            }
        }
    }
    moved
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Resampling is exact on a cyclic piecewise-linear curve whose corners are the samples: at
    /// the samples (n = m: identity), halfway between them (the neighbours' mean), and across
    /// the wrap from the last sample to the first.
    #[test]
    fn resampling_interpolates_linearly_and_wraps() {
        let m = 5;
        let value = |k: usize| [0.0, 2.0, 1.0, 4.0, -1.0][k % m];
        let samples: Vec<Angles> = (0..m).map(|k| Angles::from_element(value(k))).collect();
        for (a, b) in resample(&samples, m).iter().zip(&samples) {
            assert!((a - b).amax() < 1e-12);
        }
        let halves = resample(&samples, 2 * m);
        for k in 0..m {
            let mean = 0.5 * (value(k) + value(k + 1));
            assert!(halves[2 * k].iter().all(|v| (v - value(k)).abs() < 1e-12));
            assert!(
                halves[2 * k + 1].iter().all(|v| (v - mean).abs() < 1e-12),
                "{k}"
            );
        }
        // the last quarter interval of the wrap: from −1 (sample 4) towards 0 (sample 0)
        let r = resample(&samples, 4 * m);
        assert!((r[4 * m - 1][0] - (-1.0 + 0.75)).abs() < 1e-12);
    }
}
