//! Running a scenario: its actions one after the other from quiet standing, each a piece of
//! motion on one clock, the figure sampled at the frame rate. A walk (consecutive walk actions
//! are one walk) is preceded by a start from standing and followed by a stop into standing
//! ([`crate::nrs::handover`]).
use crate::engine::walker::{self, Walk};
use crate::export::{MAX_FPS, MIN_FPS};
use crate::figure::placement::Placement;
use crate::figure::{Landmarks, landmarks};
use crate::kinematics::foot::Foot;
use crate::model::InputError;
use crate::nrs::handover::{planted, start, stop, walk_end};
use crate::nrs::pose::{Planted, direction, right_of};
use crate::nrs::{NrsError, NrsStep, Side, StepSpecs, TurnSpecs, Turnaround, WalkerState};
use crate::plan::Gait;
use crate::scenario::contacts::contacts;
use crate::scenario::{Action, Footprint, Goal, Motion, Scenario, ScenarioError, Span};

/// One piece of the scenario's motion.
enum Piece {
    /// The figure holds `state`'s pose.
    Hold(Box<WalkerState>),
    Step(Box<NrsStep>),
    Turn(Box<Turnaround>),
    /// The engine's walk, placed, starting at `t0` with step index `step`.
    Walk {
        walk: Box<Walk>,
        at: Placement,
        t0: f64,
        step: usize,
    },
}

/// A piece on the scenario's clock.
struct Timed {
    piece: Piece,
    span: Span,
}

impl Timed {
    /// The figure at scenario time `t` within the span.
    fn pose(&self, t: f64) -> Result<Landmarks, NrsError> {
        let d = self.span.t_end - self.span.t_start;
        let u = if d > 0.0 {
            ((t - self.span.t_start) / d).clamp(0.0, 1.0)
        } else {
            1.0
        };
        Ok(match &self.piece {
            Piece::Hold(s) => s.figure_with(&s.upper, t)?,
            Piece::Step(s) => s.advance(u),
            Piece::Turn(s) => s.advance(u),
            Piece::Walk { walk, at, t0, step } => {
                let local = (t - t0).clamp(0.0, walk.duration());
                let i = walk
                    .steps
                    .partition_point(|s| s.t_start <= local)
                    .saturating_sub(1);
                let mut lm = at.apply(&landmarks(&walk.steps[i], local, &walk.attrs)?);
                lm.time = t;
                lm.step += step;
                lm
            }
        })
    }
}

/// The scenario's pieces, built action by action.
struct Runner<'a> {
    scenario: &'a Scenario,
    state: WalkerState,
    pieces: Vec<Timed>,
    footprints: Vec<Footprint>,
}

impl Runner<'_> {
    fn push(&mut self, piece: Piece, action: usize, kind: &'static str, duration: f64) {
        let t_start = self.state.time;
        self.pieces.push(Timed {
            piece,
            span: Span {
                action,
                kind,
                t_start,
                t_end: t_start + duration,
            },
        });
    }

    fn footprint(&mut self, side: Side, action: usize, time: f64) {
        let f = *self.state.foot(side);
        self.place(f, side, action, time);
    }

    fn place(&mut self, f: Planted, side: Side, action: usize, time: f64) {
        self.footprints.push(Footprint {
            index: self.footprints.len(),
            side,
            ankle: f.flat,
            direction: f.heading,
            time,
            action,
        });
    }

    fn hold(&mut self, seconds: f64, action: usize, kind: &'static str) {
        let mut end = self.state.clone();
        end.time += seconds;
        self.push(
            Piece::Hold(Box::new(self.state.clone())),
            action,
            kind,
            seconds,
        );
        self.state = end;
    }

    fn step(&mut self, step: NrsStep, action: usize, kind: &'static str, side: Side) {
        let end = step.end_state().clone();
        let d = step.duration();
        self.push(Piece::Step(Box::new(step)), action, kind, d);
        self.state = end;
        let t = self.state.time;
        self.footprint(side, action, t);
    }

    /// A walk of `gaits` with its start and stop.
    fn walk(&mut self, gaits: &[Gait], action: usize) -> Result<(), NrsError> {
        let s = self.scenario;
        // one step more than asked: the hip velocity after the last heel strike
        let mut more = gaits.to_vec();
        more.push(gaits[gaits.len() - 1]);
        let mut walk = walker::simulate(s.body, s.attrs.clone(), &more)?;
        let next = walk.steps.pop().expect("the extra step");
        let (first, at) = start(&self.state, &walk)?;
        self.step(first, action, "start", walk.steps[0].side);
        let t0 = self.state.time;
        let tau = self.state.params.stop_handover;
        let end = walk_end(&self.state, &walk, &next, &at, (t0, tau))?;
        let closing = stop(&end, &walk, at.heading)?;
        // every later heel strike of the walk places the striking foot
        let foot = Foot::new(&s.body);
        for st in walk.steps.iter().skip(1) {
            let own = landmarks(st, st.t_start, &walk.attrs)?;
            let leg = match st.side {
                Side::Right => own.right,
                Side::Left => own.left,
            };
            let p = planted(&leg, &foot, s.attrs.metatarsal_limit);
            let [x, _, z] = at.to_world([p.flat[0], 0.0, p.flat[1]]);
            let placed = Planted {
                flat: [x, z],
                heading: at.heading,
                pitch: 0.0,
            };
            self.place(placed, st.side, action, t0 + st.t_start);
        }
        let last = walk.steps.last().expect("a walk has a step").side;
        let step = self.state.step;
        let d = walk.duration();
        // the walk runs `tau` into the next step, where the stop takes over
        walk.steps.push(next);
        self.push(
            Piece::Walk {
                walk: Box::new(walk),
                at,
                t0,
                step,
            },
            action,
            "walk",
            d + tau,
        );
        self.state = end;
        let striking = last.other();
        self.footprint(striking, action, t0 + d);
        self.step(closing, action, "stop", last);
        Ok(())
    }
}

