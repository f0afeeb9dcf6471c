//! The whole figure of a generalized step (Ko & Badler 1992 §1, §6; docs/generalize.md,
//! "Posing"): the pelvis centre on H, the stance foot turned about its heel (F1) and then its
//! ball and its toe tip (F2, M), the hind foot rolling to its toe-off (F2, M on its timeline past
//! 1), the swing foot's ankle on A at the pitch F3; the legs two-link chains from the hip joints;
//! the pelvis's rotation, list and lateral displacement from the determinants of gait, its tilt
//! from the trunk sequence, and the trunk and arms by klaw's rules — posed by the figure of
//! non-rhythmic stepping ([`crate::nrs::pose::figure`]).
use crate::figure::landmarks::{arm_swing, thigh_angle};
use crate::figure::{Landmarks, LegPoints};
use crate::generalize::condition::BodyCondition;
use crate::generalize::error::GeneralizeError;
use crate::generalize::parameters::GeneralizeParameters;
use crate::generalize::sequence::Curve;
use crate::generalize::walk_data::WalkData;
use crate::kinematics::foot::Foot;
use crate::kinematics::pelvis::{Determinants, Side};
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::nrs::pose::{FootPose, Upper, figure, hip_joint};
use glam::DVec3;

/// The fraction of the swing by which the toes are straight again: klaw's 80 % of swing1.
const TOES_STRAIGHT: f64 = 0.8 * crate::control::swing::SWING1_END;

/// A foot on the floor with its N at `n` (x), pitch `p` and toes at `m` from the floor: its
/// ankle (x, y) and toe dorsiflexion θ6. Toes up (p < 0) it turns about its heel at n − hN;
/// heel up about its toe tip at n + bN + bt, the toes at m, the ball–ankle line at θb + p
/// (before meta-off m = 0: about the ball). Neither pivot slides.
pub fn grounded(body: &BodyCondition, n: f64, p: f64, m: f64) -> ([f64; 2], f64) {
    if p <= 0.0 {
        let (s, c) = (body.heel_angle() - p).sin_cos();
        let ah = body.heel_to_ankle();
        ([n - body.heel_to_n + ah * c, ah * s], 0.0)
    } else {
        let bt = body.ball_to_toe;
        let (s4, c4) = m.sin_cos();
        let (s, c) = (body.ball_angle() + p).sin_cos();
        let ab = body.ankle_to_ball();
        (
            [n + body.ball_to_n + bt - bt * c4 - ab * c, bt * s4 + ab * s],
            p - m,
        )
    }
}

/// \[ours\] The least knee flexion a leg keeps where the hip comes down for it ([`HipDrop`]):
/// the two-link leg is singular when straight (its knee flexion κ goes as the square root of
/// l1 − |hip − ankle|), so a leg held at its full reach snaps its knee where it reaches it or
/// leaves it; held at κ ≥ 2° its knee moves at a finite rate. Below klaw's own knee at heel
/// strike (`knee_heel_strike`, 4°; its swing knee comes no straighter than 3.2°, so the bundled
/// prototype on its own body never meets it) and DeepMimic's straightest swing knee (3.4°).
const KNEE_MIN: f64 = 2.0 * std::f64::consts::PI / 180.0;

/// The samples of the step (normalized time) at which [`HipDrop`] takes the legs' needs,
/// besides every sample of the walk data.
const DROP_SAMPLES: usize = 400;

