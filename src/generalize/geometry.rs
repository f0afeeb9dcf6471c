//! The walking constraints the generalization keeps (Ko & Badler 1992 §2.1, §2.5, §3): the
//! attribute functions μ1…μ4 of the step length (eqs. 5, 6, 21, 24), the hip at heel strike
//! (eqs. 7–11), and the swing ankle just before toe-off and right after heel strike (Lemma 1,
//! corrected: docs/generalize.md).
//!
//! Coordinates: x forward, y up (m), the origin at N of the foot that stands (the point of its
//! sole under its ankle when it is flat) on the floor.
use serde::{Deserialize, Serialize};

use crate::generalize::condition::BodyCondition;
use crate::generalize::error::GeneralizeError;
use crate::numerics::roots;

/// What generalization keeps of the prototype S* (eqs. 5, 6, 21, 24): its step length per leg
/// length sl* / ll(S*), its attributes at heel strike and toe-off μ1*…μ4*, the α slopes, and
/// \[ours\] where its hip stands at heel strike (docs/generalize.md): ahead of the trailing foot's
/// N by `hip_lead` step lengths (the paper: ½), and above eq. 11's height by `hip_offset` leg
/// lengths (the paper: 0). Every generalization carries these unchanged.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Character {
    /// sl* / ll(S*): the prototype's step length in its leg lengths (eqs. 5, 6, 21, 24 take
    /// the prototype's step length normalized, as they do the new one).
    pub step_length: f64,
    /// μ1*: the leading knee's flexion at heel strike (rad; 0 straight).
    pub knee_at_strike: f64,
    /// μ2*: the landing foot's toes-up angle at heel strike (rad).
    pub foot_at_strike: f64,
    /// μ3*: the foot's heel-up angle at toe-off (rad).
    pub foot_at_toe_off: f64,
    /// μ4*: the toes' angle from the floor at toe-off (rad; the toe tip down, the ball up).
    pub meta_at_toe_off: f64,
    /// α1…α4 (rad per leg length of step length).
    pub alpha: [f64; 4],
    /// The hip's x at heel strike, from the trailing foot's N, in step lengths.
    pub hip_lead: f64,
    /// The hip's height at heel strike above eq. 11's, in leg lengths.
    pub hip_offset: f64,
}

/// \[ours\] The walk's pelvis at heel strike besides its width (a body length): its rotation
/// (the determinants' amplitude: the leading hip joint ahead of the pelvis centre by
/// ½ width · sin A) and the step width (each ankle ½ step width from the walk's line, so the
/// leading leg spans ½ width · cos A − ½ step width sideways). Both 0: the paper's sagittal
/// point pelvis.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pelvis {
    /// The pelvic rotation's amplitude A (rad).
    pub rotation: f64,
    /// The ankles' lateral distance (m).
    pub step_width: f64,
}

impl Pelvis {
    /// The leading hip joint from the pelvis centre at heel strike, (forward, sideways from the
    /// ankle) for a pelvis of `width`.
    pub fn leading_hip(&self, width: f64) -> [f64; 2] {
        let (s, c) = self.rotation.sin_cos();
        [0.5 * width * s, 0.5 * width * c - 0.5 * self.step_width]
    }

    /// Both finite, the step width ≥ 0.
    pub fn check(&self) -> Result<(), GeneralizeError> {
        if !(self.rotation.is_finite() && self.step_width.is_finite() && self.step_width >= 0.0) {
            return Err(GeneralizeError::invalid(
                "pelvis",
                format!(
                    "rotation {} rad, step width {} m: finite numbers, the width ≥ 0, are \
                     required",
                    self.rotation, self.step_width
                ),
            ));
        }
        Ok(())
    }
}

/// μ1…μ4 at one walk condition (S, sl).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mu {
    /// μ1: the knee's flexion at heel strike (rad).
    pub knee: f64,
    /// μ2: the foot's toes-up angle at heel strike (rad).
    pub strike: f64,
    /// μ3: the foot's heel-up angle at toe-off (rad).
    pub toe_off: f64,
    /// μ4: the toes' angle at toe-off (rad).
    pub meta: f64,
}

