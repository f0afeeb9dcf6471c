//! Scenario files (src/scenario/file.rs): every error kind names the action (from 0) and the
//! field; the examples of `examples/scenarios/` parse; degrees in the file are radians in the
//! scenario.
use std::f64::consts::PI;
use std::path::Path;

use klaw::GaitRequest;
use klaw::model::InputError;
use klaw::nrs::specs::{Side, TurnKind};
use klaw::scenario::file_error::{Place, Problem};
use klaw::scenario::{Action, Goal, ScenarioFileError, parse_scenario};

fn parse(text: &str) -> Result<klaw::scenario::Scenario, ScenarioFileError> {
    parse_scenario(text, Path::new("t.toml"))
}

fn error(text: &str) -> ScenarioFileError {
    parse(text).expect_err("the file is refused")
}

fn at_action(e: &ScenarioFileError, index: usize, field: &str) {
    assert!(
        matches!(&e.place, Place::Action { index: i, .. } if *i == index),
        "{e}"
    );
    assert_eq!(e.field, field, "{e}");
    let text = e.to_string();
    assert!(
        text.contains(&format!("action {index} (")) && text.contains(field),
        "{text}"
    );
}

#[test]
fn a_full_scenario_parses_with_degrees_as_radians() {
    let s = parse(
        r#"
        [body]
        height = 1.7
        mass = 70
        style = "brisk"
        [attributes]
        bounciness = 0.7
        [[action]]
        type = "stand"
        seconds = 1
        at = [1, -2]
        facing = 90
        [[action]]
        type = "walk"
        steps = 3
        step_length = 0.6
        [[action]]
        type = "walk"
        gaits = [{velocity = 1.2}, {step_length = 0.7, step_frequency = 100}]
        [[action]]
        type = "step"
        side = "left"
        forward = -0.3
        turn = 45
        duration = 0.8
        swing_height_factor = 2
        gaze = -30
        foot_angles = {toe_off_swing = 10, strike_swing = -5, strike_stance = 0}
        [[action]]
        type = "step"
        side = "right"
        position = [2, 0.5]
        direction = 180
        [[action]]
        type = "turn"
        angle = 270
        side = "right"
        kind = "stationary"
        step_duration = 0.5
        [[action]]
        type = "pause"
        seconds = 2.5
        "#,
    )
    .unwrap();
    assert_eq!(s.body.height, 1.7);
    assert_eq!(s.body.mass, 70.0);
    assert_eq!(s.attrs.bounciness, 0.7);
    assert_eq!(s.actions.len(), 7);
    assert_eq!(
        s.actions[0],
        Action::Stand {
            seconds: 1.0,
            at: Some([1.0, -2.0]),
            facing: Some(PI / 2.0)
        }
    );
    let req = |v, sl, sf| GaitRequest {
        velocity: v,
        step_length: sl,
        step_frequency: sf,
    };
    assert_eq!(
        s.actions[1],
        Action::Walk {
            gaits: vec![req(None, Some(0.6), None); 3]
        }
    );
    assert_eq!(
        s.actions[2],
        Action::Walk {
            gaits: vec![
                req(Some(1.2), None, None),
                req(None, Some(0.7), Some(100.0))
            ]
        }
    );
    let Action::Step {
        side,
        goal,
        duration,
        swing_height_factor,
        gaze,
        foot_angles,
    } = &s.actions[3]
    else {
        panic!("{:?}", s.actions[3])
    };
    assert_eq!(*side, Side::Left);
    assert_eq!(
        *goal,
        Goal::Relative {
            forward: -0.3,
            left: 0.0,
            turn: PI / 4.0
        }
    );
    assert_eq!((*duration, *swing_height_factor), (Some(0.8), Some(2.0)));
    assert!((gaze.unwrap() + PI / 6.0).abs() < 1e-15);
    let fa = foot_angles.unwrap();
    assert!((fa.toe_off_swing - 10f64.to_radians()).abs() < 1e-15);
    assert!((fa.strike_swing + 5f64.to_radians()).abs() < 1e-15);
    assert_eq!(fa.strike_stance, 0.0);
    assert!(matches!(
        s.actions[4],
        Action::Step { side: Side::Right, goal: Goal::World { position: [2.0, 0.5], direction }, .. }
            if (direction - PI).abs() < 1e-15
    ));
    assert!(matches!(
        s.actions[5],
        Action::Turn { angle, side: Side::Right, kind: TurnKind::Stationary, step_duration: Some(0.5) }
            if (angle - 1.5 * PI).abs() < 1e-15
    ));
    assert_eq!(s.actions[6], Action::Pause { seconds: 2.5 });
}

