//! Integration of one (sub)phase by an explicit Runge–Kutta pair with dense output ([`Method`]):
//! Hairer's DOP853, the Dormand–Prince 8(5,3) pair with its 7th-order dense output (Hairer,
//! Nørsett & Wanner, *Solving ODEs I*, II.10), for every phase of the walk [`METHOD`], or the
//! Dormand–Prince 5(4) pair with its 4th-order dense output (II.5: DOPRI5, the same method and
//! step control as `ode_solvers::Dopri5`). Written for fixed-size states: the stages live on the
//! stack, the right-hand side is called through a generic (inlined), and the only allocation
//! is the dense record, one entry per accepted step. (ode_solvers 0.6.2's DOP853 evaluates its
//! 12th stage at t instead of t + h — its c12 is 0 — which is why it took tiny steps and
//! reported stiffness in the walk's time-dependent phases; the tests here check the order on
//! a non-autonomous problem.) Accurate event location: the integration
//! stops after the accepted step in which an event function changes sign, and the crossing is
//! root-found on that step's dense output to ~1e-13 s (spec §4: events are located, not rounded
//! to the nearest solver step).
use nalgebra::SVector;

/// Relative and absolute integrator tolerance. Spec §6 asks for residuals that are smooth in the
/// unknowns at the level of the shooting tolerance, by rtol = atol ≤ 1e-10 *or* a fixed step
/// sequence per (sub)phase: the shooting trials follow a frozen mesh ([`integrate_on`]), so the
/// tolerance is set by accuracy alone. At 1e-8 the converged magnitudes, integrated again at
/// 1e-12, meet the step's end conditions to ≤ 1.2e-7 over the grid (`examples/evals.rs`; 6.4e-7
/// at 1e-7, too close to the 1e-6 promise; measured again after the swing1 knee damper and the
/// start-up guesses: 5.1e-8 stance, 1.3e-8 swing3 at 1e-8; at 1e-7 the swing's net work also
/// misses its energy balance, `tests/work.rs`, by 8e-4 J against the 7.9e-4 J bound; with
/// DOP853 and the segments ending at the forces' jumps and kinks: 1.0e-8 stance, 2.0e-8
/// swing1, 1.8e-8 swing3 over the grid; with the virtual leg's stance reference 1.0e-8, 1.5e-8,
/// 1.0e-8, and swing3's heel landing velocity 6.3e-6 m/s at one step, down to 3.4e-8 once the
/// reference no longer kinked at heel strike (`stance::PAST_END`); swing2 runs at 100 times
/// this, `swing::SWING2_TOLERANCE_SCALE`); docs/engine.md has the table. Now 5e-8: with DOP853
/// the grid's end conditions re-integrated at 1e-12 are met to 1.0e-8, 3.7e-8, 1.3e-8, 6.9e-8
/// (stance, swing1–3), 14 times inside the 1e-6 promise, for 15 % fewer evaluations than at
/// 1e-8 (at 1e-7: 1.6e-7 in swing1 and swing2, 25 % fewer; at 3e-8: 6.0e-8, 10 % fewer).
pub const TOLERANCE: f64 = 5e-8;

/// How precisely event times are located (s).
pub const EVENT_TIME_TOLERANCE: f64 = 1e-13;

/// Accepted steps allowed in one integration.
const MAX_STEPS: usize = 100_000;

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

/// The dense output of one accepted step on [t, t + h]: with θ = (t' − t)/h and θ' = 1 − θ,
/// y(t') = r0 + θ (r1 + θ' (r2 + θ (r3 + θ' (r4 + θ (r5 + θ' (r6 + θ r7)))))): Dopri5's
/// quartic has r5 = r6 = r7 = 0, DOP853's 7th-degree polynomial uses all eight.
/// `ready`: r4..r7 are computed (a shooting trial's DOP853 steps leave them to
/// [`Segment::densify`]).
#[derive(Clone, Copy, Debug)]
struct DenseStep<const N: usize> {
    t: f64,
    h: f64,
    r: [SVector<f64, N>; 8],
    ready: bool,
}

/// What DOP853's dense output needs of an accepted step besides its ends: the stages k1,
/// k6..k12 and k13 = f(t + h, y_new).
type Stages<const N: usize> = [SVector<f64, N>; 9];

impl<const N: usize> DenseStep<N> {
    fn eval(&self, t: f64) -> SVector<f64, N> {
        assert!(self.ready, "a dense output not computed (Segment::densify)");
        let th = (t - self.t) / self.h;
        // the nested form multiplied out, Σ w_k r_k with w = 1, θ, p, θp, p², θp², p³, θp³
        // (p = θθ'), summed as a tree: the same terms, but three vector additions deep
        // instead of a chain of seven multiply-adds
        let p = th * (1.0 - th);
        let (p2, th_p) = (p * p, th * p);
        let r = &self.r;
        (r[0] + r[1] * th + (r[2] * p + r[3] * th_p))
            + ((r[4] * p2 + r[5] * (th * p2)) + (r[6] * (p * p2) + r[7] * (th_p * p2)))
    }
}

/// The dense solution of one integration, valid on [t0, t1].
#[derive(Clone, Debug)]
pub struct Segment<const N: usize> {
    pub t0: f64,
    pub t1: f64,
    pub y0: SVector<f64, N>,
    pub y1: SVector<f64, N>,
    steps: Vec<DenseStep<N>>,
    /// Stages of the steps without their dense output, one per step (empty when every step
    /// has it).
    pending: Vec<Stages<N>>,
}

impl<const N: usize> Segment<N> {
    /// Whether [`Self::state`] is available everywhere (else [`Self::densify`] first).
    pub fn is_dense(&self) -> bool {
        self.pending.is_empty()
    }

    /// Complete the dense output that [`integrate_trial`] left out: three evaluations per step
    /// of the right-hand side `phase_at(t)` gives for the step starting at t (the phase of the
    /// integration that made it). Returns the evaluations.
    pub fn densify<P: Phase<N, K>, const K: usize>(&mut self, phase_at: impl Fn(f64) -> P) -> u32 {
        let mut evaluations = 0;
        for (step, k) in self.steps.iter_mut().zip(&self.pending) {
            if !step.ready {
                let tail = dop853_dense(&phase_at(step.t), step.t, step.h, &step.r[0], k);
                step.r[4..].copy_from_slice(&tail);
                step.ready = true;
                evaluations += 3;
            }
        }
        self.pending = Vec::new();
        evaluations
    }

