//! The difference between two walks' angle trajectories (Pronost et al. 2006, eq. 7): the root
//! mean square of their difference once the second is shifted to the first one's mean,
//!
//! e = √( (1/N) Σₖ (θ(tₖ) − θ̂(tₖ) − (θ̄ − θ̂̄))² ),
//!
//! over N common samples (the paper's (1/T) Σ over the frames of its duration T). Two files are
//! compared on their gait cycles averaged over 0, 1, …, 100 % (`analysis::cycle`), each leg's
//! angles on its own cycles, the pelvis's on the right foot's.
use serde::Serialize;

use super::CriteriaFrames;
use crate::analysis::cycle::average_cycles;
use crate::figure::clinical::angle_columns;

/// The angles compared: the paper's eleven and the ankles' dorsiflexion.
pub const COMPARED: [&str; 13] = [
    "pelvis_tilt",
    "pelvis_list",
    "pelvis_rotation",
    "hip_flexion_r",
    "hip_adduction_r",
    "hip_rotation_r",
    "knee_flexion_r",
    "ankle_dorsiflexion_r",
    "hip_flexion_l",
    "hip_adduction_l",
    "hip_rotation_l",
    "knee_flexion_l",
    "ankle_dorsiflexion_l",
];

/// Eq. 7 between two trajectories sampled at the same N instants (rad if they are): NaN when
/// they are empty or of unequal length, or a sample is not finite.
pub fn mean_shifted_rms(a: &[f64], b: &[f64]) -> f64 {
    if a.is_empty() || a.len() != b.len() {
        return f64::NAN;
    }
    let n = a.len() as f64;
    let shift = (a.iter().sum::<f64>() - b.iter().sum::<f64>()) / n;
    let sum: f64 = a.iter().zip(b).map(|(x, y)| (x - y - shift).powi(2)).sum();
    (sum / n).sqrt()
}

/// One angle's difference between two walks.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AngleRms {
    /// The angle, as the CSV column without its unit.
    pub angle: &'static str,
    /// Eq. 7 between the two averaged cycles (rad); `None` when either walk lacks the angle or
    /// a complete cycle of its foot.
    pub rms: Option<f64>,
}

/// Eq. 7 for each angle of [`COMPARED`] between the cycles of `a` and `b` averaged over
/// 0…100 % (101 samples), the first `skip` cycles of each foot left out.
pub fn compare(a: &CriteriaFrames, b: &CriteriaFrames, skip: usize) -> Vec<AngleRms> {
    let columns = angle_columns();
    let curve = |m: &CriteriaFrames, name: &str| -> Option<Vec<f64>> {
        let col = columns.iter().find(|c| c.name == name)?;
        let strikes = if name.ends_with("_l") {
            &m.heel_strikes.left
        } else {
            &m.heel_strikes.right
        };
        let values: Vec<Vec<f64>> = m.frames.iter().map(|f| vec![(col.get)(f)]).collect();
        let rows = average_cycles(&m.times(), &values, strikes, skip).ok()?;
        let curve: Vec<f64> = rows.iter().map(|r| r[0]).collect();
        curve.iter().all(|v| v.is_finite()).then_some(curve)
    };
    COMPARED
        .iter()
        .map(|&angle| AngleRms {
            angle,
            rms: curve(a, angle)
                .zip(curve(b, angle))
                .map(|(x, y)| mean_shifted_rms(&x, &y)),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant offset is removed entirely; what is left of a change of shape is its own RMS:
    /// sin against sin + 0.3 + 0.1 sin(2·) leaves 0.1/√2 over whole periods.
    #[test]
    fn the_mean_shift_removes_a_constant_offset() {
        let n = 400;
        let t: Vec<f64> = (0..n)
            .map(|k| k as f64 / n as f64 * std::f64::consts::TAU)
            .collect();
        let a: Vec<f64> = t.iter().map(|t| t.sin()).collect();
        let shifted: Vec<f64> = a.iter().map(|x| x + 0.3).collect();
        assert!(mean_shifted_rms(&a, &shifted) < 1e-15);
        // without the shift the offset would be the whole error
        let plain = (a
            .iter()
            .zip(&shifted)
            .map(|(x, y)| (x - y).powi(2))
            .sum::<f64>()
            / n as f64)
            .sqrt();
        assert!((plain - 0.3).abs() < 1e-12);
        let reshaped: Vec<f64> = t
            .iter()
            .map(|t| t.sin() + 0.3 + 0.1 * (2.0 * t).sin())
            .collect();
        let e = mean_shifted_rms(&a, &reshaped);
        assert!((e - 0.1 / 2f64.sqrt()).abs() < 1e-12, "{e}");
        assert!(mean_shifted_rms(&a, &a[1..]).is_nan());
        assert!(mean_shifted_rms(&[], &[]).is_nan());
    }
}
