//! Stance control (KLAW 1989 §4.2, spec §4): the forces of the telescopic stance model — the leg
//! torque step τ1, the upper-body balance torque, the leg axis force with its position actuator
//! pa — the telescopic / locked subphases, and one trial integration of a step's stance.
use nalgebra::{SVector, Vector2, Vector3};
use std::f64::consts::PI;

use crate::dynamics::StanceModel;
use crate::dynamics::impact;
use crate::kinematics::pelvis::Determinants;
use crate::numerics::ode::{self, Phase, Segment};
use crate::numerics::roots;
use crate::numerics::trig::sin_cos;

/// State (w, θ1, θ2, ẇ, θ̇1, θ̇2).
pub type StanceState = SVector<f64, 6>;

/// Fraction of the step after which the leg torque τ1 is switched off (paper: EMG shows the
/// hip-extensor push only early in stance).
pub const TORQUE_OFF: f64 = 0.4;
/// A trial stops when |θ1| exceeds this (rad): the residual of a wild guess (spec §4).
pub const THETA1_ABORT: f64 = PI / 3.0;

/// Everything about one step's stance that does not change between shooting trials.
#[derive(Clone, Copy, Debug)]
pub struct StanceSetup {
    pub model: StanceModel,
    /// Leg length l1 (m).
    pub l1: f64,
    /// Leg axis spring and damper (N/m, N s/m).
    pub k_w: f64,
    pub d_w: f64,
    /// Balance spring and damper (N m/rad, N m s/rad) and the forward-lean reference (rad).
    pub k_2: f64,
    pub d_2: f64,
    pub theta2_ref: f64,
    pub t_step: f64,
    /// |θ1| at the start of the step (the previous step's θ1*) and θ1* at its end.
    pub theta1_start: f64,
    pub theta1_end: f64,
    /// w* at the end of the step.
    pub w_end: f64,
    /// Hip heights at the two heel strikes (m).
    pub y_start: f64,
    pub y_end: f64,
    /// Bounce e of the hip reference (m).
    pub bounce: f64,
    /// The virtual leg's reference from mid-stance on.
    pub terminal: TerminalStance,
}

/// The hip height reference and its derivative with respect to θ1 [ours]:
/// - up to mid-stance (θ1 < 0), spec §4: y_ref = ȳ(u) + e cos²(πu/2), u = sin θ1 / sin θ1^−
///   clipped to [−1, 1], ȳ blending the two heel-strike heights with a half-sine (ȳ = y_hs in a
///   steady gait): the bounce e = ε·E gives the loading response;
/// - from mid-stance (θ1 ≥ 0), spec §7 "replace y_ref": the pelvis centre where the virtual leg
///   puts it with its knee held at the mid-stance value, l9 + W(θ1) cos θ1 ([`TerminalStance`]).
pub fn hip_reference(s: &StanceSetup, theta1: f64) -> (f64, f64) {
    let (s1, c1) = sin_cos(theta1);
    hip_reference_sc(s, s1, c1, 1.0 / s.theta1_start.sin(), theta1 >= 0.0)
}

/// [`hip_reference`] from sin θ1, cos θ1 and the reciprocal of the bounce's denominator
/// sin θ1^− (start), on the side of mid-stance `terminal` says (each side's formula continues
/// smoothly past θ1 = 0, so that an integration segment ending there sees its own side's
/// reference): one
/// `sin_cos` of πu/2 for the bounce, since 1 + cos πu = 2 cos²(πu/2) and
/// sin πu = 2 sin(πu/2) cos(πu/2).
#[inline(always)]
fn hip_reference_sc(
    s: &StanceSetup,
    s1: f64,
    c1: f64,
    inv_sin_start: f64,
    terminal: bool,
) -> (f64, f64) {
    if terminal {
        let (w, dw) = s.terminal.length(s1, c1);
        return (s.model.l9 + w * c1, dw * c1 - w * s1);
    }
    let raw = s1 * inv_sin_start;
    let (u, du) = if raw.abs() >= 1.0 {
        (raw.signum(), 0.0)
    } else {
        (raw, c1 * inv_sin_start)
    };
    let (sh, ch) = sin_cos(0.5 * PI * u);
    let dy = s.y_end - s.y_start;
    let base = s.y_start + dy * 0.5 * (1.0 + sh);
    let dbase = dy * 0.25 * PI * ch;
    let bump = s.bounce * ch * ch;
    let dbump = -s.bounce * PI * sh * ch;
    (base + bump, (dbase + dbump) * du)
}

/// The virtual stance leg from mid-stance to heel strike (spec §7), as the telescopic leg's
/// length W(θ1) from the pivot P (the flat foot's ankle) to the pelvis centre C [ours]. The knee
/// stays at its mid-stance flexion κ0, so the stance hip joint J is the leg's mid-stance reach
/// a0 from the ankle A in space, and √(a0² − dz²) in the leg's plane (dz: the lateral offset):
/// - foot flat (A = P) while the ankle's dorsiflexion, the lean of the shank (the ankle–J line's
///   angle plus the shank's lead δ over it at κ0), is below θ5_max;
/// - heel-off: the foot turns about its metatarsal joint M by the pitch
///   p = p_hs s⁴ (1 + c (s − 1)), s = (sin θ1 − sin θ_ho) / (sin θ1* − sin θ_ho), so that the
///   reference is C³ at heel-off (the swing reads the hip's acceleration from a quintic table,
///   [`HipPath`], which a C² reference's jerk kink pushed to 1.6e-5 m/s², over its 5e-6 bound)
///   and the heel rises ever faster into push-off; p_hs puts C at (θ1*, w*) at
///   heel strike and c ∈ [−4, 1] makes C arrive there level (as the spec §4 reference did, so
///   that the hip does not dip below y_hs before it), or as nearly as a monotone pitch allows.
///
/// The pelvis moves J from C by o(u) = (−(l0/2) sin(A sin(πu/2)), (l0/2) sin(L cos(πu/2))) and
/// dz(u) = D cos(πu/2) + l0/2 − b/2 (rotation A, list L, lateral displacement D, step width b;
/// u = sin θ1 / sin θ1* stands for the step's time, and cos L cos R ≈ 1 in dz: ≤ 0.4 mm), so
/// C lies on the circle of radius √(a0² − dz²) about A − o:
/// W = e·(A − o) + √((e·(A − o))² − |A − o|² + a0² − dz²), e = (sin θ1, cos θ1).
/// Heel-off comes no later than at 0.7 sin θ1*, since the heel must rise before heel strike
/// (w* > l1). A reference: `kinematics::stance_leg` is the exact figure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TerminalStance {
    /// a0: hip joint to ankle with the knee at κ0 (m).
    pub reach: f64,
    /// M relative to the pivot (m).
    pub meta: [f64; 2],
    /// Foot pitch at heel strike p_hs (rad), and c of the pitch's shape
    /// s⁴ (1 + c (s − 1)), c ∈ [−4, 1] (monotone, ≥ 0; end rate 4 + c).
    pub pitch_end: f64,
    pub end_rate: f64,
    /// sin θ_ho, sin θ1*.
    pub sin_heel_off: f64,
    pub sin_end: f64,
    /// The determinants of gait (with the step's list), which move the hip joint.
    pub pelvis: Determinants,
    /// W as a function of sin θ1 in Chebyshev series, on [0, sin θ_ho] (foot flat) and from
    /// there to where the pitch is held ([`PAST_END`]): what [`Self::length`] evaluates.
    table: [Chebyshev; 2],
}

