//! Export checks (issue items 7 and 8) on synthetic figures built here from chosen angles by this
//! file's own forward kinematics, independent of the engine and of `klaw::figure::skeleton`:
//! - the clinical angles point the anatomical way (geometric checks on the points alone);
//! - landmarks → clinical angles returns the chosen angles (property test);
//! - BVH written, parsed back and run through forward kinematics reproduces every joint and
//!   contact point (hip, knee, ankle, heel, mtp, toe; shoulder, elbow, wrist) to ≤ 1 mm;
//! - the `.mot` coordinates, put through gait2392's joint definitions as read from the model file,
//!   point the thigh and shank where the landmarks do;
//! - the CSV columns and the cycle averaging against an analytic periodic signal;
//! - bad input gives typed errors and no file.
use std::f64::consts::PI;
use std::fs;
use std::path::Path;

use glam::{DMat3, DVec3};
use klaw::analysis::cycle;
use klaw::error::Error;
use klaw::export::{self, ExportError, Format, OpenSimModel, Options, bvh};
use klaw::figure::clinical::{self, Clinical};
use klaw::figure::skeleton::Skeleton;
use klaw::figure::{ArmAngles, FigureError, Landmarks, LegPoints};
use klaw::model::InputError;
use klaw::model::body::Body;
use proptest::prelude::*;

mod common;

use common::default_body as body;

fn rx(a: f64) -> DMat3 {
    DMat3::from_rotation_x(a)
}
fn ry(a: f64) -> DMat3 {
    DMat3::from_rotation_y(a)
}
fn rz(a: f64) -> DMat3 {
    DMat3::from_rotation_z(a)
}

/// Chosen angles of one leg (rad, clinical signs).
#[derive(Clone, Copy, Debug, Default)]
struct LegQ {
    hip_flexion: f64,
    hip_adduction: f64,
    hip_rotation: f64,
    knee_flexion: f64,
    dorsiflexion: f64,
    inversion: f64,
    foot_adduction: f64,
    mtp: f64,
}

/// A chosen pose of the whole figure.
#[derive(Clone, Copy, Debug, Default)]
struct Pose {
    time: f64,
    pelvis: [f64; 3],
    tilt: f64,
    list: f64,
    rotation: f64,
    lumbar: [f64; 3], // extension, bending, rotation
    neck: f64,
    right: LegQ,
    left: LegQ,
    right_arm: ArmAngles,
    left_arm: ArmAngles,
}

/// Points of the head, this file's own forward kinematics: the neck base (0, spine, 0) in the
/// thorax, and a point `FACE` ahead of the head at the level of its base (the head's frame
/// R_thorax · R_y(neck), as `Landmarks` defines it).
struct HeadPoints {
    base: DVec3,
    face: DVec3,
}

/// The face point in the head's frame: 0.1 m ahead of the neck's top.
fn face_offset(b: &Body) -> DVec3 {
    DVec3::new(0.1, b.figure.neck, 0.0)
}

/// The head of the landmarks `lm` (from their pelvis, lumbar and neck angles).
fn head_points(lm: &Landmarks, b: &Body) -> HeadPoints {
    let rt = ry(lm.pelvis_rotation)
        * rx(-lm.pelvis_list)
        * rz(-lm.pelvis_tilt)
        * ry(lm.lumbar_rotation)
        * rx(lm.lumbar_bending)
        * rz(lm.lumbar_extension);
    let base = v(lm.pelvis) + rt * DVec3::new(0.0, b.figure.spine, 0.0);
    HeadPoints {
        base,
        face: base + rt * ry(lm.neck_rotation) * face_offset(b),
    }
}

/// Points of the arms, this file's own forward kinematics.
struct ArmPoints {
    shoulder: DVec3,
    elbow: DVec3,
    wrist: DVec3,
}

/// The figure of `pose`, following the conventions the issue and `Landmarks` state: pelvis
/// R = R_y(rot) R_x(−list) R_z(−tilt), hips at ± R (0, 0, l0/2), thorax R · R_y R_x R_z (lumbar);
/// each joint R_z(flexion-like) R_x(±adduction-like) R_y(±rotation) (right +, left −), knee
/// R_z(−flexion); the segment lengths of the body table.
fn figure(pose: &Pose, b: &Body) -> (Landmarks, [ArmPoints; 2]) {
    let h12 = (b.l12 * b.l12 - b.l9 * b.l9).sqrt();
    let pelvis = DVec3::from_array(pose.pelvis);
    let rp = ry(pose.rotation) * rx(-pose.list) * rz(-pose.tilt);
    let [le, lb, lr] = pose.lumbar;
    let rt = rp * ry(lr) * rx(lb) * rz(le);
    let leg = |q: &LegQ, s: f64| {
        let hip = pelvis + rp * DVec3::new(0.0, 0.0, s * b.l0 / 2.0);
        let thigh = rp * rz(q.hip_flexion) * rx(s * q.hip_adduction) * ry(s * q.hip_rotation);
        let knee = hip + thigh * DVec3::new(0.0, -b.l3, 0.0);
        let shank = thigh * rz(-q.knee_flexion);
        let ankle = knee + shank * DVec3::new(0.0, -b.l4, 0.0);
        let foot = shank * rz(q.dorsiflexion) * rx(s * q.inversion) * ry(s * q.foot_adduction);
        let mtp = ankle + foot * DVec3::new(h12, -b.l9, 0.0);
        LegPoints {
            hip: hip.to_array(),
            knee: knee.to_array(),
            ankle: ankle.to_array(),
            heel: (ankle + foot * DVec3::new(-b.l8, -b.l9, 0.0)).to_array(),
            mtp: mtp.to_array(),
            toe: (mtp + foot * rz(q.mtp) * DVec3::new(b.l13, 0.0, 0.0)).to_array(),
            knee_axis: (thigh * DVec3::Z).to_array(),
        }
    };
    let f = &b.figure;
    let arm = |a: &ArmAngles, s: f64| {
        let shoulder = pelvis + rt * DVec3::new(0.0, f.spine, s * f.shoulder_width / 2.0);
        let upper = rt * rz(a.shoulder_flexion) * rx(-s * a.shoulder_abduction);
        let elbow = shoulder + upper * DVec3::new(0.0, -f.upper_arm, 0.0);
        let wrist = elbow + upper * rz(a.elbow_flexion) * DVec3::new(0.0, -f.forearm, 0.0);
        ArmPoints {
            shoulder,
            elbow,
            wrist,
        }
    };
    let lm = Landmarks {
        time: pose.time,
        step: 0,
        pelvis: pose.pelvis,
        pelvis_tilt: pose.tilt,
        pelvis_list: pose.list,
        pelvis_rotation: pose.rotation,
        lumbar_extension: le,
        lumbar_bending: lb,
        lumbar_rotation: lr,
        neck_rotation: pose.neck,
        right: leg(&pose.right, 1.0),
        left: leg(&pose.left, -1.0),
        right_arm: pose.right_arm,
        left_arm: pose.left_arm,
    };
    (lm, [arm(&pose.right_arm, 1.0), arm(&pose.left_arm, -1.0)])
}

