//! The step loop (KLAW 1989 Figure 1, top to bottom): plan the step constraints, shoot the stance,
//! complete the hind leg through double support, shoot the swing subphases, strike the heel, and
//! carry the warm starts to the next step.
use nalgebra::{Vector2, Vector3};
use std::f64::consts::PI;

use crate::control::shooting::{self, Memory1, Memory2, Options, SolveReport, Start1, Start2};
use crate::control::stance::{HipPath, StanceRun, StanceSetup, StanceState, TerminalStance};
use crate::control::swing::{self, Subphase, SwingSetup, SwingState, SwingTrial};
use crate::dynamics::impact::{self, ImpactReport};
use crate::dynamics::{StanceModel, SwingModel};
use crate::engine::report::{Achieved, Report, SolveRecord, StateFrame, StepReport, Target};
use crate::engine::work;
use crate::error::{Error, Result};
use crate::kinematics::foot::{Foot, FootPoints};
use crate::kinematics::pelvis::{Determinants, PelvisMotion, Side, fold_height};
use crate::kinematics::stance_leg::{KneeCurve, LegPose, StanceLeg, leg_points, leg_points_sc};
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::numerics::minimise::{least_in, minima};
use crate::numerics::ode::Segment;
use crate::plan::StepConstraints;
use crate::plan::gait::Gait;

/// Shooting tolerance on every end condition (rad or m): 100× inside the 1e-6 the walk promises.
/// The residuals are smooth (frozen mesh, `ode::integrate_on`), so no noise floor sets it; the
/// heel-contact check does: it differences the heel height over 1e-6 s (0.1 m/s × 1e-6 s =
/// 1e-7 m), and at 1e-7 the end-state error of ≈ 1e-7 m brought the grid's highest heel contact
/// velocity to −0.02 m/s and one walk to +1e-8 (docs/engine.md).
pub const SOLVE_TOLERANCE: f64 = 1e-8;

/// [ours] Shooting tolerance of swing1's and swing2's end conditions (rad): 10× inside the 1e-6
/// the walk promises. They are waypoints, not the step's end: the next subphase starts from the
/// state they reach, and swing3 meets the heel strike's conditions at [`SOLVE_TOLERANCE`]
/// whatever it is; swing2's error is the knee's jump where it locks. The last trial of these
/// solves typically took the residual from 1e-7 to 1e-10.
pub const WAYPOINT_TOLERANCE: f64 = 1e-7;

/// The least mid-swing toe clearance a step may have (m): the feet's placement precision.
pub const TOE_CLEARANCE_MIN: f64 = 1e-6;
/// Trial integrations allowed per solve.
pub const MAX_ITERATIONS: usize = 25;
/// Fraction of swing1 at which the swing ankle is back at neutral.
pub const ANKLE_NEUTRAL: f64 = 0.8;

/// A simulated step: its constraints, its dynamic records and its report.
#[derive(Clone, Debug)]
pub struct Step {
    pub index: usize,
    /// Time of the heel strike that starts the step (s).
    pub t_start: f64,
    /// Global x of the stance ankle pivot (m).
    pub x_ankle: f64,
    pub constraints: StepConstraints,
    pub stance_setup: StanceSetup,
    pub stance: StanceRun,
    pub impact: ImpactReport,
    pub solves: Vec<SolveRecord>,
    /// The stance side (step 0 stands on the right leg).
    pub side: Side,
    /// The determinants of gait.
    pub determinants: Determinants,
    /// This step's virtual stance leg (heel strike to the next heel strike; its toe-off falls in
    /// the next step, which continues it as its hind leg).
    pub stance_leg: StanceLeg,
    /// The previous step's stance leg, completing its stance through this double support.
    pub hind_leg: StanceLeg,
    /// The swing subphases, in order.
    pub swing: Vec<(Subphase, Segment<4>)>,
    /// Swing foot: ankle dorsiflexion and toe angle at toe-off (rad).
    pub theta5_off: f64,
    pub theta6_off: f64,
    /// Toe clearance attribute (m).
    pub toe_clearance: f64,
    /// Where in the swing (fraction) the foot is lowest.
    pub lowest_at: f64,
    /// Measurements of the step (targets, achievements, invariants).
    pub report: StepReport,
}

/// Walks step after step, carrying the state and the warm starts.
pub struct Walker {
    pub body: Body,
    pub attrs: Attributes,
    stance_model: StanceModel,
    swing_model: SwingModel,
    options: Options,
    prev: Option<(StepConstraints, StanceState)>,
    determinants: Determinants,
    prev_leg: Option<StanceLeg>,
    stance_memory: Option<Memory2>,
    swing1_memory: Option<Memory2>,
    swing2_memory: Option<Memory1>,
    swing3_memory: Option<Memory2>,
    /// The step sequences of the last step's kept trials (stance; swing1, swing2, swing3):
    /// the next step's first trials follow them ([`ode::Mesh`]) instead of choosing their own.
    stance_mesh: Option<StanceRun>,
    swing_meshes: [Option<Segment<4>>; 3],
    t: f64,
    x_ankle: f64,
    index: usize,
    /// Right-hand-side evaluations of the current step, over all trials.
    evaluations: std::cell::Cell<u64>,
    /// Start the first steps' solves from the fitted guesses ([`STEP0`]).
    startup_guesses: bool,
}

impl Walker {
    /// What the last step's solves leave for the next one's warm starts (stance, swing1,
    /// swing2, swing3): `examples/startup_fit.rs` reads the cold Jacobians from it.
    pub fn memories(
        &self,
    ) -> (
        Option<Memory2>,
        Option<Memory2>,
        Option<Memory1>,
        Option<Memory2>,
    ) {
        (
            self.stance_memory,
            self.swing1_memory,
            self.swing2_memory,
            self.swing3_memory,
        )
    }

    pub fn new(body: Body, attrs: Attributes) -> Self {
        let determinants = Determinants::new(&attrs, body.l0);
        Walker {
            stance_model: StanceModel::new(&body),
            swing_model: SwingModel::new(&body),
            body,
            attrs,
            options: Options {
                tol: SOLVE_TOLERANCE,
                max_iterations: MAX_ITERATIONS,
            },
            prev: None,
            determinants,
            prev_leg: None,
            stance_memory: None,
            swing1_memory: None,
            swing2_memory: None,
            swing3_memory: None,
            stance_mesh: None,
            swing_meshes: [None, None, None],
            t: 0.0,
            x_ankle: 0.0,
            index: 0,
            evaluations: std::cell::Cell::new(0),
            startup_guesses: true,
        }
    }

    /// The same walker with every solve started plainly (body-scaled constants, zero torques,
    /// difference Jacobians) instead of from the fitted start-up guesses: what
    /// `examples/startup_fit.rs` fits, so that its output does not depend on its last output.
    pub fn without_startup_guesses(mut self) -> Self {
        self.startup_guesses = false;
        self
    }

