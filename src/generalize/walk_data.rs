//! Walk data W(S, sl) = {H, F1, F2, F3, M, A} (Ko & Badler 1992, eq. 4) of one step, with the
//! body condition B(S), the step lengths and the prototype's character it is generalized with.
//!
//! Time is the step's normalized time: 0 at the heel strike that starts it (HSM⁻), 1 at the next
//! (HSM⁺). Each foot has its own timeline (docs/generalize.md): the *stance* foot's runs from its
//! heel strike at 0 through the next step's double support to its toe-off at 1 + TOM (F1, F2, M);
//! the *swing* foot's from its toe-off at TOM to its heel strike at 1 (F3, A). Positions are
//! relative to the stance foot's N (its flat-foot ankle's point on the floor), x forward, y up
//! (m); angles in rad. A foot's angle is its pitch, the heel → ball line's angle from the floor,
//! heel up + (the paper's FAHSM is −pitch, its FATOM +pitch).
use serde::{Deserialize, Serialize};

use crate::generalize::condition::BodyCondition;
use crate::generalize::error::GeneralizeError;
use crate::generalize::geometry::{Character, Mu, Pelvis};
use crate::generalize::sequence::{Curve, Path, interpolate};

/// The phase moments (normalized step time).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Phases {
    /// FGM: the stance foot flat, in [0, 1).
    pub fgm: f64,
    /// \[ours\] Heel-off: the stance foot's heel leaves the floor, in [FGM, 1 + TOM] (a phase
    /// moment inside F2 that the paper does not name: the gait events report it, and the
    /// sampling keeps F2's corner there).
    pub heel_off: f64,
    /// MOM: the stance foot's toes start to turn about their tip, in [FGM, 1 + TOM] (1 + TOM:
    /// never, a foot without toes).
    pub mom: f64,
    /// TOM: the swing foot's toe-off, in (0, 1); the stance foot's is 1 + TOM.
    pub tom: f64,
}

/// An angle sequence that the generalization scales to a new end value (eqs. 20, 22, 26): its
/// value is `amplitude` × `shape`, the shape 1 at the anchored end. \[ours\] The paper scales the
/// values by μ / f_anchor; holding the shape and the amplitude apart is the same wherever
/// f_anchor ≠ 0 and stays defined where it is 0 (a flat landing, a rigid foot, or a μ that
/// crosses 0): docs/generalize.md.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Piece {
    /// Times, strictly increasing.
    pub t: Vec<f64>,
    /// The shape, 1 at the anchored end.
    pub shape: Vec<f64>,
    /// The value at the anchored end (rad).
    pub amplitude: f64,
}

impl Piece {
    /// The piece of `values` at times `t`, anchored at the first sample (`at_end` false) or at
    /// the last: the shape is values / anchor where |anchor| ≥ `epsilon`, else a ramp in time
    /// from 0 at the other end to 1 at the anchor (1 for a single sample).
    pub fn new(t: Vec<f64>, values: &[f64], at_end: bool, epsilon: f64) -> Self {
        let n = values.len();
        let anchor = if at_end { values[n - 1] } else { values[0] };
        let shape = if anchor.abs() >= epsilon {
            values.iter().map(|v| v / anchor).collect()
        } else if n < 2 || t[n - 1] == t[0] {
            vec![1.0; n]
        } else {
            let (a, b) = (t[0], t[n - 1]);
            t.iter()
                .map(|&x| {
                    let s = (x - a) / (b - a);
                    if at_end { s } else { 1.0 - s }
                })
                .collect()
        };
        Piece {
            t,
            shape,
            amplitude: anchor,
        }
    }

    /// The value at t (eq. 2 on the shape), the ends held outside.
    pub fn at(&self, t: f64) -> f64 {
        self.amplitude * interpolate(&self.t, &self.shape, t)
    }

    /// The values at the samples.
    pub fn values(&self) -> Vec<f64> {
        self.shape.iter().map(|s| self.amplitude * s).collect()
    }

    /// The same shape with the amplitude `a`.
    pub fn with_amplitude(&self, a: f64) -> Self {
        Piece {
            amplitude: a,
            ..self.clone()
        }
    }
}

/// W(S, sl) with B(S), sl, the previous step's length and the prototype's character.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WalkData {
    /// Where the data comes from, in words.
    pub source: String,
    /// B(S).
    pub body: BodyCondition,
    /// sl: from the stance foot's N to the landing foot's (m).
    pub step_length: f64,
    /// sl_before: from the trailing foot's N to the stance foot's (m; eq. 15).
    pub step_length_before: f64,
    /// \[ours\] The walk's pelvic rotation and step width (eq. 11's leading hip joint).
    pub pelvis: Pelvis,
    /// What every generalization of the data keeps.
    pub character: Character,
    /// FGM, MOM, TOM.
    pub phases: Phases,
    /// H: the pelvis centre over [0, 1] (eq. 12).
    pub hip: Path,
    /// F1: the stance foot's pitch over [0, FGM], anchored at heel strike (eq. 17).
    pub f1: Piece,
    /// F2: the stance foot's pitch over [FGM, 1 + TOM], anchored at toe-off (eq. 18).
    pub f2: Piece,
    /// F3: the swing foot's pitch over [TOM, 1] (eq. 19).
    pub f3: Curve,
    /// M: the stance foot's toes' angle from the floor over [MOM, 1 + TOM], anchored at
    /// toe-off (eq. 25).
    pub meta: Piece,
    /// A: the swing ankle over [TOM, 1] (eq. 27).
    pub ankle: Path,
    /// \[ours\] The upper body's pitch from its lean attribute over [0, 1] (rad, forward +;
    /// klaw's θ2 − trunk_lean): angular, so every generalization keeps it (§4).
    pub trunk: Curve,
}

