//! The laws of Ko & Badler 1992 for the generalizations of `klaw::generalize`, on random walk
//! data, bodies (similar and not) and ratios ρ: Lemmas 2 and 3 (the step length exact), Theorem
//! 1 (φ_ρ2 ∘ φ_ρ1 = φ_ρ1ρ2), Corollaries 1 and 2, Theorem 2 (transitive), Theorem 3 (ψ
//! transitive), Theorem 4 (φ and ψ commute), Theorem 5 (the combination transitive), the
//! identities at ρ = 1 and the same body, the similarity assumption, and the hip continuous
//! from step to step. The step length and the feet's contacts are measured from the data with
//! the foot's own geometry, not read from the code's targets.
use klaw::generalize::sequence::{Curve, Path, grid};
use klaw::generalize::{
    BodyCondition, Character, Pelvis, Phases, Piece, Target, WalkData, combined, generalize, phi,
    psi, steady,
};
use proptest::prelude::*;

/// The largest absolute difference between two walk data's numbers (∞ for different shapes).
fn difference(a: &WalkData, b: &WalkData) -> f64 {
    let mut d: f64 = 0.0;
    let mut cmp = |x: &[f64], y: &[f64]| {
        if x.len() != y.len() {
            d = f64::INFINITY;
            return;
        }
        for (p, q) in x.iter().zip(y) {
            d = d.max((p - q).abs());
        }
    };
    let body = |c: &BodyCondition| {
        vec![
            c.thigh,
            c.shin,
            c.heel_to_n,
            c.ankle_to_n,
            c.ball_to_n,
            c.ball_to_toe,
        ]
    };
    cmp(&body(&a.body), &body(&b.body));
    cmp(
        &[a.step_length, a.step_length_before],
        &[b.step_length, b.step_length_before],
    );
    cmp(&a.hip.t, &b.hip.t);
    cmp(&a.hip.x, &b.hip.x);
    cmp(&a.hip.y, &b.hip.y);
    for (p, q) in [(&a.f1, &b.f1), (&a.f2, &b.f2), (&a.meta, &b.meta)] {
        cmp(&p.t, &q.t);
        cmp(&p.values(), &q.values());
    }
    cmp(&a.f3.v, &b.f3.v);
    cmp(&a.ankle.x, &b.ankle.x);
    cmp(&a.ankle.y, &b.ankle.y);
    cmp(&a.trunk.v, &b.trunk.v);
    d
}

/// Rotate a foot-frame vector (x forward, y up, foot flat) by the pitch p (heel up +).
fn pitched(v: [f64; 2], p: f64) -> [f64; 2] {
    let (s, c) = p.sin_cos();
    [v[0] * c + v[1] * s, -v[0] * s + v[1] * c]
}

/// Where the landing foot stands after the step: the heel from the swing ankle's last point
/// and the swing foot's last pitch; returns (its N: heel x + hN, the heel's height).
fn landing(w: &WalkData) -> (f64, f64) {
    let a = w.ankle.last();
    let b = &w.body;
    let h = pitched([-b.heel_to_n, -b.ankle_to_n], w.f3.last());
    (a[0] + h[0] + b.heel_to_n, a[1] + h[1])
}

/// Where the trailing foot stood: its toe tip from the swing ankle's first point, the swing
/// foot's pitch at TOM and the stance toes' angle at toe-off (equal to the hind foot's);
/// returns (its N: toe x − bN − bt, the toe tip's height).
fn trailing(w: &WalkData) -> (f64, f64) {
    let a = w.ankle.first();
    let b = &w.body;
    let p = w.f3.first();
    let ball = pitched([b.ball_to_n, -b.ankle_to_n], p);
    let toe = pitched(
        [b.ball_to_toe, 0.0],
        p - (p - w.meta.values().last().unwrap()),
    );
    (
        a[0] + ball[0] + toe[0] - b.ball_to_n - b.ball_to_toe,
        a[1] + ball[1] + toe[1],
    )
}

fn body_strategy() -> impl Strategy<Value = BodyCondition> {
    (
        0.30..0.50f64,
        0.30..0.50f64,
        0.03..0.07f64,
        0.05..0.09f64,
        0.10..0.16f64,
        0.0..0.08f64,
        0.0..0.2f64,
    )
        .prop_map(|(thigh, shin, h, a, b, t, w)| BodyCondition {
            thigh,
            shin,
            heel_to_n: h,
            ankle_to_n: a,
            ball_to_n: b,
            ball_to_toe: t,
            pelvis_width: w,
        })
}