    /// The stance of a step from the previous step's constraints to `c`, with pelvic list `list`.
    fn stance_setup(&self, prev: &StepConstraints, c: &StepConstraints, list: f64) -> StanceSetup {
        let a = &self.attrs;
        let m = self.stance_model;
        let b = &self.body;
        let y_mid = 0.5 * (prev.hip[1] + c.hip[1]) + c.bounce;
        let ww = 2.0 * PI * a.leg_frequency;
        let w2 = 2.0 * PI * a.trunk_frequency;
        let j2 = m.trunk_inertia();
        StanceSetup {
            model: m,
            l1: self.body.l1,
            k_w: m.m2 * ww * ww,
            d_w: 2.0 * a.servo_damping_ratio * m.m2 * ww,
            k_2: j2 * w2 * w2,
            d_2: 2.0 * a.trunk_damping_ratio * j2 * w2,
            theta2_ref: a.trunk_lean,
            t_step: c.timing.t_step,
            theta1_start: prev.theta1,
            theta1_end: c.theta1,
            w_end: c.w,
            y_start: prev.hip[1],
            y_end: c.hip[1],
            bounce: c.bounce,
            terminal: TerminalStance::new(
                y_mid,
                &Determinants {
                    list,
                    ..self.determinants
                },
                (c.theta1, c.w),
                (b.l3, b.l4, b.l9, b.ankle_to_metatarsal_horizontal()),
                a.heel_off_dorsiflexion,
            ),
        }
    }

    /// Simulate the next step with gait `gait`. When the swing fails with the attributes'
    /// pelvic list (the foot under the ground, or no convergence), the step is tried again with
    /// half the list, then none [ours]: the list lowers the swing hip by (l0/2) sin L at mid
    /// step, ≈ 5 mm, which the fastest walks of short bodies (v = 2 m/s at H = 1.5 m) cannot
    /// spare. The list used is in the step's `determinants`.
    pub fn step(&mut self, gait: Gait) -> Result<Step> {
        let saved = (
            self.stance_memory,
            self.swing1_memory,
            self.swing2_memory,
            self.swing3_memory,
        );
        let mut list = self.attrs.pelvic_list;
        self.evaluations.set(0);
        loop {
            match self.step_with_list(gait, list) {
                Err(e) if list > 0.0 && e.is_swing_failure() => {
                    (
                        self.stance_memory,
                        self.swing1_memory,
                        self.swing2_memory,
                        self.swing3_memory,
                    ) = saved;
                    list = if list > 1e-3 { 0.5 * list } else { 0.0 };
                }
                result => return result,
            }
        }
    }

    fn step_with_list(&mut self, gait: Gait, list: f64) -> Result<Step> {
        let c = StepConstraints::new(&self.body, &self.attrs, gait)?;
        let index = self.index;
        // pre-impact posture and rates about the new pivot
        let (prev_c, q, hip_v, trunk_rate) = match &self.prev {
            // first step [ours]: the mirrored heel-strike posture, hip moving horizontally at v
            None => (
                c,
                Vector3::new(c.w, -c.theta1, self.attrs.trunk_lean),
                [gait.velocity, 0.0],
                0.0,
            ),
            Some((pc, y_end)) => {
                let q_old = Vector3::new(y_end[0], y_end[1], y_end[2]);
                let qd_old = Vector3::new(y_end[3], y_end[4], y_end[5]);
                let v = self.stance_model.hip_velocity(&q_old, &qd_old);
                (*pc, Vector3::new(pc.w, -pc.theta1, y_end[2]), v, y_end[5])
            }
        };
        let qd_minus = impact::rates_about_pivot(&q, hip_v, trunk_rate);
        let (qd, impact) = impact::heel_strike(&self.stance_model, &q, &qd_minus);
        let y0 = StanceState::from([q[0], q[1], q[2], qd[0], qd[1], qd[2]]);
        let setup = self.stance_setup(&prev_c, &c, list);

        let (torque, l1) = (self.body.mass * self.body.l1, self.body.l1);
        let froude = gait.velocity / (crate::model::GRAVITY * l1).sqrt();
        let guesses = self.startup_guesses;
        let startup =
            |memory: Option<Memory2>, unknowns, x_unit, cold, plain| match (guesses, memory) {
                (false, None) => (plain, None),
                (false, Some(m)) => (Start2::Warm(m), None),
                (true, _) => startup(memory, index, froude, unknowns, x_unit, cold, plain),
            };
        // the plain cold starts (the fallbacks): the stance at the default walk's step-0
        // solution of before the knee's cubic, body-scaled; the swings from zero torques
        let (start, fallback) = startup(
            self.stance_memory,
            [0, 1],
            [torque, l1],
            (COLD_STANCE, [1.0, l1]),
            Start2::Cold {
                x0: Vector2::new(2.0 * torque, 0.0055 * l1),
                h: Vector2::new(0.01 * torque, 1e-3),
            },
        );
        let best = std::cell::RefCell::new(None::<StanceRun>);
        // every trial follows the step sequences of the last one that chose its own steps (at
        // first, the last step's kept trial's)
        let mesh = std::cell::RefCell::new(self.stance_mesh.take());
        let residual = |x: Vector2<f64>| {
            let run = StanceRun::simulate_on(
                &setup,
                y0,
                x[0],
                x[1],
                crate::numerics::ode::TOLERANCE,
                mesh.borrow().as_ref(),
            )?;
            if run.adapted {
                *mesh.borrow_mut() = Some(run.clone());
            }
            self.count(run.evaluations);
            let r = run.residual;
            let mut b = best.borrow_mut();
            if b.as_ref()
                .is_none_or(|o: &StanceRun| r.amax() < o.residual.amax())
            {
                *b = Some(run);
            }
            Ok(r)
        };
        let ((x, memory), report) = with_fallback(start, fallback, |start| {
            shooting::solve2(residual, start, &self.options).map(|(x, r, m)| ((x, m), r))
        })
        .map_err(|reason| Error::Integration {
            step: index,
            phase: "stance",
            reason,
        })?;
        let mut stance = best.into_inner().expect("at least one trial ran");
        self.count(stance.densify(&setup));
        if !report.converged {
            return Err(Error::NotConverged {
                step: index,
                phase: "stance",
                residual: report.residual,
                iterations: report.iterations,
            });
        }
        debug_assert!(stance.tau1 == x[0] && stance.p == x[1]);
        self.stance_memory = Some(memory);
        // [ours] the swings' warm starts extrapolate with the stance's step ratio: the walk
        // approaches its limit cycle with one ratio for all seven unknowns (λ ≈ −0.04 to −0.15
        // over the grid), which the stance's history shows from step 2 on while the swings' own
        // start with the first step's (+0.03 to +0.4 for swing1's A at step 2)
        if index >= 3 {
            let ratio = shooting::step_ratio(
                memory.x.into(),
                [memory.earlier[0].into(), memory.earlier[1].into()],
            );
            for m in [&mut self.swing1_memory, &mut self.swing3_memory]
                .into_iter()
                .flatten()
            {
                m.ratio = ratio;
            }
            if let Some(m) = self.swing2_memory.as_mut() {
                m.ratio = ratio;
            }
        }
        self.stance_mesh = Some(stance.clone());
        let mut solves = vec![SolveRecord {
            phase: "stance",
            report,
        }];

        // the determinants of gait move each leg's hip joint off the pelvis centre
        let t = c.timing;
        let side = Side::of_step(index);
        let det = Determinants {
            list,
            ..self.determinants
        };
        let (t0, x0) = (self.t, self.x_ankle);
        let pelvis = |tau: f64| det.at(side, tau, t.t_step);
        // a leg's hip joint at step time τ: world (x, y) and lateral offset from its ankle
        let hip_joint = |leg: Side, tau: f64| {
            let h = stance.hip_position(&setup, tau);
            let p = pelvis(tau);
            let o = det.hip_offset(leg, &p);
            ([x0 + h[0] + o[0], h[1] + o[1]], det.lateral_offset(leg, &p))
        };
        let geometry = |phase: &'static str| {
            move |what: String| Error::Invariant {
                step: index,
                phase,
                what,
            }
        };
        let kappa_to = self.attrs.toe_off_knee;
        // double support: the previous stance leg completes its stance to toe-off
        let mut hind = match self.prev_leg {
            Some(leg) => leg,
            None => {
                // first step [ours]: a hind foot flat at −sl, its heel already off at the heel
                // strike with the knee at κ_hs
                let mut leg = StanceLeg::new(
                    &self.body,
                    x0 - gait.step_length,
                    t0 - t.t_step,
                    0.0,
                    self.attrs.foot_flat_time * t.t_cycle,
                    self.attrs.heel_off_dorsiflexion,
                    self.attrs.metatarsal_limit,
                );
                leg.heel_off = Some(KneeCurve::new(
                    t0,
                    self.attrs.heel_strike_knee,
                    0.0,
                    t0 + t.t_ds,
                    kappa_to,
                ));
                leg
            }
        };
        let hind_side = side.other();
        hind.continue_to_toe_off(
            |tw| hip_joint(hind_side, tw - t0),
            t0,
            t0 + t.t_ds,
            kappa_to,
        )
        .map_err(geometry("double_support"))?;
        let hind_pose = |tau: f64| {
            let (h, dz) = hip_joint(hind_side, tau);
            hind.pose(h, dz, t0 + tau)
        };
        let off = hind_pose(t.t_ds).map_err(geometry("double_support"))?;
        let h = 1e-4 * t.t_ds;
        let theta3_at = |tau: f64| hind_pose(tau).map(|p| p.theta3);
        let d3 = (-theta3_at(t.t_ds + 2.0 * h).map_err(geometry("double_support"))?
            + 8.0 * theta3_at(t.t_ds + h).map_err(geometry("double_support"))?
            - 8.0 * theta3_at(t.t_ds - h).map_err(geometry("double_support"))?
            + theta3_at(t.t_ds - 2.0 * h).map_err(geometry("double_support"))?)
            / (12.0 * h);
        let knee_rate = hind.knee_curve(t0 + t.t_ds).map_or(0.0, |k| k.1);
        let y_off = SwingState::from([off.theta3, off.theta4, d3, knee_rate]);

