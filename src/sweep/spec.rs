//! Value specifications of the sweep flags and files: a number `X`, an inclusive range
//! `START:STOP:STEP` or a list `A,B,C`; `NAME=SPEC` of `--attr`; style names.
use crate::error::{Error, Result};
use crate::model::attributes::{AttributeTable, STYLES};

/// Largest number of values one flag may expand to.
pub(crate) const MAX_VALUES: usize = 1_000_000;
/// Relative tolerance with which a range's STOP is included.
const RANGE_TOLERANCE: f64 = 1e-9;

/// The error of a bad value for `--flag`.
pub(super) fn bad(flag: &str, reason: impl Into<String>) -> Error {
    Error::BadSpec {
        flag: flag.to_string(),
        reason: reason.into(),
    }
}

/// Round to 12 significant digits, so that `0.6 + 3 · 0.1` is written `0.9`.
pub(super) fn tidy(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    format!("{x:.11e}").parse().unwrap_or(x)
}

fn number(flag: &str, text: &str) -> Result<f64> {
    let t = text.trim();
    let v: f64 = t
        .parse()
        .map_err(|_| bad(flag, format!("`{t}` is not a number")))?;
    if !v.is_finite() {
        return Err(bad(flag, format!("`{t}` is not a finite number")));
    }
    Ok(v)
}

/// Parse a value specification for `--flag`: a single number `X`, an inclusive range
/// `START:STOP:STEP` (STOP included within 1e-9 relative; STEP may be negative when
/// STOP < START) or a list `A,B,C`. Errors name the flag.
pub fn parse_spec(flag: &str, spec: &str) -> Result<Vec<f64>> {
    let spec = spec.trim();
    if spec.is_empty() {
        return Err(bad(flag, "empty value"));
    }
    if spec.contains(':') {
        let parts: Vec<&str> = spec.split(':').collect();
        if parts.len() != 3 {
            return Err(bad(
                flag,
                format!("range `{spec}` must be START:STOP:STEP (three numbers)"),
            ));
        }
        let start = number(flag, parts[0])?;
        let stop = number(flag, parts[1])?;
        let step = number(flag, parts[2])?;
        if step == 0.0 {
            return Err(bad(flag, format!("range `{spec}`: STEP must not be 0")));
        }
        let span = (stop - start) / step;
        if span < 0.0 {
            let dir = if step > 0.0 { "below" } else { "above" };
            return Err(bad(
                flag,
                format!("range `{spec}`: STOP is {dir} START for this STEP's sign"),
            ));
        }
        let n = (span + RANGE_TOLERANCE * span.max(1.0)).floor();
        if !n.is_finite() || n + 1.0 > MAX_VALUES as f64 {
            return Err(bad(
                flag,
                format!("range `{spec}` has more than {MAX_VALUES} values"),
            ));
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
                Err(bad(flag, format!("empty item in list `{spec}`")))
            } else {
                number(flag, t)
            }
        })
        .collect::<Result<Vec<_>>>()?;
    if values.len() > MAX_VALUES {
        return Err(bad(flag, format!("more than {MAX_VALUES} values")));
    }
    Ok(values)
}

/// Parse `NAME=SPEC` of `--attr`; the name must be a locomotion attribute.
pub fn parse_attr(arg: &str, table: &AttributeTable) -> Result<(String, Vec<f64>)> {
    let (name, spec) = arg
        .split_once('=')
        .ok_or_else(|| bad("attr", format!("`{arg}` must be NAME=SPEC")))?;
    let name = name.trim();
    if !table.0.contains_key(name) {
        let known: Vec<&str> = table.0.keys().map(String::as_str).collect();
        return Err(bad(
            "attr",
            format!(
                "unknown attribute `{name}`; known attributes: {}",
                known.join(", ")
            ),
        ));
    }
    let values = parse_spec(&format!("attr {name}"), spec)?;
    Ok((name.to_string(), values))
}

/// Parse a list of style names `A,B,C` into their indices in `attributes::STYLES`.
pub fn parse_styles(spec: &str) -> Result<Vec<f64>> {
    spec.split(',')
        .map(|name| {
            let name = name.trim();
            STYLES
                .iter()
                .position(|(n, _)| *n == name)
                .map(|i| i as f64)
                .ok_or_else(|| {
                    bad(
                        "style",
                        format!(
                            "unknown style `{name}`; the styles are {}",
                            STYLES
                                .iter()
                                .map(|(n, _)| *n)
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    )
                })
        })
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
            assert!(matches!(e, Error::BadSpec { .. }), "{spec}: {e}");
            assert!(e.to_string().starts_with("--velocity:"), "{spec}: {e}");
            assert_eq!(e.exit_code(), 2);
        }
        let table = AttributeTable::builtin();
        let e = parse_attr("nonsense=1", &table).unwrap_err().to_string();
        assert!(e.contains("--attr") && e.contains("nonsense"), "{e}");
        let e = parse_attr("bounciness", &table).unwrap_err().to_string();
        assert!(e.contains("--attr"), "{e}");
        let e = parse_attr("bounciness=x", &table).unwrap_err().to_string();
        assert!(e.contains("--attr bounciness"), "{e}");
        let (n, v) = parse_attr("bounciness=0.2,0.5", &table).unwrap();
        assert_eq!((n.as_str(), v), ("bounciness", vec![0.2, 0.5]));
    }
}
