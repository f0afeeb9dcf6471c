//! The engine's model constants, read from `models/engine.toml` (each value's source is there):
//! the servos, what the walker's shooting solves converge to and may spend, how its
//! measurements sample a step, what a step's invariants allow, and the fallbacks' limits
//! (spec §4, §5; the decisions behind each value: docs/engine.md, "Decisions" and "Engine").
use std::path::Path;

use serde::Deserialize;

use crate::control::stance::ReferenceShape;
use crate::model::InputError;
use crate::model::servos::Servos;
use crate::numerics::ode::Tolerance;

/// The bundled constants.
pub const BUILTIN_TABLE: &str = include_str!("../../models/engine.toml");

/// The model constants of a walker: [`crate::engine::walker::Walker`] runs with the `Default`,
/// the bundled `models/engine.toml`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EngineParameters {
    /// The servos' natural frequencies and damping ratios.
    pub servos: Servos,
    /// The stance hip reference's shape constants in terminal stance.
    pub stance_reference: ReferenceShape,
    /// The fraction of the step after which the stance leg torque τ1 is switched off.
    pub torque_off: f64,
    /// How far the bounce's mid-stance peak stays below the straight stance leg's reach, as a
    /// fraction of the bounce.
    pub reach_margin: f64,
    /// Shooting tolerance of the stance's and swing3's end conditions (rad or m): 100× inside
    /// the 1e-6 the walk promises, and small enough for the heel-contact check, which
    /// differences the heel height over 1e-6 s.
    pub solve_tolerance: f64,
    /// \[ours\] Shooting tolerance of swing1's and swing2's end conditions (rad): 10× inside the
    /// 1e-6 the walk promises, since they are waypoints: the next subphase starts from the state
    /// they reach, swing3 meets the heel strike's conditions at `solve_tolerance` whatever it
    /// is, and swing2's error is the knee's jump where it locks.
    pub waypoint_tolerance: f64,
    /// Trial integrations allowed per solve (count): about twice the most any solve of the
    /// grid of `tests/walk.rs` needs (13).
    pub max_iterations: usize,
    /// Integrator tolerance of every shooting trial (relative and absolute, 1) and the
    /// integrator's limits (event location, steps, frozen mesh): the ODE integrator's own,
    /// [`Tolerance::default`], its step tolerance set by the accuracy of the end conditions.
    pub ode: Tolerance,
    /// \[ours\] How much looser swing2 integrates than the other phases (factor on
    /// `ode.step`): [`crate::control::swing`]'s default, 100, since swing2's stiff servos damp
    /// the local errors away.
    pub swing2_tolerance_scale: f64,
    /// Largest grid step of the stance hip's acceleration table the swing reads (s): 3 ms, its quintic
    /// interpolation 1.3e-6 m/s² from the stance dynamics (docs/engine.md, "Engine").
    pub hip_path_step: f64,
    /// The least mid-swing toe clearance a step may have (m): the feet's placement precision.
    pub toe_clearance_min: f64,
    /// How far the hip may drop below its heel-strike height and the swing foot go under the
    /// ground (m): the 1e-6 the walk promises.
    pub invariant_slack: f64,
    /// Uniform samples of the hip height and of the swing knee per interval in the step's
    /// measurements (count): each sampled local extreme is then refined by Brent's search.
    pub coarse_samples: usize,
    /// Uniform samples of the swing foot's height (count): narrow dips (the toe under the
    /// ground for 1 % of the swing while the heel rests on its floor) need them denser.
    pub foot_samples: usize,
    /// Least Gauss–Legendre panels per integration segment in the work of the step's report
    /// (count): one per integrator step (≈ 140 in a stance, ≈ 200 in a swing) is within 0.5 %
    /// of 8000 per segment (`tests/work.rs`).
    pub work_panels: usize,
    /// How many times a step that less pelvic list can mend is tried again, each time with the
    /// list lowered by 1 / `list_retries` of the attribute's, the last time with none (count;
    /// 10: 90, 80, …, 0 %; 0: never). Halving instead (50 %, 25 %, …) gave up 2.7° of a 5.4°
    /// list where 4.3° walks; fifths gave up 20 % of a 4.87° list where 10 % less walks
    /// (1.8 m/s, H 1.8 m; docs/realism.md).
    pub list_retries: usize,
    /// How many times a step whose flat foot falls out of the straight leg's reach is tried
    /// again before its list is lowered, each time with the bounce's reach margin
    /// (`reach_margin`, a fraction of the bounce) larger by `reach_margin_step` (count; 0:
    /// never): where the reach cuts the bounce, less list only lets the bounce rise again.
    pub reach_retries: usize,
    /// The reach margin's growth per retry (fraction of the bounce).
    pub reach_margin_step: f64,
    /// How many times a step whose rolling hind foot cannot reach the hip in double support is
    /// tried again, each time with the toe-off knee κ_TO lowered by `toe_off_knee_step`, never
    /// under the attribute's least value (count; 0: never): a straighter trailing knee reaches
    /// further, as long steps at a slow cadence need.
    pub toe_off_retries: usize,
    /// The toe-off knee's fall per retry (rad).
    pub toe_off_knee_step: f64,
}