#[test]
fn defaults_are_those_of_klaw_walk() {
    let s = parse("[[action]]\ntype = \"walk\"\nsteps = 2\n").unwrap();
    assert_eq!((s.body.height, s.body.mass), (1.8, 80.0));
    // No gait given: the style's preferred speed, 1.4 m/s by default (models/attributes.toml).
    assert_eq!(
        s.actions[0],
        Action::Walk {
            gaits: vec![
                GaitRequest {
                    velocity: Some(1.4),
                    ..Default::default()
                };
                2
            ]
        }
    );
}

#[test]
fn unknown_keys_are_refused_where_they_are() {
    let e = error("[[action]]\ntype = \"pause\"\nseconds = 1\nsecs = 2\n");
    at_action(&e, 0, "secs");
    assert!(matches!(e.problem, Problem::UnknownKey { .. }));
    let e = error("[body]\nheigth = 1.8\n[[action]]\ntype = \"pause\"\nseconds = 1\n");
    assert_eq!(
        (e.place.clone(), e.field.as_str()),
        (Place::Table("body"), "heigth")
    );
    let e = error("action2 = 1\n[[action]]\ntype = \"pause\"\nseconds = 1\n");
    assert_eq!((e.place.clone(), e.field.as_str()), (Place::Top, "action2"));
    let e = error("[attributes]\nbounce = 1\n[[action]]\ntype = \"pause\"\nseconds = 1\n");
    assert!(
        matches!(
            &e.problem,
            Problem::Value(v) if matches!(v.as_ref(), InputError::UnknownAttribute { .. })
        ),
        "{e}"
    );
    assert_eq!(e.field, "bounce");
}

#[test]
fn unknown_and_missing_action_types_are_refused() {
    let e = error("[[action]]\ntype = \"pause\"\nseconds = 1\n[[action]]\ntype = \"jump\"\n");
    at_action(&e, 1, "type");
    assert!(matches!(&e.problem, Problem::UnknownAction { found } if found == "jump"));
    let e = error("[[action]]\nseconds = 1\n");
    at_action(&e, 0, "type");
    assert!(matches!(e.problem, Problem::Missing { .. }));
    let e = error("[body]\nheight = 1.8\n");
    assert_eq!(e.field, "action");
}

#[test]
fn missing_and_conflicting_goals_are_refused() {
    let e = error("[[action]]\ntype = \"step\"\nside = \"left\"\n");
    at_action(&e, 0, "forward");
    assert!(matches!(e.problem, Problem::Missing { .. }));
    let e = error(
        "[[action]]\ntype = \"stand\"\n[[action]]\ntype = \"step\"\nside = \"left\"\nleft = 0.3\nposition = [0, 1]\ndirection = 0\n",
    );
    at_action(&e, 1, "position");
    assert!(
        matches!(&e.problem, Problem::Conflict { other } if other == "left"),
        "{e}"
    );
    let e = error("[[action]]\ntype = \"step\"\nside = \"left\"\nposition = [0, 1]\n");
    at_action(&e, 0, "direction");
    let e = error("[[action]]\ntype = \"step\"\nforward = 0.3\n");
    at_action(&e, 0, "side");
    let e = error("[[action]]\ntype = \"walk\"\nsteps = 2\ngaits = [{velocity = 1}]\n");
    at_action(&e, 0, "gaits");
    assert!(matches!(e.problem, Problem::Conflict { .. }));
    let e = error("[[action]]\ntype = \"walk\"\nvelocity = 1.2\n");
    at_action(&e, 0, "steps");
    let e = error("[[action]]\ntype = \"stand\"\n[[action]]\ntype = \"stand\"\nfacing = 90\n");
    at_action(&e, 1, "facing");
}