fn deg(d: f64) -> f64 {
    d.to_radians()
}

/// A gait-like pose at time t: sinusoids of the published ranges' size, 1 s cycle, walking at
/// 1.4 m/s with vertical bob and sideways sway. Every angle moves, with different phases.
fn walk_pose(t: f64) -> Pose {
    let w = 2.0 * PI * t;
    let leg = |ph: f64| LegQ {
        hip_flexion: deg(10.0 + 25.0 * (w + ph).cos()),
        hip_adduction: deg(4.0 * (w + ph + 0.3).sin()),
        hip_rotation: deg(5.0 * (w + ph + 1.0).sin()),
        knee_flexion: deg(30.0 - 28.0 * (w + ph - 0.8).cos()),
        dorsiflexion: deg(5.0 + 12.0 * (w + ph + 2.0).sin()),
        inversion: deg(4.0 * (w + ph + 0.5).cos()),
        foot_adduction: deg(-6.0 + 3.0 * (w + ph).sin()),
        mtp: deg(15.0 + 15.0 * (w + ph + 2.5).sin()),
    };
    let arm = |ph: f64| ArmAngles {
        shoulder_flexion: deg(17.0 * (w + ph).cos()),
        shoulder_abduction: deg(5.0 + 2.0 * (w + ph).sin()),
        elbow_flexion: deg(25.0 + 10.0 * (w + ph).cos()),
    };
    Pose {
        time: t,
        pelvis: [1.4 * t, 0.95 + 0.02 * (2.0 * w).cos(), 0.02 * w.sin()],
        tilt: deg(9.0 + 2.0 * (2.0 * w).sin()),
        list: deg(5.0 * w.sin()),
        rotation: deg(6.0 * w.cos()),
        lumbar: [
            deg(-3.0 + (2.0 * w).cos()),
            deg(-5.0 * w.sin()),
            deg(-10.0 * w.cos()),
        ],
        neck: deg(15.0 * (w + 0.7).sin()),
        right: leg(0.0),
        left: leg(PI),
        right_arm: arm(PI),
        left_arm: arm(0.0),
    }
}

fn walk(fps: f64, seconds: f64) -> Vec<(Pose, Landmarks)> {
    let b = body();
    let n = (seconds * fps).round() as usize;
    (0..n)
        .map(|i| {
            let p = walk_pose(i as f64 / fps);
            let (lm, _) = figure(&p, &b);
            (p, lm)
        })
        .collect()
}

fn v(p: [f64; 3]) -> DVec3 {
    DVec3::from_array(p)
}

// ---------------------------------------------------------------------------------------------
// clinical angles

/// Each positive clinical angle moves the points the anatomical way; checked on the points of
/// this file's figure alone, so the conventions `figure` encodes are the clinical ones.
#[test]
fn positive_angles_are_anatomical() {
    let b = body();
    let one = |f: &dyn Fn(&mut Pose)| {
        let mut p = Pose {
            pelvis: [0.0, 1.0, 0.0],
            ..Pose::default()
        };
        f(&mut p);
        figure(&p, &b)
    };
    let a = deg(20.0);
    let (lm, _) = one(&|p| p.right.hip_flexion = a);
    assert!(
        lm.right.knee[0] > lm.right.hip[0] + 0.1,
        "hip flexion: knee forward"
    );
    let (lm, _) = one(&|p| {
        p.right.hip_adduction = a;
        p.left.hip_adduction = a
    });
    assert!(
        lm.right.knee[2] < lm.right.hip[2] - 0.1,
        "right adduction: knee to the midline"
    );
    assert!(
        lm.left.knee[2] > lm.left.hip[2] + 0.1,
        "left adduction: knee to the midline"
    );
    let (lm, _) = one(&|p| {
        p.right.hip_rotation = a;
        p.left.hip_rotation = a
    });
    assert!(
        lm.right.toe[2] < lm.right.heel[2] - 0.05,
        "right internal rotation: toe-in"
    );
    assert!(
        lm.left.toe[2] > lm.left.heel[2] + 0.05,
        "left internal rotation: toe-in"
    );
    let (lm, _) = one(&|p| p.right.knee_flexion = a);
    assert!(
        lm.right.ankle[0] < lm.right.knee[0] - 0.1,
        "knee flexion: ankle behind"
    );
    let (lm, _) = one(&|p| p.right.dorsiflexion = a);
    assert!(
        lm.right.mtp[1] > lm.right.heel[1] + 0.03,
        "dorsiflexion: forefoot up"
    );
    let (lm, _) = one(&|p| {
        p.right.inversion = a;
        p.left.inversion = a
    });
    // the sole under the ankle swings medially when the sole turns to face the midline
    assert!(
        lm.right.heel[2] < lm.right.ankle[2] - 0.01,
        "right inversion"
    );
    assert!(lm.left.heel[2] > lm.left.ankle[2] + 0.01, "left inversion");
    let (lm, _) = one(&|p| {
        p.right.foot_adduction = a;
        p.left.foot_adduction = a
    });
    assert!(
        lm.right.toe[2] < lm.right.heel[2] - 0.05,
        "right foot adduction: toe-in"
    );
    assert!(
        lm.left.toe[2] > lm.left.heel[2] + 0.05,
        "left foot adduction: toe-in"
    );
    let (lm, _) = one(&|p| p.right.mtp = a);
    assert!(
        lm.right.toe[1] > lm.right.mtp[1] + 0.01,
        "mtp dorsiflexion: toe up"
    );
    let (lm, arms) = one(&|p| p.tilt = a);
    assert!(
        arms[0].shoulder.x > 0.1,
        "anterior tilt: trunk forward {}",
        lm.pelvis[0]
    );
    let (lm, _) = one(&|p| p.list = a);
    assert!(
        lm.right.hip[1] > lm.left.hip[1] + 0.05,
        "list +: right side up"
    );
    let (lm, _) = one(&|p| p.rotation = a);
    assert!(
        lm.right.hip[0] > lm.left.hip[0] + 0.05,
        "rotation +: right side forward"
    );
    let (_, arms) = one(&|p| p.lumbar[0] = a);
    assert!(arms[0].shoulder.x < -0.1, "lumbar extension: trunk back");
    let (_, arms) = one(&|p| p.lumbar[1] = a);
    assert!(
        arms[0].shoulder.y < arms[1].shoulder.y - 0.05,
        "bending right: right shoulder down"
    );
    let (_, arms) = one(&|p| p.lumbar[2] = a);
    assert!(
        arms[0].shoulder.x > arms[1].shoulder.x + 0.05,
        "lumbar rotation: right shoulder forward"
    );
    let (lm, _) = one(&|p| p.neck = a);
    let head = head_points(&lm, &b);
    assert!(
        head.face.z < head.base.z - 0.03,
        "neck rotation +: the face turns to the left (−z)"
    );
    let (_, arms) = one(&|p| {
        p.right_arm.shoulder_flexion = a;
        p.right_arm.elbow_flexion = a;
        p.left_arm.shoulder_abduction = a
    });
    assert!(
        arms[0].elbow.x > arms[0].shoulder.x + 0.05,
        "shoulder flexion: elbow forward"
    );
    assert!(
        arms[0].wrist.x > arms[0].elbow.x + 0.1,
        "elbow flexion: wrist forward"
    );
    assert!(
        arms[1].elbow.z < arms[1].shoulder.z - 0.05,
        "left abduction: elbow outwards"
    );
}

