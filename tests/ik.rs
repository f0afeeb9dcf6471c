//! The inverse kinematics of Pronost et al. (src/ik/) on klaw's own walks: the chain's angles
//! are klaw's clinical angles (its forward kinematics reproduces a walk's ankles from them), and
//! the closed loop follows a walk's ankle trajectories within its tolerance at every frame, every
//! angle inside its joint limits.
mod common;

use klaw::figure::clinical::clinical;
use klaw::ik::{Angles, Ik};
use klaw::poulaine::Trajectory;
use klaw::poulaine::validate::chain_angles;

/// The forward kinematics at a walk's clinical angles puts the ankles where the walk has them
/// relative to its pelvis (an independent check of the chain's axes, signs and Euler orders
/// against src/figure/clinical.rs), over a whole gait cycle.
#[test]
fn the_chain_at_a_walks_clinical_angles_reproduces_its_ankles() {
    let body = common::default_body();
    let walk = klaw::Simulation::new(body)
        .velocity(1.3)
        .steps(4)
        .run()
        .unwrap();
    let (poulaine, frames) = Trajectory::from_walk(&walk, 100.0).unwrap();
    let ik = Ik::new(&body);
    for (f, x) in frames.iter().zip(poulaine.targets()) {
        let theta = chain_angles(&clinical(f, &body).unwrap());
        let e = (ik.chain.ankles(&theta) - x).amax();
        assert!(e < 1e-12, "t {}: {e} m", f.time);
    }
}

/// The closed loop on a walk's own ankle trajectories (60 Hz, the paper's rate): at every frame
/// the ankles are within the tolerance (10 µm, far inside the 1 mm), every angle within
/// its limits, and the cycle closes: the first frame follows from the last like any other.
#[test]
fn the_closed_loop_follows_a_walks_ankles_within_the_limits() {
    let (_, poulaine, ik, sol) = solved(1.4, 6);
    assert_eq!(sol.frames.len(), poulaine.time.len());
    for (i, f) in sol.frames.iter().enumerate() {
        assert!(
            f.residual <= ik.params.tolerance,
            "frame {i}: {} m",
            f.residual
        );
        let x = ik.chain.ankles(&f.theta);
        assert!((x - poulaine.targets()[i]).amax() <= 1e-3);
        assert!(ik.model.within_limits(&f.theta), "frame {i}: {:?}", f.theta);
    }
    // cyclic: the step from the last frame to the first is no larger than the largest step
    let steps: Vec<f64> = sol
        .frames
        .windows(2)
        .map(|w| (w[1].theta - w[0].theta).amax())
        .collect();
    let wrap = (sol.frames[0].theta - sol.frames.last().unwrap().theta).amax();
    let largest = steps.iter().cloned().fold(0.0, f64::max);
    assert!(wrap <= largest, "{wrap} vs {largest}");
}

