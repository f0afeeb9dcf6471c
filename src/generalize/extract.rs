//! A prototype from a klaw walk (docs/generalize.md, "Extraction"): one steady step of a walk
//! simulated by the dynamic engine, read from its figure ([`crate::figure::landmarks()`]) and its
//! gait events, as walk data made consistent with its own walk condition.
use crate::analysis::events::step_events;
use crate::engine::walker::Walk;
use crate::figure::{Landmarks, LegPoints, landmarks};
use crate::generalize::condition::BodyCondition;
use crate::generalize::error::GeneralizeError;
use crate::generalize::geometry::{Character, Pelvis, hip_at_strike};
use crate::generalize::parameters::GeneralizeParameters;
use crate::generalize::sequence::{Curve, Path, grid};
use crate::generalize::transform::{Target, generalize};
use crate::generalize::walk_data::{Phases, Piece, WalkData};
use crate::kinematics::pelvis::Side;

/// The anchor of a piece is 0 below this (rad): its shape is then a ramp.
pub(crate) const AMPLITUDE_EPSILON: f64 = 1e-6;

/// A foot's pitch, heel up +: the heel → ball (metatarsal joint) line's angle from the floor.
pub fn foot_pitch(leg: &LegPoints) -> f64 {
    (leg.heel[1] - leg.mtp[1]).atan2(leg.mtp[0] - leg.heel[0])
}

/// The toes' angle from the floor, the ball up +: the ball → toe tip line's.
pub fn toe_angle(leg: &LegPoints) -> f64 {
    (leg.mtp[1] - leg.toe[1]).atan2(leg.toe[0] - leg.mtp[0])
}

/// The knee's flexion (rad, 0 straight): the angle between thigh and shank.
pub fn knee_flexion(leg: &LegPoints) -> f64 {
    let d = |a: [f64; 3], b: [f64; 3]| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let (u, v) = (d(leg.hip, leg.knee), d(leg.knee, leg.ankle));
    let dot: f64 = (0..3).map(|i| u[i] * v[i]).sum();
    let cross = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let c: f64 = cross.iter().map(|x| x * x).sum::<f64>().sqrt();
    c.atan2(dot)
}

/// A function sampled on [a, b] so that eq. 2's linear interpolation reproduces it to
/// `tolerance` (each component) at the middle of every interval: first `per_unit` intervals per
/// unit of time (at least 2), then each interval whose midpoint is off by more is halved, down
/// to 1e-5 of normalized time. A single sample where a = b.
pub(crate) type Sampled<const K: usize> = (Vec<f64>, Vec<[f64; K]>);

/// The samples of [`Sampled`].
pub(crate) fn adaptive<const K: usize>(
    a: f64,
    b: f64,
    per_unit: usize,
    tolerance: [f64; K],
    f: &dyn Fn(f64) -> Result<[f64; K], GeneralizeError>,
) -> Result<Sampled<K>, GeneralizeError> {
    if b <= a {
        return Ok((vec![a], vec![f(a)?]));
    }
    let start = grid(a, b, (((b - a) * per_unit as f64).ceil() as usize).max(2));
    let mut out_t = vec![a];
    let mut out_v = vec![f(a)?];
    for w in start.windows(2) {
        // depth-first: the stack holds the right parts still to do
        let mut stack = vec![(w[1], f(w[1])?)];
        while let Some(&(t1, v1)) = stack.last() {
            let (t0, v0) = (out_t[out_t.len() - 1], out_v[out_v.len() - 1]);
            let mid = 0.5 * (t0 + t1);
            let vm = f(mid)?;
            let off = (0..K).any(|j| (vm[j] - 0.5 * (v0[j] + v1[j])).abs() > tolerance[j]);
            if off && t1 - t0 > 1e-5 {
                stack.push((mid, vm));
            } else {
                out_t.push(t1);
                out_v.push(v1);
                stack.pop();
            }
        }
    }
    Ok((out_t, out_v))
}

/// The sequences of one step as read from a walk, before they are made walk data: F1, F2 and M
/// as (times, values) of the stance foot's timeline, F3 and A of the swing foot's, H and the
/// trunk of the step.
pub(crate) struct Sequences {
    pub(crate) f1: (Vec<f64>, Vec<f64>),
    pub(crate) f2: (Vec<f64>, Vec<f64>),
    pub(crate) meta: (Vec<f64>, Vec<f64>),
    pub(crate) f3: Curve,
    pub(crate) ankle: Path,
    pub(crate) hip: Path,
    pub(crate) trunk: Curve,
}

