//! Integration of one (sub)phase by an explicit Runge–Kutta pair with dense output ([`Method`]):
//! Hairer's DOP853, the Dormand–Prince 8(5,3) pair with its 7th-order dense output (Hairer,
//! Nørsett & Wanner, *Solving ODEs I*, II.10), for every phase of the walk (`METHOD`), or the
//! Dormand–Prince 5(4) pair with its 4th-order dense output (II.5–II.6: DOPRI5, the same method
//! and step control as `ode_solvers::Dopri5`). Written for fixed-size states: the stages live on
//! the stack, the right-hand side is called through a generic (inlined), and the only allocation
//! is the dense record, one entry per accepted step. Events are located on the dense output, not
//! rounded to the nearest solver step (spec §4).
//!
//! `tableau.rs` holds the two pairs' coefficients (and why klaw has its own DOP853),
//! `stepping.rs` one attempted step of each, the step-size control and the integration loop,
//! `dense.rs` the dense output, `events.rs` the event location.
use nalgebra::SVector;

mod dense;
mod events;
mod stepping;
mod tableau;

use dense::{DenseStep, Stages};

/// Relative and absolute integrator tolerance. Spec §6 asks for residuals that are smooth in the
/// unknowns at the level of the shooting tolerance, by rtol = atol ≤ 1e-10 *or* a fixed step
/// sequence per (sub)phase: the shooting trials follow a frozen mesh ([`integrate_on`]), so the
/// tolerance is set by accuracy alone, the largest at which the converged magnitudes,
/// integrated again at 1e-12, still meet the step's end conditions well inside the 1e-6 promise
/// (docs/engine.md, "Numerics", has the measurements; swing2 runs at 100 times this,
/// `swing::SWING2_TOLERANCE_SCALE`).
pub const TOLERANCE: f64 = 5e-8;

/// The accuracy and the limits of one integration: the error allowed per step, how precisely
/// events are located, how many steps it may take, how far a frozen mesh may be followed. An
/// `f64` converts to the step tolerance with the other three at their defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Relative and absolute error allowed per step (1), [`TOLERANCE`] by default.
    pub step: f64,
    /// How precisely event times are located (s), 1e-13 by default.
    pub event_time: f64,
    /// Steps one integration may take before it fails (count), 100 000 by default.
    pub max_steps: usize,
    /// A frozen mesh ([`integrate_on`]) is followed while every step's error estimate stays
    /// within this multiple of the step tolerance, 2 by default; beyond it the step-size control
    /// takes over from that step on.
    pub frozen_mesh: f64,
}

impl Tolerance {
    /// `step` as the error allowed per step, the limits at their defaults.
    pub const fn new(step: f64) -> Self {
        Tolerance {
            step,
            event_time: 1e-13,
            max_steps: 100_000,
            frozen_mesh: 2.0,
        }
    }

    /// This tolerance with its step tolerance multiplied by `factor`.
    pub fn scaled(self, factor: f64) -> Self {
        Tolerance {
            step: self.step * factor,
            ..self
        }
    }
}

impl Default for Tolerance {
    fn default() -> Self {
        Tolerance::new(TOLERANCE)
    }
}

impl From<f64> for Tolerance {
    fn from(step: f64) -> Self {
        Tolerance::new(step)
    }
}

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

impl<P: Phase<N, K>, const N: usize, const K: usize> Phase<N, K> for &P {
    fn rhs(&self, t: f64, y: &SVector<f64, N>) -> SVector<f64, N> {
        (*self).rhs(t, y)
    }
    fn events(&self, t: f64, y: &SVector<f64, N>) -> [f64; K] {
        (*self).events(t, y)
    }
}