impl Character {
    /// μ1…μ4 of a body with leg length `leg_length` at step length `sl`: μ_i = α_i (sl / ll −
    /// sl*) + μ_i* (eqs. 6, 21, 24; eq. 5 with the knee's flexion, π minus the paper's knee
    /// angle, so that its − α1 becomes + α1).
    pub fn mu(&self, leg_length: f64, sl: f64) -> Mu {
        let x = sl / leg_length - self.step_length;
        let [a1, a2, a3, a4] = self.alpha;
        Mu {
            knee: a1 * x + self.knee_at_strike,
            strike: a2 * x + self.foot_at_strike,
            toe_off: a3 * x + self.foot_at_toe_off,
            meta: a4 * x + self.meta_at_toe_off,
        }
    }

    /// Every number finite.
    pub fn check(&self) -> Result<(), GeneralizeError> {
        let values = [
            ("step_length", self.step_length),
            ("knee_at_strike", self.knee_at_strike),
            ("foot_at_strike", self.foot_at_strike),
            ("foot_at_toe_off", self.foot_at_toe_off),
            ("meta_at_toe_off", self.meta_at_toe_off),
            ("alpha1", self.alpha[0]),
            ("alpha2", self.alpha[1]),
            ("alpha3", self.alpha[2]),
            ("alpha4", self.alpha[3]),
            ("hip_lead", self.hip_lead),
            ("hip_offset", self.hip_offset),
        ];
        for (name, v) in values {
            if !v.is_finite() {
                return Err(GeneralizeError::invalid(
                    format!("character.{name}"),
                    format!("{v}: a finite number is required"),
                ));
            }
        }
        Ok(())
    }
}

/// The landing foot's ankle right after heel strike, (b2x, b2y) of Lemma 1 (eqs. 34–35): its heel
/// on the floor at sl − hN, the foot turned toes-up by μ2 about it.
pub fn ankle_after_strike(body: &BodyCondition, sl: f64, mu2: f64) -> [f64; 2] {
    let (ah, th) = (body.heel_to_ankle(), body.heel_angle());
    let (s, c) = (th + mu2).sin_cos();
    [sl - body.heel_to_n + ah * c, ah * s]
}

/// The trailing foot's ankle just before toe-off, (b1x, b1y) of Lemma 1 corrected \[ours\]: in
/// that foot's own frame (origin at its N), the toe tip on the floor at bN + bt, the toes at μ4
/// from the floor, the heel–ball line at μ3; the ball–ankle line then leaves the floor at
/// θb + μ3. The paper's eqs. 32–33 write μ3 for θb + μ3, which puts the flat foot's ankle on the
/// floor.
pub fn ankle_before_toe_off(body: &BodyCondition, mu3: f64, mu4: f64) -> [f64; 2] {
    let (bt, ab) = (body.ball_to_toe, body.ankle_to_ball());
    let (s4, c4) = mu4.sin_cos();
    let (s, c) = (body.ball_angle() + mu3).sin_cos();
    [body.ball_to_n + bt - bt * c4 - ab * c, bt * s4 + ab * s]
}

/// The hip (the pelvis centre) at heel strike after a step of `sl` (eqs. 7–11): the leading
/// leg's hip–ankle distance a1 from the knee flexion μ1 (eq. 7), its ankle A turned about the
/// heel by μ2 (eqs. 8–9), the pelvis centre `hip_lead` · sl ahead of the trailing foot's N (the
/// paper: sl / 2) and \[ours\] the leading hip joint ahead of it and beside the ankle by
/// [`Pelvis::leading_hip`], so that its sagittal reach is √(a1² − dz²) and a3 = √(reach² −
/// (x_A − x_joint)²) above A (eqs. 10–11); raised by `hip_offset` leg lengths. Err: the step is
/// too long for the leading leg to reach the hip.
pub fn hip_at_strike(
    body: &BodyCondition,
    character: &Character,
    pelvis: &Pelvis,
    sl: f64,
) -> Result<[f64; 2], GeneralizeError> {
    let ll = body.leg_length();
    match hip_height(body, character, pelvis, sl) {
        Some(y) => Ok([character.hip_lead * sl, y + character.hip_offset * ll]),
        None => Err(GeneralizeError::TooLong {
            step_length: sl,
            leg_length: ll,
            limit: longest_step(body, character, pelvis),
            reason: "its leading leg cannot reach the hip at heel strike (eq. 10)".into(),
        }),
    }
}