fn check_clinical(c: &Clinical, p: &Pose, tol: f64) {
    let near = |name: &str, got: f64, want: f64| {
        assert!((got - want).abs() < tol, "{name}: got {got}, want {want}");
    };
    near("tilt", c.pelvis_tilt, p.tilt);
    near("list", c.pelvis_list, p.list);
    near("rotation", c.pelvis_rotation, p.rotation);
    near("lumbar_extension", c.lumbar_extension, p.lumbar[0]);
    near("lumbar_bending", c.lumbar_bending, p.lumbar[1]);
    near("lumbar_rotation", c.lumbar_rotation, p.lumbar[2]);
    near("neck_rotation", c.neck_rotation, p.neck);
    for (l, q) in [(&c.right, &p.right), (&c.left, &p.left)] {
        near("hip flexion", l.hip.flexion, q.hip_flexion);
        near("hip adduction", l.hip.adduction, q.hip_adduction);
        near("hip rotation", l.hip.rotation, q.hip_rotation);
        near("knee flexion", l.knee.flexion, q.knee_flexion);
        near("knee varus", l.knee.adduction, 0.0);
        near("knee rotation", l.knee.rotation, 0.0);
        near("dorsiflexion", l.ankle.flexion, q.dorsiflexion);
        near("inversion", l.ankle.adduction, q.inversion);
        near("foot adduction", l.ankle.rotation, q.foot_adduction);
        near("mtp", l.mtp.flexion, q.mtp);
    }
    for (a, q) in [(&c.right_arm, &p.right_arm), (&c.left_arm, &p.left_arm)] {
        near("shoulder flexion", a.shoulder.flexion, q.shoulder_flexion);
        near(
            "shoulder abduction",
            -a.shoulder.adduction,
            q.shoulder_abduction,
        );
        near("elbow", a.elbow.flexion, q.elbow_flexion);
    }
}

/// A neck rotation of 0.3 rad is read back as 0.3 by both ways to the clinical angles (the
/// frames' and the landmarks' own), and changes no other angle: the head is a leaf of the
/// skeleton.
#[test]
fn neck_rotation_is_its_own_joint() {
    let b = body();
    let mut p = walk_pose(0.37);
    p.neck = 0.0;
    let (still, _) = figure(&p, &b);
    p.neck = 0.3;
    let (turned, _) = figure(&p, &b);
    let from_frames = |lm: &Landmarks| Skeleton::new(lm, &b).unwrap().clinical(lm.time, lm.step);
    let direct = |lm: &Landmarks| clinical::clinical(lm, &b).unwrap();
    for way in [&from_frames as &dyn Fn(&Landmarks) -> Clinical, &direct] {
        let (c0, c1) = (way(&still), way(&turned));
        assert_eq!(c0.neck_rotation, 0.0);
        assert!(
            (c1.neck_rotation - 0.3).abs() < 1e-15,
            "{}",
            c1.neck_rotation
        );
        assert_eq!(
            Clinical {
                neck_rotation: 0.0,
                ..c1
            },
            c0,
            "the other joints"
        );
    }
}

fn leg_q() -> impl Strategy<Value = LegQ> {
    (
        (-0.5..1.1f64, -0.35..0.35f64, -0.5..0.5f64, 0.0..1.6f64),
        (-0.5..0.5f64, -0.3..0.3f64, -0.3..0.3f64, -0.3..0.9f64),
    )
        .prop_map(|((hf, ha, hr, k), (d, i, fa, m))| LegQ {
            hip_flexion: hf,
            hip_adduction: ha,
            hip_rotation: hr,
            knee_flexion: k,
            dorsiflexion: d,
            inversion: i,
            foot_adduction: fa,
            mtp: m,
        })
}

fn arm_q() -> impl Strategy<Value = ArmAngles> {
    (-0.8..0.8f64, -0.2..0.6f64, 0.0..1.5f64).prop_map(|(f, a, e)| ArmAngles {
        shoulder_flexion: f,
        shoulder_abduction: a,
        elbow_flexion: e,
    })
}