/// \[ours\] Where a leg cannot reach the hip on H (klaw's own telescopic stance leg is longer
/// than the anatomical one just after heel strike; eq. 14 raises a shorter step's whole hip path
/// by its ends' rise, past a straight stance leg at mid-stance; a clip whose swing knee comes
/// within a few degrees of straight in terminal swing, DeepMimic's at 3.4°, reaches further
/// than the leg at a longer step or on a body of other proportions: 15 mm at 1.4 m/s on de Leva's
/// male H 1.85), the hip comes down until every leg reaches, as non-rhythmic stepping's centre
/// path does (docs/generalize.md): the feet, the constraints on the floor, stay where the data
/// put them. The walk data stay as they are (the composition laws are the data's).
///
/// How far the hip comes down is planned over the whole step, not found instant by instant: the
/// least *concave* function of t on [0, 1] at or above every leg's need at every instant (the
/// upper hull of the needs, each the drop that lets the leg reach its ankle with the knee bent
/// `KNEE_MIN`, 2°). Found instant by instant the drop was the need itself: the
/// leg that set it was held straight, and where it began or stopped setting it its knee snapped
/// (0.15–0.17° in 2 µs on DeepMimic's clip: the square root of a straight leg) and the pelvis
/// turned from H's vertical speed to the leg's reach arc in an instant (it fell 7 mm in one 10 ms
/// frame at 1.4 m/s on de Leva's male H 1.85, and rose again as fast where the need ended).
/// Concave: a sum of pieces linear in t between the instants where the reach binds, as eq. 14
/// moves H linearly in t between the two heel strikes where eqs. 7–11 bind it; so the hip comes
/// down once and goes back up once in a step, never turning twice. At the heel strikes the drop
/// is the need there, the same at the end of a step and the start of the next (the same figure),
/// so the figure is continuous from step to step. The largest drop is the largest need, as
/// before (`hip_drop_max` refuses the same steps).
#[derive(Clone, Debug)]
pub struct HipDrop {
    /// The hull's corners: normalized times from 0 to 1 and the drop there (m).
    pub corners: Curve,
}

impl HipDrop {
    /// No drop.
    fn none() -> Self {
        HipDrop {
            corners: Curve {
                t: vec![0.0, 1.0],
                v: vec![0.0, 0.0],
            },
        }
    }

    /// The least concave function on [0, 1] at or above the needs `(t, m)` (sorted by t, the
    /// first at 0 and the last at 1): the upper hull of the points (Andrew's monotone chain).
    fn above(needs: &[(f64, f64)]) -> Self {
        let mut hull: Vec<(f64, f64)> = Vec::with_capacity(needs.len());
        for &p in needs {
            while hull.len() >= 2 {
                let (a, b) = (hull[hull.len() - 2], hull[hull.len() - 1]);
                // b is under the chord from a to p (or on it): not a corner of the upper hull
                let cross = (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
                if cross >= 0.0 {
                    hull.pop();
                } else {
                    break;
                }
            }
            hull.push(p);
        }
        HipDrop {
            corners: Curve {
                t: hull.iter().map(|p| p.0).collect(),
                v: hull.iter().map(|p| p.1).collect(),
            },
        }
    }

    /// The drop at normalized time t (m).
    pub fn at(&self, t: f64) -> f64 {
        self.corners.at(t)
    }
}

/// One generalized step ready to pose: its walk data on the body, the body's foot and the
/// determinants of gait.
#[derive(Clone, Debug)]
pub struct StepPose {
    /// The walk data (on `body`).
    pub data: WalkData,
    /// The body.
    pub body: Body,
    /// The locomotion attributes (determinants, tilt, lean, arm swing, step width).
    pub attrs: Attributes,
    /// Step duration (s).
    pub duration: f64,
    determinants: Determinants,
    foot: Foot,
    /// The leading thigh's sagittal angle at heel strike, for the arms.
    strike_thigh: f64,
    /// How far the hip comes down over the step.
    pub hip_drop: HipDrop,
}

impl StepPose {
    /// The step of `data` (already on `body`) lasting `duration` s.
    pub fn new(
        data: WalkData,
        body: Body,
        attrs: Attributes,
        duration: f64,
    ) -> Result<Self, GeneralizeError> {
        let mut pose = StepPose {
            determinants: Determinants::new(&attrs, body.l0),
            foot: Foot::new(&body),
            data,
            body,
            attrs,
            duration,
            strike_thigh: 1.0,
            hip_drop: HipDrop::none(),
        };
        pose.hip_drop = pose.planned_drop()?;
        let end = pose.figure(0, Side::Right, 0.0, 1.0, 0.0)?;
        pose.strike_thigh = thigh_angle(&end.left);
        Ok(pose)
    }

