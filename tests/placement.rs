//! A placed walk (`figure::placement`, issue 15 item 10): the frames of a real simulated walk put
//! at a floor point and a heading keep every joint angle but the pelvis rotation, which gains
//! the heading, and every distance between their points; the CSV, `.mot` and BVH of the placed
//! walk carry the world pose. The expected values come from glam's rotations and Euler
//! conversions and from the unplaced walk's own files, not from `Placement`.
use std::f64::consts::{PI, TAU};
use std::fs;
use std::path::Path;

use glam::{DMat3, DVec3, EulerRot};
use klaw::export::{self, Format, Options, bvh};
use klaw::figure::skeleton::Skeleton;
use klaw::{Body, Clinical, Landmarks, Placement, Simulation};

/// The placements checked: turns in both senses, across ±π, several turns, far from the origin.
const PLACEMENTS: [([f64; 2], f64); 5] = [
    ([0.0, 0.0], 0.5),
    ([3.0, -2.0], -2.0),
    ([-1.0, 4.0], 3.0),
    ([0.2, 0.1], 10.0),
    ([120.0, -75.0], -0.9),
];

fn walk_frames() -> (Body, Vec<Landmarks>) {
    let walk = Simulation::default().steps(2).run().unwrap();
    let frames = walk.frames(100.0).unwrap();
    (*walk.body(), frames)
}

/// `R_y(h) · p + (o_x, 0, o_z)` by glam.
fn placed_point(origin: [f64; 2], heading: f64, p: [f64; 3]) -> DVec3 {
    DMat3::from_rotation_y(heading) * DVec3::from_array(p) + DVec3::new(origin[0], 0.0, origin[1])
}

/// `x` wrapped into (−π, π].
fn wrap(x: f64) -> f64 {
    x - TAU * ((x + PI) / TAU).ceil() + TAU
}

/// Every clinical angle of a frame but the pelvis rotation, by name.
fn angles_but_pelvis_rotation(c: &Clinical) -> Vec<(String, f64)> {
    let mut out = vec![
        ("pelvis_tilt".to_string(), c.pelvis_tilt),
        ("pelvis_list".to_string(), c.pelvis_list),
        ("lumbar_extension".to_string(), c.lumbar_extension),
        ("lumbar_bending".to_string(), c.lumbar_bending),
        ("lumbar_rotation".to_string(), c.lumbar_rotation),
        ("neck_rotation".to_string(), c.neck_rotation),
    ];
    for (s, leg, arm) in [("r", &c.right, &c.right_arm), ("l", &c.left, &c.left_arm)] {
        let joints = [
            ("hip", leg.hip),
            ("knee", leg.knee),
            ("ankle", leg.ankle),
            ("mtp", leg.mtp),
            ("shoulder", arm.shoulder),
            ("elbow", arm.elbow),
        ];
        for (j, q) in joints {
            out.push((format!("{j}_flexion_{s}"), q.flexion));
            out.push((format!("{j}_adduction_{s}"), q.adduction));
            out.push((format!("{j}_rotation_{s}"), q.rotation));
        }
    }
    out
}

fn points(lm: &Landmarks) -> Vec<[f64; 3]> {
    let mut p = vec![lm.pelvis];
    for l in [&lm.right, &lm.left] {
        p.extend([l.hip, l.knee, l.ankle, l.heel, l.mtp, l.toe]);
    }
    p
}

