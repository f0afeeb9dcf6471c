//! C1, the total jerk of a gait cycle (Pronost et al. 2006, eq. 8). The printed equation,
//! C1 = 1/11 Σᵢ d³/dt³ θ²(i), is garbled (a third derivative of squared angles, no sum over
//! time, and Table 1 gives rad·s⁻³ for values near 7·10⁷); Table 1's values fit the sum over the
//! frames of the squared third derivatives of the eleven angles at the capture's 60 frames/s,
//! averaged over the angles (issue 18):
//!
//! C1 = (1/11) Σᵢ Σₖ θ⃛ᵢ(tₖ)²  (rad² s⁻⁶),
//!
//! with θ⃛ by finite differences on the frames (`numerics::sampled::third_derivative`: central,
//! second order). C1 grows with the frame count; (1/T) ∫ θ⃛² dt, by the trapezoidal rule on the
//! same frames and averaged over the angles, does not: the mean squared jerk.
use std::ops::Range;

use super::segments::{DOFS, POSE};
use crate::numerics::sampled::third_derivative;

/// (C1, mean squared jerk) of the frames `inside` of `poses` (spaced `h` apart; the frames
/// around them, where given, serve the central differences at the cycle's ends).
pub fn total_jerk(poses: &[[f64; POSE]], h: f64, inside: Range<usize>) -> (f64, f64) {
    let (mut total, mut mean) = (0.0, 0.0);
    for &i in &DOFS {
        let angle: Vec<f64> = poses.iter().map(|p| p[i]).collect();
        let squares: Vec<f64> = third_derivative(&angle, h)[inside.clone()]
            .iter()
            .map(|j| j * j)
            .collect();
        let sum: f64 = squares.iter().sum();
        total += sum;
        let ends = squares.first().unwrap_or(&0.0) + squares.last().unwrap_or(&0.0);
        let duration = h * squares.len().saturating_sub(1) as f64;
        mean += h * (sum - 0.5 * ends) / duration;
    }
    let n = DOFS.len() as f64;
    (total / n, mean / n)
}
