//! The virtual stance leg (KLAW 1989 §4.2, Figure 6; the foot rules of spec §7): a human leg —
//! thigh, shank and a foot with ankle and metatarsal joints — laid over the telescopic stance leg
//! from its heel strike to its toe-off (which falls in the next step's double support). The hip
//! joint is given at each instant (the dynamic hip moved by the determinants of gait); the foot's
//! contact with the ground does not slide:
//! - *heel rocker* (heel strike → foot flat, FGM): the foot turns about its heel, sole angle
//!   φ(t) = φ_hs (1 − s)² (1 + s/2), s = t / t_FGM (`rocker_sole`); the knee by two-link
//!   trigonometry;
//! - *foot flat* (FGM → heel-off): ankle fixed; the knee follows from the hip–ankle distance;
//! - *heel-off* and *meta-off*: the knee flexion κ(t) is prescribed, C¹ from its value and rate
//!   at heel-off to κ_TO at toe-off, and the one unknown foot pitch p solves
//!   |hip − ankle(p)| = a(κ), rolling about the metatarsal joint, then the toe tip.
//!
//! Heel-off starts when the flat foot's ankle dorsiflexion reaches θ5_max, or when the straight
//! leg can no longer reach the hip. Legs are worked in their own plane: a hip joint with lateral
//! offset `dz` from the ankle is at 3-D distance √(Δx² + Δy² + dz²), and the leg's plane contains
//! the forward axis, so the in-plane drop from hip to ankle is √(Δy² + dz²).
use std::f64::consts::FRAC_PI_3;

use crate::kinematics::arc::{Arc, first_in};
use crate::kinematics::error::GeometryError;
use crate::kinematics::foot::{Foot, FootPoints, GUESS_SLACK};
pub(crate) use crate::kinematics::knee_curve::KneeCurve;
pub(crate) use crate::kinematics::leg::{LegPose, leg_points, leg_points_sc};
use crate::kinematics::leg::{chain, reach};
use crate::model::body::Body;
use crate::numerics::roots;
use crate::numerics::trig::sin_cos;

/// Which foot rule holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FootPhase {
    /// Heel strike to foot flat (FGM): the foot turns about its heel.
    HeelRocker,
    /// Foot flat to heel-off: the ankle is fixed on the ground.
    FootFlat,
    /// Heel-off to toe-off: the knee follows its prescribed curve and the foot rolls about the
    /// metatarsal joint, then the toe tip.
    Rolling,
}

/// The stance leg of one step, from its heel strike to its toe-off. Times are world times (s),
/// x positions world x (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StanceLeg {
    /// The foot's dimensions.
    pub foot: Foot,
    /// Thigh length l3 (m).
    pub l3: f64,
    /// Shank length l4 (m).
    pub l4: f64,
    /// Flat-foot ankle x.
    pub ankle_x: f64,
    /// Heel strike time.
    pub t_hs: f64,
    /// The sole angle φ_hs at heel strike (rad, toe up +).
    pub sole_hs: f64,
    /// Heel strike to foot flat (s).
    pub t_fgm: f64,
    /// θ5_max, the ankle dorsiflexion that triggers heel-off (rad).
    pub(crate) theta5_max: f64,
    /// θ6_max, the metatarsal dorsiflexion at which the foot rolls on about the toe tip
    /// (meta-off, rad).
    pub theta6_max: f64,
    /// The knee after heel-off: from heel-off to the next heel strike, then (re-anchored there)
    /// to toe-off. `None` until found.
    pub heel_off: Option<KneeCurve>,
    pub(crate) to_toe_off: Option<KneeCurve>,
}

/// The heel rocker's sole angle as a fraction of φ_hs at s = t / t_FGM, (1 − s)² (1 + s/2)
/// \[ours\]: the foot starts down at 1.5 × the rate of the straight line to foot flat, and its
/// rate, −(3/2)(1 − s²), falls from there to zero at foot flat (the rate's size
/// (1 − s)(2 − β + 3βs) of (1 − s)² (1 + βs) is non-increasing only for β ≤ ½). A smoothstep
/// (spec §7) held the sole at its heel-strike angle at first while the stance knee flexed into
/// the loading response, rocking the ankle into dorsiflexion and then slapping the foot down
/// mid-way; with β = 1 the foot's fall, fastest a third of the way, outran the hip's approach
/// and paused the loading-response knee (docs/realism.md, "The heel in terminal stance").
fn rocker_sole(s: f64) -> f64 {
    (1.0 - s) * (1.0 - s) * (1.0 + 0.5 * s)
}

