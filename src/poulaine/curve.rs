//! The poulaine's curve model (Pronost et al. §3.2): per ankle, four characteristic points and
//! four cubic Hermite (Coons) segments between them, closed and C¹, parameterized by the
//! cycle's phase φ = t / T ∈ [0, 1).
//!
//! Points, in the cycle's order: (1) the ankle at its highest, (2) most forward, (3) under the
//! pelvis in support (x nearest 0 between 2 and 4), (4) most backward. Between knots k and k+1
//! (phases φ_k < φ_{k+1}, cyclically), with s = (φ − φ_k) / Δ_k:
//!
//! `p(φ) = h₀₀(s) P_k + h₁₀(s) Δ_k m_k + h₀₁(s) P_{k+1} + h₁₁(s) Δ_k m_{k+1}`,
//!
//! h₀₀ = 2s³ − 3s² + 1, h₁₀ = s³ − 2s² + s, h₀₁ = −2s³ + 3s², h₁₁ = s³ − s²; m_k is the
//! derivative dp/dφ at knot k (m per cycle), shared by the segments on either side: the curve
//! passes through the points and its velocity is continuous.
//!
//! \[ours\] Each coordinate is its own closed curve with its own four knots ([`Component`]): a
//! fitted poulaine has the same knots on its three coordinates, and the database's selection
//! (§4) takes each coordinate from a different poulaine, knots and all.
//!
//! The shape and the speed along it are apart (§3.2, "the shape of the trajectories but not
//! the speed … an average profile computed after isolation, synchronization and normalization
//! of walk cycles according to the duration of the steps and the size of the trajectories"):
//! the curve's parameter ψ runs through the knots at their phases (the characteristic points
//! are the synchronization), and within knot interval k the ankle is at ψ = φ_k + Δ_k g_k(s)
//! at the time s = (φ − φ_k) / Δ_k of the interval ([`Speed`], both normalized to [0, 1]).
//! With g_k(s) = s the parameter is the phase itself.
use serde::{Deserialize, Serialize};

/// The Hermite basis (h₀₀, h₁₀, h₀₁, h₁₁) at s.
pub fn hermite(s: f64) -> [f64; 4] {
    let (s2, s3) = (s * s, s * s * s);
    [
        2.0 * s3 - 3.0 * s2 + 1.0,
        s3 - 2.0 * s2 + s,
        -2.0 * s3 + 3.0 * s2,
        s3 - s2,
    ]
}

/// One coordinate of one ankle: a closed C¹ cubic Hermite curve through four knots.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Component {
    /// The knots' phases, in [0, 1), increasing cyclically from the first (not necessarily
    /// from 0: the first may follow the last across the cycle's end).
    pub phase: [f64; 4],
    /// The coordinate at the knots (m).
    pub value: [f64; 4],
    /// Its derivative at the knots, d/dψ (m per unit of the curve's parameter ψ, which passes
    /// the knots at their phases: m per cycle when ψ is the phase).
    pub slope: [f64; 4],
}

impl Component {
    /// The knot interval holding phase φ: its index k, the local s and the interval Δ_k. The
    /// interval starts at the knot last passed (the least (φ − φ_k) mod 1); s is at most 1, so
    /// a φ a rounding error short of a knot stays at the end of the interval before it (a
    /// fall-through to the last interval put s at (1 − ε) / Δ₃ and the cubic far off the curve).
    pub fn locate(&self, phi: f64) -> (usize, f64, f64) {
        let phi = phi.rem_euclid(1.0);
        let since = |k: usize| (phi - self.phase[k]).rem_euclid(1.0);
        let k = (0..4)
            .min_by(|&a, &b| since(a).total_cmp(&since(b)))
            .expect("four knots");
        let d = (self.phase[(k + 1) % 4] - self.phase[k]).rem_euclid(1.0);
        (k, (since(k) / d).min(1.0), d)
    }

    /// The coordinate at the curve's parameter ψ = `phi` (the phase itself when the speed
    /// profile is the identity; [`LegCurve::at`] maps a phase to ψ).
    pub fn at(&self, phi: f64) -> f64 {
        let (k, s, d) = self.locate(phi);
        let [a, b, c, e] = hermite(s);
        let j = (k + 1) % 4;
        a * self.value[k] + b * d * self.slope[k] + c * self.value[j] + e * d * self.slope[j]
    }

    /// The same coordinate with its knots moved to the phases `to` \[ours, for a poulaine
    /// combined from several entries ([`crate::poulaine::Database::poulaine`])\]: the values at
    /// the knots kept, each knot's slope scaled by its two neighbouring intervals' total span
    /// before over after, so that the coordinate crosses each knot at the same rate per share
    /// of its surrounding intervals.
    pub fn retimed(&self, to: [f64; 4]) -> Component {
        let span = |p: &[f64; 4], k: usize| (p[(k + 1) % 4] - p[k]).rem_euclid(1.0);
        let around = |p: &[f64; 4], k: usize| span(p, k) + span(p, (k + 3) % 4);
        Component {
            phase: to,
            value: self.value,
            slope: std::array::from_fn(|k| self.slope[k] * around(&self.phase, k) / around(&to, k)),
        }
    }

