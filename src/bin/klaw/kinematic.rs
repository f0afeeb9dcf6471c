//! `klaw walk --mode kinematic`: a prototype generalized to the body and the gait (Ko & Badler
//! 1992, docs/generalize.md) and walked, written as `klaw walk` writes a simulated walk.
use std::io::Write;
use std::path::Path;

use klaw::figure::clinical::clinical;
use klaw::generalize::{GeneralizeParameters, KinematicWalk, WalkData, default_prototype, text};
use klaw::model::{InputError, Shown};
use klaw::{Result, export, plot};

use crate::walk::{WalkArgs, check_outputs, options, print_files};
use crate::{MAX_FPS, MIN_FPS, count};

/// The generalization's constants: the model file's (`--generalize-model`), or the bundled
/// `models/generalize.toml`.
pub(crate) fn generalize_parameters(path: Option<&Path>) -> Result<GeneralizeParameters> {
    Ok(match path {
        Some(p) => GeneralizeParameters::read(p)?,
        None => GeneralizeParameters::default(),
    })
}

/// Warn when a model file's α slopes differ from the prototype's: the prototype carries its own
/// (`character.alpha1…4`, written when it was made), and those generalize it; a file's α enter a
/// prototype made with `klaw prototype --generalize-model`.
pub(crate) fn warn_alphas(
    model: Option<&Path>,
    params: &GeneralizeParameters,
    prototype: &WalkData,
) {
    let Some(path) = model else { return };
    let (file, own) = (params.alphas(), prototype.character.alpha);
    if file.iter().zip(own).any(|(a, b)| (a - b).abs() > 1e-9) {
        let deg = |a: [f64; 4]| a.map(|x| format!("{:.2}", x.to_degrees())).join(", ");
        eprintln!(
            "warning: {}'s α slopes ({} °/leg length) are not the prototype's ({}), which \
             generalize it: a file's α enter a prototype made with klaw prototype \
             --generalize-model",
            path.display(),
            deg(file),
            deg(own)
        );
    }
}

/// Walk data from a file, JSON or CSV by its extension.
pub(crate) fn read_walk_data(path: &Path) -> Result<WalkData> {
    let text = std::fs::read_to_string(path).map_err(|source| klaw::Error::Io {
        action: "reading",
        path: path.to_path_buf(),
        source,
    })?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let read = match ext.as_deref() {
        Some("json") => text::from_json(&text),
        Some("csv") => text::from_csv(&text),
        _ => {
            let reason = format!("{}: walk data are .json or .csv", path.display());
            return Err(InputError::bad_value("prototype", reason).into());
        }
    };
    read.map_err(|e| InputError::malformed("walk data", path, e.to_string()).into())
}

/// `klaw walk --mode kinematic`: the prototype generalized to the walk's body and gait, written out.
pub(crate) fn run(args: &WalkArgs) -> Result<()> {
    if args.gait.engine_model.is_some() {
        let reason = "applies to --mode dynamic only (the kinematic mode simulates nothing)";
        return Err(InputError::bad_value("engine-model", reason).into());
    }
    let fps = InputError::check_range("fps", args.fps, MIN_FPS, MAX_FPS, "frames/s")?;
    let params = generalize_parameters(args.generalize_model.as_deref())?;
    if args.report.is_some() {
        let reason = "the report records the engine's shooting solves; the kinematic mode has \
                      none (use --mode dynamic)";
        return Err(InputError::bad_value("report", reason).into());
    }
    let body = args.gait.body()?;
    let attrs = args.gait.attributes()?;
    let gaits = args.gait.gaits(&body, &attrs)?;
    if gaits.windows(2).any(|w| w[0] != w[1]) {
        let reason = "the kinematic mode walks one gait, the same every step; a schedule of \
                      different gaits needs --mode dynamic";
        return Err(InputError::bad_value("schedule", reason).into());
    }
    let plot = check_outputs(args, gaits.len())?;
    let format = export::Format::from_path(&args.out)?;
    let options = options(args, format)?;
    let prototype = match &args.prototype {
        Some(p) => read_walk_data(p)?,
        None => default_prototype(),
    };
    warn_alphas(args.generalize_model.as_deref(), &params, &prototype);
    let walk = KinematicWalk::new(&prototype, body, attrs, gaits[0], gaits.len(), &params)?;
    let (mut clinical_rows, mut state) = (Vec::new(), Vec::new());
    let keep_state = |step: usize| match (&args.state_out, &plot) {
        (Some(_), _) => true,
        (None, Some(_)) => step < plot::walk::FIGURE_STEPS,
        (None, None) => false,
    };
    let frames = walk.frames(fps).map(|frame| -> Result<_> {
        let lm = frame?;
        if args.cycle_out.is_some() {
            clinical_rows.push(clinical(&lm, &body)?);
        }
        if keep_state(lm.step) {
            state.push(walk.state_frame(&lm));
        }
        Ok(lm)
    });
    export::try_write(&args.out, format, &body, fps, frames, &options)?;
    if let Some(path) = &args.state_out {
        export::write_frames_csv(path, &state)?;
    }
    if let Some(path) = &args.events {
        export::write_events_csv(path, &walk.events())?;
    }
    if let Some(path) = &args.cycle_out {
        let curves =
            klaw::analysis::cycle::cycle_average(&clinical_rows, &walk.right_heel_strikes(), 1)?;
        export::write_cycle_csv(path, &curves)?;
    }
    if let Some(path) = &plot {
        plot::walk::walk_figure(&state, walk.steps, path)?;
    }
    print_summary(args, &walk, &prototype, fps, plot.as_deref());
    Ok(())
}

fn print_summary(
    args: &WalkArgs,
    walk: &KinematicWalk,
    prototype: &WalkData,
    fps: f64,
    plot: Option<&Path>,
) {
    let frames = klaw::generalize::walk::frame_count(walk.duration(), fps);
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "walked {} kinematically: {:.3} s, {} at {} frames/s",
        count(walk.steps, "step"),
        walk.duration(),
        count(frames, "frame"),
        Shown(fps)
    );
    let _ = writeln!(
        out,
        "prototype: {}; step length {:.4} m; the hip comes down {:.1} mm at most to let the legs reach",
        prototype.source,
        walk.step.data.step_length,
        1e3 * walk.hip_drop
    );
    print_files(&mut out, args, "state rows", plot);
}
