//! The crate's error type: the union of the levels' own errors, which the outer modules (the
//! exports, the input files, the simulation API, sweeps and figures) return, and the failures of
//! reading and writing files. How an error is shown and which exit status it gives is the
//! binary's business (`src/bin/klaw/`).
use std::path::PathBuf;

use crate::analysis::criteria::CriteriaError;
use crate::analysis::cycle::CycleError;
use crate::engine::SimulationError;
use crate::export::error::ExportError;
use crate::figure::FigureError;
use crate::generalize::GeneralizeError;
use crate::model::InputError;
use crate::plot::error::DrawError;
use crate::scenario::{ScenarioError, ScenarioFileError};

/// Everything that can go wrong, from a bad value to a shooting solve that does not converge.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A value, a file or a path given as input that cannot be used.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A walk that cannot be simulated.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
    /// A frame of the figure that cannot be built.
    #[error(transparent)]
    Figure(#[from] FigureError),
    /// Frames that cannot be averaged over the gait cycle.
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// Motion that cannot be exported as asked.
    #[error(transparent)]
    Export(#[from] ExportError),
    /// A scenario whose action cannot be run.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// A scenario file that cannot be read into a scenario (boxed: the union stays small).
    #[error(transparent)]
    ScenarioFile(Box<ScenarioFileError>),
    /// Walk data that cannot be read, generalized or posed (Ko & Badler 1992).
    #[error(transparent)]
    Generalize(#[from] GeneralizeError),
    /// Reading or writing a file failed.
    #[error("{action} {path}: {source}")]
    Io {
        /// What was being done: `reading` or `writing`.
        action: &'static str,
        /// The file's path.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Frames the quality criteria cannot be computed from.
    #[error(transparent)]
    Criteria(#[from] CriteriaError),
    /// An inverse kinematics that cannot follow its targets.
    #[error(transparent)]
    Ik(#[from] crate::ik::IkError),
    /// A poulaine, its model or its database that cannot be made or used.
    #[error(transparent)]
    Poulaine(#[from] crate::poulaine::PoulaineError),
    /// A figure (`what`) that cannot be drawn, so `path` is not written.
    #[error("writing {path}: drawing {what}: {source}")]
    Draw {
        /// The file not written.
        path: PathBuf,
        /// The figure, in words.
        what: &'static str,
        /// Why it cannot be drawn.
        source: DrawError,
    },
}

impl From<ScenarioFileError> for Error {
    fn from(e: ScenarioFileError) -> Self {
        Error::ScenarioFile(Box::new(e))
    }
}

/// A result of the crate, [`Error`] by default.
pub type Result<T, E = Error> = std::result::Result<T, E>;
