//! `klaw step` and `klaw turn`: one non-rhythmic step or one turnaround from quiet standing
//! (Ko & Badler 1993), run as a one-action scenario and written like `klaw scenario`'s.
use clap::{Args, ValueEnum};
use klaw::Result;
use klaw::model::InputError;
use klaw::nrs::{Side, TurnKind};
use klaw::scenario::file::{MAX_RELATIVE, MAX_TURN_DEG};
use klaw::scenario::{Action, Goal, Scenario};

use crate::args::BodyArgs;
use crate::scenario::{MotionOutputs, NrsModelArg};

/// A leg or a direction of turn.
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum SideArg {
    Right,
    Left,
}

impl From<SideArg> for Side {
    fn from(s: SideArg) -> Side {
        match s {
            SideArg::Right => Side::Right,
            SideArg::Left => Side::Left,
        }
    }
}

/// "right" or "left".
fn name(side: Side) -> &'static str {
    match side {
        Side::Right => "right",
        Side::Left => "left",
    }
}

/// A turnaround's type.
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum KindArg {
    /// The second foot lands ahead, ready to walk on
    Dynamic,
    /// The second foot lands beside the first
    Stationary,
}

#[derive(Args)]
pub(crate) struct StepArgs {
    /// The stepping leg
    #[arg(long, value_enum, default_value = "right")]
    side: SideArg,
    /// Metres forward of the stepping foot's standing place (negative: backward), range [-2, 2]
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    forward: Option<f64>,
    /// Metres to the left of it (negative: to the right), range [-2, 2]
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    left: Option<f64>,
    /// The change of the foot's heading in degrees (+ left), range [-180, 180]
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    turn: f64,
    /// The step's duration in s [default: that of the walking step of the same length]
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    duration: Option<f64>,
    /// swhf, the swing height factor of eq. 3 [default: models/nrs.toml's, 1]
    #[arg(long, value_name = "F", allow_negative_numbers = true)]
    swing_height_factor: Option<f64>,
    /// Where the gaze ends, degrees from the facing (+ left) [default: where the pelvis faces]
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    gaze: Option<f64>,
    #[command(flatten)]
    body: BodyArgs,
    #[command(flatten)]
    nrs: NrsModelArg,
    #[command(flatten)]
    outputs: MotionOutputs,
}

#[derive(Args)]
pub(crate) struct TurnArgs {
    /// The turn in degrees; above 100° it is split into equal turnarounds, range (0, 1080]
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 90.0,
        allow_negative_numbers = true
    )]
    angle: f64,
    /// The direction of the turn (its leg steps first)
    #[arg(long, value_enum, default_value = "left")]
    side: SideArg,
    /// Dynamic (ready to walk on) or stationary (feet side by side)
    #[arg(long, value_enum, default_value = "dynamic")]
    kind: KindArg,
    /// δ, the first step's duration in s; a turnaround takes 2.5 δ [default: models/nrs.toml's]
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    step_duration: Option<f64>,
    #[command(flatten)]
    body: BodyArgs,
    #[command(flatten)]
    nrs: NrsModelArg,
    #[command(flatten)]
    outputs: MotionOutputs,
}

/// `action` after a moment of standing, for the body of `body` with the NRS constants of `nrs`.
fn scenario(body: &BodyArgs, nrs: &NrsModelArg, action: Action) -> Result<Scenario> {
    let stand = Action::Stand {
        seconds: 0.0,
        at: None,
        facing: None,
    };
    Ok(Scenario {
        body: body.body()?,
        attrs: body.attributes()?,
        nrs: nrs.parameters()?,
        actions: vec![stand, action],
    })
}

pub(crate) fn step(args: &StepArgs) -> Result<()> {
    let out = args.outputs.out_path("step");
    args.outputs.check(&out)?;
    if args.forward.is_none() && args.left.is_none() {
        let reason = "a step needs a goal: --forward and/or --left (m, from the foot's place)";
        return Err(InputError::bad_value("forward", reason).into());
    }
    let range = |name, v: Option<f64>| -> Result<f64> {
        let v = v.unwrap_or(0.0);
        Ok(InputError::check_range(
            name,
            v,
            -MAX_RELATIVE,
            MAX_RELATIVE,
            "m",
        )?)
    };
    let goal = Goal::Relative {
        forward: range("forward", args.forward)?,
        left: range("left", args.left)?,
        turn: InputError::check_range("turn", args.turn, -180.0, 180.0, "°")?.to_radians(),
    };
    let gaze = match args.gaze {
        Some(g) => Some(InputError::check_range("gaze", g, -180.0, 180.0, "°")?.to_radians()),
        None => None,
    };
    let side = Side::from(args.side);
    let action = Action::Step {
        side,
        goal,
        duration: args.duration,
        swing_height_factor: args.swing_height_factor,
        gaze,
        foot_angles: None,
    };
    let what = format!("{} step", name(side));
    args.outputs
        .write(&scenario(&args.body, &args.nrs, action)?, &out, &what)
}

pub(crate) fn turn(args: &TurnArgs) -> Result<()> {
    let out = args.outputs.out_path("turn");
    args.outputs.check(&out)?;
    let angle = InputError::check_range("angle", args.angle, 1e-3, MAX_TURN_DEG, "°")?;
    let side = Side::from(args.side);
    let kind = match args.kind {
        KindArg::Dynamic => TurnKind::Dynamic,
        KindArg::Stationary => TurnKind::Stationary,
    };
    let action = Action::Turn {
        angle: angle.to_radians(),
        side,
        kind,
        step_duration: args.step_duration,
    };
    let what = format!("{angle}° turn to the {}", name(side));
    args.outputs
        .write(&scenario(&args.body, &args.nrs, action)?, &out, &what)
}
