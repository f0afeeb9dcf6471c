//! Determinants of gait (Saunders, Inman & Eberhart 1953; KLAW 1989 §4.2; spec §7): pelvic
//! rotation, pelvic list and lateral displacement of the pelvis centre, as functions of the time
//! in a step, and the hip joints they move.
//!
//! Boundary values are the spec's: rotation +A at right heel strike, 0 at mid-step, −A at left
//! heel strike; list 0 at heel strike and ±L at mid-step with the stance side up; lateral
//! displacement 0 at heel strike and ±D at mid-step towards the stance leg. Between them the
//! spec's half-cosine blends \[ours\] replace the paper's linear interpolation: rotation
//! A·cos(π s) has zero rate at both heel strikes, list L·sin(π s) and lateral D·sin(π s) are
//! C¹ across a heel strike where the stance side changes (s = τ / t_step).
use std::f64::consts::PI;

use crate::model::attributes::Attributes;

/// The list's shape over a step, peak 1 \[ours\]: g(s) = a1 sin πs + a3 sin 3πs + b (sin 2πs −
/// ½ sin 4πs), s = τ / t_step, fitted by least squares to Schwartz et al. 2008's Free mean
/// obliquity curve (the stance side up, both steps averaged, its heel-strike offset removed) and
/// scaled to a peak of 1 (at s = 0.341). Every term is 0 at both heel strikes and the rates meet
/// g'(1) = −g'(0), so the list stays C¹ where the stance side changes; the paper's half-sine
/// peaks at mid-step, people's in the loading response (16 % of the cycle) and are near level
/// by mid-stance.
const LIST_SHAPE: [f64; 3] = [0.5395805, 0.05195615, 0.40902743];

/// The list's shape g(s) and its first two derivatives in s ([`LIST_SHAPE`]) from (sin πs,
/// cos πs): the multiple angles by their recurrences (one `sin_cos` for all four harmonics).
pub(crate) fn list_shape_sc((s1, c1): (f64, f64)) -> [f64; 3] {
    let [a1, a3, b] = LIST_SHAPE;
    let (s2, c2) = (2.0 * s1 * c1, c1 * c1 - s1 * s1);
    let (s3, c3) = (s1 * (3.0 - 4.0 * s1 * s1), c1 * (4.0 * c1 * c1 - 3.0));
    let (s4, c4) = (2.0 * s2 * c2, c2 * c2 - s2 * s2);
    [
        a1 * s1 + a3 * s3 + b * (s2 - 0.5 * s4),
        PI * (a1 * c1 + 3.0 * a3 * c3 + b * (2.0 * c2 - 2.0 * c4)),
        -PI * PI * (a1 * s1 + 9.0 * a3 * s3 + b * (4.0 * s2 - 8.0 * s4)),
    ]
}

/// A side of the body: +1 right, −1 left (the sign of its world z).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Side {
    /// The right side (world z > 0).
    Right,
    /// The left side (world z < 0).
    Left,
}

impl Side {
    /// +1 for the right side, −1 for the left (world z points to the right).
    pub(crate) fn sign(self) -> f64 {
        match self {
            Side::Right => 1.0,
            Side::Left => -1.0,
        }
    }

    /// The opposite side.
    pub fn other(self) -> Side {
        match self {
            Side::Right => Side::Left,
            Side::Left => Side::Right,
        }
    }

    /// The stance side of step `index`: step 0 stands on the right leg.
    pub(crate) fn of_step(index: usize) -> Side {
        if index.is_multiple_of(2) {
            Side::Right
        } else {
            Side::Left
        }
    }

    pub(crate) fn name(self) -> &'static str {
        match self {
            Side::Right => "right",
            Side::Left => "left",
        }
    }

    /// The suffix of column and coordinate names: `r` or `l`.
    pub(crate) fn suffix(self) -> &'static str {
        match self {
            Side::Right => "r",
            Side::Left => "l",
        }
    }
}

/// The pelvis at one instant: angles (rad, clinical signs) and the lateral position of its
/// centre (m, world z), with their time derivatives.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PelvisMotion {
    pub(crate) rotation: f64,
    pub(crate) list: f64,
    /// The paper's half-sine list L sin πs (stance side up), on which the stance references
    /// and the engine's hip are built ([`Determinants::centre_shift`]).
    pub(crate) klaw_list: f64,
    pub(crate) lateral: f64,
    pub(crate) rotation_rate: f64,
    pub(crate) list_rate: f64,
    pub(crate) lateral_rate: f64,
}