/// Coefficients of each piece of [`TerminalStance`]'s table of W.
const TABLE_TERMS: usize = 20;

/// A function on [lo, hi] interpolated at the Chebyshev nodes: the series Σ′ c_j T_j(y),
/// y = (2x − lo − hi)/(hi − lo) (the first term halved; Press et al., *Numerical Recipes*, §5.8:
/// `chebft`), kept as the polynomial Σ a_k y^k (§5.10: `chebpc`) and its derivative's
/// Σ (k + 1) a_{k+1} y^k, each evaluated by Estrin's scheme (Knuth, *TAOCP* vol. 2, §4.6.4):
/// one multiply-add a term like Horner's rule, where Clenshaw's recurrence on the series and its
/// derivative's takes three a term for each, but in a tree five multiply-adds deep instead of a
/// chain of twenty: the stance right-hand side waits for W, and with Horner's chain the hip
/// reference took 9.3 % of the default walk's time (`perf record` of `klaw bench --frames`).
/// The power form is accurate here because the coefficients fall fast (to 1e-12 of W by the
/// 20th): the large coefficients of T_j's high powers multiply small c_j.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Chebyshev {
    lo: f64,
    hi: f64,
    /// y = (x − mid) · scale: the interval's midpoint and 2 / (hi − lo), kept so that an
    /// evaluation divides nothing.
    mid: f64,
    scale: f64,
    a: [f64; TABLE_TERMS],
    /// The derivative's coefficients (in y), (k + 1) a_{k+1}; the last is 0.
    da: [f64; TABLE_TERMS],
}

/// Σ a_k y^k by Estrin's scheme: pairs a_{2i} + a_{2i+1} y, then pairs of those with y², y⁴,
/// y⁸, y¹⁶ (twenty terms).
#[inline(always)]
fn estrin(a: &[f64; TABLE_TERMS], y: f64) -> f64 {
    const _: () = assert!(TABLE_TERMS == 20);
    let y2 = y * y;
    let y4 = y2 * y2;
    let y8 = y4 * y4;
    let p: [f64; 10] = std::array::from_fn(|i| a[2 * i] + a[2 * i + 1] * y);
    let q: [f64; 5] = std::array::from_fn(|i| p[2 * i] + p[2 * i + 1] * y2);
    let r = [q[0] + q[1] * y4, q[2] + q[3] * y4];
    (r[0] + r[1] * y8) + q[4] * (y8 * y8)
}

impl Chebyshev {
    /// The zero function on [0, 1].
    const ZERO: Chebyshev = Chebyshev {
        lo: 0.0,
        hi: 1.0,
        mid: 0.5,
        scale: 2.0,
        a: [0.0; TABLE_TERMS],
        da: [0.0; TABLE_TERMS],
    };

    /// The series interpolating `f` at the TABLE_TERMS Chebyshev nodes of [lo, hi].
    fn fit(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Self {
        const N: usize = TABLE_TERMS;
        let (mid, half) = (0.5 * (hi + lo), 0.5 * (hi - lo));
        // c_j = (2/N) Σ_k f(x_k) T_j(y_k), y_k = cos(π (k + ½)/N), T_j by its recurrence
        let mut c = [0.0; N];
        for k in 0..N {
            let y = (PI * (k as f64 + 0.5) / N as f64).cos();
            let f = 2.0 / N as f64 * f(mid + half * y);
            let (mut t0, mut t1) = (1.0, y);
            for cj in c.iter_mut() {
                *cj += f * t0;
                (t0, t1) = (t1, 2.0 * y * t1 - t0);
            }
        }
        c[0] *= 0.5;
        // Σ c_j T_j as powers of y: the coefficients of T_j and T_{j+1}, by the same recurrence
        let mut a = [0.0; N];
        let (mut t0, mut t1) = ([0.0; N], [0.0; N]);
        (t0[0], t1[1]) = (1.0, 1.0);
        for &cj in &c {
            a.iter_mut().zip(&t0).for_each(|(ak, tk)| *ak += cj * tk);
            let next = std::array::from_fn(|k| if k > 0 { 2.0 * t1[k - 1] } else { 0.0 } - t0[k]);
            (t0, t1) = (t1, next);
        }
        let da = std::array::from_fn(|k| {
            if k + 1 < N {
                (k + 1) as f64 * a[k + 1]
            } else {
                0.0
            }
        });
        Chebyshev {
            lo,
            hi,
            mid,
            scale: 1.0 / half,
            a,
            da,
        }
    }

    /// f(x) and f′(x) ([`estrin`]).
    #[inline]
    fn eval(&self, x: f64) -> (f64, f64) {
        let y = (x - self.mid) * self.scale;
        (estrin(&self.a, y), estrin(&self.da, y) * self.scale)
    }
}

/// m of the margin m (1 − x)² above y_hs that the reference keeps between heel-off (x = 0) and
/// heel strike (x = 1) (m) [ours]: with less (2 mm, 5 mm) the tracking hip dipped 1–3 µm under
/// y_hs just before heel strike in slow walks of tall bodies (0.6–0.8 m/s, H 1.95 m).
pub const END_MARGIN: f64 = 1e-2;

/// sin x and cos x by their Taylor polynomials to x⁵ and x⁶, for the pelvis's angles (|x| ≤ 0.2
/// rad: errors ≤ x⁷/5040 = 2.5e-9 and x⁸/40320 = 6e-11): the reference's hip joint offsets,
/// evaluated at every stance right-hand side, at a fifth of the cost of `sin_cos`.
fn small_sin_cos(x: f64) -> (f64, f64) {
    let x2 = x * x;
    (
        x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0)),
        1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0)),
    )
}