fn pose_q() -> impl Strategy<Value = Pose> {
    (
        (-5.0..5.0f64, 0.7..1.1f64, -0.3..0.3f64),
        (-0.4..0.4f64, -0.3..0.3f64, -0.5..0.5f64),
        (-0.4..0.4f64, -0.3..0.3f64, -0.5..0.5f64),
        (leg_q(), leg_q(), arm_q(), arm_q()),
        -1.2..1.2f64,
    )
        .prop_map(
            |((x, y, z), (t, l, r), (le, lb, lr), (rl, ll, ra, la), neck)| Pose {
                time: 0.0,
                pelvis: [x, y, z],
                tilt: t,
                list: l,
                rotation: r,
                lumbar: [le, lb, lr],
                neck,
                right: rl,
                left: ll,
                right_arm: ra,
                left_arm: la,
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// angles → this file's forward kinematics → landmarks → `clinical::clinical` → the same
    /// angles.
    #[test]
    fn clinical_angles_round_trip(p in pose_q()) {
        let b = body();
        let (lm, _) = figure(&p, &b);
        let c = clinical::clinical(&lm, &b).unwrap();
        check_clinical(&c, &p, 1e-9);
    }

    /// angles → landmarks → BVH file → parse → forward kinematics reproduces the landmarks.
    #[test]
    fn bvh_round_trips_random_poses(p in pose_q()) {
        let b = body();
        let (lm, arms) = figure(&p, &b);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("p.bvh");
        export::write(&path, Format::Bvh, &b, 100.0, [lm], &Options::default()).unwrap();
        let parsed = bvh::parse(&fs::read_to_string(&path).unwrap(), &path).unwrap();
        let err = bvh_error(&parsed, 0, &lm, &arms, &b, false);
        prop_assert!(err < 1e-9, "FK error {err} m");
    }
}

// ---------------------------------------------------------------------------------------------
// BVH

/// The largest distance (m) between a BVH frame's forward kinematics and the figure: hips,
/// knees, ankles, heels (from the foot joint's frame and the body's l8, l9), mtps, toe tips (End
/// Site), shoulders, elbows, wrists, the pelvis centre, the neck base and the face point of
/// [`head_points`] (from the `Neck` joint's frame: it shows the neck rotation).
fn bvh_error(
    bvh: &bvh::Bvh,
    frame: usize,
    lm: &Landmarks,
    arms: &[ArmPoints; 2],
    b: &Body,
    in_place: bool,
) -> f64 {
    let pose = bvh.pose(frame).unwrap();
    let at = |name: &str| {
        let i = bvh.joint(name).unwrap_or_else(|| panic!("no joint {name}"));
        &pose[i]
    };
    let shift = if in_place {
        DVec3::new(lm.pelvis[0], 0.0, 0.0)
    } else {
        DVec3::ZERO
    };
    let world = |p: DVec3| bvh::from_bvh(p) + shift;
    let mut worst: f64 = world(at("Hips").position).distance(v(lm.pelvis));
    let head = head_points(lm, b);
    let neck = at("Neck");
    let face = neck.position + neck.rotation * bvh::to_bvh(face_offset(b));
    worst = worst
        .max(world(neck.position).distance(head.base))
        .max(world(face).distance(head.face));
    for (side, pts, arm) in [("Right", &lm.right, &arms[0]), ("Left", &lm.left, &arms[1])] {
        let foot = at(&format!("{side}Foot"));
        let heel = foot.position + foot.rotation * bvh::to_bvh(DVec3::new(-b.l8, -b.l9, 0.0));
        let toe = at(&format!("{side}ToeBase"));
        let checks = [
            (at(&format!("{side}UpLeg")).position, v(pts.hip)),
            (at(&format!("{side}Leg")).position, v(pts.knee)),
            (foot.position, v(pts.ankle)),
            (heel, v(pts.heel)),
            (toe.position, v(pts.mtp)),
            (toe.end_site.unwrap(), v(pts.toe)),
            (at(&format!("{side}Arm")).position, arm.shoulder),
            (at(&format!("{side}ForeArm")).position, arm.elbow),
            (at(&format!("{side}Hand")).position, arm.wrist),
        ];
        for (got, want) in checks {
            worst = worst.max(world(got).distance(want));
        }
    }
    worst
}

#[test]
fn bvh_forward_kinematics_reproduces_a_walk() {
    let b = body();
    let frames = walk(100.0, 2.0);
    let dir = tempfile::tempdir().unwrap();
    for in_place in [false, true] {
        let path = dir.path().join("walk.bvh");
        let opts = Options {
            in_place,
            ..Options::default()
        };
        export::write(
            &path,
            Format::Bvh,
            &b,
            100.0,
            frames.iter().map(|f| f.1),
            &opts,
        )
        .unwrap();
        let text = fs::read_to_string(&path).unwrap();
        let parsed = bvh::parse(&text, &path).unwrap();
        assert_eq!(parsed.frames.len(), frames.len());
        assert!((parsed.frame_time - 0.01).abs() < 1e-12);
        let names: Vec<&str> = parsed.joints.iter().map(|j| j.name.as_str()).collect();
        for n in [
            "Hips",
            "Spine",
            "Chest",
            "Neck",
            "Head",
            "LeftShoulder",
            "LeftArm",
            "LeftForeArm",
            "LeftHand",
            "RightShoulder",
            "RightArm",
            "RightForeArm",
            "RightHand",
            "LeftUpLeg",
            "LeftLeg",
            "LeftFoot",
            "LeftToeBase",
            "RightUpLeg",
            "RightLeg",
            "RightFoot",
            "RightToeBase",
        ] {
            assert!(names.contains(&n), "missing joint {n}");
        }
        let mut worst: f64 = 0.0;
        for (i, (p, lm)) in frames.iter().enumerate() {
            let (_, arms) = figure(p, &b);
            worst = worst.max(bvh_error(&parsed, i, lm, &arms, &b, in_place));
        }
        println!(
            "BVH forward kinematics, in_place = {in_place}: max error {:.3e} m",
            worst
        );
        assert!(worst <= 1e-3, "max FK error {worst} m");
        // far tighter in fact: the file's numbers round-trip, what is left is round-off
        assert!(worst <= 1e-9, "max FK error {worst} m");
        if !in_place && let Ok(dir) = std::env::var("KLAW_BVH_OUT") {
            write_blender_check(Path::new(&dir), &text, &frames, &b);
        }
        if in_place {
            let z = parsed.joints[0].first_channel + 2;
            assert!(parsed.frames.iter().all(|f| f[z] == 0.0));
        }
    }
}

/// For the Blender check (`docs/export.md`): the BVH and, per frame, where the joints must be
/// (BVH axes), from this file's figure: joint heads and the toe tips.
fn write_blender_check(dir: &Path, bvh_text: &str, frames: &[(Pose, Landmarks)], b: &Body) {
    fs::write(dir.join("walk.bvh"), bvh_text).unwrap();
    let mut json = String::from("[");
    for (i, (p, lm)) in frames.iter().enumerate() {
        let (_, arms) = figure(p, b);
        let mut items = Vec::new();
        let mut put = |name: &str, w: DVec3| {
            let q = bvh::to_bvh(w);
            items.push(format!("\"{name}\": [{}, {}, {}]", q.x, q.y, q.z));
        };
        put("Hips", v(lm.pelvis));
        for (side, pts, arm) in [("Right", &lm.right, &arms[0]), ("Left", &lm.left, &arms[1])] {
            put(&format!("{side}UpLeg"), v(pts.hip));
            put(&format!("{side}Leg"), v(pts.knee));
            put(&format!("{side}Foot"), v(pts.ankle));
            put(&format!("{side}ToeBase"), v(pts.mtp));
            put(&format!("{side}ToeBase.tail"), v(pts.toe));
            put(&format!("{side}Arm"), arm.shoulder);
            put(&format!("{side}ForeArm"), arm.elbow);
            put(&format!("{side}Hand"), arm.wrist);
        }
        let sep = if i == 0 { "" } else { "," };
        json.push_str(&format!("{sep}\n{{{}}}", items.join(", ")));
    }
    json.push_str("\n]\n");
    fs::write(dir.join("expected.json"), json).unwrap();
}

/// The rest offsets are the body table's, in the file's axes (X left, Y up, Z forward).
#[test]
fn bvh_offsets_are_the_body_table() {
    let b = body();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("o.bvh");
    let frames = walk(100.0, 0.05);
    export::write(
        &path,
        Format::Bvh,
        &b,
        100.0,
        frames.iter().map(|f| f.1),
        &Options::default(),
    )
    .unwrap();
    let parsed = bvh::parse(&fs::read_to_string(&path).unwrap(), &path).unwrap();
    let off = |n: &str| parsed.joints[parsed.joint(n).unwrap()].offset;
    let h12 = (b.l12 * b.l12 - b.l9 * b.l9).sqrt();
    let close = |a: DVec3, e: [f64; 3]| (a - v(e)).abs().max_element() < 1e-6;
    assert!(
        close(off("LeftUpLeg"), [b.l0 / 2.0, 0.0, 0.0]),
        "left hip at +X"
    );
    assert!(close(off("RightUpLeg"), [-b.l0 / 2.0, 0.0, 0.0]));
    assert!(close(off("RightLeg"), [0.0, -b.l3, 0.0]));
    assert!(close(off("RightFoot"), [0.0, -b.l4, 0.0]));
    assert!(
        close(off("RightToeBase"), [0.0, -b.l9, h12]),
        "mtp ahead (+Z), below"
    );
    let toe = parsed.joints[parsed.joint("RightToeBase").unwrap()]
        .end_site
        .unwrap();
    assert!(close(toe, [0.0, 0.0, b.l13]));
    assert!(close(
        off("LeftArm"),
        [b.figure.shoulder_width / 2.0, 0.0, 0.0]
    ));
    let hips = &parsed.joints[0];
    assert_eq!(hips.offset, DVec3::ZERO);
    assert_eq!(hips.channels.len(), 6);
}

/// At the anatomical zero every channel is 0; a single clinical angle shows up in its channel
/// with the sign of `docs/export.md`'s table.
#[test]
fn bvh_channels_carry_the_clinical_angles() {
    let b = body();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("c.bvh");
    let a = deg(20.0);
    let mut poses = vec![Pose {
        pelvis: [0.0, 1.0, 0.0],
        ..Pose::default()
    }];
    let mut next = |f: &dyn Fn(&mut Pose)| {
        let mut p = poses[0];
        p.time = poses.len() as f64 / 100.0;
        f(&mut p);
        poses.push(p);
    };
    next(&|p| p.right.hip_flexion = a);
    next(&|p| p.right.knee_flexion = a);
    next(&|p| p.left.hip_adduction = a);
    next(&|p| p.right.dorsiflexion = a);
    next(&|p| p.tilt = a);
    next(&|p| p.right_arm.elbow_flexion = a);
    next(&|p| p.neck = a);
    let lms: Vec<Landmarks> = poses.iter().map(|p| figure(p, &b).0).collect();
    export::write(&path, Format::Bvh, &b, 100.0, lms, &Options::default()).unwrap();
    let parsed = bvh::parse(&fs::read_to_string(&path).unwrap(), &path).unwrap();
    let ch = |frame: usize, joint: &str, k: usize| {
        parsed.frames[frame][parsed.joints[parsed.joint(joint).unwrap()].first_channel + k]
    };
    assert!(
        parsed.frames[0][3..].iter().all(|x| x.abs() < 1e-9),
        "rest = all zero"
    );
    // Xrotation is about +X (the figure's left): a hip flexion is a negative Xrotation, a knee
    // flexion a positive one
    assert!((ch(1, "RightUpLeg", 0) + 20.0).abs() < 1e-6);
    assert!((ch(2, "RightLeg", 0) - 20.0).abs() < 1e-6);
    // Zrotation about +Z (forward): left hip adduction moves the knee to −X (the midline)
    assert!((ch(3, "LeftUpLeg", 1) + 20.0).abs() < 1e-6);
    assert!((ch(4, "RightFoot", 0) + 20.0).abs() < 1e-6);
    // the root's last channel is Xrotation = anterior tilt
    assert!((ch(5, "Hips", 5) - 20.0).abs() < 1e-6);
    assert!((ch(6, "RightForeArm", 0) + 20.0).abs() < 1e-6);
    // the neck's Yrotation (about +Y = up) is the neck rotation, its other channels 0
    assert!((ch(7, "Neck", 2) - 20.0).abs() < 1e-6);
    assert!(ch(7, "Neck", 0) == 0.0 && ch(7, "Neck", 1) == 0.0);
    assert!(
        (0..7).all(|f| (0..3).all(|k| ch(f, "Neck", k) == 0.0)),
        "no neck rotation: the Neck channels are 0 exactly"
    );
}

// ---------------------------------------------------------------------------------------------
// OpenSim

fn read_storage(path: &Path) -> (Vec<String>, Vec<String>, Vec<Vec<f64>>) {
    let text = fs::read_to_string(path).unwrap();
    let (head, body) = text.split_once("endheader\n").unwrap();
    let header: Vec<String> = head.lines().map(str::to_string).collect();
    let mut lines = body.lines();
    let names: Vec<String> = lines
        .next()
        .unwrap()
        .split('\t')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split('\t').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    (header, names, rows)
}

/// Writes a walk as `.mot`, reads it back, and puts the coordinates through gait2392's joints as
/// its `.osim` defines them (ground_pelvis: tilt z, list x, rotation y; hip_r: flexion z,
/// adduction x, rotation y; hip_l: z, −x, −y; knee: z; back: z, x, y; the femur and tibia run
/// along −y): the thigh, shank and trunk directions must be the landmarks'.
#[test]
fn mot_coordinates_drive_gait2392_like_the_landmarks() {
    let b = body();
    let frames = walk(50.0, 1.0);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("walk.mot");
    export::write(
        &path,
        Format::Mot,
        &b,
        50.0,
        frames.iter().map(|f| f.1),
        &Options::default(),
    )
    .unwrap();
    let (header, names, rows) = read_storage(&path);
    assert_eq!(header[0], "Coordinates");
    assert!(header.contains(&"version=1".to_string()));
    assert!(header.contains(&format!("nRows={}", frames.len())));
    assert!(header.contains(&format!("nColumns={}", names.len())));
    assert!(header.contains(&"inDegrees=yes".to_string()));
    assert_eq!(names[0], "time");
    assert_eq!(rows.len(), frames.len());
    for n in [
        "pelvis_tilt",
        "pelvis_list",
        "pelvis_rotation",
        "pelvis_tx",
        "pelvis_ty",
        "pelvis_tz",
        "hip_flexion_r",
        "hip_adduction_r",
        "hip_rotation_r",
        "knee_angle_r",
        "ankle_angle_r",
        "subtalar_angle_r",
        "mtp_angle_r",
        "hip_flexion_l",
        "hip_adduction_l",
        "hip_rotation_l",
        "knee_angle_l",
        "ankle_angle_l",
        "subtalar_angle_l",
        "mtp_angle_l",
        "lumbar_extension",
        "lumbar_bending",
        "lumbar_rotation",
    ] {
        assert!(names.iter().any(|x| x == n), "missing {n}");
    }
    assert!(
        !names.iter().any(|x| x.starts_with("arm_")),
        "gait2392 has no arms"
    );
    let col = |n: &str| names.iter().position(|x| x == n).unwrap();
    for ((p, lm), row) in frames.iter().zip(&rows) {
        let q = |n: &str| row[col(n)].to_radians();
        let pelvis = rz(q("pelvis_tilt")) * rx(q("pelvis_list")) * ry(q("pelvis_rotation"));
        // gait2392's pelvis origin: 0.0707 m ahead of and 0.0661 m above the hip centres, × H/1.8
        let origin = v(lm.pelvis) + pelvis * DVec3::new(0.0707, 0.0661, 0.0);
        for (k, axis) in ["pelvis_tx", "pelvis_ty", "pelvis_tz"].iter().enumerate() {
            assert!((row[col(axis)] - origin[k]).abs() < 1e-9);
        }
        for (s, pts) in [("r", &lm.right), ("l", &lm.left)] {
            let m = if s == "r" { 1.0 } else { -1.0 };
            let femur = pelvis
                * rz(q(&format!("hip_flexion_{s}")))
                * rx(m * q(&format!("hip_adduction_{s}")))
                * ry(m * q(&format!("hip_rotation_{s}")));
            let tibia = femur * rz(q(&format!("knee_angle_{s}")));
            let thigh = (v(pts.knee) - v(pts.hip)).normalize();
            let shank = (v(pts.ankle) - v(pts.knee)).normalize();
            assert!((femur * DVec3::NEG_Y - thigh).length() < 1e-9, "thigh {s}");
            assert!((tibia * DVec3::NEG_Y - shank).length() < 1e-9, "shank {s}");
            assert!(
                q(&format!("knee_angle_{s}")) <= 0.0,
                "gait2392 knee is negative in flexion"
            );
        }
        let torso =
            pelvis * rz(q("lumbar_extension")) * rx(q("lumbar_bending")) * ry(q("lumbar_rotation"));
        let [le, lb, lr] = p.lumbar;
        let want = ry(p.rotation) * rx(-p.list) * rz(-p.tilt) * ry(lr) * rx(lb) * rz(le);
        assert!(
            (torso - want)
                .abs()
                .to_cols_array()
                .iter()
                .all(|d| *d < 1e-9)
        );
        // small angles: gait2392's tilt and list are the opposite of the clinical ones
        assert!((q("pelvis_tilt") + p.tilt).abs() < deg(1.5));
        assert!((q("pelvis_list") + p.list).abs() < deg(1.5));
    }
}

#[test]
fn rajagopal_adds_arms_and_flips_the_knee() {
    let b = body();
    let frames = walk(50.0, 0.2);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("walk.sto");
    let opts = Options {
        opensim_model: OpenSimModel::Rajagopal2015,
        ..Options::default()
    };
    export::write(
        &path,
        Format::from_path(&path).unwrap(),
        &b,
        50.0,
        frames.iter().map(|f| f.1),
        &opts,
    )
    .unwrap();
    let (_, names, rows) = read_storage(&path);
    let col = |n: &str| names.iter().position(|x| x == n).unwrap();
    for ((p, _), row) in frames.iter().zip(&rows) {
        assert!((row[col("knee_angle_r")] - p.right.knee_flexion.to_degrees()).abs() < 1e-9);
        assert!((row[col("arm_flex_l")] - p.left_arm.shoulder_flexion.to_degrees()).abs() < 1e-9);
        assert!((row[col("arm_add_r")] + p.right_arm.shoulder_abduction.to_degrees()).abs() < 1e-9);
        assert!((row[col("elbow_flex_r")] - p.right_arm.elbow_flexion.to_degrees()).abs() < 1e-9);
    }
}

// ---------------------------------------------------------------------------------------------
// CSV and cycles

#[test]
fn csv_has_the_issue_columns_in_degrees() {
    let b = body();
    let frames = walk(100.0, 0.5);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("walk.csv");
    export::write(
        &path,
        Format::Csv,
        &b,
        100.0,
        frames.iter().map(|f| f.1),
        &Options::default(),
    )
    .unwrap();
    let text = fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut required = vec![
        "time_s",
        "pelvis_tx_m",
        "pelvis_ty_m",
        "pelvis_tz_m",
        "pelvis_tilt_deg",
        "pelvis_list_deg",
        "pelvis_rotation_deg",
        "lumbar_extension_deg",
        "neck_rotation_deg",
    ];
    let per_side = [
        "hip_flexion",
        "hip_adduction",
        "hip_rotation",
        "knee_flexion",
        "ankle_dorsiflexion",
        "mtp_dorsiflexion",
        "shoulder_flexion",
        "elbow_flexion",
    ];
    let sided: Vec<String> = ["r", "l"]
        .iter()
        .flat_map(|s| per_side.iter().map(move |n| format!("{n}_{s}_deg")))
        .collect();
    required.extend(sided.iter().map(String::as_str));
    for r in &required {
        assert!(header.contains(r), "missing column {r}");
    }
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), frames.len());
    for ((p, _), row) in frames.iter().zip(&rows) {
        assert_eq!(row[col("time_s")], p.time);
        assert_eq!(row[col("pelvis_tx_m")], p.pelvis[0]);
        let d = |n: &str, want: f64| assert!((row[col(n)] - want.to_degrees()).abs() < 1e-7, "{n}");
        d("pelvis_tilt_deg", p.tilt);
        d("neck_rotation_deg", p.neck);
        d("hip_flexion_r_deg", p.right.hip_flexion);
        d("hip_adduction_l_deg", p.left.hip_adduction);
        d("knee_flexion_l_deg", p.left.knee_flexion);
        d("ankle_dorsiflexion_r_deg", p.right.dorsiflexion);
        d("mtp_dorsiflexion_l_deg", p.left.mtp);
        d("shoulder_abduction_r_deg", p.right_arm.shoulder_abduction);
        d("elbow_flexion_l_deg", p.left_arm.elbow_flexion);
    }
}

