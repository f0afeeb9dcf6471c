//! Locomotion parameters: completion of velocity, step length and step frequency by the
//! normalizing formula (KLAW 1989 eq. 1, after Inman: sl = 0.004 · sf · H, v = sl · sf / 60) and
//! the anatomical limits checked before anything is simulated.
use serde::{Deserialize, Serialize};

use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::model::{GRAVITY, InputError, Shown};

/// Normalizing constant of eq. 1: metres of step per (step/min · m of body height).
pub(crate) const NORMALIZING_CONSTANT: f64 = 0.004;
/// Relative tolerance of v = sl · sf / 60 when all three are given: the rounding of user input
/// (1.4 m/s, 0.78 m, 108 steps/min agree to 0.3 %).
pub(crate) const CONSISTENCY_TOLERANCE: f64 = 0.01;

/// What the user asked for: any of v (m/s), sl (m), sf (steps/min).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GaitRequest {
    /// Velocity v (m/s).
    pub velocity: Option<f64>,
    /// Step length sl (m).
    pub step_length: Option<f64>,
    /// Step frequency sf (steps/min).
    pub step_frequency: Option<f64>,
}

/// A complete, checked gait: v = sl · sf / 60.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Gait {
    /// Velocity v (m/s).
    pub velocity: f64,
    /// Step length sl (m).
    pub step_length: f64,
    /// Step frequency sf (steps/min).
    pub step_frequency: f64,
}

/// The fastest walk of `body` (m/s): the attributes' `velocity_max`, or below it the
/// walk–run transition √(Fr_max g l1) (Fr_max the attribute `froude_max`, l1 the leg length;
/// Alexander 1989), rounded down to 0.1 mm/s so that the limit shown is the one checked.
pub fn velocity_limit(body: &Body, attrs: &Attributes) -> f64 {
    let transition = (attrs.froude_max * GRAVITY * body.l1).sqrt();
    attrs.velocity_max.min((transition * 1e4).floor() / 1e4)
}

/// Check the velocity `v` against [velocity_min, [`velocity_limit`]]: beyond the walk–run
/// transition but not beyond `velocity_max` (a walking speed too fast for this body) an
/// [`InputError::BeyondWalkRun`] naming the body's limit, else [`InputError::check_range`]'s
/// errors with that range.
fn check_velocity(v: f64, body: &Body, attrs: &Attributes) -> Result<f64, InputError> {
    let max = velocity_limit(body, attrs);
    if v.is_finite() && v > max && v <= attrs.velocity_max {
        return Err(InputError::BeyondWalkRun {
            value: v,
            min: attrs.velocity_min,
            max,
            froude_max: attrs.froude_max,
            leg: round4(body.l1),
            note: String::new(),
        });
    }
    InputError::check_range("velocity", v, attrs.velocity_min, max, "m/s")
}

/// The duration (s) of a walk of one step per gait, known before it is simulated: Σ 60 / sf.
pub fn walk_duration(gaits: &[Gait]) -> f64 {
    gaits.iter().map(|g| 60.0 / g.step_frequency).sum()
}

impl GaitRequest {
    /// The gait walked when none is given: the attributes' `preferred_velocity` (a style's own
    /// speed, 1.4 m/s by default), sl and sf by the normalizing formula; out of range, the error
    /// says the speed was the default.
    pub fn preferred(body: &Body, attrs: &Attributes) -> Result<Gait, InputError> {
        let request = GaitRequest {
            velocity: Some(attrs.preferred_velocity),
            ..GaitRequest::default()
        };
        request.complete(body, attrs).map_err(|e| {
            e.with_note(
                "the default speed: attribute preferred_velocity, which must lie in the \
                 attributes' [velocity_min, velocity_max]; give a gait or set it",
            )
        })
    }