    /// The accepted steps (start, end), in order, within [t0, t1]: on each, the dense output is
    /// one quartic polynomial.
    pub fn steps(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.steps
            .iter()
            .map(|s| (s.t.max(self.t0), (s.t + s.h).min(self.t1)))
            .filter(|(a, b)| b > a)
    }

    /// The state at `t`, clamped to [t0, t1].
    pub fn state(&self, t: f64) -> SVector<f64, N> {
        if t <= self.t0 {
            return self.y0;
        }
        if t >= self.t1 {
            return self.y1;
        }
        let i = self
            .steps
            .partition_point(|s| s.t + s.h < t)
            .min(self.steps.len() - 1);
        self.steps[i].eval(t)
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
    /// Some step was chosen by the step-size control (always, without a mesh to follow).
    pub adapted: bool,
}

impl<const N: usize> Outcome<N> {
    /// This integration followed by `next`, which starts where this one ends: one segment,
    /// the evaluations added, `next`'s event.
    pub fn then(mut self, next: Outcome<N>) -> Outcome<N> {
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

// Dormand–Prince 5(4) coefficients (Hairer, Nørsett & Wanner, Table II.5.2; dense output II.6).
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// Dormand–Prince 8(5,3) coefficients (Hairer, Nørsett & Wanner, *Solving ODEs I*, II.10, and
/// Hairer's DOP853 code: the stages, the 5th- and 3rd-order error estimators, the dense output
/// of order 7 with three more stages). The 12th stage is at t + h (c12 = 1).
#[allow(clippy::excessive_precision, clippy::unreadable_literal)]
mod dop853 {
    pub const A2_1: f64 = 0.05260015195876773;
    pub const A3_1: f64 = 0.0197250569845379;
    pub const A3_2: f64 = 0.0591751709536137;
    pub const A4_1: f64 = 0.02958758547680685;
    pub const A4_3: f64 = 0.08876275643042054;
    pub const A5_1: f64 = 0.2413651341592667;
    pub const A5_3: f64 = -0.8845494793282861;
    pub const A5_4: f64 = 0.924834003261792;
    pub const A6_1: f64 = 0.037037037037037035;
    pub const A6_4: f64 = 0.17082860872947386;
    pub const A6_5: f64 = 0.12546768756682242;
    pub const A7_1: f64 = 0.037109375;
    pub const A7_4: f64 = 0.17025221101954405;
    pub const A7_5: f64 = 0.06021653898045596;
    pub const A7_6: f64 = -0.017578125;
    pub const A8_1: f64 = 0.03709200011850479;
    pub const A8_4: f64 = 0.17038392571223998;
    pub const A8_5: f64 = 0.10726203044637328;
    pub const A8_6: f64 = -0.015319437748624402;
    pub const A8_7: f64 = 0.008273789163814023;
    pub const A9_1: f64 = 0.6241109587160757;
    pub const A9_4: f64 = -3.3608926294469414;
    pub const A9_5: f64 = -0.868219346841726;
    pub const A9_6: f64 = 27.59209969944671;
    pub const A9_7: f64 = 20.154067550477894;
    pub const A9_8: f64 = -43.48988418106996;
    pub const A10_1: f64 = 0.47766253643826434;
    pub const A10_4: f64 = -2.4881146199716677;
    pub const A10_5: f64 = -0.590290826836843;
    pub const A10_6: f64 = 21.230051448181193;
    pub const A10_7: f64 = 15.279233632882423;
    pub const A10_8: f64 = -33.28821096898486;
    pub const A10_9: f64 = -0.020331201708508627;
    pub const A11_1: f64 = -0.9371424300859873;
    pub const A11_4: f64 = 5.186372428844064;
    pub const A11_5: f64 = 1.0914373489967295;
    pub const A11_6: f64 = -8.149787010746927;
    pub const A11_7: f64 = -18.52006565999696;
    pub const A11_8: f64 = 22.739487099350505;
    pub const A11_9: f64 = 2.4936055526796523;
    pub const A11_10: f64 = -3.0467644718982196;
    pub const A12_1: f64 = 2.273310147516538;
    pub const A12_4: f64 = -10.53449546673725;
    pub const A12_5: f64 = -2.0008720582248625;
    pub const A12_6: f64 = -17.9589318631188;
    pub const A12_7: f64 = 27.94888452941996;
    pub const A12_8: f64 = -2.8589982771350235;
    pub const A12_9: f64 = -8.87285693353063;
    pub const A12_10: f64 = 12.360567175794303;
    pub const A12_11: f64 = 0.6433927460157636;
    pub const A14_1: f64 = 0.056167502283047954;
    pub const A14_7: f64 = 0.25350021021662483;
    pub const A14_8: f64 = -0.2462390374708025;
    pub const A14_9: f64 = -0.12419142326381637;
    pub const A14_10: f64 = 0.15329179827876568;
    pub const A14_11: f64 = 0.00820105229563469;
    pub const A14_12: f64 = 0.007567897660545699;
    pub const A14_13: f64 = -0.008298;
    pub const A15_1: f64 = 0.03183464816350214;
    pub const A15_6: f64 = 0.028300909672366776;
    pub const A15_7: f64 = 0.053541988307438566;
    pub const A15_8: f64 = -0.05492374857139099;
    pub const A15_11: f64 = -0.00010834732869724932;
    pub const A15_12: f64 = 0.0003825710908356584;
    pub const A15_13: f64 = -0.00034046500868740456;
    pub const A15_14: f64 = 0.1413124436746325;
    pub const A16_1: f64 = -0.42889630158379194;
    pub const A16_6: f64 = -4.697621415361164;
    pub const A16_7: f64 = 7.683421196062599;
    pub const A16_8: f64 = 4.06898981839711;
    pub const A16_9: f64 = 0.3567271874552811;
    pub const A16_13: f64 = -0.0013990241651590145;
    pub const A16_14: f64 = 2.9475147891527724;
    pub const A16_15: f64 = -9.15095847217987;
    pub const C2: f64 = 0.05260015195876773;
    pub const C3: f64 = 0.0789002279381516;
    pub const C4: f64 = 0.1183503419072274;
    pub const C5: f64 = 0.2816496580927726;
    pub const C6: f64 = 0.3333333333333333;
    pub const C7: f64 = 0.25;
    pub const C8: f64 = 0.3076923076923077;
    pub const C9: f64 = 0.6512820512820513;
    pub const C10: f64 = 0.6;
    pub const C11: f64 = 0.8571428571428571;
    pub const C14: f64 = 0.1;
    pub const C15: f64 = 0.2;
    pub const C16: f64 = 0.7777777777777778;
    pub const B1: f64 = 0.054293734116568765;
    pub const B6: f64 = 4.450312892752409;
    pub const B7: f64 = 1.8915178993145003;
    pub const B8: f64 = -5.801203960010585;
    pub const B9: f64 = 0.3111643669578199;
    pub const B10: f64 = -0.1521609496625161;
    pub const B11: f64 = 0.20136540080403034;
    pub const B12: f64 = 0.04471061572777259;
    pub const BHH1: f64 = 0.2440944881889764;
    pub const BHH2: f64 = 0.7338466882816118;
    pub const BHH3: f64 = 0.022058823529411766;
    pub const ER1: f64 = 0.01312004499419488;
    pub const ER6: f64 = -1.2251564463762044;
    pub const ER7: f64 = -0.4957589496572502;
    pub const ER8: f64 = 1.6643771824549864;
    pub const ER9: f64 = -0.35032884874997366;
    pub const ER10: f64 = 0.3341791187130175;
    pub const ER11: f64 = 0.08192320648511571;
    pub const ER12: f64 = -0.022355307863886294;
    pub const D4: [f64; 16] = [
        -8.428938276109013,
        0.0,
        0.0,
        0.0,
        0.0,
        0.5667149535193777,
        -3.0689499459498917,
        2.38466765651207,
        2.117034582445028,
        -0.871391583777973,
        2.2404374302607883,
        0.6315787787694688,
        -0.08899033645133331,
        18.148505520854727,
        -9.194632392478356,
        -4.436036387594894,
    ];
    pub const D5: [f64; 16] = [
        10.427508642579134,
        0.0,
        0.0,
        0.0,
        0.0,
        242.28349177525817,
        165.20045171727028,
        -374.5467547226902,
        -22.113666853125306,
        7.733432668472264,
        -30.674084731089398,
        -9.332130526430229,
        15.697238121770845,
        -31.139403219565178,
        -9.35292435884448,
        35.81684148639408,
    ];
    pub const D6: [f64; 16] = [
        19.985053242002433,
        0.0,
        0.0,
        0.0,
        0.0,
        -387.0373087493518,
        -189.17813819516758,
        527.8081592054236,
        -11.57390253995963,
        6.8812326946963,
        -1.0006050966910838,
        0.7777137798053443,
        -2.778205752353508,
        -60.19669523126412,
        84.32040550667716,
        11.99229113618279,
    ];
    pub const D7: [f64; 16] = [
        -25.69393346270375,
        0.0,
        0.0,
        0.0,
        0.0,
        -154.18974869023643,
        -231.5293791760455,
        357.6391179106141,
        93.40532418362432,
        -37.45832313645163,
        104.0996495089623,
        29.8402934266605,
        -43.53345659001114,
        96.32455395918828,
        -39.17726167561544,
        -149.72683625798564,
    ];
}

// PI step-size controller (Hairer's DOPRI5 defaults, as in ode_solvers).
const BETA: f64 = 0.04;
const ALPHA: f64 = 0.2 - 0.75 * BETA;
const SAFETY: f64 = 0.9;
/// 1 / (smallest step factor 0.2) and 1 / (largest 10).
const FACC1: f64 = 5.0;
const FACC2: f64 = 0.1;

/// Weighted RMS norm of `e` with the scale atol + rtol max(|a|, |b|).
fn error_norm<const N: usize>(
    e: &SVector<f64, N>,
    a: &SVector<f64, N>,
    b: &SVector<f64, N>,
    tol: f64,
) -> f64 {
    let mut sum = 0.0;
    for i in 0..N {
        let sc = tol + tol * a[i].abs().max(b[i].abs());
        let q = e[i] / sc;
        sum += q * q;
    }
    (sum / N as f64).sqrt()
}

/// Initial step (Hairer's HINIT): two right-hand-side evaluations, `f0` given.
fn initial_step<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: &SVector<f64, N>,
    f0: &SVector<f64, N>,
    h_max: f64,
    tol: f64,
    order: f64,
) -> f64 {
    let zero = SVector::<f64, N>::zeros();
    let d0 = error_norm(y0, y0, &zero, tol);
    let d1 = error_norm(f0, y0, &zero, tol);
    let mut h0 = if d0 < 1e-10 || d1 < 1e-10 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    h0 = h0.min(h_max);
    let f1 = phase.rhs(t0 + h0, &(y0 + f0 * h0));
    let d2 = error_norm(&(f1 - f0), y0, &zero, tol) / h0;
    let h1 = if d1.max(d2) <= 1e-15 {
        1e-6_f64.max(h0 * 1e-3)
    } else {
        (0.01 / d1.max(d2)).powf(1.0 / order)
    };
    (100.0 * h0).min(h1).min(h_max)
}

/// Integrate `phase` from (t0, y0) to t1, stopping at the first event.
pub fn integrate<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
) -> Result<Outcome<N>, String> {
    integrate_with(phase, t0, y0, t1, TOLERANCE)
}

/// [`integrate`] with relative and absolute tolerance `tol`.
pub fn integrate_with<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tol: f64,
) -> Result<Outcome<N>, String> {
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

/// A frozen mesh is followed while every step's error estimate stays within this multiple of
/// the tolerance; beyond it the step-size control takes over from that step on.
pub const FROZEN_MESH_LIMIT: f64 = 2.0;

/// [`integrate_with`] on the step sequence of `mesh` (a previous integration from the same t0,
/// typically the previous shooting trial), so that the end state is a smooth function of the
/// phase's parameters: an adaptive integrator's end state jumps by about its global error
/// whenever a trial changes the step sequence, and in ill-conditioned phases (swing1 at the
/// grid's corners) those jumps reach 1e3 times the tolerance and stall the shooting. The mesh
/// is followed while each step's error estimate stays within [`FROZEN_MESH_LIMIT`] times the
/// tolerance (and, past its end, the control takes over); `Outcome::adapted` tells whether any
/// step was chosen by the control, i.e. whether this integration's mesh should replace it.
pub fn integrate_on<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tol: f64,
    mesh: Mesh<'_, N>,
) -> Result<Outcome<N>, String> {
    integrate_by(METHOD, phase, t0, y0, t1, tol, mesh)
}