        // this step's stance leg, to its heel-off
        let mut stance_leg = StanceLeg::new(
            &self.body,
            x0,
            t0,
            prev_c.sole_angle,
            self.attrs.foot_flat_time * t.t_cycle,
            self.attrs.heel_off_dorsiflexion,
            self.attrs.metatarsal_limit,
        );
        stance_leg
            .find_heel_off(
                |tw| hip_joint(side, tw - t0),
                t0,
                t0 + t.t_step,
                t0 + t.t_step + t.t_ds,
                kappa_to,
            )
            .map_err(geometry("stance"))?;

        // swing: three subphases, each solved by shooting; the dynamics hang from the swing
        // side's hip joint, in the leg's own plane
        let swing_offset = |tau: f64| swing_hip_offset(&det, side, &c, &pelvis(tau));
        let swing_offset_acc =
            |tau: f64| det.swing_offset_acceleration(side, tau, t.t_step, c.fold_length);
        let hip_path = HipPath::with_offset_acceleration(
            &stance,
            &setup,
            t.t_ds,
            t.t_step,
            &swing_offset,
            &swing_offset_acc,
        );
        let hip_vy_end = swing_hip_vy_end(&stance, &setup, &swing_offset);
        let sw = SwingSetup::new(self.swing_model, &hip_path, hip_vy_end, &c, &self.attrs);
        let fail = |phase: &'static str| {
            move |reason: String| Error::Integration {
                step: index,
                phase,
                reason,
            }
        };
        let not_converged = |phase: &'static str, r: &SolveReport| Error::NotConverged {
            step: index,
            phase,
            residual: r.residual,
            iterations: r.iterations,
        };
        let mut record = |phase: &'static str, report: SolveReport| {
            solves.push(SolveRecord { phase, report });
            if report.converged {
                Ok(())
            } else {
                Err(not_converged(phase, &report))
            }
        };
        // swing1: hip and knee magnitudes (A, B) together
        let [mesh1, mesh2, mesh3] = std::mem::take(&mut self.swing_meshes);
        let (s1, rep1, mem1) = self
            .solve_2d(
                &sw,
                startup(
                    self.swing1_memory,
                    [2, 3],
                    [torque; 2],
                    (COLD_SWING1, [1.0; 2]),
                    Start2::Cold {
                        x0: Vector2::zeros(),
                        h: Vector2::new(0.01 * torque, 0.005 * torque),
                    },
                ),
                |x| Subphase::Swing1 {
                    hip: x[0],
                    knee: x[1],
                },
                (sw.t_off, y_off),
                mesh1,
                WAYPOINT_TOLERANCE,
            )
            .map_err(fail("swing1"))?;
        record("swing1", rep1)?;
        self.swing1_memory = Some(mem1);
        // swing2: knee torque C
        let y1 = s1.segment.y1;
        let (s2, rep2, mem2) = self
            .solve_1d(
                &sw,
                {
                    let fit = |c: &[[f64; 3]; 7]| quadratic(c[4], froude) * torque;
                    let plain = Start1::Cold {
                        x0: 0.0,
                        dx: 0.1 * torque,
                    };
                    match self.swing2_memory {
                        Some(m) if !guesses => (Start1::Warm(m), None),
                        None if !guesses => (plain, None),
                        Some(mut m) => {
                            let unmoved = m;
                            startup_moves(index, &mut m.x, &mut m.earlier, f64::NAN, |i| {
                                fit(&CHANGES[i - 1])
                            });
                            let fallback =
                                (1..=2).contains(&index).then_some(Start1::Warm(unmoved));
                            (Start1::Warm(m), fallback)
                        }
                        None => (
                            Start1::Warm(Memory1 {
                                x: fit(&STEP0),
                                slope: COLD_SWING2_SLOPE / torque,
                                earlier: [f64::NAN; 2],
                                ratio: f64::NAN,
                            }),
                            Some(plain),
                        ),
                    }
                },
                |x| Subphase::Swing2 {
                    knee: x,
                    knee_start: y1[1],
                },
                (sw.t1, y1),
                mesh2,
                WAYPOINT_TOLERANCE,
            )
            .map_err(fail("swing2"))?;
        record("swing2", rep2)?;
        self.swing2_memory = Some(mem2);
        // knee lock, then swing3: hip moment D0 + D1 s
        let y2 = s2.segment.y1;
        let q2 = Vector2::new(y2[0], y2[1]);
        let qd2 = impact::knee_lock(&self.swing_model, &q2, &Vector2::new(y2[2], y2[3]));
        let y2 = SwingState::from([y2[0], c.theta4, qd2[0], 0.0]);
        let (s3, rep3, mem3) = self
            .solve_2d(
                &sw,
                startup(
                    self.swing3_memory,
                    [5, 6],
                    [torque; 2],
                    (COLD_SWING3, [1.0; 2]),
                    Start2::Cold {
                        x0: Vector2::zeros(),
                        h: Vector2::repeat(0.01 * torque),
                    },
                ),
                |x| Subphase::Swing3 {
                    hip: x[0],
                    ramp: x[1],
                },
                (sw.t2, y2),
                mesh3,
                SOLVE_TOLERANCE,
            )
            .map_err(fail("swing3"))?;
        record("swing3", rep3)?;
        self.swing3_memory = Some(mem3);
        self.swing_meshes = [&s1, &s2, &s3].map(|s| Some(s.segment.clone()));
        let work = work::stance_work(&setup, &stance, work::SAMPLES)
            + work::swing_work(
                &sw,
                &[
                    (s1.sub, &s1.segment),
                    (s2.sub, &s2.segment),
                    (s3.sub, &s3.segment),
                ],
                work::SAMPLES,
            );

        let step = Step {
            index,
            t_start: self.t,
            x_ankle: self.x_ankle,
            constraints: c,
            stance_setup: setup,
            impact,
            solves,
            side,
            determinants: det,
            stance_leg,
            hind_leg: hind,
            swing: vec![
                (s1.sub, s1.segment),
                (s2.sub, s2.segment),
                (s3.sub, s3.segment),
            ],
            theta5_off: off.theta3 + off.theta4 - off.pitch,
            theta6_off: off.theta6,
            toe_clearance: self.attrs.toe_clearance,
            lowest_at: 0.0,
            stance,
            report: StepReport {
                index,
                target: Target {
                    velocity: gait.velocity,
                    step_length: gait.step_length,
                    step_frequency: gait.step_frequency,
                },
                achieved: Achieved {
                    velocity: f64::NAN,
                    step_length: f64::NAN,
                    duration: t.t_step,
                },
                solves: Vec::new(),
                end_condition_error: f64::NAN,
                heel_height_at_strike: f64::NAN,
                hip_excursion: f64::NAN,
                bounce_reference: c.bounce,
                hip_min_margin: f64::NAN,
                impact_speed_ratio: impact.speed_ratio,
                min_foot_height: f64::NAN,
                min_toe_clearance: f64::NAN,
                heel_contact_velocity: f64::NAN,
                rhs_evaluations: 0,
                peak_swing_knee_flexion: f64::NAN,
                positive_work: work.positive,
                net_work: work.net,
            },
        };
        let mut step = step;
        step.measure(&Foot::new(&self.body));
        step.report.rhs_evaluations = self.evaluations.get();
        step.check_invariants()?;
        let y_end = step
            .stance
            .segments
            .last()
            .expect("a converged run has segments")
            .0
            .y1;
        self.prev = Some((c, y_end));
        self.prev_leg = Some(step.stance_leg);
        self.t += c.timing.t_step;
        self.x_ankle += gait.step_length;
        self.index += 1;
        Ok(step)
    }

    fn count(&self, evaluations: u32) {
        self.evaluations
            .set(self.evaluations.get() + u64::from(evaluations));
    }

    /// A 2-D swing solve (Broyden) from `start` (then `fallback`, [`with_fallback`]).
    fn solve_2d(
        &self,
        sw: &SwingSetup,
        (start, fallback): (Start2, Option<Start2>),
        sub: impl Fn(Vector2<f64>) -> Subphase,
        (t0, y0): (f64, SwingState),
        mesh: Option<Segment<4>>,
        tol: f64,
    ) -> std::result::Result<(SwingTrial, SolveReport, Memory2), String> {
        let best = std::cell::RefCell::new(None::<SwingTrial>);
        // every trial follows the step sequence of the last one that chose its own steps (at
        // first, `mesh`: the last step's)
        let mesh = std::cell::RefCell::new(mesh);
        let residual = |x| self.swing_trial(sw, sub(x), t0, y0, &mesh, &best);
        let (mem, report) = with_fallback(start, fallback, |start| {
            let opts = Options {
                tol,
                ..self.options
            };
            shooting::solve2(residual, start, &opts).map(|(_, r, m)| (m, r))
        })?;
        let mut trial = best.into_inner().ok_or("no trial ran")?;
        self.count(trial.densify(sw));
        Ok((trial, report, mem))
    }

    /// One swing trial of a solve: it follows the solve's mesh (or, when it had to choose its
    /// own steps, becomes it), counts its evaluations and is kept if it is the best so far.
    fn swing_trial(
        &self,
        sw: &SwingSetup,
        sub: Subphase,
        t0: f64,
        y0: SwingState,
        mesh: &std::cell::RefCell<Option<Segment<4>>>,
        best: &std::cell::RefCell<Option<SwingTrial>>,
    ) -> std::result::Result<Vector2<f64>, String> {
        let trial = SwingTrial::simulate_on(
            sw,
            sub,
            t0,
            y0,
            sub.tolerance(crate::numerics::ode::TOLERANCE),
            mesh.borrow().as_ref(),
        )?;
        if trial.adapted {
            *mesh.borrow_mut() = Some(trial.segment.clone());
        }
        let r = trial.residual;
        self.count(trial.evaluations);
        keep_best(best, trial);
        Ok(r)
    }

    /// A 1-D swing solve (bisection then secant) from `start` (then `fallback`,
    /// [`with_fallback`]).
    fn solve_1d(
        &self,
        sw: &SwingSetup,
        (start, fallback): (Start1, Option<Start1>),
        sub: impl Fn(f64) -> Subphase,
        (t0, y0): (f64, SwingState),
        mesh: Option<Segment<4>>,
        tol: f64,
    ) -> std::result::Result<(SwingTrial, SolveReport, Memory1), String> {
        let best = std::cell::RefCell::new(None::<SwingTrial>);
        // every trial follows the step sequence of the last one that chose its own steps (at
        // first, `mesh`: the last step's)
        let mesh = std::cell::RefCell::new(mesh);
        let residual = |x| Ok(self.swing_trial(sw, sub(x), t0, y0, &mesh, &best)?[0]);
        let (mem, report) = with_fallback(start, fallback, |start| {
            let opts = Options {
                tol,
                ..self.options
            };
            shooting::solve1(residual, start, &opts).map(|(_, r, m)| (m, r))
        })?;
        let mut trial = best.into_inner().ok_or("no trial ran")?;
        self.count(trial.densify(sw));
        Ok((trial, report, mem))
    }
}

