//! Scenario files (`klaw scenario FILE.toml`, docs/nrs.md): an optional `[body]` (height m,
//! mass kg, style, table: a bundled name or a table file relative to the scenario file's folder,
//! docs/bodies.md), optional `[attributes]` (the names, units and ranges of
//! `klaw walk --attributes`), and `[[action]]` tables of type stand, walk, step, turn, pause.
//! Angles are degrees in the file and radians in the [`Scenario`]. The body, attributes and
//! gaits are built by the same code as `klaw walk`'s ([`Body::standard`],
//! [`crate::input::attributes_with`], [`GaitRequest::complete`]).
use std::collections::BTreeMap;
use std::path::Path;

use toml::{Table, Value};

use super::fields::{FieldError, Fields, wrong};
use super::file_error::{Place, Problem, ScenarioFileError};
use super::{Action, Goal, Scenario};
use crate::error::Result;
use crate::model::InputError;
use crate::model::attributes::{Attributes, overrides_of_table};
use crate::model::body::{Body, BodyTable, DEFAULT_BODY_TABLE};
use crate::nrs::parameters::NrsParameters;
use crate::nrs::specs::{FootAngles, Side, TurnKind};
use crate::plan::GaitRequest;

/// `klaw walk`'s default body height (m) and mass (kg).
pub const DEFAULT_HEIGHT: f64 = 1.8;
/// `klaw walk`'s default body mass (kg).
pub const DEFAULT_MASS: f64 = 80.0;
/// The most steps of one walk action (the scenario holds its whole motion in memory).
pub const MAX_WALK_STEPS: i64 = 10_000;
/// The longest stand or pause (s).
pub const MAX_SECONDS: f64 = 3600.0;
/// The farthest a relative step goal may lie (m) in each direction (the NRS checks reach).
pub const MAX_RELATIVE: f64 = 2.0;
pub use super::fields::MAX_WORLD;
/// The largest turn of one turn action (deg); it is split into turnarounds of at most 100°.
pub const MAX_TURN_DEG: f64 = 1080.0;
/// The largest |foot angle| of `foot_angles` (deg).
pub const MAX_FOOT_ANGLE_DEG: f64 = 60.0;

/// Read the scenario file `path` (see the module's documentation), with `models/nrs.toml`'s
/// constants.
pub fn read_scenario(path: &Path) -> Result<Scenario> {
    read_scenario_with(path, NrsParameters::default())
}

/// [`read_scenario`] with the NRS constants `nrs` (a model file's, [`NrsParameters::read`]):
/// the steps' and turns' values are checked against its ranges, and the scenario runs with it.
pub fn read_scenario_with(path: &Path, nrs: NrsParameters) -> Result<Scenario> {
    let text = std::fs::read_to_string(path).map_err(|source| crate::Error::Io {
        action: "reading",
        path: path.to_path_buf(),
        source,
    })?;
    Ok(parse_scenario_with(&text, path, nrs)?)
}

/// Parse the text of a scenario file; `path` names it in errors.
pub fn parse_scenario(text: &str, path: &Path) -> Result<Scenario, ScenarioFileError> {
    parse_scenario_with(text, path, NrsParameters::default())
}

