//! The foot as a rigid hind/mid-foot with a toe segment at the 1st metatarsal joint (Table B-1:
//! l8, l9, l12, l13), and its two rolling rules (spec §7): about the metatarsal joint M while the
//! pitch is below the metatarsal limit θ6_max, then about the toe tip T.
use crate::model::body::Body;
use crate::numerics::roots;
use crate::numerics::trig::sin_cos;

/// How far under the ground or the floor a swing foot point may be and still keep the rule's
/// pitch in [`Foot::clear_pitch`] (m) \[ours\]: at toe-off the swing poses the hind leg's last
/// posture through another chain, and its toe tip, on the floor, comes out a rounding error
/// under it; clamped, a foot rolled to 69° by the hip's lead's push-off jumped to the end of
/// [`Foot::max_pitch`]'s search range (then π/3) for that one instant.
pub(crate) const CLEAR_SLACK: f64 = 1e-9;

/// The floor the swing foot's toe keeps above \[ours\]: c sin²(πs) at the fraction s of the
/// swing, rising from the ground at toe-off to the toe-clearance attribute c at mid swing and
/// back at heel strike (the engine's swing, the NRS's airborne foot and the kinematic mode's
/// swing foot alike, each through [`Foot::clear_pitch`]).
pub(crate) fn swing_floor(toe_clearance: f64, s: f64) -> f64 {
    toe_clearance * sin_cos(std::f64::consts::PI * s).0.powi(2)
}

/// Rotate a foot-frame vector (x forward, y up, foot flat) by the pitch p (heel up +).
#[inline]
pub(crate) fn pitch(v: [f64; 2], p: f64) -> [f64; 2] {
    rotate(v, sin_cos(p))
}

/// [`pitch`] by the pitch whose sine and cosine are (s, c).
#[inline]
pub(crate) fn rotate(v: [f64; 2], (s, c): (f64, f64)) -> [f64; 2] {
    [v[0] * c + v[1] * s, -v[0] * s + v[1] * c]
}

fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// Heel, metatarsal joint and toe tip.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FootPoints {
    pub(crate) heel: [f64; 2],
    pub(crate) meta: [f64; 2],
    pub(crate) toe: [f64; 2],
}

impl FootPoints {
    /// Lowest height of the foot's sole polygon (heel, M, T).
    pub fn lowest(&self) -> f64 {
        self.heel[1].min(self.meta[1]).min(self.toe[1])
    }
}

/// Foot dimensions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Foot {
    /// Heel behind the ankle (horizontal, foot flat).
    pub l8: f64,
    /// Ankle height (foot flat).
    pub l9: f64,
    /// Ankle to metatarsal joint, horizontal (foot flat).
    pub h12: f64,
    /// Metatarsal joint to toe tip.
    pub(crate) l13: f64,
    /// |(l8, l9)| and atan2(l9, l8) (the heel's reach in [`Self::min_pitch_closed_form`]), and
    /// |(h12, l9)| and atan2(l9, h12) (the metatarsal joint's in
    /// [`Self::max_pitch_closed_form`]), and the toe tip's there with the toe in line (θ6 = 0):
    /// constants of the foot, computed once.
    heel_reach: (f64, f64),
    meta_reach: (f64, f64),
    toe_reach: (f64, f64),
    /// −atan(l8 / l9): the pitch with the heel straight under the ankle, [`Self::min_pitch`]'s
    /// lower end.
    heel_lowest: f64,
}

/// `x.asin()`, without libm's domain-error path (errno and the floating-point exception before
/// its NaN for |x| > 1): the closed forms below take the asin of ratios that are often out of
/// range (the floor out of the foot's reach).
#[inline]
fn asin(x: f64) -> f64 {
    if x.abs() <= 1.0 { x.asin() } else { f64::NAN }
}

impl Foot {
    /// The foot of `body` (Table B-1: l8, l9, l12, l13).
    pub fn new(body: &Body) -> Self {
        let (l8, l9, h12) = (body.l8, body.l9, body.ankle_to_metatarsal_horizontal());
        Foot {
            l8,
            l9,
            h12,
            l13: body.l13,
            heel_reach: (l8.hypot(l9), l9.atan2(l8)),
            // (the crate's atan2: the rolling foot's arc about M takes its phase from here)
            meta_reach: (h12.hypot(l9), crate::numerics::trig::atan2(l9, h12)),
            toe_reach: Self::toe_reach(h12, l9, body.l13, 0.0),
            heel_lowest: -(l8 / l9).atan(),
        }
    }