/// [ours] Start-up guesses of the seven unknowns — τ1, p (stance), A, B (swing1), C (swing2),
/// D0, D1 (swing3) — in body units (torques / (M l1), lengths / l1), as quadratics c0 + c1 F +
/// c2 F² in the Froude speed F = v / √(g l1), least-squares fits over the grid of
/// `tests/walk.rs` (v 0.6–2.0 m/s × H 1.5–1.95 m, M = 23 H²): the solutions of step 0 (cold
/// start), and their changes from step 0 to step 1 and from step 1 to step 2 (the transient of
/// the artificial first posture: τ1 falls from ≈ 3 to ≈ −0.3 M l1, then rises to ≈ 0), added
/// to the previous solution at steps 1 and 2. Generated by `cargo run --release --example
/// startup_fit` (rerun it when the model changes: stale fits only cost trials, the fallback keeps
/// convergence).
const STEP0: [[f64; 3]; 7] =
    // step 0
    [
        [5.94477e-1, 2.75285e0, 1.12557e0], // τ1: largest residual 1.58e-1
        [-2.99372e-4, 1.10376e-2, 1.77189e-3], // p: largest residual 1.97e-3
        [5.43914e-1, -6.44801e0, 7.58348e0], // A: largest residual 2.30e-1
        [1.69408e-1, -2.89793e0, 2.14220e0], // B: largest residual 1.84e-1
        [-2.19923e-1, 8.84428e-1, -5.10054e-1], // C: largest residual 3.44e-2
        [-3.66406e0, 1.21026e1, -7.95248e0], // D0: largest residual 7.71e-1
        [9.37425e0, -3.41445e1, 2.32587e1], // D1: largest residual 1.66e0
    ];
