//! The actuators' work read back from a walk's report (`klaw walk --report`, `docs/export.md`):
//! the body, and per step the positive work and the step length achieved.
use std::path::Path;

use serde::Deserialize;

use crate::error::{Error, Result};
use crate::model::InputError;

#[derive(Deserialize)]
struct ReportFile {
    height: f64,
    mass: f64,
    steps: Vec<StepFile>,
}

#[derive(Deserialize)]
struct StepFile {
    achieved: Achieved,
    positive_work: f64,
}

#[derive(Deserialize)]
struct Achieved {
    step_length: f64,
    duration: f64,
}

/// What a walk's report says of its body and its actuators' work.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct WalkWork {
    /// Body height (m).
    pub height: f64,
    /// Body mass (kg).
    pub mass: f64,
    /// The walk's steps.
    pub steps: usize,
    /// The walk's duration, the sum of its steps' (s).
    pub duration: f64,
    /// Σ positive work of the actuators (J; `engine::work`).
    pub positive_work: f64,
    /// Σ step lengths (m).
    pub distance: f64,
}

impl WalkWork {
    /// The actuators' positive work per metre walked (J/m), as `klaw sweep`'s `work_per_m`.
    pub fn per_metre(&self) -> f64 {
        self.positive_work / self.distance
    }
}

/// Read the report `path`. Errors: reading it ([`Error::Io`]); JSON that is not a klaw walk
/// report, no step, a number not finite ([`InputError::Malformed`]).
pub fn read_walk_work(path: &Path) -> Result<WalkWork> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        action: "reading",
        path: path.to_path_buf(),
        source,
    })?;
    let malformed = |reason: String| InputError::malformed("walk report", path, reason);
    let r: ReportFile = serde_json::from_str(&text)
        .map_err(|e| malformed(format!("{e} (the JSON of klaw walk --report)")))?;
    if r.steps.is_empty() {
        return Err(malformed("no steps".to_string()).into());
    }
    let w = WalkWork {
        height: r.height,
        mass: r.mass,
        steps: r.steps.len(),
        duration: r.steps.iter().map(|s| s.achieved.duration).sum(),
        positive_work: r.steps.iter().map(|s| s.positive_work).sum(),
        distance: r.steps.iter().map(|s| s.achieved.step_length).sum(),
    };
    let values = [w.height, w.mass, w.duration, w.positive_work, w.distance];
    if !values.iter().all(|v| v.is_finite()) || w.distance <= 0.0 {
        return Err(malformed("a height, mass, duration, work or step length that is not a finite number (or no distance walked)".to_string()).into());
    }
    Ok(w)
}