    /// The toe tip's reach in [`Self::max_pitch_closed_form`] for toe angle θ6: |(a, b)| and
    /// atan2(b, a) with (a, b) = (h12 + l13 cos θ6, l9 − l13 sin θ6).
    fn toe_reach(h12: f64, l9: f64, l13: f64, theta6: f64) -> (f64, f64) {
        let (s6, c6) = sin_cos(theta6);
        let (a, b) = (h12 + l13 * c6, l9 - l13 * s6);
        (a.hypot(b), crate::numerics::trig::atan2(b, a))
    }

    /// |(h12, l9)| and atan2(l9, h12): the radius and phase of the ankle's circle about the
    /// metatarsal joint as the foot rolls over it (constants of the foot).
    pub(crate) fn meta_reach(&self) -> (f64, f64) {
        self.meta_reach
    }

    /// Foot points for an ankle at `ankle`, foot pitch `p` (heel up +) and toe dorsiflexion θ6.
    #[inline]
    pub(crate) fn points(&self, ankle: [f64; 2], p: f64, theta6: f64) -> FootPoints {
        let sc = sin_cos(p);
        // the toe's pitch p − θ6 is p itself with the toe in line (stance, most of the swing)
        let toe_sc = if theta6 == 0.0 {
            sc
        } else {
            sin_cos(p - theta6)
        };
        self.points_sc(ankle, sc, toe_sc)
    }

    /// [`Self::points`] from the (sin, cos) of the pitch p and of the toe's pitch p − θ6, for
    /// callers that have them already.
    #[inline]
    pub(crate) fn points_sc(
        &self,
        ankle: [f64; 2],
        sc: (f64, f64),
        toe_sc: (f64, f64),
    ) -> FootPoints {
        let meta = add(ankle, rotate([self.h12, -self.l9], sc));
        FootPoints {
            heel: add(ankle, rotate([-self.l8, -self.l9], sc)),
            meta,
            toe: add(meta, rotate([self.l13, 0.0], toe_sc)),
        }
    }

    /// The largest pitch (heel up +) at which the metatarsal joint and the toe tip of a foot with
    /// its ankle at height `ankle_y` and toe angle θ6 stay at or above `floor` (the lower of the
    /// two heights falls monotonically with the pitch on [−π/2, [`Self::max_pitch_end`]]).
    /// By bisection, steered by [`Self::max_pitch_closed_form`].
    pub(crate) fn max_pitch(&self, ankle_y: f64, theta6: f64, floor: f64) -> f64 {
        let meta = |p: f64| ankle_y + pitch([self.h12, -self.l9], p)[1];
        boundary(
            |p| {
                let m = meta(p);
                m.min(m + pitch([self.l13, 0.0], p - theta6)[1]) >= floor
            },
            (-std::f64::consts::FRAC_PI_2, self.max_pitch_end(theta6)),
            true,
            self.max_pitch_closed_form(ankle_y, theta6, floor),
        )
    }

    /// The end of the range on which [`Self::max_pitch`]'s heights fall with the pitch: the
    /// toe tip's lowest point, π/2 − atan2(l9 − l13 sin θ6, h12 + l13 cos θ6) (69° with the toe
    /// in line on the standard body). Beyond the metatarsal joint's own lowest point,
    /// π/2 − atan2(l9, h12), the toe tip is the lower of the two (the toe points down for
    /// p > θ6, and θ6 ≤ the metatarsal limit, at most 60°), so their minimum still falls. A swing
    /// foot rolled beyond π/3 at toe-off (the hip's lead's push-off) is thus clamped onto its
    /// floor continuously, not to the end of a shorter range.
    fn max_pitch_end(&self, theta6: f64) -> f64 {
        std::f64::consts::FRAC_PI_2 - self.toe_reach_at(theta6).1
    }

    /// [`Self::toe_reach`] for toe angle θ6, the toe in line (the swing's usual case) from the
    /// foot's constants.
    fn toe_reach_at(&self, theta6: f64) -> (f64, f64) {
        if theta6 == 0.0 {
            self.toe_reach
        } else {
            Self::toe_reach(self.h12, self.l9, self.l13, theta6)
        }
    }

