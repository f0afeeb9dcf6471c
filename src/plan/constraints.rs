//! The step constraints: the final conditions of a step from step symmetry (KLAW 1989 eq. 3 and
//! Figures 4–5, made precise in the spec §3), with the step's state-phase timings (eq. 2).
use serde::Serialize;

use crate::model::InputError;
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::plan::gait::Gait;
use crate::plan::timing::Timing;

use crate::kinematics::pelvis::Determinants;
use crate::model::GRAVITY;

/// Everything the lower levels must achieve in one step. Positions are relative to the step's
/// stance ankle pivot (x = 0, y = l9); heights are absolute (ground at y = 0).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StepConstraints {
    /// The step's completed gait (eq. 1).
    pub gait: Gait,
    /// The step's state-phase timings (eq. 2).
    pub timing: Timing,
    /// θ1*: stance leg angle at the end of the step (rad, hip ahead of the ankle +).
    pub theta1: f64,
    /// w*: telescopic leg length at the end of the step (m).
    pub w: f64,
    /// The next step's stance leg at this heel strike: its angle θ1 (rad, negative: the hip
    /// behind its ankle) and its telescopic length w, from the landing foot's flat-foot ankle
    /// (sl, l9) to the hip. The next step starts here.
    pub lead: (f64, f64),
    /// θ3*: swing thigh angle at heel strike (rad, negative: knee ahead of the hip).
    pub theta3: f64,
    /// θ4* = κ_hs: swing knee flexion at heel strike (rad).
    pub theta4: f64,
    /// Hip at heel strike: (φ sl, y_hs).
    pub hip: [f64; 2],
    /// Heel of the striking foot at impact: (sl − l8, 0).
    pub heel_x: f64,
    /// Sole angle of the striking foot, toe up (rad).
    pub sole_angle: f64,
    /// Ankle dorsiflexion at impact δ_hs (rad).
    pub ankle: f64,
    /// Height budget E = l1 + l9 − y_hs (m).
    pub height_budget: f64,
    /// Bounce e = min(ε E, g t_step² / 4π²) (m): the hip's rise above y_hs at mid-stance,
    /// then kept within the straight stance leg's reach (`StepConstraints::within_reach`).
    pub bounce: f64,
    /// The striking leg's hip joint is (l0/2) sin A ahead of the pelvis centre at heel strike
    /// (pelvic rotation A, spec §7), m.
    pub hip_shift: f64,
    /// The striking leg's lateral offset from hip joint to ankle at heel strike,
    /// (l0/2) cos A − step width / 2 (m).
    pub lateral_offset: f64,
    /// In-plane hip–ankle drop of the striking leg at heel strike (m): the length with which a
    /// lateral offset folds the leg's height (`pelvis::fold_height`) all through the swing.
    pub fold_length: f64,
}

/// The fraction of the hip's lead kept for a step of length `sl` at speed `v` for leg length
/// `l1` \[ours\]: the product of two linear fades, each 1 before its start and 0 past its end:
/// the Froude number v² / (g l1) from `hip_lead_froude` to the walk–run transition `froude_max`
/// (1 throughout if that comes first), and the step length sl / l1 from `hip_lead_step_from`,
/// later by `hip_lead_step_rise` × [`lead_rise`], to `hip_lead_step_to`. People keep their lead
/// up to the transition (Schwartz et al. 2008's very fast children, Fr ≈ 0.48, sl ≈ 0.95 l1:
/// φ = 0.577), but klaw's legs cannot: near the transition the virtual leg's reference asks for
/// the hip under y_hs before heel strike and de Leva's women's swing toe meets the floor; on
/// steps longer than the leg the trailing foot cannot reach the hip in double support, the
/// sooner the slower the walk (docs/realism.md).
pub fn lead_fade(attrs: &Attributes, sl: f64, v: f64, l1: f64) -> f64 {
    let from = attrs.hip_lead_step_from + attrs.hip_lead_step_rise * lead_rise(attrs, v, l1);
    fade(froude(v, l1), attrs.hip_lead_froude, attrs.froude_max)
        * fade(sl / l1, from, attrs.hip_lead_step_to)
}