/// Eq. 11's height (without the offset), None where a3 has no real root.
fn hip_height(
    body: &BodyCondition,
    character: &Character,
    pelvis: &Pelvis,
    sl: f64,
) -> Option<f64> {
    let mu = character.mu(body.leg_length(), sl);
    let a1 = body.reach(mu.knee);
    let [ahead, dz] = pelvis.leading_hip(body.pelvis_width);
    let a = ankle_after_strike(body, sl, mu.strike);
    let dx = a[0] - character.hip_lead * sl - ahead;
    let a3 = a1 * a1 - dz * dz - dx * dx;
    (a3 >= 0.0).then(|| a[1] + a3.sqrt())
}

/// The longest step length for which [`hip_at_strike`] has a hip (to 1e-9 m), searched over
/// (0, 3 ll].
pub fn longest_step(body: &BodyCondition, character: &Character, pelvis: &Pelvis) -> f64 {
    let ok = |sl: f64| hip_height(body, character, pelvis, sl).is_some();
    let hi = 3.0 * body.leg_length();
    if ok(hi) {
        return hi;
    }
    let lo = 1e-6 * hi;
    if !ok(lo) {
        return 0.0;
    }
    roots::bisect(ok, lo, hi, 1e-9).0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::body::Body;

    fn body() -> BodyCondition {
        BodyCondition::of(&Body::standard(1.8, 80.0).unwrap())
    }

    const POINT: Pelvis = Pelvis {
        rotation: 0.0,
        step_width: 0.0,
    };

    fn character() -> Character {
        Character {
            step_length: 0.85,
            knee_at_strike: 0.07,
            foot_at_strike: 0.3,
            foot_at_toe_off: 0.9,
            meta_at_toe_off: 0.4,
            alpha: [0.0, 0.2, 0.3, 0.1],
            hip_lead: 0.5,
            hip_offset: 0.0,
        }
    }

    /// Lemma 1 with flat feet puts the ankle at (0, aN) of its own N (the paper's b1 put it on
    /// the floor); the toe tip stays at bN + bt and the heel at −hN for any angles (the pivots
    /// do not slide), and the ankle is at ah from the heel and ab from the ball.
    #[test]
    fn lemma_1_keeps_the_pivots_and_the_foots_shape() {
        let b = body();
        let a = ankle_before_toe_off(&b, 0.0, 0.0);
        assert!(a[0].abs() < 1e-15 && (a[1] - b.ankle_to_n).abs() < 1e-15);
        let a = ankle_after_strike(&b, 0.0, 0.0);
        assert!(a[0].abs() < 1e-15 && (a[1] - b.ankle_to_n).abs() < 1e-15);
        for (m3, m4) in [(0.3, 0.0), (0.7, 0.2), (1.1, 0.5)] {
            let a = ankle_before_toe_off(&b, m3, m4);
            // the ball from the toe tip, back along the toes
            let ball = [
                b.ball_to_n + b.ball_to_toe - b.ball_to_toe * m4.cos(),
                b.ball_to_toe * m4.sin(),
            ];
            let d = (a[0] - ball[0]).hypot(a[1] - ball[1]);
            assert!((d - b.ankle_to_ball()).abs() < 1e-15);
            // the heel–ball line at μ3 from the floor: the heel is hb behind the ball, down μ3
            let heel = [
                ball[0] - b.heel_to_ball() * m3.cos(),
                ball[1] + b.heel_to_ball() * m3.sin(),
            ];
            let d = (a[0] - heel[0]).hypot(a[1] - heel[1]);
            assert!((d - b.heel_to_ankle()).abs() < 1e-14, "{d}");
        }
        for m2 in [0.1, 0.4] {
            let a = ankle_after_strike(&b, 0.8, m2);
            let heel = [0.8 - b.heel_to_n, 0.0];
            let d = (a[0] - heel[0]).hypot(a[1] - heel[1]);
            assert!((d - b.heel_to_ankle()).abs() < 1e-15);
            // turning toes-up by μ2 about the heel: the heel → ankle line at θh + μ2
            let angle = (a[1] - heel[1]).atan2(a[0] - heel[0]);
            assert!((angle - b.heel_angle() - m2).abs() < 1e-14);
        }
    }

    /// Eq. 11: the leading leg reaches the hip with its knee at μ1, the hip is `hip_lead` sl
    /// ahead, the offset raises it by so many leg lengths; beyond the longest step it is the
    /// typed error naming the limit.
    #[test]
    fn the_hip_at_heel_strike_is_reached_by_the_leading_leg() {
        let mut b = body();
        b.pelvis_width = 0.0;
        let mut c = character();
        for sl in [0.4, 0.7, 0.9] {
            let h = hip_at_strike(&b, &c, &POINT, sl).unwrap();
            let mu = c.mu(b.leg_length(), sl);
            let a = ankle_after_strike(&b, sl, mu.strike);
            let d = (h[0] - a[0]).hypot(h[1] - a[1]);
            assert!((d - b.reach(mu.knee)).abs() < 1e-12);
            assert!((h[0] - 0.5 * sl).abs() < 1e-15);
            assert!(h[1] > a[1]);
        }
        let y0 = hip_at_strike(&b, &c, &POINT, 0.7).unwrap()[1];
        c.hip_offset = 0.01;
        let y1 = hip_at_strike(&b, &c, &POINT, 0.7).unwrap()[1];
        assert!((y1 - y0 - 0.01 * b.leg_length()).abs() < 1e-14);
        let limit = longest_step(&b, &c, &POINT);
        assert!(hip_at_strike(&b, &c, &POINT, limit).is_ok());
        let e = hip_at_strike(&b, &c, &POINT, limit + 1e-6).unwrap_err();
        match e {
            GeneralizeError::TooLong { limit: l, .. } => assert_eq!(l, limit),
            e => panic!("{e}"),
        }
        // a pelvis of width w rotated by A: the leading hip joint, (w/2 sin A) ahead of the
        // centre and (w/2 cos A − step width/2) beside the ankle, is a1 from it
        let pelvis = Pelvis {
            rotation: 0.07,
            step_width: 0.1,
        };
        let wide = BodyCondition {
            pelvis_width: 0.18,
            ..b
        };
        let h = hip_at_strike(&wide, &c, &pelvis, 0.7).unwrap();
        let mu = c.mu(b.leg_length(), 0.7);
        let a = ankle_after_strike(&b, 0.7, mu.strike);
        let joint = [
            h[0] + 0.09 * 0.07f64.sin(),
            h[1] - c.hip_offset * b.leg_length(),
        ];
        let dz = 0.09 * 0.07f64.cos() - 0.05;
        let d = ((joint[0] - a[0]).powi(2) + (joint[1] - a[1]).powi(2) + dz * dz).sqrt();
        assert!((d - b.reach(mu.knee)).abs() < 1e-12, "{d}");
        // a longer step lowers the hip (Figure 4)
        let h = |sl| hip_at_strike(&b, &c, &POINT, sl).unwrap()[1];
        assert!(h(0.5) > h(0.7) && h(0.7) > h(0.9));
    }

    /// The μ functions are invariant under scaling the body and the step together (eq. 124).
    #[test]
    fn mu_is_invariant_under_similarity() {
        let c = character();
        let (m, n) = (c.mu(0.9, 0.7), c.mu(1.8, 1.4));
        assert!((m.strike - n.strike).abs() < 1e-15 && (m.toe_off - n.toe_off).abs() < 1e-15);
        let at = c.mu(1.0, 0.85);
        assert_eq!(at.meta, c.meta_at_toe_off);
    }
}
