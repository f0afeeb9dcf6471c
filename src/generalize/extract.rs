//! A prototype from a klaw walk (docs/generalize.md, "Extraction"): one steady step of a walk
//! simulated by the dynamic engine, read from its figure ([`crate::figure::landmarks()`]) and its
//! gait events, as walk data made consistent with its own walk condition.
use crate::analysis::events::step_events;
use crate::engine::walker::Walk;
use crate::figure::{LegPoints, landmarks};
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

/// The walk data of step `k` of `walk` (a steady step: 1 ≤ k, and step k + 1 simulated, through
/// whose double support the stance foot rolls to its toe-off), made consistent with its own
/// walk condition ([`generalize`] onto it: its ends on eq. 11's hip and Lemma 1's ankles; a
/// steady walk moves them by well under a millimetre). The α slopes are `params`'.
/// (Longer than 80 lines: it reads the step's sequences in the order of eq. 4 from one set of
/// closures over the walk; split, each part would take them all as arguments.)
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
    let side = step.side;
    let leg = |lm: &crate::figure::Landmarks, s: Side| match s {
        Side::Right => lm.right,
        Side::Left => lm.left,
    };
    let x0 = step.x_ankle;

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

    let (ang, len) = (params.sample_angle, params.sample_length);
    let min = params.samples_per_step;
    let stance = |t: f64| pose(t).map(|lm| leg(&lm, side));
    let swing = |t: f64| pose(t).map(|lm| leg(&lm, side.other()));
    let (t1, f1) = adaptive(0.0, fgm, min, [ang], &|t| {
        stance(t).map(|l| [foot_pitch(&l).min(0.0)])
    })?;
    // F2 sampled piecewise, so that its corners at heel-off and at MOM are samples
    let mut t2 = Vec::new();
    let mut f2 = Vec::new();
    for (a, b) in [(fgm, heel_off), (heel_off, mom), (mom, 1.0 + tom)] {
        if b > a || (t2.is_empty() && b == 1.0 + tom) {
            let (t, v) = adaptive(a, b, min, [ang], &|t| stance(t).map(|l| [foot_pitch(&l)]))?;
            let skip = usize::from(!t2.is_empty());
            t2.extend_from_slice(&t[skip..]);
            f2.extend_from_slice(&v[skip..]);
        }
    }
    let (tm, meta) = adaptive(mom, 1.0 + tom, min, [ang], &|t| {
        stance(t).map(|l| [toe_angle(&l).max(0.0)])
    })?;
    let (ts, sw) = adaptive(tom, 1.0, min, [ang, len, len], &|t| {
        swing(t).map(|l| [foot_pitch(&l), l.ankle[0] - x0, l.ankle[1]])
    })?;
    let (th, up) = adaptive(0.0, 1.0, min, [len, len, ang], &|t| {
        pose(t).map(|f| {
            [
                f.pelvis[0] - x0,
                f.pelvis[1],
                f.pelvis_tilt - attrs.pelvis_tilt,
            ]
        })
    })?;
    let column = |v: &[[f64; 3]], j: usize| v.iter().map(|r| r[j]).collect::<Vec<f64>>();
    let first = |v: &[[f64; 1]]| v.iter().map(|r| r[0]).collect::<Vec<f64>>();
    let (f1, f2, meta, f3) = (first(&f1), first(&f2), first(&meta), column(&sw, 0));
    let hip = Path {
        t: th.clone(),
        x: column(&up, 0),
        y: column(&up, 1),
    };
    let trunk = Curve {
        t: th,
        v: column(&up, 2),
    };
    let (ax, ay) = (column(&sw, 1), column(&sw, 2));

    let body = BodyCondition::of(&walk.body);
    let sl = next.x_ankle - x0;
    let before = x0 - prev.x_ankle;
    let landing = swing(1.0)?;
    let ll = body.leg_length();
    let pelvis = Pelvis {
        rotation: attrs.pelvic_rotation,
        step_width: attrs.step_width,
    };
    let mut character = Character {
        step_length: sl / ll,
        knee_at_strike: knee_flexion(&landing),
        foot_at_strike: -f3[f3.len() - 1],
        foot_at_toe_off: f2[f2.len() - 1],
        meta_at_toe_off: meta[meta.len() - 1],
        alpha: params.alphas(),
        hip_lead: hip.last()[0] / sl,
        hip_offset: 0.0,
    };
    character.hip_offset = (hip.last()[1] - hip_at_strike(&body, &character, &pelvis, sl)?[1]) / ll;
    let raw = WalkData {
        source: format!(
            "klaw walk, step {k} of {n}: H {} m, M {} kg, sl {sl:.4} m, sf {:.2} steps/min",
            walk.body.height, walk.body.mass, step.constraints.gait.step_frequency
        ),
        body,
        step_length: sl,
        step_length_before: before,
        pelvis,
        character,
        phases,
        hip,
        f1: Piece::new(t1, &f1, false, AMPLITUDE_EPSILON),
        f2: Piece::new(t2, &f2, true, AMPLITUDE_EPSILON),
        f3: Curve {
            t: ts.clone(),
            v: f3,
        },
        meta: Piece::new(tm, &meta, true, AMPLITUDE_EPSILON),
        ankle: Path {
            t: ts,
            x: ax,
            y: ay,
        },
        trunk,
    };
    raw.check()?;
    generalize(&raw, &Target::of(&raw))
}
