//! Smooth blends between 0 and 1.

/// smoothstep(x) = 3x² − 2x³ on [0, 1], clamped: the cubic Hermite blend from 0 to 1 with zero
/// slope at both ends.
pub(crate) fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// smootherstep(x) = 10x³ − 15x⁴ + 6x⁵ on [0, 1], clamped: the quintic blend from 0 to 1 with
/// zero slope and zero curvature at both ends (a motion started with it starts without a jump
/// in acceleration).
pub(crate) fn smootherstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * x * (10.0 + x * (6.0 * x - 15.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 0 and 1 at the ends (and beyond them), ½ in the middle, symmetric about it.
    #[test]
    fn smoothstep_blends_from_0_to_1() {
        assert_eq!((smoothstep(-1.0), smoothstep(0.0)), (0.0, 0.0));
        assert_eq!((smoothstep(1.0), smoothstep(2.0)), (1.0, 1.0));
        assert_eq!(smoothstep(0.5), 0.5);
        for x in [0.1, 0.25, 0.4] {
            assert!((smoothstep(x) + smoothstep(1.0 - x) - 1.0).abs() < 1e-15);
        }
    }

    /// 0 and 1 at the ends, ½ in the middle, symmetric; its slope 30x²(1 − x)² and curvature
    /// 60x(1 − x)(1 − 2x) against central differences, both 0 at the ends.
    #[test]
    fn smootherstep_starts_and_ends_at_rest() {
        assert_eq!((smootherstep(-1.0), smootherstep(0.0)), (0.0, 0.0));
        assert_eq!((smootherstep(1.0), smootherstep(2.0)), (1.0, 1.0));
        assert_eq!(smootherstep(0.5), 0.5);
        let h = 1e-4;
        for i in 1..100 {
            let x = i as f64 / 100.0;
            assert!((smootherstep(x) + smootherstep(1.0 - x) - 1.0).abs() < 1e-14);
            let d1 = (smootherstep(x + h) - smootherstep(x - h)) / (2.0 * h);
            let d2 = (smootherstep(x + h) - 2.0 * smootherstep(x) + smootherstep(x - h)) / (h * h);
            assert!(
                (d1 - 30.0 * x * x * (1.0 - x) * (1.0 - x)).abs() < 1e-6,
                "{x}"
            );
            assert!(
                (d2 - 60.0 * x * (1.0 - x) * (1.0 - 2.0 * x)).abs() < 1e-4,
                "{x}"
            );
        }
        let h = 1e-3;
        assert!(
            smootherstep(h) < 11.0 * h * h * h && smootherstep(1.0 - h) > 1.0 - 11.0 * h * h * h
        );
    }
}