/// How far a walk at speed `v` for leg length `l1` is into the rise of the hip's lead
/// \[ours\]: 0 up to the Froude number `hip_lead_rise_froude`, growing linearly to 1 at
/// `hip_lead_froude`, where [`lead_fade`] takes over (0 throughout if the rise would not end
/// after it starts). People's lead keeps growing with speed (Schwartz et al. 2008: 0.553 fast,
/// 0.577 very fast); klaw's caps keep the slower walks walking, and their rise brings the
/// trailing ankle of fast walks into its norm (docs/realism.md).
pub fn lead_rise(attrs: &Attributes, v: f64, l1: f64) -> f64 {
    1.0 - fade(
        froude(v, l1),
        attrs.hip_lead_rise_froude,
        attrs.hip_lead_froude,
    )
}

/// The largest hip lead at speed `v` for leg length `l1`: φ_max grown by `hip_lead_max_rise` ×
/// [`lead_rise`].
pub fn lead_cap(attrs: &Attributes, v: f64, l1: f64) -> f64 {
    attrs.hip_lead_max + attrs.hip_lead_max_rise * lead_rise(attrs, v, l1)
}

/// The Froude number v² / (g l1).
fn froude(v: f64, l1: f64) -> f64 {
    v * v / (crate::model::GRAVITY * l1)
}

/// 1 up to `from`, falling linearly to 0 at `to` (1 throughout if `to` ≤ `from`).
fn fade(x: f64, from: f64, to: f64) -> f64 {
    if to <= from {
        1.0
    } else {
        ((to - x) / (to - from)).clamp(0.0, 1.0)
    }
}