    /// The figure at normalized time t ∈ [0, 1] of step `index` standing on `side`, whose stance
    /// foot's N is at world x `n`; `time` is the frame's time (s).
    pub fn figure(
        &self,
        index: usize,
        side: Side,
        n: f64,
        t: f64,
        time: f64,
    ) -> Result<Landmarks, GeneralizeError> {
        Ok(self.posed(index, side, n, t, time)?.0)
    }

    /// [`Self::figure`] and how far the hip came down from H to let the legs reach (m).
    fn posed(
        &self,
        index: usize,
        side: Side,
        n: f64,
        t: f64,
        time: f64,
    ) -> Result<(Landmarks, f64), GeneralizeError> {
        let w = &self.data;
        let tom = w.phases.tom;
        let mut upper = self.upper(side, n, t);
        let swing = (t > tom).then(|| self.swing_foot(side.other(), n, t));
        let hind = (n - w.step_length_before, 1.0 + t);
        let stretched = |s: Side, distance: f64| GeneralizeError::Stretched {
            side: s.name(),
            step: index,
            t,
            distance,
            length: self.body.l1,
        };
        // the hip comes down as planned ([`HipDrop`]), and further if a leg still cannot
        // reach (between the plan's samples, within the knee's margin: not met on the tests'
        // walks)
        let half = self.body.l0 / 2.0;
        let planned = self.hip_drop.at(t);
        upper.centre[1] -= planned;
        let mut drop: f64 = 0.0;
        for (s, grounded_at) in [
            (side, Some((n, t))),
            (side.other(), swing.is_none().then_some(hind)),
        ] {
            let hip = hip_joint(&upper, s, half);
            let need = match (grounded_at, &swing) {
                (Some((n, t)), _) => self.on_floor(s, n, t, hip).1,
                (None, Some(f)) => self.need(hip, f.ankle),
                (None, None) => Ok(0.0),
            };
            drop = drop.max(need.map_err(|d| stretched(s, d))?);
        }
        upper.centre[1] -= drop;
        let drop = planned + drop;
        let stance = self.on_floor(side, n, t, hip_joint(&upper, side, half)).0;
        let other = match swing {
            Some(f) => f,
            None => {
                self.on_floor(
                    side.other(),
                    hind.0,
                    hind.1,
                    hip_joint(&upper, side.other(), half),
                )
                .0
            }
        };
        let feet = match side {
            Side::Right => [&stance, &other],
            Side::Left => [&other, &stance],
        };
        let mut lm = figure(
            &upper,
            feet,
            (&self.body, &self.foot),
            f64::INFINITY,
            time,
            index,
        )
        .map_err(|(s, distance)| stretched(s, distance))?;
        lm.right_arm = arm_swing(thigh_angle(&lm.left), self.strike_thigh, &self.attrs);
        lm.left_arm = arm_swing(thigh_angle(&lm.right), self.strike_thigh, &self.attrs);
        Ok((lm, drop))
    }

    /// The pelvis and upper body at t of a step standing on `side` with its stance N at `n`: the
    /// centre on H, the determinants' rotation, list and lateral displacement, the tilt from the
    /// trunk sequence, klaw's lumbar rules (arms set after the legs).
    fn upper(&self, side: Side, n: f64, t: f64) -> Upper {
        let w = &self.data;
        let pm = self.determinants.at(side, t * self.duration, self.duration);
        let [hx, hy] = w.hip.at(t);
        Upper {
            centre: [n + hx, hy, pm.lateral],
            heading: pm.rotation,
            tilt: self.attrs.pelvis_tilt + w.trunk.at(t),
            list: pm.list,
            lumbar_extension: self.attrs.pelvis_tilt - self.attrs.trunk_lean,
            lumbar_bending: pm.list,
            lumbar_rotation: -1.8 * pm.rotation,
            neck_rotation: 0.0,
            arms: Default::default(),
        }
    }