#[test]
fn wrong_types_are_refused() {
    let e = error("[[action]]\ntype = \"pause\"\nseconds = \"1\"\n");
    at_action(&e, 0, "seconds");
    assert!(
        matches!(
            e.problem,
            Problem::WrongType {
                expected: "a number",
                found: "string"
            }
        ),
        "{e}"
    );
    let e = error("[[action]]\ntype = \"stand\"\nat = [1]\n");
    at_action(&e, 0, "at");
    assert!(matches!(e.problem, Problem::WrongType { .. }));
    let e = error("[[action]]\ntype = \"turn\"\nangle = 90\nside = \"up\"\nkind = \"dynamic\"\n");
    at_action(&e, 0, "side");
    assert!(e.to_string().contains("left, right"), "{e}");
    let e = error("[[action]]\ntype = \"walk\"\ngaits = [{velocity = true}]\n");
    at_action(&e, 0, "gaits[0].velocity");
    let e = error("[[action]]\ntype = \"walk\"\ngaits = [{speed = 1}]\n");
    at_action(&e, 0, "gaits[0].speed");
    let e = error("action = 3\n");
    assert!(matches!(e.problem, Problem::WrongType { .. }));
    let e = error("[[action]\n");
    assert!(matches!(e.problem, Problem::Toml(_)));
}

#[test]
fn out_of_range_numbers_name_the_range() {
    let cases = [
        ("type = \"pause\"\nseconds = -1\n", "seconds", "[0, 3600] s"),
        (
            "type = \"turn\"\nangle = 0\nside = \"left\"\nkind = \"dynamic\"\n",
            "angle",
            "> 0",
        ),
        (
            "type = \"turn\"\nangle = 90\nside = \"left\"\nkind = \"dynamic\"\nstep_duration = 9\n",
            "step_duration",
            "[0.3, 3] s",
        ),
        (
            "type = \"step\"\nside = \"left\"\nforward = 5\n",
            "forward",
            "[-2, 2] m",
        ),
        (
            "type = \"step\"\nside = \"left\"\nforward = 0.3\nswing_height_factor = 5\n",
            "swing_height_factor",
            "[0, 4]",
        ),
        (
            "type = \"step\"\nside = \"left\"\nforward = 0.3\nfoot_angles = {toe_off_swing = 90, strike_swing = 0, strike_stance = 0}\n",
            "foot_angles.toe_off_swing",
            "[-60, 60] deg",
        ),
        ("type = \"walk\"\nsteps = 0\n", "steps", "[1, 10000]"),
        (
            "type = \"walk\"\nsteps = 3\nvelocity = 3\n",
            "velocity",
            "[0.4, 2.0634] m/s",
        ),
        (
            "type = \"walk\"\ngaits = [{velocity = 1}, {step_frequency = 300}]\n",
            "gaits[1]",
            "[50, 182]",
        ),
    ];
    for (body, field, range) in cases {
        let e = error(&format!("[[action]]\n{body}"));
        at_action(&e, 0, field);
        assert!(e.to_string().contains(range), "{field}: {e}");
    }
    let e = error("[body]\nheight = 3\n[[action]]\ntype = \"pause\"\nseconds = 1\n");
    assert_eq!(
        (e.place.clone(), e.field.as_str()),
        (Place::Table("body"), "height")
    );
    assert!(e.to_string().contains("[1.2, 2.2] m"), "{e}");
    let e = error("[body]\nstyle = \"fast\"\n[[action]]\ntype = \"pause\"\nseconds = 1\n");
    assert_eq!(e.field, "style");
}

#[test]
fn a_file_error_is_bad_input_of_the_crate() {
    let e: klaw::Error = error("[[action]]\ntype = \"jump\"\n").into();
    assert!(matches!(e, klaw::Error::ScenarioFile(_)));
}

#[test]
fn the_examples_parse() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenarios");
    let mut n = 0;
    for name in ["table.toml", "doorway.toml", "spin.toml"] {
        let s = klaw::scenario::read_scenario(&dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert!(!s.actions.is_empty());
        n += 1;
    }
    assert_eq!(n, 3);
    // spin.toml: one 270° turn on the spot between two stands.
    let s = klaw::scenario::read_scenario(&dir.join("spin.toml")).unwrap();
    let turns: f64 = s
        .actions
        .iter()
        .map(|a| match a {
            Action::Turn { angle, .. } => *angle,
            _ => 0.0,
        })
        .sum();
    assert!((turns - 1.5 * PI).abs() < 1e-12);
}