/// Amplitudes of the determinants and the geometry they act on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Determinants {
    /// Rotation amplitude A (rad).
    pub(crate) rotation: f64,
    /// List amplitude L (rad).
    pub(crate) list: f64,
    /// Lateral displacement amplitude D (m).
    pub(crate) lateral: f64,
    /// Half the pelvis width, l0/2 (m).
    pub(crate) half_width: f64,
    /// Half the step width (m): each ankle's |z|.
    pub(crate) half_step_width: f64,
}

impl Determinants {
    pub(crate) fn new(attrs: &Attributes, l0: f64) -> Self {
        Determinants {
            rotation: attrs.pelvic_rotation,
            list: attrs.pelvic_list,
            lateral: attrs.lateral_displacement,
            half_width: 0.5 * l0,
            half_step_width: 0.5 * attrs.step_width,
        }
    }

    /// The pelvis at time τ of a step of duration `t_step` standing on `stance`.
    pub(crate) fn at(&self, stance: Side, tau: f64, t_step: f64) -> PelvisMotion {
        let sign = stance.sign();
        // not clamped: the sinusoids continue smoothly past the step's ends, so that finite
        // differences there see the true derivatives
        let s = tau / t_step;
        let w = PI / t_step;
        let (sn, cs) = crate::numerics::trig::sin_cos(PI * s);
        let [g, g1, _] = list_shape_sc((sn, cs));
        PelvisMotion {
            rotation: sign * self.rotation * cs,
            list: sign * self.list * g,
            klaw_list: sign * self.list * sn,
            lateral: sign * self.lateral * sn,
            rotation_rate: -sign * self.rotation * w * sn,
            list_rate: sign * self.list * g1 / t_step,
            lateral_rate: sign * self.lateral * w * cs,
        }
    }

    /// The hip joint of `side` relative to the pelvis centre (m, world axes), for pelvic rotation
    /// and list (tilt turns about the hip axis and moves neither hip):
    /// R_y(rot) R_x(−list) (0, 0, ±l0/2).
    pub(crate) fn hip_offset(&self, side: Side, p: &PelvisMotion) -> [f64; 3] {
        self.hip_offset_listed(side, p.list, p.rotation)
    }

    /// [`Self::hip_offset`] for the list `list`.
    fn hip_offset_listed(&self, side: Side, list: f64, rotation: f64) -> [f64; 3] {
        let h = side.sign() * self.half_width;
        let (sl, cl) = crate::numerics::trig::sin_cos(list);
        let (sr, cr) = crate::numerics::trig::sin_cos(rotation);
        [h * cl * sr, h * sl, h * cl * cr]
    }

    /// Where the pelvis centre is relative to the engine's dynamic hip (m, world axes) \[ours\]:
    /// the engine's stance model, its bounce and its virtual leg (spec §4, §7) hang the stance
    /// hip joint from its hip by the paper's half-sine list, and the figure's pelvis lists as
    /// people's do ([`list_shape_sc`]); the centre moves by the difference, so that the stance hip
    /// joint stays where the engine put it: (stance hip joint with the half-sine list) − (with
    /// people's). 0 at heel strike, where both lists are 0.
    pub(crate) fn centre_shift(&self, stance: Side, p: &PelvisMotion) -> [f64; 3] {
        let klaw = self.hip_offset_listed(stance, p.klaw_list, p.rotation);
        let own = self.hip_offset(stance, p);
        [klaw[0] - own[0], klaw[1] - own[1], klaw[2] - own[2]]
    }

    /// The hip joint of `leg` relative to the engine's dynamic hip of a step standing on
    /// `stance`: [`Self::centre_shift`] + [`Self::hip_offset`], i.e. the half-sine list's offset
    /// for the stance hip and that less twice people's for the other (the offsets of the two
    /// hips are opposite).
    pub(crate) fn engine_offset(&self, leg: Side, stance: Side, p: &PelvisMotion) -> [f64; 3] {
        let klaw = self.hip_offset_listed(stance, p.klaw_list, p.rotation);
        if leg == stance {
            return klaw;
        }
        let own = self.hip_offset(stance, p);
        std::array::from_fn(|k| klaw[k] - 2.0 * own[k])
    }

    /// The stance hip joint at mid-stance relative to its flat foot's ankle, to first order in
    /// the list (rotation 0 there): how far the list L raises it above the pelvis centre,
    /// (l0/2) sin L, and its lateral offset from the ankle, l0/2 − b/2 + D (step width b,
    /// lateral displacement D).
    pub(crate) fn mid_stance_hip(&self) -> (f64, f64) {
        let h = self.half_width;
        (h * self.list.sin(), h - self.half_step_width + self.lateral)
    }

