//! Gait events of each foot (spec §9), at their exact times (bisection on the continuous motion
//! to 1e-9 s, not rounded to frames): heel strike (HS), foot flat (FGM: the sole angle reaches
//! 0), heel-off (the foot pitch leaves 0), metatarsal-off (MOM: the toe joint reaches its limit
//! θ6_max and the foot rolls on over the toe tip) and toe-off (TO: heel strike + t_stance).
use serde::Serialize;

use crate::engine::walker::{Step, Walk};
use crate::kinematics::pelvis::Side;
use crate::numerics::roots;

/// One event.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Event {
    /// Time of the event since the first heel strike (s).
    pub time_s: f64,
    /// `right` or `left`.
    pub side: &'static str,
    /// `HS`, `FGM`, `heel_off`, `MOM` or `TO`.
    pub event: &'static str,
    /// The step whose heel strike started this foot's stance.
    pub step: usize,
}

const TIME_TOLERANCE: f64 = 1e-9;

/// Foot pitch (heel up +) of the stance foot of `steps[0]` at world time t, through the next
/// step's double support (`steps[1]`, if any).
fn pitch(steps: &[Step], t: f64) -> f64 {
    let s = &steps[0];
    match steps.get(1) {
        Some(next) if t >= next.t_start => {
            let foot = next.stance_leg.foot;
            let p = next.swing_pose(t - next.t_start, &foot);
            // heel above the metatarsal joint: the pitch of the hind foot
            (p.foot.heel[1] - p.foot.meta[1]).atan2(p.foot.meta[0] - p.foot.heel[0])
        }
        _ => s.stance_pose(t - s.t_start).map_or(f64::NAN, |p| p.pitch),
    }
}

/// Every event of the walk, in time order. The stance of the last step has no toe-off inside
/// the walk: its events stop at the walk's end.
pub fn events(walk: &Walk) -> Vec<Event> {
    let mut out: Vec<Event> = (0..walk.steps.len())
        .flat_map(|i| {
            step_events(
                &walk.steps[i..(i + 2).min(walk.steps.len())],
                walk.duration(),
            )
        })
        .collect();
    out.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
    out
}

/// The events of the stance that starts with `steps[0]`, through the next step's double
/// support (`steps[1]`, when there is one; without it they stop at `end`).
pub(crate) fn step_events(steps: &[Step], end: f64) -> Vec<Event> {
    let mut out = Vec::new();
    let s = &steps[0];
    let side = Side::of_step(s.index).name();
    let mut push = |event, time_s| {
        out.push(Event {
            time_s,
            side,
            event,
            step: s.index,
        })
    };
    let t0 = s.t_start;
    push("HS", t0);
    let t_off = steps.get(1).map(|n| n.t_start + n.constraints.timing.t_ds);
    let stop = t_off.unwrap_or(end);
    let p = |t: f64| pitch(steps, t);
    // foot flat: the sole angle (−pitch) comes down to 0
    let flat = |t: f64| p(t) >= 0.0;
    let t_fgm = s.t_start + s.stance_leg.t_fgm;
    if let Some(fgm) = [t_fgm, stop]
        .into_iter()
        .find(|&t| flat(t))
        .map(|t| roots::bisect(flat, t, t0, TIME_TOLERANCE).0)
    {
        push("FGM", fgm);
        // heel-off: the pitch leaves 0; scan in 1 ms steps, then bisect
        let lifted = |t: f64| p(t) > 1e-12;
        let ms = std::iter::successors(Some(fgm), |&t| (t < stop).then(|| (t + 1e-3).min(stop)));
        if let Some(((t, _), (u, _))) = roots::scan(fgm, ms.skip(1), lifted, |&on| on) {
            let heel_off = roots::bisect(lifted, u, t, TIME_TOLERANCE).0;
            push("heel_off", heel_off);
            let limit = s.stance_leg.theta6_max;
            let rolled = |t: f64| p(t) >= limit;
            if rolled(stop) {
                push(
                    "MOM",
                    roots::bisect(rolled, stop, heel_off, TIME_TOLERANCE).0,
                );
            }
        }
    }
    if let Some(t_off) = t_off {
        push("TO", t_off);
    }
    out
}
