//! The stance hip height reference that the leg axis force tracks (KLAW 1989 §4.2, spec §4 and
//! §7): the bounce of the loading response up to mid-stance, the virtual leg's from there on.
use std::f64::consts::PI;

use serde::Deserialize;

use crate::kinematics::pelvis::Determinants;
use crate::numerics::chebyshev::Chebyshev;
use crate::numerics::roots;
use crate::numerics::trig::{sin_cos, small_sin_cos};

use super::StanceSetup;

/// The hip height reference and its derivative with respect to θ1 \[ours\]:
/// - up to mid-stance (θ1 < 0), spec §4: y_ref = ȳ(u) + e cos²(πu/2), u = sin θ1 / sin θ1^−
///   clipped to [−1, 1], ȳ blending the two heel-strike heights with a half-sine (ȳ = y_hs in a
///   steady gait): the bounce e = ε·E gives the loading response;
/// - from mid-stance (θ1 ≥ 0), spec §7 "replace y_ref": the pelvis centre where the virtual leg
///   puts it with its knee held at the mid-stance value, l9 + W(θ1) cos θ1 ([`TerminalStance`]).
#[cfg(test)]
pub(crate) fn hip_reference(s: &StanceSetup, theta1: f64) -> (f64, f64) {
    let (s1, c1) = sin_cos(theta1);
    hip_reference_sc(s, s1, c1, 1.0 / s.theta1_start.sin(), theta1 >= 0.0)
}

/// [`hip_reference`] from sin θ1, cos θ1 and the reciprocal of the bounce's denominator
/// sin θ1^− (start), on the side of mid-stance `terminal` says (each side's formula continues
/// smoothly past θ1 = 0, so that an integration segment ending there sees its own side's
/// reference): one `sin_cos` of πu/2 for the bounce, since 1 + cos πu = 2 cos²(πu/2) and
/// sin πu = 2 sin(πu/2) cos(πu/2).
#[inline(always)]
pub(super) fn hip_reference_sc(
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
/// length W(θ1) from the pivot P (the flat foot's ankle) to the pelvis centre C \[ours\]. The knee
/// stays at its mid-stance flexion κ0, so the stance hip joint J is the leg's mid-stance reach
/// a0 from the ankle A in space, and √(a0² − dz²) in the leg's plane (dz: the lateral offset):
/// - foot flat (A = P) while the ankle's dorsiflexion, the lean of the shank (the ankle–J line's
///   angle plus the shank's lead δ over it at κ0), is below θ5_max;
/// - heel-off: the foot turns about its metatarsal joint M by the pitch
///   p = p_hs s⁴ (1 + c (s − 1) + D (1 − s)²), s = (sin θ1 − sin θ_ho) / (sin θ1* − sin θ_ho),
///   so that the reference is C³ at heel-off (the swing reads the hip's acceleration from a
///   quintic table, [`HipPath`](super::HipPath), which a C² reference's jerk kink pushes over
///   its error bound) and the heel rises ever faster into push-off; p_hs puts C at (θ1*, w*) at
///   heel strike, c ∈ [−4, 1] makes C arrive there level (as the spec §4 reference did, so
///   that the hip does not dip below y_hs before it), or as nearly as a monotone pitch allows,
///   and D (`ReferenceShape::pitch_bulge`) raises the heel in mid terminal stance without changing either end.
///
/// The pelvis moves J from C by o(u) = (−(l0/2) sin(A sin(πu/2)), (l0/2) sin(L cos(πu/2))) and
/// dz(u) = D cos(πu/2) + l0/2 − b/2 (rotation A, list L, lateral displacement D, step width b;
/// u = sin θ1 / sin θ1* stands for the step's time, and cos L cos R ≈ 1 in dz: ≤ 0.4 mm), so
/// C lies on the circle of radius √(a0² − dz²) about A − o:
/// W = e·(A − o) + √((e·(A − o))² − |A − o|² + a0² − dz²), e = (sin θ1, cos θ1).
/// Heel-off comes no later than at 0.7 sin θ1*, since the heel must rise before heel strike
/// (w* > l1). A reference: `kinematics::stance_leg` is the exact figure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TerminalStance {
    /// a0: hip joint to ankle with the knee at κ0 (m).
    pub(crate) reach: f64,
    /// M relative to the pivot (m).
    pub(crate) meta: [f64; 2],
    /// Foot pitch at heel strike p_hs (rad), and c of the pitch's shape
    /// s⁴ (1 + c (s − 1) + D (1 − s)²), c ∈ [−4, 1] (monotone, ≥ 0; end rate 4 + c).
    pub(crate) pitch_end: f64,
    pub(crate) end_rate: f64,
    /// sin θ_ho, sin θ1*.
    pub(crate) sin_heel_off: f64,
    pub(crate) sin_end: f64,
    /// The determinants of gait (with the step's list), which move the hip joint.
    pub(crate) pelvis: Determinants,
    /// W as a function of sin θ1 in Chebyshev series, on [0, sin θ_ho] (foot flat) and from
    /// there to where the pitch is held (`ReferenceShape::past_end`) in two halves: what [`Self::length`]
    /// evaluates.
    /// Its shape constants.
    shape: ReferenceShape,
    table: [Chebyshev; 3],
}