    fn foot_at(&self, s: Side, [x, y]: [f64; 2], pitch: f64, theta6: f64) -> FootPose {
        FootPose {
            ankle: [x, y, self.determinants.ankle_z(s)],
            heading: 0.0,
            pitch,
            theta6,
        }
    }

    /// The swing foot of `s` at t: its ankle on A, its pitch F3's unless that would put the heel
    /// or a toe under klaw's swing floor, rising from 0 at toe-off to the `toe_clearance`
    /// attribute at mid swing, c sin²(πu) (klaw's swing rule, `Step::swing_pose`,
    /// `Foot::clear_pitch`), its toes straightening
    /// by klaw's swing rule (a half cosine over the first 80 % of swing1, engine/pose.rs).
    fn swing_foot(&self, s: Side, n: f64, t: f64) -> FootPose {
        let w = &self.data;
        let tom = w.phases.tom;
        let [ax, ay] = w.ankle.at(t);
        let end = 1.0 + tom;
        let off = w.stance_pitch(end) - w.stance_meta(end);
        let x = ((t - tom) / (TOES_STRAIGHT * (1.0 - tom))).clamp(0.0, 1.0);
        let rule = off * 0.5 * (1.0 + (std::f64::consts::PI * x).cos());
        // the toes bend at least so far that their tip stays above the floor by half what the
        // ball has risen since toe-off: a prototype whose foot is shorter (no toes) lifts its
        // ball close over the floor, and toes straightening there would drag their tip along
        // it. From the rise, not the ball's height: at toe-off the tip is on the floor with the
        // ball at bt sin μ4 over it (on klaw's walks 44 mm), and a bound of half the ball's
        // height lifted the tip 22–24 mm in that instant (`tests/kinematic_figure.rs`)
        let ball = |t: f64| {
            let ay = w.ankle.at(t)[1];
            self.foot.points([0.0, ay], w.f3.at(t), 0.0).meta[1].max(0.0)
        };
        let f3 = w.f3.at(t);
        let l13 = self.foot.l13;
        let t6 = match l13 > 0.0 {
            true => {
                let lowest = 0.5 * (ball(t) + ball(tom));
                rule.max(f3 - (lowest / l13).min(1.0).asin())
            }
            false => rule,
        };
        // the toe above klaw's rising swing floor
        let u = ((t - tom) / (1.0 - tom)).clamp(0.0, 1.0);
        let floor = crate::kinematics::foot::swing_floor(self.attrs.toe_clearance, u);
        let (pitch, _) = self.foot.clear_pitch(f3, [0.0, ay], t6, floor);
        self.foot_at(s, [n + ax, ay], pitch, t6)
    }

    /// The step's [`HipDrop`]: the legs' needs (the hip on H, the knee bent at least
    /// [`KNEE_MIN`]) at [`DROP_SAMPLES`] + 1 instants and at every sample of the walk data, the
    /// stance on either side, and the least concave function above them. Err: a leg that cannot
    /// reach its ankle even across the floor.
    fn planned_drop(&self) -> Result<HipDrop, GeneralizeError> {
        let w = &self.data;
        let (l3, l4) = (self.body.l3, self.body.l4);
        let reach = (l3 * l3 + l4 * l4 + 2.0 * l3 * l4 * KNEE_MIN.cos()).sqrt();
        let mut times: Vec<f64> = (0..=DROP_SAMPLES)
            .map(|i| i as f64 / DROP_SAMPLES as f64)
            .collect();
        let stance = [&w.f1.t, &w.f2.t, &w.meta.t];
        for ts in [&w.hip.t, &w.ankle.t, &w.f3.t, &w.trunk.t]
            .into_iter()
            .chain(stance)
        {
            // the stance foot's timeline runs to 1 + TOM: past 1 it is the hind foot's
            times.extend(ts.iter().map(|&t| if t > 1.0 { t - 1.0 } else { t }));
        }
        let p = w.phases;
        times.extend([p.tom, p.fgm, p.heel_off, p.mom - 1.0]);
        times.retain(|t| (0.0..=1.0).contains(t));
        times.sort_by(f64::total_cmp);
        times.dedup();
        let half = self.body.l0 / 2.0;
        let mut needs = Vec::with_capacity(times.len());
        for &t in &times {
            let mut most: f64 = 0.0;
            for (index, side) in [(0, Side::Right), (1, Side::Left)] {
                let upper = self.upper(side, 0.0, t);
                let swing = (t > p.tom).then(|| self.swing_foot(side.other(), 0.0, t));
                let feet = [
                    (side, self.on_floor(side, 0.0, t, DVec3::ZERO).0),
                    match swing {
                        Some(f) => (side.other(), f),
                        None => {
                            let at = (-w.step_length_before, 1.0 + t);
                            (
                                side.other(),
                                self.on_floor(side.other(), at.0, at.1, DVec3::ZERO).0,
                            )
                        }
                    },
                ];
                for (s, foot) in feet {
                    let hip = hip_joint(&upper, s, half);
                    let need = self
                        .need_within(hip, foot.ankle, reach)
                        .map_err(|distance| GeneralizeError::Stretched {
                            side: s.name(),
                            step: index,
                            t,
                            distance,
                            length: self.body.l1,
                        })?;
                    most = most.max(need);
                }
            }
            needs.push((t, most));
        }
        Ok(HipDrop::above(&needs))
    }

