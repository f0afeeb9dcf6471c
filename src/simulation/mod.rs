//! The library's front door: a builder that checks and completes a walk's inputs as the `klaw`
//! command line does (the body, the attributes or a style preset, the gait of every step
//! completed by the normalizing formula, KLAW 1989 eq. 1), runs the step loop (KLAW 1989
//! Figure 1) and hands back a [`Walk`] whose figure frames, clinical angles, gait events, report
//! and exports are methods. It composes the levels below it (plan, engine, figure, analysis,
//! export, input) and adds nothing to the physics.
//!
//! A [`Walk`] keeps every step's records, its memory grows with the step count; for long walks
//! [`Prepared::stream`] samples the figure step by step in bounded memory.

pub mod stream;

use std::fmt;
use std::path::Path;

use crate::analysis::cycle::{CycleCurves, cycle_average};
use crate::analysis::events::{self, Event};
use crate::engine::parameters::EngineParameters;
use crate::engine::report::{Report, StateFrame};
use crate::engine::walker::{self, simulate_with};
use crate::error::Result;
use crate::export::{self, Format, Options};
use crate::figure::clinical::{Clinical, clinical};
use crate::figure::{Landmarks, frames, landmarks};
use crate::model::InputError;
use crate::model::attributes::{AttributeTable, Attributes, style};
use crate::model::body::Body;
use crate::plan::{Gait, GaitRequest};
use crate::simulation::stream::{Gather, WalkStream};

/// Body height H of [`Simulation::default`] (m): the paper's example figure.
pub const DEFAULT_HEIGHT: f64 = 1.8;
/// Body mass M of [`Simulation::default`] (kg).
pub const DEFAULT_MASS: f64 = 80.0;
/// Number of steps (heel strike to heel strike) of a walk with one gait, when not given.
pub const DEFAULT_STEPS: usize = 10;
/// Most steps of one walk, as the command line allows.
pub const MAX_STEPS: usize = 1_000_000;
pub use crate::export::{MAX_FPS, MIN_FPS};

/// Where the walk's attributes come from.
#[derive(Clone, Debug)]
enum AttributeSource {
    /// Attributes given whole (boxed: they are 29 numbers).
    Given(Box<Attributes>),
    /// A bundled style preset (`models/styles/`) over the defaults.
    Style(String),
}

/// What the walk's steps ask for.
#[derive(Clone, Debug)]
enum Requests {
    /// The attributes' preferred gait ([`GaitRequest::preferred`]) for every step.
    Preferred,
    /// One gait for every step.
    One(GaitRequest),
    /// One gait per step, the last one held.
    Schedule(Vec<GaitRequest>),
}

/// A walk to simulate: body, attributes, gait(s) and step count, each with a default.
///
/// Nothing is checked or simulated until [`prepare`](Simulation::prepare) or
/// [`run`](Simulation::run); the setters only record. Defaults: the body of
/// [`Simulation::default`] (H = 1.8 m, M = 80 kg) or the one given to [`new`](Simulation::new),
/// the bundled default attributes, v = 1.4 m/s completed by the normalizing formula, 10 steps.
///
/// ```
/// use klaw::{GaitRequest, Simulation};
///
/// let walk = Simulation::default()
///     .gait(GaitRequest { step_frequency: Some(100.0), ..Default::default() })
///     .style("brisk")
///     .steps(2)
///     .run()?;
/// assert_eq!(walk.report().steps.len(), 2);
/// # Ok::<(), klaw::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Simulation {
    body: Body,
    attributes: AttributeSource,
    requests: Requests,
    steps: Option<usize>,
    parameters: EngineParameters,
}

impl Default for Simulation {
    /// The default walk: H = [`DEFAULT_HEIGHT`], M = [`DEFAULT_MASS`], v = the attributes'
    /// `preferred_velocity` (1.4 m/s),
    /// [`DEFAULT_STEPS`] steps, the default attributes.
    fn default() -> Self {
        let body = Body::standard(DEFAULT_HEIGHT, DEFAULT_MASS)
            .expect("the default body lies inside the body table's limits");
        Simulation::new(body)
    }
}

impl Simulation {
    /// A walk of `body` (e.g. [`Body::standard`]`(height, mass)`) with the other defaults.
    pub fn new(body: Body) -> Self {
        Simulation {
            body,
            attributes: AttributeSource::Given(Box::default()),
            requests: Requests::Preferred,
            steps: None,
            parameters: EngineParameters::default(),
        }
    }