fn values(n: usize, lo: f64, hi: f64) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(lo..hi, n)
}

/// Random walk data: a body, step lengths of 0.45–0.8 leg lengths, a character, phases, and
/// sequences of random values on their intervals (not the ends of any walk: the laws hold for
/// any data).
fn walk_strategy() -> impl Strategy<Value = WalkData> {
    let character = (
        0.5..0.9f64,
        (0.0..0.3f64, 0.0..0.4f64, 0.3..1.2f64, 0.0..0.6f64),
        (-0.5..0.5f64, -0.5..0.5f64, -0.5..0.5f64, -0.5..0.5f64),
        (0.4..0.6f64, -0.02..0.02f64),
    )
        .prop_map(
            |(sl, (m1, m2, m3, m4), (a1, a2, a3, a4), (lead, off))| Character {
                step_length: sl,
                knee_at_strike: m1,
                foot_at_strike: m2,
                foot_at_toe_off: m3,
                meta_at_toe_off: m4,
                alpha: [a1, a2, a3, a4],
                hip_lead: lead,
                hip_offset: off,
            },
        );
    let phases =
        (0.02..0.2f64, 0.1..0.3f64, 0.0..1.0f64, 0.0..1.0f64).prop_map(|(fgm, tom, m, h)| {
            let mom = fgm + m * (1.0 + tom - fgm);
            Phases {
                fgm,
                heel_off: fgm + h * (mom - fgm),
                mom,
                tom,
            }
        });
    let pelvis = (0.0..0.15f64, 0.0..0.15f64).prop_map(|(rotation, step_width)| Pelvis {
        rotation,
        step_width,
    });
    (
        body_strategy(),
        (0.45..0.8f64, 0.45..0.8f64),
        character,
        phases,
        (values(9, -0.2, 0.2), values(9, 0.8, 1.0)),
        (
            values(4, -0.3, 0.0),
            values(7, 0.0, 1.0),
            values(6, -1.0, 0.4),
        ),
        (
            values(5, 0.0, 0.6),
            values(6, -0.5, 0.5),
            values(6, 0.0, 0.15),
        ),
        (values(9, -0.05, 0.05), pelvis),
    )
        .prop_map(
            |(
                body,
                (s, sb),
                character,
                ph,
                (hx, hy),
                (f1, f2, f3),
                (m, ax, ay),
                (trunk, pelvis),
            )| {
                let ll = body.leg_length();
                let end = 1.0 + ph.tom;
                let mut hx = hx;
                // the hip and the ankle move forward
                hx.sort_by(f64::total_cmp);
                let mut ax = ax;
                ax.sort_by(f64::total_cmp);
                ax[5] += 0.1;
                WalkData {
                    source: "random".into(),
                    body,
                    step_length: s * ll,
                    step_length_before: sb * ll,
                    pelvis,
                    character,
                    phases: ph,
                    hip: Path {
                        t: grid(0.0, 1.0, 8),
                        x: hx,
                        y: hy,
                    },
                    f1: Piece::new(grid(0.0, ph.fgm, 3), &f1, false, 1e-9),
                    f2: Piece::new(grid(ph.fgm, end, 6), &f2, true, 1e-9),
                    f3: Curve {
                        t: grid(ph.tom, 1.0, 5),
                        v: f3,
                    },
                    meta: Piece::new(grid(ph.mom, end, 4), &m, true, 1e-9),
                    ankle: Path {
                        t: grid(ph.tom, 1.0, 5),
                        x: ax,
                        y: ay,
                    },
                    trunk: Curve {
                        t: grid(0.0, 1.0, 8),
                        v: trunk,
                    },
                }
            },
        )
}

/// Walk data made consistent: generalized to its own walk condition (its ends on its
/// constraints).
fn consistent(w: &WalkData) -> WalkData {
    generalize(w, &Target::of(w)).unwrap()
}