/// How far past heel strike (in s and u, where heel strike is 1) the pitch and the pelvis's
/// offsets continue their formulas before they are held [ours]: held at heel strike itself, the
/// reference's slope jumps where every converged trial ends, and the integrator's last steps
/// straddling that kink shrank geometrically (14 steps of < 0.1 ms at the end of each stance
/// trial of the default walk). Not far: at 2 m/s the leg no longer reaches the hip at 1.5.
const PAST_END: f64 = 1.1;

/// Points between heel-off and heel strike at which [`TerminalStance::new`] checks that the
/// reference stays above its heel-strike height.
const HEEL_RISE_CHECKS: usize = 32;

impl TerminalStance {
    /// `y_mid`: the pelvis centre's reference height at mid-stance; `det`: the determinants
    /// (with the step's list); `end`: θ1* and w*; `(l3, l4, l9, h12)`: thigh, shank, ankle
    /// height and ankle to M (foot flat); `theta5_max`: the heel-off dorsiflexion.
    pub fn new(
        y_mid: f64,
        det: &Determinants,
        (theta1_end, w_end): (f64, f64),
        (l3, l4, l9, h12): (f64, f64, f64, f64),
        theta5_max: f64,
    ) -> Self {
        let h = det.half_width;
        let lateral_hs = h - det.half_step_width;
        let w0 = y_mid + h * det.list.sin() - l9;
        let reach = w0.hypot(lateral_hs + det.lateral).min(l3 + l4);
        let cos_knee = ((reach * reach - l3 * l3 - l4 * l4) / (2.0 * l3 * l4)).clamp(-1.0, 1.0);
        let delta = (l3 * cos_knee.acos().sin() / reach).asin();
        let sin_end = theta1_end.sin();
        let mut t = TerminalStance {
            reach,
            meta: [h12, -l9],
            pitch_end: 0.0,
            end_rate: 0.0,
            sin_heel_off: 0.7 * sin_end,
            sin_end,
            pelvis: *det,
            table: [Chebyshev::ZERO; 2],
        };
        // heel-off: the flat foot's ankle–J line reaches θ5_max − δ (rising with θ1)
        let line = |s1: f64| {
            let (w, _) = t.exact_length_at(s1);
            let ([o, _], _) = t.offset(s1 / sin_end);
            (w * s1 + o[0]).atan2(w * (1.0 - s1 * s1).sqrt() + o[1])
        };
        let rise = |s1: f64| line(s1) - (theta5_max - delta);
        let late = rise(t.sin_heel_off);
        if late > 0.0 {
            let early = rise(0.0);
            t.sin_heel_off = if early < 0.0 {
                let (lo, hi) =
                    roots::illinois(rise, (0.0, early), (t.sin_heel_off, late), 1e-15, 60);
                0.5 * (lo + hi)
            } else {
                0.0
            };
        }
        // the heel rises earlier (by tenths of the way back to mid-stance) while the reference
        // would dip below its heel-strike height before heel strike: slow, short steps, where
        // the flat foot's arc falls below y_hs before the ankle reaches θ5_max
        let y_end = w_end * theta1_end.cos();
        for _ in 0..10 {
            t.fit_end(w_end);
            let dips = (1..HEEL_RISE_CHECKS).any(|k| {
                let x = k as f64 / HEEL_RISE_CHECKS as f64;
                let s1 = t.sin_heel_off + (sin_end - t.sin_heel_off) * x;
                t.exact_length_at(s1).0 * (1.0 - s1 * s1).sqrt()
                    < y_end + END_MARGIN * (1.0 - x).powi(2)
            });
            if !dips {
                break;
            }
            t.sin_heel_off *= 0.9;
        }
        // the flat foot's W on at least a tenth of the way to heel strike (heel-off can come at
        // mid-stance), the rising heel's up to where its pitch is held
        let flat = TerminalStance {
            pitch_end: 0.0,
            ..t
        };
        let held = t.sin_heel_off + PAST_END * (sin_end - t.sin_heel_off);
        t.table = [
            Chebyshev::fit(
                |s1| flat.exact_length_at(s1).0,
                0.0,
                t.sin_heel_off.max(0.1 * sin_end),
            ),
            Chebyshev::fit(|s1| t.exact_length_at(s1).0, t.sin_heel_off, held),
        ];
        t
    }

    /// p_hs so that W(θ1*) = w* (W rises with p: the ankle rises towards the hip), then c so
    /// that the hip arrives level, dy/dθ1 = W' cos θ1* − W sin θ1* = 0, where a monotone pitch
    /// allows (dW/dθ1 at the end is linear in the pitch's end rate 4 + c). A falling arrival
    /// (10 % of the rigid leg's rate, tried) let the tracking hip dip 7e-5 m under y_hs at
    /// 0.6 m/s.
    fn fit_end(&mut self, w_end: f64) {
        let sin_end = self.sin_end;
        let short = |p: f64| {
            let t = TerminalStance {
                pitch_end: p,
                ..*self
            };
            t.exact_length_at(sin_end).0 - w_end
        };
        // on [0, 1.2] rad, its end where W stays on one side of w*
        let (lo, hi) = (short(0.0), short(1.2));
        self.pitch_end = if lo >= 0.0 {
            0.0
        } else if hi < 0.0 {
            1.2
        } else {
            let (a, b) = roots::illinois(short, (0.0, lo), (1.2, hi), 1e-13, 60);
            0.5 * (a + b)
        };
        let slope = |c: f64| {
            let t = TerminalStance {
                end_rate: c,
                ..*self
            };
            let (w, dw) = t.exact_length_at(sin_end);
            dw - w * sin_end / (1.0 - sin_end * sin_end).sqrt()
        };
        let (lo, hi) = (slope(-4.0), slope(1.0));
        self.end_rate = if hi != lo {
            (-4.0 + 5.0 * lo / (lo - hi)).clamp(-4.0, 1.0)
        } else {
            0.0
        };
    }

    /// The ankle A(p) (relative to P) and dA/dp: P turned about M by −p (heel up).
    fn ankle(&self, p: f64) -> ([f64; 2], [f64; 2]) {
        let [mx, my] = self.meta;
        let (sp, cp) = sin_cos(p);
        // P − M = (−mx, −my), turned clockwise by p
        let (dx, dy) = (-mx * cp - my * sp, mx * sp - my * cp);
        ([mx + dx, my + dy], [mx * sp - my * cp, mx * cp + my * sp])
    }