/// The clinical angles, read off the segment frames of the placed frames, are those of the
/// walk but the pelvis rotation, which is the walk's plus the heading (mod 2π); the points are
/// where glam's rotation puts them, and every distance between two of them is kept.
#[test]
fn placing_a_walk_changes_only_where_it_is() {
    let (body, frames) = walk_frames();
    assert!(frames.len() > 100);
    for (origin, heading) in PLACEMENTS {
        let at = Placement::new(origin, heading);
        let (mut worst_angle, mut worst_rotation, mut worst_distance): (f64, f64, f64) =
            (0.0, 0.0, 0.0);
        for lm in &frames {
            let placed = at.apply(lm);
            let clinical =
                |l: &Landmarks| Skeleton::new(l, &body).unwrap().clinical(l.time, l.step);
            let (c0, c1) = (clinical(lm), clinical(&placed));
            for ((name, a), (_, b)) in angles_but_pelvis_rotation(&c0)
                .into_iter()
                .zip(angles_but_pelvis_rotation(&c1))
            {
                assert!((a - b).abs() < 1e-10, "{heading}: {name} {a} → {b}");
                worst_angle = worst_angle.max((a - b).abs());
            }
            let d = wrap(c1.pelvis_rotation - c0.pelvis_rotation - heading);
            worst_rotation = worst_rotation.max(d.abs());
            let (p0, p1) = (points(lm), points(&placed));
            for (a, b) in p0.iter().zip(&p1) {
                let want = placed_point(origin, heading, *a);
                assert!(
                    want.distance(DVec3::from_array(*b)) < 1e-12,
                    "{a:?} → {b:?}"
                );
            }
            for i in 0..p0.len() {
                for j in 0..i {
                    let d0 = DVec3::from_array(p0[i]).distance(DVec3::from_array(p0[j]));
                    let d1 = DVec3::from_array(p1[i]).distance(DVec3::from_array(p1[j]));
                    worst_distance = worst_distance.max((d0 - d1).abs());
                }
            }
        }
        println!(
            "heading {heading}: angles {worst_angle:.1e} rad, pelvis rotation − heading \
             {worst_rotation:.1e} rad, distances {worst_distance:.1e} m"
        );
        assert!(
            worst_rotation < 1e-10,
            "pelvis rotation off by {worst_rotation}"
        );
        assert!(worst_distance < 1e-12, "distances off by {worst_distance}");
    }
}

/// Placing and then placing by the inverse gives the walk back; placing by `a` then `b`
/// (b within a) is placing by `a.compose(b)`.
#[test]
fn inverse_and_compose_act_on_frames_as_maps() {
    let (_, frames) = walk_frames();
    let a = Placement::new([3.0, -2.0], 1.1);
    let b = Placement::new([-0.5, 0.7], -2.6);
    for lm in frames.iter().step_by(17) {
        let back = a.inverse().apply(&a.apply(lm));
        let twice = a.apply(&b.apply(lm));
        let once = a.compose(&b).apply(lm);
        for (p, q, (r, s)) in points(lm)
            .into_iter()
            .zip(points(&back))
            .zip(points(&twice).into_iter().zip(points(&once)))
            .map(|((p, q), rs)| (p, q, rs))
        {
            assert!(DVec3::from_array(p).distance(DVec3::from_array(q)) < 1e-13);
            assert!(DVec3::from_array(r).distance(DVec3::from_array(s)) < 1e-13);
        }
        assert!((back.pelvis_rotation - lm.pelvis_rotation).abs() < 1e-15);
        assert!((twice.pelvis_rotation - once.pelvis_rotation).abs() < 1e-15);
    }
}

fn write(path: &Path, body: &Body, frames: &[Landmarks], options: &Options) {
    let format = Format::from_path(path).unwrap();
    export::write(path, format, body, 100.0, frames.iter().copied(), options).unwrap();
}

/// A delimited file's header and rows (numbers).
fn table(path: &Path, after: &str, sep: char) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = fs::read_to_string(path).unwrap();
    let body = text.split_once(after).map_or(text.as_str(), |(_, b)| b);
    let mut lines = body.lines();
    let names = lines
        .next()
        .unwrap()
        .split(sep)
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(sep).map(|x| x.parse().unwrap()).collect())
        .collect();
    (names, rows)
}