    /// How far the hip joint `hip` must come down for `ankle` to lie within `reach` of it (m; 0
    /// when it does; within the leg's own length l1 when `reach` is not reached even across the
    /// floor; Err(the distance) when l1 is not).
    fn need_within(&self, hip: DVec3, ankle: [f64; 3], reach: f64) -> Result<f64, f64> {
        let d = hip - DVec3::from_array(ankle);
        if d.length() <= reach {
            return Ok(0.0);
        }
        let across = d.x * d.x + d.z * d.z;
        if across < reach * reach {
            Ok(d.y - (reach * reach - across).sqrt())
        } else {
            self.need(hip, ankle)
        }
    }

    /// How far the hip joint `hip` must come down for its leg to reach `ankle` (m; 0 when it
    /// does; Err(the distance) when the ankle is farther than the leg across the floor).
    fn need(&self, hip: DVec3, ankle: [f64; 3]) -> Result<f64, f64> {
        let l1 = self.body.l1;
        let d = hip - DVec3::from_array(ankle);
        if d.length() <= l1 {
            return Ok(0.0);
        }
        let across = d.x * d.x + d.z * d.z;
        if across < l1 * l1 {
            Ok(d.y - (l1 * l1 - across).sqrt())
        } else {
            Err(d.length())
        }
    }

    /// The grounded foot of `s` with its N at `n` at t of its timeline, for a leg hanging from
    /// `hip`, and how far the hip must come down for the leg to reach it.
    fn on_floor(&self, s: Side, n: f64, t: f64, hip: DVec3) -> (FootPose, Result<f64, f64>) {
        let w = &self.data;
        let p = w.stance_pitch(t);
        let (a, t6) = grounded(&w.body, n, p, w.stance_meta(t));
        let pose = self.foot_at(s, a, p, t6);
        (pose, self.need(hip, pose.ankle))
    }

    /// The swing foot's heel, ball and toe tip at t of the step with `side` in stance.
    fn swing_points(
        &self,
        index: usize,
        side: Side,
        t: f64,
    ) -> Result<[[f64; 3]; 3], GeneralizeError> {
        Ok(swing_leg(&self.posed(index, side, 0.0, t, 0.0)?.0, side))
    }

