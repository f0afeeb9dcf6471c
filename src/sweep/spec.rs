//! Value specifications of the sweep flags and files: a number `X`, an inclusive range
//! `START:STOP:STEP` or a list `A,B,C`; `NAME=SPEC` of `--attr`; style names.
use std::path::Path;

use crate::model::InputError;
use crate::model::attributes::{AttributeTable, STYLES, unknown_style};

/// Largest number of values one flag may expand to.
pub(crate) const MAX_VALUES: usize = 1_000_000;
/// Relative tolerance with which a range's STOP is included.
const RANGE_TOLERANCE: f64 = 1e-9;

/// Why the values given for a sweep's parameter cannot be used (an
/// [`InputError::BadValue`] naming the parameter).
#[derive(Debug, thiserror::Error)]
pub enum SpecError {
    /// A value that is empty or blank.
    #[error("empty value")]
    Empty,
    /// A number that does not parse.
    #[error("`{text}` is not a number")]
    NotANumber {
        /// The text given, trimmed.
        text: String,
    },
    /// A number that is NaN or infinite.
    #[error("`{text}` is not a finite number")]
    NotFinite {
        /// The text given, trimmed.
        text: String,
    },
    /// A range that is not three numbers separated by `:`.
    #[error("range `{spec}` must be START:STOP:STEP (three numbers)")]
    RangeShape {
        /// The range given.
        spec: String,
    },
    /// A range whose STEP is 0.
    #[error("range `{spec}`: STEP must not be 0")]
    ZeroStep {
        /// The range given.
        spec: String,
    },
    /// STOP lies `side` ("below" or "above") START, against STEP's sign.
    #[error("range `{spec}`: STOP is {side} START for this STEP's sign")]
    Backwards {
        /// The range given.
        spec: String,
        /// Where STOP lies: `below` or `above` START.
        side: &'static str,
    },
    /// A range of more values than one flag may expand to (one million).
    #[error("range `{spec}` has more than {MAX_VALUES} values")]
    LongRange {
        /// The range given.
        spec: String,
    },
    /// A list with an empty item (`1,,2`, a trailing comma).
    #[error("empty item in list `{spec}`")]
    EmptyItem {
        /// The list given.
        spec: String,
    },
    /// A list of more values than one flag may expand to (one million).
    #[error("more than {MAX_VALUES} values")]
    LongList,
    /// An `--attr` argument without `=`.
    #[error("`{arg}` must be NAME=SPEC")]
    AttributeShape {
        /// The argument given.
        arg: String,
    },
    /// `--attr` naming no locomotion attribute; `known` lists them.
    #[error("unknown attribute `{name}`; known attributes: {known}")]
    UnknownAttribute {
        /// The name given.
        name: String,
        /// The locomotion attributes, comma-separated.
        known: String,
    },
    /// A parameter given twice among the flags.
    #[error("given twice")]
    GivenTwice,
    /// A parameter of the sweep with no values.
    #[error("no values")]
    NoValues,
    /// Both mass and mass per height² given.
    #[error("mass and mass_per_height2 exclude each other (M = K · H²): give one")]
    MassTwice,
    /// A step count that is not a whole number.
    #[error("{value} is not a whole number of steps")]
    NotWholeSteps {
        /// The value given (in steps).
        value: f64,
    },
}

/// The error of a bad value for the parameter `parameter`.
pub(super) fn bad(parameter: &str, reason: SpecError) -> InputError {
    InputError::bad_value(parameter, reason)
}

/// Round to 12 significant digits, so that `0.6 + 3 · 0.1` is written `0.9`.
pub(super) fn tidy(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    format!("{x:.11e}").parse().unwrap_or(x)
}

fn number(text: &str) -> Result<f64, SpecError> {
    let t = text.trim();
    let v: f64 = t
        .parse()
        .map_err(|_| SpecError::NotANumber { text: t.into() })?;
    if !v.is_finite() {
        return Err(SpecError::NotFinite { text: t.into() });
    }
    Ok(v)
}

/// Parse a value specification for the parameter `parameter` (e.g. `velocity`): a single
/// number `X`, an inclusive range `START:STOP:STEP` (STOP included within 1e-9 relative; STEP
/// may be negative when STOP < START) or a list `A,B,C`. Errors name the parameter.
pub fn parse_spec(parameter: &str, spec: &str) -> Result<Vec<f64>, InputError> {
    values(spec).map_err(|e| bad(parameter, e))
}

/// [`parse_spec`]'s values, or why there are none.
pub fn values(spec: &str) -> Result<Vec<f64>, SpecError> {
    let spec = spec.trim();
    if spec.is_empty() {
        return Err(SpecError::Empty);
    }
    if spec.contains(':') {
        let range = || spec.to_string();
        let parts: Vec<&str> = spec.split(':').collect();
        if parts.len() != 3 {
            return Err(SpecError::RangeShape { spec: range() });
        }
        let start = number(parts[0])?;
        let stop = number(parts[1])?;
        let step = number(parts[2])?;
        if step == 0.0 {
            return Err(SpecError::ZeroStep { spec: range() });
        }
        let span = (stop - start) / step;
        if span < 0.0 {
            let side = if step > 0.0 { "below" } else { "above" };
            return Err(SpecError::Backwards {
                spec: range(),
                side,
            });
        }
        let n = (span + RANGE_TOLERANCE * span.max(1.0)).floor();
        if !n.is_finite() || n + 1.0 > MAX_VALUES as f64 {
            return Err(SpecError::LongRange { spec: range() });
        }
        let n = n as usize;
        return Ok((0..=n)
            .map(|i| {
                if i == n && (span - n as f64).abs() <= RANGE_TOLERANCE * span.max(1.0) {
                    stop
                } else {
                    tidy(start + i as f64 * step)
                }
            })
            .collect());
    }
    let values = spec
        .split(',')
        .map(|t| {
            if t.trim().is_empty() {
                Err(SpecError::EmptyItem { spec: spec.into() })
            } else {
                number(t)
            }
        })
        .collect::<Result<Vec<_>, _>>()?;
    if values.len() > MAX_VALUES {
        return Err(SpecError::LongList);
    }
    Ok(values)
}