    /// Walk with these attributes (SI units, e.g. from [`AttributeTable::resolve`]); replaces a
    /// [`style`](Simulation::style) set before.
    pub fn attributes(mut self, attributes: Attributes) -> Self {
        self.attributes = AttributeSource::Given(Box::new(attributes));
        self
    }

    /// Walk in a bundled style preset (`normal`, `brisk`, `elderly`, `march`, `long-stride`, `paper`:
    /// `models/styles/`), its values over the default attributes; replaces
    /// [`attributes`](Simulation::attributes) set before. An unknown name is an error of
    /// [`prepare`](Simulation::prepare).
    pub fn style(mut self, name: &str) -> Self {
        self.attributes = AttributeSource::Style(name.to_string());
        self
    }

    /// Every step walks this gait: any of v (m/s), sl (m), sf (steps/min), completed by the
    /// normalizing formula and checked against the attributes' limits
    /// ([`GaitRequest::complete`]; an empty request is [`InputError::MissingGait`]). Replaces a
    /// [`schedule`](Simulation::schedule) set before.
    pub fn gait(mut self, request: GaitRequest) -> Self {
        self.requests = Requests::One(request);
        self
    }

    /// Every step walks at `velocity` (m/s), sl and sf from the normalizing formula: the same as
    /// [`gait`](Simulation::gait) with only the velocity.
    pub fn velocity(self, velocity: f64) -> Self {
        self.gait(GaitRequest {
            velocity: Some(velocity),
            ..GaitRequest::default()
        })
    }

    /// One gait request per step (each completed and checked as by
    /// [`gait`](Simulation::gait)): the walk has as many steps as the schedule unless
    /// [`steps`](Simulation::steps) says otherwise (fewer: the schedule is cut; more: its last
    /// gait is held). An empty schedule is [`InputError::MissingGait`].
    pub fn schedule(mut self, requests: Vec<GaitRequest>) -> Self {
        self.requests = Requests::Schedule(requests);
        self
    }

    /// The number of steps, heel strike to heel strike: 1 to [`MAX_STEPS`] (default
    /// [`DEFAULT_STEPS`], or the schedule's length).
    pub fn steps(mut self, steps: usize) -> Self {
        self.steps = Some(steps);
        self
    }

    /// The engine's model constants (default: the bundled `models/engine.toml`; a user's copy
    /// through [`EngineParameters::parse`]).
    pub fn engine_parameters(mut self, parameters: EngineParameters) -> Self {
        self.parameters = parameters;
        self
    }

    /// Check and complete the inputs without simulating anything: the step count, the style,
    /// and every step's gait (the errors of the command line for the same values).
    pub fn prepare(&self) -> Result<Prepared> {
        if let Some(n) = self.steps {
            check_steps(n)?;
        }
        let attributes = match &self.attributes {
            AttributeSource::Given(a) => (**a).clone(),
            AttributeSource::Style(name) => {
                AttributeTable::builtin().resolve(&style(name)?, &format!("style {name}"))?
            }
        };
        let complete = |r: &GaitRequest| r.complete(&self.body, &attributes);
        let gaits = match &self.requests {
            Requests::Preferred => {
                let n = self.steps.unwrap_or(DEFAULT_STEPS);
                vec![GaitRequest::preferred(&self.body, &attributes)?; n]
            }
            Requests::One(request) => {
                let n = self.steps.unwrap_or(DEFAULT_STEPS);
                vec![complete(request)?; n]
            }
            Requests::Schedule(rows) => {
                if rows.is_empty() {
                    return Err(InputError::MissingGait.into());
                }
                let n = check_steps(self.steps.unwrap_or(rows.len()))?;
                let mut gaits = rows
                    .iter()
                    .take(n)
                    .map(complete)
                    .collect::<Result<Vec<_>, _>>()?;
                gaits.resize(n, gaits[gaits.len() - 1]);
                gaits
            }
        };
        Ok(Prepared {
            body: self.body,
            attributes,
            gaits,
            parameters: self.parameters,
        })
    }

    /// Check the inputs ([`prepare`](Simulation::prepare)), then simulate the walk.
    pub fn run(&self) -> Result<Walk> {
        self.prepare()?.run()
    }
}

fn check_steps(n: usize) -> Result<usize, InputError> {
    InputError::check_range("steps", n as f64, 1.0, MAX_STEPS as f64, "steps")?;
    Ok(n)
}

