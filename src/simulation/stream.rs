//! A walk simulated one step at a time and sampled into figure frames as the steps come, so that
//! a walk of any length runs in bounded memory: one step is alive (two while the gait events of
//! the finished one are found: they need the new step's double support). Per-step
//! reports, events, the engine's state frames and the clinical angles for cycle averaging are
//! gathered on the side, each only when asked for.
use crate::analysis::events::{Event, step_events};
use crate::engine::parameters::EngineParameters;
use crate::engine::report::{StateFrame, StepReport};
use crate::engine::walker::{Step, Walker, walk_attributes};
use crate::error::{Error, Result};
use crate::figure::clinical::{Clinical, clinical};
use crate::figure::{Landmarks, landmarks};
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::plan::gait::Gait;

/// What to gather besides the figure frames.
#[derive(Clone, Copy, Debug, Default)]
pub struct Gather {
    /// Keep every step's report (otherwise only the shooting statistics are kept).
    pub reports: bool,
    /// Find the gait events of every step ([`Event`]).
    pub events: bool,
    /// Sample the engine's state frames ([`StateFrame`]) at the stream's rate for the first
    /// this many steps: 0 for none, `usize::MAX` for every step (a figure of the walk needs
    /// only its first steps, [`crate::plot::walk::FIGURE_STEPS`], and then holds a bounded
    /// number of frames however long the walk).
    pub state_frame_steps: usize,
    /// Compute the clinical angles of every frame, for the gait-cycle average.
    pub clinical: bool,
}

/// The frames of a walk, as an iterator of figure frames (`Err` ends it: a step failed).
pub struct WalkStream<'a> {
    walker: Walker,
    gaits: std::slice::Iter<'a, Gait>,
    fps: f64,
    /// Frames 0..=last, at k / fps.
    next_frame: usize,
    last_frame: usize,
    duration: f64,
    current: Option<Step>,
    gather: Gather,
    failed: bool,
    /// Every step's report (with [`Gather::reports`]).
    pub reports: Vec<StepReport>,
    /// Steps simulated.
    pub steps: usize,
    /// Shooting solves over all steps.
    pub solves: usize,
    /// Trial integrations over all solves.
    pub iterations: usize,
    /// The most trial integrations of one solve.
    pub max_iterations: usize,
    /// Gait events (with [`Gather::events`]).
    pub events: Vec<Event>,
    /// The engine's state frames (of the first [`Gather::state_frame_steps`] steps).
    pub state_frames: Vec<StateFrame>,
    /// Clinical angles of every frame (with [`Gather::clinical`]).
    pub clinical: Vec<Clinical>,
    /// Heel strikes of the right foot (the start of every even step), gathered with `clinical`.
    pub right_heel_strikes: Vec<f64>,
}

impl<'a> WalkStream<'a> {
    /// The stream with the engine's model constants `parameters` instead of the bundled ones
    /// (before its first frame).
    pub fn with_parameters(mut self, parameters: EngineParameters) -> Self {
        self.walker = self.walker.with_parameters(parameters);
        self
    }

    /// One step per gait, frames at `fps` from t = 0 to the last heel strike (inclusive), with
    /// the walk's attributes ([`walk_attributes`]).
    pub fn new(body: Body, attrs: Attributes, gaits: &'a [Gait], fps: f64, gather: Gather) -> Self {
        // the walk lasts Σ 60 / sf, known before anything is simulated
        let duration = crate::plan::gait::walk_duration(gaits);
        WalkStream {
            walker: Walker::new(body, walk_attributes(&body, &attrs, gaits)),
            gaits: gaits.iter(),
            fps,
            next_frame: 0,
            last_frame: crate::engine::step::last_frame(duration, fps),
            duration,
            current: None,
            gather,
            failed: false,
            reports: Vec::new(),
            steps: 0,
            solves: 0,
            iterations: 0,
            max_iterations: 0,
            events: Vec::new(),
            state_frames: Vec::new(),
            clinical: Vec::new(),
            right_heel_strikes: Vec::new(),
        }
    }

    /// Simulated duration (s).
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// The frames the stream yields: at k / fps from t = 0 to the last heel strike.
    pub fn frames(&self) -> usize {
        self.last_frame + 1
    }

    /// The walker's locomotion attributes.
    pub fn attributes(&self) -> &Attributes {
        &self.walker.attrs
    }

    /// Simulate the next step; the step before it is then complete (its events are known).
    fn advance(&mut self) -> Option<Result<()>> {
        let gait = *self.gaits.next()?;
        let step = match self.walker.step(gait) {
            Ok(s) => s,
            Err(e) => return Some(Err(e.into())),
        };
        if self.gather.clinical && step.index.is_multiple_of(2) {
            self.right_heel_strikes.push(step.t_start);
        }
        self.steps += 1;
        for solve in &step.solves {
            self.solves += 1;
            self.iterations += solve.report.iterations;
            self.max_iterations = self.max_iterations.max(solve.report.iterations);
        }
        if self.gather.reports {
            self.reports.push(step.report.clone());
        }
        if let Some(done) = self.current.take()
            && self.gather.events
        {
            self.events
                .extend(step_events(&[done, step.clone()], self.duration));
        }
        self.current = Some(step);
        Some(Ok(()))
    }

    /// Call after the iteration: the events of the last stance (which ends with the walk) and
    /// the events in time order.
    pub fn finish(&mut self) {
        if self.gather.events
            && let Some(last) = &self.current
        {
            self.events
                .extend(step_events(std::slice::from_ref(last), self.duration));
            self.events.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
            self.gather.events = false;
        }
    }

    fn frame(&mut self, t: f64) -> Option<Result<Landmarks>> {
        loop {
            let need = match &self.current {
                None => true,
                Some(s) => t >= s.t_start + s.constraints.timing.t_step && self.gaits.len() > 0,
            };
            if !need {
                break;
            }
            if let Err(e) = self.advance()? {
                return Some(Err(e));
            }
        }
        let step = self.current.as_ref()?;
        let lm = landmarks(step, t, &self.walker.attrs).map_err(Error::from);
        if step.index < self.gather.state_frame_steps {
            self.state_frames.push(step.frame(t, &step.stance_leg.foot));
        }
        if self.gather.clinical
            && let Ok(l) = &lm
        {
            match clinical(l, &self.walker.body) {
                Ok(c) => self.clinical.push(c),
                Err(e) => return Some(Err(e.into())),
            }
        }
        Some(lm)
    }
}

impl Iterator for WalkStream<'_> {
    type Item = Result<Landmarks>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed || self.next_frame > self.last_frame {
            return None;
        }
        let t = self.next_frame as f64 / self.fps;
        self.next_frame += 1;
        let mut item = self.frame(t);
        if self.next_frame > self.last_frame && matches!(item, Some(Ok(_))) {
            // the steps after the last frame (a low frame rate) are walked too, before it is
            // handed out: their reports, events and failures belong to the walk, and a failure
            // takes the last frame's place (so there are never more items than frames)
            while self.gaits.len() > 0 {
                if let Some(Err(e)) = self.advance() {
                    item = Some(Err(e));
                    break;
                }
            }
        }
        if matches!(item, Some(Err(_))) {
            self.failed = true;
        }
        item
    }

    /// At most the frames left (a failure ends the stream early): what a motion file's header
    /// counts (`export::try_write` writes it first then).
    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = if self.failed {
            0
        } else {
            (self.last_frame + 1).saturating_sub(self.next_frame)
        };
        (0, Some(left))
    }
}
