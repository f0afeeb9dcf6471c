//! A scenario's foot contacts: when each foot comes down on the floor (foot strike) and leaves
//! it (foot off), found on the continuous motion, not on the frames: whatever moves the foot —
//! the walking engine, an NRS⁻, a turnaround — a foot touches the floor while its lowest point
//! (heel, first metatarsal joint or toe tip) is within `contact_height` of it (models/nrs.toml).
//! Each change is bracketed on a 1 ms grid and bisected to 1e-9 s.
use serde::Serialize;

use crate::figure::{Landmarks, LegPoints};
use crate::nrs::Side;
use crate::scenario::Span;

/// The grid on which a change of contact is bracketed (s).
const SCAN: f64 = 1e-3;
/// The bisection's stop: the bracket's width (s).
const TIME_TOLERANCE: f64 = 1e-9;

/// One contact event of a scenario.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Contact {
    /// Its time (s, from the scenario's start).
    pub time_s: f64,
    /// `right` or `left`.
    pub side: &'static str,
    /// `foot_strike` (the foot comes down to the floor) or `foot_off` (it leaves it).
    pub event: &'static str,
    /// The index of the action it belongs to (the scenario's, from 0).
    pub action: usize,
    /// What ran then (the span's kind: `start`, `walk`, `stop`, `step`, `turn`).
    pub kind: &'static str,
}

/// The height of the foot's lowest point above the floor (m).
pub fn lowest(leg: &LegPoints) -> f64 {
    leg.heel[1].min(leg.mtp[1]).min(leg.toe[1])
}

/// Whether each foot (right, left) touches the floor in `lm`.
fn touching(lm: &Landmarks, height: f64) -> [bool; 2] {
    [lowest(&lm.right) <= height, lowest(&lm.left) <= height]
}

/// Every contact event of the spans, in time order: `pose(k, t)` is the figure at time t of
/// span k, and the feet's contacts at the first span's start are the state events change. A
/// span that holds a pose (`stand`, `pause`) has none.
pub(crate) fn contacts<E>(
    spans: &[Span],
    height: f64,
    pose: impl Fn(usize, f64) -> Result<Landmarks, E>,
) -> Result<Vec<Contact>, E> {
    let mut out = Vec::new();
    let Some(first) = spans.first() else {
        return Ok(out);
    };
    let mut state = touching(&pose(0, first.t_start)?, height);
    for (k, span) in spans.iter().enumerate() {
        if matches!(span.kind, "stand" | "pause") || span.t_end <= span.t_start {
            continue;
        }
        let n = ((span.t_end - span.t_start) / SCAN).ceil().max(1.0) as usize;
        let at = |i: usize| (span.t_start + i as f64 * SCAN).min(span.t_end);
        let mut a = span.t_start;
        for i in 0..=n {
            let b = at(i);
            let now = touching(&pose(k, b)?, height);
            for (foot, (&was, &is)) in state.iter().zip(&now).enumerate() {
                if was == is {
                    continue;
                }
                let (mut lo, mut hi) = (a, b);
                while hi - lo > TIME_TOLERANCE {
                    let mid = 0.5 * (lo + hi);
                    if touching(&pose(k, mid)?, height)[foot] == was {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                out.push(Contact {
                    time_s: hi,
                    side: [Side::Right, Side::Left][foot].name(),
                    event: if is { "foot_strike" } else { "foot_off" },
                    action: span.action,
                    kind: span.kind,
                });
            }
            state = now;
            a = b;
        }
    }
    out.sort_by(|x, y| x.time_s.total_cmp(&y.time_s));
    Ok(out)
}