/// Every CSV cell parses to the value the writers' former formatting (`{}` of the f64, shortest
/// round-trip digits) gave, bit for bit, except that a zero is never `-0`; integers (the step)
/// are written as integers.
#[test]
fn csv_cells_are_the_former_formatting_values() {
    let b = body();
    let frames = walk(100.0, 0.5);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("walk.csv");
    let lms: Vec<Landmarks> = frames.iter().map(|f| f.1).collect();
    export::write(
        &path,
        Format::Csv,
        &b,
        100.0,
        lms.clone(),
        &Options::default(),
    )
    .unwrap();
    let text = fs::read_to_string(&path).unwrap();
    let columns = clinical::angle_columns();
    let mut zeros = 0;
    for (lm, line) in lms.iter().zip(text.lines().skip(1)) {
        let c = Skeleton::new(lm, &b).unwrap().clinical(lm.time, lm.step);
        let mut want: Vec<f64> = vec![c.time, c.step as f64, c.pelvis[0], c.pelvis[1], c.pelvis[2]];
        want.extend(columns.iter().map(|col| (col.get)(&c).to_degrees()));
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), want.len());
        assert_eq!(cells[1], c.step.to_string());
        for (cell, w) in cells.iter().zip(&want) {
            let former: f64 = format!("{w}").parse().unwrap();
            let got: f64 = cell.parse().unwrap();
            assert_eq!(got.to_bits(), (former + 0.0).to_bits(), "{cell} vs {w}");
            assert!(!cell.starts_with("-0") || cell.contains('.'), "{cell}");
            if *w == 0.0 {
                assert_eq!(*cell, "0");
                zeros += 1;
            }
        }
    }
    // the first frame is at t = 0 exactly: the zero rule is exercised
    assert!(zeros > 0);
}