    /// The knots' phases are distinct and in [0, 1), and every number finite.
    pub fn is_valid(&self) -> bool {
        let finite = self.value.iter().chain(&self.slope).all(|v| v.is_finite());
        let spans: f64 = (0..4)
            .map(|k| (self.phase[(k + 1) % 4] - self.phase[k]).rem_euclid(1.0))
            .sum();
        finite
            && self.phase.iter().all(|p| (0.0..1.0).contains(p))
            && (0..4).all(|k| self.phase[k] != self.phase[(k + 1) % 4])
            && (spans - 1.0).abs() < 1e-9
    }
}

/// The samples of each interval's speed profile after the first (at s = j / [`SPEED_STEPS`]).
pub const SPEED_STEPS: usize = 24;

/// The speed along one ankle's curve (module doc): per knot interval k, the normalized
/// parameter g_k at the normalized times s = j / [`SPEED_STEPS`], from 0 to 1 nondecreasing,
/// linear between.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Speed(pub [[f64; SPEED_STEPS + 1]; 4]);

impl Default for Speed {
    /// g_k(s) = s: the parameter is the phase.
    fn default() -> Self {
        Speed([std::array::from_fn(|j| j as f64 / SPEED_STEPS as f64); 4])
    }
}

impl Speed {
    /// g_k(s), linear between the samples.
    pub fn warp(&self, k: usize, s: f64) -> f64 {
        let u = s.clamp(0.0, 1.0) * SPEED_STEPS as f64;
        let j = (u.floor() as usize).min(SPEED_STEPS - 1);
        let g = &self.0[k];
        g[j] + (u - j as f64) * (g[j + 1] - g[j])
    }

    /// Whether every profile runs from 0 to 1 nondecreasing, every number finite.
    pub fn is_valid(&self) -> bool {
        self.0.iter().all(|g| {
            g[0] == 0.0
                && g[SPEED_STEPS] == 1.0
                && g.iter().all(|v| v.is_finite())
                && g.windows(2).all(|w| w[1] >= w[0])
        })
    }

    /// The mean of `profiles` (none: the identity).
    pub fn mean<'a>(profiles: impl IntoIterator<Item = &'a Speed>) -> Speed {
        let mut sum = [[0.0; SPEED_STEPS + 1]; 4];
        let mut n = 0;
        for p in profiles {
            for (a, b) in sum.iter_mut().flatten().zip(p.0.iter().flatten()) {
                *a += b;
            }
            n += 1;
        }
        if n == 0 {
            return Speed::default();
        }
        let mut mean = Speed(sum.map(|g| g.map(|v| v / n as f64)));
        for g in &mut mean.0 {
            (g[0], g[SPEED_STEPS]) = (0.0, 1.0);
        }
        mean
    }
}

/// One ankle's curve: its x (forward), y (up) and z (right) coordinates, and the speed along
/// them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LegCurve {
    /// x, forward.
    pub x: Component,
    /// y, up.
    pub y: Component,
    /// z, to the right.
    pub z: Component,
    /// The speed profile (absent in a file: the parameter is the phase).
    #[serde(default)]
    pub speed: Speed,
}

impl LegCurve {
    /// The ankle at phase φ: each coordinate at its parameter ψ (module doc).
    pub fn at(&self, phi: f64) -> [f64; 3] {
        let at = |c: &Component| {
            let (k, s, d) = c.locate(phi);
            c.at(c.phase[k] + d * self.speed.warp(k, s))
        };
        [at(&self.x), at(&self.y), at(&self.z)]
    }

    /// The ankle at the curve's own parameter ψ (the shape, whatever the speed).
    pub fn shape_at(&self, psi: f64) -> [f64; 3] {
        [self.x.at(psi), self.y.at(psi), self.z.at(psi)]
    }