    /// [`Self::max_pitch`] in closed form: the metatarsal joint is at height
    /// `ankle_y − (h12 sin p + l9 cos p)` and the toe tip at `ankle_y − (A sin p + B cos p)`
    /// with (A, B) = (h12 + l13 cos θ6, l9 − l13 sin θ6), so each reaches the floor where
    /// `sin(p + atan2(b, a)) = (ankle_y − floor) / |(a, b)|`; the boundary is the lower of the
    /// two (NaN when neither reaches it).
    /// (The toe in line, θ6 = 0, the swing's usual case, takes the toe's reach from the foot's
    /// constants.)
    fn max_pitch_closed_form(&self, ankle_y: f64, theta6: f64, floor: f64) -> f64 {
        let reach = |(r, angle): (f64, f64)| asin((ankle_y - floor) / r) - angle;
        reach(self.meta_reach).min(reach(self.toe_reach_at(theta6)))
    }

    /// The smallest pitch (heel up +) that keeps the heel at or above the ground, for an ankle at
    /// height `ankle_y` (the heel's height l8 sin p − l9 cos p rises with p from its lowest
    /// point, p = −atan(l8/l9) with the heel straight under the ankle, up to π/3).
    /// By bisection, steered by [`Self::min_pitch_closed_form`].
    pub(crate) fn min_pitch(&self, ankle_y: f64) -> f64 {
        boundary(
            |p| ankle_y + pitch([-self.l8, -self.l9], p)[1] >= 0.0,
            (self.heel_lowest, std::f64::consts::FRAC_PI_3),
            false,
            self.min_pitch_closed_form(ankle_y),
        )
    }

    /// [`Self::min_pitch`] in closed form: l8 sin p − l9 cos p = r sin(p − β) with
    /// r = |(l8, l9)| and β = atan2(l9, l8), so the heel touches at p = β − asin(ankle_y / r).
    fn min_pitch_closed_form(&self, ankle_y: f64) -> f64 {
        let (r, beta) = self.heel_reach;
        beta - asin(ankle_y / r)
    }

    /// The swing foot's pitch, and its points with the ankle at `ankle`: the rule's pitch when
    /// it keeps the heel on or above the ground and the toe on or above `floor` (to
    /// [`CLEAR_SLACK`]); otherwise the
    /// rule clamped into the range where both hold (the floor drops to the ground when both
    /// cannot hold).
    pub(crate) fn clear_pitch(
        &self,
        rule: f64,
        ankle: [f64; 2],
        theta6: f64,
        floor: f64,
    ) -> (f64, FootPoints) {
        let pts = self.points(ankle, rule, theta6);
        if pts.heel[1] >= -CLEAR_SLACK && pts.meta[1].min(pts.toe[1]) >= floor - CLEAR_SLACK {
            return (rule, pts);
        }
        let ankle_y = ankle[1];
        let lo = self.min_pitch(ankle_y);
        let mut hi = self.max_pitch(ankle_y, theta6, floor);
        if hi < lo {
            hi = self.max_pitch(ankle_y, theta6, 0.0).max(lo);
        }
        let pitch = rule.clamp(lo, hi);
        (pitch, self.points(ankle, pitch, theta6))
    }

    /// Ankle of a foot rolling over the ground whose metatarsal joint stood at `meta_x` when the
    /// foot was flat: about M (toe flat, θ6 = p) while p ≤ θ6_max, then about the toe tip with
    /// θ6 = θ6_max. Returns the ankle and θ6.
    pub fn rolling_ankle(&self, meta_x: f64, p: f64, theta6_max: f64) -> ([f64; 2], f64) {
        if p <= theta6_max {
            (sub([meta_x, 0.0], pitch([self.h12, -self.l9], p)), p)
        } else {
            let toe = [meta_x + self.l13, 0.0];
            let meta = sub(toe, pitch([self.l13, 0.0], p - theta6_max));
            (sub(meta, pitch([self.h12, -self.l9], p)), theta6_max)
        }
    }

