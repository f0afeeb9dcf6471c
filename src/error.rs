//! The one error type of the crate. Input errors (exit status 2) name the value and its valid
//! range; simulation failures (exit status 1) name the step, the phase and the residual.
use std::path::PathBuf;

/// Everything that can go wrong, from a bad flag to a shooting solve that does not converge.
#[derive(Debug, thiserror::Error)]
pub enum Error {
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
    /// The gait leaves no double support: that is running, not walking.
    #[error(
        "step frequency {step_frequency} steps/min leaves no double support (t_ds = {t_ds:.4} s): \
         walking needs sf < 181.75 steps/min"
    )]
    NoDoubleSupport { step_frequency: f64, t_ds: f64 },
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
    /// A sweep flag whose value list cannot be parsed (`--flag`: reason).
    #[error("--{flag}: {reason}")]
    BadSpec { flag: String, reason: String },
    /// A model, attribute or schedule file that cannot be parsed.
    #[error("malformed {what} {path}: {reason}")]
    Malformed {
        what: &'static str,
        path: PathBuf,
        reason: String,
    },
    /// Reading or writing a file failed.
    #[error("{action} {path}: {source}")]
    Io {
        action: &'static str,
        path: PathBuf,
        source: std::io::Error,
    },
    /// A geometric construction has no solution for these inputs.
    #[error("{what}")]
    Geometry { what: String },
    /// A shooting solve ended without meeting its end conditions.
    #[error(
        "step {step}, {phase}: shooting did not converge: residual {residual:.3e} after {iterations} trial integrations"
    )]
    NotConverged {
        step: usize,
        phase: &'static str,
        residual: f64,
        iterations: usize,
    },
    /// The integrator failed (step size underflow, too many steps).
    #[error("step {step}, {phase}: integration failed: {reason}")]
    Integration {
        step: usize,
        phase: &'static str,
        reason: String,
    },
    /// A converged walk breaks an invariant (the swing foot under the ground, the hip under its
    /// heel-strike height).
    #[error("step {step}, {phase}: {what}")]
    Invariant {
        step: usize,
        phase: &'static str,
        what: String,
    },
    /// An export that cannot be written as asked (unknown file extension, frames out of order, no
    /// complete steady-state gait cycle to average).
    #[error("{what}")]
    Export { what: String },
}

impl Error {
    /// A failure of the swing: its shooting, or its foot under the ground.
    pub fn is_swing_failure(&self) -> bool {
        match self {
            Error::NotConverged { phase, .. } | Error::Integration { phase, .. } => {
                phase.starts_with("swing")
            }
            Error::Invariant { phase, .. } => *phase == "swing",
            _ => false,
        }
    }

    /// Process exit status: 2 for bad input, 1 for a simulation that failed.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::NotConverged { .. } | Error::Integration { .. } | Error::Invariant { .. } => 1,
            Error::Io { action, .. } if *action == "writing" => 1,
            _ => 2,
        }
    }

    /// Check that `value` is finite and inside [min, max].
    pub fn check_range(name: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64> {
        if !value.is_finite() {
            return Err(Error::NotFinite {
                name: name.to_string(),
                value,
            });
        }
        if value < min || value > max {
            return Err(Error::OutOfRange {
                name: name.to_string(),
                value,
                min,
                max,
                unit: unit.to_string(),
            });
        }
        Ok(value)
    }
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
