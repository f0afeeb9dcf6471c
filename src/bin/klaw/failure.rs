//! How a failed command is reported: the message after `error: ` and the exit status, 2 for bad
//! input (a value, a file or a path), 1 when the simulation or writing the output fails.
use klaw::Error;
use klaw::analysis::cycle::CycleError;
use klaw::engine::SimulationError;
use klaw::figure::FigureError;
use klaw::ik::IkError;
use klaw::model::InputError;
use klaw::nrs::NrsError;
use klaw::poulaine::PoulaineError;

/// The message of `e`: a bad value names the flag it was given for (`--velocity: …`).
pub(crate) fn message(e: &Error) -> String {
    match e {
        Error::Input(InputError::BadValue { parameter, reason }) => {
            format!("--{parameter}: {reason}")
        }
        e => e.to_string(),
    }
}

/// The exit status of `e`.
pub(crate) fn exit_code(e: &Error) -> u8 {
    const BAD_INPUT: u8 = 2;
    const FAILED: u8 = 1;
    let figure = |f: &FigureError| match f {
        FigureError::Pose { .. } => FAILED,
        FigureError::NotFinite { .. }
        | FigureError::ZeroLength { .. }
        | FigureError::Parallel { .. } => BAD_INPUT,
    };
    let ik = |e: &IkError| match e {
        IkError::Input(_) => BAD_INPUT,
        IkError::NotConverged { .. } | IkError::Minimiser { .. } => FAILED,
    };
    match e {
        Error::Input(_) | Error::Export(_) | Error::ScenarioFile(_) => BAD_INPUT,
        Error::Ik(e) | Error::Poulaine(PoulaineError::Ik(e)) => ik(e),
        Error::Poulaine(PoulaineError::Fit { .. }) => FAILED,
        Error::Poulaine(_) => BAD_INPUT,
        // walk data that cannot be read, or a walk condition it cannot be generalized to
        Error::Generalize(_) => BAD_INPUT,
        Error::Simulation(SimulationError::Plan(_)) => BAD_INPUT,
        Error::Simulation(
            SimulationError::NotConverged { .. }
            | SimulationError::Integration { .. }
            | SimulationError::Invariant { .. },
        ) => FAILED,
        Error::Figure(f) | Error::Cycle(CycleError::Frame(f)) => figure(f),
        Error::Cycle(_) => BAD_INPUT,
        Error::Criteria(_) => BAD_INPUT,
        Error::Io { action, .. } if *action == "writing" => FAILED,
        Error::Io { .. } => BAD_INPUT,
        Error::Draw { .. } => FAILED,
        Error::Scenario(s) => match s.source.as_ref() {
            NrsError::Goal { .. } | NrsError::Input(_) => BAD_INPUT,
            NrsError::Walk(SimulationError::Plan(_)) => BAD_INPUT,
            NrsError::Walking {
                source: SimulationError::Plan(_),
                ..
            } => BAD_INPUT,
            NrsError::Walk(_) | NrsError::Walking { .. } => FAILED,
            NrsError::Figure(f) => figure(f),
        },
    }
}