    /// [`Self::rolling_ankle`] and the foot's [`Self::points`] there, each sine and cosine
    /// computed once (the same numbers: the toe's pitch p − θ6 is 0 while rolling about M, and
    /// `sin_cos(0)` is (0, 1)). Returns the ankle, θ6 and the points.
    pub(crate) fn rolling_points(
        &self,
        meta_x: f64,
        p: f64,
        theta6_max: f64,
    ) -> ([f64; 2], f64, FootPoints) {
        let sc = sin_cos(p);
        if p <= theta6_max {
            let ankle = sub([meta_x, 0.0], rotate([self.h12, -self.l9], sc));
            (ankle, p, self.points_sc(ankle, sc, (0.0, 1.0)))
        } else {
            let toe_sc = sin_cos(p - theta6_max);
            let meta = sub([meta_x + self.l13, 0.0], rotate([self.l13, 0.0], toe_sc));
            let ankle = sub(meta, rotate([self.h12, -self.l9], sc));
            (ankle, theta6_max, self.points_sc(ankle, sc, toe_sc))
        }
    }
}

/// The pitch on [lo, hi] where `ok` changes, to 1e-12 rad (its closed form `guess`, NaN for
/// none): `ok` holds below the boundary when `below` (a good pitch at most 1e-12 below the
/// boundary is returned), above it otherwise (at most 1e-12 above). Returns the end of the
/// range when `ok` holds, or fails, everywhere. `ok` changes at most once on the range (the
/// heights it compares are monotonic there), so when the guess lies inside the range, the
/// guess moved [`GUESS_SLACK`] to the good side where `ok` holds and 1e-12 further to the bad
/// side where it fails is the boundary to 1e-12, in two evaluations of `ok`; else
/// [`roots::bisect_with_guess`].
fn boundary(ok: impl Fn(f64) -> bool, (lo, hi): (f64, f64), below: bool, guess: f64) -> f64 {
    let (good, bad) = if below { (lo, hi) } else { (hi, lo) };
    if guess > lo && guess < hi {
        let toward_bad = if below { 1.0 } else { -1.0 };
        let p = guess - toward_bad * GUESS_SLACK;
        if ok(p) && !ok(p + toward_bad * 1e-12) {
            return p;
        }
        if let Some(p) = roots::bisect_steered(&ok, good, bad, 1e-12, guess, GUESS_SLACK) {
            return p;
        }
    }
    if ok(bad) {
        return bad;
    }
    if !ok(good) {
        return good;
    }
    roots::bisect_with_guess(ok, good, bad, 1e-12, guess, GUESS_SLACK)
}

/// Within this distance (rad) of a closed-form boundary [`roots::bisect_steered`] evaluates its
/// predicate: the closed forms are exact to ≈ 1e-15 rad, and 2e-13 rad moves a foot point by
/// ≈ 2e-14 m, still far more than the round-off of the heights and distances the predicates
/// compare (≈ 1e-17 m). The bisection stops at 1e-12 rad, so few of its last midpoints fall
/// within it (each costs an evaluation). [`boundary`] returns the guess moved by it to the good
/// side, where the predicate is checked.
pub(crate) const GUESS_SLACK: f64 = 2e-13;

#[cfg(test)]
mod tests {
    use super::*;

    fn foot() -> Foot {
        Foot::new(&Body::standard(1.8, 80.0).unwrap())
    }

    #[test]
    fn flat_foot_stands_on_heel_meta_and_toe() {
        let f = foot();
        let pts = f.points([0.3, f.l9], 0.0, 0.0);
        for p in [pts.heel, pts.meta, pts.toe] {
            assert!(p[1].abs() < 1e-15);
        }
        assert!((pts.toe[0] - pts.heel[0] - (f.l8 + f.h12 + f.l13)).abs() < 1e-15);
    }

    #[test]
    fn rolling_keeps_the_pivot_on_the_ground_and_is_continuous() {
        let f = foot();
        let lim = 0.6;
        for i in 0..=100 {
            let p = 1.2 * i as f64 / 100.0;
            let (ankle, t6) = f.rolling_ankle(0.5, p, lim);
            let pts = f.points(ankle, p, t6);
            if p <= lim {
                assert!((pts.meta[0] - 0.5).abs() < 1e-14 && pts.meta[1].abs() < 1e-14);
                assert!(pts.toe[1].abs() < 1e-14, "toe flat while rolling about M");
            } else {
                assert!((pts.toe[0] - 0.5 - f.l13).abs() < 1e-14 && pts.toe[1].abs() < 1e-14);
            }
            // nothing goes below the ground while rolling
            assert!(pts.lowest() > -1e-14);
        }
        let (a, _) = f.rolling_ankle(0.5, lim, lim);
        let (b, _) = f.rolling_ankle(0.5, lim + 1e-9, lim);
        assert!((a[0] - b[0]).abs() < 1e-8 && (a[1] - b[1]).abs() < 1e-8);
    }

