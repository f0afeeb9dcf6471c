//! The stance hip's acceleration tabulated for the swing (spec §5: the swing hangs from the hip
//! of the same step's stance).
use super::{StanceRun, StanceSetup};

/// The hip's acceleration over an interval, tabulated on a uniform grid from the stance run
/// and interpolated by the quintic through the six nearest grid points (Lagrange; at the ends of
/// a piece the six are shifted inside it): the swing's right-hand side reads the moving hip
/// here instead of re-evaluating the stance dynamics at every stage (spec §5: the swing uses
/// the hip of the same step's stance). The table is split wherever the stance run has a segment
/// boundary — the leg torque switching off, the position actuator's blend starting, the leg
/// locking or releasing, the leg force's clamp — since the acceleration or its derivative jumps
/// there, and at the reference's heel-off, where its third derivative jumps. The swing
/// integrations stop at the same [`HipPath::breaks`], so that no integrator step straddles a
/// jump (a step across one leaves a global error far above the integrator's tolerance). The
/// grid step is at most [`HIP_PATH_STEP`]. A kinematic offset of the swing-side hip joint from
/// the dynamic hip (the determinants of gait, spec §7) adds its acceleration, by central second
/// differences (step [`OFFSET_DIFFERENCE_STEP`]: truncation ≈ h² f⁗ / 12 ≈ 1e-8 m/s²).
#[derive(Clone, Debug)]
pub struct HipPath {
    pieces: Vec<Piece>,
}

/// [`HipPath`] between two breaks.
#[derive(Clone, Debug)]
struct Piece {
    t0: f64,
    t1: f64,
    dt: f64,
    /// Intervals n ≥ 5 of the grid t0 + i dt, i = 0..=n (the ends just inside the piece).
    n: usize,
    /// For each window of six grid values a_j..a_{j+5} (j = 0..=n − 5), the Newton form of the
    /// quintic through them: Δᵐa_j / m!, m = 0..=5 (forward differences), per component.
    newton: Vec<[[f64; 6]; 2]>,
}

impl Piece {
    /// The windows' forward differences of the grid values `acc`.
    fn new(t0: f64, t1: f64, dt: f64, acc: &[[f64; 2]]) -> Self {
        const FACTORIAL: [f64; 6] = [1.0, 1.0, 2.0, 6.0, 24.0, 120.0];
        let n = acc.len() - 1;
        let newton = (0..=n - 5)
            .map(|j| {
                let mut out = [[0.0; 6]; 2];
                for (c, o) in out.iter_mut().enumerate() {
                    let mut d: [f64; 6] = std::array::from_fn(|k| acc[j + k][c]);
                    for m in 0..6 {
                        o[m] = d[0] / FACTORIAL[m];
                        for k in 0..5 - m {
                            d[k] = d[k + 1] - d[k];
                        }
                    }
                }
                out
            })
            .collect();
        Piece {
            t0,
            t1,
            dt,
            n,
            newton,
        }
    }
}

/// Largest grid step of [`HipPath::new`] (s); the walker's is
/// `EngineParameters::hip_path_step`.
pub const HIP_PATH_STEP: f64 = 3e-3;

/// The step of [`HipPath::new`]'s central difference of the swing hip's offset (s).
pub const OFFSET_DIFFERENCE_STEP: f64 = 1e-4;
const H: f64 = OFFSET_DIFFERENCE_STEP;

impl HipPath {
    /// Tabulate the hip acceleration of `run` plus that of `offset(t)` on [t0, t1].
    pub fn new(
        run: &StanceRun,
        setup: &StanceSetup,
        t0: f64,
        t1: f64,
        offset: &dyn Fn(f64) -> [f64; 2],
    ) -> Self {
        Self::with_offset_acceleration(run, setup, t0, t1, HIP_PATH_STEP, offset, &|_| None)
    }

    /// [`Self::new`] on a grid step of at most `step`, with the offset's acceleration where
    /// `offset_acceleration(t)` gives it (in closed form); elsewhere the offset is differenced
    /// as in [`Self::new`].
    pub(crate) fn with_offset_acceleration(
        run: &StanceRun,
        setup: &StanceSetup,
        t0: f64,
        t1: f64,
        step: f64,
        offset: &dyn Fn(f64) -> [f64; 2],
        offset_acceleration: &dyn Fn(f64) -> Option<[f64; 2]>,
    ) -> Self {
        let hip_acceleration = run.hip_acceleration(setup);
        let acceleration = |t: f64| {
            let a = hip_acceleration(t);
            if let Some(o) = offset_acceleration(t) {
                return [a[0] + o[0], a[1] + o[1]];
            }
            let (m, o, p) = (offset(t - H), offset(t), offset(t + H));
            [
                a[0] + (m[0] - 2.0 * o[0] + p[0]) / (H * H),
                a[1] + (m[1] - 2.0 * o[1] + p[1]) / (H * H),
            ]
        };
        let mut cuts = vec![t0];
        cuts.extend(
            run.segments
                .iter()
                .map(|(seg, _)| seg.t1)
                .filter(|&t| t > t0 && t < t1),
        );
        if let Some(t) = run.heel_off_time(setup).filter(|&t| t > t0 && t < t1) {
            cuts.push(t);
            cuts.sort_by(f64::total_cmp);
        }
        cuts.push(t1);
        // the ends of a piece are its inner limits (the state or the forces jump at a cut)
        let eps = 1e-12 * setup.t_step;
        let pieces = cuts
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let n = ((b - a) / step).ceil().max(5.0) as usize;
                let dt = (b - a) / n as f64;
                let mut acc = Vec::with_capacity(n + 1);
                for i in 0..=n {
                    let t = if i == n {
                        b - eps
                    } else if i == 0 {
                        a + eps
                    } else {
                        a + i as f64 * dt
                    };
                    acc.push(acceleration(t));
                }
                Piece::new(a, b, dt, &acc)
            })
            .collect();
        HipPath { pieces }
    }

    /// The times inside the tabulated interval where the acceleration may jump.
    pub fn breaks(&self) -> impl Iterator<Item = f64> + '_ {
        self.pieces[..self.pieces.len() - 1].iter().map(|p| p.t1)
    }

    /// The hip acceleration at t (clamped to the tabulated interval).
    pub fn acceleration(&self, t: f64) -> [f64; 2] {
        self.acceleration_on(self.piece(t), t)
    }

    /// The index of the piece (between [`Self::breaks`]) that holds t, a break starting the
    /// next piece.
    pub fn piece(&self, t: f64) -> usize {
        self.pieces
            .iter()
            .position(|p| t < p.t1)
            .unwrap_or(self.pieces.len() - 1)
    }

    /// The acceleration of piece `piece` at t (clamped to the piece): at a break, the limit
    /// from inside the piece, which an integration that stops at the break needs for its last
    /// stages.
    pub fn acceleration_on(&self, piece: usize, t: f64) -> [f64; 2] {
        let p = &self.pieces[piece];
        let x = ((t - p.t0) / p.dt).clamp(0.0, p.n as f64);
        // the six grid points around t's interval (shifted inside the piece at its ends), the
        // quintic through them in Newton's form, nested
        // (x ≥ 0: the cast truncates, a floor without libm's floor, which baseline x86-64 calls)
        let j = (x as usize).saturating_sub(2).min(p.n - 5);
        let u = x - j as f64;
        p.newton[j].map(|d| {
            d[0] + u
                * (d[1]
                    + (u - 1.0)
                        * (d[2] + (u - 2.0) * (d[3] + (u - 3.0) * (d[4] + (u - 4.0) * d[5]))))
        })
    }
}
