//! Model files: a user's own copy of a bundled `models/*.toml` (a body table, the inverse
//! kinematics' model, the NRS constants, the generalization's constants), read whole and
//! checked by its type's parser before any work (docs/cli.md, "Model files").
use std::path::Path;

use crate::model::InputError;

/// Whether a body-table value (`--body-table`, a scenario's `[body] table`, a sweep's
/// `body_table` item) names a file rather than a bundled table: it ends in `.toml` or contains
/// a `/`.
pub fn names_a_file(spec: &str) -> bool {
    spec.ends_with(".toml") || spec.contains('/')
}

/// The text of the model file `path`; `what` names the kind of file in the error.
pub fn read_text(what: &'static str, path: &Path) -> Result<String, InputError> {
    std::fs::read_to_string(path).map_err(|source| InputError::Unreadable {
        what,
        path: path.to_path_buf(),
        source,
    })
}

/// Parse the model file's `text` as `T` (a `deny_unknown_fields` layout, so that a missing or an
/// unknown key is an error naming it); the parser's error on one line, `line L, column C: …`
/// where it gives a position, and the table a key is missing from (`in [leg]`).
pub fn parse_toml<T: serde::de::DeserializeOwned>(text: &str) -> Result<T, String> {
    toml::from_str(text).map_err(|e| {
        let message = e.message().trim_end().replace('\n', " ");
        let Some(span) = e.span() else {
            return message;
        };
        let (line, column) = line_col(text, span.start);
        // a missing key's span is its table's: name the table from its header
        let header = text.lines().nth(line - 1).map(str::trim).unwrap_or("");
        let table = match header.split_once(']') {
            Some((name, _)) if header.starts_with('[') && message.starts_with("missing") => {
                format!(" in {name}]")
            }
            _ => String::new(),
        };
        format!("line {line}, column {column}: {message}{table}")
    })
}

/// Line and column (1-based) of byte `offset` in `text`.
pub(crate) fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_are_told_from_names() {
        for spec in ["mine.toml", "dir/mine", "./x", "/abs/t.toml"] {
            assert!(names_a_file(spec), "{spec}");
        }
        for spec in ["winter", "deleva-female", "toml"] {
            assert!(!names_a_file(spec), "{spec}");
        }
    }

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Layout {
        a: f64,
        b: f64,
    }

    /// A missing, an unknown or a malformed key is named on one line with its place.
    #[test]
    fn toml_errors_are_one_line_with_the_place() {
        let e = parse_toml::<Layout>("a = 1.0\nb = 2.0\nc = 3.0\n").unwrap_err();
        assert!(e.starts_with("line 3, column 1: unknown field `c`"), "{e}");
        let e = parse_toml::<Layout>("a = 1.0\n").unwrap_err();
        assert!(e.contains("missing field `b`"), "{e}");
        let e =
            parse_toml::<std::collections::BTreeMap<String, Layout>>("[t]\na = 1.0\n").unwrap_err();
        assert!(e.contains("missing field `b` in [t]"), "{e}");
        let e = parse_toml::<Layout>("a = 1.0\nb = \n").unwrap_err();
        assert!(e.starts_with("line 2, column 5: "), "{e}");
        assert!(!e.contains('\n'), "{e}");
    }

    #[test]
    fn a_missing_file_names_itself() {
        let e = read_text("body table", Path::new("/nonexistent/t.toml")).unwrap_err();
        let m = e.to_string();
        assert!(
            m.starts_with("reading body table /nonexistent/t.toml: "),
            "{m}"
        );
    }
}
