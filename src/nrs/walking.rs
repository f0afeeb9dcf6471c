//! The walking step an NRS⁻ is built on (Ko & Badler 1993 §5.1, §5.3): the hip (centre site)
//! height and forward time law, both feet's pitch and the phase moments FGM, heel-off and TOM of
//! a step simulated by the dynamic engine, sampled uniformly over its normalized time.
use crate::engine::walker::{self, Step};
use crate::figure::{FigureError, LegPoints, landmarks};
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::nrs::NrsError;
use crate::plan::Gait;

/// How much longer each try of [`WalkingStep::borrowed`] is (m), and how many tries.
const BORROW_STEP: f64 = 0.05;
const BORROW_TRIES: usize = 8;

/// A foot's pitch (heel up +) from its heel and metatarsal joint, in the walk's sagittal plane.
pub(crate) fn sagittal_pitch(leg: &LegPoints) -> f64 {
    (leg.heel[1] - leg.mtp[1]).atan2(leg.mtp[0] - leg.heel[0])
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// One walking step sampled at `n + 1` uniform points of its normalized time (0 at the heel
/// strike that starts it, 1 at the next).
#[derive(Clone, Debug)]
pub struct WalkingStep {
    /// Step length (m) and duration (s).
    pub length: f64,
    /// Duration (s).
    pub duration: f64,
    /// The centre site's height (m).
    pub height: Vec<f64>,
    /// The centre site's forward travel from the step's start, as a fraction of its whole travel
    /// (the time law of §5.3: 0 at the start, 1 at the end).
    pub travel: Vec<f64>,
    /// The stance foot's pitch (rad, heel up +).
    pub stance_pitch: Vec<f64>,
    /// The swing foot's pitch: the hind foot's until toe-off, then the swinging foot's.
    pub swing_pitch: Vec<f64>,
    /// FGM, the stance foot flat (normalized time).
    pub flat: f64,
    /// Where the stance foot leaves flat again (normalized time): heel-off, or a toe lift (the
    /// engine's stance foot tips toes-up by up to 0.9° just before heel-off: issue 16).
    pub heel_off: f64,
    /// TOM, the swing foot's toe-off (normalized time).
    pub toe_off: f64,
    /// The hip-to-ankle distances of the leg that strikes and of the stance leg at the end (m):
    /// the knee flexions an NRS keeps at HSM⁺ (§5.3).
    pub reach_at_strike: [f64; 2],
}

impl WalkingStep {
    /// Sample `step` (a step of a simulated walk) at `n + 1` points.
    pub fn from_step(step: &Step, attrs: &Attributes, n: usize) -> Result<Self, FigureError> {
        let t = step.constraints.timing;
        let mut rows = Vec::with_capacity(n + 1);
        for i in 0..=n {
            let lm = landmarks(step, step.t_start + t.t_step * i as f64 / n as f64, attrs)?;
            rows.push(lm);
        }
        let stance = |lm: &crate::figure::Landmarks| match step.side {
            crate::kinematics::pelvis::Side::Right => lm.right,
            crate::kinematics::pelvis::Side::Left => lm.left,
        };
        let swing = |lm: &crate::figure::Landmarks| match step.side {
            crate::kinematics::pelvis::Side::Right => lm.left,
            crate::kinematics::pelvis::Side::Left => lm.right,
        };
        let x0 = rows[0].pelvis[0];
        let span = rows[n].pelvis[0] - x0;
        let stance_pitch: Vec<f64> = rows.iter().map(|r| sagittal_pitch(&stance(r))).collect();
        let at = |i: usize| i as f64 / n as f64;
        let flat = stance_pitch.iter().position(|p| *p > -1e-6).map_or(0.0, at);
        let i_flat = (flat * n as f64).round() as usize;
        let heel_off = stance_pitch[i_flat..]
            .iter()
            .position(|p| p.abs() > 1e-6)
            .map_or(1.0, |i| at(i + i_flat));
        let last = &rows[n];
        Ok(WalkingStep {
            length: step.constraints.gait.step_length,
            duration: t.t_step,
            height: rows.iter().map(|r| r.pelvis[1]).collect(),
            travel: rows.iter().map(|r| (r.pelvis[0] - x0) / span).collect(),
            stance_pitch,
            swing_pitch: rows.iter().map(|r| sagittal_pitch(&swing(r))).collect(),
            flat,
            heel_off,
            toe_off: t.t_ds / t.t_step,
            reach_at_strike: [
                distance(swing(last).hip, swing(last).ankle),
                distance(stance(last).hip, stance(last).ankle),
            ],
        })
    }

    /// The second step of a two-step walk of `gait` simulated by the engine (the first is the
    /// start-up step), sampled at `n + 1` points.
    pub fn simulate(
        body: Body,
        attrs: &Attributes,
        gait: Gait,
        n: usize,
    ) -> Result<Self, NrsError> {
        let failed = |source| NrsError::Walking {
            step_length: gait.step_length,
            duration: 60.0 / gait.step_frequency,
            source,
        };
        let walk = walker::simulate(body, attrs.clone(), &[gait, gait]).map_err(failed)?;
        Ok(Self::from_step(&walk.steps[1], attrs, n)?)
    }

    /// [`Self::simulate`], or where the engine cannot walk `gait` (a short step's start-up step
    /// fails: docs/nrs.md) \[ours\] the first of the steps `BORROW_STEP` m, 2 × …, up to
    /// `BORROW_TRIES` × longer at the same frequency that it can walk, its hip height's
    /// excursion about the line between its ends scaled by the length ratio ([`Self::shortened`]);
    /// the engine's error when none works.
    pub fn borrowed(
        body: Body,
        attrs: &Attributes,
        gait: Gait,
        n: usize,
    ) -> Result<Self, NrsError> {
        let first = match Self::simulate(body, attrs, gait, n) {
            Ok(w) => return Ok(w),
            Err(e @ NrsError::Walking { .. }) => e,
            Err(e) => return Err(e),
        };
        for k in 1..=BORROW_TRIES {
            let request = crate::plan::GaitRequest {
                step_length: Some(gait.step_length + k as f64 * BORROW_STEP),
                step_frequency: Some(gait.step_frequency),
                velocity: None,
            };
            let Ok(longer) = request.complete(&body, attrs) else {
                break;
            };
            if let Ok(w) = Self::simulate(body, attrs, longer, n) {
                return Ok(w.shortened(gait.step_length));
            }
        }
        Err(first)
    }

    /// This step as the hip heights of a step of `length`: the height's excursion about the
    /// straight line between its two ends scaled by `length / self.length` (a shorter step
    /// vaults less over its stance leg); the time law, the feet's pitches and the phase moments
    /// kept.
    pub fn shortened(mut self, length: f64) -> Self {
        let ratio = length / self.length;
        let n = self.height.len() - 1;
        let (a, b) = (self.height[0], self.height[n]);
        for (i, h) in self.height.iter_mut().enumerate() {
            let line = a + (b - a) * i as f64 / n as f64;
            *h = line + ratio * (*h - line);
        }
        self.length = length;
        self
    }

    /// The swing foot's pitch at TOM.
    pub fn toe_off_pitch(&self) -> f64 {
        at_fraction(&self.swing_pitch, self.toe_off)
    }
}

/// A uniformly sampled curve at normalized time t (linear interpolation).
pub(crate) fn at_fraction(q: &[f64], t: f64) -> f64 {
    let n = q.len() - 1;
    let x = t.clamp(0.0, 1.0) * n as f64;
    let i = (x.floor() as usize).min(n - 1);
    q[i] + (x - i as f64) * (q[i + 1] - q[i])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::GaitRequest;

    /// The sampled step agrees with the engine's own records: its heights are the pelvis
    /// centre's (`Instant::pelvis_centre`: the dynamic hip moved by the list's centre shift),
    /// its phase moments lie in the order FGM ≤ heel-off, TOM at t_ds, the stance foot is flat
    /// between FGM and heel-off, and the reach at heel strike is at most the leg's length.
    #[test]
    fn a_walking_step_is_sampled_from_the_engine() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let attrs = crate::model::attributes::AttributeTable::builtin().defaults();
        let gait = GaitRequest {
            velocity: Some(1.2),
            ..Default::default()
        }
        .complete(&body, &attrs)
        .unwrap();
        let walk = walker::simulate(body, attrs.clone(), &[gait, gait]).unwrap();
        let w = WalkingStep::from_step(&walk.steps[1], &attrs, 100).unwrap();
        let s = &walk.steps[1];
        for i in [0, 37, 100] {
            let tau = s.constraints.timing.t_step * i as f64 / 100.0;
            assert!((w.height[i] - s.at(tau).pelvis_centre()[1]).abs() < 1e-12);
        }
        assert!(w.travel[0] == 0.0 && (w.travel[100] - 1.0).abs() < 1e-15);
        assert!(
            w.travel.windows(2).all(|p| p[1] >= p[0]),
            "the hip only moves forward"
        );
        assert!(w.flat <= w.heel_off && w.toe_off > 0.0 && w.toe_off < 0.5);
        let (a, b) = (
            // the first flat sample (`flat` is a sample's time, and ×100 may round up past it)
            (w.flat * 100.0).round() as usize,
            (w.heel_off * 100.0) as usize,
        );
        assert!(
            w.stance_pitch[a..b].iter().all(|p| p.abs() < 1e-6),
            "{} {}",
            w.flat,
            w.heel_off
        );
        assert!(
            w.stance_pitch[..a].iter().all(|p| *p < 0.0),
            "the heel rocker: toes up"
        );
        assert!(
            w.reach_at_strike
                .iter()
                .all(|r| *r <= body.l1 + 1e-9 && *r > 0.8 * body.l1)
        );
        assert!((w.duration - 60.0 / gait.step_frequency).abs() < 1e-12);
    }

    /// A shortened step keeps its end heights and its time law, and its height's excursion about
    /// the line between the ends is the original's times the length ratio, at every sample.
    #[test]
    fn a_shortened_step_scales_its_hip_excursion() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let attrs = crate::model::attributes::AttributeTable::builtin().defaults();
        let gait = GaitRequest {
            velocity: Some(1.0),
            ..Default::default()
        }
        .complete(&body, &attrs)
        .unwrap();
        let w = WalkingStep::simulate(body, &attrs, gait, 64).unwrap();
        let s = w.clone().shortened(0.5 * w.length);
        let (a, b) = (w.height[0], w.height[64]);
        assert_eq!((s.height[0], s.height[64]), (a, b));
        for i in 0..=64 {
            let line = a + (b - a) * i as f64 / 64.0;
            assert!(((s.height[i] - line) - 0.5 * (w.height[i] - line)).abs() < 1e-15);
        }
        assert_eq!(s.travel, w.travel);
        assert!((s.length - 0.5 * w.length).abs() < 1e-15);
    }
}