/// An analytic periodic signal, continuous across heel strikes, with cycles of unequal duration
/// and a per-cycle amplitude A_k of the first harmonic: the average over the steady cycles (the
/// first skipped) has the mean amplitude (1), to the linear-interpolation error of 100 Hz
/// sampling.
#[test]
fn cycle_average_recovers_an_analytic_periodic_signal() {
    let strikes = [0.0, 1.0, 2.1, 3.05, 4.15, 5.2];
    let amplitude = [6.0, 1.5, 0.5, 1.2, 0.8];
    let shaped = |a: f64, u: f64| a * (2.0 * PI * u).sin() + 0.5 * (4.0 * PI * u).cos();
    let shape = |u: f64| shaped(1.0, u);
    let signal = |t: f64| {
        let k = strikes.windows(2).position(|w| t < w[1]).unwrap_or(4);
        let u = (t - strikes[k]) / (strikes[k + 1] - strikes[k]);
        shaped(amplitude[k], u)
    };
    let times: Vec<f64> = (0..=520).map(|i| i as f64 / 100.0).collect();
    let values: Vec<Vec<f64>> = times
        .iter()
        .map(|&t| vec![signal(t), 2.0 * signal(t)])
        .collect();
    let rows = cycle::average_cycles(&times, &values, &strikes, 1).unwrap();
    assert_eq!(rows.len(), 101);
    for (p, row) in rows.iter().enumerate() {
        let want = shape(p as f64 / 100.0);
        assert!((row[0] - want).abs() < 2e-3, "{p} %: {} vs {want}", row[0]);
        assert!((row[1] - 2.0 * want).abs() < 4e-3);
    }
    // without skipping, the start-up cycle's amplitude of 6 shows (mean 2): the skip removes it
    let all = cycle::average_cycles(&times, &values, &strikes, 0).unwrap();
    assert!(
        (all[25][0] - shaped(2.0, 0.25)).abs() < 1e-2,
        "{}",
        all[25][0]
    );
    // one cycle, skipped: nothing left
    let e = cycle::average_cycles(&times, &values, &strikes[..2], 1).unwrap_err();
    assert!(
        matches!(e, cycle::CycleError::NoSteadyCycle { .. }) && e.to_string().contains("steady"),
        "{e}"
    );
    // strikes out of order
    assert!(cycle::average_cycles(&times, &values, &[1.0, 0.5, 2.0], 0).is_err());
}

