//! The type of an NRS⁻ from where its goal lies around the stance heel (Ko & Badler 1993 §4,
//! Figure 2, reconstructed in `docs/nrs.md`).
use crate::nrs::pose::{Planted, direction, right_of, turn_between};
use crate::nrs::specs::{Side, StepType};

/// The type of the step to `goal` (the flat foot's ankle) from the stance foot `stance` for the
/// `side` leg, with the goal's foot heading `goal_heading` (§4, Figure 2): φ, the angle of the
/// goal foot's heel (`heel_behind` behind its ankle, as the stance heel) around the stance heel
/// from the stance foot's direction — so that a foot set down beside the stance foot is at
/// 90°, lateral — + towards the stepping leg's side; lateral for
/// φ ∈ [90° − ν/2, 90° + ν/2], forward from there down to −(90° − (90° − ν/2)) and backward up to
/// the same angle beyond 180°, illegal in between (the stance side). Strictly within `boundary` of the
/// forward/lateral or lateral/backward boundary a foot heading within `parallel` of the stance
/// foot's makes the step lateral. Returns the type or φ (rad) for an illegal goal.
pub fn classify(
    stance: &Planted,
    side: Side,
    goal: [f64; 2],
    goal_heading: f64,
    (nu, boundary, parallel): (f64, f64, f64),
    heel_behind: f64,
) -> Result<StepType, f64> {
    let d = direction(stance.heading);
    let r = right_of(stance.heading);
    let heel = [
        stance.flat[0] - heel_behind * d[0],
        stance.flat[1] - heel_behind * d[1],
    ];
    let gd = direction(goal_heading);
    let g = [
        goal[0] - heel_behind * gd[0] - heel[0],
        goal[1] - heel_behind * gd[1] - heel[1],
    ];
    let lat = side.sign() * (g[0] * r[0] + g[1] * r[1]);
    let phi = lat.atan2(g[0] * d[0] + g[1] * d[1]);
    let right = std::f64::consts::FRAC_PI_2;
    let (lo, hi) = (right - nu / 2.0, right + nu / 2.0);
    let parallel_foot = turn_between(stance.heading, goal_heading).abs() <= parallel;
    // "within": strictly, to 1e-9 rad, so that a goal exactly `boundary` from it is outside
    let near = |edge: f64| (phi - edge).abs() < boundary - 1e-9;
    if near(lo) || near(hi) {
        return Ok(if parallel_foot {
            StepType::Lateral
        } else if phi < right {
            StepType::Forward
        } else {
            StepType::Backward
        });
    }
    if (lo..=hi).contains(&phi) {
        Ok(StepType::Lateral)
    } else if phi < lo && phi >= lo - right {
        Ok(StepType::Forward)
    } else if phi > hi || phi <= hi + right - 2.0 * std::f64::consts::PI {
        Ok(StepType::Backward)
    } else {
        Err(phi)
    }
}
