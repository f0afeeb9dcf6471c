//! sin and cos together for the right-hand sides: libm's `sincos` costs ≈ 110 instructions a
//! call and was a third of a walk's instructions. Here: Cody–Waite reduction by π/2 and the
//! minimax polynomials of fdlibm's `__kernel_sin` / `__kernel_cos` (Sun Microsystems 1993, as in
//! FreeBSD msun and musl; error < 2⁻⁵⁸ on [−π/4, π/4]), ≈ 40 instructions, within 1 ulp of libm
//! (test below).
// the constants are fdlibm's decimal spellings of the exact doubles, digit for digit
#![allow(clippy::excessive_precision)]
use std::f64::consts::FRAC_2_PI;

/// Larger arguments go to libm (the two-part reduction below is exact for |n| < 2²⁰).
const REDUCTION_LIMIT: f64 = 1e5;
/// π/2 = PIO2_1 + PIO2_1T, PIO2_1 with 33 significant bits (fdlibm `__ieee754_rem_pio2`), so
/// that n · PIO2_1 is exact for |n| < 2²⁰.
const PIO2_1: f64 = 1.570_796_326_734_125_614_17e0;
const PIO2_1T: f64 = 6.077_100_506_506_192_249_32e-11;
/// 1.5 · 2⁵²: adding and subtracting it rounds to the nearest integer.
const ROUND: f64 = 6_755_399_441_055_744.0;

const S1: f64 = -1.666_666_666_666_663_243_48e-1;
const S2: f64 = 8.333_333_333_322_489_461_24e-3;
const S3: f64 = -1.984_126_982_985_794_931_34e-4;
const S4: f64 = 2.755_731_370_707_006_767_89e-6;
const S5: f64 = -2.505_076_025_340_686_341_95e-8;
const S6: f64 = 1.589_690_995_211_550_102_21e-10;
const C1: f64 = 4.166_666_666_666_660_190_37e-2;
const C2: f64 = -1.388_888_888_887_410_957_49e-3;
const C3: f64 = 2.480_158_728_947_672_941_78e-5;
const C4: f64 = -2.755_731_435_139_066_330_35e-7;
const C5: f64 = 2.087_572_321_298_174_827_90e-9;
const C6: f64 = -1.135_964_755_778_819_482_65e-11;

/// (sin x, cos x).
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if x.is_nan() || x.abs() >= REDUCTION_LIMIT {
        return x.sin_cos();
    }
    let k = x * FRAC_2_PI + ROUND;
    let quadrant = k.to_bits() & 3;
    let n = k - ROUND;
    let r = (x - n * PIO2_1) - n * PIO2_1T;
    let z = r * r;
    // __kernel_sin(r, 0, 0)
    let v = z * r;
    let s = r + v * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    // __kernel_cos(r, 0)
    let p = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let c = w + (((1.0 - w) - hz) + z * p);
    match quadrant {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against libm over [−40, 40] (every quadrant), next to multiples of π/4 and at the
    /// reduction's limit: within 1 ulp of max(|value|, 1). (Near the zeros the error is
    /// absolute, ≈ n · 1e-26 from the two-part π/2, not relative as libm's.)
    #[test]
    fn agrees_with_libm() {
        let mut worst: f64 = 0.0;
        let mut check = |x: f64| {
            let (s, c) = sin_cos(x);
            let (s0, c0) = x.sin_cos();
            let err = |a: f64, b: f64| (a - b).abs() / b.abs().max(1.0) / f64::EPSILON;
            worst = worst.max(err(s, s0)).max(err(c, c0));
        };
        for i in -400_000..=400_000 {
            check(i as f64 * 1e-4 + 3.7e-9);
        }
        for k in -100..=100 {
            let x = k as f64 * std::f64::consts::FRAC_PI_4;
            for d in [-1e-12, 0.0, 1e-12] {
                check(x + d);
            }
        }
        for x in [0.0, -0.0, 1e-300, 1e-8, 9.9e4, -9.9e4, 2e5, 1e300] {
            check(x);
        }
        assert!(worst <= 1.0, "worst error {worst} ulp");
        assert!(sin_cos(f64::NAN).0.is_nan());
    }
}