    /// The components.
    pub fn components(&self) -> [&Component; 3] {
        [&self.x, &self.y, &self.z]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn component() -> Component {
        Component {
            phase: [0.8, 0.1, 0.35, 0.6],
            value: [0.1, 0.4, 0.0, -0.35],
            slope: [2.0, -0.5, -1.5, 0.3],
        }
    }

    /// The curve passes through its knots with their slopes, and it is C¹ across every knot and
    /// across the cycle's end (central differences of the value on either side agree).
    #[test]
    fn it_interpolates_the_knots_and_is_c1_and_closed() {
        let c = component();
        assert!(c.is_valid());
        let h = 1e-6;
        for k in 0..4 {
            let p = c.phase[k];
            assert!((c.at(p) - c.value[k]).abs() < 1e-12);
            let left = (c.at(p) - c.at(p - h)) / h;
            let right = (c.at(p + h) - c.at(p)) / h;
            assert!((left - c.slope[k]).abs() < 1e-4, "{k}: {left}");
            assert!((right - c.slope[k]).abs() < 1e-4, "{k}: {right}");
        }
        assert!((c.at(0.999_999_999) - c.at(0.0)).abs() < 1e-6);
        assert_eq!(c.at(1.25), c.at(0.25));
    }

    /// A cubic is reproduced exactly by Hermite segments with its values and derivatives at the
    /// knots (the basis's defining property), here p(φ) = φ³ − φ on one span.
    #[test]
    fn a_cubic_is_reproduced() {
        let p = |t: f64| t * t * t - t;
        let dp = |t: f64| 3.0 * t * t - 1.0;
        let (a, b) = (0.2, 0.7);
        let d = b - a;
        for s in [0.0, 0.3, 0.5, 0.9] {
            let [h0, h1, h2, h3] = hermite(s);
            let v = h0 * p(a) + h1 * d * dp(a) + h2 * p(b) + h3 * d * dp(b);
            assert!((v - p(a + s * d)).abs() < 1e-14);
        }
    }

    /// A phase one rounding step short of a knot, however the knots lie across the cycle's end,
    /// reads the knot's value (to the curve's slope times the step), not the last interval's
    /// cubic far beyond its end.
    #[test]
    fn a_phase_a_hair_short_of_a_knot_reads_the_knot() {
        let mut c = component();
        for phase in [
            c.phase,
            [
                0.17272727272727276,
                0.4545454545454545,
                0.7636363636363634,
                0.10909090909090895,
            ],
        ] {
            c.phase = phase;
            for k in 0..4 {
                let p = c.phase[k];
                for q in [
                    f64::from_bits(p.to_bits() - 1),
                    f64::from_bits(p.to_bits() - 3),
                    p + 1.0 - 1e-16,
                ] {
                    assert!(
                        (c.at(q) - c.value[k]).abs() < 1e-9,
                        "knot {k} at {q}: {}",
                        c.at(q)
                    );
                }
            }
        }
    }

    /// Retimed, a coordinate passes its knot values at the new phases; onto its own phases it
    /// is unchanged, and there and back it comes back to its last bits; a knot whose two
    /// intervals together keep their span keeps its slope, and one whose intervals grow from
    /// 0.5 to 0.65 of the cycle takes 0.5 / 0.65 of it.
    #[test]
    fn retiming_moves_the_knots_and_keeps_their_values() {
        let c = component();
        assert_eq!(c.retimed(c.phase), c);
        let to = [0.75, 0.05, 0.4, 0.55];
        let r = c.retimed(to);
        assert!(r.is_valid());
        let back = r.retimed(c.phase);
        for (k, &p) in to.iter().enumerate() {
            assert!((r.at(p) - c.value[k]).abs() < 1e-12);
            assert!((back.slope[k] - c.slope[k]).abs() < 1e-12);
        }
        // knot 0: intervals 0.6→0.8 and 0.8→0.1 (0.5 together) become 0.55→0.75 and 0.75→0.05
        // (0.5): its slope kept; knot 2: 0.1→0.35 and 0.35→0.6 (0.5) become 0.05→0.4 and
        // 0.4→0.55 (0.5): kept too
        assert!((r.slope[0] - c.slope[0]).abs() < 1e-12 && (r.slope[2] - c.slope[2]).abs() < 1e-12);
        let squeezed = c.retimed([0.9, 0.05, 0.2, 0.7]);
        // knot 2: 0.1→0.35→0.6 (0.5) become 0.05→0.2→0.7 (0.65)
        assert!((squeezed.slope[2] - c.slope[2] * 0.5 / 0.65).abs() < 1e-12);
    }

    #[test]
    fn bad_knots_are_invalid() {
        let mut c = component();
        c.phase = [0.1, 0.35, 0.8, 0.6];
        assert!(!c.is_valid());
        let mut c = component();
        c.slope[2] = f64::NAN;
        assert!(!c.is_valid());
    }

    /// The speed moves the ankle along the shape, never off it: with g(s) = s², the ankle at
    /// phase φ in interval k is the shape at φ_k + Δ_k s², it still passes the knots at their
    /// phases, and the mean of two profiles is their pointwise mean (hand-computed at s = ½).
    #[test]
    fn the_speed_moves_the_ankle_along_the_shape() {
        let c = component();
        let square = Speed([std::array::from_fn(|j| (j as f64 / SPEED_STEPS as f64).powi(2)); 4]);
        assert!(square.is_valid() && Speed::default().is_valid());
        let leg = LegCurve {
            x: c,
            y: c,
            z: c,
            speed: square,
        };
        for (k, s) in [(0, 0.5), (1, 0.25), (2, 0.75), (3, 0.0)] {
            let d = (c.phase[(k + 1) % 4] - c.phase[k]).rem_euclid(1.0);
            let got = leg.at(c.phase[k] + d * s)[0];
            assert!(
                (got - c.at(c.phase[k] + d * s * s)).abs() < 1e-12,
                "{k} {s}"
            );
            assert!((leg.at(c.phase[k])[1] - c.value[k]).abs() < 1e-12);
        }
        let mean = Speed::mean([&square, &Speed::default()]);
        assert!((mean.warp(2, 0.5) - (0.25 + 0.5) / 2.0).abs() < 1e-12);
        assert_eq!(Speed::mean([]), Speed::default());
        let mut back = square;
        back.0[1][4] = 0.9;
        assert!(!back.is_valid());
    }
}
