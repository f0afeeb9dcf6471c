//! klaw: goal-directed, dynamically simulated human walking after Bruderlin & Calvert,
//! "Goal-directed, dynamic animation of human walking" (SIGGRAPH 1989).
//!
//! A walk is built with [`Simulation`]: a body (height, mass), locomotion attributes or a style
//! preset, the gait of every step (any of velocity, step length, step frequency, completed by
//! the paper's normalizing formula) and a step count, each with a default (H = 1.8 m, M = 80 kg,
//! v = 1.4 m/s, 10 steps, the default attributes). [`Simulation::run`] checks the inputs and
//! simulates the walk; the [`Walk`] it returns gives the figure's frames, the clinical joint
//! angles, the gait events, the per-step report and the exports (CSV, OpenSim `.mot` / `.sto`,
//! BVH). [`Prepared::stream`] walks any number of steps in bounded memory.
//!
//! ```
//! use klaw::{GaitRequest, Options, Simulation};
//!
//! let walk = Simulation::default()
//!     .gait(GaitRequest { velocity: Some(1.2), ..Default::default() })
//!     .steps(4)
//!     .run()?;
//! let report = walk.report();
//! assert_eq!(report.steps.len(), 4);
//! // the right knee's largest flexion (rad), from the clinical angles at 100 frames/s
//! let knee = walk
//!     .clinical_angles(100.0)?
//!     .iter()
//!     .map(|c| c.right.knee.flexion)
//!     .fold(f64::NEG_INFINITY, f64::max);
//! assert!((0.8..1.4).contains(&knee), "{}°", knee.to_degrees());
//! let path = std::env::temp_dir().join(format!("klaw-doc-{}.mot", std::process::id()));
//! walk.write(&path, 100.0, &Options::default())?;
//! # std::fs::remove_file(&path).unwrap();
//! # Ok::<(), klaw::Error>(())
//! ```

#![warn(missing_docs)]

// The levels of the control hierarchy, lowest first (tests/architecture.rs holds them); a module
// imports only from lower levels.
// 0, numerics: ODE integration, root finding, trigonometry.
pub mod numerics;
// 1, model: body segments, locomotion attributes.
pub mod model;
// 2, kinematics: the foot, the pelvis determinants, the virtual stance leg.
pub mod kinematics;
// 2, dynamics: the stance and swing models, the heel-strike impulse.
pub mod dynamics;
// 3, the high level: the gait completed by the normalizing formula, the step constraints.
pub mod plan;
// 4, the low level: the stance and swing controllers, their shooting solves.
pub mod control;
// 5, engine: the step loop, the streamed walk, the per-step report, the actuators' work.
pub mod engine;
// 6, the figure around the dynamic model: landmarks, skeleton, clinical angles.
pub mod figure;
// 7, analysis of a walk: the gait events.
pub mod analysis;
// 8, non-rhythmic stepping: single steps and turnarounds (Ko & Badler 1993).
pub mod nrs;
// 9, walk data and its generalization to other step lengths and bodies (Ko & Badler 1992).
pub mod generalize;
// 10, motion files: clinical-angle CSV, OpenSim .mot / .sto, BVH, gait-cycle curves.
pub mod export;
// 10, files in and out: atomic writes, frames, events, report, attribute and schedule files.
pub mod input;
// 10, inverse kinematics of the lower limbs from ankle trajectories (Pronost et al.).
pub mod ik;
// 11, sweeps: many walks over a grid of inputs, their summary rows.
pub mod sweep;
// 11, scenarios: stand, walk, step, turn and pause in one motion.
pub mod scenario;
// 11, beside the binary: the library API, the `Simulation` builder and the `Walk` it returns.
pub mod simulation;
// 12, figures: the walk, the gait cycle, the animated GIF, sweep heat maps.
pub mod plot;
// 12, poulaines: ankle trajectories relative to the pelvis, their model and database.
pub mod poulaine;

// 0, the memory policy of long-running callers; beside the levels, the crate's error type.
pub mod error;
pub mod memory;

pub use analysis::cycle::CycleCurves;
pub use analysis::events::Event;
pub use engine::report::{Report, StepReport};
pub use error::{Error, Result};
pub use export::{Format, OpenSimModel, Options};
pub use figure::clinical::Clinical;
pub use figure::{Landmarks, Placement};
pub use model::attributes::{AttributeTable, Attributes};
pub use model::body::Body;
pub use plan::{Gait, GaitRequest, StepConstraints, Timing};
pub use simulation::stream::{Gather, WalkStream};
pub use simulation::{Prepared, Simulation, Walk};