/// The CSV of a placed walk: the pelvis centre where glam puts it, the pelvis rotation the
/// walk's plus the heading (wrapped to ±180°), every other column the walk's.
#[test]
fn placed_csv_carries_the_world_pose() {
    let (body, frames) = walk_frames();
    let dir = tempfile::tempdir().unwrap();
    let (origin, heading) = PLACEMENTS[2];
    let at = Placement::new(origin, heading);
    let placed: Vec<Landmarks> = frames.iter().map(|lm| at.apply(lm)).collect();
    let (a, b) = (dir.path().join("walk.csv"), dir.path().join("placed.csv"));
    write(&a, &body, &frames, &Options::default());
    write(&b, &body, &placed, &Options::default());
    let ((names, rows0), (names1, rows1)) = (table(&a, "", ','), table(&b, "", ','));
    assert_eq!(names, names1);
    assert!(names.iter().any(|n| n == "neck_rotation_deg"));
    let col = |n: &str| names.iter().position(|x| x == n).unwrap();
    let (tx, ty, tz, rot) = (
        col("pelvis_tx_m"),
        col("pelvis_ty_m"),
        col("pelvis_tz_m"),
        col("pelvis_rotation_deg"),
    );
    for (r0, r1) in rows0.iter().zip(&rows1) {
        let want = placed_point(origin, heading, [r0[tx], r0[ty], r0[tz]]);
        assert!(want.distance(DVec3::new(r1[tx], r1[ty], r1[tz])) < 1e-12);
        let d = wrap((r1[rot] - r0[rot]).to_radians() - heading);
        assert!(d.abs() < 1e-10, "pelvis rotation {} → {}", r0[rot], r1[rot]);
        assert!(r1[rot] > -180.0 && r1[rot] <= 180.0);
        for (k, n) in names.iter().enumerate() {
            if ![tx, ty, tz, rot].contains(&k) {
                assert!((r0[k] - r1[k]).abs() < 1e-8, "{n}: {} → {}", r0[k], r1[k]);
            }
        }
    }
}

/// The `.mot` of a placed walk: gait2392's pelvis (tilt about z, list about x, rotation about
/// y, in that order) is the walk's pelvis turned by the heading, its origin (pelvis_tx/ty/tz,
/// a point of the pelvis) placed as a point, and the joint coordinates unchanged. The pelvis
/// rotation carries the heading: exactly the ZXY angle glam finds, and within the tilt's and
/// list's mixing of the walk's own rotation plus the heading.
#[test]
fn placed_mot_carries_the_world_pose() {
    let (body, frames) = walk_frames();
    let dir = tempfile::tempdir().unwrap();
    for (origin, heading) in PLACEMENTS {
        let at = Placement::new(origin, heading);
        let placed: Vec<Landmarks> = frames.iter().map(|lm| at.apply(lm)).collect();
        let (a, b) = (dir.path().join("walk.mot"), dir.path().join("placed.mot"));
        write(&a, &body, &frames, &Options::default());
        write(&b, &body, &placed, &Options::default());
        let ((names, rows0), (_, rows1)) = (
            table(&a, "endheader\n", '\t'),
            table(&b, "endheader\n", '\t'),
        );
        let col = |n: &str| names.iter().position(|x| x == n).unwrap();
        let mut worst_mix: f64 = 0.0;
        for (r0, r1) in rows0.iter().zip(&rows1) {
            let q = |r: &[f64], n: &str| r[col(n)].to_radians();
            let pelvis = |r: &[f64]| {
                DMat3::from_rotation_z(q(r, "pelvis_tilt"))
                    * DMat3::from_rotation_x(q(r, "pelvis_list"))
                    * DMat3::from_rotation_y(q(r, "pelvis_rotation"))
            };
            let want = DMat3::from_rotation_y(heading) * pelvis(r0);
            let got = pelvis(r1);
            assert!(got.abs_diff_eq(want, 1e-9), "{heading}");
            let (_, _, rotation) = want.to_euler(EulerRot::ZXY);
            assert!(wrap(q(r1, "pelvis_rotation") - rotation).abs() < 1e-9);
            let d = wrap(q(r1, "pelvis_rotation") - q(r0, "pelvis_rotation") - heading);
            worst_mix = worst_mix.max(d.abs());
            let o0 = [
                r0[col("pelvis_tx")],
                r0[col("pelvis_ty")],
                r0[col("pelvis_tz")],
            ];
            let o1 = DVec3::new(
                r1[col("pelvis_tx")],
                r1[col("pelvis_ty")],
                r1[col("pelvis_tz")],
            );
            assert!(placed_point(origin, heading, o0).distance(o1) < 1e-12);
            for (k, n) in names.iter().enumerate() {
                if n.starts_with("hip") || n.starts_with("knee") || n.starts_with("lumbar") {
                    assert!((r0[k] - r1[k]).abs() < 1e-8, "{n}");
                }
            }
        }
        println!(
            "heading {heading}: .mot pelvis_rotation − walk's − heading ≤ {:.3}°",
            worst_mix.to_degrees()
        );
        assert!(
            worst_mix < 2f64.to_radians(),
            "{heading}: {}°",
            worst_mix.to_degrees()
        );
    }
}

