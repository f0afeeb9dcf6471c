//! The closed-loop inverse kinematics of Pronost et al. §5 over a trajectory of ankle targets.
//!
//! Each frame, from the previous posture θ_t and the frame's targets X*:
//! 1. the primary step Δθ_m = J⁺ (X* − f(θ_t)) (eq. 2, closed loop: the error, not the targets'
//!    increment, so no drift accumulates);
//! 2. the secondary step in the null space, c* = argmin z(θ_t + Δθ_m + V c) by the chosen
//!    minimiser (eq. 3–6, [`crate::ik::tasks`]);
//! 3. corrections θ ← θ + J⁺ (X* − f(θ)) until the ankles' error is below the tolerance (the
//!    null-space step is exact to first order only, and the damped primary step short of the
//!    target): a frame that cannot get there fails, naming the residual.
//!
//! The first frame starts from the rest posture, with rounds of steps 1–3 without the kinetic
//! term; a periodic trajectory (one gait cycle) is then solved once through as a warm-up, and the
//! kept pass starts from the warm-up's last posture.
use argmin::core::{Executor, State};
use argmin::solver::neldermead::NelderMead;
use serde::Serialize;

use crate::ik::chain::{Angles, Ankles, Chain, leg_offset};
use crate::ik::error::IkError;
use crate::ik::mds::MultiDirectional;
use crate::ik::model::IkModel;
use crate::ik::parameters::{IkParameters, Optimizer};
use crate::ik::tasks::{self, FrameProblem, NULL};
use crate::kinematics::pelvis::Side;
use crate::model::InputError;
use crate::model::body::Body;

/// One frame solved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameResult {
    /// The posture θ (rad).
    pub theta: Angles,
    /// The ankles' error after the corrections, largest coordinate (m).
    pub residual: f64,
    /// The minimiser's iterations.
    pub iterations: u64,
    /// Its cost evaluations.
    pub evaluations: u64,
    /// The primary-task corrections after the secondary step.
    pub corrections: usize,
    /// z at the minimiser's result.
    pub cost: f64,
}

/// A trajectory solved, one frame per target.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// The frames.
    pub frames: Vec<FrameResult>,
    /// The frame period (s).
    pub dt: f64,
}

/// What the minimiser returned.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Minimum {
    /// The null-space coordinates c*.
    pub point: Vec<f64>,
    /// z there.
    pub cost: f64,
    /// Iterations.
    pub iterations: u64,
    /// Cost evaluations.
    pub evaluations: u64,
}

/// The inverse kinematics of one body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ik {
    /// The chain.
    pub chain: Chain,
    /// The secondary tasks' data.
    pub model: IkModel,
    /// Tolerances.
    pub params: IkParameters,
}

impl Ik {
    /// The chain and `models/ik.toml` for `body`, default tolerances.
    pub fn new(body: &Body) -> Self {
        Ik {
            chain: Chain::new(body),
            model: IkModel::new(body),
            params: IkParameters::default(),
        }
    }

    /// Solve the trajectory `targets` (one per frame, period `dt` s); `periodic`: the targets
    /// are one cycle whose last frame is followed by its first (module doc).
    pub fn solve(&self, targets: &[Ankles], dt: f64, periodic: bool) -> Result<Solution, IkError> {
        self.solve_referenced(targets, dt, periodic, None)
    }

