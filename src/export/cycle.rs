//! Gait-cycle normalized curves (issue item 8): every clinical angle resampled on 0, 1, …, 100 %
//! of the gait cycle (right heel strike to the next right heel strike) and averaged over the
//! steady-state cycles.
//!
//! Steady state: the cycles between consecutive right heel strikes, less the first `skip` of
//! them (`skip` = 1 drops the first cycle, which starts from the engine's initial conditions), and
//! only those the frames cover completely (first frame at or before the cycle's heel strike, last
//! frame at or after the next one). Each cycle is sampled at t = t_HS + p/100 · (t_HS' − t_HS) by
//! linear interpolation between the two frames around t; the curves are the means over the
//! cycles, sample by sample.
use std::path::Path;

use super::angle_columns;
use crate::error::{Error, Result};
use crate::figure::skeleton::Clinical;

/// Cycle-normalized curves: 101 rows (0…100 %) of the column values.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleCurves {
    /// Column names (from [`super::angle_columns`] for [`cycle_average`]).
    pub columns: Vec<String>,
    /// rows[p][k]: column k at p % of the cycle (rad for angles).
    pub rows: Vec<Vec<f64>>,
    /// How many cycles were averaged.
    pub cycles: usize,
}

fn export_error(what: String) -> Error {
    Error::Export { what }
}

/// Average `values` (one row per frame, at `times`) over the steady-state cycles delimited by
/// `right_heel_strikes` (see the module doc). Errors ([`Error::Export`]): times or strikes not
/// finite and strictly increasing, rows of unequal length, no complete cycle after skipping
/// `skip`.
pub fn average_cycles(
    times: &[f64],
    values: &[Vec<f64>],
    right_heel_strikes: &[f64],
    skip: usize,
) -> Result<Vec<Vec<f64>>> {
    if times.len() != values.len() {
        return Err(export_error(format!(
            "{} frame times for {} frames",
            times.len(),
            values.len()
        )));
    }
    let width = values.first().map_or(0, Vec::len);
    if let Some(i) = values.iter().position(|v| v.len() != width) {
        return Err(export_error(format!(
            "frame {i} has {} values, frame 0 has {width}",
            values[i].len()
        )));
    }
    let increasing =
        |xs: &[f64]| xs.iter().all(|x| x.is_finite()) && xs.windows(2).all(|w| w[0] < w[1]);
    if !increasing(times) {
        return Err(export_error(
            "frame times must be finite and strictly increasing".into(),
        ));
    }
    if !increasing(right_heel_strikes) {
        return Err(export_error(
            "right heel strike times must be finite and strictly increasing".into(),
        ));
    }
    let (Some(&t_first), Some(&t_last)) = (times.first(), times.last()) else {
        return Err(export_error("no frames to average".into()));
    };
    let cycles: Vec<(f64, f64)> = right_heel_strikes
        .windows(2)
        .skip(skip)
        .map(|w| (w[0], w[1]))
        .filter(|&(a, b)| a >= t_first && b <= t_last)
        .collect();
    if cycles.is_empty() {
        return Err(export_error(format!(
            "no complete steady-state gait cycle: {} right heel strikes give {} cycles, the \
             first {skip} skipped as the start-up, and the frames cover {t_first} … {t_last} s; \
             walk more steps",
            right_heel_strikes.len(),
            right_heel_strikes.len().saturating_sub(1)
        )));
    }
    let sample = |t: f64, k: usize| -> f64 {
        // the last frame at or before t (t is inside [t_first, t_last])
        let i = times.partition_point(|&x| x <= t).saturating_sub(1);
        if i + 1 >= times.len() {
            return values[i][k];
        }
        let (t0, t1) = (times[i], times[i + 1]);
        let u = (t - t0) / (t1 - t0);
        values[i][k] + u * (values[i + 1][k] - values[i][k])
    };
    let mut rows = vec![vec![0.0; width]; 101];
    for &(a, b) in &cycles {
        for (p, row) in rows.iter_mut().enumerate() {
            let t = a + (b - a) * p as f64 / 100.0;
            for (k, cell) in row.iter_mut().enumerate() {
                *cell += sample(t, k);
            }
        }
    }
    let n = cycles.len() as f64;
    for row in &mut rows {
        for cell in row.iter_mut() {
            *cell /= n;
        }
    }
    Ok(rows)
}

/// The clinical angles of [`super::angle_columns`] averaged over the steady-state cycles.
pub fn cycle_average(
    frames: &[Clinical],
    right_heel_strikes: &[f64],
    skip: usize,
) -> Result<CycleCurves> {
    let columns = angle_columns();
    let times: Vec<f64> = frames.iter().map(|c| c.time).collect();
    let values: Vec<Vec<f64>> = frames
        .iter()
        .map(|c| columns.iter().map(|col| (col.get)(c)).collect())
        .collect();
    let rows = average_cycles(&times, &values, right_heel_strikes, skip)?;
    let cycles = right_heel_strikes
        .windows(2)
        .skip(skip)
        .filter(|w| w[0] >= times[0] && w[1] <= times[times.len() - 1])
        .count();
    Ok(CycleCurves {
        columns: columns.into_iter().map(|c| c.name).collect(),
        rows,
        cycles,
    })
}

/// Write the curves as CSV: `cycle_pct` (0…100), then each column as `*_deg`; 101 rows.
pub fn write_cycle_csv(path: &Path, curves: &CycleCurves) -> Result<()> {
    super::file::write_atomic(path, |out| {
        write!(out, "cycle_pct")?;
        for c in &curves.columns {
            write!(out, ",{c}_deg")?;
        }
        writeln!(out)?;
        for (p, row) in curves.rows.iter().enumerate() {
            write!(out, "{p}")?;
            for v in row {
                write!(out, ",{}", v.to_degrees())?;
            }
            writeln!(out)?;
        }
        Ok(())
    })
}