/// The shape constants of the stance hip's reference in terminal stance \[ours\] (model
/// constants of `models/engine.toml`'s `[stance]`, where each one's derivation is).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceShape {
    /// m of the margin m (1 − x)² above y_hs that the reference keeps between heel-off (x = 0)
    /// and heel strike (x = 1) (m): with less the tracking hip dipped under y_hs just before
    /// heel strike in slow walks of tall bodies.
    pub end_margin: f64,
    /// The reference's arrival slope at heel strike, dy/dθ1 = end_rise cos θ1* (m/rad): the
    /// hip lags its reference, and with a level arrival it undershot y_hs by up to 40 µm just
    /// before heel strike and climbed back to it; a slightly rising reference brings it in
    /// falling.
    pub end_rise: f64,
    /// D of the heel-off pitch's shape s⁴ (1 + c (s − 1) + D (1 − s)²): the bulge D s⁴ (1 − s)²
    /// lifts the heel in mid terminal stance and leaves the pitch's C³ start at heel-off, its
    /// heel-strike value and its end rate alone. The pitch stays monotone for every c ∈ [−4, 1]
    /// while D ≤ 10 (at c = −4 its rate is s³ u (20 − 2D + 6D u), u = 1 − s).
    pub pitch_bulge: f64,
    /// How far past heel strike (in s and u, where heel strike is 1) the pitch and the pelvis's
    /// offsets continue their formulas before they are held: held at heel strike itself, the
    /// reference's slope jumps where every converged trial ends, and the integrator's last steps
    /// straddling that kink shrink geometrically.
    pub past_end: f64,
}

impl ReferenceShape {
    /// The constants with their names, for checks and messages.
    pub fn named(&self) -> [(&'static str, f64); 4] {
        [
            ("end_margin", self.end_margin),
            ("end_rise", self.end_rise),
            ("pitch_bulge", self.pitch_bulge),
            ("past_end", self.past_end),
        ]
    }
}

/// Points between heel-off and heel strike at which [`TerminalStance::new`] checks that the
/// reference stays above its heel-strike height.
const HEEL_RISE_CHECKS: usize = 32;

impl TerminalStance {
    /// `y_mid`: the pelvis centre's reference height at mid-stance; `det`: the determinants
    /// (with the step's list); `end`: θ1* and w*; `(l3, l4, l9, h12)`: thigh, shank, ankle
    /// height and ankle to M (foot flat); `theta5_max`: the heel-off dorsiflexion; `shape`: the
    /// reference's shape constants.
    pub(crate) fn new(
        y_mid: f64,
        det: &Determinants,
        (theta1_end, w_end): (f64, f64),
        (l3, l4, l9, h12): (f64, f64, f64, f64),
        theta5_max: f64,
        shape: ReferenceShape,
    ) -> Self {
        let (rise, lateral) = det.mid_stance_hip();
        let w0 = y_mid + rise - l9;
        let reach = w0.hypot(lateral).min(l3 + l4);
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
            table: [Chebyshev::ZERO; 3],
            shape,
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
                let arrival = shape.end_rise * (theta1_end - s1.asin());
                t.exact_length_at(s1).0 * (1.0 - s1 * s1).sqrt()
                    < y_end + shape.end_margin * (1.0 - x).powi(2) - arrival
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
        let held = t.sin_heel_off + shape.past_end * (sin_end - t.sin_heel_off);
        let half = 0.5 * (t.sin_heel_off + held);
        t.table = [
            Chebyshev::fit(
                |s1| flat.exact_length_at(s1).0,
                0.0,
                t.sin_heel_off.max(0.1 * sin_end),
            ),
            Chebyshev::fit(|s1| t.exact_length_at(s1).0, t.sin_heel_off, half),
            Chebyshev::fit(|s1| t.exact_length_at(s1).0, half, held),
        ];
        t
    }