/// The specs of a step action from the walker's state: a relative goal is the stepping foot's
/// displacement in the pelvis's facing frame, a gaze the change from that facing.
fn step_specs(state: &WalkerState, action: &Action) -> Option<(StepSpecs, Option<f64>)> {
    let Action::Step {
        side,
        goal,
        duration,
        swing_height_factor,
        gaze,
        foot_angles,
    } = action
    else {
        return None;
    };
    let facing = state.upper.heading;
    let (foot_position, foot_direction) = match *goal {
        Goal::Relative {
            forward,
            left,
            turn,
        } => {
            let f = state.foot(*side);
            let (d, r) = (direction(facing), right_of(facing));
            (
                [
                    f.flat[0] + forward * d[0] - left * r[0],
                    f.flat[1] + forward * d[1] - left * r[1],
                ],
                f.heading + turn,
            )
        }
        Goal::World {
            position,
            direction,
        } => (position, direction),
    };
    Some((
        StepSpecs {
            foot_position,
            foot_direction,
            side: *side,
            swing_height_factor: swing_height_factor.unwrap_or(state.params.swing_height_factor),
            gaze_direction: gaze.map(|g| facing + g),
            foot_angles: *foot_angles,
        },
        *duration,
    ))
}

/// Check what can be checked without simulating: the frame rate, the times, where a stand
/// may place the figure, and every walk's gaits.
fn check(s: &Scenario, fps: f64) -> Result<Vec<Option<Vec<Gait>>>, ScenarioError> {
    let fail = |index: usize, name: &'static str, e: NrsError| ScenarioError {
        index,
        name,
        source: Box::new(e),
    };
    InputError::check_range("fps", fps, MIN_FPS, MAX_FPS, "frames/s")
        .map_err(|e| fail(0, "scenario", e.into()))?;
    let mut gaits = Vec::with_capacity(s.actions.len());
    for (i, a) in s.actions.iter().enumerate() {
        let name = a.name();
        let err = |e: InputError| fail(i, name, e.into());
        let seconds = |v: f64| InputError::check_range("seconds", v, 0.0, 86_400.0, "s");
        match a {
            Action::Stand {
                seconds: t,
                at,
                facing,
            } => {
                seconds(*t).map_err(err)?;
                if i > 0 && (at.is_some() || facing.is_some()) {
                    return Err(err(InputError::malformed(
                        "scenario",
                        std::path::Path::new("stand"),
                        "`at` and `facing` place the figure in the first action only",
                    )));
                }
            }
            Action::Pause { seconds: t } => {
                seconds(*t).map_err(err)?;
            }
            Action::Walk { gaits: g } if g.is_empty() => {
                return Err(err(InputError::MissingGait));
            }
            _ => {}
        }
        gaits.push(match a {
            Action::Walk { gaits: g } => Some(
                g.iter()
                    .map(|r| r.complete(&s.body, &s.attrs))
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(err)?,
            ),
            _ => None,
        });
    }
    Ok(gaits)
}