    /// [`Self::solve`] with a reference posture per frame in f3 (eq. 6) instead of the rest
    /// posture, where `reference` is given (one per target): e.g. a database walk's angles at
    /// the same phase of its cycle (`docs/ik.md`, Table 2's analysis). The first frame starts
    /// from the first reference.
    pub fn solve_referenced(
        &self,
        targets: &[Ankles],
        dt: f64,
        periodic: bool,
        reference: Option<&[Angles]>,
    ) -> Result<Solution, IkError> {
        InputError::check_range("IK frame period", dt, 1e-4, 1.0, "s")?;
        if let Some(r) = reference
            && (r.len() != targets.len() || !r.iter().all(|a| a.iter().all(|v| v.is_finite())))
        {
            let reason = format!(
                "{} finite reference postures for {} targets: one per target",
                r.len(),
                targets.len()
            );
            return Err(InputError::bad_value("reference", reason).into());
        }
        // the solver with frame i's reference as its rest posture
        let at = |i: usize| {
            let mut ik = *self;
            if let Some(r) = reference {
                ik.model.rest = r[i];
            }
            ik
        };
        if targets.is_empty() {
            return Err(InputError::bad_value("targets", "no frame to solve").into());
        }
        if let Some(i) = targets
            .iter()
            .position(|t| !t.iter().all(|v| v.is_finite()))
        {
            let reason = format!("frame {i}'s ankle target is not finite");
            return Err(InputError::bad_value("targets", reason).into());
        }
        let first = at(0).start(&targets[0])?;
        let mut theta = first.theta;
        if periodic && self.params.warm_up {
            for (i, t) in targets.iter().enumerate().skip(1) {
                theta = at(i).step(&theta, t, Some(dt), i, dt)?.theta;
            }
        }
        let mut frames = Vec::with_capacity(targets.len());
        for (i, t) in targets.iter().enumerate() {
            let f = if i == 0 && !(periodic && self.params.warm_up) {
                first
            } else {
                at(i).step(&theta, t, Some(dt), i, dt)?
            };
            theta = f.theta;
            frames.push(f);
        }
        Ok(Solution { frames, dt })
    }

    /// The first frame: from the rest posture, rounds of primary and secondary steps without
    /// the kinetic term, the targets moved from the rest posture's ankles to `target` over the
    /// first half of the rounds (a large first step could land the chain on a wrong branch).
    pub fn start(&self, target: &Ankles) -> Result<FrameResult, IkError> {
        let from = self.chain.ankles(&self.model.rest);
        let rounds = self.params.start_rounds.max(2);
        let ramp = (rounds / 2).max(1);
        let mut theta = self.model.rest;
        let mut last = None;
        for k in 1..=rounds {
            let w = (k as f64 / ramp as f64).min(1.0);
            let t = from + (target - from) * w;
            let f = self.step(&theta, &t, None, 0, 0.0)?;
            theta = f.theta;
            last = Some(f);
        }
        Ok(last.expect("at least one round"))
    }

    /// One frame from θ_t = `previous` towards `target` (module doc); `dt` None: no kinetic term
    /// (a posture, not a motion).
    pub fn step(
        &self,
        previous: &Angles,
        target: &Ankles,
        dt: Option<f64>,
        frame: usize,
        frame_period: f64,
    ) -> Result<FrameResult, IkError> {
        let problem = self.problem(previous, target, dt);
        let min = self.minimise(&problem).map_err(|e| IkError::Minimiser {
            frame,
            reason: e.to_string(),
        })?;
        let theta = problem.posture(&min.point);
        let (theta, residual, corrections) = self.correct(theta, target);
        if residual > self.params.tolerance {
            return Err(IkError::NotConverged {
                frame,
                time: frame as f64 * frame_period,
                residual,
                corrections,
                tolerance: self.params.tolerance,
            });
        }
        Ok(FrameResult {
            theta,
            residual,
            iterations: min.iterations,
            evaluations: min.evaluations,
            corrections,
            cost: min.cost,
        })
    }