const SPAN: f64 = 1e-9;

/// `field`: times strictly increasing from `a` to `b` (to 1e-9), values as many and finite.
fn check_times(
    field: &str,
    t: &[f64],
    values: &[&[f64]],
    a: f64,
    b: f64,
) -> Result<(), GeneralizeError> {
    let bad = |reason: String| Err(GeneralizeError::invalid(field, reason));
    if t.is_empty() {
        return bad("no samples".into());
    }
    for v in values {
        if v.len() != t.len() {
            return bad(format!("{} times but {} values", t.len(), v.len()));
        }
    }
    if let Some(i) = t.windows(2).position(|w| w[1] <= w[0]) {
        return bad(format!("times not strictly increasing at sample {}", i + 1));
    }
    for (i, x) in t
        .iter()
        .chain(values.iter().flat_map(|v| v.iter()))
        .enumerate()
    {
        if !x.is_finite() {
            return bad(format!("{x} at entry {i}: finite numbers are required"));
        }
    }
    let (first, last) = (t[0], t[t.len() - 1]);
    if (first - a).abs() > SPAN || (last - b).abs() > SPAN {
        return bad(format!(
            "runs over [{first}, {last}]; it must run over [{a}, {b}] (normalized time)"
        ));
    }
    Ok(())
}

impl WalkData {
    /// μ1…μ4 at the data's own walk condition.
    pub fn mu(&self) -> Mu {
        self.character.mu(self.body.leg_length(), self.step_length)
    }

    /// The stance foot's pitch at t of its timeline [0, 1 + TOM] (F1, then F2).
    pub fn stance_pitch(&self, t: f64) -> f64 {
        if t < self.phases.fgm {
            self.f1.at(t)
        } else {
            self.f2.at(t)
        }
    }

    /// The stance foot's toes' angle from the floor at t of its timeline (0 before MOM).
    pub fn stance_meta(&self, t: f64) -> f64 {
        if t < self.phases.mom {
            0.0
        } else {
            self.meta.at(t)
        }
    }

    /// The layout of docs/generalize.md: every number finite, the lengths positive, the phases
    /// in order and every sequence over its interval with strictly increasing times.
    pub fn check(&self) -> Result<(), GeneralizeError> {
        self.body.check()?;
        self.pelvis.check()?;
        self.character.check()?;
        for (name, v) in [
            ("step_length", self.step_length),
            ("step_length_before", self.step_length_before),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(GeneralizeError::invalid(
                    name,
                    format!("{v} m: a finite length > 0 is required"),
                ));
            }
        }
        let Phases {
            fgm,
            heel_off,
            mom,
            tom,
        } = self.phases;
        let ordered = [fgm, heel_off, mom, tom].iter().all(|x| x.is_finite())
            && (0.0..1.0).contains(&fgm)
            && tom > 0.0
            && tom < 1.0
            && fgm <= heel_off
            && heel_off <= mom
            && mom <= 1.0 + tom;
        if !ordered {
            return Err(GeneralizeError::invalid(
                "phases",
                format!(
                    "fgm {fgm}, heel_off {heel_off}, mom {mom}, tom {tom}: 0 ≤ fgm < 1, \
                     0 < tom < 1 and fgm ≤ heel_off ≤ mom ≤ 1 + tom are required"
                ),
            ));
        }
        let end = 1.0 + tom;
        check_times("hip", &self.hip.t, &[&self.hip.x, &self.hip.y], 0.0, 1.0)?;
        check_times("f1", &self.f1.t, &[&self.f1.shape], 0.0, fgm)?;
        check_times("f2", &self.f2.t, &[&self.f2.shape], fgm, end)?;
        check_times("f3", &self.f3.t, &[&self.f3.v], tom, 1.0)?;
        check_times("meta", &self.meta.t, &[&self.meta.shape], mom, end)?;
        check_times(
            "ankle",
            &self.ankle.t,
            &[&self.ankle.x, &self.ankle.y],
            tom,
            1.0,
        )?;
        check_times("trunk", &self.trunk.t, &[&self.trunk.v], 0.0, 1.0)?;
        for (name, a) in [
            ("f1.amplitude", self.f1.amplitude),
            ("f2.amplitude", self.f2.amplitude),
            ("meta.amplitude", self.meta.amplitude),
        ] {
            if !a.is_finite() {
                return Err(GeneralizeError::invalid(
                    name,
                    format!("{a}: a finite number is required"),
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A piece is its values again, anchored at either end; a zero anchor gets the ramp, which
    /// any amplitude then scales.
    #[test]
    fn pieces_hold_their_values() {
        let t = vec![0.0, 0.1, 0.3];
        let v = [-0.3, -0.1, 0.0];
        let p = Piece::new(t.clone(), &v, false, 1e-9);
        for (a, b) in p.values().iter().zip(v) {
            assert!((a - b).abs() < 1e-16);
        }
        assert!((p.at(0.2) + 0.05).abs() < 1e-15);
        let q = Piece::new(t.clone(), &[0.0, 0.0, 0.0], true, 1e-9);
        assert!((q.shape[1] - 1.0 / 3.0).abs() < 1e-15 && q.shape[2] == 1.0);
        assert_eq!(q.with_amplitude(0.6).values()[2], 0.6);
        let one = Piece::new(vec![0.0], &[0.0], false, 1e-9);
        assert_eq!(one.shape, vec![1.0]);
    }
}