/// [`parse_scenario`] with the NRS constants `nrs`.
pub fn parse_scenario_with(
    text: &str,
    path: &Path,
    nrs: NrsParameters,
) -> Result<Scenario, ScenarioFileError> {
    let err = |place: Place, field: &str, problem: Problem| ScenarioFileError {
        path: path.to_path_buf(),
        place,
        field: field.to_string(),
        problem,
    };
    let at = |e: FieldError| err(e.place, &e.field, e.problem);
    let mut top: Table =
        toml::from_str(text).map_err(|e| err(Place::Top, "", Problem::Toml(Box::new(e))))?;
    let known_top = ["body", "attributes", "action"];
    if let Some(k) = top.keys().find(|k| !known_top.contains(&k.as_str())) {
        let known = known_top.join(", ");
        return Err(err(Place::Top, k, Problem::UnknownKey { known }));
    }
    let fields = |name: &'static str, v: Option<Value>| -> Result<Fields, ScenarioFileError> {
        match v {
            None => Ok(Fields::new(Place::Table(name), Table::new())),
            Some(Value::Table(t)) => Ok(Fields::new(Place::Table(name), t)),
            Some(other) => Err(err(Place::Top, name, wrong("a table", &other))),
        }
    };
    let mut body_table = fields("body", top.remove("body"))?;
    let height = body_table
        .number("height")
        .map_err(at)?
        .unwrap_or(DEFAULT_HEIGHT);
    let mass = body_table
        .number("mass")
        .map_err(at)?
        .unwrap_or(DEFAULT_MASS);
    let style = body_table.string("style").map_err(at)?;
    let table = body_table.string("table").map_err(at)?;
    body_table
        .finish("height, mass, style, table")
        .map_err(at)?;
    let table = table.as_deref().unwrap_or(DEFAULT_BODY_TABLE);
    let body = BodyTable::load(table, path.parent()).and_then(|t| Body::new(&t, height, mass));
    let body = body.map_err(|e| {
        let field = match &e {
            InputError::OutOfRange { name, .. } | InputError::NotFinite { name, .. } => {
                name.clone()
            }
            InputError::BadValue { .. }
            | InputError::Malformed { .. }
            | InputError::Unreadable { .. } => "table".into(),
            _ => "height".into(),
        };
        err(Place::Table("body"), &field, e.into())
    })?;
    let attr_table = fields("attributes", top.remove("attributes"))?;
    let attrs = attributes(path, style.as_deref(), attr_table.table).map_err(at)?;
    let list = match top.remove("action") {
        Some(Value::Array(a)) if !a.is_empty() => a,
        Some(Value::Array(_)) | None => {
            let what = "at least one [[action]] table".to_string();
            return Err(err(Place::Top, "action", Problem::Missing { what }));
        }
        Some(other) => {
            return Err(err(
                Place::Top,
                "action",
                wrong("an array of tables", &other),
            ));
        }
    };
    let ctx = Context {
        body: &body,
        attrs: &attrs,
        nrs,
    };
    let mut actions = Vec::with_capacity(list.len());
    for (index, value) in list.into_iter().enumerate() {
        let place = Place::Action {
            index,
            name: "?".into(),
        };
        let Value::Table(t) = value else {
            return Err(err(place, "action", wrong("a table", &value)));
        };
        actions.push(ctx.action(index, t).map_err(at)?);
    }
    Ok(Scenario {
        body,
        attrs,
        nrs,
        actions,
    })
}

/// The attributes: the defaults, the style's, then the `[attributes]` table's, as
/// `klaw walk --style … --attributes …` resolves them.
fn attributes(path: &Path, style: Option<&str>, table: Table) -> Result<Attributes, FieldError> {
    let place = Place::Table("attributes");
    let fail = |field: &str, e: InputError| FieldError {
        place: if field == "style" {
            Place::Table("body")
        } else {
            place.clone()
        },
        field: field.to_string(),
        problem: e.into(),
    };
    let overrides: BTreeMap<String, f64> =
        overrides_of_table(table, "scenario [attributes]", path).map_err(|e| fail("", e))?;
    let source = format!("{} [attributes]", path.display());
    crate::input::attributes_with(style, overrides, &source).map_err(|e| {
        let field = match &e {
            InputError::OutOfRange { name, .. }
            | InputError::NotFinite { name, .. }
            | InputError::UnknownAttribute { name, .. } => name.clone(),
            InputError::UnknownStyle { .. } | InputError::BadValue { .. } => "style".into(),
            _ => String::new(),
        };
        fail(&field, e)
    })
}

/// What the actions are checked against.
struct Context<'a> {
    body: &'a Body,
    attrs: &'a Attributes,
    nrs: NrsParameters,
}

const SIDES: &[(&str, Side)] = &[("left", Side::Left), ("right", Side::Right)];
const KINDS: &[(&str, TurnKind)] = &[
    ("dynamic", TurnKind::Dynamic),
    ("stationary", TurnKind::Stationary),
];