const CHANGES: [[[f64; 3]; 7]; 2] = [
    // step 0 to 1
    [
        [-1.95710e0, 1.87123e0, -4.22192e0], // τ1: largest residual 4.45e-1
        [-2.24176e-4, 6.02331e-4, -5.71620e-4], // p: largest residual 6.76e-5
        [-1.29732e0, 7.06466e0, -1.29906e1], // A: largest residual 1.88e-1
        [-1.31518e-1, 8.43777e-1, -1.67196e0], // B: largest residual 6.20e-2
        [3.72783e-2, -2.21044e-1, 4.17782e-1], // C: largest residual 6.79e-3
        [-7.93594e-3, -2.53846e-1, 1.51814e-2], // D0: largest residual 2.42e-2
        [-1.45481e-1, 1.43134e0, -1.51461e0], // D1: largest residual 6.26e-2
    ],
    // step 1 to 2
    [
        [2.01613e-1, 2.20566e-1, -1.86355e-1], // τ1: largest residual 7.38e-2
        [2.72812e-5, -5.55637e-5, 3.68041e-5], // p: largest residual 7.73e-6
        [-3.23401e-2, 7.79124e-2, -1.12006e-1], // A: largest residual 2.43e-1
        [-1.01251e-3, -2.67600e-2, 2.26243e-2], // B: largest residual 4.40e-2
        [1.50207e-4, -3.66019e-4, 4.16825e-3], // C: largest residual 7.44e-3
        [-6.39472e-3, 4.39218e-2, -4.65281e-2], // D0: largest residual 2.32e-2
        [1.65605e-2, -1.22104e-1, 1.15393e-1], // D1: largest residual 1.97e-2
    ],
];
/// [ours] Cold Jacobians (`J[i][k]` = ∂rᵢ/∂xₖ, in body units): the default walk's (1.4 m/s,
/// H = 1.8 m, M = 80 kg) at the end of its step-0 solves, so that step 0 needs no difference
/// trials; swing2's residual slope. Generated with [`STEP0`], from walks started plainly
/// ([`Walker::without_startup_guesses`]), so a rerun reproduces them.
const COLD_STANCE: [[f64; 2]; 2] = [[1.39854e-1, -3.26875e-1], [5.30547e-2, 8.05430e-1]];
const COLD_SWING1: [[f64; 2]; 2] = [[4.01516e-1, -2.98615e-1], [2.24522e-1, 4.54508e-1]];
const COLD_SWING2_SLOPE: f64 = 3.22758e-1;
const COLD_SWING3: [[f64; 2]; 2] = [[4.76559e-2, 1.59202e-2], [-4.89486e-1, -2.46284e-1]];

fn quadratic(c: [f64; 3], x: f64) -> f64 {
    c[0] + x * (c[1] + x * c[2])
}

/// The start of step `index`'s 2-D solve of `unknowns` (of [`STEP0`]), unknown k in units of
/// `x_unit[k]`, and the start to fall back on ([`with_fallback`]): at step 0 the fit with the
/// cold Jacobian (`cold`: body units, residual i in units of `cold.1[i]`), then `plain`; at
/// steps 1 and 2 the memory moved by [`startup_moves`], then the memory itself; later the
/// memory alone.
fn startup(
    memory: Option<Memory2>,
    index: usize,
    froude: f64,
    unknowns: [usize; 2],
    x_unit: [f64; 2],
    cold: ([[f64; 2]; 2], [f64; 2]),
    plain: Start2,
) -> (Start2, Option<Start2>) {
    let fit =
        |c: &[[f64; 3]; 7]| Vector2::from_fn(|k, _| quadratic(c[unknowns[k]], froude) * x_unit[k]);
    match memory {
        Some(mut m) => {
            let unmoved = m;
            let nan = Vector2::repeat(f64::NAN);
            startup_moves(index, &mut m.x, &mut m.earlier, nan, |i| {
                fit(&CHANGES[i - 1])
            });
            let fallback = (1..=2).contains(&index).then_some(Start2::Warm(unmoved));
            (Start2::Warm(m), fallback)
        }
        None => {
            let (j, r_unit) = cold;
            let guess = Memory2 {
                x: fit(&STEP0),
                jacobian: nalgebra::Matrix2::from_fn(|i, k| j[i][k] * r_unit[i] / x_unit[k]),
                earlier: [Vector2::repeat(f64::NAN); 2],
                ratio: f64::NAN,
            };
            (Start2::Warm(guess), Some(plain))
        }
    }
}

