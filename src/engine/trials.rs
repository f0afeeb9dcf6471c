//! The trials of one shooting solve (KLAW 1989 §4.1, spec §6: each trial integrates the phase with trial
//! magnitudes and measures its end-condition residual): the step sequence they follow, the best
//! of them, and the right-hand-side evaluations they spend.
use std::cell::{Cell, RefCell};

use nalgebra::Vector2;

use crate::control::stance::StanceRun;
use crate::control::swing::SwingTrial;
use crate::numerics::ode::{IntegrationError, Segment};

/// A trial integration of a shooting solve.
pub(super) trait Trial: Sized {
    /// What the next trials follow: a trial's step sequence
    /// ([`crate::numerics::ode::integrate_on`]).
    type Mesh;
    fn residual(&self) -> Vector2<f64>;
    /// The trial's own step sequence, when it chose (some of) its steps rather than following
    /// the mesh it was given.
    fn own_mesh(&self) -> Option<Self::Mesh>;
    fn evaluations(&self) -> u32;
}

impl Trial for StanceRun {
    type Mesh = StanceRun;
    fn residual(&self) -> Vector2<f64> {
        self.residual
    }
    fn own_mesh(&self) -> Option<StanceRun> {
        self.adapted.then(|| self.clone())
    }
    fn evaluations(&self) -> u32 {
        self.evaluations
    }
}

impl Trial for SwingTrial {
    type Mesh = Segment<4>;
    fn residual(&self) -> Vector2<f64> {
        self.residual
    }
    fn own_mesh(&self) -> Option<Segment<4>> {
        self.adapted.then(|| self.segment.clone())
    }
    fn evaluations(&self) -> u32 {
        self.evaluations
    }
}

/// The trials of one solve, its fallback's included: every trial follows the step sequence of
/// the last one that chose its own steps (at first, the last step's kept trial's), so that the
/// residual stays smooth in the unknowns; the trial with the smallest residual is kept (it is
/// the one the solver returns). In cells because `control::shooting::solve1` and `solve2` take
/// `Fn` residuals.
pub(super) struct Trials<T: Trial> {
    mesh: RefCell<Option<T::Mesh>>,
    best: RefCell<Option<T>>,
    evaluations: Cell<u64>,
}

impl<T: Trial> Trials<T> {
    pub fn new(mesh: Option<T::Mesh>) -> Self {
        Trials {
            mesh: RefCell::new(mesh),
            best: RefCell::new(None),
            evaluations: Cell::new(0),
        }
    }

    /// Run one trial, `simulate` on the current mesh, and return its residual.
    pub fn run(
        &self,
        simulate: impl FnOnce(Option<&T::Mesh>) -> Result<T, IntegrationError>,
    ) -> Result<Vector2<f64>, IntegrationError> {
        let trial = simulate(self.mesh.borrow().as_ref())?;
        if let Some(mesh) = trial.own_mesh() {
            *self.mesh.borrow_mut() = Some(mesh);
        }
        self.evaluations
            .set(self.evaluations.get() + u64::from(trial.evaluations()));
        let r = trial.residual();
        let mut best = self.best.borrow_mut();
        if best.as_ref().is_none_or(|b| r.amax() < b.residual().amax()) {
            *best = Some(trial);
        }
        Ok(r)
    }

    /// The best trial (none if no trial ran) and the evaluations of all.
    pub fn finish(self) -> (Option<T>, u64) {
        (self.best.into_inner(), self.evaluations.get())
    }
}
