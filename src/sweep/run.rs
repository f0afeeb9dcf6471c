//! The walks of a sweep, run in parallel on the rayon pool a chunk at a time, each summarized.
use crate::plan::gait::GaitRequest;
use std::collections::BTreeMap;

use rayon::prelude::*;

use super::product::{Inputs, Sweep};
use super::rows::{Row, Summary};
use crate::engine::walker::simulate;
use crate::error::Result;
use crate::model::InputError;
use crate::model::attributes::{AttributeTable, STYLES};
use crate::model::body::Body;
use crate::plan::Timing;

/// Steps per walk: valid range.
pub(crate) const MAX_STEPS: usize = 1_000_000;

/// Walks run in parallel per chunk, for each thread: rows are written chunk by chunk, so memory
/// holds at most a chunk of rows whatever the size of the sweep.
pub(crate) const CHUNK_PER_THREAD: usize = 32;

impl Sweep {
    /// Walk point `k` and summarize it; a failure is recorded in the row, never returned.
    pub(crate) fn walk(&self, k: usize, table: &AttributeTable) -> Row {
        let mut inputs = self.inputs(k);
        let outcome = run_walk(&mut inputs, table);
        Row { inputs, outcome }
    }

    /// Run the walks of `points` (any order) on the rayon pool, a chunk of
    /// `CHUNK_PER_THREAD × threads` at a time; `emit` receives every row, in the order of
    /// `points`, as soon as its chunk is done; `progress()` is called after each walk (from any
    /// thread). An `emit` error stops the sweep.
    pub(crate) fn run(
        &self,
        points: impl IntoIterator<Item = usize>,
        progress: &(dyn Fn() + Sync),
        mut emit: impl FnMut(Row) -> Result<()>,
    ) -> Result<()> {
        let table = AttributeTable::builtin();
        let chunk = (CHUNK_PER_THREAD * rayon::current_num_threads()).max(64);
        let mut points = points.into_iter();
        loop {
            let batch: Vec<usize> = points.by_ref().take(chunk).collect();
            if batch.is_empty() {
                return Ok(());
            }
            let rows: Vec<Row> = batch
                .into_par_iter()
                .map(|k| {
                    let row = self.walk(k, &table);
                    progress();
                    row
                })
                .collect();
            for row in rows {
                emit(row)?;
            }
        }
    }
}

/// Simulate one walk and summarize it; a point that sweeps no gait quantity walks at its
/// attributes' preferred velocity (a style's own speed), which becomes its requested velocity.
pub(crate) fn run_walk(inputs: &mut Inputs, table: &AttributeTable) -> Result<Summary> {
    let steps = InputError::check_range("steps", inputs.steps, 1.0, MAX_STEPS as f64, "steps")?;
    if steps.fract() != 0.0 {
        return Err(InputError::NotWhole {
            name: "steps",
            value: steps,
        }
        .into());
    }
    // index 0: the default table
    let body_table = super::tables::table(inputs.body_table.unwrap_or(0));
    let body = Body::new(&body_table, inputs.height, inputs.mass)?;
    let mut overrides: BTreeMap<String, f64> = match inputs.style {
        Some(i) => crate::model::attributes::style(STYLES[i].0)?,
        None => BTreeMap::new(),
    };
    overrides.extend(inputs.attributes.iter().cloned());
    let attrs = table.resolve(&overrides, "--attr")?;
    let gait = if inputs.request == GaitRequest::default() {
        inputs.request.velocity = Some(attrs.preferred_velocity);
        GaitRequest::preferred(&body, &attrs)?
    } else {
        inputs.request.complete(&body, &attrs)?
    };
    let timing = Timing::new(gait.step_frequency)?;
    let walk = simulate(body, attrs, &vec![gait; steps as usize])?;
    let report = walk.report();
    let iterations: Vec<usize> = report
        .steps
        .iter()
        .flat_map(|s| s.solves.iter().map(|r| r.report.iterations))
        .collect();
    let n = report.steps.len().max(1) as f64;
    let mean = |f: &dyn Fn(&crate::engine::report::StepReport) -> f64| {
        report.steps.iter().map(f).sum::<f64>() / n
    };
    let distance: f64 = report.steps.iter().map(|s| s.achieved.step_length).sum();
    let work: f64 = report.steps.iter().map(|s| s.positive_work).sum();
    Ok(Summary {
        mean_iterations: if iterations.is_empty() {
            0.0
        } else {
            iterations.iter().sum::<usize>() as f64 / iterations.len() as f64
        },
        max_iterations: iterations.iter().copied().max().unwrap_or(0),
        achieved_velocity: mean(&|s| s.achieved.velocity),
        achieved_step_length: mean(&|s| s.achieved.step_length),
        achieved_step_frequency: mean(&|s| 60.0 / s.achieved.duration),
        mean_hip_excursion: mean(&|s| s.hip_excursion),
        max_peak_swing_knee_flexion_deg: report
            .steps
            .iter()
            .map(|s| s.peak_swing_knee_flexion.to_degrees())
            .fold(f64::NEG_INFINITY, f64::max),
        stance_pct: 100.0 * (timing.t_step + timing.t_ds) / timing.t_cycle,
        double_support_pct: 100.0 * 2.0 * timing.t_ds / timing.t_cycle,
        min_toe_clearance: report
            .steps
            .iter()
            .map(|s| s.min_toe_clearance)
            .fold(f64::INFINITY, f64::min),
        work_per_m: work / distance,
        work_per_kg_m: work / distance / inputs.mass,
        repaired_steps: report.steps.iter().filter(|s| s.repairs.any()).count(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::Axis;

    #[test]
    fn failed_point_records_the_reason() {
        let s = Sweep {
            axes: vec![(Axis::Velocity, vec![5.0]), (Axis::Steps, vec![2.0])],
        };
        let mut rows = Vec::new();
        s.run(0..1, &|| {}, |r| {
            rows.push(r);
            Ok(())
        })
        .unwrap();
        assert_eq!(rows.len(), 1);
        let e = rows[0].outcome.as_ref().unwrap_err().to_string();
        assert!(e.contains("velocity"), "{e}");
        assert_eq!(rows[0].cells().len(), s.header().len());
    }
}