/// The figure posed from the solution: its clinical angles are the chain's (hips, knees,
/// pelvis), no foot goes through the floor and one touches it at every frame, the pelvis
/// advances at the walk's speed, and the exporters take it (CSV, .mot, BVH).
#[test]
fn the_posed_figure_carries_the_angles_and_stands_on_the_floor() {
    let (body, poulaine, _, sol) = solved(1.2, 4);
    let dt = poulaine.uniform_step().unwrap();
    let angles: Vec<Angles> = sol.frames.iter().map(|f| f.theta).collect();
    let attrs = common::default_attributes();
    let frames = klaw::ik::figure::frames((&body, &attrs), &angles, dt, 1.2, 2);
    assert_eq!(frames.len(), 2 * angles.len());
    for (k, f) in frames.iter().enumerate() {
        let c = clinical(f, &body).unwrap();
        let e = (chain_angles(&c) - angles_at(&angles, k)).amax();
        assert!(e < 1e-9, "frame {k}: {e}");
        let lowest = [f.right, f.left]
            .iter()
            .flat_map(|l| [l.heel[1], l.mtp[1], l.toe[1]])
            .fold(f64::INFINITY, f64::min);
        assert!(lowest.abs() < 1e-9, "frame {k}: lowest foot point {lowest}");
        assert!((f.pelvis[0] - 1.2 * f.time).abs() < 1e-12);
    }
    let dir = std::env::temp_dir().join(format!("klaw-ik-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["ik.csv", "ik.mot", "ik.bvh"] {
        let path = dir.join(name);
        let format = klaw::Format::from_path(&path).unwrap();
        klaw::export::write(
            &path,
            format,
            &body,
            1.0 / dt,
            frames.clone(),
            &Default::default(),
        )
        .unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() > 1000);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The figure's steps are numbered as klaw's (the right foot's even, the left's odd), so
/// `klaw evaluate` reads its heel strikes from the step column: each step starts where its
/// foot's ankle is farthest forward of the pelvis (the support's first frame), and the heel
/// strikes of one foot come a cycle apart.
#[test]
fn the_posed_figures_steps_start_on_their_own_foot() {
    let (body, poulaine, _, sol) = solved(1.2, 4);
    let dt = poulaine.uniform_step().unwrap();
    let angles: Vec<Angles> = sol.frames.iter().map(|f| f.theta).collect();
    let n = angles.len();
    let attrs = common::default_attributes();
    let frames = klaw::ik::figure::frames((&body, &attrs), &angles, dt, 1.2, 3);
    let clin: Vec<_> = frames.iter().map(|f| clinical(f, &body).unwrap()).collect();
    let strikes = klaw::analysis::criteria::heel_strikes::from_steps(&clin);
    let front = |x: &dyn Fn(usize) -> f64| (0..n).fold(0, |b, i| if x(i) > x(b) { i } else { b });
    let right = front(&|i| poulaine.right[i][0]);
    let left = front(&|i| poulaine.left[i][0]);
    for (times, k) in [(&strikes.right, right), (&strikes.left, left)] {
        let later: Vec<f64> = times.iter().copied().filter(|&t| t > 0.0).collect();
        assert!(later.len() >= 2, "{strikes:?}");
        for t in &later {
            let i = (t / dt).round() as usize % n;
            assert_eq!(i, k, "{strikes:?}");
        }
    }
}

/// A walk at `v` m/s of the default body (`steps` steps), its poulaine at 60 Hz, the IK and its
/// solution.
fn solved(v: f64, steps: usize) -> (klaw::Body, Trajectory, Ik, klaw::ik::Solution) {
    let body = common::default_body();
    let walk = klaw::Simulation::new(body)
        .velocity(v)
        .steps(steps)
        .run()
        .unwrap();
    let (poulaine, _) = Trajectory::from_walk(&walk, 60.0).unwrap();
    let dt = poulaine.uniform_step().unwrap();
    let ik = Ik::new(&body);
    let sol = ik.solve(&poulaine.targets(), dt, true).unwrap();
    (body, poulaine, ik, sol)
}

fn angles_at(a: &[Angles], k: usize) -> Angles {
    a[k % a.len()]
}

/// Near the straight knee the damped pseudo-inverse's gain is up to 1 / (2λ): a right ankle
/// target 2 cm beyond a straight leg's reach asks for a step of radians, and the primary step
/// (eq. 2) is shortened to `max_step` along its own direction; a small error's step is kept
/// whole (the step J⁺ ΔX computed here independently of the solver).
#[test]
fn the_primary_step_is_bounded_near_the_straight_knee() {
    let body = common::default_body();
    let ik = Ik::new(&body);
    let mut theta = Angles::zeros();
    theta[6] = 1e-3; // right knee all but straight
    let pose = ik.chain.pose(&theta);
    let x = pose.ankles();
    let inverse = klaw::ik::tasks::pseudo_inverse(&pose.jacobian(), ik.params.damping).unwrap();
    for (push, clamped) in [(0.02, true), (1e-4, false)] {
        let mut target = x;
        target[1] -= push; // the right ankle pulled down, away from its hip
        let full = inverse * (target - x);
        let step = ik.problem(&theta, &target, None).base - theta;
        if clamped {
            assert!(full.norm() > 5.0 * ik.params.max_step, "{}", full.norm());
            assert!(
                (step.norm() - ik.params.max_step).abs() < 1e-12,
                "{}",
                step.norm()
            );
            assert!((step.normalize() - full.normalize()).amax() < 1e-12);
        } else {
            assert!((step - full).amax() < 1e-15, "{step}");
        }
    }
}

/// A hyperextended knee's flexed twin (`flexed_knees`) reaches as far: each leg's hip–ankle
/// distance is the same (forward kinematics, both legs, knees −0.05 and −0.3 rad); knees within
/// their limit come back unchanged. A frame solved from a hyperextended posture comes back with
/// both knees flexed and the ankles on their targets.
#[test]
fn a_hyperextended_knee_turns_to_its_flexed_twin() {
    use klaw::ik::solve::flexed_knees;
    let body = common::default_body();
    let ik = Ik::new(&body);
    let theta = Angles::from_row_slice(&[
        0.1, 0.05, -0.04, 0.3, 0.02, 0.1, -0.05, -0.2, -0.03, 0.05, -0.3,
    ]);
    let twin = flexed_knees(theta);
    assert_eq!((twin[6], twin[10]), (0.05, 0.3));
    let (a, b) = (ik.chain.pose(&theta), ik.chain.pose(&twin));
    for (p, q) in [(&a.right, &b.right), (&a.left, &b.left)] {
        let (d, e) = ((p.ankle - p.hip).length(), (q.ankle - q.hip).length());
        assert!((d - e).abs() < 1e-12, "{d} {e}");
        assert!(
            (p.ankle - q.ankle).length() > 1e-3,
            "the twin is another posture"
        );
    }
    assert_eq!(flexed_knees(twin), twin);
    let target = ik.chain.pose(&twin).ankles();
    let f = ik.step(&theta, &target, None, 0, 0.0).unwrap();
    assert!(f.residual <= ik.params.tolerance);
    assert!(f.theta[6] >= 0.0 && f.theta[10] >= 0.0, "{}", f.theta);
}
