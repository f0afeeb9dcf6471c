//! What can be wrong with the inputs of a walk, from the body and the attributes to the gait:
//! the errors of the model and plan levels, and of the files and values that give them.
use std::error::Error;
use std::path::{Path, PathBuf};

/// The reason of [`InputError::BadValue`] and [`InputError::Malformed`]: the error of the value's
/// parser or of the file's format (a TOML error, the BVH parser's), or the rule broken, in words.
pub type Reason = Box<dyn Error + Send + Sync>;

/// An input that cannot be walked: out of its range, not finite, inconsistent, unknown, or a
/// file or value that cannot be parsed.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// A number outside its valid range.
    #[error(
        "{name} = {}{}{note} is out of range: valid range is [{}, {}]{}",
        Shown(*value), spaced(unit), Shown(*min), Shown(*max), spaced(unit)
    )]
    OutOfRange {
        /// The quantity's name.
        name: String,
        /// The value given (in `unit`).
        value: f64,
        /// Valid range's lower end (in `unit`).
        min: f64,
        /// Valid range's upper end (in `unit`).
        max: f64,
        /// The unit of `value`, `min` and `max`.
        unit: String,
        /// Where the value came from when the user did not give it, as ` (…)`: derived by the
        /// normalizing formula, or a default; empty for a value given as it is.
        note: String,
    },
    /// A speed beyond the body's walk–run transition: a Froude number v² / (g l) above the
    /// attribute `froude_max` (l the leg length l1).
    #[error(
        "velocity = {} m/s{note} is beyond the walk–run transition for this body: valid range is \
         [{}, {}] m/s (Froude number v²/(g·l) ≤ {}, leg length l = {} m)",
        Shown(*value), Shown(*min), Shown(*max), Shown(*froude_max), Shown(*leg)
    )]
    BeyondWalkRun {
        /// The velocity (in m/s).
        value: f64,
        /// The valid range's lower end (in m/s).
        min: f64,
        /// The body's limit √(Fr_max g l), rounded down to 0.1 mm/s (in m/s).
        max: f64,
        /// The largest Froude number Fr_max.
        froude_max: f64,
        /// The leg length l (in m).
        leg: f64,
        /// Where the value came from, as in [`InputError::OutOfRange`].
        note: String,
    },
    /// NaN or infinity where a number was expected.
    #[error("{name} is {value}: a finite number is required")]
    NotFinite {
        /// The quantity's name.
        name: String,
        /// The value given: NaN or ±infinity.
        value: f64,
    },
    /// A count that is not a whole number.
    #[error("{name} = {value} is not a whole number")]
    NotWhole {
        /// The count's name.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// v, sl and sf all given but v ≠ sl·sf/60.
    #[error(
        "inconsistent gait: velocity {} m/s, step length {} m and step frequency {} steps/min \
         imply {implied:.4} m/s (v = sl·sf/60); they must agree to within {tolerance_pct}%",
        Shown(*velocity), Shown(*step_length), Shown(*step_frequency)
    )]
    Inconsistent {
        /// The velocity given (in m/s).
        velocity: f64,
        /// The step length given (in m).
        step_length: f64,
        /// The step frequency given (in steps/min).
        step_frequency: f64,
        /// The velocity that step length and frequency imply, sl·sf/60 (in m/s).
        implied: f64,
        /// The largest relative difference allowed between `velocity` and `implied` (in %).
        tolerance_pct: f64,
    },
    /// The gait leaves no double support (KLAW 1989 eq. 2): that is running, not walking.
    #[error(
        "step frequency {} steps/min leaves no double support (t_ds = {t_ds:.4} s): \
         walking needs sf < 181.75 steps/min",
        Shown(*step_frequency)
    )]
    NoDoubleSupport {
        /// The step frequency (in steps/min).
        step_frequency: f64,
        /// The double-support time it gives, zero or negative (in s).
        t_ds: f64,
    },
    /// A step too long for the leg: the swing heel cannot reach the ground at heel strike (the
    /// step constraints, spec §3).
    #[error("step length {} m: the swing heel cannot reach the ground", Shown(*step_length))]
    StepTooLong {
        /// The step length (in m).
        step_length: f64,
    },
    /// Neither velocity, step length nor step frequency was given.
    #[error("no gait given: give at least one of velocity, step length, step frequency")]
    MissingGait,
    /// An attribute name that the model does not know.
    #[error("unknown attribute `{name}` in {source_name}; known attributes: {known}")]
    UnknownAttribute {
        /// The name given.
        name: String,
        /// Where the name came from: an attribute file, a style, `--attr`.
        source_name: String,
        /// The known attributes, comma-separated.
        known: String,
    },
    /// A style preset that does not exist; `known` lists the presets.
    #[error("unknown style `{name}`; the styles are {known}")]
    UnknownStyle {
        /// The name given.
        name: String,
        /// The presets, comma-separated.
        known: String,
    },
    /// A value given for a parameter (a flag of the command line without its dashes, a key of a
    /// sweep file) that cannot be used.
    #[error("{parameter}: {reason}")]
    BadValue {
        /// The parameter's name.
        parameter: String,
        /// Why the value cannot be used.
        #[source]
        reason: Reason,
    },
    /// A model file (`--body-table FILE.toml`, `--ik-model`, …) that cannot be read.
    #[error("reading {what} {path}: {source}")]
    Unreadable {
        /// What the file is, in words (`body table`, …).
        what: &'static str,
        /// The file's path.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// A model, attribute, schedule, sweep or motion file that cannot be parsed, or a path whose
    /// extension names no format.
    #[error("malformed {what} {path}: {reason}")]
    Malformed {
        /// What the file is, in words (`schedule`, `sweep file`, `BVH file`, …).
        what: &'static str,
        /// The file's path.
        path: PathBuf,
        /// Why it cannot be parsed.
        #[source]
        reason: Reason,
    },
}