/// A solve from `start`, and when it does not converge (or its first trial fails) once more
/// from `fallback`, the report counting both: the start-up guesses are fits over the default
/// attributes' grid, and outside it (a style preset) they can lead where the residual has no
/// root nearby (the elderly preset's swing2 at 0.9 m/s).
fn with_fallback<S, T>(
    start: S,
    fallback: Option<S>,
    solve: impl Fn(S) -> std::result::Result<(T, SolveReport), String>,
) -> std::result::Result<(T, SolveReport), String> {
    let first = solve(start);
    match (first, fallback) {
        (Ok((t, report)), _) if report.converged => Ok((t, report)),
        (first, None) => first,
        (first, Some(fallback)) => {
            let spent = first.as_ref().map_or(1, |(_, r)| r.iterations);
            solve(fallback).map(|(t, mut report)| {
                report.iterations += spent;
                (t, report)
            })
        }
    }
}

/// A warm start at step `index` moved by the fitted start-up transient, `change(i)` from step
/// i − 1 to step i ([`CHANGES`]): the point `x` at steps 1 and 2; the extrapolation's history
/// `earlier` (`shooting::Memory2`) emptied at step 1 (step 0 started from a fit, not from a
/// solution), and its latest entry moved back at steps 2 and 3 (it is the moved start).
fn startup_moves<T>(
    index: usize,
    x: &mut T,
    earlier: &mut [T; 2],
    nan: T,
    change: impl Fn(usize) -> T,
) where
    T: Copy + std::ops::Add<Output = T> + std::ops::Sub<Output = T>,
{
    if index == 1 {
        *earlier = [nan; 2];
    }
    if (2..=3).contains(&index) {
        earlier[0] = earlier[0] - change(index - 1);
    }
    if (1..=2).contains(&index) {
        *x = *x + change(index);
    }
}

/// The swing-side hip's vertical velocity at heel strike: the stance hip's plus the rate of the
/// determinants' `offset` (a backward difference over 1e-6 t_step).
pub fn swing_hip_vy_end(
    stance: &StanceRun,
    setup: &StanceSetup,
    offset: &dyn Fn(f64) -> [f64; 2],
) -> f64 {
    let t = setup.t_step;
    let e = 1e-6 * t;
    stance.hip(setup, t)[1][1] + (offset(t)[1] - offset(t - e)[1]) / e
}

/// Uniform samples per interval in [`minima`].
const COARSE_SAMPLES: usize = 32;
/// Uniform samples of the swing foot's height in [`minima`]: narrow dips (the toe under the
/// ground for 1 % of the swing while the heel rests on its floor) need them denser; each local
/// minimum among them is then refined.
const FOOT_SAMPLES: usize = 100;

/// Move a pose's x coordinates by `dx`.
fn shift_pose(p: &mut LegPose, dx: f64) {
    for q in [
        &mut p.knee,
        &mut p.ankle,
        &mut p.foot.heel,
        &mut p.foot.meta,
        &mut p.foot.toe,
    ] {
        q[0] += dx;
    }
}

/// The swing-side hip joint relative to the pelvis centre, in the swing leg's plane (spec §7):
/// the determinants' offset, raised by the fold of the leg's lateral offset (with the striking
/// leg's in-plane drop, exact at heel strike).
fn swing_hip_offset(
    det: &Determinants,
    stance: Side,
    c: &StepConstraints,
    p: &PelvisMotion,
) -> [f64; 2] {
    let leg = stance.other();
    let o = det.hip_offset(leg, p);
    let dz = det.lateral_offset(leg, p);
    [o[0], o[1] + fold_height(c.fold_length, dz)]
}

/// Keep the trial with the smallest residual (the one the solver returns).
fn keep_best(best: &std::cell::RefCell<Option<SwingTrial>>, trial: SwingTrial) {
    let mut b = best.borrow_mut();
    if b.as_ref()
        .is_none_or(|o| trial.residual.amax() < o.residual.amax())
    {
        *b = Some(trial);
    }
}

/// A simulated walk.
pub struct Walk {
    pub body: Body,
    pub attrs: Attributes,
    pub steps: Vec<Step>,
}

/// Simulate one step per entry of `gaits` (parameters may change from step to step).
pub fn simulate(body: Body, attrs: Attributes, gaits: &[Gait]) -> Result<Walk> {
    let mut walker = Walker::new(body, attrs.clone());
    let steps = gaits
        .iter()
        .map(|g| walker.step(*g))
        .collect::<Result<Vec<_>>>()?;
    Ok(Walk { body, attrs, steps })
}

impl Walk {
    /// Simulated duration (s).
    pub fn duration(&self) -> f64 {
        self.steps.iter().map(|s| s.constraints.timing.t_step).sum()
    }

    /// Frames at `fps` frames per second from t = 0 to the last heel strike (inclusive).
    pub fn frames(&self, fps: f64) -> Vec<StateFrame> {
        let foot = Foot::new(&self.body);
        let n = (self.duration() * fps + 1e-9).floor() as usize;
        let mut frames = Vec::with_capacity(n + 1);
        let mut i = 0;
        for k in 0..=n {
            let t = k as f64 / fps;
            while i + 1 < self.steps.len() && t >= self.steps[i + 1].t_start {
                i += 1;
            }
            if let Some(step) = self.steps.get(i) {
                frames.push(step.frame(t, &foot));
            }
        }
        frames
    }

    /// The per-step report.
    pub fn report(&self) -> Report {
        Report {
            height: self.body.height,
            mass: self.body.mass,
            steps: self.steps.iter().map(|s| s.report.clone()).collect(),
        }
    }
}

/// The swing leg at one instant: subphase, in-plane angles, and points (x relative to the
/// stance ankle, world heights; the hip joint's lateral offset from the ankle `dz`).
#[derive(Clone, Copy, Debug)]
pub struct SwingPose {
    pub phase: &'static str,
    pub theta3: f64,
    pub theta4: f64,
    /// (sin, cos) of θ3 and of θ3 + θ4, as [`leg_points`] (or the hind leg's pose) computed
    /// them.
    pub sin_cos: [(f64, f64); 2],
    pub hip: [f64; 2],
    pub dz: f64,
    pub knee: [f64; 2],
    pub ankle: [f64; 2],
    pub foot: FootPoints,
}