impl StepConstraints {
    /// The heel-strike posture, spec §3 steps 1–4 with the hip's lead \[ours\]: at heel strike
    /// the hip is φ sl ahead of the stance ankle (0, l9), φ = min(1/2 + k_φ (sl/H − s_φ), φ_max)
    /// with φ − 1/2 scaled by [`lead_fade`] near the walk–run transition
    /// (the attributes `hip_lead_slope`, `hip_lead_neutral`, `hip_lead_max` grown by
    /// [`lead_cap`] in fast walks; φ = 1/2 is the
    /// paper's step symmetry, eq. 3, the hip midway to the flat-foot position (sl, l9) of the
    /// swing ankle). Real gait puts the hip further ahead the longer the step, the trailing heel
    /// raised about its metatarsal joint (docs/realism.md). The swing leg (hip–ankle distance
    /// a1 for knee flexion κ_hs) reaches the heel at (sl − l8, 0) with ankle dorsiflexion δ_hs.
    /// Cosine law: r² = a1² + l11² + 2 a1 l11 cos(ω8 − δ_hs + α), cos ω8 = l9/l11,
    /// where α = κ − β is the angle between shank and hip–ankle line (0 for a straight knee, the
    /// paper's case; the spec's formula omits it and misses the ground by 0.75 mm at κ = 4°).
    ///
    /// With the determinants of gait (spec §7) the striking leg hangs from its own hip joint,
    /// (l0/2) sin A ahead of the pelvis centre (rotation at its maximum, list and lateral
    /// displacement 0), with a lateral offset d to its ankle: the leg works in its own plane,
    /// where the hip sits d_v − √(d_v² − d²) higher than in the world (d_v the in-plane drop).
    /// The cosine law is solved in that plane; the pelvis centre is then that much lower.
    pub fn new(body: &Body, attrs: &Attributes, gait: Gait) -> Result<Self, InputError> {
        let timing = Timing::new(gait.step_frequency)?;
        let sl = gait.step_length;
        let kappa = attrs.heel_strike_knee;
        let delta = attrs.heel_strike_ankle;
        let a1 = body.hip_ankle_distance(kappa);
        let omega8 = (body.l9 / body.l11).acos();
        // triangle hip–knee–ankle: the thigh is ahead of the hip–ankle line by β, the shank
        // behind it by α = κ − β; δ_hs is relative to the shank, so relative to the line the
        // foot is dorsiflexed by δ_hs − α
        let beta = (body.l4 * kappa.sin() / a1).asin();
        let alpha = kappa - beta;
        let r2 =
            a1 * a1 + body.l11 * body.l11 + 2.0 * a1 * body.l11 * (omega8 - delta + alpha).cos();
        let r = r2.sqrt();
        let heel_x = sl - body.l8;
        let phi = (0.5 + attrs.hip_lead_slope * (sl / body.height - attrs.hip_lead_neutral))
            .min(lead_cap(attrs, gait.velocity, body.l1));
        let phi = 0.5 + (phi - 0.5) * lead_fade(attrs, sl, gait.velocity, body.l1);
        let x_h = phi * sl;
        let half = 0.5 * body.l0;
        let hip_shift = half * attrs.pelvic_rotation.sin();
        let lateral_offset = half * attrs.pelvic_rotation.cos() - 0.5 * attrs.step_width;
        let dx = heel_x - x_h - hip_shift;
        if dx.abs() >= r {
            return Err(InputError::StepTooLong { step_length: sl });
        }
        let y_plane = (r2 - dx * dx).sqrt();
        let omega3 = ((a1 * a1 + r2 - body.l11 * body.l11) / (2.0 * a1 * r)).acos();
        // angle of the hip–ankle line from the downward vertical (negative: ankle ahead)
        let line = -(omega3 + (dx / r).asin());
        let fold_length = a1 * line.cos();
        let y_h = y_plane - crate::kinematics::pelvis::fold_height(fold_length, lateral_offset);
        let w = ((y_h - body.l9).powi(2) + x_h * x_h).sqrt();
        let theta1 = (x_h / w).asin();
        let w_lead = ((y_h - body.l9).powi(2) + (sl - x_h).powi(2)).sqrt();
        let lead = (-((sl - x_h) / w_lead).asin(), w_lead);
        let theta3 = line - beta;
        let shank = theta3 + kappa;
        let height_budget = body.l1 + body.l9 - y_h;
        let cap = GRAVITY * timing.t_step.powi(2) / (4.0 * std::f64::consts::PI.powi(2));
        Ok(StepConstraints {
            gait,
            timing,
            theta1,
            w,
            lead,
            theta3,
            theta4: kappa,
            hip: [x_h, y_h],
            heel_x,
            sole_angle: -shank + delta,
            ankle: delta,
            height_budget,
            bounce: (attrs.bounciness * height_budget).min(cap),
            hip_shift,
            lateral_offset,
            fold_length,
        })
    }
}

