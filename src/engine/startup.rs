//! [ours] Start-up guesses of the walker's shooting solves: the seven unknowns — τ1, p (stance),
//! A, B (swing1), C (swing2), D0, D1 (swing3) — of steps 0, 1 and 2 as quadratics in the Froude
//! speed, and the cold Jacobians of step 0, fitted over the grid of `tests/walk.rs` by
//! `examples/startup_fit.rs`. The first step starts from an
//! artificial posture (the mirrored heel strike), and its transient (τ1 falls from ≈ 3 to
//! ≈ −0.3 M l1, then rises to ≈ 0) is what the fits of the changes from step 0 to 1 and from 1
//! to 2 follow; later steps start from the previous step's solution alone. The guesses only save
//! trials: every start has a fallback ([`with_fallback`]).
use nalgebra::{Matrix2, Vector2};

use crate::control::shooting::{Memory1, Memory2, SolveReport, Start1, Start2};

/// Quadratics c0 + c1 F + c2 F² of the seven unknowns, in body units (torques / (M l1),
/// lengths / l1).
type Fits = [[f64; 3]; 7];

/// The fitted tables, printed by `cargo run --release --example startup_fit`.
pub(super) struct Tables {
    /// The solutions of step 0 (a cold start).
    pub step0: Fits,
    /// Their changes from step 0 to step 1 and from step 1 to step 2.
    pub changes: [Fits; 2],
    /// Cold Jacobians (`J[i][k]` = ∂rᵢ/∂xₖ, body units): the default walk's (1.4 m/s,
    /// H = 1.8 m, M = 80 kg) at the end of its step-0 solves, so that step 0 needs no difference
    /// trials; swing2's residual slope.
    pub cold_stance: [[f64; 2]; 2],
    pub cold_swing1: [[f64; 2]; 2],
    pub cold_swing2_slope: f64,
    pub cold_swing3: [[f64; 2]; 2],
}

const STEP0: [[f64; 3]; 7] =
    // step 0
    [
        [5.94477e-1, 2.75285e0, 1.12557e0], // τ1: largest residual 1.58e-1
        [-2.99372e-4, 1.10376e-2, 1.77189e-3], // p: largest residual 1.97e-3
        [5.43914e-1, -6.44801e0, 7.58348e0], // A: largest residual 2.30e-1
        [1.69408e-1, -2.89793e0, 2.14220e0], // B: largest residual 1.84e-1
        [-2.19923e-1, 8.84428e-1, -5.10054e-1], // C: largest residual 3.44e-2
        [-3.66406e0, 1.21026e1, -7.95248e0], // D0: largest residual 7.71e-1
        [9.37425e0, -3.41445e1, 2.32587e1], // D1: largest residual 1.66e0
    ];
const CHANGES: [[[f64; 3]; 7]; 2] = [
    // step 0 to 1
    [
        [-1.95710e0, 1.87123e0, -4.22192e0], // τ1: largest residual 4.45e-1
        [-2.24176e-4, 6.02331e-4, -5.71620e-4], // p: largest residual 6.76e-5
        [-1.29732e0, 7.06466e0, -1.29906e1], // A: largest residual 1.88e-1
        [-1.31518e-1, 8.43777e-1, -1.67196e0], // B: largest residual 6.20e-2
        [3.72783e-2, -2.21044e-1, 4.17782e-1], // C: largest residual 6.79e-3
        [-7.93594e-3, -2.53846e-1, 1.51814e-2], // D0: largest residual 2.42e-2
        [-1.45481e-1, 1.43134e0, -1.51461e0], // D1: largest residual 6.26e-2
    ],
    // step 1 to 2
    [
        [2.01613e-1, 2.20566e-1, -1.86355e-1], // τ1: largest residual 7.38e-2
        [2.72812e-5, -5.55637e-5, 3.68041e-5], // p: largest residual 7.73e-6
        [-3.23401e-2, 7.79124e-2, -1.12006e-1], // A: largest residual 2.43e-1
        [-1.01251e-3, -2.67600e-2, 2.26243e-2], // B: largest residual 4.40e-2
        [1.50207e-4, -3.66019e-4, 4.16825e-3], // C: largest residual 7.44e-3
        [-6.39472e-3, 4.39218e-2, -4.65281e-2], // D0: largest residual 2.32e-2
        [1.65605e-2, -1.22104e-1, 1.15393e-1], // D1: largest residual 1.97e-2
    ],
];
/// Cold Jacobians (`J[i][k]` = ∂rᵢ/∂xₖ, in body units): the default walk's (1.4 m/s,
/// H = 1.8 m, M = 80 kg) at the end of its step-0 solves, so that step 0 needs no difference
/// trials; swing2's residual slope. Generated with [`STEP0`], from walks started plainly
/// ([`Walker::without_startup_guesses`]), so a rerun reproduces them.
const COLD_STANCE: [[f64; 2]; 2] = [[1.39854e-1, -3.26875e-1], [5.30547e-2, 8.05430e-1]];
const COLD_SWING1: [[f64; 2]; 2] = [[4.01516e-1, -2.98615e-1], [2.24522e-1, 4.54508e-1]];
const COLD_SWING2_SLOPE: f64 = 3.22758e-1;
const COLD_SWING3: [[f64; 2]; 2] = [[4.76559e-2, 1.59202e-2], [-4.89486e-1, -2.46284e-1]];

const TABLES: Tables = Tables {
    step0: STEP0,
    changes: CHANGES,
    cold_stance: COLD_STANCE,
    cold_swing1: COLD_SWING1,
    cold_swing2_slope: COLD_SWING2_SLOPE,
    cold_swing3: COLD_SWING3,
};