    /// J − C = o(u) and the lateral offset dz(u), with their derivatives in u.
    fn offset(&self, u: f64) -> ([[f64; 2]; 2], [f64; 2]) {
        let (sh, ch) = sin_cos(0.5 * PI * u);
        let d = &self.pelvis;
        let h = d.half_width;
        let (sr, cr) = small_sin_cos(d.rotation * sh);
        let (sl, cl) = small_sin_cos(d.list * ch);
        let k = 0.5 * PI;
        (
            [
                [-h * sr, h * sl],
                [-h * cr * d.rotation * k * ch, -h * cl * d.list * k * sh],
            ],
            [h - d.half_step_width + d.lateral * ch, -d.lateral * k * sh],
        )
    }

    /// [`Self::exact_length`] from sin θ1 alone.
    fn exact_length_at(&self, s1: f64) -> (f64, f64) {
        self.exact_length(s1, (1.0 - s1 * s1).sqrt())
    }

    /// W(θ1) and dW/dθ1 from sin θ1, cos θ1, from the table: W(sin θ1) is smooth on each piece
    /// (the pelvis's sines, the foot's rotation and a square root), and 20 Chebyshev terms meet
    /// [`Self::exact_length`] to ≤ 2e-12 m and dW/dθ1 to ≤ 2.2e-9 m/rad (0.6–2.0 m/s, tested),
    /// by two Estrin sums of 20 terms instead of ≈ 300 instructions (the stance right-hand side
    /// evaluates it about a thousand times a step). Outside the table (θ1 < 0, or the pitch held), the
    /// formula itself.
    pub fn length(&self, s1: f64, c1: f64) -> (f64, f64) {
        let [flat, heel_off] = &self.table;
        let piece = if s1 < flat.lo || s1 > heel_off.hi {
            return self.exact_length(s1, c1);
        } else if s1 < heel_off.lo {
            flat
        } else {
            heel_off
        };
        let (w, dw) = piece.eval(s1);
        (w, dw * c1)
    }

    /// W(θ1) and dW/dθ1 from sin θ1, cos θ1 (θ1 ≥ 0), by the formula above.
    pub fn exact_length(&self, s1: f64, c1: f64) -> (f64, f64) {
        let span = self.sin_end - self.sin_heel_off;
        let s = ((s1 - self.sin_heel_off) / span).min(PAST_END);
        let c = self.end_rate;
        let (p, dp) = if s <= 0.0 {
            (0.0, 0.0)
        } else {
            let rate = if s < PAST_END {
                self.pitch_end * s * s * s * (4.0 + c * (5.0 * s - 4.0)) * c1 / span
            } else {
                0.0
            };
            (self.pitch_end * s * s * s * s * (1.0 + c * (s - 1.0)), rate)
        };
        // flat foot: the ankle is the pivot
        let (ankle, dankle) = if p == 0.0 {
            ([0.0; 2], [0.0; 2])
        } else {
            self.ankle(p)
        };
        let u = (s1 / self.sin_end).min(PAST_END);
        let du = if u < PAST_END { c1 / self.sin_end } else { 0.0 };
        let ([o, o_u], [dz, dz_u]) = self.offset(u);
        // the circle's centre A − o and radius² a0² − dz², with their θ1-derivatives
        let a = [ankle[0] - o[0], ankle[1] - o[1]];
        let da = [dankle[0] * dp - o_u[0] * du, dankle[1] * dp - o_u[1] * du];
        let r2 = self.reach * self.reach - dz * dz;
        let dr2 = -2.0 * dz * dz_u * du;
        // W² − 2W (e·a) + |a|² − r² = 0, the larger root
        let ea = s1 * a[0] + c1 * a[1];
        let aa = a[0] * a[0] + a[1] * a[1];
        let w = ea + (ea * ea - aa + r2).max(0.0).sqrt();
        // implicitly: W' (W − e·a) = W (e'·a + e·a') − a·a' + (r²)'/2, e' = (cos θ1, −sin θ1)
        let e1a = c1 * a[0] - s1 * a[1];
        let eda = s1 * da[0] + c1 * da[1];
        let ada = a[0] * da[0] + a[1] * da[1];
        (w, (w * (e1a + eda) - ada + 0.5 * dr2) / (w - ea))
    }
}

/// smoothstep(x) = 3x² − 2x³ on [0, 1], clamped.
pub fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// Clamp events (the leg force reaching or leaving 0) located per stance trial; after them the
/// clamp's kink is left to the step-size control.
const CLAMP_EVENTS: usize = 8;

/// One stance trial: the unknown magnitudes (τ1, p) and the subphase.
#[derive(Clone, Copy, Debug)]
pub struct StanceForces<'a> {
    pub setup: &'a StanceSetup,
    /// Leg torque magnitude τ1 (N m), on for t < 0.4 t_step.
    pub tau1: f64,
    /// Leg extension p (m) of the position actuator, blended in over the second half-step.
    pub p: f64,
    pub locked: bool,
    /// In an integration segment: whether it runs after mid-stance (event 4 has fired), which
    /// picks the hip reference's side; `None`: by the sign of θ1, and no mid-stance event.
    pub past_mid: Option<bool>,
    /// The leg torque on or off whatever t ([`Self::with_torque`]); `None`: on for
    /// t < 0.4 t_step.
    torque: Option<bool>,
    /// Which side of its clamp at 0 the leg force F_w starts on in this integration segment
    /// ([`Self::with_loaded`]; the clamp event fires when it leaves it); `None`: no clamp event.
    loaded: Option<bool>,
    /// 1 / sin θ1^− of the hip reference's bounce (a constant of the step).
    inv_sin_start: f64,
}

impl<'a> StanceForces<'a> {
    pub fn new(setup: &'a StanceSetup, tau1: f64, p: f64, locked: bool) -> Self {
        StanceForces {
            setup,
            tau1,
            p,
            locked,
            past_mid: None,
            torque: None,
            loaded: None,
            inv_sin_start: 1.0 / setup.theta1_start.sin(),
        }
    }

    /// The same forces with the leg torque on (or off) at every t: an integration segment lies
    /// on one side of the switch at 0.4 t_step, and the stages at its end, t = 0.4 t_step, must
    /// see the segment's torque (its limit from inside), not the value past the switch (the
    /// step then failed its error test, down to 1e-5 s steps, and kept a 1e-7 error).
    pub fn with_torque(mut self, on: bool) -> Self {
        self.torque = Some(on);
        self
    }