    /// Pose the step at `params.check_samples` + 1 instants on either side and check that no
    /// foot point is below the floor by more than `floor_tolerance` (a leg too short to reach is
    /// an error of the pose itself) and that no swing foot slides on it (`check_slides`).
    /// Returns the most the hip came down from H (m).
    pub fn check(&self, params: &GeneralizeParameters) -> Result<f64, GeneralizeError> {
        let (samples, tolerance) = (params.check_samples, params.floor_tolerance);
        let mut most: f64 = 0.0;
        let tom = self.data.phases.tom;
        for (index, side) in [(0, Side::Right), (1, Side::Left)] {
            let mut swing = vec![(tom, self.swing_points(index, side, tom)?)];
            for i in 0..=samples {
                let t = i as f64 / samples as f64;
                let (lm, drop) = self.posed(index, side, 0.0, t, 0.0)?;
                most = most.max(drop);
                for (leg, name) in [(&lm.right, "right"), (&lm.left, "left")] {
                    below_floor(leg, name, index, t, tolerance)?;
                }
                if t > tom {
                    swing.push((t, swing_leg(&lm, side)));
                }
            }
            self.check_slides(index, side, &swing, params)?;
        }
        Ok(most)
    }

    /// The swing foot of the step with `side` in stance: no point of it, while on the floor
    /// (within `floor_tolerance`), farther than `slide_max` from where it met it (at toe-off, or
    /// later); the stance foot is grounded without sliding by construction, the swing foot only
    /// by the data. Each point is checked at the `samples` (instant, points; from toe-off on) and
    /// at the instants it meets or leaves the floor between two of them (found by bisection).
    fn check_slides(
        &self,
        index: usize,
        side: Side,
        samples: &[(f64, [[f64; 3]; 3])],
        params: &GeneralizeParameters,
    ) -> Result<(), GeneralizeError> {
        let points = |t: f64| self.swing_points(index, side, t);
        let on = |p: [f64; 3]| p[1] <= params.floor_tolerance;
        let slide = |t: f64, p: [f64; 3], at: [f64; 3], k: usize| {
            let distance = (p[0] - at[0]).hypot(p[2] - at[2]);
            match distance > params.slide_max {
                true => Err(GeneralizeError::Slides {
                    point: format!("{} {}", side.other().name(), POINT_NAMES[k]),
                    step: index,
                    t,
                    distance,
                    max: params.slide_max,
                }),
                false => Ok(()),
            }
        };
        let (mut t0, mut before) = samples[0];
        let mut anchor = before.map(|p| on(p).then_some(p));
        for &(t, now) in &samples[1..] {
            for k in 0..3 {
                if on(before[k]) != on(now[k]) {
                    // the instant between t0 and t where the point meets or leaves the floor
                    let (mut a, mut b) = (t0, t);
                    for _ in 0..20 {
                        let m = 0.5 * (a + b);
                        match on(points(m)?[k]) == on(before[k]) {
                            true => a = m,
                            false => b = m,
                        }
                    }
                    let at = if on(before[k]) { a } else { b };
                    let p = points(at)?[k];
                    match anchor[k] {
                        Some(q) => slide(at, p, q, k)?,
                        None => anchor[k] = Some(p),
                    }
                }
                match (on(now[k]), anchor[k]) {
                    (true, Some(q)) => slide(t, now[k], q, k)?,
                    _ => anchor[k] = None,
                }
            }
            (t0, before) = (t, now);
        }
        Ok(())
    }
}

/// The heel, ball and toe tip of the swing leg of the step with `side` in stance.
fn swing_leg(lm: &Landmarks, side: Side) -> [[f64; 3]; 3] {
    let leg = if side == Side::Right {
        lm.left
    } else {
        lm.right
    };
    [leg.heel, leg.mtp, leg.toe]
}

/// The foot points in the order `check_slides` reads them.
const POINT_NAMES: [&str; 3] = ["heel", "ball", "toe tip"];

fn below_floor(
    leg: &LegPoints,
    side: &str,
    step: usize,
    t: f64,
    tolerance: f64,
) -> Result<(), GeneralizeError> {
    for (p, point) in [(leg.heel, "heel"), (leg.mtp, "ball"), (leg.toe, "toe tip")] {
        if p[1] < -tolerance {
            return Err(GeneralizeError::BelowFloor {
                point: format!("{side} {point}"),
                step,
                t,
                depth: -p[1],
                tolerance,
            });
        }
    }
    Ok(())
}