    /// Complete the request by the normalizing formula and check it against the anatomical
    /// limits of `attrs` (KLAW 1989 §3.1) and the body's walk–run transition
    /// ([`velocity_limit`]): only v → sf = √(15000 v / (k H)), sl = 60 v / sf;
    /// only sf → sl = 0.004 k sf H; only sl → sf = sl / (0.004 k H) (k the `stride_factor`
    /// attribute, 1 for the paper's formula); two given → the third from
    /// v = sl sf / 60; all three → they must agree within `CONSISTENCY_TOLERANCE`.
    pub fn complete(&self, body: &Body, attrs: &Attributes) -> Result<Gait, InputError> {
        for (name, value) in [
            ("velocity", self.velocity),
            ("step_length", self.step_length),
            ("step_frequency", self.step_frequency),
        ] {
            if let Some(v) = value
                && !v.is_finite()
            {
                return Err(InputError::NotFinite {
                    name: name.into(),
                    value: v,
                });
            }
        }
        let h = body.height;
        let k = NORMALIZING_CONSTANT * attrs.stride_factor;
        let (v, sl, sf) = match (self.velocity, self.step_length, self.step_frequency) {
            (None, None, None) => return Err(InputError::MissingGait),
            (Some(v), None, None) => {
                let sf = (60.0 * v / (k * h)).sqrt();
                (v, 60.0 * v / sf, sf)
            }
            (None, None, Some(sf)) => (k * sf * h * sf / 60.0, k * sf * h, sf),
            (None, Some(sl), None) => {
                let sf = sl / (k * h);
                (sl * sf / 60.0, sl, sf)
            }
            (Some(v), Some(sl), None) => (v, sl, 60.0 * v / sl),
            (Some(v), None, Some(sf)) => (v, 60.0 * v / sf, sf),
            (None, Some(sl), Some(sf)) => (sl * sf / 60.0, sl, sf),
            (Some(v), Some(sl), Some(sf)) => {
                let implied = sl * sf / 60.0;
                if (implied - v).abs() > CONSISTENCY_TOLERANCE * v {
                    return Err(InputError::Inconsistent {
                        velocity: v,
                        step_length: sl,
                        step_frequency: sf,
                        implied,
                        tolerance_pct: CONSISTENCY_TOLERANCE * 100.0,
                    });
                }
                (v, sl, sf)
            }
        };
        let checks = [
            (
                "velocity",
                v,
                attrs.velocity_min,
                attrs.velocity_max,
                "m/s",
                self.velocity,
            ),
            (
                "step_length",
                sl,
                round4(attrs.step_length_min * body.l1),
                round4(attrs.step_length_max * body.l1),
                "m",
                self.step_length,
            ),
            (
                "step_frequency",
                sf,
                attrs.step_frequency_min,
                attrs.step_frequency_max,
                "steps/min",
                self.step_frequency,
            ),
        ];
        // what the user gave is named first, what was derived from it after
        let check = |name: &str, value: f64, min: f64, max: f64, unit: &str| {
            if name == "velocity" {
                check_velocity(value, body, attrs)
            } else {
                InputError::check_range(name, value, min, max, unit)
            }
        };
        for (name, value, min, max, unit, _) in checks.iter().filter(|c| c.5.is_some()) {
            check(name, *value, *min, *max, unit)?;
        }
        let given: Vec<String> = checks
            .iter()
            .filter(|c| c.5.is_some())
            .map(|(name, value, _, _, unit, _)| format!("{name} = {} {unit}", Shown(*value)))
            .collect();
        let origin = if given.len() == 1 {
            format!(
                "derived from {} and H = {} m by the normalizing formula sl = {} · sf · H, \
                 v = sl · sf / 60",
                given[0],
                Shown(h),
                Shown(k)
            )
        } else {
            format!("derived from {} by v = sl · sf / 60", given.join(" and "))
        };
        for (name, value, min, max, unit, _) in checks.iter().filter(|c| c.5.is_none()) {
            check(name, *value, *min, *max, unit).map_err(|e| e.with_note(&origin))?;
        }
        Ok(Gait {
            velocity: v,
            step_length: sl,
            step_frequency: sf,
        })
    }
}

