//! Torczon's multi-directional search (V. Torczon, *Multi-directional Search: A Direct Search
//! Algorithm for Parallel Machines*, PhD thesis, Rice University, 1989; J. E. Dennis & V.
//! Torczon, "Direct search methods on parallel machines", SIAM J. Optim. 1(4), 1991), the
//! minimiser Pronost et al. use for their secondary tasks (§5), as an [`argmin`] solver.
//!
//! A simplex of n + 1 vertices with the best v₀ first. Each iteration reflects every other
//! vertex through v₀, rᵢ = 2v₀ − vᵢ; if the best reflection beats v₀, the expansion
//! eᵢ = v₀ − μ (vᵢ − v₀) (μ = 2) is tried and the better of the two simplices kept; otherwise the
//! simplex contracts towards v₀, cᵢ = v₀ + θ (vᵢ − v₀) (θ = ½). The new best vertex comes first.
//! Every step keeps the simplex's shape (its edges are scaled, not distorted, unlike
//! Nelder–Mead's), which is what gives the method its convergence theory on smooth functions.
//! It stops when every vertex lies within `tolerance` of the best one.
use argmin::core::{
    CostFunction, Error as ArgminError, IterState, KV, Problem, Solver, TerminationReason,
    TerminationStatus,
};

/// The state argmin keeps for it: parameters `Vec<f64>`, cost `f64`.
pub type MdsState = IterState<Vec<f64>, (), (), (), (), f64>;

/// Torczon's multi-directional search (module doc).
#[derive(Clone, Debug)]
pub struct MultiDirectional {
    /// The simplex, best vertex first, with the vertices' costs.
    simplex: Vec<(Vec<f64>, f64)>,
    /// The expansion factor μ > 1.
    expansion: f64,
    /// The contraction factor θ in (0, 1).
    contraction: f64,
    /// Converged when every vertex lies within this distance (Euclidean) of the best.
    tolerance: f64,
}

impl MultiDirectional {
    /// The search from `start` with the initial simplex `start + h eᵢ` (i = 1…n), stopping at a
    /// simplex of size `tolerance`. Err: an empty start, or h or the tolerance not positive.
    pub fn new(start: Vec<f64>, h: f64, tolerance: f64) -> Result<Self, ArgminError> {
        if start.is_empty() || !(h > 0.0 && h.is_finite()) || tolerance.is_nan() || tolerance <= 0.0
        {
            return Err(ArgminError::msg(
                "multi-directional search: the start must have a coordinate, h and the tolerance \
                 must be positive",
            ));
        }
        let mut simplex = vec![(start.clone(), f64::NAN)];
        for i in 0..start.len() {
            let mut v = start.clone();
            v[i] += h;
            simplex.push((v, f64::NAN));
        }
        Ok(MultiDirectional {
            simplex,
            expansion: 2.0,
            contraction: 0.5,
            tolerance,
        })
    }

    /// The largest distance from the best vertex to another.
    pub fn size(&self) -> f64 {
        let best = &self.simplex[0].0;
        self.simplex[1..]
            .iter()
            .map(|(v, _)| distance(v, best))
            .fold(0.0, f64::max)
    }

    /// The vertices `v₀ + factor (vᵢ − v₀)`, i = 1…n, and their costs.
    fn transformed<O>(
        &self,
        problem: &mut Problem<O>,
        factor: f64,
    ) -> Result<Vec<(Vec<f64>, f64)>, ArgminError>
    where
        O: CostFunction<Param = Vec<f64>, Output = f64>,
    {
        let best = &self.simplex[0].0;
        self.simplex[1..]
            .iter()
            .map(|(v, _)| {
                let p: Vec<f64> = best
                    .iter()
                    .zip(v)
                    .map(|(b, x)| b + factor * (x - b))
                    .collect();
                let c = finite(problem.cost(&p)?);
                Ok((p, c))
            })
            .collect()
    }

    /// Put the best vertex first (the rest keep their order: the simplex's shape is kept).
    fn best_first(&mut self) {
        let (i, _) = self
            .simplex
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.1.total_cmp(&b.1.1))
            .expect("a simplex has vertices");
        self.simplex.swap(0, i);
    }
}