    /// p_hs so that W(θ1*) = w* (W rises with p: the ankle rises towards the hip), then c so
    /// that the hip arrives nearly level, dy/dθ1 = W' cos θ1* − W sin θ1* = `end_rise` cos θ1*,
    /// where a monotone pitch
    /// allows (dW/dθ1 at the end is linear in the pitch's end rate 4 + c): with a falling
    /// arrival the tracking hip dips under y_hs in slow walks.
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
            dw - w * sin_end / (1.0 - sin_end * sin_end).sqrt() - self.shape.end_rise
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
    /// (the pelvis's sines, the foot's rotation and a square root), so that its coefficients
    /// fall fast (to 1e-12 of W by the 20th) and the 20 Chebyshev terms of each piece (the rising
    /// heel's in two halves, since the pitch's bulge bends it) meet [`Self::exact_length`] to
    /// ≤ 3e-13 m and dW/dθ1 to ≤ 4.5e-10 m/rad (0.6–2.0 m/s, tested), for two Estrin sums, a
    /// fraction of the formula's cost (the stance right-hand side evaluates it at every stage).
    /// Outside the table (θ1 < 0, or the pitch held), the formula itself.
    pub(crate) fn length(&self, s1: f64, c1: f64) -> (f64, f64) {
        let [flat, rising, rolling] = &self.table;
        let piece = if s1 < flat.lo() || s1 > rolling.hi() {
            return self.exact_length(s1, c1);
        } else if s1 < rising.lo() {
            flat
        } else if s1 < rolling.lo() {
            rising
        } else {
            rolling
        };
        let (w, dw) = piece.eval(s1);
        (w, dw * c1)
    }