/// The largest pitch (rad) the rolling foot may take to reach the hip.
const MAX_PITCH: f64 = 1.8;

/// The largest gap (m) between the straight leg and the hip at heel-off that is still a
/// continuous roll onto the metatarsal joint ([`StanceLeg::find_heel_off`]): the heel-off root is
/// found to 1e-9 s, and the gap is read 1e-7 s after it, when the hip has moved ≤ 3e-7 m.
const FLAT_REACH_SLACK: f64 = 1e-6;

impl StanceLeg {
    /// The stance leg of `body` whose flat foot's ankle is at `ankle_x`, striking at `t_hs` with
    /// sole angle `sole_hs`, flat at `t_hs + t_fgm`, with the foot rules' limits θ5_max and
    /// θ6_max (rad); its knee curves are found later ([`Self::find_heel_off`]).
    pub fn new(
        body: &Body,
        ankle_x: f64,
        t_hs: f64,
        sole_hs: f64,
        t_fgm: f64,
        theta5_max: f64,
        theta6_max: f64,
    ) -> Self {
        StanceLeg {
            foot: Foot::new(body),
            l3: body.l3,
            l4: body.l4,
            ankle_x,
            t_hs,
            sole_hs,
            t_fgm,
            theta5_max,
            theta6_max,
            heel_off: None,
            to_toe_off: None,
        }
    }

    /// The rolling foot at pitch p: ankle, θ6 and points ([`Foot::rolling_points`]).
    fn rolling(&self, p: f64) -> ([f64; 2], f64, FootPoints) {
        self.foot
            .rolling_points(self.ankle_x + self.foot.h12, p, self.theta6_max)
    }

    /// The prescribed knee after heel-off at time t, if the heel is off by then.
    pub fn knee_curve(&self, t: f64) -> Option<(f64, f64)> {
        match (&self.heel_off, &self.to_toe_off) {
            (_, Some(k)) if t >= k.t0 => Some(k.at(t)),
            (Some(k), _) if t >= k.t0 => Some(k.at(t)),
            _ => None,
        }
    }

    /// The foot rule at time t.
    pub fn phase(&self, t: f64) -> FootPhase {
        if self.knee_curve(t).is_some() {
            FootPhase::Rolling
        } else if t < self.t_hs + self.t_fgm {
            FootPhase::HeelRocker
        } else {
            FootPhase::FootFlat
        }
    }

    /// The pose at time t for a hip joint at `hip` (world x, y) with lateral offset `dz` from the
    /// ankle.
    pub fn pose(&self, hip: [f64; 2], dz: f64, t: f64) -> Result<LegPose, GeometryError> {
        // the rule of [`Self::phase`], the knee curve evaluated once
        match self.knee_curve(t) {
            Some((kappa, _)) => self.rolling_pose(hip, dz, kappa),
            None => {
                let rule = if t < self.t_hs + self.t_fgm {
                    self.sole_hs * rocker_sole((t - self.t_hs) / self.t_fgm)
                } else {
                    0.0
                };
                // the foot turns about its heel, at (ankle_x − l8, 0), to pitch p = −φ; the
                // rule's ankle is also the reach test's first point
                let mut sc = sin_cos(-rule);
                let mut ankle = self.rocker_ankle(sc);
                let mut phi = rule;
                if hip[0] < self.ankle_x && self.too_far(hip, dz, ankle) {
                    phi = self.reach_limited_sole(hip, dz, rule);
                    sc = sin_cos(-phi);
                    ankle = self.rocker_ankle(sc);
                }
                let p = -phi;
                let c = chain(self.l3, self.l4, hip, dz, ankle);
                Ok(LegPose {
                    knee: c.knee,
                    ankle,
                    foot: self.foot.points_sc(ankle, sc, sc),
                    theta3: c.theta3,
                    theta4: c.kappa,
                    sin_cos: c.sin_cos(c.knee_sc),
                    pitch: p,
                    theta6: 0.0,
                    gap: c.gap,
                })
            }
        }
    }