/// A cost that is not a number counts as +∞ (the step is never taken).
fn finite(c: f64) -> f64 {
    if c.is_nan() { f64::INFINITY } else { c }
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

fn least(vertices: &[(Vec<f64>, f64)]) -> f64 {
    vertices.iter().map(|v| v.1).fold(f64::INFINITY, f64::min)
}

impl<O> Solver<O, MdsState> for MultiDirectional
where
    O: CostFunction<Param = Vec<f64>, Output = f64>,
{
    fn name(&self) -> &str {
        "Multi-directional search (Torczon)"
    }

    fn init(
        &mut self,
        problem: &mut Problem<O>,
        state: MdsState,
    ) -> Result<(MdsState, Option<KV>), ArgminError> {
        for (p, c) in self.simplex.iter_mut() {
            *c = finite(problem.cost(p)?);
        }
        self.best_first();
        let (p, c) = self.simplex[0].clone();
        Ok((state.param(p).cost(c), None))
    }

    fn next_iter(
        &mut self,
        problem: &mut Problem<O>,
        state: MdsState,
    ) -> Result<(MdsState, Option<KV>), ArgminError> {
        let best = self.simplex[0].1;
        let reflected = self.transformed(problem, -1.0)?;
        let next = if least(&reflected) < best {
            let expanded = self.transformed(problem, -self.expansion)?;
            if least(&expanded) < least(&reflected) {
                expanded
            } else {
                reflected
            }
        } else {
            self.transformed(problem, self.contraction)?
        };
        self.simplex.truncate(1);
        self.simplex.extend(next);
        self.best_first();
        let (p, c) = self.simplex[0].clone();
        Ok((state.param(p).cost(c), None))
    }

    fn terminate(&mut self, _state: &MdsState) -> TerminationStatus {
        if self.size() <= self.tolerance {
            TerminationStatus::Terminated(TerminationReason::SolverConverged)
        } else {
            TerminationStatus::NotTerminated
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use argmin::core::{Executor, State};

    struct F(fn(&[f64]) -> f64);

    impl CostFunction for F {
        type Param = Vec<f64>;
        type Output = f64;
        fn cost(&self, p: &Vec<f64>) -> Result<f64, ArgminError> {
            Ok((self.0)(p))
        }
    }

    /// Minimise `f` from `start` and return the point, its cost and the termination.
    fn minimise(f: fn(&[f64]) -> f64, start: Vec<f64>, tol: f64) -> (Vec<f64>, f64, String) {
        let solver = MultiDirectional::new(start, 0.5, tol).unwrap();
        let res = Executor::new(F(f), solver)
            .configure(|s| s.max_iters(200_000))
            .run()
            .unwrap();
        let s = res.state();
        (
            s.get_best_param().unwrap().clone(),
            s.get_best_cost(),
            s.get_termination_reason().unwrap().text().to_string(),
        )
    }

    fn rosenbrock(p: &[f64]) -> f64 {
        (1.0 - p[0]).powi(2) + 100.0 * (p[1] - p[0] * p[0]).powi(2)
    }

    /// Known minima: a shifted, scaled quadratic in 5 unknowns (at (1, −2, 3, 0.5, −1)), Booth's
    /// function (at (1, 3)), Beale's (at (3, ½)) and Rosenbrock's valley (at (1, 1)); each is
    /// found, with a cost below 1e-11, and the search stops by convergence, not by the cap. The
    /// distance bound is √(cost / λ_min) of each minimum's Hessian (Rosenbrock's smallest
    /// eigenvalue is 0.4: its flat valley leaves the point 1e-5 off for a 1e-11 cost).
    #[test]
    fn it_finds_known_minima() {
        let quad = |p: &[f64]| {
            let m = [1.0, -2.0, 3.0, 0.5, -1.0];
            p.iter()
                .zip(m)
                .enumerate()
                .map(|(i, (x, c))| (i as f64 + 1.0) * (x - c) * (x - c))
                .sum()
        };
        let booth =
            |p: &[f64]| (p[0] + 2.0 * p[1] - 7.0).powi(2) + (2.0 * p[0] + p[1] - 5.0).powi(2);
        let beale = |p: &[f64]| {
            let (x, y) = (p[0], p[1]);
            (1.5 - x + x * y).powi(2)
                + (2.25 - x + x * y * y).powi(2)
                + (2.625 - x + x * y * y * y).powi(2)
        };
        for (f, start, at, within) in [
            (
                quad as fn(&[f64]) -> f64,
                vec![0.0; 5],
                vec![1.0, -2.0, 3.0, 0.5, -1.0],
                1e-6,
            ),
            (booth, vec![-3.0, 0.0], vec![1.0, 3.0], 1e-6),
            (beale, vec![1.0, 1.0], vec![3.0, 0.5], 1e-5),
            (rosenbrock, vec![-1.2, 1.0], vec![1.0, 1.0], 1e-5),
        ] {
            let (p, c, why) = minimise(f, start, 1e-9);
            assert!(why.contains("converged"), "{why}");
            assert!(distance(&p, &at) < within, "{p:?} vs {at:?}");
            assert!(c < 1e-11, "{c}");
        }
    }

    /// Each iteration keeps the simplex's shape: its pairwise distances are the previous ones
    /// scaled by one factor, 1, 2 or ½ (a reflection through the best vertex, an expansion or a
    /// contraction), never distorted.
    #[test]
    fn the_simplex_keeps_its_shape() {
        let mut s = MultiDirectional::new(vec![0.3, -0.2, 0.1], 0.4, 1e-12).unwrap();
        let mut problem = Problem::new(F(rosenbrock3));
        let (mut state, _) = s.init(&mut problem, MdsState::new()).unwrap();
        let pairwise = |simplex: &[(Vec<f64>, f64)]| -> Vec<f64> {
            let mut d = Vec::new();
            for (i, a) in simplex.iter().enumerate() {
                for b in &simplex[i + 1..] {
                    d.push(distance(&a.0, &b.0));
                }
            }
            d.sort_by(f64::total_cmp);
            d
        };
        let mut factors = Vec::new();
        for _ in 0..40 {
            let before = pairwise(&s.simplex);
            state = s.next_iter(&mut problem, state).unwrap().0;
            let after = pairwise(&s.simplex);
            let k = after[0] / before[0];
            assert!([0.5, 1.0, 2.0].iter().any(|f| (k - f).abs() < 1e-9), "{k}");
            for (a, b) in before.iter().zip(&after) {
                assert!(
                    (a * k - b).abs() < 1e-9 * a.max(1e-300),
                    "{before:?} {after:?}"
                );
            }
            factors.push(k);
        }
        // the walk went both ways: some contraction and some reflection or expansion
        assert!(factors.iter().any(|&k| k < 0.9) && factors.iter().any(|&k| k > 0.9));
    }

    fn rosenbrock3(p: &[f64]) -> f64 {
        rosenbrock(&p[..2]) + (p[2] - 1.0).powi(2)
    }

    #[test]
    fn bad_settings_are_refused() {
        assert!(MultiDirectional::new(vec![], 1.0, 1e-6).is_err());
        assert!(MultiDirectional::new(vec![0.0], 0.0, 1e-6).is_err());
        assert!(MultiDirectional::new(vec![0.0], 1.0, 0.0).is_err());
    }
}
