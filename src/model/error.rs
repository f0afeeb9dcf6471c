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
    #[error("{name} = {value} {unit} is out of range: valid range is [{min}, {max}] {unit}")]
    OutOfRange {
        name: String,
        value: f64,
        min: f64,
        max: f64,
        unit: String,
    },
    /// NaN or infinity where a number was expected.
    #[error("{name} is {value}: a finite number is required")]
    NotFinite { name: String, value: f64 },
    /// A count that is not a whole number.
    #[error("{name} = {value} is not a whole number")]
    NotWhole { name: &'static str, value: f64 },
    /// v, sl and sf all given but v ≠ sl·sf/60.
    #[error(
        "inconsistent gait: velocity {velocity} m/s, step length {step_length} m and step frequency \
         {step_frequency} steps/min imply {implied:.4} m/s (v = sl·sf/60); they must agree to within {tolerance_pct}%"
    )]
    Inconsistent {
        velocity: f64,
        step_length: f64,
        step_frequency: f64,
        implied: f64,
        tolerance_pct: f64,
    },
    /// The gait leaves no double support (KLAW 1989 eq. 2): that is running, not walking.
    #[error(
        "step frequency {step_frequency} steps/min leaves no double support (t_ds = {t_ds:.4} s): \
         walking needs sf < 181.75 steps/min"
    )]
    NoDoubleSupport { step_frequency: f64, t_ds: f64 },
    /// A step too long for the leg: the swing heel cannot reach the ground at heel strike (the
    /// step constraints, spec §3).
    #[error("step length {step_length} m: the swing heel cannot reach the ground")]
    StepTooLong { step_length: f64 },
    /// Neither velocity, step length nor step frequency was given.
    #[error("no gait given: give at least one of velocity, step length, step frequency")]
    MissingGait,
    /// An attribute name that the model does not know.
    #[error("unknown attribute `{name}` in {source_name}; known attributes: {known}")]
    UnknownAttribute {
        name: String,
        source_name: String,
        known: String,
    },
    /// A style preset that does not exist; `known` lists the presets.
    #[error("unknown style `{name}`; the styles are {known}")]
    UnknownStyle { name: String, known: String },
    /// A value given for a parameter (a flag of the command line without its dashes, a key of a
    /// sweep file) that cannot be used.
    #[error("{parameter}: {reason}")]
    BadValue {
        parameter: String,
        #[source]
        reason: Reason,
    },
    /// A model, attribute, schedule, sweep or motion file that cannot be parsed, or a path whose
    /// extension names no format.
    #[error("malformed {what} {path}: {reason}")]
    Malformed {
        what: &'static str,
        path: PathBuf,
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
            });
        }
        Ok(value)
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