pub(super) fn tables() -> &'static Tables {
    &TABLES
}

fn quadratic(c: [f64; 3], x: f64) -> f64 {
    c[0] + x * (c[1] + x * c[2])
}

/// How the solves of step `index` start, at Froude speed `froude` = v / √(g l1).
#[derive(Clone, Copy, Debug)]
pub(super) struct Startup {
    /// From the fitted guesses; otherwise plainly: the plain start at step 0, the memory later
    /// ([`crate::engine::walker::Walker::without_startup_guesses`]).
    pub enabled: bool,
    pub index: usize,
    pub froude: f64,
}

impl Startup {
    /// The start of a 2-D solve of `unknowns` (rows of the tables), unknown k in units of
    /// `x_unit[k]`, and the start to fall back on ([`with_fallback`]): at step 0 the fit with
    /// the cold Jacobian (`cold`: body units, residual i in units of `cold.1[i]`), then `plain`;
    /// at steps 1 and 2 the memory moved by [`startup_moves`], then the memory itself; later the
    /// memory alone.
    pub fn start2(
        &self,
        memory: Option<Memory2>,
        unknowns: [usize; 2],
        x_unit: [f64; 2],
        (j, r_unit): ([[f64; 2]; 2], [f64; 2]),
        plain: Start2,
    ) -> (Start2, Option<Start2>) {
        let fit =
            |c: &Fits| Vector2::from_fn(|k, _| quadratic(c[unknowns[k]], self.froude) * x_unit[k]);
        match (self.enabled, memory) {
            (false, None) => (plain, None),
            (false, Some(m)) => (Start2::Warm(m), None),
            (true, Some(mut m)) => {
                let unmoved = m;
                let nan = Vector2::repeat(f64::NAN);
                startup_moves(self.index, &mut m.x, &mut m.earlier, nan, |i| {
                    fit(&tables().changes[i - 1])
                });
                let fallback = (1..=2)
                    .contains(&self.index)
                    .then_some(Start2::Warm(unmoved));
                (Start2::Warm(m), fallback)
            }
            (true, None) => {
                let guess = Memory2 {
                    x: fit(&tables().step0),
                    jacobian: Matrix2::from_fn(|i, k| j[i][k] * r_unit[i] / x_unit[k]),
                    earlier: [Vector2::repeat(f64::NAN); 2],
                    ratio: f64::NAN,
                };
                (Start2::Warm(guess), Some(plain))
            }
        }
    }

    /// [`Self::start2`] for a 1-D solve of the tables' row `unknown`, in units of `x_unit`,
    /// with the cold residual slope `slope` (body units).
    pub fn start1(
        &self,
        memory: Option<Memory1>,
        unknown: usize,
        x_unit: f64,
        slope: f64,
        plain: Start1,
    ) -> (Start1, Option<Start1>) {
        let fit = |c: &Fits| quadratic(c[unknown], self.froude) * x_unit;
        match (self.enabled, memory) {
            (false, None) => (plain, None),
            (false, Some(m)) => (Start1::Warm(m), None),
            (true, Some(mut m)) => {
                let unmoved = m;
                startup_moves(self.index, &mut m.x, &mut m.earlier, f64::NAN, |i| {
                    fit(&tables().changes[i - 1])
                });
                let fallback = (1..=2)
                    .contains(&self.index)
                    .then_some(Start1::Warm(unmoved));
                (Start1::Warm(m), fallback)
            }
            (true, None) => (
                Start1::Warm(Memory1 {
                    x: fit(&tables().step0),
                    slope: slope / x_unit,
                    earlier: [f64::NAN; 2],
                    ratio: f64::NAN,
                }),
                Some(plain),
            ),
        }
    }
}

/// A solve from `start`, and when it does not converge (or its first trial fails) once more
/// from `fallback`, the report counting both: the start-up guesses are fits over the default
/// attributes' grid, and outside it (a style preset) they can lead where the residual has no
/// root nearby (the elderly preset's swing2 at 0.9 m/s).
pub(super) fn with_fallback<S, T>(
    start: S,
    fallback: Option<S>,
    solve: impl Fn(S) -> Result<(T, SolveReport), String>,
) -> Result<(T, SolveReport), String> {
    let first = solve(start);
    match (first, fallback) {
        (Ok((t, report)), _) if report.converged => Ok((t, report)),
        (first, None) => first,
        (first, Some(fallback)) => {
            let spent = first.as_ref().map_or(1, |(_, r)| r.iterations);
            solve(fallback).map(|(t, mut report)| {
                report.iterations += spent;
                (t, report)
            })
        }
    }
}

/// A warm start at step `index` moved by the fitted start-up transient, `change(i)` from step
/// i − 1 to step i ([`Tables::changes`]): the point `x` at steps 1 and 2; the extrapolation's
/// history `earlier` (`shooting::Memory2`) emptied at step 1 (step 0 started from a fit, not
/// from a solution), and its latest entry moved back at steps 2 and 3 (it is the moved start).
fn startup_moves<T>(
    index: usize,
    x: &mut T,
    earlier: &mut [T; 2],
    nan: T,
    change: impl Fn(usize) -> T,
) where
    T: Copy + std::ops::Add<Output = T> + std::ops::Sub<Output = T>,
{
    if index == 1 {
        *earlier = [nan; 2];
    }
    if (2..=3).contains(&index) {
        earlier[0] = earlier[0] - change(index - 1);
    }
    if (1..=2).contains(&index) {
        *x = *x + change(index);
    }
}