/// [`integrate_on`] for a shooting trial: DOP853's dense output is left out (the three extra
/// evaluations of each step) except on an event's step, where the event is located; the trial
/// the shooting keeps gets it by [`Segment::densify`], the others never need it.
pub fn integrate_trial<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tol: f64,
    mesh: Mesh<'_, N>,
) -> Result<Outcome<N>, String> {
    run(METHOD, true, phase, t0, y0, t1, tol, mesh)
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

/// The method of [`integrate_on`]: at the walk's tolerance 1e-8, DOP853's steps are 3–5 times
/// Dopri5's (stance 5–25 ms, swing2 2–7 ms), and every phase takes fewer evaluations
/// (docs/engine.md, "Speed").
pub const METHOD: Method = Method::Dop853;

impl Method {
    /// The order that sets the step-size control's exponent.
    fn order(self) -> f64 {
        match self {
            Method::Dopri5 => 5.0,
            Method::Dop853 => 8.0,
        }
    }

    /// The step-size control (Hairer's defaults for each code): exponents α and β of the PI
    /// controller, 1 / smallest and 1 / largest step factor.
    fn control(self) -> (f64, f64, f64, f64) {
        match self {
            Method::Dopri5 => (ALPHA, BETA, FACC1, FACC2),
            Method::Dop853 => (0.125, 0.0, 1.0 / 0.333, 1.0 / 6.0),
        }
    }
}

/// One attempted step: the new state, the error norm, the stages.
struct Attempt<const N: usize> {
    y_new: SVector<f64, N>,
    err: f64,
    k: [SVector<f64, N>; 12],
}

/// A Dopri5 step from (t, y) with k1 = f(t, y): its stages k2..k7 (k7 = f(t + h, y_new)) in
/// `k[1..7]`.
fn dopri5_attempt<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t: f64,
    y: &SVector<f64, N>,
    k1: &SVector<f64, N>,
    h: f64,
    tol: f64,
) -> Attempt<N> {
    let k1 = *k1;
    let k2 = phase.rhs(t + C2 * h, &(y + k1 * (h * A21)));
    let k3 = phase.rhs(t + C3 * h, &(y + (k1 * A31 + k2 * A32) * h));
    let k4 = phase.rhs(t + C4 * h, &(y + (k1 * A41 + k2 * A42 + k3 * A43) * h));
    let k5 = phase.rhs(
        t + C5 * h,
        &(y + (k1 * A51 + k2 * A52 + k3 * A53 + k4 * A54) * h),
    );
    let k6 = phase.rhs(
        t + h,
        &(y + (k1 * A61 + k2 * A62 + k3 * A63 + k4 * A64 + k5 * A65) * h),
    );
    let y_new = y + (k1 * A71 + k3 * A73 + k4 * A74 + k5 * A75 + k6 * A76) * h;
    let k7 = phase.rhs(t + h, &y_new);
    let e = (k1 * E1 + k3 * E3 + k4 * E4 + k5 * E5 + k6 * E6 + k7 * E7) * h;
    let err = error_norm(&e, y, &y_new, tol);
    let z = SVector::<f64, N>::zeros();
    Attempt {
        y_new,
        err,
        k: [k1, k2, k3, k4, k5, k6, k7, z, z, z, z, z],
    }
}