const EXACT: f64 = 1e-9;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Lemma 2: φ_ρ makes the step ρ sl long, measured from where the landing foot's heel comes
    /// down, and leaves the previous step as it was; the landing heel and the trailing toe tip
    /// are on the floor. Lemma 3: ψ makes it ll(S')/ll(S) times as long.
    #[test]
    fn lemmas_2_and_3_the_step_length_is_exact(
        w in walk_strategy(), rho in 0.6..1.4f64, other in body_strategy()
    ) {
        let g = phi(&w, rho).unwrap();
        g.check().unwrap();
        let (n, heel) = landing(&g);
        prop_assert!((n - rho * w.step_length).abs() < EXACT, "{n} vs {}", rho * w.step_length);
        prop_assert!(heel.abs() < EXACT);
        let (n, toe) = trailing(&g);
        prop_assert!((n + w.step_length_before).abs() < EXACT, "{n}");
        prop_assert!(toe.abs() < EXACT);
        let p = psi(&w, &other).unwrap();
        let alpha = other.leg_length() / w.body.leg_length();
        let (n, heel) = landing(&p);
        prop_assert!((n - alpha * w.step_length).abs() < EXACT);
        prop_assert!(heel.abs() < EXACT);
        prop_assert!((trailing(&p).0 + alpha * w.step_length_before).abs() < EXACT);
        // the previous step is as it was: the stance foot lands and the hip starts as before
        let c = consistent(&w);
        let g = phi(&c, rho).unwrap();
        prop_assert!((g.f1.amplitude - c.f1.amplitude).abs() < EXACT);
        prop_assert!((g.hip.first()[0] - c.hip.first()[0]).abs() < EXACT);
        prop_assert!((g.hip.first()[1] - c.hip.first()[1]).abs() < EXACT);
    }

    /// Theorem 1, Corollaries 1 and 2, Theorem 2.
    #[test]
    fn theorem_1_and_its_corollaries(
        w in walk_strategy(), r1 in 0.7..1.3f64, r2 in 0.7..1.3f64, r3 in 0.8..1.2f64
    ) {
        let two = phi(&phi(&w, r1).unwrap(), r2).unwrap();
        let one = phi(&w, r1 * r2).unwrap();
        prop_assert!(difference(&two, &one) < EXACT, "{}", difference(&two, &one));
        // Corollary 1: commutative
        let other = phi(&phi(&w, r2).unwrap(), r1).unwrap();
        prop_assert!(difference(&two, &other) < EXACT);
        // Corollary 2: associative
        let left = phi(&phi(&phi(&w, r3).unwrap(), r2).unwrap(), r1).unwrap();
        let right = phi(&w, r1 * r2 * r3).unwrap();
        prop_assert!(difference(&left, &right) < EXACT);
        // Theorem 2: through sl2 to sl3 is straight to sl3
        let (sl1, sl2, sl3) = (w.step_length, r1 * w.step_length, r2 * w.step_length);
        let through = phi(&phi(&w, sl2 / sl1).unwrap(), sl3 / sl2).unwrap();
        let direct = phi(&w, sl3 / sl1).unwrap();
        prop_assert!(difference(&through, &direct) < EXACT);
    }

    /// Theorem 3: ψ_S1^S2 ∘ ψ_S^S1 = ψ_S^S2, for bodies of any proportions.
    #[test]
    fn theorem_3_psi_is_transitive(
        w in walk_strategy(), s1 in body_strategy(), s2 in body_strategy()
    ) {
        let two = psi(&psi(&w, &s1).unwrap(), &s2).unwrap();
        let one = psi(&w, &s2).unwrap();
        prop_assert!(difference(&two, &one) < EXACT, "{}", difference(&two, &one));
    }

    /// Theorem 4: φ_{(S1/S2)(sl2/sl1)} ∘ ψ_S1^S2 = ψ_S1^S2 ∘ φ_{(S1/S2)(sl2/sl1)}.
    #[test]
    fn theorem_4_phi_and_psi_commute(
        w in walk_strategy(), s2 in body_strategy(), k in 0.7..1.3f64
    ) {
        let sl2 = k * w.step_length * s2.leg_length() / w.body.leg_length();
        let rho = w.body.leg_length() / s2.leg_length() * sl2 / w.step_length;
        let lhs = phi(&psi(&w, &s2).unwrap(), rho).unwrap();
        let rhs = psi(&phi(&w, rho).unwrap(), &s2).unwrap();
        prop_assert!(difference(&lhs, &rhs) < EXACT, "{}", difference(&lhs, &rhs));
        prop_assert!(difference(&lhs, &combined(&w, &s2, sl2).unwrap()) < EXACT);
    }

    /// Theorem 5: τ23 ∘ τ12 = τ13 for the combined generalizations.
    #[test]
    fn theorem_5_the_combination_is_transitive(
        w in walk_strategy(), s2 in body_strategy(), s3 in body_strategy(),
        k2 in 0.8..1.2f64, k3 in 0.8..1.2f64
    ) {
        let sl = |s: &BodyCondition, k: f64| k * w.step_length * s.leg_length() / w.body.leg_length();
        let (sl2, sl3) = (sl(&s2, k2), sl(&s3, k3));
        let two = combined(&combined(&w, &s2, sl2).unwrap(), &s3, sl3).unwrap();
        let one = combined(&w, &s3, sl3).unwrap();
        prop_assert!(difference(&two, &one) < EXACT, "{}", difference(&two, &one));
    }

    /// At ρ = 1 and the same body the generalizations are the identity (on data whose ends are
    /// on its constraints: what extraction produces); a similar body scales every length by α
    /// and keeps every angle (§4's similarity assumption, eqs. 122, 124).
    #[test]
    fn identities_and_similarity(w in walk_strategy(), a in 0.8..1.25f64) {
        let c = consistent(&w);
        prop_assert!(difference(&phi(&c, 1.0).unwrap(), &c) < EXACT);
        prop_assert!(difference(&psi(&c, &c.body).unwrap(), &c) < EXACT);
        prop_assert!(difference(&consistent(&c), &c) < EXACT);
        let s = psi(&c, &c.body.scaled(a)).unwrap();
        for (x, y) in s.hip.x.iter().zip(&c.hip.x) {
            prop_assert!((x - a * y).abs() < EXACT);
        }
        for (x, y) in s.hip.y.iter().zip(&c.hip.y) {
            prop_assert!((x - a * y).abs() < EXACT);
        }
        for (x, y) in s.ankle.y.iter().zip(&c.ankle.y) {
            prop_assert!((x - a * y).abs() < EXACT);
        }
        prop_assert!((s.step_length - a * c.step_length).abs() < EXACT);
        for (p, q) in [(&s.f1, &c.f1), (&s.f2, &c.f2), (&s.meta, &c.meta)] {
            for (x, y) in p.values().iter().zip(q.values()) {
                prop_assert!((x - y).abs() < EXACT);
            }
        }
        for (x, y) in s.f3.v.iter().zip(&c.f3.v) {
            prop_assert!((x - y).abs() < EXACT);
        }
    }

    /// A steady walk of generalized steps: the hip at one step's end, moved into the next
    /// step's frame (back by the step length), is where the next step's hip starts; the swing
    /// foot lands as the next stance foot starts (pitch −μ2 both), and leaves as the hind foot
    /// (the stance foot's F2 and M at 1 + TOM) ends.
    #[test]
    fn the_hip_and_the_feet_are_continuous_from_step_to_step(
        w in walk_strategy(), other in body_strategy(), k in 0.6..1.4f64
    ) {
        let sl = k * w.step_length * other.leg_length() / w.body.leg_length();
        let g = steady(&w, &other, &w.pelvis, sl).unwrap();
        let (a, b) = (g.hip.first(), g.hip.last());
        prop_assert!((b[0] - sl - a[0]).abs() < EXACT && (b[1] - a[1]).abs() < EXACT);
        prop_assert!((g.f3.last() - g.f1.values()[0]).abs() < EXACT);
        prop_assert!((g.f3.first() - g.f2.values().last().unwrap()).abs() < EXACT);
    }
}

