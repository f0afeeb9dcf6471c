//! Smooth blends between 0 and 1.

/// smoothstep(x) = 3x² − 2x³ on [0, 1], clamped: the cubic Hermite blend from 0 to 1 with zero
/// slope at both ends.
pub(crate) fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
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
}