    /// World z of the ankle of `side`.
    pub(crate) fn ankle_z(&self, side: Side) -> f64 {
        side.sign() * self.half_step_width
    }

    /// Lateral offset Δz from the ankle of `side` to its hip joint (m) at pelvis state `p`, the
    /// hip joint `offset` from the engine's hip ([`Self::engine_offset`]).
    pub(crate) fn lateral_offset(&self, side: Side, p: &PelvisMotion, offset: [f64; 3]) -> f64 {
        p.lateral + offset[2] - self.ankle_z(side)
    }
}

impl Determinants {
    /// The second time derivative of the swing-side hip offset from the engine's hip, `o =
    /// engine_offset(leg)`, `[o[0], o[1] + fold_height(d_v, lateral_offset(leg, o))]` (`leg` =
    /// `stance.other()`) at
    /// step time τ, in closed form (the determinants are sinusoids in τ); `None` when the fold
    /// is degenerate (a lateral offset as long as the leg), where the caller differences
    /// numerically.
    pub(crate) fn swing_offset_acceleration(
        &self,
        stance: Side,
        tau: f64,
        t_step: f64,
        d_v: f64,
    ) -> Option<[f64; 2]> {
        let leg = stance.other();
        let sign = stance.sign();
        let h = leg.sign() * self.half_width;
        let w = PI / t_step;
        let (sn, cs) = crate::numerics::trig::sin_cos(PI * tau / t_step);
        let w2 = w * w;
        // rotation R, lateral displacement D and their rates
        let r = sign * self.rotation * cs;
        let r1 = -sign * self.rotation * w * sn;
        let r2 = -w2 * r;
        let d1 = sign * self.lateral * w * cs;
        let d2 = -w2 * sign * self.lateral * sn;
        let (sr, cr) = crate::numerics::trig::sin_cos(r);
        // the swing hip joint relative to the engine's hip, [`Self::engine_offset`]: twice the
        // offset of people's list less the paper's, each h (cos L sin R, sin L, cos L cos R);
        // per list L (with its rates) its x and y accelerations and its z with two rates
        let terms = |l: f64, l1: f64, l2: f64| {
            let (sl, cl) = crate::numerics::trig::sin_cos(l);
            let ax = h
                * (-cl * sr * (l1 * l1 + r1 * r1) - sl * l2 * sr - 2.0 * sl * l1 * cr * r1
                    + cl * cr * r2);
            let ay = h * (-sl * l1 * l1 + cl * l2);
            let z = h * cl * cr;
            let z1 = h * (-sl * l1 * cr - cl * sr * r1);
            let z2 = h
                * (-cl * cr * (l1 * l1 + r1 * r1) - sl * l2 * cr + 2.0 * sl * l1 * sr * r1
                    - cl * sr * r2);
            [ax, ay, z, z1, z2]
        };
        let [g, g1, g2] = list_shape_sc((sn, cs));
        let own = terms(
            sign * self.list * g,
            sign * self.list * g1 / t_step,
            sign * self.list * g2 / (t_step * t_step),
        );
        let kl = sign * self.list * sn;
        let klaw = terms(kl, sign * self.list * w * cs, -w2 * kl);
        let [ax, ay, z, z1, z2] = std::array::from_fn(|k| 2.0 * own[k] - klaw[k]);
        // the fold of dz = D + z − ankle z
        let dz = sign * self.lateral * sn + z - self.ankle_z(leg);
        let dz1 = d1 + z1;
        let dz2 = d2 + z2;
        let q = d_v * d_v - dz * dz;
        if q <= 0.0 {
            return None;
        }
        let root = q.sqrt();
        let fold2 = (dz1 * dz1 + dz * dz2) / root + dz * dz * dz1 * dz1 / (root * q);
        Some([ax, ay + fold2])
    }
}