    /// Ankle of the foot turned about its heel to pitch p (heel up +; the sole angle is −p),
    /// given (sin p, cos p).
    fn rocker_ankle(&self, sc: (f64, f64)) -> [f64; 2] {
        let heel = [self.ankle_x - self.foot.l8, 0.0];
        let off = crate::kinematics::foot::rotate([-self.foot.l8, -self.foot.l9], sc);
        [heel[0] - off[0], heel[1] - off[1]]
    }

    /// Whether the straight leg falls short of the hip from an ankle at `ankle`.
    fn too_far(&self, hip: [f64; 2], dz: f64, ankle: [f64; 2]) -> bool {
        let l1 = self.l3 + self.l4;
        ((hip[0] - ankle[0]).powi(2) + (hip[1] - ankle[1]).powi(2) + dz * dz).sqrt() > l1
    }

    /// The heel rocker's sole angle when the straight leg cannot reach the hip with the rule's
    /// (the caller tests that, the hip being behind the ankle): the smallest angle at which it
    /// can \[ours\]: the telescopic leg is longer than the anatomical one just after heel strike
    /// (w* > l1 at most speeds, spec §7 "known geometric tension"), so the foot comes down as
    /// the hip passes over it. Bisection to 1e-12 rad (the knee is acos of the leg's extension
    /// there, so the bisection's last bits set it), steered by the closed form
    /// ([`roots::bisect_with_guess`]): the ankle turns about the heel, so the angle is the first
    /// on (rule, π/3] where that circle meets the one of in-plane radius √(l1² − dz²) about the
    /// hip.
    fn reach_limited_sole(&self, hip: [f64; 2], dz: f64, rule: f64) -> f64 {
        let l1 = self.l3 + self.l4;
        let too_far = |phi: f64| self.too_far(hip, dz, self.rocker_ankle(sin_cos(-phi)));
        if too_far(FRAC_PI_3) {
            return FRAC_PI_3;
        }
        // the leg reaches at π/3 and not at the rule: the circles meet in between (NaN if
        // round-off hides where); the pitch is −φ
        let heel = Arc::new(
            [self.ankle_x - self.foot.l8, 0.0],
            [-self.foot.l8, -self.foot.l9],
        );
        let guess = heel
            .pitches_at(hip, (l1 * l1 - dz * dz).sqrt())
            .and_then(|roots| first_in(roots.map(|p| -p), rule, FRAC_PI_3))
            .unwrap_or(f64::NAN);
        roots::bisect_with_guess(
            |phi| !too_far(phi),
            FRAC_PI_3,
            rule,
            1e-12,
            guess,
            GUESS_SLACK,
        )
    }