fn check_fps(fps: f64) -> Result<f64, InputError> {
    InputError::check_range("fps", fps, MIN_FPS, MAX_FPS, "frames/s")
}

/// A simulation whose inputs are checked and completed: the body, the attributes and one gait
/// per step. Nothing is simulated yet.
#[derive(Clone, Debug)]
pub struct Prepared {
    body: Body,
    attributes: Attributes,
    gaits: Vec<Gait>,
    parameters: EngineParameters,
}

impl Prepared {
    /// The body.
    pub fn body(&self) -> &Body {
        &self.body
    }

    /// The resolved attributes (SI units).
    pub fn attributes(&self) -> &Attributes {
        &self.attributes
    }

    /// The completed gait of every step.
    pub fn gaits(&self) -> &[Gait] {
        &self.gaits
    }

    /// The walk's duration (s), known before it is simulated: Σ 60 / sf over the steps.
    pub fn duration(&self) -> f64 {
        crate::plan::gait::walk_duration(&self.gaits)
    }

    /// Simulate the walk, every step kept.
    pub fn run(self) -> Result<Walk> {
        Ok(Walk {
            walk: simulate_with(self.body, self.attributes, &self.gaits, self.parameters)?,
            gaits: self.gaits,
        })
    }

    /// The walk simulated one step at a time as an iterator of figure frames at `fps` frames/s
    /// (t = 0 to the last heel strike, inclusive), in bounded memory whatever the step count;
    /// `gather` says what else the stream keeps (reports, events, engine state frames, clinical
    /// angles). Call [`WalkStream::finish`] after the last frame to complete the events.
    ///
    /// ```
    /// use klaw::{Format, Gather, Options, Simulation};
    ///
    /// let prepared = Simulation::default().steps(3).prepare()?;
    /// let path = std::env::temp_dir().join(format!("klaw-doc-{}.csv", std::process::id()));
    /// let mut stream = prepared.stream(100.0, Gather { events: true, ..Gather::default() })?;
    /// let options = Options::default();
    /// klaw::export::try_write(&path, Format::Csv, prepared.body(), 100.0, &mut stream, &options)?;
    /// stream.finish();
    /// assert_eq!(stream.events.first().map(|e| e.event), Some("HS"));
    /// # std::fs::remove_file(&path).unwrap();
    /// # Ok::<(), klaw::Error>(())
    /// ```
    pub fn stream(&self, fps: f64, gather: Gather) -> Result<WalkStream<'_>> {
        check_fps(fps)?;
        Ok(
            WalkStream::new(self.body, self.attributes.clone(), &self.gaits, fps, gather)
                .with_parameters(self.parameters),
        )
    }
}

/// A simulated walk: every step's records, and what is read from them on demand (figure
/// frames, clinical angles, events, the report, exports).
///
/// Frames are sampled at t = k / fps, k = 0, 1, … up to the last heel strike (inclusive):
/// ⌊T · fps⌋ + 1 frames for a walk of duration T; `fps` must lie in [[`MIN_FPS`],
/// [`MAX_FPS`]]. The world frame is OpenSim's (x forward, y up, z to the right, metres), its
/// origin on the ground under the first stance ankle.
pub struct Walk {
    walk: walker::Walk,
    gaits: Vec<Gait>,
}

impl fmt::Debug for Walk {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Walk")
            .field("body", &self.walk.body)
            .field("gaits", &self.gaits)
            .field("duration", &self.duration())
            .finish_non_exhaustive()
    }
}

impl Walk {
    /// The body.
    pub fn body(&self) -> &Body {
        &self.walk.body
    }

    /// The attributes the walk was simulated with (SI units): the resolved ones with the pelvic
    /// list and rotation at the walk's speed ([`walk_attributes`](crate::engine::walker::walk_attributes)).
    pub fn attributes(&self) -> &Attributes {
        &self.walk.attrs
    }

    /// The gait each step was asked to walk (completed).
    pub fn gaits(&self) -> &[Gait] {
        &self.gaits
    }

    /// Simulated duration (s): first heel strike to last.
    pub fn duration(&self) -> f64 {
        self.walk.duration()
    }