impl StepConstraints {
    /// The bounce limited to the straight stance leg's reach \[ours\]: at mid-stance the stance
    /// hip joint is (l0/2) sin L above the pelvis centre (list L) and d = l0/2 − b/2 + D to the
    /// side of its ankle (step width b, lateral displacement D), so a straight leg on a flat foot
    /// holds the pelvis centre at most at y_r = l9 + √(l1² − d²) − (l0/2) sin L. The reference
    /// peaks at ȳ + e with ȳ the mean of the step's start height `y_start` and y_hs, so
    /// e ≤ (y_r − ȳ) / (1 + m), m the margin (the engine's constant `reach_margin`, more where a step needed it:
    /// `Walker::step`). Above that the hip passes over the ankle out of the flat foot's reach,
    /// and the foot's pitch jumps from its heel to its metatarsal joint (in 99 of the 181 walks
    /// of the valid range, with the hip midway at heel strike).
    pub(crate) fn within_reach(
        mut self,
        body: &Body,
        det: &Determinants,
        y_start: f64,
        margin: f64,
    ) -> Self {
        let (rise, d) = det.mid_stance_hip();
        let top = body.l9 + (body.l1 * body.l1 - d * d).sqrt() - rise;
        let mean = 0.5 * (y_start + self.hip[1]);
        self.bounce = self.bounce.min((top - mean) / (1.0 + margin));
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::gait::GaitRequest;

    /// The spec's worked examples have no determinants: no pelvic rotation, and a step width
    /// equal to the pelvis width (no lateral offset).
    fn worked(kappa_deg: f64, delta_deg: f64) -> (Body, StepConstraints) {
        let body = Body::standard(1.8, 80.0).unwrap();
        let attrs = Attributes {
            heel_strike_knee: kappa_deg.to_radians(),
            heel_strike_ankle: delta_deg.to_radians(),
            pelvic_rotation: 0.0,
            step_width: body.l0,
            hip_lead_slope: 0.0,
            ..Default::default()
        };
        (body, constraints(&body, &attrs))
    }

    fn constraints(body: &Body, attrs: &Attributes) -> StepConstraints {
        let gait = GaitRequest {
            velocity: Some(1.4),
            ..Default::default()
        }
        .complete(body, attrs)
        .unwrap();
        StepConstraints::new(body, attrs, gait).unwrap()
    }

    /// Spec §3 worked example: hip = (0.3888, 0.8768), w* = 0.8963, θ1* = 25.71°,
    /// θ3* = −24.20°, E = 6.05 cm, sole angle 24.2°.
    #[test]
    fn final_conditions_of_the_worked_example() {
        let (_, c) = worked(0.0, 0.0);
        assert!((c.hip[0] - 0.3888).abs() < 1e-4, "{c:?}");
        assert!((c.hip[1] - 0.8768).abs() < 1e-4, "{c:?}");
        assert!((c.w - 0.8963).abs() < 1e-4);
        assert!((c.theta1.to_degrees() - 25.71).abs() < 0.01);
        assert!((c.theta3.to_degrees() + 24.20).abs() < 0.01);
        assert!((c.height_budget - 0.0605).abs() < 1e-4);
        assert!((c.sole_angle.to_degrees() - 24.20).abs() < 0.01);
    }

    /// Spec §3: with δ_hs = −4.645° the sole angle is 20°, w* = 0.8922 m, θ1* = 25.84°, θ3* = −24.64°.
    #[test]
    fn final_conditions_with_plantarflexed_ankle() {
        let (_, c) = worked(0.0, -4.645);
        assert!((c.sole_angle.to_degrees() - 20.0).abs() < 0.01, "{c:?}");
        assert!((c.w - 0.8922).abs() < 1e-4);
        assert!((c.theta1.to_degrees() - 25.84).abs() < 0.01);
        assert!((c.theta3.to_degrees() + 24.64).abs() < 0.01);
    }

    /// Independent check of the cosine-law construction for a flexed knee: forward kinematics of
    /// thigh (θ3*), shank (θ3* + κ) and a foot pitched by (shank − δ_hs) puts the heel on the
    /// ground at sl − l8, and the hip–stance-ankle distance is w*.
    ///
    /// With the determinants, the same in the striking leg's plane: its hip joint is
    /// (l0/2) sin A ahead of the pelvis centre, and the world drop √(d_v² − d²) of a leg of
    /// in-plane drop d_v and lateral offset d puts the world hip at the pelvis centre's height.
    #[test]
    fn forward_kinematics_lands_the_heel() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let with_determinants = constraints(
            &body,
            &Attributes {
                pelvic_rotation: 6f64.to_radians(),
                step_width: 0.05,
                ..Default::default()
            },
        );
        let cases = [(4.0, 0.0), (10.0, -5.0), (0.0, 5.0)]
            .map(|(k, d)| worked(k, d))
            .into_iter()
            .chain([(body, with_determinants)]);
        for (b, c) in cases {
            let (kappa, delta) = (c.theta4.to_degrees(), c.ankle.to_degrees());
            let xh = c.hip[0] + c.hip_shift;
            // in-plane drop from the hip to the ankle, then the world hip height
            let drop = b.l3 * c.theta3.cos() + b.l4 * (c.theta3 + c.theta4).cos();
            let d = c.lateral_offset;
            let yh = c.hip[1] + drop - (drop * drop - d * d).sqrt();
            let shank = c.theta3 + c.theta4;
            let knee = [xh - b.l3 * c.theta3.sin(), yh - b.l3 * c.theta3.cos()];
            let ankle = [knee[0] - b.l4 * shank.sin(), knee[1] - b.l4 * shank.cos()];
            let p = shank - c.ankle; // foot pitch, heel up +
            let heel = [
                ankle[0] - b.l8 * p.cos() - b.l9 * p.sin(),
                ankle[1] + b.l8 * p.sin() - b.l9 * p.cos(),
            ];
            assert!(heel[1].abs() < 1e-12, "κ {kappa} δ {delta}: heel {heel:?}");
            assert!(
                (heel[0] - c.heel_x).abs() < 1e-12,
                "κ {kappa} δ {delta}: heel {heel:?}"
            );
            // the telescopic leg runs from the stance ankle pivot to the pelvis centre
            let w = (c.hip[0].powi(2) + (c.hip[1] - b.l9).powi(2)).sqrt();
            assert!((w - c.w).abs() < 1e-12 && (c.theta1 - (c.hip[0] / w).asin()).abs() < 1e-12);
            assert!((c.sole_angle + p).abs() < 1e-12);
            // the next stance leg runs from the landing foot's flat-foot ankle (heel + l8)
            let ahead = c.heel_x + b.l8 - c.hip[0];
            let w = (ahead.powi(2) + (c.hip[1] - b.l9).powi(2)).sqrt();
            assert!((w - c.lead.1).abs() < 1e-12 && (c.lead.0 + (ahead / w).asin()).abs() < 1e-12);
        }
    }