    /// The secondary problem of one frame: the primary step from θ_t, the null space and M
    /// there.
    pub fn problem(&self, previous: &Angles, target: &Ankles, dt: Option<f64>) -> FrameProblem<'_> {
        let pose = self.chain.pose(previous);
        let j = pose.jacobian();
        let (e, _) = tasks::error(target, &pose.ankles());
        let inverse = tasks::pseudo_inverse(&j, self.params.damping)
            .expect("J Jᵀ + λ² I is positive definite for λ > 0");
        let (energy, dt, scale) = match dt {
            Some(dt) => (
                Some(tasks::energy_matrix(&pose, &self.model)),
                dt,
                self.params.reference_step / dt,
            ),
            None => (None, 1.0, 1.0),
        };
        FrameProblem {
            model: &self.model,
            previous: *previous,
            base: previous + self.primary_step(&inverse, &e),
            basis: tasks::null_basis(&j),
            energy,
            dt,
            scale,
        }
    }

    /// Minimise a frame's problem with the chosen minimiser, from c = 0 with the initial simplex
    /// 0, h e₁, …, h e₅.
    pub fn minimise(&self, problem: &FrameProblem<'_>) -> Result<Minimum, argmin::core::Error> {
        let p = &self.params;
        let start = vec![0.0; NULL];
        let problem = problem.clone();
        let result = match p.optimizer {
            Optimizer::MultiDirectional => {
                let solver = MultiDirectional::new(start, p.simplex, p.simplex_tolerance)?;
                let r = Executor::new(problem, solver)
                    .configure(|s| s.max_iters(p.max_iterations).counting(true))
                    .timer(false)
                    .run()?;
                summary(r.state())
            }
            Optimizer::NelderMead => {
                let mut simplex = vec![start.clone()];
                for i in 0..NULL {
                    let mut v = start.clone();
                    v[i] += p.simplex;
                    simplex.push(v);
                }
                let solver = NelderMead::new(simplex).with_sd_tolerance(p.simplex_tolerance)?;
                let r = Executor::new(problem, solver)
                    .configure(|s| s.max_iters(p.max_iterations).counting(true))
                    .timer(false)
                    .run()?;
                summary(r.state())
            }
        };
        Ok(result)
    }

    /// The primary-task corrections: θ ← θ + J⁺ (X* − f(θ)) until the error is within the
    /// tolerance or the corrections run out, each knee kept on its flexed branch
    /// ([`flexed_knees`]). Returns θ, the error and the corrections made.
    fn correct(&self, mut theta: Angles, target: &Ankles) -> (Angles, f64, usize) {
        for k in 0..=self.params.max_corrections {
            theta = flexed_knees(theta);
            let pose = self.chain.pose(&theta);
            let (e, r) = tasks::error(target, &pose.ankles());
            if r <= self.params.tolerance || k == self.params.max_corrections {
                return (theta, r, k);
            }
            let inverse = tasks::pseudo_inverse(&pose.jacobian(), self.params.damping)
                .expect("J Jᵀ + λ² I is positive definite for λ > 0");
            theta += self.primary_step(&inverse, &e);
        }
        unreachable!("the loop returns at its last round")
    }

    /// The primary step J⁺ ΔX (eq. 2), shortened to [`IkParameters::max_step`] along its
    /// direction.
    fn primary_step(&self, inverse: &tasks::Inverse, e: &Ankles) -> Angles {
        let step = inverse * e;
        let norm = step.norm();
        if norm > self.params.max_step {
            step * (self.params.max_step / norm)
        } else {
            step
        }
    }
}

/// θ with each hyperextended knee (flexion < 0, beyond AAOS's lower limit of 0°) turned to
/// its flexed twin |flexion| \[ours\]: a hinge's hip–ankle distance depends on the knee's
/// cosine only, so the twin reaches as far, and the corrections that follow put the ankle back
/// on the target with the knee flexed. Near the straight knee a damped step can cross 0, and
/// eq. 4's exponential cannot bring it back: no small null-space move leads from one branch to
/// the other (docs/ik.md).
pub fn flexed_knees(mut theta: Angles) -> Angles {
    for side in [Side::Right, Side::Left] {
        let knee = leg_offset(side) + 3;
        theta[knee] = theta[knee].abs();
    }
    theta
}

/// The minimum and the counts of a finished argmin run.
fn summary(state: &argmin::core::IterState<Vec<f64>, (), (), (), (), f64>) -> Minimum {
    Minimum {
        point: state
            .get_best_param()
            .cloned()
            .unwrap_or_else(|| vec![0.0; NULL]),
        cost: state.get_best_cost(),
        iterations: state.get_iter(),
        evaluations: state
            .get_func_counts()
            .get("cost_count")
            .copied()
            .unwrap_or(0),
    }
}
