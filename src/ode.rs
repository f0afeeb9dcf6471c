//! Integration of one (sub)phase with `ode_solvers::Dopri5` (dense output), and accurate event
//! location: the integration stops after the accepted step in which an event function changes
//! sign, and the crossing is root-found on the dense output to ~1e-13 s (spec §4: events are
//! located, not rounded to the nearest solver step).
use nalgebra::SVector;
use ode_solvers::continuous_output_model::ContinuousOutputModel;
use ode_solvers::{Dopri5, System};
use std::cell::Cell;

/// Relative and absolute integrator tolerance: the shooting residuals must be smooth functions
/// of the unknowns at the level of the solver tolerance (spec §6: ≤ 1e-10).
pub const TOLERANCE: f64 = 1e-10;

/// How precisely event times are located (s).
pub const EVENT_TIME_TOLERANCE: f64 = 1e-13;

/// A right-hand side with up to `K` event functions. Event `k` fires when `events(t, y)[k]`
/// goes from positive to ≤ 0.
pub trait Phase<const N: usize, const K: usize> {
    /// dy/dt at (t, y). Must not allocate.
    fn rhs(&self, t: f64, y: &SVector<f64, N>) -> SVector<f64, N>;
    /// Event functions; return +1 for the ones that do not apply.
    fn events(&self, _t: f64, _y: &SVector<f64, N>) -> [f64; K] {
        [1.0; K]
    }
}

/// The dense solution of one integration, valid on [t0, t1].
#[derive(Clone, Debug)]
pub struct Segment<const N: usize> {
    pub t0: f64,
    pub t1: f64,
    pub y0: SVector<f64, N>,
    pub y1: SVector<f64, N>,
    dense: ContinuousOutputModel<f64, SVector<f64, N>>,
}

impl<const N: usize> Segment<N> {
    /// The state at `t`, clamped to [t0, t1].
    pub fn state(&self, t: f64) -> SVector<f64, N> {
        if t <= self.t0 {
            return self.y0;
        }
        if t >= self.t1 {
            return self.y1;
        }
        self.dense.evaluate(t).unwrap_or(self.y1)
    }
}

/// How an integration ended.
#[derive(Clone, Debug)]
pub struct Outcome<const N: usize> {
    pub segment: Segment<N>,
    /// The event that stopped it, if any, at `segment.t1`.
    pub event: Option<usize>,
    /// Right-hand side evaluations.
    pub evaluations: u32,
}

struct Adapter<'a, P, const N: usize, const K: usize> {
    phase: &'a P,
    last_t: f64,
    last_g: [f64; K],
    hit: &'a Cell<Option<(usize, f64, f64)>>,
}

impl<P: Phase<N, K>, const N: usize, const K: usize> System<f64, SVector<f64, N>>
    for Adapter<'_, P, N, K>
{
    fn system(&self, t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        *dy = self.phase.rhs(t, y);
    }

    fn solout(&mut self, t: f64, y: &SVector<f64, N>, _dy: &SVector<f64, N>) -> bool {
        let g = self.phase.events(t, y);
        for (k, (&before, &now)) in self.last_g.iter().zip(&g).enumerate() {
            if before > 0.0 && now <= 0.0 {
                self.hit.set(Some((k, self.last_t, t)));
                return true;
            }
        }
        self.last_t = t;
        self.last_g = g;
        false
    }
}

/// Integrate `phase` from (t0, y0) to t1, stopping at the first event.
pub fn integrate<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
) -> Result<Outcome<N>, String> {
    if !y0.iter().all(|v| v.is_finite()) {
        return Err(format!("non-finite state at t = {t0}"));
    }
    let g0 = phase.events(t0, &y0);
    let hit = Cell::new(None);
    let adapter = Adapter {
        phase,
        last_t: t0,
        last_g: g0,
        hit: &hit,
    };
    let mut dense = ContinuousOutputModel::new();
    let (y_last, stats) = {
        let mut stepper = Dopri5::new(adapter, t0, t1, t1 - t0, y0, TOLERANCE, TOLERANCE);
        let stats = stepper
            .integrate_with_continuous_output_model(&mut dense)
            .map_err(|e| e.to_string())?;
        (*stepper.y_out().last().unwrap_or(&y0), stats)
    };
    if !y_last.iter().all(|v| v.is_finite()) {
        return Err("the state became non-finite".into());
    }
    let mut segment = Segment {
        t0,
        t1,
        y0,
        y1: y_last,
        dense,
    };
    let event = match hit.get() {
        None => None,
        Some((k, mut a, mut b)) => {
            let g = |t: f64| phase.events(t, &segment.state(t))[k];
            let (mut ga, mut gb) = (g(a), g(b));
            // Illinois-safeguarded regula falsi on the dense output
            let mut side = 0;
            for _ in 0..100 {
                if b - a <= EVENT_TIME_TOLERANCE {
                    break;
                }
                let mut t = (a * gb - b * ga) / (gb - ga);
                if !(t > a && t < b) {
                    t = 0.5 * (a + b);
                }
                let gt = g(t);
                if gt > 0.0 {
                    a = t;
                    ga = gt;
                    if side == -1 {
                        gb *= 0.5;
                    }
                    side = -1;
                } else {
                    b = t;
                    gb = gt;
                    if side == 1 {
                        ga *= 0.5;
                    }
                    side = 1;
                }
            }
            segment.y1 = segment.state(b);
            segment.t1 = b;
            Some(k)
        }
    };
    Ok(Outcome {
        segment,
        event,
        evaluations: stats.num_eval,
    })
}

impl<P: Phase<N, K>, const N: usize, const K: usize> Phase<N, K> for &P {
    fn rhs(&self, t: f64, y: &SVector<f64, N>) -> SVector<f64, N> {
        (*self).rhs(t, y)
    }
    fn events(&self, t: f64, y: &SVector<f64, N>) -> [f64; K] {
        (*self).events(t, y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Harmonic oscillator x'' = −x from (1, 0): x = cos t, the first zero at π/2.
    struct Oscillator;
    impl Phase<2, 1> for Oscillator {
        fn rhs(&self, _t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
            SVector::<f64, 2>::new(y[1], -y[0])
        }
        fn events(&self, _t: f64, y: &SVector<f64, 2>) -> [f64; 1] {
            [y[0]]
        }
    }

    #[test]
    fn event_is_located_on_the_dense_output() {
        let out = integrate(&Oscillator, 0.0, SVector::<f64, 2>::new(1.0, 0.0), 3.0).unwrap();
        assert_eq!(out.event, Some(0));
        assert!(
            (out.segment.t1 - std::f64::consts::FRAC_PI_2).abs() < 1e-9,
            "{}",
            out.segment.t1
        );
        assert!(out.segment.y1[0].abs() < 1e-9);
        assert!((out.segment.y1[1] + 1.0).abs() < 1e-9);
    }

    #[test]
    fn dense_output_matches_the_analytic_solution() {
        struct Free;
        impl Phase<2, 0> for Free {
            fn rhs(&self, _t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
                SVector::<f64, 2>::new(y[1], -y[0])
            }
        }
        let out = integrate(&Free, 0.0, SVector::<f64, 2>::new(1.0, 0.0), 3.0).unwrap();
        assert_eq!(out.event, None);
        for i in 0..=30 {
            let t = 0.1 * i as f64;
            let y = out.segment.state(t);
            assert!((y[0] - t.cos()).abs() < 1e-8, "t {t}: {}", y[0]);
        }
        assert!((out.segment.y1[0] - 3.0_f64.cos()).abs() < 1e-9);
    }
}