    /// The hip's lead φ = 1/2 + k_φ (sl/H − s_φ): at sl/H = s_φ, or with k_φ = 0, the hip is
    /// midway (the next stance starts from the mirror image, as in the paper); a longer step
    /// puts it further ahead, so the trailing leg ends longer than the leading one starts.
    #[test]
    fn the_hip_leads_by_its_fraction_of_the_step() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let sl = 0.7777;
        let at = |slope: f64, neutral: f64| {
            let attrs = Attributes {
                hip_lead_slope: slope,
                hip_lead_neutral: neutral,
                ..Default::default()
            };
            constraints(&body, &attrs)
        };
        let neutral = at(0.0, 0.339).gait.step_length / 1.8;
        for c in [at(0.0, 0.339), at(0.595, neutral)] {
            assert!((c.hip[0] - sl / 2.0).abs() < 1e-4, "{c:?}");
            assert!((c.lead.0 + c.theta1).abs() < 1e-12 && (c.lead.1 - c.w).abs() < 1e-12);
        }
        // below the cap φ_max, and held at it
        let phi = 0.5 + 0.595 * (sl / 1.8 - 0.339);
        for (max, want) in [(0.6, phi), (0.54, 0.54)] {
            let c = constraints(
                &body,
                &Attributes {
                    hip_lead_slope: 0.595,
                    hip_lead_max: max,
                    ..Default::default()
                },
            );
            assert!((c.hip[0] / c.gait.step_length - want).abs() < 1e-4, "{c:?}");
        }
        let c = at(0.595, 0.339);
        assert!(c.w > c.lead.1 && c.theta1 > -c.lead.0);
        // the hip stands higher than midway: the leading leg reaches less far ahead
        assert!(c.hip[1] > at(0.0, 0.339).hip[1] + 0.01);
    }

    #[test]
    fn running_is_refused() {
        let e = Timing::new(181.9).unwrap_err();
        assert!(e.to_string().contains("181.75"), "{e}");
        assert!(Timing::new(181.7).is_ok());
    }

    /// Where the straight leg cannot reach the bounce's peak (a slow walk of a tall body: a
    /// small height budget, the list raising the stance hip joint), the bounce is cut so that
    /// the stance hip joint, lifted reach_margin e more, is exactly l1 from the flat foot's
    /// ankle (by Pythagoras with its lateral offset); with no list the cut is less.
    #[test]
    fn the_bounce_stays_within_the_straight_legs_reach() {
        let body = Body::standard(2.0, 92.0).unwrap();
        let attrs = Attributes::default();
        let gait = GaitRequest {
            velocity: Some(0.4),
            ..Default::default()
        }
        .complete(&body, &attrs)
        .unwrap();
        let plain = StepConstraints::new(&body, &attrs, gait).unwrap();
        let det = Determinants::new(&attrs, body.l0);
        let reach_margin = crate::engine::parameters::EngineParameters::default().reach_margin;
        let c = plain.within_reach(&body, &det, plain.hip[1], reach_margin);
        assert!(c.bounce < plain.bounce, "{} {}", c.bounce, plain.bounce);
        let joint = c.hip[1] + (1.0 + reach_margin) * c.bounce + det.half_width * det.list.sin();
        let d = det.half_width - det.half_step_width + det.lateral;
        assert!(((joint - body.l9).hypot(d) - body.l1).abs() < 1e-12);
        let flat = Determinants { list: 0.0, ..det };
        assert!(
            plain
                .within_reach(&body, &flat, plain.hip[1], reach_margin)
                .bounce
                > c.bounce
        );
    }

    /// The bounce is capped so that the reference never asks for more than g/2 downward:
    /// e ≤ g t_step² / 4π².
    #[test]
    fn bounce_is_epsilon_e_or_capped() {
        let (_, c) = worked(4.0, 0.0);
        assert!((c.bounce - 0.8 * c.height_budget).abs() < 1e-15);
        let cap = GRAVITY * c.timing.t_step.powi(2) / (4.0 * std::f64::consts::PI.powi(2));
        assert!(c.bounce <= cap);
    }

    /// The hip's lead fades linearly from Fr_φ to the walk–run transition: whole below, half
    /// halfway, none at Fr_max, whole throughout when Fr_max ≤ Fr_φ; and the hip's place at
    /// heel strike moves with it, by (φ − 1/2) sl.
    #[test]
    fn the_hip_lead_fades_to_midway_at_the_walk_run_transition() {
        let body = Body::standard(1.8, 80.0).unwrap();
        // the cap held, so that only the fade moves the hip here (its rise: the next test)
        let attrs = Attributes {
            hip_lead_slope: 0.595,
            hip_lead_froude: 0.4,
            froude_max: 0.5,
            hip_lead_max_rise: 0.0,
            hip_lead_step_rise: 0.0,
            ..Attributes::default()
        };
        let v_at = |fr: f64| (fr * GRAVITY * body.l1).sqrt();
        assert_eq!(lead_fade(&attrs, 0.5, v_at(0.3), body.l1), 1.0);
        assert!((lead_fade(&attrs, 0.5, v_at(0.45), body.l1) - 0.5).abs() < 1e-12);
        assert!(lead_fade(&attrs, 0.5, v_at(0.5), body.l1).abs() < 1e-12);
        let early = Attributes {
            froude_max: 0.35,
            ..attrs.clone()
        };
        assert_eq!(lead_fade(&early, 0.5, v_at(0.34), body.l1), 1.0);
        // the step length's fade, from 0.98 to 1.12 leg lengths, multiplies the speed's
        let l1 = body.l1;
        let steps = Attributes {
            hip_lead_step_from: 0.98,
            hip_lead_step_to: 1.12,
            ..attrs.clone()
        };
        assert_eq!(lead_fade(&steps, 0.9 * l1, v_at(0.3), l1), 1.0);
        assert!((lead_fade(&steps, 1.05 * l1, v_at(0.3), l1) - 0.5).abs() < 1e-12);
        assert!((lead_fade(&steps, 1.05 * l1, v_at(0.45), l1) - 0.25).abs() < 1e-12);
        assert_eq!(lead_fade(&steps, 1.2 * l1, v_at(0.3), l1), 0.0);
        let hip_x = |a: &Attributes| {
            let gait = GaitRequest {
                velocity: Some(v_at(0.45)),
                ..Default::default()
            }
            .complete(&body, a)
            .unwrap();
            StepConstraints::new(&body, a, gait).unwrap().hip[0]
        };
        let faded = hip_x(&attrs);
        let midway = hip_x(&Attributes {
            hip_lead_slope: 0.0,
            ..attrs.clone()
        });
        let whole = hip_x(&Attributes {
            hip_lead_froude: 0.5,
            ..attrs.clone()
        });
        assert!(whole > midway + 0.01, "{whole} {midway}");
        assert!((faded - midway - 0.5 * (whole - midway)).abs() < 1e-12);
    }

    /// The cap φ_max and the start of the step length's fade grow linearly in the Froude number
    /// from `hip_lead_rise_froude` to `hip_lead_froude`: not below, halfway up halfway, all the
    /// way from there on, not at all when the rise would end before it starts; and a lead that
    /// reaches the cap puts the hip at heel strike φ_cap sl ahead of the trailing ankle.
    #[test]
    fn the_hip_leads_cap_rises_with_the_froude_number() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let attrs = Attributes {
            hip_lead_max: 0.54,
            hip_lead_max_rise: 0.012,
            hip_lead_rise_froude: 0.3,
            hip_lead_froude: 0.4,
            ..Attributes::default()
        };
        let v_at = |fr: f64| (fr * GRAVITY * body.l1).sqrt();
        let cap = |a: &Attributes, fr: f64| lead_cap(a, v_at(fr), body.l1);
        assert_eq!(cap(&attrs, 0.2), 0.54);
        assert_eq!(cap(&attrs, 0.3), 0.54);
        assert!((cap(&attrs, 0.35) - 0.546).abs() < 1e-12);
        assert!((cap(&attrs, 0.4) - 0.552).abs() < 1e-12);
        assert!((cap(&attrs, 0.48) - 0.552).abs() < 1e-12);
        let none = Attributes {
            hip_lead_rise_froude: 0.4,
            ..attrs.clone()
        };
        assert_eq!(cap(&none, 0.45), 0.54);
        // the step fade from 0.98 (+ 0.05 × the rise) to 1.12 leg lengths: at 1.05 l1 it keeps
        // half of the lead below the rise, 0.07 / 0.115 of it halfway up (from 1.005), 0.07 /
        // 0.09 at the top (from 1.03), where a step of 1.03 l1 keeps all of it
        let steps = Attributes {
            hip_lead_step_from: 0.98,
            hip_lead_step_rise: 0.05,
            hip_lead_step_to: 1.12,
            ..attrs.clone()
        };
        let kept = |fr: f64, sl: f64| lead_fade(&steps, sl * body.l1, v_at(fr), body.l1);
        assert!((kept(0.25, 1.05) - 0.5).abs() < 1e-12);
        assert!((kept(0.35, 1.05) - 0.07 / 0.115).abs() < 1e-12);
        assert!((kept(0.35, 1.075) - 0.045 / 0.115).abs() < 1e-12);
        assert!((kept(0.4, 1.05) - 0.07 / 0.09).abs() < 1e-12);
        assert_eq!(kept(0.4, 1.03), 1.0);
        // a steep lead law meets the cap; no fade at Fr 0.35 (halfway up the rise: the step fade
        // from 0.98 + 0.025 l1) for a step under 1.005 l1
        let steep = Attributes {
            hip_lead_slope: 1.5,
            ..attrs.clone()
        };
        let gait = GaitRequest {
            velocity: Some(v_at(0.35)),
            ..Default::default()
        }
        .complete(&body, &steep)
        .unwrap();
        assert!(gait.step_length < 1.005 * body.l1, "{gait:?}");
        let c = StepConstraints::new(&body, &steep, gait).unwrap();
        assert!((c.hip[0] / gait.step_length - 0.546).abs() < 1e-12, "{c:?}");
    }
}