/// A DOP853 step from (t, y) with k1 = f(t, y): its stages k2..k12 in `k[1..12]`.
fn dop853_attempt<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t: f64,
    y: &SVector<f64, N>,
    k1: &SVector<f64, N>,
    h: f64,
    tol: f64,
) -> Attempt<N> {
    let k1 = *k1;
    // each stage's argument sums y and its older stages first and the newest, k_{i−1}, last,
    // with the coefficients scaled by h: one multiply and one add stand between the right-hand
    // side that produced k_{i−1} and the next (the stages are a chain: its latency is the step's)
    let k2 = phase.rhs(t + dop853::C2 * h, &(y + k1 * (h * dop853::A2_1)));
    let k3 = phase.rhs(
        t + dop853::C3 * h,
        &((y + k1 * (h * dop853::A3_1)) + k2 * (h * dop853::A3_2)),
    );
    let k4 = phase.rhs(
        t + dop853::C4 * h,
        &((y + k1 * (h * dop853::A4_1)) + k3 * (h * dop853::A4_3)),
    );
    let k5 = phase.rhs(
        t + dop853::C5 * h,
        &((y + k1 * (h * dop853::A5_1) + k3 * (h * dop853::A5_3)) + k4 * (h * dop853::A5_4)),
    );
    let k6 = phase.rhs(
        t + dop853::C6 * h,
        &((y + k1 * (h * dop853::A6_1) + k4 * (h * dop853::A6_4)) + k5 * (h * dop853::A6_5)),
    );
    let k7 = phase.rhs(
        t + dop853::C7 * h,
        &((y + k1 * (h * dop853::A7_1) + k4 * (h * dop853::A7_4) + k5 * (h * dop853::A7_5))
            + k6 * (h * dop853::A7_6)),
    );
    let k8 = phase.rhs(
        t + dop853::C8 * h,
        &((y + k1 * (h * dop853::A8_1)
            + k4 * (h * dop853::A8_4)
            + k5 * (h * dop853::A8_5)
            + k6 * (h * dop853::A8_6))
            + k7 * (h * dop853::A8_7)),
    );
    let k9 = phase.rhs(
        t + dop853::C9 * h,
        &((y + k1 * (h * dop853::A9_1)
            + k4 * (h * dop853::A9_4)
            + k5 * (h * dop853::A9_5)
            + k6 * (h * dop853::A9_6)
            + k7 * (h * dop853::A9_7))
            + k8 * (h * dop853::A9_8)),
    );
    let k10 = phase.rhs(
        t + dop853::C10 * h,
        &((y + k1 * (h * dop853::A10_1)
            + k4 * (h * dop853::A10_4)
            + k5 * (h * dop853::A10_5)
            + k6 * (h * dop853::A10_6)
            + k7 * (h * dop853::A10_7)
            + k8 * (h * dop853::A10_8))
            + k9 * (h * dop853::A10_9)),
    );
    let k11 = phase.rhs(
        t + dop853::C11 * h,
        &((y + k1 * (h * dop853::A11_1)
            + k4 * (h * dop853::A11_4)
            + k5 * (h * dop853::A11_5)
            + k6 * (h * dop853::A11_6)
            + k7 * (h * dop853::A11_7)
            + k8 * (h * dop853::A11_8)
            + k9 * (h * dop853::A11_9))
            + k10 * (h * dop853::A11_10)),
    );
    let k12 = phase.rhs(
        t + h,
        &((y + k1 * (h * dop853::A12_1)
            + k4 * (h * dop853::A12_4)
            + k5 * (h * dop853::A12_5)
            + k6 * (h * dop853::A12_6)
            + k7 * (h * dop853::A12_7)
            + k8 * (h * dop853::A12_8)
            + k9 * (h * dop853::A12_9)
            + k10 * (h * dop853::A12_10))
            + k11 * (h * dop853::A12_11)),
    );
    let slope = k1 * dop853::B1
        + k6 * dop853::B6
        + k7 * dop853::B7
        + k8 * dop853::B8
        + k9 * dop853::B9
        + k10 * dop853::B10
        + k11 * dop853::B11
        + k12 * dop853::B12;
    let y_new = y + slope * h;
    // the 5th-order estimate, and the 3rd-order one that keeps it from being too optimistic
    // (Hairer's err = h e5² / √(e5² + 0.01 e3²))
    let e5 = k1 * dop853::ER1
        + k6 * dop853::ER6
        + k7 * dop853::ER7
        + k8 * dop853::ER8
        + k9 * dop853::ER9
        + k10 * dop853::ER10
        + k11 * dop853::ER11
        + k12 * dop853::ER12;
    let e3 = slope - k1 * dop853::BHH1 - k9 * dop853::BHH2 - k12 * dop853::BHH3;
    let (mut s5, mut s3) = (0.0, 0.0);
    for i in 0..N {
        let sc = tol + tol * y[i].abs().max(y_new[i].abs());
        s5 += (e5[i] / sc).powi(2);
        s3 += (e3[i] / sc).powi(2);
    }
    let deno = s5 + 0.01 * s3;
    let deno = if deno > 0.0 { deno } else { 1.0 };
    let err = h.abs() * s5 * (1.0 / (deno * N as f64)).sqrt();
    Attempt {
        y_new,
        err,
        k: [k1, k2, k3, k4, k5, k6, k7, k8, k9, k10, k11, k12],
    }
}

