//! The body condition B(S) (Ko & Badler 1992 §1, eq. 3, Figure 7): the segment lengths the walk
//! data depends on, the leg length ll = thigh + shin, and the foot's lengths and angles.
//!
//! The foot is a rigid triangle heel – ankle – ball (1st metatarsophalangeal joint) with the toes
//! a segment from the ball to the toe tip; heel, ball and toe tip lie on the sole. With the foot
//! flat, N is the point of the sole under the ankle: hN = heel to N, aN = ankle to N (the ankle's
//! height), bN = ball to N, bt = ball to toe tip. In klaw's body (Table B-1) these are l8, l9,
//! √(l12² − l9²) and l13.
use serde::{Deserialize, Serialize};

use crate::generalize::error::GeneralizeError;
use crate::model::body::Body;

/// B(S): thigh, shin and the foot (m).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyCondition {
    /// Thigh, hip to knee (m; klaw's l3).
    pub thigh: f64,
    /// Shin, knee to ankle (m; klaw's l4).
    pub shin: f64,
    /// hN: the heel behind N, foot flat (m; l8).
    pub heel_to_n: f64,
    /// aN: the ankle above N, foot flat (m; l9).
    pub ankle_to_n: f64,
    /// bN: the ball ahead of N, foot flat (m; √(l12² − l9²)).
    pub ball_to_n: f64,
    /// bt: ball to toe tip (m; l13; 0 for a foot without toes).
    pub ball_to_toe: f64,
    /// \[ours\] The pelvis's width, hip joint to hip joint (m; l0; 0 for the paper's point
    /// pelvis): eq. 11 places the leading hip joint.
    pub pelvis_width: f64,
}

impl BodyCondition {
    /// The body condition of a klaw body.
    pub fn of(body: &Body) -> Self {
        BodyCondition {
            thigh: body.l3,
            shin: body.l4,
            heel_to_n: body.l8,
            ankle_to_n: body.l9,
            ball_to_n: body.ankle_to_metatarsal_horizontal(),
            ball_to_toe: body.l13,
            pelvis_width: body.l0,
        }
    }

    /// The body condition of a foot given as the paper's Figure 7 gives it: the sides of its
    /// triangle ah (heel–ankle), ab (ankle–ball), hb (heel–ball) and the toe bt; the angles by
    /// the law of cosines, hN = ah cos θh, aN = ah sin θh, bN = hb − hN.
    pub fn from_triangle(
        thigh: f64,
        shin: f64,
        [ah, ab, hb, bt]: [f64; 4],
        pelvis_width: f64,
    ) -> Result<Self, GeneralizeError> {
        let cos_heel = (ah * ah + hb * hb - ab * ab) / (2.0 * ah * hb);
        let cos_ball = (ab * ab + hb * hb - ah * ah) / (2.0 * ab * hb);
        if !(cos_heel > 0.0 && cos_heel < 1.0 && cos_ball > 0.0 && cos_ball < 1.0) {
            return Err(GeneralizeError::invalid(
                "foot",
                format!(
                    "heel–ankle {ah} m, ankle–ball {ab} m and heel–ball {hb} m make no foot: the \
                     ankle must stand above the sole between heel and ball (both base angles \
                     acute)"
                ),
            ));
        }
        let heel = cos_heel.acos();
        let c = BodyCondition {
            thigh,
            shin,
            heel_to_n: ah * cos_heel,
            ankle_to_n: ah * heel.sin(),
            ball_to_n: hb - ah * cos_heel,
            ball_to_toe: bt,
            pelvis_width,
        };
        c.check()?;
        Ok(c)
    }

    /// Every length finite and positive (the toe may be 0).
    pub fn check(&self) -> Result<(), GeneralizeError> {
        for (name, v, zero_ok) in [
            ("thigh", self.thigh, false),
            ("shin", self.shin, false),
            ("heel_to_n", self.heel_to_n, false),
            ("ankle_to_n", self.ankle_to_n, false),
            ("ball_to_n", self.ball_to_n, false),
            ("ball_to_toe", self.ball_to_toe, true),
            ("pelvis_width", self.pelvis_width, true),
        ] {
            if !(v.is_finite() && (v > 0.0 || (zero_ok && v == 0.0))) {
                let what = if zero_ok { "≥ 0" } else { "> 0" };
                return Err(GeneralizeError::invalid(
                    format!("body.{name}"),
                    format!("{v} m: a finite length {what} is required"),
                ));
            }
        }
        Ok(())
    }

    /// ll(S) = thigh + shin (eq. 3's leg length).
    pub fn leg_length(&self) -> f64 {
        self.thigh + self.shin
    }

    /// ah: heel to ankle.
    pub fn heel_to_ankle(&self) -> f64 {
        self.heel_to_n.hypot(self.ankle_to_n)
    }

    /// ab: ankle to ball.
    pub fn ankle_to_ball(&self) -> f64 {
        self.ball_to_n.hypot(self.ankle_to_n)
    }

