//! sin and cos together for the right-hand sides, a fraction of libm's `sincos` cost
//! (docs/engine.md, "Numerics"): Cody–Waite reduction by π/2 and the minimax polynomials of
//! fdlibm's `__kernel_sin` / `__kernel_cos` (Sun Microsystems 1993, as in FreeBSD msun and musl;
//! error < 2⁻⁵⁸ on [−π/4, π/4]), within 1 ulp of libm (test below). Also `atan2` (fdlibm's,
//! below).
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
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    // |x| < π/4 (the stance leg, the trunk, the thigh): the reduction's n is 0 and r is x
    // itself, so the kernels alone give the same bits, without the reduction's five dependent
    // operations in front of them (a right-hand side waits for its sines)
    if x.abs() < std::f64::consts::FRAC_PI_4 {
        kernels(x)
    } else {
        reduced(x)
    }
}

/// [`sin_cos`] by Cody–Waite reduction by π/2 (libm beyond [`REDUCTION_LIMIT`] and for NaN).
#[inline]
fn reduced(x: f64) -> (f64, f64) {
    if x.is_nan() || x.abs() >= REDUCTION_LIMIT {
        return x.sin_cos();
    }
    let k = x * FRAC_2_PI + ROUND;
    let quadrant = k.to_bits() & 3;
    let n = k - ROUND;
    let (s, c) = kernels((x - n * PIO2_1) - n * PIO2_1T);
    match quadrant {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// fdlibm's `__kernel_sin(r, 0, 0)` and `__kernel_cos(r, 0)`, |r| ≤ π/4.
#[inline(always)]
fn kernels(r: f64) -> (f64, f64) {
    let z = r * r;
    // __kernel_sin(r, 0, 0)
    let v = z * r;
    let s = r + v * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    // __kernel_cos(r, 0)
    let p = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let c = w + (((1.0 - w) - hz) + z * p);
    (s, c)
}

/// fdlibm's `atan` (s_atan.c): atan(0.5), atan(1) = π/4, atan(1.5), atan(∞) = π/2 as high and
/// low parts (π/4 and π/2 are std's, the same doubles), and the coefficients of its odd
/// polynomial on [−7/16, 7/16].
const ATAN_HI: [f64; 4] = [
    4.636_476_090_008_060_935_15e-1,
    std::f64::consts::FRAC_PI_4,
    9.827_937_232_473_290_540_82e-1,
    std::f64::consts::FRAC_PI_2,
];
const ATAN_LO: [f64; 4] = [
    2.269_877_745_296_168_709_24e-17,
    3.061_616_997_868_383_017_93e-17,
    1.390_331_103_123_099_845_16e-17,
    6.123_233_995_736_766_035_87e-17,
];
const AT: [f64; 11] = [
    3.333_333_333_333_293_180_27e-1,
    -1.999_999_999_987_648_324_76e-1,
    1.428_571_427_250_346_637_11e-1,
    -1.111_111_040_546_235_578_80e-1,
    9.090_887_133_436_506_561_96e-2,
    -7.691_876_205_044_829_994_95e-2,
    6.661_073_137_387_531_206_69e-2,
    -5.833_570_133_790_573_486_45e-2,
    4.976_877_994_615_932_360_17e-2,
    -3.653_157_274_421_691_552_70e-2,
    1.628_582_011_536_578_236_23e-2,
];
/// π = PI_HI + PI_LO (fdlibm e_atan2.c's `pi`, `pi_lo`).
const PI_HI: f64 = std::f64::consts::PI;
const PI_LO: f64 = 1.224_646_799_147_353_177_2e-16;

/// atan t for t > 0 (fdlibm's `atan`: t reduced to |x| < 7/16 about 0.5, 1, 1.5 or ∞, then
/// the polynomial; error < 1 ulp).
#[inline]
fn atan_positive(t: f64) -> f64 {
    // the thresholds are fdlibm's high-word tests, exact as comparisons
    let (id, x) = if t < 0.4375 {
        (None, t)
    } else if t < 0.6875 {
        (Some(0), (2.0 * t - 1.0) / (2.0 + t))
    } else if t < 1.1875 {
        (Some(1), (t - 1.0) / (t + 1.0))
    } else if t < 2.4375 {
        (Some(2), (t - 1.5) / (1.0 + 1.5 * t))
    } else {
        (Some(3), -1.0 / t)
    };
    let z = x * x;
    let w = z * z;
    let s1 = z * (AT[0] + w * (AT[2] + w * (AT[4] + w * (AT[6] + w * (AT[8] + w * AT[10])))));
    let s2 = w * (AT[1] + w * (AT[3] + w * (AT[5] + w * (AT[7] + w * AT[9]))));
    match id {
        None => x - x * (s1 + s2),
        Some(i) => ATAN_HI[i] - ((x * (s1 + s2) - ATAN_LO[i]) - x),
    }
}

/// atan2(y, x) for the clinical angles' Euler decompositions, cheaper than libm's
/// (docs/engine.md, "Numerics"): fdlibm's `__ieee754_atan2` (e_atan2.c), atan of |y / x|, then
/// the quadrant; within 1 ulp of libm (test below; the kernel's error is < 1 ulp,
/// the division's rounding adds up to ½ ulp of the quotient). A zero quotient (y = ±0, or x
/// infinite) takes the same path and gives libm's ±0 and ±π; only when |y / x| is not finite —
/// x = ±0, y infinite, or a NaN — libm's `atan2` answers (its ±π/2 and NaN conventions).
#[inline]
pub(crate) fn atan2(y: f64, x: f64) -> f64 {
    let t = (y / x).abs();
    if !t.is_finite() {
        return y.atan2(x);
    }
    let z = atan_positive(t);
    match (x.is_sign_negative(), y.is_sign_negative()) {
        (false, false) => z,
        (false, true) => -z,
        (true, false) => PI_HI - (z - PI_LO),
        (true, true) => (z - PI_LO) - PI_HI,
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

    /// Below π/4 the kernels alone give the reduction's bits (n = 0, r = x).
    #[test]
    fn small_angles_skip_the_reduction_bit_for_bit() {
        let bits = |(s, c): (f64, f64)| (s.to_bits(), c.to_bits());
        for i in -100_000..=100_000 {
            let x = i as f64 * 7.853e-6 + 1.1e-11;
            assert_eq!(bits(sin_cos(x)), bits(reduced(x)), "{x}");
        }
        let below = std::f64::consts::FRAC_PI_4.next_down();
        for x in [below, -below, 0.0, -0.0, 1e-310] {
            assert_eq!(bits(sin_cos(x)), bits(reduced(x)), "{x}");
        }
    }

    /// The constants are fdlibm's doubles (its comments give their hex words).
    #[test]
    fn atan_constants_are_fdlibms() {
        let words = |c: f64| c.to_bits();
        assert_eq!(words(ATAN_HI[0]), 0x3FDD_AC67_0561_BB4F);
        assert_eq!(words(ATAN_HI[1]), 0x3FE9_21FB_5444_2D18);
        assert_eq!(words(ATAN_HI[2]), 0x3FEF_730B_D281_F69B);
        assert_eq!(words(ATAN_HI[3]), 0x3FF9_21FB_5444_2D18);
        assert_eq!(words(ATAN_LO[0]), 0x3C7A_2B7F_222F_65E2);
        assert_eq!(words(ATAN_LO[1]), 0x3C81_A626_3314_5C07);
        assert_eq!(words(ATAN_LO[2]), 0x3C70_0788_7AF0_CBBD);
        assert_eq!(words(ATAN_LO[3]), 0x3C91_A626_3314_5C07);
        let at = [
            0x3FD5_5555_5555_550D,
            0xBFC9_9999_9998_EBC4,
            0x3FC2_4924_9200_83FF,
            0xBFBC_71C6_FE23_1671,
            0x3FB7_45CD_C54C_206E,
            0xBFB3_B0F2_AF74_9A6D,
            0x3FB1_0D66_A0D0_3D51,
            0xBFAD_DE2D_52DE_FD9A,
            0x3FA9_7B4B_2476_0DEB,
            0xBFA2_B444_2C6A_6C2F,
            0x3F90_AD3A_E322_DA11,
        ];
        for (c, w) in AT.iter().zip(at) {
            assert_eq!(words(*c), w);
        }
        assert_eq!(words(PI_LO), 0x3CA1_A626_3314_5C07);
    }

    /// Against libm: angles all round the circle (every quadrant and octant, next to the
    /// reduction's thresholds 7/16, 11/16, 19/16, 39/16 and their reciprocals), radii from 1e-300
    /// to 1e300, within 1 ulp of the result; zeros, infinities and NaN exactly as libm.
    #[test]
    fn atan2_agrees_with_libm() {
        let mut worst: f64 = 0.0;
        let mut check = |y: f64, x: f64| {
            let (a, b) = (atan2(y, x), y.atan2(x));
            if b == 0.0 || !b.is_finite() || y == 0.0 || x.is_infinite() {
                assert!(
                    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()),
                    "{y} {x}"
                );
            } else {
                let ulp = f64::from_bits(b.abs().to_bits() + 1) - b.abs();
                worst = worst.max((a - b).abs() / ulp);
            }
        };
        for i in 0..2_000_000 {
            let angle = -3.2 + 6.4 * (i as f64 + 0.37) / 2e6;
            let (s, c) = angle.sin_cos();
            check(s, c);
            check(3e-7 * s, 3e-7 * c);
        }
        for t in [0.4375f64, 0.6875, 1.1875, 2.4375, 1.0, 0.5, 1.5] {
            for t in [t, 1.0 / t] {
                let mut u = t;
                for _ in 0..50 {
                    u = f64::from_bits(u.to_bits() - 1);
                }
                for _ in 0..100 {
                    u = f64::from_bits(u.to_bits() + 1);
                    for (sy, sx) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
                        check(sy * u, sx);
                        check(sy * 1.7 * u, sx * 1.7);
                    }
                }
            }
        }
        for r in [1e-300, 1e-160, 1e-20, 1.0, 1e20, 1e160, 1e300] {
            for (y, x) in [(0.3, 0.7), (-2.0, 0.1), (1e-5, -1.0), (-0.6, -0.8)] {
                check(y * r, x * r);
            }
        }
        // zeros, infinities, NaN, quotients that overflow or underflow: libm's answers, bit for
        // bit where y is zero or x infinite (±0, ±π)
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e-310,
            -1e300,
            f64::MIN_POSITIVE,
        ];
        for y in special {
            for x in special {
                check(y, x);
            }
        }
        assert!(worst <= 1.0, "worst error {worst} ulp");
    }
}

/// sin x and cos x by their Taylor polynomials to x⁵ and x⁶, for small angles such as the
/// pelvis's (|x| ≤ 0.2 rad: errors ≤ x⁷/5040 = 2.5e-9 and x⁸/40320 = 6e-11), at a fraction of
/// the cost of [`sin_cos`].
pub(crate) fn small_sin_cos(x: f64) -> (f64, f64) {
    let x2 = x * x;
    (
        x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0)),
        1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0)),
    )
}

#[cfg(test)]
mod small_angle_tests {
    use super::*;

    /// The small-angle sine and cosine against libm within their Taylor remainders.
    #[test]
    fn small_sin_cos_is_within_its_remainder() {
        for k in -200..=200 {
            let x = 0.2 * k as f64 / 200.0;
            let (s, c) = small_sin_cos(x);
            assert!(
                (s - x.sin()).abs() <= x.powi(7).abs() / 5040.0 + 1e-17,
                "{x}"
            );
            assert!((c - x.cos()).abs() <= x.powi(8) / 40320.0 + 1e-16, "{x}");
        }
    }
}
