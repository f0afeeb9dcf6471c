//! State-phase timings of a step from its frequency (KLAW 1989 eq. 2).
use serde::Serialize;

use crate::model::InputError;

/// State-phase timings of one step (s), KLAW 1989 eq. 2.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Timing {
    /// One step, heel strike to heel strike: t_step = 60 / sf.
    pub t_step: f64,
    /// The gait cycle, two steps: t_cycle = 2 t_step.
    pub t_cycle: f64,
    /// Double support: t_ds = (−0.16 sf + 29.08) · t_cycle / 100.
    pub t_ds: f64,
    /// Stance, heel strike to toe-off: t_stance = t_step + t_ds.
    pub t_stance: f64,
    /// Swing, toe-off to heel strike: t_swing = t_step − t_ds.
    pub t_swing: f64,
}

impl Timing {
    /// Eq. 2 for a step frequency in steps/min. Fails when double support vanishes
    /// (sf ≥ 181.75: running).
    pub(crate) fn new(step_frequency: f64) -> Result<Self, InputError> {
        let t_step = 60.0 / step_frequency;
        let t_cycle = 2.0 * t_step;
        let t_ds = (-0.16 * step_frequency + 29.08) * t_cycle / 100.0;
        if t_ds <= 0.0 {
            return Err(InputError::NoDoubleSupport {
                step_frequency,
                t_ds,
            });
        }
        Ok(Timing {
            t_step,
            t_cycle,
            t_ds,
            t_stance: t_step + t_ds,
            t_swing: t_step - t_ds,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Spec §3 worked example, recomputed by hand: sf = 108.01, t_step = 60/108.01 = 0.5555 s,
    /// t_ds = (−0.16·108.01 + 29.08)·1.1110/100 = 0.1311 s.
    #[test]
    fn timings_of_the_worked_example() {
        let t = Timing::new(108.01).unwrap();
        assert!((t.t_step - 0.5555).abs() < 1e-4);
        assert!((t.t_ds - 0.1311).abs() < 1e-4);
        assert!((t.t_stance - 0.6866).abs() < 1e-4);
        assert!((t.t_swing - 0.4244).abs() < 1e-4);
        assert!((t.t_cycle - 2.0 * t.t_step).abs() < 1e-15);
    }
}