#[test]
fn cycle_csv_has_101_rows_from_right_heel_strike() {
    let b = body();
    let frames = walk(100.0, 3.05);
    let clinical: Vec<Clinical> = frames
        .iter()
        .map(|(_, lm)| clinical::clinical(lm, &b).unwrap())
        .collect();
    let curves = cycle::cycle_average(&clinical, &[0.0, 1.0, 2.0, 3.0], 1).unwrap();
    assert_eq!(curves.cycles, 2);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cycle.csv");
    export::write_cycle_csv(&path, &curves).unwrap();
    let text = fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 102);
    let header: Vec<&str> = lines[0].split(',').collect();
    assert_eq!(header[0], "cycle_pct");
    let k = header
        .iter()
        .position(|h| *h == "hip_flexion_r_deg")
        .unwrap();
    for (p, line) in lines[1..].iter().enumerate() {
        let cells: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert_eq!(cells[0], p as f64);
        let want = walk_pose(1.0 + p as f64 / 100.0)
            .right
            .hip_flexion
            .to_degrees();
        assert!(
            (cells[k] - want).abs() < 0.05,
            "{p} %: {} vs {want}",
            cells[k]
        );
    }
}

// ---------------------------------------------------------------------------------------------
// errors

fn files(dir: &Path) -> Vec<String> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// The three ways a motion file is finished give the same bytes: the header first and the spool
/// renamed over the target (the frames' size hint gives the count, as a `Vec`'s), no size hint
/// (the header then the spooled rows copied into the target), a size hint larger than the frames
/// that come (the header written first is replaced). Nothing else is left in the directory, and
/// the file has the usual mode of a new file.
#[test]
fn every_way_to_the_file_writes_the_same_bytes() {
    let b = body();
    let frames: Vec<Landmarks> = walk(100.0, 0.3).into_iter().map(|f| f.1).collect();
    let n = frames.len();
    let dir = tempfile::tempdir().unwrap();
    let opts = Options::default();
    for name in ["a.csv", "a.mot", "a.bvh"] {
        let path = dir.path().join(name);
        let fmt = Format::from_path(&path).unwrap();
        let read = |p: &Path| fs::read(p).unwrap();
        export::write(&path, fmt, &b, 100.0, frames.clone(), &opts).unwrap();
        let counted = read(&path);
        let mut k = 0;
        let unhinted = std::iter::from_fn(|| {
            k += 1;
            frames.get(k - 1).copied()
        });
        export::write(&path, fmt, &b, 100.0, unhinted, &opts).unwrap();
        assert!(read(&path) == counted, "{name}: no size hint");
        export::write(&path, fmt, &b, 100.0, frames[..n - 1].to_vec(), &opts).unwrap();
        let shorter = read(&path);
        let mut k = 0;
        let fewer = frames.iter().copied().filter(|_| {
            k += 1;
            k < n
        });
        export::write(&path, fmt, &b, 100.0, fewer, &opts).unwrap();
        assert!(
            read(&path) == shorter,
            "{name}: fewer frames than the size hint"
        );
        assert!(shorter.len() < counted.len());
        assert_eq!(files(dir.path()), [name], "{name}");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let plain = dir.path().join("plain");
            fs::write(&plain, b"x").unwrap();
            let mode = |p: &Path| fs::metadata(p).unwrap().permissions().mode();
            assert_eq!(mode(&path), mode(&plain), "{name}");
            fs::remove_file(&plain).unwrap();
        }
        fs::remove_file(&path).unwrap();
    }
}

/// The frames are made on the caller's thread and written on another: the error reported is
/// still the first frame's that fails, whether the writer or the frames' iterator finds it.
#[test]
fn the_first_failing_frame_gives_the_error() {
    let b = body();
    let frames: Vec<Landmarks> = walk(100.0, 2.0).into_iter().map(|f| f.1).collect();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a.bvh");
    let opts = Options::default();
    let marker = || -> Error {
        ExportError::UnknownFormat {
            path: "marker".into(),
        }
        .into()
    };
    for (bad, fail) in [(3, 150), (150, 3), (100, 101), (199, 200)] {
        let mut lms = frames.clone();
        lms[bad].time += 0.5e-2;
        let stream = lms
            .into_iter()
            .enumerate()
            .map(|(i, lm)| if i == fail { Err(marker()) } else { Ok(lm) });
        let e = export::try_write(&path, Format::Bvh, &b, 100.0, stream, &opts).unwrap_err();
        if bad < fail {
            assert!(
                matches!(e, Error::Export(ExportError::FrameTime { frame, .. }) if frame == bad),
                "{bad} {fail}: {e}"
            );
        } else {
            assert!(e.to_string().contains("marker"), "{bad} {fail}: {e}");
        }
        assert!(files(dir.path()).is_empty(), "{:?}", files(dir.path()));
    }
}