/// The dense output's r4..r7 of DOP853's accepted step from (t, y) with stages `k` (k1,
/// k6..k13): three more stages.
fn dop853_dense<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t: f64,
    h: f64,
    y: &SVector<f64, N>,
    k: &Stages<N>,
) -> [SVector<f64, N>; 4] {
    let [k1, k6, k7, k8, k9, k10, k11, k12, k13] = *k;
    let k14 = phase.rhs(
        t + dop853::C14 * h,
        &(y + (k1 * dop853::A14_1
            + k7 * dop853::A14_7
            + k8 * dop853::A14_8
            + k9 * dop853::A14_9
            + k10 * dop853::A14_10
            + k11 * dop853::A14_11
            + k12 * dop853::A14_12
            + k13 * dop853::A14_13)
            * h),
    );
    let k15 = phase.rhs(
        t + dop853::C15 * h,
        &(y + (k1 * dop853::A15_1
            + k6 * dop853::A15_6
            + k7 * dop853::A15_7
            + k8 * dop853::A15_8
            + k11 * dop853::A15_11
            + k12 * dop853::A15_12
            + k13 * dop853::A15_13
            + k14 * dop853::A15_14)
            * h),
    );
    let k16 = phase.rhs(
        t + dop853::C16 * h,
        &(y + (k1 * dop853::A16_1
            + k6 * dop853::A16_6
            + k7 * dop853::A16_7
            + k8 * dop853::A16_8
            + k9 * dop853::A16_9
            + k13 * dop853::A16_13
            + k14 * dop853::A16_14
            + k15 * dop853::A16_15)
            * h),
    );
    let d = |c: [f64; 16]| {
        (k1 * c[0]
            + k6 * c[5]
            + k7 * c[6]
            + k8 * c[7]
            + k9 * c[8]
            + k10 * c[9]
            + k11 * c[10]
            + k12 * c[11]
            + k13 * c[12]
            + k14 * c[13]
            + k15 * c[14]
            + k16 * c[15])
            * h
    };
    [d(dop853::D4), d(dop853::D5), d(dop853::D6), d(dop853::D7)]
}

/// [`integrate_on`] by `method`.
pub fn integrate_by<P: Phase<N, K>, const N: usize, const K: usize>(
    method: Method,
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tol: f64,
    mesh: Mesh<'_, N>,
) -> Result<Outcome<N>, String> {
    run(method, false, phase, t0, y0, t1, tol, mesh)
}