/// What a read step is besides its sequences: where it came from, the body, its step length
/// and the one before it (m), the pelvis, the swing knee's flexion at heel strike (rad), the α
/// slopes and the phase moments.
pub(crate) struct Condition {
    pub(crate) source: String,
    pub(crate) body: BodyCondition,
    pub(crate) step_length: f64,
    pub(crate) before: f64,
    pub(crate) pelvis: Pelvis,
    pub(crate) knee_at_strike: f64,
    /// A foot that lands flat lands flat at every step length: μ2 = 0.
    pub(crate) lands_flat: bool,
    pub(crate) alpha: [f64; 4],
    pub(crate) phases: Phases,
}

/// The walk data of a read step: its character from the sequences' ends (μ2 = −F3 at heel
/// strike, μ3 = F2 and μ4 = M at toe-off, the hip's lead over the step and its height over
/// eq. 11's), checked and made consistent with its own walk condition ([`generalize`] onto it:
/// its ends on eq. 11's hip and Lemma 1's ankles).
pub(crate) fn assemble(c: Condition, s: Sequences) -> Result<WalkData, GeneralizeError> {
    let (sl, ll) = (c.step_length, c.body.leg_length());
    let last = |v: &[f64]| v[v.len() - 1];
    let mut character = Character {
        step_length: sl / ll,
        knee_at_strike: c.knee_at_strike,
        foot_at_strike: if c.lands_flat { 0.0 } else { -last(&s.f3.v) },
        foot_at_toe_off: last(&s.f2.1),
        meta_at_toe_off: last(&s.meta.1),
        alpha: c.alpha,
        hip_lead: s.hip.last()[0] / sl,
        hip_offset: 0.0,
    };
    let strike = hip_at_strike(&c.body, &character, &c.pelvis, sl)?;
    character.hip_offset = (s.hip.last()[1] - strike[1]) / ll;
    let raw = WalkData {
        source: c.source,
        body: c.body,
        step_length: sl,
        step_length_before: c.before,
        pelvis: c.pelvis,
        character,
        phases: c.phases,
        hip: s.hip,
        f1: Piece::new(s.f1.0, &s.f1.1, false, AMPLITUDE_EPSILON),
        f2: Piece::new(s.f2.0, &s.f2.1, true, AMPLITUDE_EPSILON),
        f3: s.f3,
        meta: Piece::new(s.meta.0, &s.meta.1, true, AMPLITUDE_EPSILON),
        ankle: s.ankle,
        trunk: s.trunk,
    };
    raw.check()?;
    generalize(&raw, &Target::of(&raw))
}

/// A leg of a figure.
fn leg(lm: &Landmarks, s: Side) -> LegPoints {
    match s {
        Side::Right => lm.right,
        Side::Left => lm.left,
    }
}

/// The sequences of a step whose figure at the stance foot's normalized time is `pose`, standing
/// on `side` with its flat ankle at x0, sampled by [`adaptive`] (F2 piecewise, so that its
/// corners at heel-off and at MOM are samples); the trunk less the pelvis tilt `tilt`.
fn sample(
    pose: &dyn Fn(f64) -> Result<Landmarks, GeneralizeError>,
    side: Side,
    x0: f64,
    tilt: f64,
    ph: &Phases,
    params: &GeneralizeParameters,
) -> Result<Sequences, GeneralizeError> {
    let (ang, len) = (params.sample_angle, params.sample_length);
    let min = params.samples_per_step;
    let end = 1.0 + ph.tom;
    let stance = |t: f64| pose(t).map(|lm| leg(&lm, side));
    let swing = |t: f64| pose(t).map(|lm| leg(&lm, side.other()));
    let first = |(t, v): Sampled<1>| (t, v.iter().map(|r| r[0]).collect::<Vec<f64>>());
    let f1 = first(adaptive(0.0, ph.fgm, min, [ang], &|t| {
        stance(t).map(|l| [foot_pitch(&l).min(0.0)])
    })?);
    let mut f2 = (Vec::new(), Vec::new());
    for (a, b) in [(ph.fgm, ph.heel_off), (ph.heel_off, ph.mom), (ph.mom, end)] {
        if b > a || (f2.0.is_empty() && b == end) {
            let (t, v) = first(adaptive(a, b, min, [ang], &|t| {
                stance(t).map(|l| [foot_pitch(&l)])
            })?);
            let skip = usize::from(!f2.0.is_empty());
            f2.0.extend_from_slice(&t[skip..]);
            f2.1.extend_from_slice(&v[skip..]);
        }
    }
    let meta = first(adaptive(ph.mom, end, min, [ang], &|t| {
        stance(t).map(|l| [toe_angle(&l).max(0.0)])
    })?);
    let (ts, sw) = adaptive(ph.tom, 1.0, min, [ang, len, len], &|t| {
        swing(t).map(|l| [foot_pitch(&l), l.ankle[0] - x0, l.ankle[1]])
    })?;
    let (th, up) = adaptive(0.0, 1.0, min, [len, len, ang], &|t| {
        pose(t).map(|f| [f.pelvis[0] - x0, f.pelvis[1], f.pelvis_tilt - tilt])
    })?;
    let column = |v: &[[f64; 3]], j: usize| v.iter().map(|r| r[j]).collect::<Vec<f64>>();
    Ok(Sequences {
        f1,
        f2,
        meta,
        f3: Curve {
            t: ts.clone(),
            v: column(&sw, 0),
        },
        ankle: Path {
            t: ts,
            x: column(&sw, 1),
            y: column(&sw, 2),
        },
        hip: Path {
            t: th.clone(),
            x: column(&up, 0),
            y: column(&up, 1),
        },
        trunk: Curve {
            t: th,
            v: column(&up, 2),
        },
    })
}