    /// The clearance limits sit exactly where the toe meets its floor and the heel the ground.
    #[test]
    fn pitch_limits_touch_the_floor() {
        let f = foot();
        let ankle_y = 0.12;
        let p = f.max_pitch(ankle_y, 0.1, 0.01);
        let pts = f.points([0.0, ankle_y], p, 0.1);
        assert!((pts.meta[1].min(pts.toe[1]) - 0.01).abs() < 1e-9, "{pts:?}");
        for ankle_y in [0.06, 0.065] {
            let p = f.min_pitch(ankle_y);
            assert!(
                f.points([0.0, ankle_y], p, 0.0).heel[1].abs() < 1e-9,
                "{ankle_y}"
            );
        }
        // the rule is kept when it is clear, clamped when it is not
        assert_eq!(f.clear_pitch(0.2, [0.0, 0.3], 0.0, 0.01).0, 0.2);
        let (clamped, pts) = f.clear_pitch(1.0, [0.1, ankle_y], 0.0, 0.01);
        assert_eq!(pts, f.points([0.1, ankle_y], clamped, 0.0));
        assert!(clamped < 1.0 && f.points([0.0, ankle_y], clamped, 0.0).lowest() >= 0.01 - 1e-9);
    }

    /// A swing foot rolled beyond π/3 (a push-off to 66°) whose toe tip is 0.1 mm under its
    /// floor is turned just far enough to clear it: the pitch changes by the toe's height over its
    /// rate (≈ 0.01 rad), not to the π/3 end of a shorter search range (0.1 rad), and the toe
    /// sits on the floor.
    #[test]
    fn a_foot_rolled_past_sixty_degrees_clears_its_floor_continuously() {
        let f = foot();
        let rule = 1.15;
        let toe_at_zero = f.points([0.0, 0.0], rule, 0.0).toe[1];
        let ankle = [0.0, 0.005 - toe_at_zero];
        let (p, pts) = f.clear_pitch(rule, ankle, 0.0, 0.0051);
        assert!(p < rule && rule - p < 0.02, "{p}");
        assert!((pts.toe[1] - 0.0051).abs() < 1e-9, "{:?}", pts.toe);
    }

    /// The clearance limits' closed forms are the boundaries their predicates change at (to
    /// 1e-12 rad, against bisection alone), and the limits are within 1e-12 rad of bisection
    /// alone's, on the good side with the bad side 1e-12 beyond, over a grid of ankle heights,
    /// toe angles and floors.
    #[test]
    fn pitch_limits_closed_forms_are_the_bisections() {
        let f = foot();
        let (lo_min, hi) = (-(f.l8 / f.l9).atan(), std::f64::consts::FRAC_PI_3);
        let lo_max = -std::f64::consts::FRAC_PI_2;
        let (mut steered_min, mut steered_max) = (0, 0);
        for i in 0..=400 {
            let ankle_y = 0.02 + 0.0005 * i as f64;
            let heel_ok = |p: f64| ankle_y + pitch([-f.l8, -f.l9], p)[1] >= 0.0;
            if !heel_ok(lo_min) && heel_ok(hi) {
                let plain = roots::bisect(heel_ok, hi, lo_min, 1e-12).0;
                assert!((f.min_pitch_closed_form(ankle_y) - plain).abs() < 1e-12);
                let p = f.min_pitch(ankle_y);
                assert!((p - plain).abs() <= 1e-12 && heel_ok(p) && !heel_ok(p - 1e-12));
                steered_min += 1;
            }
            for theta6 in [0.0, 0.15, 0.3, 0.6, 1.0] {
                for floor in [0.0, 0.005, 0.01, 0.03] {
                    let meta = |p: f64| ankle_y + pitch([f.h12, -f.l9], p)[1];
                    let ok =
                        |p: f64| meta(p).min(meta(p) + pitch([f.l13, 0.0], p - theta6)[1]) >= floor;
                    let hi_max = f.max_pitch_end(theta6);
                    if ok(lo_max) && !ok(hi_max) {
                        let plain = roots::bisect(ok, lo_max, hi_max, 1e-12).0;
                        let closed = f.max_pitch_closed_form(ankle_y, theta6, floor);
                        assert!((closed - plain).abs() < 1e-12, "{ankle_y} {theta6} {floor}");
                        let p = f.max_pitch(ankle_y, theta6, floor);
                        assert!((p - plain).abs() <= 1e-12 && ok(p) && !ok(p + 1e-12));
                        steered_max += 1;
                    }
                    let reference = plain_boundary(ok, (lo_max, hi_max), true);
                    assert!((f.max_pitch(ankle_y, theta6, floor) - reference).abs() <= 1e-12);
                }
            }
            let reference = plain_boundary(heel_ok, (lo_min, hi), false);
            assert!((f.min_pitch(ankle_y) - reference).abs() <= 1e-12);
        }
        assert!(
            steered_min > 5 && steered_max > 50,
            "{steered_min} {steered_max}"
        );
    }