/// The dense solution of one integration, valid on [t0, t1] (its dense output: `dense.rs`).
#[derive(Clone, Debug)]
pub struct Segment<const N: usize> {
    /// Start time (s).
    pub t0: f64,
    /// End time (s): the end asked for, or the event's time.
    pub t1: f64,
    /// State at t0.
    pub y0: SVector<f64, N>,
    /// State at t1.
    pub y1: SVector<f64, N>,
    steps: Vec<DenseStep<N>>,
    /// Stages of the steps without their dense output, one per step (empty when every step
    /// has it).
    pending: Vec<Stages<N>>,
}

/// Why an integration stopped before its end time (Hairer's DOP853 driver gives up the same
/// ways: a non-finite start, too many steps, a step size below the time's resolution).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum IntegrationError {
    /// The initial state has a NaN or an infinity.
    #[error("non-finite state at t = {t}")]
    NonFiniteStart {
        /// The start time (in s).
        t: f64,
    },
    /// The integration took `limit` steps without reaching its end time.
    #[error("more than {limit} steps at t = {t}")]
    TooManySteps {
        /// The most steps allowed.
        limit: usize,
        /// The time reached (in s).
        t: f64,
    },
    /// The step size fell below the resolution of the time t.
    #[error("step size underflow at t = {t}")]
    StepSizeUnderflow {
        /// The time reached (in s).
        t: f64,
    },
    /// An attempted step's error estimate is not finite: the state blew up.
    #[error("the state became non-finite at t = {t}")]
    NonFinite {
        /// The start of the step that blew up (in s).
        t: f64,
    },
}

/// How an integration ended.
#[derive(Clone, Debug)]
pub struct Outcome<const N: usize> {
    /// The dense solution from t0 to where the integration stopped.
    pub segment: Segment<N>,
    /// The event that stopped it, if any, at `segment.t1`.
    pub event: Option<usize>,
    /// Right-hand side evaluations.
    pub evaluations: u32,
    /// Some step was chosen by the step-size control (always, without a mesh to follow).
    pub adapted: bool,
}

impl<const N: usize> Outcome<N> {
    /// This integration followed by `next`, which starts where this one ends: one segment,
    /// the evaluations added, `next`'s event.
    pub(crate) fn then(mut self, next: Outcome<N>) -> Outcome<N> {
        debug_assert!(self.segment.t1 == next.segment.t0);
        let (a, b) = (&mut self.segment, &next.segment);
        if !a.pending.is_empty() || !b.pending.is_empty() {
            let zero = [SVector::<f64, N>::zeros(); 9];
            a.pending.resize(a.steps.len(), zero);
            if b.pending.is_empty() {
                a.pending.resize(a.steps.len() + b.steps.len(), zero);
            } else {
                a.pending.extend_from_slice(&b.pending);
            }
        }
        self.segment.steps.extend_from_slice(&next.segment.steps);
        self.segment.t1 = next.segment.t1;
        self.segment.y1 = next.segment.y1;
        Outcome {
            segment: self.segment,
            event: next.event,
            evaluations: self.evaluations + next.evaluations,
            adapted: self.adapted || next.adapted,
        }
    }
}

/// Integrate `phase` from (t0, y0) to t1 with relative and absolute tolerance `tol` (and its
/// limits, [`Tolerance`]), stopping at the first event.
pub fn integrate_with<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tol: impl Into<Tolerance>,
) -> Result<Outcome<N>, IntegrationError> {
    integrate_on(phase, t0, y0, t1, tol, Mesh::Adaptive)
}