/// Height gained by folding a lateral offset out of a leg (spec §7: "the sagittal leg length is
/// √(a1² − d²)"): a leg whose hip–ankle line has in-plane length `d_v` and lateral offset `dz`
/// spans only √(d_v² − dz²) vertically, so in the leg's own plane the hip sits
/// d_v − √(d_v² − dz²) higher than in the world.
pub(crate) fn fold_height(d_v: f64, dz: f64) -> f64 {
    d_v - (d_v * d_v - dz * dz).max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn list_shape(s: f64) -> [f64; 3] {
        list_shape_sc(crate::numerics::trig::sin_cos(PI * s))
    }

    fn det() -> Determinants {
        Determinants {
            rotation: 4f64.to_radians(),
            list: 5f64.to_radians(),
            lateral: 0.02,
            half_width: 0.09,
            half_step_width: 0.04,
        }
    }

    /// The spec's boundary values, continuity of value and rate across a heel strike where the
    /// stance side changes, and rates that match finite differences.
    #[test]
    fn boundary_values_and_continuity() {
        let d = det();
        let t = 0.55;
        let r0 = d.at(Side::Right, 0.0, t);
        assert!((r0.rotation - d.rotation).abs() < 1e-15 && r0.list.abs() < 1e-15);
        assert!(r0.lateral.abs() < 1e-15);
        let mid = d.at(Side::Right, 0.5 * t, t);
        assert!(mid.rotation.abs() < 1e-15);
        assert!((mid.klaw_list - d.list).abs() < 1e-15 && (mid.lateral - 0.02).abs() < 1e-15);
        assert!((mid.list - d.list * list_shape(0.5)[0]).abs() < 1e-15);
        let end = d.at(Side::Right, t, t);
        let next = d.at(Side::Left, 0.0, t);
        assert!((end.rotation + d.rotation).abs() < 1e-15);
        for (a, b) in [
            (end.rotation, next.rotation),
            (end.list, next.list),
            (end.klaw_list, next.klaw_list),
            (end.lateral, next.lateral),
            (end.rotation_rate, next.rotation_rate),
            (end.list_rate, next.list_rate),
            (end.lateral_rate, next.lateral_rate),
        ] {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
        let h = 1e-6;
        for tau in [0.05, 0.2, 0.4] {
            let (a, b) = (d.at(Side::Left, tau - h, t), d.at(Side::Left, tau + h, t));
            let c = d.at(Side::Left, tau, t);
            assert!(((b.rotation - a.rotation) / (2.0 * h) - c.rotation_rate).abs() < 1e-7);
            assert!(((b.list - a.list) / (2.0 * h) - c.list_rate).abs() < 1e-7);
            assert!(((b.lateral - a.lateral) / (2.0 * h) - c.lateral_rate).abs() < 1e-7);
        }
    }

    /// The hip joints stay l0 apart and symmetric about the centre; with list +L the right hip is
    /// higher by (l0/2) sin L, with rotation +A the right hip is ahead by (l0/2) sin A.
    #[test]
    fn hip_offsets_are_a_rigid_pelvis() {
        let d = det();
        let p = PelvisMotion {
            rotation: 0.1,
            list: 0.07,
            ..Default::default()
        };
        let (r, l) = (d.hip_offset(Side::Right, &p), d.hip_offset(Side::Left, &p));
        let dist = ((r[0] - l[0]).powi(2) + (r[1] - l[1]).powi(2) + (r[2] - l[2]).powi(2)).sqrt();
        assert!((dist - 0.18).abs() < 1e-15);
        for k in 0..3 {
            assert!((r[k] + l[k]).abs() < 1e-15);
        }
        assert!((r[1] - 0.09 * 0.07f64.sin()).abs() < 1e-15);
        let p = PelvisMotion {
            rotation: 0.1,
            ..Default::default()
        };
        assert!((d.hip_offset(Side::Right, &p)[0] - 0.09 * 0.1f64.sin()).abs() < 1e-15);
    }

    /// Folding: a leg of in-plane length d_v tilted by φ drops d_v cos φ, so the fold is
    /// d_v (1 − cos φ) with sin φ = dz / d_v.
    #[test]
    fn swing_offset_acceleration_is_the_second_derivative() {
        let d = det();
        let (t_step, d_v) = (0.55, 0.84);
        for stance in [Side::Right, Side::Left] {
            let offset = |tau: f64| {
                let p = d.at(stance, tau, t_step);
                let leg = stance.other();
                let o = d.engine_offset(leg, stance, &p);
                [o[0], o[1] + fold_height(d_v, d.lateral_offset(leg, &p, o))]
            };
            // the ends included: the determinants continue smoothly past them
            for k in 0..=20 {
                let tau = t_step * k as f64 / 20.0;
                let a = d
                    .swing_offset_acceleration(stance, tau, t_step, d_v)
                    .unwrap();
                let h = 1e-3;
                for (i, ai) in a.into_iter().enumerate() {
                    let f = |dt: f64| offset(tau + dt)[i];
                    let fd = (-f(-2.0 * h) + 16.0 * f(-h) - 30.0 * f(0.0) + 16.0 * f(h)
                        - f(2.0 * h))
                        / (12.0 * h * h);
                    assert!((ai - fd).abs() < 1e-6, "{stance:?} {tau} {i}: {ai} {fd}");
                }
            }
            // a lateral offset as long as the leg: no fold to differentiate
            assert!(
                d.swing_offset_acceleration(stance, 0.1, t_step, 0.01)
                    .is_none()
            );
        }
    }

    /// The list's shape: 0 at both heel strikes with g'(1) = −g'(0) (C¹ where the stance side
    /// changes), a peak of 1 (to 1e-7, sampled every 1e-5 of the step) at a third of the step
    /// as Schwartz's Free obliquity (16 % of the cycle: s 0.32), below 1/2 at mid-step, and its
    /// derivatives against finite differences.
    #[test]
    fn the_list_shape_peaks_early_and_is_c1_across_heel_strike() {
        let [g0, d0, _] = list_shape(0.0);
        let [g1, d1, _] = list_shape(1.0);
        assert!(g0.abs() < 1e-15 && g1.abs() < 1e-15, "{g0} {g1}");
        assert!((d0 + d1).abs() < 1e-12, "{d0} {d1}");
        let (peak, at) = (0..=100_000)
            .map(|k| (list_shape(k as f64 * 1e-5)[0], k as f64 * 1e-5))
            .fold((f64::MIN, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        assert!((peak - 1.0).abs() < 1e-7, "{peak}");
        assert!((0.3..0.38).contains(&at), "{at}");
        assert!(list_shape(0.5)[0] < 0.5);
        // the recurrences against the harmonics' own sines and cosines
        let [a1, a3, b] = LIST_SHAPE;
        for k in 0..=50 {
            let x = PI * k as f64 / 50.0;
            let direct =
                a1 * x.sin() + a3 * (3.0 * x).sin() + b * ((2.0 * x).sin() - 0.5 * (4.0 * x).sin());
            assert!(
                (list_shape(k as f64 / 50.0)[0] - direct).abs() < 1e-14,
                "{k}"
            );
        }
        let h = 1e-4;
        for s in [0.1, 0.34, 0.5, 0.8] {
            let [_, d, dd] = list_shape(s);
            let (a, b) = (list_shape(s - h), list_shape(s + h));
            assert!(((b[0] - a[0]) / (2.0 * h) - d).abs() < 1e-6, "{s}");
            assert!(((b[1] - a[1]) / (2.0 * h) - dd).abs() < 1e-5, "{s}");
        }
    }

    /// The pelvis centre moves so that the stance hip joint stays where the half-sine list put
    /// it: centre shift + the stance hip's offset is the offset with the paper's list, to 1e-15;
    /// the shift is 0 at heel strike and lifts the centre at mid-step (people's list is lower
    /// there), so the swing hip rises by twice that.
    #[test]
    fn the_stance_hip_joint_keeps_the_papers_list() {
        let d = det();
        let t = 0.55;
        for stance in [Side::Right, Side::Left] {
            for k in 0..=10 {
                let p = d.at(stance, t * k as f64 / 10.0, t);
                let e = d.engine_offset(stance, stance, &p);
                let klaw = PelvisMotion {
                    list: p.klaw_list,
                    ..p
                };
                let o = d.hip_offset(stance, &klaw);
                // the other hip: the shifted centre plus its own offset with people's list
                let other = d.engine_offset(stance.other(), stance, &p);
                let shift = d.centre_shift(stance, &p);
                let own = d.hip_offset(stance.other(), &p);
                for i in 0..3 {
                    assert!((e[i] - o[i]).abs() < 1e-15, "{stance:?} {k} {i}");
                    assert!(
                        (other[i] - shift[i] - own[i]).abs() < 1e-15,
                        "{stance:?} {k} {i}"
                    );
                }
            }
            let zero = d.centre_shift(stance, &d.at(stance, 0.0, t));
            assert!(zero.iter().all(|x| x.abs() < 1e-15), "{zero:?}");
            let p = d.at(stance, 0.5 * t, t);
            let lift = d.centre_shift(stance, &p)[1];
            let want = d.half_width * (d.list.sin() - (d.list * list_shape(0.5)[0]).sin());
            assert!((lift - want).abs() < 1e-15 && lift > 0.0, "{lift} {want}");
        }
    }

    #[test]
    fn fold_height_is_the_tilted_leg_drop() {
        let (d_v, phi) = (0.85_f64, 0.07_f64);
        let dz = d_v * phi.sin();
        assert!((fold_height(d_v, dz) - d_v * (1.0 - phi.cos())).abs() < 1e-15);
        assert_eq!(fold_height(0.8, 0.0), 0.0);
    }
}