    /// [`boundary`] without a guess: the range's ends checked, then plain bisection.
    fn plain_boundary(ok: impl Fn(f64) -> bool, (lo, hi): (f64, f64), below: bool) -> f64 {
        let (good, bad) = if below { (lo, hi) } else { (hi, lo) };
        if ok(bad) {
            bad
        } else if !ok(good) {
            good
        } else {
            roots::bisect(ok, good, bad, 1e-12).0
        }
    }

    /// The foot's constants are their expressions, and the asin without libm's domain error is
    /// libm's inside [−1, 1] and NaN outside.
    #[test]
    fn constants_and_asin_are_what_they_replace() {
        let f = foot();
        assert_eq!(f.heel_lowest, -(f.l8 / f.l9).atan());
        let (a, b) = (f.h12 + f.l13, f.l9);
        assert_eq!(
            f.toe_reach,
            (a.hypot(b), crate::numerics::trig::atan2(b, a))
        );
        assert_eq!(f.toe_reach, Foot::toe_reach(f.h12, f.l9, f.l13, 0.0));
        for i in -300..=300 {
            let x = i as f64 / 200.0;
            for x in [x, x.next_up(), x.next_down()] {
                let (ours, libm) = (asin(x), x.asin());
                assert!(ours == libm || (ours.is_nan() && libm.is_nan()), "{x}");
            }
        }
        assert!(asin(f64::NAN).is_nan() && asin(f64::INFINITY).is_nan());
    }

    /// [`Foot::rolling_points`] is [`Foot::rolling_ankle`] then [`Foot::points`], bit for bit,
    /// on both rolling rules and at their switch.
    #[test]
    fn rolling_points_are_the_ankle_then_the_points() {
        let f = foot();
        let lim = 0.6;
        for i in -10..=150 {
            for p in [i as f64 * 0.01, i as f64 * 0.01 + 1e-13, lim] {
                let (ankle, t6) = f.rolling_ankle(0.5, p, lim);
                let (a, t, pts) = f.rolling_points(0.5, p, lim);
                assert_eq!((a, t), (ankle, t6), "{p}");
                assert_eq!(pts, f.points(ankle, p, t6), "{p}");
            }
        }
    }

    /// Rotating about the heel: the distances between the foot points are those of the body
    /// table for any pitch (rigid foot).
    #[test]
    fn foot_is_rigid() {
        let f = foot();
        let b = Body::standard(1.8, 80.0).unwrap();
        for p in [-0.4, 0.0, 0.3, 1.0] {
            let a = [0.1, 0.2];
            let pts = f.points(a, p, 0.0);
            let d = |u: [f64; 2], v: [f64; 2]| (u[0] - v[0]).hypot(u[1] - v[1]);
            assert!((d(a, pts.heel) - b.l11).abs() < 1e-14);
            assert!((d(a, pts.meta) - b.l12).abs() < 1e-14);
            assert!((d(pts.meta, pts.toe) - b.l13).abs() < 1e-14);
        }
    }
}
