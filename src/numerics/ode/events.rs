//! Event location (spec §4: events are located, not rounded to the nearest solver step): the
//! integration stops after the accepted step in which an event function goes from positive to
//! ≤ 0, and the crossing is root-found on that step's dense output (Hairer, Nørsett & Wanner,
//! *Solving ODEs I*, II.6) by the Illinois method ([`roots::illinois`]) to
//! [`super::Tolerance::event_time`].
use super::{Phase, Segment};
use crate::numerics::roots;

/// The first event that fires over an accepted step: positive at its start (`before`), ≤ 0 at
/// its end (`after`).
#[inline]
pub(super) fn fired<const K: usize>(before: &[f64; K], after: &[f64; K]) -> Option<usize> {
    (0..K).find(|&k| before[k] > 0.0 && after[k] <= 0.0)
}

/// Move the end of `segment`, whose last step fired event `k` of `phase`, to the event: the
/// crossing on that step's dense output, which a shooting trial's step gets here first
/// (pending stages). Returns the right-hand-side evaluations spent on it.
pub(super) fn locate<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    segment: &mut Segment<N>,
    k: usize,
    event_time: f64,
) -> u32 {
    let mut evaluations = 0;
    let last = segment.steps.len() - 1;
    let step = &mut segment.steps[last];
    if !step.ready {
        step.complete(phase, &segment.pending[last]);
        evaluations += 3;
    }
    let step = *step;
    let g = |t: f64| phase.events(t, &step.eval(t))[k];
    let (a, b) = (step.t, segment.t1);
    let (_, b) = roots::illinois(g, (a, g(a)), (b, g(b)), event_time, 100);
    segment.y1 = step.eval(b);
    segment.t1 = b;
    evaluations
}

#[cfg(test)]
mod tests {
    use super::super::problems::Oscillator;
    use super::super::{Mesh, Method, integrate_by, integrate_with};
    use nalgebra::SVector;

    #[test]
    fn event_is_located_on_the_dense_output() {
        let out = integrate_with(
            &Oscillator,
            0.0,
            SVector::<f64, 2>::new(1.0, 0.0),
            3.0,
            1e-10,
        )
        .unwrap();
        assert_eq!(out.event, Some(0));
        assert!(
            (out.segment.t1 - std::f64::consts::FRAC_PI_2).abs() < 1e-9,
            "{}",
            out.segment.t1
        );
        assert!(out.segment.y1[0].abs() < 1e-9);
        assert!((out.segment.y1[1] + 1.0).abs() < 1e-9);
    }

    /// The oscillator's first zero at π/2, by both methods.
    #[test]
    fn both_methods_locate_the_event() {
        for method in [Method::Dop853, Method::Dopri5] {
            let y0 = SVector::<f64, 2>::new(1.0, 0.0);
            let out =
                integrate_by(method, &Oscillator, 0.0, y0, 3.0, 1e-10, Mesh::Adaptive).unwrap();
            assert_eq!(out.event, Some(0));
            let err = (out.segment.t1 - std::f64::consts::FRAC_PI_2).abs();
            assert!(err < 1e-10, "{method:?}: {err:e}");
        }
    }
}