impl InputError {
    /// Check that `value` is finite and inside [min, max].
    pub fn check_range(
        name: &str,
        value: f64,
        min: f64,
        max: f64,
        unit: &str,
    ) -> Result<f64, InputError> {
        if !value.is_finite() {
            return Err(InputError::NotFinite {
                name: name.to_string(),
                value,
            });
        }
        if value < min || value > max {
            return Err(InputError::OutOfRange {
                name: name.to_string(),
                value,
                min,
                max,
                unit: unit.to_string(),
                note: String::new(),
            });
        }
        Ok(value)
    }

    /// `self` with the origin of its value (`derived from …`, `the default …`) added to its
    /// note, when it is an [`InputError::OutOfRange`] or [`InputError::BeyondWalkRun`]; any
    /// other error unchanged.
    pub fn with_note(mut self, origin: &str) -> Self {
        if let InputError::OutOfRange { note, .. } | InputError::BeyondWalkRun { note, .. } =
            &mut self
        {
            *note = match note.strip_suffix(')') {
                Some(inner) => format!("{inner}; {origin})"),
                None => format!(" ({origin})"),
            };
        }
        self
    }

    /// [`InputError::BadValue`] for `parameter`.
    pub fn bad_value(parameter: impl Into<String>, reason: impl Into<Reason>) -> Self {
        InputError::BadValue {
            parameter: parameter.into(),
            reason: reason.into(),
        }
    }

    /// [`InputError::Malformed`]: the `what` at `path`, and why.
    pub fn malformed(what: &'static str, path: &Path, reason: impl Into<Reason>) -> Self {
        InputError::Malformed {
            what,
            path: path.to_path_buf(),
            reason: reason.into(),
        }
    }
}

/// A unit after a number: ` m/s`, or nothing for a number without one.
fn spaced(unit: &str) -> String {
    if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    }
}

/// A number as a message shows it: at most 9 significant digits, so that a derived value reads
/// `3.9705132`, not `3.9705132000000005`, and in exponent form outside [1e-4, 1e9), so that
/// `1e308` is not 309 digits.
#[derive(Clone, Copy, Debug)]
pub struct Shown(pub f64);

impl std::fmt::Display for Shown {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        const DIGITS: i32 = 9;
        let x = self.0;
        let a = x.abs();
        if !x.is_finite() || x == 0.0 {
            return write!(f, "{}", if x == 0.0 { 0.0 } else { x });
        }
        if (1e-4..1e9).contains(&a) {
            let decimals = (DIGITS - 1 - a.log10().floor() as i32).max(0) as usize;
            let text = format!("{x:.decimals$}");
            let text = if text.contains('.') {
                text.trim_end_matches('0').trim_end_matches('.')
            } else {
                &text
            };
            f.write_str(text)
        } else {
            let text = format!("{x:.*e}", (DIGITS - 1) as usize);
            let (mantissa, exponent) = text.split_once('e').expect("exponent form");
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            write!(f, "{mantissa}e{exponent}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shown_numbers_have_no_float_noise_and_no_runs_of_digits() {
        let shown = |x: f64| Shown(x).to_string();
        assert_eq!(shown(3.9705132000000005), "3.9705132");
        assert_eq!(shown(1e308), "1e308");
        assert_eq!(shown(-2.5e-7), "-2.5e-7");
        assert_eq!(shown(1.4), "1.4");
        assert_eq!(shown(-5.0), "-5");
        assert_eq!(shown(0.1736), "0.1736");
        assert_eq!(shown(1_000_000.0), "1000000");
        assert_eq!(shown(123_456_789_012.0), "1.23456789e11");
        assert_eq!(shown(-0.0), "0");
        assert_eq!(shown(f64::NAN), "NaN");
        // exact values keep every digit they have up to 9 significant
        assert_eq!(shown(0.123456789), "0.123456789");
        assert_eq!(shown(0.1234567891), "0.123456789");
    }

    #[test]
    fn a_note_names_where_an_out_of_range_value_came_from() {
        let e = InputError::check_range("velocity", 1.4, 0.5, 1.1, "m/s")
            .unwrap_err()
            .with_note("the default");
        assert_eq!(
            e.to_string(),
            "velocity = 1.4 m/s (the default) is out of range: valid range is [0.5, 1.1] m/s"
        );
    }
}