    /// The same forces in an integration segment that starts with the leg force F_w positive
    /// (`loaded`) or clamped at 0: F_w is that side's (the servo's force, or 0) throughout, and
    /// the clamp event (event 3) fires where the servo's force changes sign, so that no
    /// integrator step straddles the clamp's kink (after the heel strike the unloaded leg's
    /// servo pulls, and F_w is 0 for the first ≈ 60 ms). The step in which the event fires
    /// continues that side's force smoothly past the crossing, where the event is located.
    pub fn with_loaded(mut self, loaded: bool) -> Self {
        self.loaded = Some(loaded);
        self
    }

    /// The leg force F_w at (t, y) before its clamp at 0 (telescopic subphase).
    pub fn leg_force(&self, t: f64, y: &StanceState) -> f64 {
        let (s1, c1) = sin_cos(y[1]);
        self.leg_force_sc(t, y, s1, c1)
    }

    /// [`Self::leg_force`] with sin θ1, cos θ1 known.
    #[inline(always)]
    fn leg_force_sc(&self, t: f64, y: &StanceState, s1: f64, c1: f64) -> f64 {
        let s = self.setup;
        let (w, wd, th1d) = (y[0], y[3], y[4]);
        // pa = w_ref − l1 + (m2 g cos θ1 + d_w ẇ_ref)/k_w + p s(t), F_w = k_w (l1 + pa − w) − d_w ẇ ≥ 0
        let terminal = self.past_mid.unwrap_or(s1 >= 0.0);
        let (y_ref, dy_ref) = hip_reference_sc(s, s1, c1, self.inv_sin_start, terminal);
        // w_ref = (y_ref − l9) / cos θ1, dw_ref/dθ1 = (dy_ref + w_ref sin θ1) / cos θ1
        let inv_c1 = 1.0 / c1;
        let w_ref = (y_ref - s.model.l9) * inv_c1;
        let dw_ref = (dy_ref + w_ref * s1) * inv_c1;
        let wd_ref = dw_ref * th1d;
        let blend = smoothstep((t - 0.5 * s.t_step) / (0.5 * s.t_step));
        s.k_w * (w_ref - w + self.p * blend) + s.model.m2 * s.model.g * c1 + s.d_w * (wd_ref - wd)
    }

    /// Generalized forces Q = (F_w, F_θ1 − F_θ2, F_θ2) at (t, y).
    pub fn generalized(&self, t: f64, y: &StanceState) -> Vector3<f64> {
        let (s1, c1) = sin_cos(y[1]);
        self.generalized_sc(t, y, s1, c1)
    }

    /// [`Self::generalized`] with sin θ1, cos θ1 known.
    #[inline(always)]
    fn generalized_sc(&self, t: f64, y: &StanceState, s1: f64, c1: f64) -> Vector3<f64> {
        let s = self.setup;
        let (th2, th2d) = (y[2], y[5]);
        let f2 = -s.k_2 * (th2 - s.theta2_ref) - s.d_2 * th2d;
        let f1 = if self.torque.unwrap_or(t < TORQUE_OFF * s.t_step) {
            self.tau1
        } else {
            0.0
        };
        // in a segment on one side of the clamp, that side's force continued smoothly past the
        // crossing (the integrator's steps see no kink; the event ends the segment there)
        let fw = match (self.locked, self.loaded) {
            (true, _) | (false, Some(false)) => 0.0,
            (false, Some(true)) => self.leg_force_sc(t, y, s1, c1),
            (false, None) => self.leg_force_sc(t, y, s1, c1).max(0.0),
        };
        Vector3::new(fw, f1 - f2, f2)
    }

    /// q̈ at (t, y).
    pub fn accelerations(&self, t: f64, y: &StanceState) -> Vector3<f64> {
        let q = Vector3::new(y[0], y[1], y[2]);
        let qd = Vector3::new(y[3], y[4], y[5]);
        let (s1, c1) = sin_cos(y[1]);
        self.setup.model.accelerations_with(
            s1,
            c1,
            &q,
            &qd,
            &self.generalized_sc(t, y, s1, c1),
            self.locked,
        )
    }
}

/// Events: 0 lock / release, 1 |θ1| too large, 2 leg collapsed, 3 the leg force's clamp engages
/// or lets go ([`StanceForces::with_loaded`]), 4 mid-stance (θ1 rising through 0, where the hip
/// reference changes from the bounce to the virtual leg and its curvature jumps: the
/// integration and the hip table break there).
impl Phase<6, 5> for StanceForces<'_> {
    fn rhs(&self, t: f64, y: &StanceState) -> StanceState {
        let a = self.accelerations(t, y);
        StanceState::from([y[3], y[4], y[5], a[0], a[1], a[2]])
    }

    fn events(&self, t: f64, y: &StanceState) -> [f64; 5] {
        let (w, th1) = (y[0], y[1]);
        let switch = if self.locked {
            -th1 // release when the leg passes the vertical
        } else if th1 < 0.0 {
            self.setup.l1 - w // lock when w crosses l1 upward while θ1 < 0
        } else {
            1.0
        };
        let clamp = match (self.locked, self.loaded) {
            (false, Some(true)) => self.leg_force(t, y),
            (false, Some(false)) => -self.leg_force(t, y),
            _ => 1.0,
        };
        let mid = if !self.locked && self.past_mid == Some(false) {
            -th1
        } else {
            1.0
        };
        [
            switch,
            THETA1_ABORT - th1.abs(),
            w - 0.5 * self.setup.l1,
            clamp,
            mid,
        ]
    }
}

/// The dense record of one stance trial.
#[derive(Clone, Debug)]
pub struct StanceRun {
    pub tau1: f64,
    pub p: f64,
    /// Integration segments with their subphase (`true` = locked leg).
    pub segments: Vec<(Segment<6>, bool)>,
    /// The trial stopped early (|θ1| > 60° or w < l1/2).
    pub aborted: bool,
    /// End-condition residual (θ1 − θ1*, w − w*) at the end (or where it stopped).
    pub residual: Vector2<f64>,
    /// Right-hand-side evaluations spent.
    pub evaluations: u32,
    /// Some integration step was chosen by the step-size control (no mesh was followed
    /// throughout).
    pub adapted: bool,
}