#[test]
fn bad_input_is_a_typed_error_and_leaves_no_file() {
    let b = body();
    let frames: Vec<Landmarks> = walk(100.0, 0.3).into_iter().map(|f| f.1).collect();
    let dir = tempfile::tempdir().unwrap();
    let opts = Options::default();
    for name in ["a.csv", "a.mot", "a.bvh"] {
        let path = dir.path().join(name);
        let fmt = Format::from_path(&path).unwrap();
        let mut bad = frames.clone();
        bad[10].right.knee[1] = f64::NAN;
        let e = export::write(&path, fmt, &b, 100.0, bad, &opts).unwrap_err();
        assert!(
            matches!(e, Error::Figure(FigureError::NotFinite { .. }))
                && e.to_string().contains("r.knee.y"),
            "{e}"
        );
        let mut bad = frames.clone();
        bad[20].time = bad[19].time;
        let e = export::write(&path, fmt, &b, 100.0, bad, &opts).unwrap_err();
        assert!(matches!(e, Error::Export(_)), "{e}");
        let mut bad = frames.clone();
        bad[5].left.mtp = bad[5].left.heel;
        let e = export::write(&path, fmt, &b, 100.0, bad, &opts).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Figure(FigureError::ZeroLength { .. } | FigureError::Parallel { .. })
            ),
            "{e}"
        );
        let e = export::write(&path, fmt, &b, 0.0, frames.clone(), &opts).unwrap_err();
        assert!(e.to_string().contains("fps"), "{e}");
        let e = export::write(&path, fmt, &b, 100.0, Vec::new(), &opts).unwrap_err();
        assert!(matches!(e, Error::Export(_)), "{e}");
        assert!(files(dir.path()).is_empty(), "{:?}", files(dir.path()));
    }
    // BVH only: landmarks of another body, and frames not 1/fps apart
    let path = dir.path().join("b.bvh");
    fs::write(&path, "old").unwrap();
    let other = Body::standard(1.6, 60.0).unwrap();
    let e = export::write(&path, Format::Bvh, &other, 100.0, frames.clone(), &opts).unwrap_err();
    assert!(
        matches!(e, Error::Export(ExportError::SegmentLength { .. }))
            && e.to_string().contains("mm"),
        "{e}"
    );
    let e = export::write(&path, Format::Bvh, &b, 50.0, frames.clone(), &opts).unwrap_err();
    assert!(
        matches!(e, Error::Export(_)) && e.to_string().contains("1/50"),
        "{e}"
    );
    assert_eq!(fs::read_to_string(&path).unwrap(), "old");
    assert_eq!(files(dir.path()), ["b.bvh"]);
    let e = Format::from_path(Path::new("x.txt")).unwrap_err();
    assert!(
        e.to_string().contains(".bvh") && matches!(e, ExportError::UnknownFormat { .. }),
        "{e}"
    );
    assert_eq!(Format::from_path(Path::new("X.BVH")).unwrap(), Format::Bvh);
}

#[test]
fn malformed_bvh_is_rejected() {
    let p = Path::new("m.bvh");
    let good = "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zposition\n \
                End Site\n {\n OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 1\nFrame Time: 0.01\n1 2 3\n";
    let b = bvh::parse(good, p).unwrap();
    assert_eq!(
        b.pose(0).unwrap()[0].end_site,
        Some(DVec3::new(1.0, 3.0, 3.0))
    );
    for (bad, why) in [
        (good.replace("1 2 3", "1 2"), "values"),
        (good.replace("Frames: 1", "Frames: 2"), "frame lines"),
        (good.replace("Xposition", "Wposition"), "unknown channel"),
        (good.replace("MOTION", ""), "MOTION"),
        (good.replace("OFFSET 0 0 0", "OFFSET 0 x 0"), "number"),
    ] {
        let e = bvh::parse(&bad, p).unwrap_err();
        assert!(
            matches!(e, InputError::Malformed { .. }) && e.to_string().contains(why),
            "{why}: {e}"
        );
    }
}

/// A real walk (the engine's figure, determinants on) written as BVH and read back: forward
/// kinematics of the file puts the pelvis, every leg joint and every foot contact point where
/// the engine put them, to 1 mm (measured ≈ 1e-6 m), in place or not.
#[test]
fn bvh_of_a_real_walk_reproduces_the_engine() {
    let b = body();
    let walk = common::default_walk(4);
    let lms: Vec<Landmarks> = klaw::figure::frames(&walk, 50.0)
        .collect::<Result<_, _>>()
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    for in_place in [false, true] {
        let path = dir.path().join("walk.bvh");
        let options = Options {
            in_place,
            ..Options::default()
        };
        export::write(&path, Format::Bvh, &b, 50.0, lms.clone(), &options).unwrap();
        let parsed = bvh::parse(&fs::read_to_string(&path).unwrap(), &path).unwrap();
        assert_eq!(parsed.frames.len(), lms.len());
        let mut worst: f64 = 0.0;
        for (k, lm) in lms.iter().enumerate() {
            let pose = parsed.pose(k).unwrap();
            let at = |name: &str| &pose[parsed.joint(name).unwrap()];
            let shift = if in_place {
                DVec3::new(lm.pelvis[0], 0.0, 0.0)
            } else {
                DVec3::ZERO
            };
            let world = |p: DVec3| bvh::from_bvh(p) + shift;
            worst = worst.max(world(at("Hips").position).distance(v(lm.pelvis)));
            for (side, pts) in [("Right", &lm.right), ("Left", &lm.left)] {
                let foot = at(&format!("{side}Foot"));
                let heel =
                    foot.position + foot.rotation * bvh::to_bvh(DVec3::new(-b.l8, -b.l9, 0.0));
                let toe = at(&format!("{side}ToeBase"));
                for (got, want) in [
                    (at(&format!("{side}UpLeg")).position, pts.hip),
                    (at(&format!("{side}Leg")).position, pts.knee),
                    (foot.position, pts.ankle),
                    (heel, pts.heel),
                    (toe.position, pts.mtp),
                    (toe.end_site.unwrap(), pts.toe),
                ] {
                    worst = worst.max(world(got).distance(v(want)));
                }
            }
        }
        assert!(worst < 1e-3, "in place {in_place}: worst {worst} m");
        // the walk does not turn the head: the Neck channels are 0 exactly
        let neck = parsed.joints[parsed.joint("Neck").unwrap()].first_channel;
        assert!(parsed.frames.iter().all(|f| f[neck..neck + 3] == [0.0; 3]));
    }
}