/// The paper's literal hip map x′ = ρ′x (eqs. 13, 15) on a steady walk's step: at ρ = 1.4 its
/// hip lands a tenth of a step length from where the next step's starts, at each end; the
/// pinned map lands on both.
#[test]
fn the_literal_hip_map_jumps_and_the_pinned_one_does_not() {
    let runner_w = {
        use proptest::strategy::ValueTree;
        let mut runner = proptest::test_runner::TestRunner::deterministic();
        walk_strategy().new_tree(&mut runner).unwrap().current()
    };
    let mut w = consistent(&runner_w);
    w.character.hip_lead = 0.5;
    w.body.pelvis_width = 0.0;
    let w = steady(&w, &w.body.clone(), &w.pelvis, w.step_length).unwrap();
    let (sl, rho) = (w.step_length, 1.4);
    let rho1 = (sl + rho * sl) / (sl + sl);
    let literal_end = rho1 * w.hip.last()[0];
    let jump = (literal_end - 0.5 * rho * sl).abs() / sl;
    assert!((jump - 0.1).abs() < 1e-9, "{jump}");
    let g = phi(&w, rho).unwrap();
    assert!((g.hip.last()[0] - 0.5 * rho * sl).abs() < 1e-12);
    assert!((g.hip.first()[0] + 0.5 * sl).abs() < 1e-12);
}