impl Default for EngineParameters {
    /// The bundled constants, `models/engine.toml` (parsed once per process: compiled-in text,
    /// the same every time; other constants come through [`Self::parse`]).
    fn default() -> Self {
        static BUNDLED: std::sync::OnceLock<EngineParameters> = std::sync::OnceLock::new();
        *BUNDLED.get_or_init(|| {
            Self::parse(BUILTIN_TABLE, Path::new("models/engine.toml"))
                .expect("the bundled engine constants parse (tested)")
        })
    }
}

/// `models/engine.toml`'s layout.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    servos: Servos,
    stance: Stance,
    solve: Solve,
    measure: Measure,
    fallbacks: Fallbacks,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Stance {
    torque_off: f64,
    reach_margin: f64,
    reference: ReferenceShape,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Solve {
    tolerance: f64,
    waypoint_tolerance: f64,
    max_iterations: usize,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Measure {
    toe_clearance_min: f64,
    invariant_slack: f64,
    coarse_samples: usize,
    foot_samples: usize,
    work_panels: usize,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Fallbacks {
    list_retries: usize,
    reach_retries: usize,
    reach_margin_step: f64,
    toe_off_retries: usize,
    toe_off_knee_step: f64,
}

impl EngineParameters {
    /// The constants of the model file `path` (a user's copy of `models/engine.toml`, docs/cli.md
    /// "Model files"), checked as [`Self::parse`] checks them.
    pub fn read(path: &Path) -> Result<Self, InputError> {
        Self::parse(
            &crate::model::file::read_text("engine constants", path)?,
            path,
        )
    }

    /// The constants of a table in `models/engine.toml`'s layout (`path` names it in errors):
    /// every key present, none unknown, each finite and in its range (frequencies and damping
    /// ratios positive, tolerances in (0, 1e-3], counts at least 1 where a step needs one).
    pub fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        let what = "engine constants";
        let t: Table = crate::model::file::parse_toml(text)
            .map_err(|reason| InputError::malformed(what, path, reason))?;
        let bad =
            |name: &str, e: InputError| InputError::malformed(what, path, format!("{name}: {e}"));
        let (s, m, f) = (&t.solve, &t.measure, &t.fallbacks);
        let mut checks: Vec<(&str, f64, f64, f64)> = t
            .servos
            .named()
            .iter()
            .map(|&(name, v)| (name, v, 1e-3, 1e3))
            .collect();
        let r = &t.stance.reference;
        checks.extend([
            ("torque_off", t.stance.torque_off, 0.0, 1.0),
            ("reach_margin", t.stance.reach_margin, 0.0, 1.0),
            ("end_margin", r.end_margin, 0.0, 0.1),
            ("end_rise", r.end_rise, 0.0, 0.1),
            // the heel-off pitch stays monotone while D ≤ 10 (ReferenceShape::pitch_bulge)
            ("pitch_bulge", r.pitch_bulge, 0.0, 10.0),
            ("past_end", r.past_end, 1.0, 1.5),
        ]);
        checks.extend([
            ("tolerance", s.tolerance, 1e-15, 1e-3),
            ("waypoint_tolerance", s.waypoint_tolerance, 1e-15, 1e-3),
            ("max_iterations", s.max_iterations as f64, 1.0, 1e4),
            ("toe_clearance_min", m.toe_clearance_min, 0.0, 0.1),
            ("invariant_slack", m.invariant_slack, 0.0, 0.01),
            ("coarse_samples", m.coarse_samples as f64, 2.0, 1e6),
            ("foot_samples", m.foot_samples as f64, 2.0, 1e6),
            ("work_panels", m.work_panels as f64, 1.0, 1e6),
            ("list_retries", f.list_retries as f64, 0.0, 1e3),
            ("reach_retries", f.reach_retries as f64, 0.0, 1e3),
            ("reach_margin_step", f.reach_margin_step, 0.0, 1.0),
            ("toe_off_retries", f.toe_off_retries as f64, 0.0, 1e3),
            ("toe_off_knee_step", f.toe_off_knee_step, 0.0, 90.0),
        ]);
        for (name, v, lo, hi) in checks {
            InputError::check_range(name, v, lo, hi, "").map_err(|e| bad(name, e))?;
        }
        Ok(EngineParameters {
            servos: t.servos,
            stance_reference: t.stance.reference,
            torque_off: t.stance.torque_off,
            reach_margin: t.stance.reach_margin,
            solve_tolerance: s.tolerance,
            waypoint_tolerance: s.waypoint_tolerance,
            max_iterations: s.max_iterations,
            ode: Tolerance::default(),
            swing2_tolerance_scale: crate::control::swing::SWING2_TOLERANCE_SCALE,
            hip_path_step: crate::control::stance::HIP_PATH_STEP,
            toe_clearance_min: m.toe_clearance_min,
            invariant_slack: m.invariant_slack,
            coarse_samples: m.coarse_samples,
            foot_samples: m.foot_samples,
            work_panels: m.work_panels,
            list_retries: f.list_retries,
            reach_retries: f.reach_retries,
            reach_margin_step: f.reach_margin_step,
            toe_off_retries: f.toe_off_retries,
            toe_off_knee_step: f.toe_off_knee_step.to_radians(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bundled table parses to the values its file states (an independent reading of the
    /// text: the leg servo's 5 Hz, the toe-off knee's 5° in radians); a value out of its range,
    /// a missing key and an unknown one are errors naming them.
    #[test]
    fn the_bundled_constants_parse_and_bad_ones_are_named() {
        let p = EngineParameters::default();
        assert_eq!(p.servos.leg_frequency, 5.0);
        assert_eq!(p.max_iterations, 25);
        assert!((p.toe_off_knee_step - 5f64.to_radians()).abs() < 1e-15);
        let path = Path::new("e.toml");
        let e = EngineParameters::parse(
            &BUILTIN_TABLE.replace("damping_ratio = 0.7", "damping_ratio = -0.7"),
            path,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("damping_ratio") && e.contains("e.toml"), "{e}");
        let e = EngineParameters::parse(&BUILTIN_TABLE.replace("foot_samples = 100\n", ""), path)
            .unwrap_err()
            .to_string();
        assert!(e.contains("foot_samples"), "{e}");
        let e = EngineParameters::parse(&format!("{BUILTIN_TABLE}\n[extra]\nx = 1\n"), path)
            .unwrap_err()
            .to_string();
        assert!(e.contains("extra"), "{e}");
    }
}