/// The BVH of a placed walk, parsed and posed: every joint where the placed landmarks put it,
/// the root's yaw (its forward axis on the floor) the walk's plus the heading, its `Yrotation`
/// the walk's plus the heading in degrees; with `in_place` only the world x translation
/// (`Zposition`) is dropped.
#[test]
fn placed_bvh_carries_the_world_pose() {
    let (body, frames) = walk_frames();
    let dir = tempfile::tempdir().unwrap();
    let (origin, heading) = PLACEMENTS[1];
    let at = Placement::new(origin, heading);
    let placed: Vec<Landmarks> = frames.iter().map(|lm| at.apply(lm)).collect();
    let parse = |frames: &[Landmarks], name: &str, in_place: bool| {
        let path = dir.path().join(name);
        let options = Options {
            in_place,
            ..Options::default()
        };
        write(&path, &body, frames, &options);
        bvh::parse(&fs::read_to_string(&path).unwrap(), &path).unwrap()
    };
    let (walk, moved, kept) = (
        parse(&frames, "walk.bvh", false),
        parse(&placed, "placed.bvh", false),
        parse(&placed, "kept.bvh", true),
    );
    let yaw = |m: DMat3| {
        let forward = m * DVec3::Z; // BVH: Z forward, X left, so a turn to the left is +X
        forward.x.atan2(forward.z)
    };
    let hips = moved.joint("Hips").unwrap();
    let mut worst: f64 = 0.0;
    for (k, lm) in placed.iter().enumerate() {
        let pose = moved.pose(k).unwrap();
        let at_joint = |name: &str| bvh::from_bvh(pose[moved.joint(name).unwrap()].position);
        worst = worst.max(at_joint("Hips").distance(DVec3::from_array(lm.pelvis)));
        for (side, pts) in [("Right", &lm.right), ("Left", &lm.left)] {
            for (joint, p) in [("UpLeg", pts.hip), ("Leg", pts.knee), ("Foot", pts.ankle)] {
                let d = at_joint(&format!("{side}{joint}")).distance(DVec3::from_array(p));
                worst = worst.max(d);
            }
            let toe = &pose[moved.joint(&format!("{side}ToeBase")).unwrap()];
            let tip = bvh::from_bvh(toe.end_site.unwrap());
            worst = worst.max(tip.distance(DVec3::from_array(pts.toe)));
        }
        let turn = yaw(pose[hips].rotation) - yaw(walk.pose(k).unwrap()[hips].rotation);
        assert!(
            wrap(turn - heading).abs() < 1e-9,
            "root yaw turned by {turn}"
        );
        let y = moved.joints[hips].first_channel + 3; // Yrotation, the first rotation channel
        let d = (moved.frames[k][y] - walk.frames[k][y]).to_radians() - heading;
        assert!(wrap(d).abs() < 1e-9);
        let (p, q) = (&moved.frames[k], &kept.frames[k]);
        assert_eq!(q[2], 0.0, "in place: no Zposition (world x)");
        assert_eq!(
            [q[0], q[1]],
            [p[0], p[1]],
            "in place keeps Xposition (world −z), height"
        );
        assert_eq!(p[2], lm.pelvis[0]);
        assert_eq!(q[3..], p[3..]);
    }
    assert!(worst < 1e-9, "placed BVH off by {worst} m");
}
