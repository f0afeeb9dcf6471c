//! The knee's prescribed flexion from heel-off to toe-off (spec §7).

/// Knee flexion after heel-off (spec §7: "a C¹ cubic from its value and rate at heel-off to
/// κ_TO at toe-off"): the cubic Hermite from (κ0, κ̇0) at t0 to (κ_TO, κ̇_TO) at t_to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KneeCurve {
    /// Where the curve starts: heel-off, or the next heel strike where it is re-anchored (s).
    pub t0: f64,
    pub(crate) kappa0: f64,
    pub(crate) rate0: f64,
    pub(crate) t_to: f64,
    pub(crate) kappa_to: f64,
    pub(crate) rate_to: f64,
}

/// The knee's rate at toe-off as a multiple of its mean rate from heel-off \[ours\]: the knee
/// stays nearly straight after heel-off and folds in pre-swing, as in human gait (Perry: ≈ 5° at
/// 40 % of the cycle, 35–40° at toe-off, still flexing), while the foot rolls up and the ankle
/// plantarflexes. With a start rate of 0 the cubic is κ0 + (κ_TO − κ0) s³ at 3, the largest
/// multiple at which it never dips below κ0 (at R it is (R − 2) s³ − (R − 3) s² of the rise).
pub(crate) const TOE_OFF_KNEE_RATE: f64 = 3.0;

impl KneeCurve {
    /// The curve from (κ0, κ̇0) at t0 to κ_TO at t_to, reaching it at TOE_OFF_KNEE_RATE × the
    /// mean rate. A start rate below −κ0 / (t_to − t0) is raised to it \[ours\]: the cubic then
    /// starts no steeper down than the line to a straight knee at toe-off and cannot swing
    /// through hyperextension (a flat-foot knee that straightens into heel-off has an unbounded
    /// rate, the acos of a distance at its maximum).
    pub(crate) fn new(t0: f64, kappa0: f64, rate0: f64, t_to: f64, kappa_to: f64) -> Self {
        KneeCurve {
            t0,
            kappa0,
            rate0: rate0.max(-kappa0.max(0.0) / (t_to - t0)),
            t_to,
            kappa_to,
            rate_to: TOE_OFF_KNEE_RATE * (kappa_to - kappa0) / (t_to - t0),
        }
    }

    /// Value and rate at t.
    pub(crate) fn at(&self, t: f64) -> (f64, f64) {
        let d = self.t_to - self.t0;
        let s = (t - self.t0) / d;
        let (p0, m0, p1, m1) = (self.kappa0, self.rate0 * d, self.kappa_to, self.rate_to * d);
        let (s2, s3) = (s * s, s * s * s);
        let value = (2.0 * s3 - 3.0 * s2 + 1.0) * p0
            + (s3 - 2.0 * s2 + s) * m0
            + (-2.0 * s3 + 3.0 * s2) * p1
            + (s3 - s2) * m1;
        let rate = ((6.0 * s2 - 6.0 * s) * p0
            + (3.0 * s2 - 4.0 * s + 1.0) * m0
            + (-6.0 * s2 + 6.0 * s) * p1
            + (3.0 * s2 - 2.0 * s) * m1)
            / d;
        (value, rate)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// From rest at heel-off the curve is κ0 + (κ_TO − κ0) s³ (the toe-off rate 3 × the mean),
    /// so the knee never flexes less than at heel-off and has risen by an eighth of its rise
    /// half-way.
    #[test]
    fn from_rest_the_knee_rises_as_the_cube_of_the_time() {
        let (k0, k1) = (0.1, 0.7);
        let c = KneeCurve::new(2.0, k0, 0.0, 2.4, k1);
        for i in 0..=100 {
            let s = i as f64 / 100.0;
            let (v, _) = c.at(2.0 + 0.4 * s);
            assert!((v - (k0 + (k1 - k0) * s.powi(3))).abs() < 1e-12, "{s}: {v}");
        }
    }

    /// The knee curve meets its ends (value and rate, the start rate unless bounded) and never
    /// hyperextends, even from a knee straightening fast into heel-off; checked on a dense grid.
    #[test]
    fn knee_curve_meets_its_ends_and_never_hyperextends() {
        for (k0, r0) in [
            (0.2, 0.5),
            (0.15, -0.2),
            (0.01, -50.0),
            (0.0, -1e6),
            (0.1, -0.4),
        ] {
            let c = KneeCurve::new(1.0, k0, r0, 1.3, 0.7);
            let (v0, d0) = c.at(1.0);
            let (v1, d1) = c.at(1.3);
            assert!((v0 - k0).abs() < 1e-12 && (v1 - 0.7).abs() < 1e-12);
            assert!((d1 - TOE_OFF_KNEE_RATE * (0.7 - k0) / 0.3).abs() < 1e-9);
            if r0 >= -k0 / 0.3 {
                assert!((d0 - r0).abs() < 1e-9, "{k0} {r0}: {d0}");
            }
            for i in 0..=1000 {
                let (v, _) = c.at(1.0 + 0.3 * i as f64 / 1000.0);
                assert!(v >= -1e-12, "{k0} {r0}: {v} at {i}");
            }
        }
    }
}
