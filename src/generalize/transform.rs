//! The generalizations (Ko & Badler 1992): to another step length, φ_ρ (§2, eqs. 12–30), to
//! another body, ψ (§4, eqs. 120–128), and both (§5, eqs. 150–153), as one map onto a target
//! walk condition (docs/generalize.md):
//!
//! - H: x by the affine map pinned at both ends, from the data's ends to the hip's places at the
//!   two heel strikes (−(1 − φ) sl_before and φ sl); y scaled by ll(S') / ll(S) (1 for φ, α for
//!   ψ) and moved linearly in t onto eq. 11's heights of the target (eqs. 13–14, 122–123
//!   corrected: the literal x′ = ρ′x matches neither end unless ρ = 1, and eq. 123's heights
//!   keep Theorem 4 only for similar bodies);
//! - F1, F2, M: their anchored values set to μ2 (of the previous step), μ3, μ4 (eqs. 20, 22,
//!   26);
//! - F3: moved linearly onto μ3 at TOM and −μ2 at heel strike (eq. 23, its normalized time
//!   measured from TOM);
//! - A: x pinned from its ends onto Lemma 1's b3x and b4x (eqs. 29, 127), y scaled like H's
//!   and moved linearly onto b3y and b4y (eqs. 30, 128).
//!
//! Every end value depends on the target alone, so a generalization of a generalization is the
//! direct one (Theorems 1–5) to round-off.
use crate::generalize::condition::BodyCondition;
use crate::generalize::error::GeneralizeError;
use crate::generalize::geometry::{
    Pelvis, ankle_after_strike, ankle_before_toe_off, hip_at_strike,
};
use crate::generalize::sequence::{Curve, Path, pinned};
use crate::generalize::walk_data::WalkData;

/// A walk condition to generalize to: the body, the step length and the step before it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    /// The body condition B(S').
    pub body: BodyCondition,
    /// The step length (m).
    pub step_length: f64,
    /// The previous step's length (m).
    pub step_length_before: f64,
    /// The walk's pelvic rotation and step width.
    pub pelvis: Pelvis,
}

impl Target {
    /// The walk condition of `w` itself.
    pub fn of(w: &WalkData) -> Self {
        Target {
            body: w.body,
            step_length: w.step_length,
            step_length_before: w.step_length_before,
            pelvis: w.pelvis,
        }
    }

    fn check(&self) -> Result<(), GeneralizeError> {
        self.body.check()?;
        self.pelvis.check()?;
        for (name, v) in [
            ("step length", self.step_length),
            ("previous step length", self.step_length_before),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(GeneralizeError::invalid(
                    name,
                    format!("{v} m: a finite length > 0 is required"),
                ));
            }
        }
        Ok(())
    }
}

/// `w` generalized to the walk condition `target` (module doc). Err: a step too long for the
/// target body (eq. 10), a degenerate swing (the data's swing ankle does not travel).
pub fn generalize(w: &WalkData, target: &Target) -> Result<WalkData, GeneralizeError> {
    target.check()?;
    let Target {
        body,
        step_length: sl,
        step_length_before: before,
        pelvis,
    } = *target;
    let c = &w.character;
    let ll = body.leg_length();
    let scale = ll / w.body.leg_length();
    let mu = c.mu(ll, sl);
    let mu_before = c.mu(ll, before);
    let tom = w.phases.tom;

    // H: the hips at the two heel strikes, in the stance foot's frame
    let start = hip_at_strike(&body, c, &pelvis, before)?;
    let end = hip_at_strike(&body, c, &pelvis, sl)?;
    let hip = moved(&w.hip, [start[0] - before, start[1]], end, scale, |t| t);

    // A: Lemma 1 of the target, the trailing foot's N at −sl_before
    let b3 = ankle_before_toe_off(&body, mu.toe_off, mu.meta);
    let b4 = ankle_after_strike(&body, sl, mu.strike);
    let a = &w.ankle;
    if a.x[a.x.len() - 1] - a.x[0] <= 0.0 {
        return Err(GeneralizeError::invalid(
            "ankle",
            "the swing ankle does not move forward from toe-off to heel strike",
        ));
    }
    let ankle = moved(a, [b3[0] - before, b3[1]], b4, scale, |t| {
        (t - tom) / (1.0 - tom)
    });

    // F3: from μ3 at TOM to −μ2 at heel strike (eq. 23 with t' = (t − TOM) / (1 − TOM))
    let f3 = {
        let (d1, d2) = (mu.toe_off - w.f3.first(), -mu.strike - w.f3.last());
        let v =
            w.f3.t
                .iter()
                .zip(&w.f3.v)
                .map(|(&t, &f)| {
                    let s = (t - tom) / (1.0 - tom);
                    f + (1.0 - s) * d1 + s * d2
                })
                .collect();
        Curve {
            t: w.f3.t.clone(),
            v,
        }
    };
    Ok(WalkData {
        source: w.source.clone(),
        body,
        step_length: sl,
        step_length_before: before,
        pelvis,
        character: w.character,
        phases: w.phases,
        hip,
        f1: w.f1.with_amplitude(-mu_before.strike),
        f2: w.f2.with_amplitude(mu.toe_off),
        f3,
        meta: w.meta.with_amplitude(mu.meta),
        ankle,
        trunk: w.trunk.clone(),
    })
}