    /// The rolling foot's pose for knee flexion κ: the pitch solves |hip − ankle(p)| = a(κ), in
    /// closed form: the ankle turns about the metatarsal joint while p ≤ θ6_max, then about the
    /// toe tip, and the pitch is the smallest on [0, MAX_PITCH] where that circle meets the one
    /// of in-plane radius √(a² − dz²) about the hip (the distance first falls as the heel rises,
    /// then, past a right angle, grows again).
    fn rolling_pose(&self, hip: [f64; 2], dz: f64, kappa: f64) -> Result<LegPose, GeometryError> {
        let knee_sc = sin_cos(kappa);
        let a = reach(self.l3, self.l4, knee_sc.1);
        let Foot { h12, l9, l13, .. } = self.foot;
        let meta_x = self.ankle_x + h12;
        // the flat foot's ankle, [`Self::rolling`] at p = 0 without its sin_cos(0) = (0, 1)
        let flat = [meta_x - h12, l9];
        let f0 = ((hip[0] - flat[0]).powi(2) + (hip[1] - flat[1]).powi(2) + dz * dz).sqrt() - a;
        if f0 < 0.0 {
            // the hip is nearer than a(κ) even with the foot flat: the foot stays flat and the
            // knee flexes by the distance [ours] (the prescribed curve resumes where it meets it)
            let ankle = [self.ankle_x, self.foot.l9];
            let c = chain(self.l3, self.l4, hip, dz, ankle);
            return Ok(LegPose {
                knee: c.knee,
                ankle,
                foot: self.foot.points(ankle, 0.0, 0.0),
                theta3: c.theta3,
                theta4: c.kappa,
                sin_cos: c.sin_cos(c.knee_sc),
                pitch: 0.0,
                theta6: 0.0,
                gap: 0.0,
            });
        }
        let p = if f0.abs() < 1e-13 {
            0.0
        } else {
            let t6 = self.theta6_max;
            // Arc::new([meta_x, 0], [h12, −l9]) with the foot's constants
            let about_meta = || {
                let (radius, phase) = self.foot.meta_reach();
                Arc {
                    pivot: [meta_x, 0.0],
                    radius,
                    phase,
                }
            };
            let about_toe = || {
                // pitch([l13, 0], p − θ6_max) = pitch(pitch([l13, 0], −θ6_max), p)
                let (s6, c6) = t6.sin_cos();
                Arc::new([meta_x + l13, 0.0], [h12 + l13 * c6, -l9 + l13 * s6])
            };
            let b = (a * a - dz * dz).sqrt();
            let first = |arc: &dyn Fn() -> Arc, lo: f64, hi: f64| {
                if lo <= hi {
                    arc()
                        .pitches_at(hip, b)
                        .and_then(|roots| first_in(roots, lo, hi))
                } else {
                    None
                }
            };
            first(&about_meta, 0.0, t6.min(MAX_PITCH))
                .or_else(|| first(&about_toe, t6.max(0.0), MAX_PITCH))
                .ok_or(GeometryError::RollingFootOutOfReach {
                    distance: a,
                    knee_flexion: kappa,
                })?
        };
        let (ankle, theta6, foot) = self.rolling(p);
        let c = chain(self.l3, self.l4, hip, dz, ankle);
        Ok(LegPose {
            knee: c.knee,
            ankle,
            foot,
            theta3: c.theta3,
            theta4: kappa,
            sin_cos: c.sin_cos(knee_sc),
            pitch: p,
            theta6,
            gap: 0.0,
        })
    }

    /// Ankle dorsiflexion of a pose (rad): the shank's in-plane lean relative to the foot.
    pub(crate) fn dorsiflexion(pose: &LegPose) -> f64 {
        pose.theta3 + pose.theta4 - pose.pitch
    }

