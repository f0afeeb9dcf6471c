//! The numbers of the motion files (CSV, `.mot` / `.sto`, BVH), one rule for all of them:
//! - a finite value is written in its shortest round-trip form (Ryū: the fewest significant
//!   digits that parse back to the same `f64`, the closest such when there are several), so a
//!   reader gets back the exact value klaw computed;
//! - an integer value is written without a fraction (`1`, not `1.0`), as integers are: frame
//!   counts and steps;
//! - a zero of either sign is written `0`: `-0` carries no information about a motion (it is the
//!   sign of a zero product, e.g. a negated zero offset) and some readers keep it as a distinct
//!   value; every other value keeps its sign and digits, however small (the writers stream, so a
//!   column's scale is not known when its first values are written, and flushing a small value
//!   to zero would lose the round trip);
//! - very small and very large magnitudes are written with an exponent (`1.5e-7`, `2e16`), which
//!   every reader of these formats accepts (C's `strtod`, C++'s `std::stod` in OpenSim's file
//!   adapters, Python's `float` in Blender's BVH importer); NaN and infinities as `NaN`, `inf`,
//!   `-inf`.
//!
//! The rule and its reasons are in `docs/export.md`.
use std::fmt;

/// `v` as the motion files write it (the rule of this module), in `buffer`.
fn text(buffer: &mut ryu::Buffer, v: f64) -> &str {
    if v == 0.0 {
        // -0.0 == 0.0
        return "0";
    }
    let s = buffer.format(v);
    // Ryū writes an integer value below 1e16 as `123.0`
    s.strip_suffix(".0").unwrap_or(s)
}

/// Append `v` to `out` as the motion files write numbers (the rule of this module).
pub(crate) fn push_f64(out: &mut Vec<u8>, v: f64) {
    out.extend_from_slice(text(&mut ryu::Buffer::new(), v).as_bytes());
}

/// Append the integer `n` to `out` in decimal.
pub(crate) fn push_usize(out: &mut Vec<u8>, n: usize) {
    out.extend_from_slice(itoa::Buffer::new().format(n).as_bytes());
}

/// An `f64` that displays as the motion files write numbers (the rule of this module): for the
/// numbers of a file's header.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Number(pub f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(text(&mut ryu::Buffer::new(), self.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn written(v: f64) -> String {
        let mut out = Vec::new();
        push_f64(&mut out, v);
        let s = String::from_utf8(out).unwrap();
        assert_eq!(s, Number(v).to_string());
        s
    }

    #[test]
    fn zeros_integers_and_exponents() {
        assert_eq!(written(0.0), "0");
        assert_eq!(written(-0.0), "0");
        assert_eq!(written(1.0), "1");
        assert_eq!(written(-222.0), "-222");
        assert_eq!(written(0.1 + 0.2), "0.30000000000000004");
        assert_eq!(written(1e-7), "1e-7");
        assert_eq!(written(-1.5e-12), "-1.5e-12");
        assert_eq!(written(1e16), "1e16");
        assert_eq!(written(1234567890123456.0), "1234567890123456");
        assert_eq!(written(f64::MIN_POSITIVE / 2.0), "1.1125369292536007e-308");
        assert_eq!(written(f64::NAN), "NaN");
        assert_eq!(written(f64::INFINITY), "inf");
        assert_eq!(written(f64::NEG_INFINITY), "-inf");
        let mut out = Vec::new();
        push_usize(&mut out, 0);
        out.push(b',');
        push_usize(&mut out, 22220);
        assert_eq!(out, b"0,22220");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]

        /// Every finite f64 (any bit pattern: subnormals, the largest, both zeros) parses back to
        /// the same bits, -0 to +0; the text has no `-0` and parses to what the standard library's
        /// shortest form (the writers' former `{}`) parses to.
        #[test]
        fn every_finite_value_round_trips(bits in any::<u64>()) {
            let v = f64::from_bits(bits);
            prop_assume!(v.is_finite());
            let s = written(v);
            let back: f64 = s.parse().unwrap();
            let want = if v == 0.0 { 0.0 } else { v };
            prop_assert_eq!(back.to_bits(), want.to_bits(), "{} → {}", v, s);
            prop_assert_eq!(back.to_bits(), (format!("{v}").parse::<f64>().unwrap() + 0.0).to_bits());
            prop_assert!(s != "-0" && !s.starts_with("-0e"), "{}", s);
        }

        /// Ordinary values too (the bit patterns above are mostly huge or tiny exponents).
        #[test]
        fn ordinary_values_round_trip(v in -1e4f64..1e4) {
            let s = written(v);
            prop_assert_eq!(s.parse::<f64>().unwrap().to_bits(), (v + 0.0).to_bits());
        }
    }
}