/// The hip's acceleration over an interval, tabulated on a uniform grid from the stance run
/// and interpolated by the quintic through the six nearest grid points (Lagrange; at the ends of
/// a piece the six are shifted inside it): the swing's right-hand side reads the moving hip
/// here instead of re-evaluating the stance dynamics at every stage (spec §5: the swing uses
/// the hip of the same step's stance). The table is split wherever the stance run has a segment
/// boundary — the leg torque switching off, the position actuator's blend starting, the leg
/// locking or releasing, the leg force's clamp — since the acceleration or its derivative jumps
/// there. The swing integrations stop at the same
/// [`HipPath::breaks`], so no integrator step straddles a jump (measured: stepping across the
/// torque switch-off left a 2e-7 global error in swing1 at a 1e-10 tolerance).
/// Grid ≤ 4 ms: measured 7e-7 m/s² (2 ms: 1.4e-7; the cubic through four points every 1 ms,
/// before: 7e-6, with 4 times the table's points). A kinematic offset of the swing-side hip
/// joint from the dynamic hip (the determinants of gait, spec §7) adds its acceleration, by
/// central second differences (step 1e-4 s: truncation ≈ h² f⁗ / 12 ≈ 1e-8 m/s²).
#[derive(Clone, Debug)]
pub struct HipPath {
    pieces: Vec<Piece>,
}

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