    /// Find heel-off after foot flat: the first time on [t_from, t_to] where the foot is flat and
    /// its ankle dorsiflexion reaches θ5_max or the leg falls short of the hip; `hip(t)` gives the hip
    /// joint and its lateral offset. The knee curve then runs from the flat-foot knee and its rate
    /// there to κ_TO at `t_toe_off`. Leaves `heel_off` empty when the foot stays flat.
    pub fn find_heel_off(
        &mut self,
        hip: impl Fn(f64) -> ([f64; 2], f64),
        t_from: f64,
        t_to: f64,
        t_toe_off: f64,
        kappa_to: f64,
    ) -> Result<(), GeometryError> {
        let flat = |t: f64| {
            let (h, dz) = hip(t);
            self.pose(h, dz, t)
        };
        // the trigger as a sign: how far past θ5_max the flat foot's ankle is, or how far the
        // leg falls short of the hip where it does (positive: heel-off); −1 while the foot is
        // not flat
        let past = |t: f64| -> Result<f64, GeometryError> {
            let p = flat(t)?;
            Ok(if p.pitch != 0.0 {
                -1.0
            } else if p.gap > 0.0 {
                p.gap
            } else {
                Self::dorsiflexion(&p) - self.theta5_max
            })
        };
        let t_from = t_from.max(self.t_hs + self.t_fgm);
        // a scan every ≈ 20 ms (the trigger, once on, stays on until toe-off), then the Illinois
        // method to 1e-9 s (the hip moves ≤ 3e-9 m; it needs far fewer poses than bisection)
        const SCAN: usize = 24;
        let points = (1..=SCAN).map(|k| t_from + (t_to - t_from) * k as f64 / SCAN as f64);
        // (an error ends the scan as the trigger does, and is returned)
        let on = |g: &Result<f64, GeometryError>| g.as_ref().map_or(true, |&g| g >= 0.0);
        let Some(((lo, g_lo), (t, g))) = roots::scan(t_from, points, past, on) else {
            return Ok(());
        };
        let hi = (t, g?);
        let g_lo = match g_lo {
            Some(g) => g?,
            None => past(lo)?,
        };
        // on at foot flat already: heel-off there (else the last time it is off; far into a long
        // walk the spacing of doubles can stop the search short of 1e-9 s, at its budget)
        let t0 = if g_lo >= 0.0 {
            lo
        } else {
            let error = std::cell::RefCell::new(None);
            let sign = |t: f64| {
                past(t).unwrap_or_else(|e| {
                    error.borrow_mut().get_or_insert(e);
                    f64::NAN
                })
            };
            let (t0, _) = roots::illinois(sign, (lo, g_lo), hi, 1e-9, 60);
            if let Some(e) = error.into_inner() {
                return Err(e);
            }
            t0
        };
        // a heel-off where the leg falls short of a foot that was not flat just before is a
        // jump of the foot's pitch from its heel to its metatarsal joint (a root found at a
        // continuous trigger has a gap of at most the hip's speed × 1e-9 s)
        let gap = flat(t0 + 1e-7)?.gap;
        if gap > FLAT_REACH_SLACK {
            return Err(GeometryError::FlatFootOutOfReach { gap });
        }
        let h = 1e-6;
        let k0 = flat(t0)?.theta4;
        let rate = (k0 - flat(t0 - h)?.theta4) / h;
        self.heel_off = Some(KneeCurve::new(t0, k0, rate, t_toe_off, kappa_to));
        Ok(())
    }