/// Parse `NAME=SPEC` of `--attr`; the name must be a locomotion attribute.
pub fn parse_attr(arg: &str, table: &AttributeTable) -> Result<(String, Vec<f64>), InputError> {
    let (name, spec) = arg.split_once('=').ok_or_else(|| {
        let arg = arg.into();
        bad("attr", SpecError::AttributeShape { arg })
    })?;
    let name = name.trim();
    if !table.0.contains_key(name) {
        let known: Vec<&str> = table.0.keys().map(String::as_str).collect();
        let (name, known) = (name.into(), known.join(", "));
        return Err(bad("attr", SpecError::UnknownAttribute { name, known }));
    }
    let values = parse_spec(&format!("attr {name}"), spec)?;
    Ok((name.to_string(), values))
}

/// Parse a list of style names `A,B,C` into their indices in `attributes::STYLES`.
pub fn parse_styles(spec: &str) -> Result<Vec<f64>, InputError> {
    spec.split(',')
        .map(|name| {
            let name = name.trim();
            STYLES
                .iter()
                .position(|(n, _)| *n == name)
                .map(|i| i as f64)
                .ok_or_else(|| InputError::bad_value("style", unknown_style(name)))
        })
        .collect()
}

/// Parse a list of body tables `A,B` into their indices in the sweep's tables: bundled names
/// or table files of your own (a value ending in `.toml` or containing a `/`, relative to `base`
/// when given, else to the working directory), each file read and checked here, once per
/// distinct path in the process.
pub fn parse_body_tables(spec: &str, base: Option<&Path>) -> Result<Vec<f64>, InputError> {
    spec.split(',')
        .map(|name| super::tables::index(name.trim(), base).map(|i| i as f64))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_value_and_list() {
        assert_eq!(parse_spec("height", "1.8").unwrap(), vec![1.8]);
        assert_eq!(
            parse_spec("height", "1.5, 1.65,1.8").unwrap(),
            vec![1.5, 1.65, 1.8]
        );
        assert_eq!(parse_spec("mass", "-3").unwrap(), vec![-3.0]);
    }

    #[test]
    fn floating_range_includes_its_stop() {
        let v = parse_spec("velocity", "0.6:2.0:0.1").unwrap();
        assert_eq!(v.len(), 15, "{v:?}");
        assert_eq!(v[0], 0.6);
        assert_eq!(v[3], 0.9);
        assert_eq!(*v.last().unwrap(), 2.0);
        let v = parse_spec("velocity", "0.1:0.3:0.1").unwrap();
        assert_eq!(v, vec![0.1, 0.2, 0.3]);
        let v = parse_spec("steps", "1:10:3").unwrap();
        assert_eq!(v, vec![1.0, 4.0, 7.0, 10.0]);
        let v = parse_spec("height", "2.0:1.5:-0.25").unwrap();
        assert_eq!(v, vec![2.0, 1.75, 1.5]);
        assert_eq!(parse_spec("height", "1.8:1.8:0.1").unwrap(), vec![1.8]);
    }

    #[test]
    fn bad_specs_name_the_flag() {
        for (flag, spec) in [
            ("velocity", ""),
            ("velocity", "abc"),
            ("velocity", "1,,2"),
            ("velocity", "1:2"),
            ("velocity", "1:2:3:4"),
            ("velocity", "1:2:0"),
            ("velocity", "2:1:0.1"),
            ("velocity", "1:x:0.1"),
            ("velocity", "nan"),
            ("velocity", "0:1e300:1e-300"),
        ] {
            let e = parse_spec(flag, spec).unwrap_err();
            assert!(matches!(e, InputError::BadValue { .. }), "{spec}: {e}");
            assert!(e.to_string().starts_with("velocity:"), "{spec}: {e}");
        }
        let table = AttributeTable::builtin();
        let e = parse_attr("nonsense=1", &table).unwrap_err().to_string();
        assert!(e.starts_with("attr:") && e.contains("nonsense"), "{e}");
        let e = parse_attr("bounciness", &table).unwrap_err().to_string();
        assert!(e.starts_with("attr:"), "{e}");
        let e = parse_attr("bounciness=x", &table).unwrap_err().to_string();
        assert!(e.starts_with("attr bounciness:"), "{e}");
        let (n, v) = parse_attr("bounciness=0.2,0.5", &table).unwrap();
        assert_eq!((n.as_str(), v), ("bounciness", vec![0.2, 0.5]));
    }
}