    /// The figure at time `t` (s, clamped to the walk).
    pub fn figure_at(&self, t: f64) -> Result<Landmarks> {
        let t = InputError::check_range("t", t, f64::MIN, f64::MAX, "s")?;
        let t = t.clamp(0.0, self.duration());
        let steps = &self.walk.steps;
        let i = steps.partition_point(|s| s.t_start <= t).saturating_sub(1);
        Ok(landmarks(&steps[i], t, &self.walk.attrs)?)
    }

    /// The figure's landmarks (joint centres, foot points, pelvis, trunk and arm angles) at
    /// `fps` frames per second.
    pub fn frames(&self, fps: f64) -> Result<Vec<Landmarks>> {
        Ok(frames(&self.walk, check_fps(fps)?).collect::<Result<_, _>>()?)
    }

    /// The clinical joint angles (rad) of every frame at `fps` frames per second.
    pub fn clinical_angles(&self, fps: f64) -> Result<Vec<Clinical>> {
        let frames = frames(&self.walk, check_fps(fps)?);
        Ok(frames
            .map(|lm| clinical(&lm?, &self.walk.body))
            .collect::<Result<_, _>>()?)
    }

    /// The engine's state (θ1…θ4, w, the sagittal joint points, phase) at `fps` frames per
    /// second: the rows of `klaw walk --state-out`.
    pub fn state_frames(&self, fps: f64) -> Result<Vec<StateFrame>> {
        Ok(self.walk.frames(check_fps(fps)?))
    }

    /// Every gait event (heel strike, foot flat, heel-off, metatarsal-off, toe-off) of both
    /// feet at its exact time, in time order.
    pub fn events(&self) -> Vec<Event> {
        events::events(&self.walk)
    }

    /// The per-step report: targets, achievements, shooting statistics, work.
    pub fn report(&self) -> Report {
        self.walk.report()
    }

    /// The clinical angles (frames at `fps`) averaged over the steady gait cycles, right heel
    /// strike to right heel strike, the first cycle skipped as the start-up: 101 rows (0…100 %).
    /// A walk needs at least 5 steps for one such cycle.
    pub fn gait_cycle(&self, fps: f64) -> Result<CycleCurves> {
        let right_heel_strikes: Vec<f64> = self
            .walk
            .steps
            .iter()
            .step_by(2)
            .map(|s| s.t_start)
            .collect();
        Ok(cycle_average(
            &self.clinical_angles(fps)?,
            &right_heel_strikes,
            1,
        )?)
    }

    /// Write the motion at `fps` frames per second to `path` in the format of its extension:
    /// `.csv` (clinical angles in degrees), `.mot` / `.sto` (OpenSim coordinates of
    /// `options.opensim_model`), `.bvh` (root in place if `options.in_place`). Written whole or
    /// not at all.
    pub fn write(&self, path: impl AsRef<Path>, fps: f64, options: &Options) -> Result<()> {
        let path = path.as_ref();
        let fps = check_fps(fps)?;
        let format = Format::from_path(path)?;
        let figure = frames(&self.walk, fps);
        export::try_write(path, format, &self.walk.body, fps, figure, options)
    }

    /// Write the [`events`](Walk::events) as CSV (`time_s, side, event, step`).
    pub fn write_events(&self, path: impl AsRef<Path>) -> Result<()> {
        crate::export::write_events_csv(path.as_ref(), &self.events())
    }

    /// Write the [`report`](Walk::report) as JSON.
    pub fn write_report(&self, path: impl AsRef<Path>) -> Result<()> {
        crate::export::write_report_json(path.as_ref(), &self.report())
    }

    /// Write the [`state_frames`](Walk::state_frames) at `fps` as CSV.
    pub fn write_state(&self, path: impl AsRef<Path>, fps: f64) -> Result<()> {
        crate::export::write_frames_csv(path.as_ref(), &self.state_frames(fps)?)
    }

    /// Write the [`gait_cycle`](Walk::gait_cycle) at `fps` as CSV (`cycle_pct`, then every
    /// angle in degrees).
    pub fn write_cycle(&self, path: impl AsRef<Path>, fps: f64) -> Result<()> {
        export::write_cycle_csv(path.as_ref(), &self.gait_cycle(fps)?)
    }

    /// The engine's walk (every step's constraints, dynamic records and report), for the
    /// functions that take one (the figures of `klaw::plot`).
    pub fn engine(&self) -> &walker::Walk {
        &self.walk
    }

    /// The engine's walk, by value.
    pub fn into_engine(self) -> walker::Walk {
        self.walk
    }
}