fn round4(x: f64) -> f64 {
    (x * 1e4).round() / 1e4
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> (Body, Attributes) {
        (Body::standard(1.8, 80.0).unwrap(), Attributes::default())
    }

    fn req(v: Option<f64>, sl: Option<f64>, sf: Option<f64>) -> GaitRequest {
        GaitRequest {
            velocity: v,
            step_length: sl,
            step_frequency: sf,
        }
    }

    /// Hand computation: sf = √(15000 · 1.4 / 1.8) = √11666.67 = 108.012; sl = 84 / 108.012 = 0.7777.
    #[test]
    fn velocity_only_worked_example() {
        let (b, a) = setup();
        let g = req(Some(1.4), None, None).complete(&b, &a).unwrap();
        assert!((g.step_frequency - 108.0123).abs() < 1e-3, "{g:?}");
        assert!((g.step_length - 0.77769).abs() < 1e-4, "{g:?}");
        // the normalizing relation holds for the completed pair
        assert!((g.step_length - 0.004 * g.step_frequency * 1.8).abs() < 1e-12);
    }

    #[test]
    fn every_completion_rule_satisfies_v_equals_sl_sf() {
        let (b, a) = setup();
        let cases = [
            req(None, None, Some(100.0)), // sl = 0.72, v = 1.2
            req(None, Some(0.72), None),  // sf = 100
            req(Some(1.2), Some(0.72), None),
            req(Some(1.2), None, Some(100.0)),
            req(None, Some(0.72), Some(100.0)),
            req(Some(1.2), Some(0.72), Some(100.0)),
        ];
        for c in cases {
            let g = c.complete(&b, &a).unwrap();
            assert!((g.velocity - 1.2).abs() < 1e-12, "{c:?} → {g:?}");
            assert!((g.step_length - 0.72).abs() < 1e-12, "{c:?} → {g:?}");
            assert!((g.step_frequency - 100.0).abs() < 1e-9, "{c:?} → {g:?}");
        }
    }

    #[test]
    fn inconsistent_triple_is_an_error_naming_the_implied_speed() {
        let (b, a) = setup();
        let e = req(Some(1.4), Some(0.6), Some(100.0))
            .complete(&b, &a)
            .unwrap_err();
        let msg = e.to_string();
        assert!(
            matches!(e, InputError::Inconsistent { .. }) && msg.contains("1.0000 m/s"),
            "{msg}"
        );
    }

    #[test]
    fn limits_name_the_value_and_range() {
        let (b, a) = setup();
        let e = req(None, None, Some(190.0))
            .complete(&b, &a)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("step_frequency = 190") && e.contains("182"),
            "{e}"
        );
        // above velocity_max and the walk–run transition, the tighter limit is named:
        // √(0.5 · 9.81 · 0.86805) = 2.06344 m/s
        let e = req(Some(3.5), None, None)
            .complete(&b, &a)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("velocity = 3.5") && e.contains("[0.4, 2.0634]"),
            "{e}"
        );
        let e = req(Some(1.0), Some(1.5), None)
            .complete(&b, &a)
            .unwrap_err()
            .to_string();
        // sl_max = 1.3 l1 = 1.3 · (0.23669 + 0.24556) · 1.8 = 1.1285 m
        assert!(
            e.contains("step_length = 1.5") && e.contains("1.1285"),
            "{e}"
        );
        let e = req(Some(f64::NAN), None, None)
            .complete(&b, &a)
            .unwrap_err();
        assert!(matches!(e, InputError::NotFinite { .. }));
        let e = req(Some(-1.0), None, None).complete(&b, &a).unwrap_err();
        assert!(matches!(e, InputError::OutOfRange { .. }));
        assert!(matches!(
            req(None, None, None).complete(&b, &a),
            Err(InputError::MissingGait)
        ));
    }

    /// The example: sf = 181.9 steps/min alone for H = 1.8 m gives, by hand,
    /// v = 0.004 · 181.9² · 1.8 / 60 = 238.230792 / 60 = 3.9705132 m/s, over the body's
    /// walk–run transition (l1 = 0.48225 · 1.8 = 0.86805 m, √(0.5 · 9.81 · l1) = 2.063440 m/s):
    /// the message shows it without float noise and says it was derived, and from what.
    #[test]
    fn a_derived_value_out_of_range_says_it_was_derived() {
        let (b, a) = setup();
        let e = req(None, None, Some(181.9)).complete(&b, &a).unwrap_err();
        assert_eq!(
            e.to_string(),
            "velocity = 3.9705132 m/s (derived from step_frequency = 181.9 steps/min and H = 1.8 m \
             by the normalizing formula sl = 0.004 · sf · H, v = sl · sf / 60) is out of range: \
             valid range is [0.4, 2.0634] m/s"
        );
        // a given value out of range has no note; over velocity_max or under velocity_min the
        // body's range is shown, between the transition and velocity_max the transition named
        let e = req(Some(3.0), None, None).complete(&b, &a).unwrap_err();
        assert_eq!(
            e.to_string(),
            "velocity = 3 m/s is out of range: valid range is [0.4, 2.0634] m/s"
        );
        let e = req(Some(2.2), None, None).complete(&b, &a).unwrap_err();
        assert_eq!(
            e.to_string(),
            "velocity = 2.2 m/s is beyond the walk–run transition for this body: valid range is \
             [0.4, 2.0634] m/s (Froude number v²/(g·l) ≤ 0.5, leg length l = 0.8681 m)"
        );
        let e = req(None, None, Some(160.0)).complete(&b, &a).unwrap_err();
        // v = 0.004 · 160² · 1.8 / 60 = 3.072 m/s: over velocity_max; sf = 140: 2.352 m/s, between
        assert!(e.to_string().contains("3.072 m/s (derived"), "{e}");
        let e = req(None, None, Some(140.0)).complete(&b, &a).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("velocity = 2.352 m/s (derived from step_frequency = 140")
                && e.to_string().contains("beyond the walk–run transition"),
            "{e}"
        );
        let e = req(Some(0.3), None, None).complete(&b, &a).unwrap_err();
        assert_eq!(
            e.to_string(),
            "velocity = 0.3 m/s is out of range: valid range is [0.4, 2.0634] m/s"
        );
    }

    /// The walk–run transition scales with the leg (Fr = v² / (g l1) ≤ 0.5, Alexander 1989): by
    /// hand, H = 1.2 m: l1 = 0.5787 m, √(0.5 · 9.81 · 0.5787) = 1.684792 m/s; H = 2.2 m:
    /// l1 = 1.06095 m, 2.281219 m/s; a speed just under the limit is accepted, just over it
    /// refused; velocity_max below the transition is the limit (and its error the plain one).
    #[test]
    fn the_walk_run_transition_limits_the_speed_by_the_leg() {
        let a = Attributes::default();
        for (h, limit) in [(1.2, 1.6847), (2.2, 2.2812)] {
            let b = Body::standard(h, 23.0 * h * h).unwrap();
            assert_eq!(velocity_limit(&b, &a), limit, "H {h}");
            assert!(req(Some(limit), None, None).complete(&b, &a).is_ok());
            let e = req(Some(limit + 0.01), None, None)
                .complete(&b, &a)
                .unwrap_err();
            assert!(matches!(e, InputError::BeyondWalkRun { .. }), "{e}");
        }
        let (b, _) = setup();
        let slow = Attributes {
            velocity_max: 1.5,
            ..a.clone()
        };
        assert_eq!(velocity_limit(&b, &slow), 1.5);
        let e = req(Some(1.8), None, None).complete(&b, &slow).unwrap_err();
        assert_eq!(
            e.to_string(),
            "velocity = 1.8 m/s is out of range: valid range is [0.4, 1.5] m/s"
        );
        let fr = Attributes {
            froude_max: 0.3,
            ..a.clone()
        };
        // √(0.3 · 9.81 · 0.86805) = 1.598334 m/s
        assert_eq!(velocity_limit(&b, &fr), 1.5983);
    }
}