    /// Complete the stance into the next step: the knee curve is re-anchored at `t_hs_next` (its
    /// value and rate there, or the flat foot's when the heel is still down, the rate then from
    /// the right) and reaches κ_TO at the actual toe-off `t_toe_off`; `hip(t)` gives the hip
    /// joint and its lateral offset for t ≥ `t_hs_next`.
    pub(crate) fn continue_to_toe_off(
        &mut self,
        hip: impl Fn(f64) -> ([f64; 2], f64),
        t_hs_next: f64,
        t_toe_off: f64,
        kappa_to: f64,
    ) -> Result<(), GeometryError> {
        // the same toe-off rate as planned at heel-off: in a steady gait the re-anchored cubic is
        // the one planned
        let planned = self.heel_off.map(|k| k.rate_to);
        let (kappa0, rate0) = match self.knee_curve(t_hs_next) {
            Some(k) => k,
            None => {
                let h = 1e-6;
                let knee = |t: f64| {
                    let (p, dz) = hip(t);
                    self.pose(p, dz, t).map(|p| p.theta4)
                };
                let k0 = knee(t_hs_next)?;
                (k0, (knee(t_hs_next + h)? - k0) / h)
            }
        };
        let mut curve = KneeCurve::new(t_hs_next, kappa0, rate0, t_toe_off, kappa_to);
        if let Some(rate_to) = planned {
            curve.rate_to = rate_to;
        }
        self.to_toe_off = Some(curve);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The heel rocker's sole: 1 at heel strike, 0 at foot flat with zero rate, its rate
    /// −(3/2)(1 − s²) against central differences, falling in size all the way.
    #[test]
    fn the_rocker_sole_lands_with_a_falling_rate() {
        assert_eq!(rocker_sole(0.0), 1.0);
        assert_eq!(rocker_sole(1.0), 0.0);
        let h = 1e-6;
        let mut last = f64::INFINITY;
        for i in 0..=100 {
            let s = i as f64 / 100.0;
            let fd = (rocker_sole(s + h) - rocker_sole(s - h)) / (2.0 * h);
            assert!((fd + 1.5 * (1.0 - s * s)).abs() < 1e-8, "s {s}: {fd}");
            assert!(-fd <= last + 1e-9, "s {s}");
            last = -fd;
        }
    }

    fn leg() -> (Body, StanceLeg) {
        let b = Body::standard(1.8, 80.0).unwrap();
        let l = StanceLeg::new(
            &b,
            0.0,
            0.0,
            20f64.to_radians(),
            0.078,
            12f64.to_radians(),
            35f64.to_radians(),
        );
        (b, l)
    }

    fn dist(u: [f64; 2], v: [f64; 2], dz: f64) -> f64 {
        ((u[0] - v[0]).powi(2) + (u[1] - v[1]).powi(2) + dz * dz).sqrt()
    }

    /// A hip that passes over the ankle higher than the straight leg reaches from the flat foot
    /// (l9 + √(l1² − dz²), by hand) is refused, naming the gap; 2 mm lower, the foot goes flat
    /// and its heel rises as usual.
    #[test]
    fn a_hip_out_of_the_flat_foots_reach_is_refused() {
        let (b, mut l) = leg();
        let dz = 0.05;
        let top = l.foot.l9 + (b.l1 * b.l1 - dz * dz).sqrt();
        let hip = |y: f64| move |t: f64| ([-0.35 + 1.4 * t, y], dz);
        match l.find_heel_off(hip(top + 0.002), 0.0, 0.55, 0.68, 0.7) {
            Err(GeometryError::FlatFootOutOfReach { gap }) => {
                assert!((gap - 0.002).abs() < 1e-5, "{gap}")
            }
            other => panic!("{other:?}"),
        }
        l.find_heel_off(hip(top - 0.002), 0.0, 0.55, 0.68, 0.7)
            .unwrap();
        assert!(l.heel_off.is_some_and(|k| k.t0 > 0.25));
    }

    /// In every foot rule the chain closes (|hip − knee| = l3, |knee − ankle| = l4 in the leg's
    /// plane), the contact point stays put and no point of the foot is under the ground.
    #[test]
    fn chain_closes_and_contacts_hold() {
        let (b, mut l) = leg();
        let dz = 0.03;
        let hip = |t: f64| ([-0.35 + 1.4 * t, 0.88 + 0.03 * (3.0 * t).sin()], dz);
        l.find_heel_off(hip, 0.0, 0.55, 0.68, 0.7).unwrap();
        assert!(l.heel_off.is_some());
        let mut phases = std::collections::BTreeSet::new();
        for i in 0..=68 {
            let t = 0.01 * i as f64;
            let (h, dz) = hip(t);
            let p = l.pose(h, dz, t).unwrap();
            // in the leg's plane the hip is the ankle plus the unfolded drop √(Δy² + dz²)
            let hip_plane = [h[0], p.ankle[1] + (h[1] - p.ankle[1]).hypot(dz)];
            if p.gap == 0.0 {
                assert!((dist(hip_plane, p.knee, 0.0) - b.l3).abs() < 1e-9, "t {t}");
                assert!((dist(p.knee, p.ankle, 0.0) - b.l4).abs() < 1e-9, "t {t}");
            }
            assert!(p.foot.lowest() > -1e-12, "t {t}: {:?}", p.foot);
            phases.insert(format!("{:?}", l.phase(t)));
            match l.phase(t) {
                FootPhase::HeelRocker => {
                    assert!(
                        (p.foot.heel[0] + l.foot.l8).abs() < 1e-12 && p.foot.heel[1].abs() < 1e-12
                    )
                }
                FootPhase::FootFlat => assert!(p.pitch == 0.0 && p.foot.heel[1].abs() < 1e-12),
                FootPhase::Rolling => {
                    assert!(
                        p.foot.toe[1].abs() < 1e-12,
                        "t {t}: the toe stays on the ground"
                    );
                    assert!(
                        (dist(h, p.ankle, dz) - reach(b.l3, b.l4, p.theta4.cos())).abs() < 1e-9
                    );
                }
            }
        }
        assert_eq!(phases.len(), 3, "every rule was exercised: {phases:?}");
    }

    /// Every pose carries the (sin, cos) of its θ3 and θ3 + θ4, and the rolling foot's arc
    /// about M from the foot's constants is the one built from its vector.
    #[test]
    fn poses_carry_their_angles_sines_and_cosines() {
        let (_, mut l) = leg();
        let hip = |t: f64| ([-0.35 + 1.4 * t, 0.88 + 0.03 * (3.0 * t).sin()], 0.03);
        l.find_heel_off(hip, 0.0, 0.55, 0.68, 0.7).unwrap();
        for i in 0..=68 {
            let t = 0.01 * i as f64;
            let (h, dz) = hip(t);
            let p = l.pose(h, dz, t).unwrap();
            let [(s3, c3), (ss, cs)] = p.sin_cos;
            let (s, c) = (p.theta3 + p.theta4).sin_cos();
            for e in [s3 - p.theta3.sin(), c3 - p.theta3.cos(), ss - s, cs - c] {
                assert!(e.abs() < 1e-15, "t {t}: {e}");
            }
        }
        let f = l.foot;
        let arc = Arc::new([0.3, 0.0], [f.h12, -f.l9]);
        let (radius, phase) = f.meta_reach();
        assert_eq!((arc.radius, arc.phase), (radius, phase));
    }

    /// The heel rocker starts at φ_hs going down at 1.5 × the line's rate φ_hs / t_FGM and ends
    /// flat with zero rate: near its ends the sole angle is φ_hs (1 − 3δ/2 + δ³/2) and
    /// φ_hs (3δ²/2 − δ³/2), δ the time from the end over t_FGM.
    #[test]
    fn heel_rocker_runs_from_strike_to_flat() {
        let (_, l) = leg();
        let hip = [-0.3, 0.88];
        let p0 = l.pose(hip, 0.0, 0.0).unwrap();
        assert!((p0.pitch + l.sole_hs).abs() < 1e-15);
        let pf = l.pose(hip, 0.0, l.t_fgm).unwrap();
        assert!(pf.pitch.abs() < 1e-15);
        let d = 1e-4 / l.t_fgm;
        let ps = l.pose(hip, 0.0, 1e-4).unwrap();
        assert!((ps.pitch + l.sole_hs * (1.0 - 1.5 * d + 0.5 * d * d * d)).abs() < 1e-12);
        let pe = l.pose(hip, 0.0, l.t_fgm - 1e-4).unwrap();
        assert!((pe.pitch + l.sole_hs * (1.5 * d * d - 0.5 * d * d * d)).abs() < 1e-12);
    }

    /// Heel-off is found where the flat-foot dorsiflexion reaches θ5_max, and the knee is C¹
    /// through it and through the re-anchoring at the next heel strike.
    #[test]
    fn heel_off_is_where_the_ankle_reaches_its_limit_and_the_knee_is_smooth() {
        let (_, mut l) = leg();
        let hip = |t: f64| ([-0.3 + 1.4 * t, 0.885], 0.02);
        l.find_heel_off(hip, 0.0, 0.55, 0.68, 0.7).unwrap();
        let k = l
            .heel_off
            .expect("the hip passes far enough ahead to lift the heel");
        let flat_before = {
            let mut f = l;
            f.heel_off = None;
            let (h, dz) = hip(k.t0);
            f.pose(h, dz, k.t0).unwrap()
        };
        assert!((StanceLeg::dorsiflexion(&flat_before) - l.theta5_max).abs() < 1e-6);
        let knee = |l: &StanceLeg, t: f64| {
            let (h, dz) = hip(t);
            l.pose(h, dz, t).unwrap().theta4
        };
        let e = 1e-7;
        let (a, b) = (knee(&l, k.t0 - e), knee(&l, k.t0 + e));
        assert!((a - b).abs() < 1e-5, "knee continuous at heel-off: {a} {b}");
        l.continue_to_toe_off(hip, 0.55, 0.70, 0.7).unwrap();
        let (a, b) = (knee(&l, 0.55 - e), knee(&l, 0.55 + e));
        assert!((a - b).abs() < 1e-5);
        let ra = (knee(&l, 0.55 - e) - knee(&l, 0.55 - 2.0 * e)) / e;
        let rb = (knee(&l, 0.55 + 2.0 * e) - knee(&l, 0.55 + e)) / e;
        assert!((ra - rb).abs() < 1e-3 * ra.abs().max(1.0), "{ra} {rb}");
        assert!((knee(&l, 0.70) - 0.7).abs() < 1e-12);
    }
}