impl Context<'_> {
    /// The action of the table `t`, the `index`th of the file (from 0).
    fn action(&self, index: usize, mut t: Table) -> Result<Action, FieldError> {
        let kind = match t.remove("type") {
            Some(Value::String(s)) => s,
            Some(other) => {
                let place = Place::Action {
                    index,
                    name: "?".into(),
                };
                let problem = wrong("a string", &other);
                return Err(FieldError {
                    place,
                    field: "type".into(),
                    problem,
                });
            }
            None => {
                let place = Place::Action {
                    index,
                    name: "?".into(),
                };
                let what = "type = \"stand\" | \"walk\" | \"step\" | \"turn\" | \"pause\"".into();
                return Err(FieldError {
                    place,
                    field: "type".into(),
                    problem: Problem::Missing { what },
                });
            }
        };
        let mut f = Fields::new(
            Place::Action {
                index,
                name: kind.clone(),
            },
            t,
        );
        let action = match kind.as_str() {
            "stand" => self.stand(index, &mut f)?,
            "pause" => Action::Pause {
                seconds: f
                    .ranged("seconds", 0.0, MAX_SECONDS, "s")?
                    .ok_or_else(|| f.missing("seconds", "seconds = the pause's duration (s)"))?,
            },
            "walk" => self.walk(&mut f)?,
            "step" => self.step(&mut f)?,
            "turn" => self.turn(&mut f)?,
            _ => {
                let problem = Problem::UnknownAction { found: kind };
                return Err(f.fail("type", problem));
            }
        };
        f.finish(known_keys(action.name()))?;
        Ok(action)
    }

    fn stand(&self, index: usize, f: &mut Fields) -> Result<Action, FieldError> {
        let seconds = f.ranged("seconds", 0.0, MAX_SECONDS, "s")?.unwrap_or(0.0);
        let at = f.point("at")?;
        let facing = f.ranged("facing", -360.0, 360.0, "deg")?;
        if index > 0 {
            for (key, given) in [("at", at.is_some()), ("facing", facing.is_some())] {
                if given {
                    let reason = "only the first action places the figure";
                    return Err(f.fail(key, InputError::bad_value(key, reason).into()));
                }
            }
        }
        Ok(Action::Stand {
            seconds,
            at,
            facing: facing.map(f64::to_radians),
        })
    }

    /// A walk: `steps` copies of one gait (`velocity`, `step_length`, `step_frequency`, or the
    /// style's preferred speed) or one `gaits` entry per step; each completed and checked.
    fn walk(&self, f: &mut Fields) -> Result<Action, FieldError> {
        let steps = f.number("steps")?;
        let flat = GaitRequest {
            velocity: f.number("velocity")?,
            step_length: f.number("step_length")?,
            step_frequency: f.number("step_frequency")?,
        };
        let list = f.table.remove("gaits");
        let requests = match (list, steps) {
            (Some(_), Some(_)) => {
                return Err(f.fail(
                    "gaits",
                    Problem::Conflict {
                        other: "steps".into(),
                    },
                ));
            }
            (Some(_), None) if flat != GaitRequest::default() => {
                let other = "velocity / step_length / step_frequency".into();
                return Err(f.fail("gaits", Problem::Conflict { other }));
            }
            (Some(v), None) => self.gait_list(f, v)?,
            (None, None) => {
                return Err(f.missing(
                    "steps",
                    "steps = N (with a gait or the style's speed) or gaits = [...]",
                ));
            }
            (None, Some(n)) => {
                let max = MAX_WALK_STEPS as f64;
                InputError::check_range("steps", n, 1.0, max, "")
                    .map_err(|e| f.fail("steps", e.into()))?;
                if n.fract() != 0.0 {
                    let e = InputError::NotWhole {
                        name: "steps",
                        value: n,
                    };
                    return Err(f.fail("steps", e.into()));
                }
                let request = if flat == GaitRequest::default() {
                    GaitRequest {
                        velocity: Some(self.attrs.preferred_velocity),
                        ..flat
                    }
                } else {
                    flat
                };
                self.check_gait(f, "velocity", &request)?;
                vec![request; n as usize]
            }
        };
        Ok(Action::Walk { gaits: requests })
    }

    /// The `gaits` array: one table of velocity / step_length / step_frequency per step.
    fn gait_list(&self, f: &Fields, v: Value) -> Result<Vec<GaitRequest>, FieldError> {
        let Value::Array(a) = v else {
            return Err(f.fail("gaits", wrong("an array of gait tables", &v)));
        };
        if a.is_empty() || a.len() as i64 > MAX_WALK_STEPS {
            let e = InputError::check_range(
                "gaits (steps)",
                a.len() as f64,
                1.0,
                MAX_WALK_STEPS as f64,
                "",
            );
            return Err(f.fail(
                "gaits",
                e.err().map_or(
                    Problem::Missing {
                        what: "a gait".into(),
                    },
                    Problem::from,
                ),
            ));
        }
        let mut out = Vec::with_capacity(a.len());
        for (i, g) in a.into_iter().enumerate() {
            let field = format!("gaits[{i}]");
            let Value::Table(t) = g else {
                return Err(f.fail(
                    &field,
                    wrong("a table {velocity, step_length, step_frequency}", &g),
                ));
            };
            let mut gf = Fields::new(f.place.clone(), t);
            let number = |gf: &mut Fields, k: &str| {
                gf.number(k).map_err(|e| FieldError {
                    field: format!("{field}.{k}"),
                    ..e
                })
            };
            let request = GaitRequest {
                velocity: number(&mut gf, "velocity")?,
                step_length: number(&mut gf, "step_length")?,
                step_frequency: number(&mut gf, "step_frequency")?,
            };
            gf.finish("velocity, step_length, step_frequency")
                .map_err(|e| FieldError {
                    field: format!("{field}.{}", e.field),
                    ..e
                })?;
            self.check_gait(f, &field, &request)?;
            out.push(request);
        }
        Ok(out)
    }

    /// Complete `request` as `klaw walk` does, to refuse a bad gait before anything runs.
    fn check_gait(&self, f: &Fields, field: &str, request: &GaitRequest) -> Result<(), FieldError> {
        request
            .complete(self.body, self.attrs)
            .map(|_| ())
            .map_err(|e| {
                let field = match &e {
                    InputError::OutOfRange { name, .. } | InputError::NotFinite { name, .. }
                        if !field.starts_with("gaits") =>
                    {
                        name.clone()
                    }
                    _ => field.to_string(),
                };
                f.fail(&field, e.into())
            })
    }

    /// A step: `side`, a relative (`forward`, `left`, `turn`) or world (`position`,
    /// `direction`) goal, and the optional attribute parameters.
    fn step(&self, f: &mut Fields) -> Result<Action, FieldError> {
        let side = f
            .choice("side", SIDES)?
            .ok_or_else(|| f.missing("side", "side = \"left\" | \"right\""))?;
        let forward = f.ranged("forward", -MAX_RELATIVE, MAX_RELATIVE, "m")?;
        let left = f.ranged("left", -MAX_RELATIVE, MAX_RELATIVE, "m")?;
        let turn = f.ranged("turn", -180.0, 180.0, "deg")?;
        let position = f.point("position")?;
        let direction = f.ranged("direction", -360.0, 360.0, "deg")?;
        let relative = forward.is_some() || left.is_some() || turn.is_some();
        let world = position.is_some() || direction.is_some();
        let goal = match (relative, world) {
            (true, true) => {
                let key = if position.is_some() {
                    "position"
                } else {
                    "direction"
                };
                let other = ["forward", "left", "turn"]
                    .into_iter()
                    .zip([forward, left, turn])
                    .find(|(_, v)| v.is_some())
                    .map_or("forward", |(k, _)| k);
                return Err(f.fail(
                    key,
                    Problem::Conflict {
                        other: other.into(),
                    },
                ));
            }
            (false, false) => {
                let what = "a goal: forward / left (m) and turn (deg), or position = [x, z] (m) and direction (deg)";
                return Err(f.missing("forward", what));
            }
            (true, false) => Goal::Relative {
                forward: forward.unwrap_or(0.0),
                left: left.unwrap_or(0.0),
                turn: turn.unwrap_or(0.0).to_radians(),
            },
            (false, true) => Goal::World {
                position: position
                    .ok_or_else(|| f.missing("position", "position = [x, z] (m) with direction"))?,
                direction: direction
                    .ok_or_else(|| f.missing("direction", "direction (deg) with position"))?
                    .to_radians(),
            },
        };
        let p = &self.nrs;
        let duration = f.ranged("duration", p.duration_min, p.duration_max, "s")?;
        let swhf = f.ranged("swing_height_factor", 0.0, p.swing_height_factor_max, "")?;
        let gaze = f.ranged("gaze", -180.0, 180.0, "deg")?;
        let foot_angles = match f.table.remove("foot_angles") {
            None => None,
            Some(Value::Table(t)) => Some(foot_angles(&f.place, t)?),
            Some(other) => return Err(f.fail("foot_angles", wrong("a table", &other))),
        };
        Ok(Action::Step {
            side,
            goal,
            duration,
            swing_height_factor: swhf,
            gaze: gaze.map(f64::to_radians),
            foot_angles,
        })
    }

    /// A turn: `angle` (deg), `side`, `kind`, optional `step_duration` (s).
    fn turn(&self, f: &mut Fields) -> Result<Action, FieldError> {
        let angle = f
            .ranged("angle", 0.0, MAX_TURN_DEG, "deg")?
            .ok_or_else(|| f.missing("angle", "angle (deg, > 0)"))?;
        if angle == 0.0 {
            let e = InputError::bad_value("angle", "a turn needs an angle > 0 deg");
            return Err(f.fail("angle", e.into()));
        }
        let side = f
            .choice("side", SIDES)?
            .ok_or_else(|| f.missing("side", "side = \"left\" | \"right\""))?;
        let kind = f
            .choice("kind", KINDS)?
            .ok_or_else(|| f.missing("kind", "kind = \"dynamic\" | \"stationary\""))?;
        let p = &self.nrs;
        let step_duration = f.ranged("step_duration", p.duration_min, p.duration_max, "s")?;
        Ok(Action::Turn {
            angle: angle.to_radians(),
            side,
            kind,
            step_duration,
        })
    }
}