/// A step at one instant: what the figure hangs from, evaluated once ([`Step::at`]).
#[derive(Clone, Copy, Debug)]
pub struct Instant {
    /// Step time τ (s).
    pub tau: f64,
    /// The stance state and whether the knee is locked.
    pub state: StanceState,
    pub locked: bool,
    /// The dynamic hip, the pelvis centre (x relative to the stance ankle): [`Step::hip`].
    pub centre: [f64; 2],
    /// The determinants: [`Step::pelvis`].
    pub pelvis: PelvisMotion,
    /// [`Determinants::hip_offset`] of the right and the left hip joint.
    pub hip_offsets: [[f64; 3]; 2],
    /// [`Determinants::ankle_z`] of the right and the left ankle.
    pub ankle_z: [f64; 2],
}

impl Instant {
    fn index(side: Side) -> usize {
        match side {
            Side::Right => 0,
            Side::Left => 1,
        }
    }

    /// The hip joint of `leg` relative to the pelvis centre (m, world axes).
    pub fn hip_offset(&self, leg: Side) -> [f64; 3] {
        self.hip_offsets[Self::index(leg)]
    }

    /// [`Step::hip_joint`]: the hip joint of `leg` (x relative to the stance ankle, world y)
    /// and [`Determinants::lateral_offset`] from that leg's ankle.
    pub fn hip_joint(&self, leg: Side) -> ([f64; 2], f64) {
        let o = self.hip_offset(leg);
        (
            [self.centre[0] + o[0], self.centre[1] + o[1]],
            self.pelvis.lateral + o[2] - self.ankle_z[Self::index(leg)],
        )
    }
}

impl Step {
    /// The dynamic hip, the pelvis centre (x relative to the stance ankle), at step time τ.
    pub fn hip(&self, tau: f64) -> [f64; 2] {
        self.stance.hip_position(&self.stance_setup, tau)
    }

    /// The pelvis's determinants at step time τ.
    pub fn pelvis(&self, tau: f64) -> PelvisMotion {
        self.determinants
            .at(self.side, tau, self.constraints.timing.t_step)
    }

    /// The hip joint of `leg` (x relative to the stance ankle, world y) and its lateral offset
    /// from that leg's ankle, at step time τ.
    pub fn hip_joint(&self, leg: Side, tau: f64) -> ([f64; 2], f64) {
        self.at(tau).hip_joint(leg)
    }

    /// The stance state, the dynamic hip and the pelvis at step time τ, each evaluated once.
    pub fn at(&self, tau: f64) -> Instant {
        let (state, locked) = self.stance.state(tau);
        let centre = self
            .stance_setup
            .model
            .hip(&Vector3::new(state[0], state[1], state[2]));
        let pelvis = self.pelvis(tau);
        let right = self.determinants.hip_offset(Side::Right, &pelvis);
        Instant {
            tau,
            state,
            locked,
            centre,
            pelvis,
            // hip_offset(Left) is hip_offset(Right) with the half width negated: exactly −right
            hip_offsets: [right, right.map(|x| -x)],
            ankle_z: [
                self.determinants.ankle_z(Side::Right),
                self.determinants.ankle_z(Side::Left),
            ],
        }
    }

    /// The swing-side hip joint relative to the pelvis centre in the swing leg's plane, at step
    /// time τ: the offset the swing dynamics hang from.
    pub fn swing_offset(&self, tau: f64) -> [f64; 2] {
        swing_hip_offset(
            &self.determinants,
            self.side,
            &self.constraints,
            &self.pelvis(tau),
        )
    }

    /// The stance leg's pose at step time τ (x relative to the stance ankle).
    pub fn stance_pose(&self, tau: f64) -> std::result::Result<LegPose, String> {
        self.stance_pose_at(&self.at(tau))
    }

    /// [`Self::stance_pose`] at an instant of this step.
    pub fn stance_pose_at(&self, now: &Instant) -> std::result::Result<LegPose, String> {
        let (h, dz) = now.hip_joint(self.side);
        let mut p =
            self.stance_leg
                .pose([h[0] + self.x_ankle, h[1]], dz, self.t_start + now.tau)?;
        shift_pose(&mut p, -self.x_ankle);
        Ok(p)
    }

    /// The swing foot's ankle dorsiflexion θ5 and toe angle θ6 at step time τ ≥ t_ds (spec §5
    /// [ours]): θ5 linear from its toe-off value to 0 over the first 80 % of swing1 (the spec
    /// says all of swing1; the toe needs the neutral ankle earlier), then to δ_hs at heel strike
    /// on a smoothstep; θ6 back to 0 on a half-cosine (no toe velocity jump at toe-off).
    pub fn swing_foot_angles(&self, tau: f64) -> (f64, f64) {
        let t = self.constraints.timing;
        let t1 = t.t_ds + swing::SWING1_END * t.t_swing;
        if tau < t1 {
            let s = ((tau - t.t_ds) / (ANKLE_NEUTRAL * (t1 - t.t_ds))).clamp(0.0, 1.0);
            (
                self.theta5_off * (1.0 - s),
                self.theta6_off * 0.5 * (1.0 + crate::numerics::trig::sin_cos(PI * s).1),
            )
        } else {
            let s = ((tau - t1) / (t.t_step - t1)).clamp(0.0, 1.0);
            (
                self.constraints.ankle * crate::control::stance::smoothstep(s),
                0.0,
            )
        }
    }

    /// The swing (or, in double support, hind) leg at step time τ.
    pub fn swing_pose(&self, tau: f64, foot: &Foot) -> SwingPose {
        self.swing_pose_at(&self.at(tau), foot)
    }

    /// [`Self::swing_pose`] at an instant of this step.
    pub fn swing_pose_at(&self, now: &Instant, foot: &Foot) -> SwingPose {
        let tau = now.tau;
        let t = self.constraints.timing;
        let (hip, dz) = now.hip_joint(self.side.other());
        let (l3, l4) = (self.stance_leg.l3, self.stance_leg.l4);
        if tau < t.t_ds
            && let Ok(mut p) =
                self.hind_leg
                    .pose([hip[0] + self.x_ankle, hip[1]], dz, self.t_start + tau)
        {
            shift_pose(&mut p, -self.x_ankle);
            let (knee, _) = leg_points_sc(hip, dz, p.sin_cos, l3, l4);
            return SwingPose {
                phase: "double_support",
                theta3: p.theta3,
                theta4: p.theta4,
                sin_cos: p.sin_cos,
                hip,
                dz,
                knee,
                ankle: p.ankle,
                foot: p.foot,
            };
        }
        let i = self
            .swing
            .partition_point(|(_, s)| s.t1 < tau)
            .min(self.swing.len() - 1);
        let (sub, seg) = &self.swing[i];
        let y = seg.state(tau);
        let (knee, ankle, sin_cos) = leg_points(hip, dz, y[0], y[1], l3, l4);
        let (theta5, theta6) = self.swing_foot_angles(tau);
        // [ours] the ankle dorsiflexes beyond its rule when the rule would put the toe below a
        // floor rising from 0 at toe-off to the toe-clearance attribute at mid swing and back to
        // 0 at heel strike: the foot's mass is in the shank, so this is kinematic only
        let t = self.constraints.timing;
        let s = ((tau - t.t_ds) / t.t_swing).clamp(0.0, 1.0);
        let floor = self.toe_clearance * crate::numerics::trig::sin_cos(PI * s).0.powi(2);
        let (_, foot_points) = foot.clear_pitch(y[0] + y[1] - theta5, ankle, theta6, floor);
        SwingPose {
            phase: sub.name(),
            theta3: y[0],
            theta4: y[1],
            sin_cos,
            hip,
            dz,
            knee,
            ankle,
            foot: foot_points,
        }
    }

