//! The heel strikes that delimit the gait cycles of a walk given only as frames: from the step
//! index of klaw's frames, or from the kinematics (the ankle's foremost position).
use glam::DVec3;
use serde::Serialize;

use super::segments::{Segments, pose};
use crate::figure::clinical::Clinical;
use crate::figure::placement::direction;
use crate::model::body::Body;

/// Heel strike times of each foot (s), increasing.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct HeelStrikes {
    /// The right foot's.
    pub right: Vec<f64>,
    /// The left foot's.
    pub left: Vec<f64>,
}

/// From klaw's step index (`Clinical::step`, the CSV's `step` column): a step starts with a heel
/// strike, of the right foot for even steps and the left for odd ones, at the step's first
/// frame; the file's first frame only if its time is 0 (klaw's frames start at the first heel
/// strike; a file cut mid-step does not). The times are the frames', so they are late by less
/// than one frame interval.
pub fn from_steps(frames: &[Clinical]) -> HeelStrikes {
    let mut out = HeelStrikes::default();
    for (k, f) in frames.iter().enumerate() {
        let starts = match k {
            0 => f.time == 0.0,
            _ => f.step != frames[k - 1].step,
        };
        if starts {
            match f.step % 2 {
                0 => out.right.push(f.time),
                _ => out.left.push(f.time),
            }
        }
    }
    out
}

/// From the kinematics alone (Zeni, Richards & Higginson 2008, who use the heel marker relative
/// to the sacrum): a heel strike is a time when the ankle (placed by [`Segments::ankles`] from
/// the hip and knee angles) is farthest ahead of the pelvis centre along the walking direction,
/// the largest such distance within `window` s either side; the time is refined between frames
/// by the parabola through the frame and its neighbours. The walking direction is the mean
/// pelvis rotation's heading (a straight walk). Maxima at the first or last frame are not
/// counted (the walk may go on beyond them).
pub fn from_kinematics(frames: &[Clinical], body: &Body, window: f64) -> HeelStrikes {
    let segments = Segments::new(body);
    let n = frames.len();
    let heading = frames.iter().map(|f| f.pelvis_rotation).sum::<f64>() / n.max(1) as f64;
    let forward = DVec3::from_array(direction(heading));
    let ahead: Vec<[f64; 2]> = frames
        .iter()
        .map(|f| {
            let mut p = pose(f);
            p[..3].fill(0.0);
            segments.ankles(&p).map(|a| a.dot(forward))
        })
        .collect();
    let times: Vec<f64> = frames.iter().map(|f| f.time).collect();
    let strikes = |side: usize| -> Vec<f64> {
        let d: Vec<f64> = ahead.iter().map(|a| a[side]).collect();
        (1..n.saturating_sub(1))
            .filter(|&k| {
                let lo = times.partition_point(|&t| t < times[k] - window);
                let hi = times.partition_point(|&t| t <= times[k] + window);
                d[k] >= d[k - 1] && d[k] > d[k + 1] && d[lo..hi].iter().all(|&x| x <= d[k])
            })
            .map(|k| {
                vertex(
                    [times[k - 1], times[k], times[k + 1]],
                    [d[k - 1], d[k], d[k + 1]],
                )
            })
            .collect()
    };
    HeelStrikes {
        right: strikes(0),
        left: strikes(1),
    }
}

/// The time of the extremum of the parabola through three points (t, y), t increasing; the
/// middle time when they are collinear.
fn vertex([t0, t1, t2]: [f64; 3], [y0, y1, y2]: [f64; 3]) -> f64 {
    let (a, b) = (t1 - t0, t2 - t1);
    let (s0, s1) = ((y1 - y0) / a, (y2 - y1) / b);
    // y' is linear: s0 at (t0 + t1)/2, s1 at (t1 + t2)/2; its zero
    let curvature = (s1 - s0) / (0.5 * (a + b));
    if curvature == 0.0 {
        return t1;
    }
    (0.5 * (t0 + t1) - s0 / curvature).clamp(t0, t2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_vertex_of_a_parabola() {
        let y = |t: f64| -(t - 0.37).powi(2) + 2.0;
        let t = [0.2, 0.35, 0.55];
        assert!((vertex(t, t.map(y)) - 0.37).abs() < 1e-12);
        assert_eq!(vertex([0.0, 1.0, 2.0], [1.0, 1.0, 1.0]), 1.0);
    }

    #[test]
    fn steps_start_with_heel_strikes() {
        let frame = |time: f64, step: usize| Clinical {
            time,
            step,
            ..Default::default()
        };
        let f: Vec<Clinical> = [(0.0, 0), (0.5, 0), (0.6, 1), (1.1, 1), (1.2, 2), (1.3, 2)]
            .map(|(t, s)| frame(t, s))
            .to_vec();
        let h = from_steps(&f);
        assert_eq!((h.right, h.left), (vec![0.0, 1.2], vec![0.6]));
        // a file cut mid-step: its first frame is no heel strike
        let h = from_steps(&f[1..]);
        assert_eq!((h.right, h.left), (vec![1.2], vec![0.6]));
    }
}