/// Largest grid step of [`HipPath`] (s).
pub const HIP_PATH_STEP: f64 = 4e-3;

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
        Self::with_offset_acceleration(run, setup, t0, t1, offset, &|_| None)
    }

    /// [`Self::new`] with the offset's acceleration where `offset_acceleration(t)` gives it (in
    /// closed form); elsewhere the offset is differenced as in [`Self::new`].
    pub fn with_offset_acceleration(
        run: &StanceRun,
        setup: &StanceSetup,
        t0: f64,
        t1: f64,
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
        cuts.push(t1);
        // the ends of a piece are its inner limits (the state or the forces jump at a cut)
        let eps = 1e-12 * setup.t_step;
        let pieces = cuts
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let n = ((b - a) / HIP_PATH_STEP).ceil().max(5.0) as usize;
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

impl StanceRun {
    /// One trial integration of the stance from `y0` over [0, t_step] with magnitudes (τ1, p).
    pub fn simulate(
        setup: &StanceSetup,
        y0: StanceState,
        tau1: f64,
        p: f64,
    ) -> Result<Self, String> {
        Self::simulate_with(setup, y0, tau1, p, ode::TOLERANCE)
    }

    /// [`Self::simulate`] at integrator tolerance `tol` (to measure the integration error).
    pub fn simulate_with(
        setup: &StanceSetup,
        y0: StanceState,
        tau1: f64,
        p: f64,
        tol: f64,
    ) -> Result<Self, String> {
        let mut run = Self::simulate_on(setup, y0, tau1, p, tol, None)?;
        run.evaluations += run.densify(setup);
        Ok(run)
    }

    /// [`Self::simulate_with`] on the step sequences of `mesh`, a previous trial of the same
    /// stance ([`ode::integrate_on`]): its i-th segment's steps for the i-th segment (from the
    /// same start time, or shifted when the segment starts at an event), when the subphases
    /// agree. The dense output is left out ([`ode::integrate_trial`]): [`Self::densify`] the
    /// trial that is kept.
    pub fn simulate_on(
        setup: &StanceSetup,
        y0: StanceState,
        tau1: f64,
        p: f64,
        tol: f64,
        mesh: Option<&StanceRun>,
    ) -> Result<Self, String> {
        let breaks = [TORQUE_OFF * setup.t_step, 0.5 * setup.t_step, setup.t_step];
        let mut run = StanceRun {
            tau1,
            p,
            // (five in a typical stance: the clamp, the torque's end, the blend, mid-stance)
            segments: Vec::with_capacity(8),
            aborted: false,
            residual: Vector2::zeros(),
            evaluations: 0,
            adapted: false,
        };
        let (mut t, mut y, mut locked, mut past_mid) = (0.0, y0, false, false);
        // the leg force's side of its clamp after a clamp event (else its sign where a segment
        // starts), and the clamp events so far: past CLAMP_EVENTS (a force grazing 0) the kink
        // is left to the step-size control
        let (mut flipped, mut clamp_events) = (None, 0);
        'outer: for t_break in breaks {
            while t < t_break {
                let forces = StanceForces {
                    past_mid: Some(past_mid),
                    ..StanceForces::new(setup, tau1, p, locked)
                }
                .with_torque(t < TORQUE_OFF * setup.t_step);
                let loaded = flipped
                    .take()
                    .unwrap_or_else(|| forces.leg_force(t, &y) > 0.0);
                let forces = if clamp_events < CLAMP_EVENTS {
                    forces.with_loaded(loaded)
                } else {
                    forces
                };
                let follow = match mesh.and_then(|m| m.segments.get(run.segments.len())) {
                    Some((seg, l)) if *l == locked && seg.t0 == t => ode::Mesh::Aligned(seg),
                    Some((seg, l)) if *l == locked => ode::Mesh::Shifted(seg),
                    _ => ode::Mesh::Adaptive,
                };
                let out = ode::integrate_trial(&forces, t, y, t_break, tol, follow)?;
                run.evaluations += out.evaluations;
                run.adapted |= out.adapted;
                t = out.segment.t1;
                y = out.segment.y1;
                run.segments.push((out.segment, locked));
                match out.event {
                    None => {}
                    Some(0) if locked => (locked, past_mid) = (false, true),
                    Some(3) => {
                        flipped = Some(!loaded);
                        clamp_events += 1;
                    }
                    Some(4) => past_mid = true,
                    Some(0) => {
                        // the knee locks: a plastic impulse along the leg stops ẇ
                        let q = Vector3::new(y[0], y[1], y[2]);
                        let (qd, _) =
                            impact::heel_strike(&setup.model, &q, &Vector3::new(y[3], y[4], y[5]));
                        y = StanceState::from([y[0], y[1], y[2], 0.0, qd[1], qd[2]]);
                        locked = true;
                    }
                    Some(_) => {
                        run.aborted = true;
                        break 'outer;
                    }
                }
            }
        }
        run.residual = Vector2::new(y[1] - setup.theta1_end, y[0] - setup.w_end);
        Ok(run)
    }

    /// Complete the dense output of a [`Self::simulate_on`] trial ([`ode::Segment::densify`]);
    /// returns the right-hand-side evaluations.
    pub fn densify(&mut self, setup: &StanceSetup) -> u32 {
        let (tau1, p, t_off) = (self.tau1, self.p, TORQUE_OFF * setup.t_step);
        self.segments
            .iter_mut()
            .map(|(seg, locked)| {
                let forces = StanceForces::new(setup, tau1, p, *locked).with_torque(seg.t0 < t_off);
                seg.densify(|_| forces)
            })
            .sum()
    }

    /// End time of the record (t_step unless aborted).
    pub fn t_end(&self) -> f64 {
        self.segments.last().map_or(0.0, |(s, _)| s.t1)
    }

    /// The state and subphase at time t.
    pub fn state(&self, t: f64) -> (StanceState, bool) {
        let i = self
            .segments
            .partition_point(|(s, _)| s.t1 < t)
            .min(self.segments.len() - 1);
        let (seg, locked) = &self.segments[i];
        (seg.state(t), *locked)
    }

    /// Hip position at t (relative to the stance ankle's x): [`Self::hip`]`[0]` without the
    /// dynamics.
    pub fn hip_position(&self, setup: &StanceSetup, t: f64) -> [f64; 2] {
        let (y, _) = self.state(t);
        setup.model.hip(&Vector3::new(y[0], y[1], y[2]))
    }

    /// The hip acceleration as a function of t: [`Self::hip`]`[2]` with the step's constants
    /// (the hip reference's sin θ1^±) computed once and one `sin_cos` of θ1 per call.
    pub fn hip_acceleration<'a>(&'a self, setup: &'a StanceSetup) -> impl Fn(f64) -> [f64; 2] + 'a {
        let forces =
            [false, true].map(|locked| StanceForces::new(setup, self.tau1, self.p, locked));
        move |t| {
            let (y, locked) = self.state(t);
            let q = Vector3::new(y[0], y[1], y[2]);
            let qd = Vector3::new(y[3], y[4], y[5]);
            let (s1, c1) = sin_cos(y[1]);
            let f = &forces[usize::from(locked)];
            let qdd = setup.model.accelerations_with(
                s1,
                c1,
                &q,
                &qd,
                &f.generalized_sc(t, &y, s1, c1),
                locked,
            );
            setup.model.hip_acceleration_with(s1, c1, &q, &qd, &qdd)
        }
    }

    /// Hip position, velocity and acceleration at t (relative to the stance ankle's x).
    pub fn hip(&self, setup: &StanceSetup, t: f64) -> [[f64; 2]; 3] {
        let (y, locked) = self.state(t);
        let q = Vector3::new(y[0], y[1], y[2]);
        let qd = Vector3::new(y[3], y[4], y[5]);
        let forces = StanceForces::new(setup, self.tau1, self.p, locked);
        let qdd = forces.accelerations(t, &y);
        let m = &setup.model;
        [
            m.hip(&q),
            m.hip_velocity(&q, &qd),
            m.hip_acceleration(&q, &qd, &qdd),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::walker::Walker;
    use crate::{Attributes, Body, GaitRequest};

    /// The stance setup of a steady step (step 5) at `v` m/s for the default body.
    fn setup_at(v: f64) -> StanceSetup {
        let body = Body::standard(1.8, 80.0).unwrap();
        let attrs = Attributes::default();
        let g = GaitRequest {
            velocity: Some(v),
            ..Default::default()
        }
        .complete(&body, &attrs)
        .unwrap();
        let mut walker = Walker::new(body, attrs);
        (0..6)
            .map(|_| walker.step(g).unwrap())
            .last()
            .unwrap()
            .stance_setup
    }

    fn steady_setup() -> StanceSetup {
        setup_at(1.4)
    }

    /// W(θ1*) = w*, and the hip arrives level (dy/dθ1 = W' cos θ1* − W sin θ1* = 0, c inside
    /// [−4, 1]) from 0.6 to 2.0 m/s; heel-off between mid-stance and heel strike.
    #[test]
    fn terminal_reference_meets_the_plan_end_and_arrives_level() {
        for v in [0.6, 1.0, 1.4, 2.0] {
            let s = setup_at(v);
            let t = &s.terminal;
            let (se, ce) = s.theta1_end.sin_cos();
            assert!((t.length(se, ce).0 - s.w_end).abs() < 1e-9);
            let th = s.theta1_end;
            let (w, dw) = t.length(th.sin(), th.cos());
            let slope = dw * th.cos() - w * th.sin();
            assert!(
                t.end_rate > -4.0 && t.end_rate < 1.0,
                "v {v}: c = {}",
                t.end_rate
            );
            assert!(slope.abs() < 1e-5, "v {v}: {slope}");
            // (at 2 m/s the ankle is past θ5_max at mid-stance already: heel-off is there,
            // sin θ_ho = 0)
            assert!(t.sin_heel_off >= 0.0 && t.sin_heel_off < se && t.pitch_end > 0.0);
        }
    }

    /// The pelvis's small-angle sine and cosine against libm within their Taylor remainders.
    #[test]
    fn small_sin_cos_is_within_its_remainder() {
        for k in -200..=200 {
            let x = 0.2 * k as f64 / 200.0;
            let (s, c) = small_sin_cos(x);
            assert!(
                (s - x.sin()).abs() <= x.powi(7).abs() / 5040.0 + 1e-17,
                "{x}"
            );
            assert!((c - x.cos()).abs() <= x.powi(8) / 40320.0 + 1e-16, "{x}");
        }
    }

    /// dW/dθ1 (the implicit derivative) against central differences of W, on the flat foot,
    /// after heel-off and near heel strike.
    #[test]
    fn terminal_reference_derivative_matches_finite_differences() {
        let s = steady_setup();
        let t = &s.terminal;
        let h = 1e-6;
        for f in [0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 1.0, 1.05] {
            let th = f * s.theta1_end;
            let w = |x: f64| t.length(x.sin(), x.cos()).0;
            let fd = (w(th + h) - w(th - h)) / (2.0 * h);
            let dw = t.length(th.sin(), th.cos()).1;
            assert!(
                (fd - dw).abs() < 1e-7 * (1.0 + dw.abs()),
                "{f}: {fd} vs {dw}"
            );
        }
    }

    /// The reference continues through heel strike with its slope (the pitch and the pelvis
    /// are not held there: every converged trial ends at θ1*, and a kink there cost the
    /// integrator 14 shrinking steps per trial), and its slope's rate of change stays bounded
    /// across it (second differences of W from both sides agree).
    #[test]
    fn terminal_reference_is_smooth_through_heel_strike() {
        for v in [0.6, 1.4, 2.0] {
            let s = setup_at(v);
            let t = &s.terminal;
            let dw = |x: f64| t.length(x.sin(), x.cos()).1;
            let (e, h) = (s.theta1_end, 1e-6);
            let jump = dw(e + h) - dw(e - h);
            let curvature = (dw(e - h) - dw(e - 3.0 * h)) / (2.0 * h);
            assert!(
                (jump / (2.0 * h) - curvature).abs() < 1e-3 * (1.0 + curvature.abs()),
                "v {v}: slope change {jump} over 2h, curvature {curvature}"
            );
        }
    }

    /// Estrin's scheme against the binomial theorem: Σ C(19, k) y^k = (1 + y)^19.
    #[test]
    fn estrin_sums_a_known_polynomial() {
        let mut a = [1.0; TABLE_TERMS];
        for k in 1..TABLE_TERMS {
            a[k] = a[k - 1] * (TABLE_TERMS - k) as f64 / k as f64;
        }
        for y in [-1.0, -0.7, -0.25, 0.0, 0.3, 0.5, 1.0] {
            let exact = (1.0_f64 + y).powi(19);
            let got = estrin(&a, y);
            assert!(
                (got - exact).abs() <= 1e-15 * 2f64.powi(19),
                "{y}: {got} {exact}"
            );
        }
    }

    /// The Chebyshev series of exp on [0.2, 0.9] and of its derivative against exp itself (the
    /// derivative to the rounding of its terms, amplified by up to TABLE_TERMS²).
    #[test]
    fn chebyshev_series_meets_an_analytic_function() {
        let ch = Chebyshev::fit(f64::exp, 0.2, 0.9);
        for k in 0..=100 {
            let x = 0.2 + 0.7 * k as f64 / 100.0;
            let (f, df) = ch.eval(x);
            assert!(
                (f - x.exp()).abs() < 1e-14 && (df - x.exp()).abs() < 1e-11,
                "{x}: {f} {df}"
            );
        }
    }

    /// The table of W ([`TerminalStance::length`]) against the formula it tabulates, over both
    /// pieces (foot flat, heel rising) and across heel-off: W to 1e-11 m, dW/dθ1 to 1e-8 m/rad
    /// (measured with 20 terms: at most 1.9e-12 m and 2.2e-9 m/rad, at 2.0 m/s, the series'
    /// truncation; under 2.1e-14 m and 3.8e-11 m/rad at 0.6–1.4 m/s).
    #[test]
    fn terminal_table_meets_the_formula() {
        for v in [0.6, 1.0, 1.4, 2.0] {
            let t = setup_at(v).terminal;
            let held = t.sin_heel_off + PAST_END * (t.sin_end - t.sin_heel_off);
            let (mut dw_worst, mut ddw_worst) = (0.0_f64, 0.0_f64);
            for k in 0..2000 {
                let s1 = held * k as f64 / 2000.0;
                let c1 = (1.0 - s1 * s1).sqrt();
                let (w, dw) = t.length(s1, c1);
                let (we, dwe) = t.exact_length(s1, c1);
                dw_worst = dw_worst.max((w - we).abs());
                ddw_worst = ddw_worst.max((dw - dwe).abs());
            }
            assert!(
                dw_worst < 1e-11 && ddw_worst < 1e-8,
                "v {v}: {dw_worst:e} {ddw_worst:e}"
            );
        }
    }

    /// The reference is the virtual leg: after heel-off the ankle A, the stance foot's ankle
    /// turned about M by the pitch p(s) (a rotation matrix here), stays |P − M| from M, and the
    /// hip joint J = C + o(u), o from the determinants, is the leg's 3-D reach a0 from A with the
    /// lateral offset dz(u) (l0/2 − b/2 + D cos(πu/2)).
    #[test]
    fn terminal_reference_is_the_virtual_leg() {
        let s = steady_setup();
        let t = &s.terminal;
        let [mx, my] = t.meta;
        let d = &t.pelvis;
        for f in [0.5, 0.7, 0.9, 1.0] {
            let s1 = t.sin_heel_off + f * (t.sin_end - t.sin_heel_off);
            let c1 = (1.0 - s1 * s1).sqrt();
            let w = t.length(s1, c1).0;
            let p = t.pitch_end * f.powi(4) * (1.0 + t.end_rate * (f - 1.0));
            // P − M turned clockwise (heel up) by p
            let (sp, cp) = p.sin_cos();
            let (vx, vy) = (-mx, -my);
            let a = [mx + cp * vx + sp * vy, my - sp * vx + cp * vy];
            assert!(((a[0] - mx).hypot(a[1] - my) - mx.hypot(my)).abs() < 1e-12);
            assert!(a[1] > 0.0, "the heel has risen");
            let u = s1 / t.sin_end;
            let half = 0.5 * PI * u;
            let j = [
                w * s1 - d.half_width * (d.rotation * half.sin()).sin(),
                w * c1 + d.half_width * (d.list * half.cos()).sin(),
            ];
            let dz = d.half_width - d.half_step_width + d.lateral * half.cos();
            let reach = ((j[0] - a[0]).powi(2) + (j[1] - a[1]).powi(2) + dz * dz).sqrt();
            assert!(
                (reach - t.reach).abs() < 1e-12,
                "{f}: {reach} vs {}",
                t.reach
            );
        }
    }

    /// The whole reference: C¹ at mid-stance where the bounce hands over to the virtual leg
    /// (value and slope from either side), at y_mid there, and never under the heel-strike
    /// height over the stance.
    #[test]
    fn hip_reference_is_c1_at_mid_stance_and_stays_above_heel_strike() {
        let s = steady_setup();
        let (ym, dm) = hip_reference(&s, -1e-9);
        let (yp, dp) = hip_reference(&s, 1e-9);
        assert!(
            (ym - yp).abs() < 1e-9 && (dm - dp).abs() < 1e-6,
            "{ym} {yp} {dm} {dp}"
        );
        let y_mid = 0.5 * (s.y_start + s.y_end) + s.bounce;
        assert!((ym - y_mid).abs() < 1e-9);
        let n = 2000;
        for k in 0..=n {
            let th = -s.theta1_start + (s.theta1_start + s.theta1_end) * k as f64 / n as f64;
            let y = hip_reference(&s, th).0;
            assert!(y >= s.y_start.min(s.y_end) - 1e-12, "θ1 {th}: {y}");
        }
    }
}