/// [`integrate_by`], the dense output left out when `lazy` ([`integrate_trial`]).
#[allow(clippy::too_many_arguments)]
fn run<P: Phase<N, K>, const N: usize, const K: usize>(
    method: Method,
    lazy: bool,
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tol: f64,
    mesh: Mesh<'_, N>,
) -> Result<Outcome<N>, String> {
    if !y0.iter().all(|v| v.is_finite()) {
        return Err(format!("non-finite state at t = {t0}"));
    }
    // the steps to follow, and the first one's size
    let (follow, h_first): (&[DenseStep<N>], f64) = match mesh {
        Mesh::Shifted(m) => (&m.steps, m.steps.first().map_or(0.0, |s| s.h)),
        Mesh::Aligned(m) => {
            // the step that contains t0 (ends after it), its rest merged into the next step
            // when under a tenth of it
            let mut i = m.steps.partition_point(|s| s.t + s.h <= t0);
            match m.steps.get(i) {
                Some(s) if s.t <= t0 => {
                    let mut h = s.t + s.h - t0;
                    if i + 1 < m.steps.len() && h < 0.1 * s.h {
                        i += 1;
                        h += m.steps[i].h;
                    }
                    let j = i + m.steps[i..].partition_point(|s| s.t < t1);
                    (&m.steps[i..j], h)
                }
                _ => (&[], 0.0),
            }
        }
        Mesh::Adaptive => (&[], 0.0),
    };
    let mut next = 0;
    let mut adapted = follow.is_empty();
    let h_max = t1 - t0;
    let mut g_last = phase.events(t0, &y0);
    let mut k1 = phase.rhs(t0, &y0);
    let mut evaluations = 1u32;
    let mut h = match follow.first() {
        Some(_) => h_first,
        None => {
            evaluations += 2;
            initial_step(phase, t0, &y0, &k1, h_max, tol, method.order())
        }
    };
    let mut steps: Vec<DenseStep<N>> = Vec::with_capacity(64);
    // (as large as `steps` when lazy: grown by doubling it was reallocated and copied 4 times
    // in a typical trial)
    let mut pending: Vec<Stages<N>> = Vec::with_capacity(if lazy { 64 } else { 0 });
    let (mut t, mut y) = (t0, y0);
    let (alpha, beta, facc1, facc2) = method.control();
    let mut fac_old = 1e-4_f64;
    let mut reject = false;
    let mut hit = None;
    loop {
        if steps.len() >= MAX_STEPS {
            return Err(format!("more than {MAX_STEPS} steps at t = {t}"));
        }
        if 0.1 * h.abs() <= f64::EPSILON * t.abs() {
            return Err(format!("step size underflow at t = {t}"));
        }
        // the last step takes up a remainder under 1 % of it (under 10 % on a mesh, whose
        // steps end where the mesh's phase ended: a start moved back would otherwise add a
        // sliver step each time the mesh is followed again)
        let stretch = if next < follow.len() { 1.1 } else { 1.01 };
        let last = t + stretch * h >= t1;
        if last {
            h = t1 - t;
        }
        let attempt = match method {
            Method::Dopri5 => dopri5_attempt(phase, t, &y, &k1, h, tol),
            Method::Dop853 => dop853_attempt(phase, t, &y, &k1, h, tol),
        };
        evaluations += match method {
            Method::Dopri5 => 6,
            Method::Dop853 => 11,
        };
        let err = attempt.err;
        if !err.is_finite() {
            return Err(format!("the state became non-finite at t = {t}"));
        }
        let following = next < follow.len();
        if following && err > FROZEN_MESH_LIMIT {
            next = follow.len();
            adapted = true;
        }
        if err <= 1.0 || (following && err <= FROZEN_MESH_LIMIT) {
            // PI control of the next step (needed only off the mesh: two `powf`)
            let (h_acc, err_old, rejected) = (h, fac_old, reject);
            let h_new = move || {
                let fac = (err.powf(alpha) / err_old.powf(beta) / SAFETY).clamp(facc2, facc1);
                let h_new = (h_acc / fac).min(h_max);
                if rejected { h_new.min(h_acc) } else { h_new }
            };
            fac_old = err.max(1e-4);
            reject = false;
            let (y_new, k_next, r, ready) = match method {
                Method::Dopri5 => {
                    let k = &attempt.k;
                    let (k1, k3, k4, k5, k6, k7) = (k[0], k[2], k[3], k[4], k[5], k[6]);
                    let ydiff = attempt.y_new - y;
                    let bspl = k1 * h - ydiff;
                    let r4 = (k1 * D1 + k3 * D3 + k4 * D4 + k5 * D5 + k6 * D6 + k7 * D7) * h;
                    let z = SVector::<f64, N>::zeros();
                    let r = [y, ydiff, bspl, ydiff - k7 * h - bspl, r4, z, z, z];
                    (attempt.y_new, k7, r, true)
                }
                Method::Dop853 => {
                    let k13 = phase.rhs(t + h, &attempt.y_new);
                    evaluations += 1;
                    let k = &attempt.k;
                    let stages = [k[0], k[5], k[6], k[7], k[8], k[9], k[10], k[11], k13];
                    let ydiff = attempt.y_new - y;
                    let bspl = k[0] * h - ydiff;
                    let z = SVector::<f64, N>::zeros();
                    let mut r = [y, ydiff, bspl, ydiff - k13 * h - bspl, z, z, z, z];
                    if lazy {
                        pending.push(stages);
                    } else {
                        let tail = dop853_dense(phase, t, h, &y, &stages);
                        r[4..].copy_from_slice(&tail);
                        evaluations += 3;
                    }
                    (attempt.y_new, k13, r, !lazy)
                }
            };
            steps.push(DenseStep { t, h, r, ready });
            t = if last { t1 } else { t + h };
            y = y_new;
            k1 = k_next;
            let g = phase.events(t, &y);
            if let Some(k) = (0..K).find(|&k| g_last[k] > 0.0 && g[k] <= 0.0) {
                hit = Some(k);
                break;
            }
            g_last = g;
            if last {
                break;
            }
            h = if following {
                next += 1;
                match follow.get(next) {
                    Some(s) => s.h,
                    None => {
                        adapted = true;
                        h_new()
                    }
                }
            } else {
                h_new()
            };
        } else {
            h /= facc1.min(err.powf(alpha) / SAFETY);
            reject = true;
        }
    }
    let mut segment = Segment {
        t0,
        t1: t,
        y0,
        y1: y,
        steps,
        pending,
    };
    if let Some(k) = hit {
        // the event's time on the last step's dense output (`roots::illinois`)
        let last = segment.steps.len() - 1;
        let step = &mut segment.steps[last];
        if !step.ready {
            let tail = dop853_dense(phase, step.t, step.h, &step.r[0], &segment.pending[last]);
            step.r[4..].copy_from_slice(&tail);
            step.ready = true;
            evaluations += 3;
        }
        let step = *step;
        let g = |t: f64| phase.events(t, &step.eval(t))[k];
        let (a, b) = (step.t, t);
        let (_, b) =
            crate::numerics::roots::illinois(g, (a, g(a)), (b, g(b)), EVENT_TIME_TOLERANCE, 100);
        segment.y1 = step.eval(b);
        segment.t1 = b;
    }
    Ok(Outcome {
        segment,
        event: hit,
        evaluations,
        adapted,
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

    #[test]
    fn dense_output_matches_the_analytic_solution() {
        struct Free;
        impl Phase<2, 0> for Free {
            fn rhs(&self, _t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
                SVector::<f64, 2>::new(y[1], -y[0])
            }
        }
        let out = integrate_with(&Free, 0.0, SVector::<f64, 2>::new(1.0, 0.0), 3.0, 1e-10).unwrap();
        assert_eq!(out.event, None);
        for i in 0..=30 {
            let t = 0.1 * i as f64;
            let y = out.segment.state(t);
            assert!((y[0] - t.cos()).abs() < 1e-8, "t {t}: {}", y[0]);
        }
        assert!((out.segment.y1[0] - 3.0_f64.cos()).abs() < 1e-9);
    }

    /// The dense output's tree sum against Hairer's nested form of DOP853's `contd8`,
    /// r0 + θ (r1 + θ' (r2 + θ (r3 + θ' (r4 + θ (r5 + θ' (r6 + θ r7)))))), on coefficients
    /// of both signs and sizes.
    #[test]
    fn dense_output_sums_the_nested_form() {
        let r: [SVector<f64, 1>; 8] = std::array::from_fn(|k| {
            SVector::<f64, 1>::new((k as f64 * 1.7 - 5.0) * 10f64.powi(k as i32 % 3))
        });
        let step = DenseStep {
            t: 0.3,
            h: 0.02,
            r,
            ready: true,
        };
        for i in 0..=20 {
            let t = 0.3 + 0.02 * i as f64 / 20.0;
            let (th, th1) = ((t - 0.3) / 0.02, 1.0 - (t - 0.3) / 0.02);
            let c = r.map(|v| v[0]);
            let nested = c[0]
                + th * (c[1]
                    + th1
                        * (c[2]
                            + th * (c[3] + th1 * (c[4] + th * (c[5] + th1 * (c[6] + th * c[7]))))));
            let got = step.eval(t)[0];
            assert!(
                (got - nested).abs() <= 1e-13 * nested.abs().max(1.0),
                "θ {th}: {got} {nested}"
            );
        }
    }

    /// A damped oscillator x'' = −ω² x − 0.1 x' with parameter ω.
    struct Damped(f64);
    impl Phase<2, 0> for Damped {
        fn rhs(&self, _t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
            SVector::<f64, 2>::new(y[1], -self.0 * self.0 * y[0] - 0.1 * y[1])
        }
    }

    #[test]
    fn a_frozen_mesh_is_followed_while_accurate() {
        let y0 = SVector::<f64, 2>::new(1.0, 0.0);
        let tol = 1e-6;
        let first = integrate_with(&Damped(3.0), 0.0, y0, 5.0, tol).unwrap();
        assert!(first.adapted);
        // on its own mesh, the same integration again, with no step-size choices
        let again = integrate_on(
            &Damped(3.0),
            0.0,
            y0,
            5.0,
            tol,
            Mesh::Aligned(&first.segment),
        )
        .unwrap();
        assert!(!again.adapted);
        assert_eq!(again.segment.y1, first.segment.y1);
        assert_eq!(
            again.evaluations + 2,
            first.evaluations,
            "no initial-step trials"
        );
        // a nearby parameter follows the same mesh, as accurately as the adaptive integration
        let near = integrate_on(
            &Damped(3.01),
            0.0,
            y0,
            5.0,
            tol,
            Mesh::Aligned(&first.segment),
        )
        .unwrap();
        let adaptive = integrate_with(&Damped(3.01), 0.0, y0, 5.0, tol).unwrap();
        assert!(!near.adapted);
        assert!((near.segment.y1 - adaptive.segment.y1).amax() < 1e-5);
        // a very different one leaves the mesh where its error estimate grows
        let far = integrate_on(
            &Damped(6.0),
            0.0,
            y0,
            5.0,
            tol,
            Mesh::Aligned(&first.segment),
        )
        .unwrap();
        assert!(far.adapted);
    }

    /// The last step's mesh, as the engine follows it into the next step
    /// (`walk::Walker::step`): entered inside one of its steps, and over a phase a sliver
    /// longer than its own, it still needs no step-size choice and no extra step.
    #[test]
    fn a_mesh_is_entered_mid_step_and_not_outgrown() {
        let y0 = SVector::<f64, 2>::new(1.0, 0.0);
        let tol = 1e-6;
        let first = integrate_with(&Damped(3.0), 0.0, y0, 5.0, tol).unwrap();
        let steps: Vec<(f64, f64)> = first.segment.steps().collect();
        let n = steps.len();
        // from the middle of the 4th step: its rest, then the mesh's steps
        let (a, b) = steps[3];
        let t0 = 0.5 * (a + b);
        let y_mid = first.segment.state(t0);
        let mid = integrate_on(
            &Damped(3.0),
            t0,
            y_mid,
            5.0,
            tol,
            Mesh::Aligned(&first.segment),
        )
        .unwrap();
        assert!(!mid.adapted);
        let mid_steps: Vec<(f64, f64)> = mid.segment.steps().collect();
        assert_eq!(mid_steps.len(), n - 3);
        assert_eq!(mid_steps[0], (t0, b));
        assert_eq!(mid_steps[1], steps[4]);
        let adaptive = integrate_with(&Damped(3.0), t0, y_mid, 5.0, tol).unwrap();
        assert!((mid.segment.y1 - adaptive.segment.y1).amax() < 1e-5);
        // a phase 5 % of its last step longer: the last step takes up the rest
        let (a, b) = steps[n - 2];
        let t1 = 5.0 + 0.05 * (b - a);
        let longer = integrate_on(
            &Damped(3.0),
            0.0,
            y0,
            t1,
            tol,
            Mesh::Shifted(&first.segment),
        )
        .unwrap();
        assert!(!longer.adapted);
        assert_eq!(longer.segment.steps().count(), n);
        assert_eq!(longer.segment.t1, t1);
    }

    /// y1' = y1 cos t, y2' = −2t y2 from (1, 1): y1 = exp(sin t), y2 = exp(−t²), a
    /// non-autonomous system (every stage's time matters).
    struct Exponentials;
    impl Phase<2, 0> for Exponentials {
        fn rhs(&self, t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
            SVector::<f64, 2>::new(y[0] * t.cos(), -2.0 * t * y[1])
        }
    }

    fn exact(t: f64) -> SVector<f64, 2> {
        SVector::<f64, 2>::new(t.sin().exp(), (-t * t).exp())
    }

    /// `method` on `n` equal steps over [0, 2] (a frozen mesh with a tolerance it never leaves):
    /// the end state's error and the dense output's largest error (10 points a step).
    fn fixed_steps(method: Method, n: usize) -> (f64, f64) {
        let h = 2.0 / n as f64;
        let zero = SVector::<f64, 2>::zeros();
        let mesh = Segment {
            t0: 0.0,
            t1: 2.0,
            y0: zero,
            y1: zero,
            steps: (0..n)
                .map(|i| DenseStep {
                    t: i as f64 * h,
                    h,
                    r: [zero; 8],
                    ready: true,
                })
                .collect(),
            pending: Vec::new(),
        };
        let out = integrate_by(
            method,
            &Exponentials,
            0.0,
            exact(0.0),
            2.0,
            1.0,
            Mesh::Aligned(&mesh),
        )
        .unwrap();
        assert!(!out.adapted);
        assert_eq!(out.segment.steps.len(), n);
        let end = (out.segment.y1 - exact(2.0)).amax();
        let dense = (0..=10 * n)
            .map(|i| {
                let t = i as f64 * h / 10.0;
                (out.segment.state(t) - exact(t)).amax()
            })
            .fold(0.0, f64::max);
        (end, dense)
    }

    #[test]
    fn both_methods_converge_at_their_orders() {
        // halving the step divides the error by 2^p: DOP853 p = 8 (dense output of order 7:
        // its error per step is O(h^8) too), Dopri5 p = 5 (dense output of order 4: O(h^5))
        for (method, n, p, dense_p) in [
            (Method::Dop853, 8, 8.0, 7.0),
            (Method::Dopri5, 32, 5.0, 4.0),
        ] {
            let (e1, d1) = fixed_steps(method, n);
            let (e2, d2) = fixed_steps(method, 2 * n);
            let order = (e1 / e2).log2();
            assert!(
                (order - p).abs() < 0.6,
                "{method:?}: end-state order {order} ({e1:e}, {e2:e})"
            );
            let dense = (d1 / d2).log2();
            assert!(
                dense > dense_p + 0.5,
                "{method:?}: dense order {dense} ({d1:e}, {d2:e})"
            );
        }
    }

    #[test]
    fn adaptive_dop853_meets_its_tolerance_and_finds_events() {
        // (at 1e-6 the steps are long and the dense output's error inside them reaches 1.8e-5)
        for tol in [1e-8, 1e-10] {
            let out = integrate_by(
                Method::Dop853,
                &Exponentials,
                0.0,
                exact(0.0),
                2.0,
                tol,
                Mesh::Adaptive,
            )
            .unwrap();
            let end = (out.segment.y1 - exact(2.0)).amax();
            assert!(end < 10.0 * tol, "{tol}: {end:e}");
            for i in 0..=200 {
                let t = 0.01 * i as f64;
                let e = (out.segment.state(t) - exact(t)).amax();
                assert!(e < 10.0 * tol, "{tol}, t {t}: {e:e}");
            }
        }
        // the oscillator's first zero at π/2, by both methods
        for method in [Method::Dop853, Method::Dopri5] {
            let y0 = SVector::<f64, 2>::new(1.0, 0.0);
            let out =
                integrate_by(method, &Oscillator, 0.0, y0, 3.0, 1e-10, Mesh::Adaptive).unwrap();
            assert_eq!(out.event, Some(0));
            let err = (out.segment.t1 - std::f64::consts::FRAC_PI_2).abs();
            assert!(err < 1e-10, "{method:?}: {err:e}");
        }
    }

    #[test]
    fn a_trial_densified_later_has_the_same_dense_output() {
        let y0 = exact(0.0);
        let eager = integrate_by(
            Method::Dop853,
            &Exponentials,
            0.0,
            y0,
            2.0,
            1e-8,
            Mesh::Adaptive,
        )
        .unwrap();
        let mut lazy = integrate_trial(&Exponentials, 0.0, y0, 2.0, 1e-8, Mesh::Adaptive).unwrap();
        assert!(!lazy.segment.is_dense());
        let n = lazy.segment.steps.len() as u32;
        assert_eq!(lazy.evaluations + 3 * n, eager.evaluations);
        assert_eq!(lazy.segment.densify(|_| Exponentials), 3 * n);
        assert!(lazy.segment.is_dense());
        assert_eq!(lazy.segment.y1, eager.segment.y1);
        for i in 0..=40 {
            let t = 0.05 * i as f64;
            assert_eq!(lazy.segment.state(t), eager.segment.state(t), "t {t}");
        }
        // an event's step gets its dense output at once: the event is located on it
        let osc = integrate_trial(
            &Oscillator,
            0.0,
            SVector::<f64, 2>::new(1.0, 0.0),
            3.0,
            1e-10,
            Mesh::Adaptive,
        )
        .unwrap();
        assert!((osc.segment.t1 - std::f64::consts::FRAC_PI_2).abs() < 1e-10);
    }

    #[test]
    #[should_panic(expected = "densify")]
    fn a_trial_without_its_dense_output_is_not_read() {
        let out =
            integrate_trial(&Exponentials, 0.0, exact(0.0), 2.0, 1e-8, Mesh::Adaptive).unwrap();
        out.segment.state(1.0);
    }
}