/// The `foot_angles` table (deg): all three of toe_off_swing, strike_swing, strike_stance.
fn foot_angles(place: &Place, t: Table) -> Result<FootAngles, FieldError> {
    let mut g = Fields::new(place.clone(), t);
    let m = MAX_FOOT_ANGLE_DEG;
    let mut take = |k: &str| -> Result<f64, FieldError> {
        let v = g.ranged(k, -m, m, "deg").map_err(|e| FieldError {
            field: format!("foot_angles.{k}"),
            ..e
        })?;
        let what = "all three of toe_off_swing, strike_swing, strike_stance (deg)";
        v.map(f64::to_radians).ok_or_else(|| FieldError {
            place: place.clone(),
            field: format!("foot_angles.{k}"),
            problem: Problem::Missing { what: what.into() },
        })
    };
    let angles = FootAngles {
        toe_off_swing: take("toe_off_swing")?,
        strike_swing: take("strike_swing")?,
        strike_stance: take("strike_stance")?,
    };
    g.finish("toe_off_swing, strike_swing, strike_stance")
        .map_err(|e| FieldError {
            field: format!("foot_angles.{}", e.field),
            ..e
        })?;
    Ok(angles)
}

/// The keys of each action type, for the message of an unknown key.
fn known_keys(name: &str) -> &'static str {
    match name {
        "stand" => "type, seconds, at, facing",
        "walk" => "type, steps, velocity, step_length, step_frequency, gaits",
        "step" => {
            "type, side, forward, left, turn, position, direction, duration, \
             swing_height_factor, gaze, foot_angles"
        }
        "turn" => "type, angle, side, kind, step_duration",
        _ => "type, seconds",
    }
}