    /// The engine's state frame at world time t.
    pub fn frame(&self, t: f64, foot: &Foot) -> StateFrame {
        let tau = (t - self.t_start).clamp(0.0, self.constraints.timing.t_step);
        let now = self.at(tau);
        let (y, locked, hip) = (now.state, now.locked, now.centre);
        let sw = self.swing_pose_at(&now, foot);
        let x0 = self.x_ankle;
        StateFrame {
            time_s: t,
            step: self.index,
            phase: sw.phase,
            stance_side: if self.index.is_multiple_of(2) {
                "right"
            } else {
                "left"
            },
            stance_mode: if locked { "locked" } else { "telescopic" },
            w_m: y[0],
            theta1_deg: y[1].to_degrees(),
            theta2_deg: y[2].to_degrees(),
            theta3_deg: sw.theta3.to_degrees(),
            theta4_deg: sw.theta4.to_degrees(),
            hip_x_m: x0 + hip[0],
            hip_y_m: hip[1],
            stance_ankle_x_m: x0,
            stance_ankle_y_m: self.stance_setup.model.l9,
            swing_knee_x_m: x0 + sw.knee[0],
            swing_knee_y_m: sw.knee[1],
            swing_ankle_x_m: x0 + sw.ankle[0],
            swing_ankle_y_m: sw.ankle[1],
            swing_heel_x_m: x0 + sw.foot.heel[0],
            swing_heel_y_m: sw.foot.heel[1],
            swing_toe_x_m: x0 + sw.foot.toe[0],
            swing_toe_y_m: sw.foot.toe[1],
        }
    }

    /// Fill the report: end conditions, step length achieved, hip excursion, foot clearance.
    fn measure(&mut self, foot: &Foot) {
        let c = self.constraints;
        let t = c.timing;
        let y_end = self.stance.segments.last().expect("converged").0.y1;
        let sw_end = self.swing.last().expect("converged").1.y1;
        let end_error = [
            y_end[1] - c.theta1,
            y_end[0] - c.w,
            sw_end[0] - c.theta3,
            sw_end[1] - c.theta4,
        ]
        .iter()
        .fold(0.0_f64, |m, e| m.max(e.abs()));
        let strike = self.swing_pose(t.t_step, foot);
        let dt = 1e-6;
        let before = self.swing_pose(t.t_step - dt, foot);
        let step_length = strike.foot.heel[0] + foot.l8;
        // hip: its highest and lowest points through the stance
        let hip_y = |tau: f64| self.hip(tau)[1];
        let (y_min, _) = least_in(&minima(hip_y, 0.0, t.t_step, COARSE_SAMPLES), 0.0, t.t_step);
        let (y_max, _) = least_in(
            &minima(|tau| -hip_y(tau), 0.0, t.t_step, COARSE_SAMPLES),
            0.0,
            t.t_step,
        );
        let y_max = -y_max;
        let s = &self.stance_setup;
        // swing foot: lowest point over the swing, and in mid swing; the knee's peak flexion
        let (t_off, t_swing) = (t.t_ds, t.t_swing);
        let foot_y = |tau: f64| self.swing_pose(tau, foot).foot.lowest();
        let swing_end = t_off + t_swing;
        let (mid_lo, mid_hi) = (t_off + 0.25 * t_swing, t_off + 0.75 * t_swing);
        // the least over mid swing is at one of its ends or at a local minimum inside
        let mut heights = minima(foot_y, t_off, swing_end, FOOT_SAMPLES);
        heights.extend([(mid_lo, foot_y(mid_lo)), (mid_hi, foot_y(mid_hi))]);
        let (mid, _) = least_in(&heights, mid_lo, mid_hi);
        let (lowest, lowest_at) = least_in(&heights, t_off, swing_end);
        let knee = |tau: f64| {
            let i = self
                .swing
                .partition_point(|(_, s)| s.t1 < tau)
                .min(self.swing.len() - 1);
            self.swing[i].1.state(tau)[1]
        };
        let (knee_peak, _) = least_in(
            &minima(|tau| -knee(tau), t_off, swing_end, COARSE_SAMPLES),
            t_off,
            swing_end,
        );
        let knee_peak = -knee_peak;
        self.lowest_at = (lowest_at - t_off) / t_swing;
        let r = &mut self.report;
        r.solves = self.solves.clone();
        r.achieved = Achieved {
            velocity: step_length / t.t_step,
            step_length,
            duration: t.t_step,
        };
        r.end_condition_error = end_error;
        r.heel_height_at_strike = strike.foot.heel[1];
        r.heel_contact_velocity = (strike.foot.heel[1] - before.foot.heel[1]) / dt;
        r.hip_excursion = y_max - s.y_end;
        r.hip_min_margin = y_min - s.y_start.min(s.y_end);
        r.min_foot_height = lowest;
        r.min_toe_clearance = mid;
        r.peak_swing_knee_flexion = knee_peak;
    }

    /// Invariants of a converged step (spec §4, §5): the hip never below its heel-strike height,
    /// no point of the swing foot under the ground, the toe clear of it in mid swing.
    fn check_invariants(&self) -> Result<()> {
        let r = &self.report;
        let fail = |phase: &'static str, what: String| {
            Err(Error::Invariant {
                step: self.index,
                phase,
                what,
            })
        };
        if r.hip_min_margin < -1e-6 {
            return fail(
                "stance",
                format!(
                    "the hip drops {:.3e} m below its heel-strike height",
                    -r.hip_min_margin
                ),
            );
        }
        // a positive clearance, by more than the 1e-6 m to which the feet are placed (spec §5):
        // where the toe-clearance rule cannot lift the toe it rests on the ground, at ±1e-16 m
        // of rounding, and that walk must not pass or fail by the sign of the rounding
        if r.min_toe_clearance <= TOE_CLEARANCE_MIN {
            return fail(
                "swing",
                format!(
                    "the toe touches the ground in mid swing (clearance {:.3e} m)",
                    r.min_toe_clearance
                ),
            );
        }
        if r.min_foot_height < -1e-6 {
            return fail(
                "swing",
                format!(
                    "the swing foot goes {:.3e} m under the ground at {:.0} % of the swing",
                    -r.min_foot_height,
                    100.0 * self.lowest_at
                ),
            );
        }
        Ok(())
    }
}