/// Run `scenario` and sample it at `fps` frames/s: its frames (world frame, times from 0), the
/// footprints and the actions' spans. Fails, naming the action, on an input out of range, an
/// illegal step goal, a leg that cannot reach or a walk the engine cannot solve.
pub fn run(scenario: &Scenario, fps: f64) -> Result<Motion, ScenarioError> {
    let gaits = check(scenario, fps)?;
    let (at, facing) = match scenario.actions.first() {
        Some(Action::Stand { at, facing, .. }) => (at.unwrap_or([0.0; 2]), facing.unwrap_or(0.0)),
        _ => ([0.0; 2], 0.0),
    };
    let (body, attrs) = (scenario.body, scenario.attrs.clone());
    let state = WalkerState::standing_with(body, attrs, scenario.nrs, at, facing);
    let mut r = Runner {
        scenario,
        state,
        pieces: Vec::new(),
        footprints: Vec::new(),
    };
    r.footprint(Side::Right, 0, 0.0);
    r.footprint(Side::Left, 0, 0.0);
    let mut i = 0;
    while i < scenario.actions.len() {
        let action = &scenario.actions[i];
        let fail = |e: NrsError| ScenarioError {
            index: i,
            name: action.name(),
            source: Box::new(e),
        };
        match action {
            Action::Stand { seconds, .. } => r.hold(*seconds, i, "stand"),
            Action::Pause { seconds } => r.hold(*seconds, i, "pause"),
            Action::Walk { .. } => {
                // consecutive walks are one walk
                let mut all: Vec<Gait> = Vec::new();
                let mut j = i;
                while let Some(Some(g)) = gaits.get(j) {
                    all.extend_from_slice(g);
                    j += 1;
                }
                r.walk(&all, i).map_err(fail)?;
                i = j;
                continue;
            }
            Action::Step { side, .. } => {
                let (specs, duration) = step_specs(&r.state, action).expect("a step");
                let step = NrsStep::initialize(&r.state, &specs, duration).map_err(fail)?;
                r.step(step, i, "step", *side);
            }
            Action::Turn {
                angle,
                side,
                kind,
                step_duration,
            } => {
                let specs = TurnSpecs {
                    angle: *angle,
                    side: *side,
                    kind: *kind,
                };
                let turn =
                    Turnaround::initialize(&r.state, &specs, *step_duration).map_err(fail)?;
                for step in turn.steps() {
                    let end = step.end_state();
                    r.place(*end.foot(step.side()), step.side(), i, end.time);
                }
                let end = turn.end_state().clone();
                let d = turn.duration();
                r.push(Piece::Turn(Box::new(turn)), i, "turn", d);
                r.state = end;
            }
        }
        i += 1;
    }
    sample(r, fps)
}

/// The frames of the pieces at `fps`, from 0 to the end.
fn sample(r: Runner<'_>, fps: f64) -> Result<Motion, ScenarioError> {
    let total = r.state.time;
    let n = (total * fps + 1e-9).floor() as usize;
    let mut frames = Vec::with_capacity(n + 1);
    let mut p = 0;
    for k in 0..=n {
        let t = k as f64 / fps;
        while p + 1 < r.pieces.len() && t >= r.pieces[p].span.t_end {
            p += 1;
        }
        let Some(piece) = r.pieces.get(p) else {
            frames.push(
                r.state
                    .figure_with(&r.state.upper, t)
                    .map_err(|e| ScenarioError {
                        index: 0,
                        name: "stand",
                        source: Box::new(e),
                    })?,
            );
            continue;
        };
        frames.push(piece.pose(t).map_err(|e| ScenarioError {
            index: piece.span.action,
            name: piece.span.kind,
            source: Box::new(e),
        })?);
    }
    let spans: Vec<Span> = r.pieces.iter().map(|p| p.span).collect();
    let contacts = contacts(&spans, r.state.params.contact_height, |k, t| {
        r.pieces[k].pose(t).map_err(|e| ScenarioError {
            index: spans[k].action,
            name: spans[k].kind,
            source: Box::new(e),
        })
    })?;
    Ok(Motion {
        frames,
        footprints: r.footprints,
        spans,
        contacts,
    })
}
