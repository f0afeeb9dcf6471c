//! The per-step report as JSON (`klaw walk --report`).
use std::path::Path;

use super::file::write_atomic;
use crate::error::Result;

/// Write the report as pretty-printed JSON (with a final newline).
pub fn write_report_json(path: &Path, report: &impl serde::Serialize) -> Result<()> {
    write_atomic(path, |out| {
        serde_json::to_writer_pretty(&mut *out, report)?;
        out.write_all(b"\n")
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::report::Report;
    use std::fs;

    #[test]
    fn report_json_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("r.json");
        let report = Report {
            height: 1.8,
            mass: 80.0,
            steps: Vec::new(),
        };
        write_report_json(&p, &report).unwrap();
        let v: serde_json::Value = serde_json::from_str(&fs::read_to_string(&p).unwrap()).unwrap();
        assert_eq!(v["height"], 1.8);
        assert_eq!(v["mass"], 80.0);
        assert!(v["steps"].as_array().unwrap().is_empty());
    }
}