    /// W(θ1) and dW/dθ1 from sin θ1, cos θ1 (θ1 ≥ 0), by the formula above.
    pub(crate) fn exact_length(&self, s1: f64, c1: f64) -> (f64, f64) {
        let span = self.sin_end - self.sin_heel_off;
        let past_end = self.shape.past_end;
        let s = ((s1 - self.sin_heel_off) / span).min(past_end);
        let c = self.end_rate;
        let (p, dp) = if s <= 0.0 {
            (0.0, 0.0)
        } else {
            let (g, dg) = pitch_shape(s, c, self.shape.pitch_bulge);
            let rate = if s < past_end {
                self.pitch_end * dg * c1 / span
            } else {
                0.0
            };
            (self.pitch_end * g, rate)
        };
        // flat foot: the ankle is the pivot
        let (ankle, dankle) = if p == 0.0 {
            ([0.0; 2], [0.0; 2])
        } else {
            self.ankle(p)
        };
        let u = (s1 / self.sin_end).min(past_end);
        let du = if u < past_end { c1 / self.sin_end } else { 0.0 };
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

/// The heel-off pitch as a fraction of p_hs, g(s) = s⁴ (1 + c (s − 1) + D (1 − s)²), and
/// dg/ds = s³ (4 (1 + c (s − 1) + D (1 − s)²) + s (c − 2 D (1 − s))) ([`TerminalStance`]).
#[inline(always)]
fn pitch_shape(s: f64, c: f64, d: f64) -> (f64, f64) {
    let u = 1.0 - s;
    let shape = 1.0 - c * u + d * u * u;
    let s3 = s * s * s;
    (s3 * s * shape, s3 * (4.0 * shape + s * (c - 2.0 * d * u)))
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

    /// The bundled shape constants (models/engine.toml).
    fn shape() -> ReferenceShape {
        crate::engine::parameters::EngineParameters::default().stance_reference
    }

    fn steady_setup() -> StanceSetup {
        setup_at(1.4)
    }

    /// W(θ1*) = w*, and the hip arrives nearly level (dy/dθ1 = W' cos θ1* − W sin θ1* =
    /// end_rise cos θ1*, c inside [−4, 1], or arriving from above less steeply with c = 1) from
    /// 0.6 to 2.0 m/s;
    /// heel-off between mid-stance and heel strike.
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
            // the fastest monotone pitch (c = 1) arrives short of the rise at 2 m/s, and with the
            // hip's lead falling at 0.6 m/s (−3.6e-3 m/rad): the hip then comes down onto y_hs
            // from above, which the walk's invariant allows (the rise only keeps a lagging hip
            // from undershooting y_hs)
            let target = shape().end_rise * th.cos();
            assert!(
                t.end_rate > -4.0 && t.end_rate <= 1.0,
                "v {v}: c = {}",
                t.end_rate
            );
            if t.end_rate < 1.0 {
                assert!((slope - target).abs() < 1e-5, "v {v}: {slope}");
            } else {
                let before = th - 0.01;
                let y_before = t.length(before.sin(), before.cos()).0 * before.cos();
                let y_end = s.w_end * th.cos();
                assert!(slope < target && y_before > y_end, "v {v}: {slope}");
            }
            // (at 2 m/s the ankle is past θ5_max at mid-stance already: heel-off is there,
            // sin θ_ho = 0)
            assert!(t.sin_heel_off >= 0.0 && t.sin_heel_off < se && t.pitch_end > 0.0);
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
    /// are not held there: every converged trial ends at θ1*, and a kink there shrinks the
    /// integrator's last steps, `ReferenceShape::past_end`), and its slope's rate of change stays bounded
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

    /// The table of W ([`TerminalStance::length`]) against the formula it tabulates, over both
    /// pieces (foot flat, heel rising) and across heel-off: W to 1e-11 m, dW/dθ1 to 1e-8 m/rad
    /// (the series' truncation is largest at 2.0 m/s).
    #[test]
    fn terminal_table_meets_the_formula() {
        for v in [0.6, 1.0, 1.4, 2.0] {
            let t = setup_at(v).terminal;
            let held = t.sin_heel_off + shape().past_end * (t.sin_end - t.sin_heel_off);
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
            let p = t.pitch_end
                * f.powi(4)
                * (1.0 + t.end_rate * (f - 1.0) + shape().pitch_bulge * (1.0 - f).powi(2));
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
    /// height over the stance but by the rising arrival's end_rise (θ1* − θ1).
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
            let arrival = shape().end_rise * (s.theta1_end - th).max(0.0);
            assert!(
                y >= s.y_start.min(s.y_end) - arrival - 1e-12,
                "θ1 {th}: {y}"
            );
        }
    }

    /// The pitch's shape: 0 with its first three derivatives at heel-off (g(h) / h⁴ → 1 − c + D),
    /// 1 with rate 4 + c at heel strike whatever D, its rate against central differences, and
    /// monotone over [0, 1] for every c ∈ [−4, 1] at D = pitch_bulge; past D = 10 it turns back
    /// at c = −4 (the bound `ReferenceShape::pitch_bulge` states).
    #[test]
    fn the_heel_off_pitch_is_c3_at_heel_off_monotone_and_meets_its_ends() {
        let d = shape().pitch_bulge;
        for k in 0..=20 {
            let c = -4.0 + 5.0 * k as f64 / 20.0;
            let h = 1e-3;
            let (g0, _) = pitch_shape(h, c, d);
            assert!(
                (g0 / h.powi(4) - (1.0 - c + d)).abs() < 0.05 * (1.0 + d),
                "c {c}"
            );
            let (g1, dg1) = pitch_shape(1.0, c, d);
            assert!(
                (g1 - 1.0).abs() < 1e-15 && (dg1 - (4.0 + c)).abs() < 1e-12,
                "c {c}"
            );
            let mut last = 0.0;
            for i in 1..=1000 {
                let s = i as f64 / 1000.0;
                let (g, dg) = pitch_shape(s, c, d);
                let e = 1e-6;
                let fd = (pitch_shape(s + e, c, d).0 - pitch_shape(s - e, c, d).0) / (2.0 * e);
                assert!((fd - dg).abs() < 1e-7, "c {c} s {s}: {fd} vs {dg}");
                assert!(g >= last && dg >= 0.0, "c {c} s {s}: not monotone");
                last = g;
            }
        }
        let turns_back = (1..1000).any(|i| pitch_shape(i as f64 / 1000.0, -4.0, 10.5).1 < 0.0);
        assert!(turns_back);
    }
}