/// A path moved onto new ends: x by the pinned affine map, y scaled by `scale` and moved
/// linearly in the weight `s(t)` (0 at the first sample, 1 at the last) onto the ends' heights.
fn moved(p: &Path, first: [f64; 2], last: [f64; 2], scale: f64, s: impl Fn(f64) -> f64) -> Path {
    let n = p.t.len() - 1;
    let from = (p.x[0], p.x[n]);
    let x =
        p.x.iter()
            .map(|&x| pinned(x, from, (first[0], last[0])))
            .collect();
    let (d1, d2) = (first[1] - scale * p.y[0], last[1] - scale * p.y[n]);
    let y =
        p.t.iter()
            .zip(&p.y)
            .map(|(&t, &y)| {
                let s = s(t);
                scale * y + (1.0 - s) * d1 + s * d2
            })
            .collect();
    Path {
        t: p.t.clone(),
        x,
        y,
    }
}

/// φ_ρ (eq. 31): the same body, the step ρ times as long, the step before it kept.
pub fn phi(w: &WalkData, rho: f64) -> Result<WalkData, GeneralizeError> {
    generalize(
        w,
        &Target {
            step_length: rho * w.step_length,
            ..Target::of(w)
        },
    )
}

/// ψ_S^S' (eq. 129): the body `body`, both step lengths (and the step width) scaled by
/// α = ll(S') / ll(S).
pub fn psi(w: &WalkData, body: &BodyCondition) -> Result<WalkData, GeneralizeError> {
    let alpha = body.leg_length() / w.body.leg_length();
    generalize(
        w,
        &Target {
            body: *body,
            step_length: alpha * w.step_length,
            step_length_before: alpha * w.step_length_before,
            pelvis: Pelvis {
                step_width: alpha * w.pelvis.step_width,
                ..w.pelvis
            },
        },
    )
}

/// The combined generalization to (S', sl') (eqs. 150–151): ψ_S^S' then
/// φ_{(S/S') (sl'/sl)}; by Theorem 4 the same as the other order.
pub fn combined(
    w: &WalkData,
    body: &BodyCondition,
    step_length: f64,
) -> Result<WalkData, GeneralizeError> {
    let to_body = psi(w, body)?;
    phi(&to_body, step_length / to_body.step_length)
}

/// A step of steady walking of the body `body` at step length `step_length` (the step before
/// it as long) with the pelvis `pelvis`: what the kinematic walk repeats.
pub fn steady(
    w: &WalkData,
    body: &BodyCondition,
    pelvis: &Pelvis,
    step_length: f64,
) -> Result<WalkData, GeneralizeError> {
    generalize(
        w,
        &Target {
            body: *body,
            step_length,
            step_length_before: step_length,
            pelvis: *pelvis,
        },
    )
}
