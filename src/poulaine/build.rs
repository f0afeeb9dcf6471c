//! A synthetic database of poulaines (Pronost et al. §3, with klaw's walks in place of the
//! motion capture of 41 subjects): one klaw walk per point of a grid of heights, step lengths
//! and attributes (step width, the stance's attributes), its last gait cycle's poulaine
//! modelled. Labelled `synthetic` in the database.
use std::collections::BTreeMap;

use rayon::prelude::*;
use serde::Serialize;

use crate::model::InputError;
use crate::model::attributes::AttributeTable;
use crate::model::body::Body;
use crate::plan::GaitRequest;
use crate::poulaine::database::{Database, Entry};
use crate::poulaine::fit::fit;
use crate::poulaine::trajectory::Trajectory;
use crate::poulaine::validate::frames_angles;
use crate::simulation::Simulation;

/// The steps of each walk: the last complete cycle (steps 4 and 5) is past the start.
const STEPS: usize = 6;
/// The poulaine's samples per second.
const RATE: f64 = 100.0;

/// The grid of walks.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Grid {
    /// Body heights (m); the mass is 23 H² kg (a body-mass index of 23, as `klaw sweep`'s
    /// grids).
    pub heights: Vec<f64>,
    /// Step lengths (m); the step frequency by klaw's normalizing formula.
    pub step_lengths: Vec<f64>,
    /// Attributes and their values (the units of `models/attributes.toml`).
    pub attributes: Vec<(String, Vec<f64>)>,
}

/// A grid point that gave no poulaine, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Skipped {
    /// The point's label.
    pub label: String,
    /// Why (a gait the body cannot walk, a walk that did not converge, …).
    pub reason: String,
}

/// One point of the grid.
struct Point {
    height: f64,
    step_length: f64,
    attributes: BTreeMap<String, f64>,
}

impl Point {
    fn label(&self) -> String {
        let mut s = format!("H{:.3}-sl{:.3}", self.height, self.step_length);
        for (k, v) in &self.attributes {
            s.push_str(&format!("-{k}{v}"));
        }
        s
    }
}

impl Grid {
    /// Check every value before any walk: heights and step lengths positive and finite, each
    /// attribute known and every value in its range.
    pub fn check(&self) -> Result<(), InputError> {
        if self.heights.is_empty() || self.step_lengths.is_empty() {
            return Err(InputError::bad_value(
                "height",
                "the grid needs a height and a step length",
            ));
        }
        for &h in &self.heights {
            Body::standard(h, 23.0 * h * h)?;
        }
        for &sl in &self.step_lengths {
            InputError::check_range("step-length", sl, 0.05, 2.0, "m")?;
        }
        let table = AttributeTable::builtin();
        for (name, values) in &self.attributes {
            for &v in values {
                table.resolve(&BTreeMap::from([(name.clone(), v)]), "--attr")?;
            }
        }
        Ok(())
    }

    fn points(&self) -> Vec<Point> {
        let mut points = Vec::new();
        for &height in &self.heights {
            for &step_length in &self.step_lengths {
                let mut combos = vec![BTreeMap::new()];
                for (name, values) in &self.attributes {
                    combos = combos
                        .into_iter()
                        .flat_map(|c| {
                            values.iter().map(move |&v| {
                                let mut c = c.clone();
                                c.insert(name.clone(), v);
                                c
                            })
                        })
                        .collect();
                }
                for attributes in combos {
                    points.push(Point {
                        height,
                        step_length,
                        attributes,
                    });
                }
            }
        }
        points
    }
}

/// One grid point's entry.
fn entry(p: &Point) -> crate::Result<Entry> {
    let body = Body::standard(p.height, 23.0 * p.height * p.height)?;
    let attrs = AttributeTable::builtin().resolve(&p.attributes, "--attr")?;
    let walk = Simulation::new(body)
        .attributes(attrs)
        .gait(GaitRequest {
            step_length: Some(p.step_length),
            ..Default::default()
        })
        .steps(STEPS)
        .run()?;
    let (poulaine, frames) = Trajectory::from_walk(&walk, RATE)?;
    let (model, error) = fit(&poulaine)?;
    let gait = walk.gaits()[0];
    let mut e = Entry::new(
        p.label(),
        "synthetic",
        body.l1,
        gait.step_length,
        model,
        error,
    );
    e.height = Some(p.height);
    e.velocity = Some(gait.velocity);
    e.attributes = p.attributes.clone();
    e.angles = frames_angles(&frames, &body)?
        .iter()
        .map(|a| (*a).into())
        .collect();
    Ok(e)
}

/// The synthetic database of `grid` (its points in parallel), and the points skipped.
pub fn synthetic(grid: &Grid) -> crate::Result<(Database, Vec<Skipped>)> {
    grid.check()?;
    let points = grid.points();
    let results: Vec<_> = points.par_iter().map(|p| (p.label(), entry(p))).collect();
    let mut entries = Vec::new();
    let mut skipped = Vec::new();
    for (label, r) in results {
        match r {
            Ok(e) => entries.push(e),
            Err(e) => skipped.push(Skipped {
                label,
                reason: e.to_string(),
            }),
        }
    }
    let description = format!(
        "synthetic: poulaines of klaw walks (the last gait cycle of {STEPS} steps, sampled at \
         {RATE} Hz, mass 23 H² kg) over heights {:?} m, step lengths {:?} m, attributes {:?}",
        grid.heights, grid.step_lengths, grid.attributes
    );
    Ok((
        Database {
            description,
            entries,
        },
        skipped,
    ))
}