/// The walk data of step `k` of `walk` (a steady step: 1 ≤ k, and step k + 1 simulated, through
/// whose double support the stance foot rolls to its toe-off), made consistent with its own
/// walk condition (its ends on eq. 11's hip and Lemma 1's ankles; a steady walk's ends move by
/// well under a millimetre). The α slopes are `params`'.
pub fn from_walk(
    walk: &Walk,
    k: usize,
    params: &GeneralizeParameters,
) -> Result<WalkData, GeneralizeError> {
    let n = walk.steps.len();
    if k == 0 || k + 1 >= n {
        return Err(GeneralizeError::invalid(
            "step",
            format!(
                "step {k} of a walk of {n} steps: a prototype is a step with one before it and \
                 one after it (1 ≤ step ≤ {})",
                n.saturating_sub(2)
            ),
        ));
    }
    let (prev, step, next) = (&walk.steps[k - 1], &walk.steps[k], &walk.steps[k + 1]);
    let attrs = &walk.attrs;
    let t_step = step.constraints.timing.t_step;
    let tom = step.constraints.timing.t_ds / t_step;
    let t_ds_next = next.constraints.timing.t_ds;
    // world time of the stance foot's normalized time: step k over [0, 1], then step k + 1's
    // double support mapped onto [1, 1 + TOM]
    let world = |t: f64| {
        if t <= 1.0 {
            step.t_start + t * t_step
        } else {
            next.t_start + (t - 1.0) / tom * t_ds_next
        }
    };
    let normalized = |w: f64| {
        if w <= next.t_start {
            (w - step.t_start) / t_step
        } else {
            1.0 + (w - next.t_start) / t_ds_next * tom
        }
    };
    let pose = |t: f64| {
        let s = if t <= 1.0 { step } else { next };
        landmarks(s, world(t), attrs).map_err(|e| GeneralizeError::invalid("walk", e.to_string()))
    };
    let events = step_events(&walk.steps[k..k + 2], walk.duration());
    let at = |name: &str| events.iter().find(|e| e.event == name).map(|e| e.time_s);
    let fgm = normalized(at("FGM").unwrap_or(step.t_start + step.stance_leg.t_fgm));
    let mom = at("MOM").map_or(1.0 + tom, normalized).min(1.0 + tom);
    let heel_off = at("heel_off").map_or(mom, normalized).clamp(fgm, mom);
    let phases = Phases {
        fgm,
        heel_off,
        mom,
        tom,
    };
    let x0 = step.x_ankle;
    let sequences = sample(&pose, step.side, x0, attrs.pelvis_tilt, &phases, params)?;
    let sl = next.x_ankle - x0;
    let condition = Condition {
        source: format!(
            "klaw walk, step {k} of {n}: H {} m, M {} kg, sl {sl:.4} m, sf {:.2} steps/min",
            walk.body.height, walk.body.mass, step.constraints.gait.step_frequency
        ),
        body: BodyCondition::of(&walk.body),
        step_length: sl,
        before: x0 - prev.x_ankle,
        pelvis: Pelvis {
            rotation: attrs.pelvic_rotation,
            step_width: attrs.step_width,
        },
        knee_at_strike: knee_flexion(&leg(&pose(1.0)?, step.side.other())),
        lands_flat: false,
        alpha: params.alphas(),
        phases,
    };
    assemble(condition, sequences)
}