/// Which step sequence [`integrate_on`] follows.
#[derive(Clone, Copy, Debug)]
pub enum Mesh<'a, const N: usize> {
    /// None: the step-size control chooses every step.
    Adaptive,
    /// The steps of this segment from t0 on: from the step that starts at t0, or from the
    /// rest of the step that contains it (the previous step's mesh of a phase whose break times
    /// moved a little); adaptive where the segment does not reach t0.
    Aligned(&'a Segment<N>),
    /// The step sizes of this segment in order, from t0 whatever its own start (a subphase
    /// that starts at an event, whose time moves from trial to trial).
    Shifted(&'a Segment<N>),
}

/// [`integrate_with`] on the step sequence of `mesh` (a previous integration from the same t0,
/// typically the previous shooting trial), so that the end state is a smooth function of the
/// phase's parameters: an adaptive integrator's end state jumps by about its global error
/// whenever a trial changes the step sequence, and in ill-conditioned phases (swing1 at the
/// grid's corners) those jumps reach 1e3 times the tolerance and stall the shooting. The mesh
/// is followed while each step's error estimate stays within [`Tolerance::frozen_mesh`] times
/// the tolerance (and, past its end, the control takes over); `Outcome::adapted` tells whether any
/// step was chosen by the control, i.e. whether this integration's mesh should replace it.
pub fn integrate_on<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tol: impl Into<Tolerance>,
    mesh: Mesh<'_, N>,
) -> Result<Outcome<N>, IntegrationError> {
    integrate_by(METHOD, phase, t0, y0, t1, tol, mesh)
}

/// [`integrate_on`] for a shooting trial: DOP853's dense output is left out (the three extra
/// evaluations of each step) except on an event's step, where the event is located; the trial
/// the shooting keeps gets it by [`Segment::densify`], the others never need it.
pub(crate) fn integrate_trial<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tol: impl Into<Tolerance>,
    mesh: Mesh<'_, N>,
) -> Result<Outcome<N>, IntegrationError> {
    stepping::run(METHOD, true, phase, t0, y0, t1, tol.into(), mesh)
}

/// The Runge–Kutta pair of an integration.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Dormand–Prince 5(4): 6 evaluations a step, a 4th-order dense output from its stages.
    Dopri5,
    /// Dormand–Prince 8(5,3), Hairer's DOP853: 12 evaluations a step, a 7th-order dense output
    /// for 3 more.
    Dop853,
}

/// The method of [`integrate_on`]: DOP853, whose longer steps take fewer evaluations than
/// Dopri5's in every phase of the walk (measured in docs/journal/engine.md).
pub(crate) const METHOD: Method = Method::Dop853;

/// [`integrate_on`] by `method`.
pub fn integrate_by<P: Phase<N, K>, const N: usize, const K: usize>(
    method: Method,
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tol: impl Into<Tolerance>,
    mesh: Mesh<'_, N>,
) -> Result<Outcome<N>, IntegrationError> {
    stepping::run(method, false, phase, t0, y0, t1, tol.into(), mesh)
}

/// Test problems with analytic solutions, shared by the integrator's tests.
#[cfg(test)]
mod problems {
    use super::Phase;
    use nalgebra::SVector;

    /// Harmonic oscillator x'' = −x from (1, 0): x = cos t, the first zero at π/2.
    pub(crate) struct Oscillator;
    impl Phase<2, 1> for Oscillator {
        fn rhs(&self, _t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
            SVector::<f64, 2>::new(y[1], -y[0])
        }
        fn events(&self, _t: f64, y: &SVector<f64, 2>) -> [f64; 1] {
            [y[0]]
        }
    }

    /// A damped oscillator x'' = −ω² x − 0.1 x' with parameter ω.
    pub(crate) struct Damped(pub f64);
    impl Phase<2, 0> for Damped {
        fn rhs(&self, _t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
            SVector::<f64, 2>::new(y[1], -self.0 * self.0 * y[0] - 0.1 * y[1])
        }
    }

    /// y1' = y1 cos t, y2' = −2t y2 from (1, 1): y1 = exp(sin t), y2 = exp(−t²), a
    /// non-autonomous system (every stage's time matters).
    pub(crate) struct Exponentials;
    impl Phase<2, 0> for Exponentials {
        fn rhs(&self, t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
            SVector::<f64, 2>::new(y[0] * t.cos(), -2.0 * t * y[1])
        }
    }

    /// [`Exponentials`]' solution.
    pub(crate) fn exact(t: f64) -> SVector<f64, 2> {
        SVector::<f64, 2>::new(t.sin().exp(), (-t * t).exp())
    }
}