    /// hb: heel to ball.
    pub fn heel_to_ball(&self) -> f64 {
        self.heel_to_n + self.ball_to_n
    }

    /// θh: the heel's inner angle, between the sole and the heel–ankle line.
    pub fn heel_angle(&self) -> f64 {
        self.ankle_to_n.atan2(self.heel_to_n)
    }

    /// θb: the ball's inner angle, between the sole and the ball–ankle line.
    pub fn ball_angle(&self) -> f64 {
        self.ankle_to_n.atan2(self.ball_to_n)
    }

    /// θa: the ankle's inner angle, π − θh − θb.
    pub fn ankle_angle(&self) -> f64 {
        std::f64::consts::PI - self.heel_angle() - self.ball_angle()
    }

    /// Every length times `a`: the body αS of §1.
    pub fn scaled(&self, a: f64) -> Self {
        BodyCondition {
            thigh: a * self.thigh,
            shin: a * self.shin,
            heel_to_n: a * self.heel_to_n,
            ankle_to_n: a * self.ankle_to_n,
            ball_to_n: a * self.ball_to_n,
            ball_to_toe: a * self.ball_to_toe,
            pelvis_width: a * self.pelvis_width,
        }
    }

    /// The hip–ankle distance of a leg whose knee is flexed by κ (rad; 0 straight): eq. 7,
    /// a1² = thigh² + shin² + 2 thigh shin cos κ (the paper's knee angle is the inner one, π − κ).
    pub fn reach(&self, knee_flexion: f64) -> f64 {
        let (t, s) = (self.thigh, self.shin);
        (t * t + s * s + 2.0 * t * s * knee_flexion.cos()).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's foot table (§6): the printed angles add up to π, and the lengths under the
    /// ankle follow from the triangle's sides as printed, to the table's rounding: hN = 5.093,
    /// aN = 5.680, bN = 10.80 (the measured subject), 3.450, 13.04, 11.74 (the animated figure);
    /// the leg lengths 73.90 and 75.25 are thigh + shin.
    #[test]
    fn the_papers_foot_table_is_reproduced() {
        // ah, ab, hb, bt; θb, θh, θa; hN, aN, bN; shin, thigh, ll
        let columns = [
            (
                [7.629, 12.20, 15.89, 7.095],
                [0.4842, 0.8400, 1.818],
                [5.093, 5.680, 10.80],
                [38.05, 35.85, 73.90],
            ),
            (
                [13.49, 17.55, 15.19, 7.200],
                [0.8378, 1.312, 0.9916],
                [3.450, 13.04, 11.74],
                [34.53, 40.72, 75.25],
            ),
        ];
        for (sides, angles, under, [shin, thigh, ll]) in columns {
            assert!((angles.iter().sum::<f64>() - std::f64::consts::PI).abs() < 1e-3);
            let c = BodyCondition::from_triangle(thigh, shin, sides, 0.0).unwrap();
            // the printed angles, 4 significant digits
            assert!(
                (c.ball_angle() - angles[0]).abs() < 2e-3,
                "{}",
                c.ball_angle()
            );
            assert!(
                (c.heel_angle() - angles[1]).abs() < 2e-3,
                "{}",
                c.heel_angle()
            );
            assert!(
                (c.ankle_angle() - angles[2]).abs() < 2e-3,
                "{}",
                c.ankle_angle()
            );
            // the printed lengths to their last digit (and the table's rounding of ah)
            for (got, want) in [c.heel_to_n, c.ankle_to_n, c.ball_to_n].iter().zip(under) {
                assert!((got - want).abs() < 0.012, "{got} vs {want}");
            }
            assert!((c.leg_length() - ll).abs() < 1e-9);
            assert!((c.heel_to_ankle() - sides[0]).abs() < 1e-12);
            assert!((c.ankle_to_ball() - sides[1]).abs() < 1e-12);
            assert!((c.heel_to_ball() - sides[2]).abs() < 1e-12);
        }
    }

    /// Klaw's foot is Table B-1's: ah = l11, ab = l12; eq. 7 is the body's hip–ankle distance.
    #[test]
    fn klaws_body_gives_its_table_lengths() {
        let b = Body::standard(1.8, 80.0).unwrap();
        let c = BodyCondition::of(&b);
        assert!((c.heel_to_ankle() - b.l11).abs() < 1e-15);
        assert!((c.ankle_to_ball() - b.l12).abs() < 1e-15);
        assert!((c.leg_length() - b.l1).abs() < 1e-15);
        for k in [0.0, 0.3, 1.2] {
            assert!((c.reach(k) - b.hip_ankle_distance(k)).abs() < 1e-15);
        }
        assert!(
            BodyCondition::from_triangle(0.4, 0.4, [0.05, 0.1, 0.2, 0.05], 0.0).is_err(),
            "no triangle"
        );
        assert!(
            BodyCondition::from_triangle(0.4, 0.4, [0.05, 0.25, 0.2, 0.05], 0.0).is_err(),
            "the ankle ahead of the ball"
        );
    }
}
