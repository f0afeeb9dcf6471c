//! What can be wrong with a scenario file (`klaw scenario FILE.toml`): the place (a table or an
//! action, by its index from 0 as in [`super::ScenarioError`]), the field, and why.
use std::fmt;
use std::path::PathBuf;

use crate::model::InputError;

/// Where in a scenario file a problem lies.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Place {
    /// The file's top level.
    Top,
    /// The `[body]` or `[attributes]` table.
    Table(&'static str),
    /// An `[[action]]`, by its index in the file from 0, with its `type` when known.
    Action {
        /// Index from 0.
        index: usize,
        /// The action's `type` (`?` when missing).
        name: String,
    },
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Place::Top => write!(f, "top level"),
            Place::Table(t) => write!(f, "[{t}]"),
            Place::Action { index, name } => write!(f, "action {index} ({name}, from 0)"),
        }
    }
}

/// Why a field cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum Problem {
    /// The file is not TOML.
    #[error("{0}")]
    Toml(Box<toml::de::Error>),
    /// A key the schema does not have; `known` lists those it has there.
    #[error("unknown key; the keys here are {known}")]
    UnknownKey {
        /// The valid keys, comma-separated.
        known: String,
    },
    /// An action `type` that does not exist.
    #[error("unknown action type `{found}`; the types are stand, walk, step, turn, pause")]
    UnknownAction {
        /// The type given.
        found: String,
    },
    /// A required field is absent.
    #[error("missing: {what}")]
    Missing {
        /// What is needed, in words.
        what: String,
    },
    /// Two fields given together that exclude each other.
    #[error("cannot be given together with `{other}`")]
    Conflict {
        /// The other field.
        other: String,
    },
    /// A value of the wrong TOML type.
    #[error("expected {expected}, found {found}")]
    WrongType {
        /// The type wanted, in words.
        expected: &'static str,
        /// The TOML type found.
        found: &'static str,
    },
    /// A value out of its range, not finite, or refused by the body, attribute or gait checks.
    #[error(transparent)]
    Value(Box<InputError>),
}

impl From<InputError> for Problem {
    fn from(e: InputError) -> Self {
        Problem::Value(Box::new(e))
    }
}

/// A scenario file that cannot be read into a [`super::Scenario`]: nothing is run or written.
#[derive(Debug, thiserror::Error)]
#[error("scenario {}: {place}, `{field}`: {problem}", path.display())]
pub struct ScenarioFileError {
    /// The file.
    pub path: PathBuf,
    /// The table or action.
    pub place: Place,
    /// The field (key) at fault; `action` for a problem with the list itself.
    pub field: String,
    /// Why.
    pub problem: Problem,
}
