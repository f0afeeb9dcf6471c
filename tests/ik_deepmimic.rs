//! Issue 18 §4: the inverse kinematics on an external walk's poulaine, DeepMimic's walking clip
//! (pybullet 3.2.7's pybullet_data, zlib licence; `scripts/deepmimic_poulaine.py` wrote both
//! files from the clip's own forward kinematics, independently of klaw), against the clip's own
//! clinical angles at the same 38 instants. docs/ik.md has the numbers next to Table 2.
use std::path::Path;

use klaw::Body;
use klaw::ik::chain::NAMES;
use klaw::ik::{Angles, Ik};
use klaw::poulaine::Trajectory;
use klaw::poulaine::validate::{recover, recover_referenced};

const POULAINE: &str = "models/prototypes/deepmimic-walk-poulaine.csv";
const ANGLES: &str = "models/prototypes/deepmimic-walk-angles.csv";
/// The clip's leg, hip to ankle (m): its thigh and shank at the URDF's scaling 0.25.
const CLIP_LEG: f64 = 0.25 * (1.686184 + 1.63948);
/// The height whose klaw leg (0.48225 H, KLAW Table B-1) is the clip's.
const HEIGHT: f64 = 1.724;

/// The clip's chain angles (rad) of the first `n` frames of the angles file: its columns in
/// the chain's order ([`NAMES`]), degrees in the file.
fn clip_angles(n: usize) -> Vec<Angles> {
    let text = std::fs::read_to_string(ANGLES).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at: Vec<usize> = NAMES
        .iter()
        .map(|n| {
            header
                .iter()
                .position(|h| *h == format!("{n}_deg"))
                .unwrap()
        })
        .collect();
    lines
        .take(n)
        .map(|l| {
            let row: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
            Angles::from_iterator(at.iter().map(|&k| row[k].to_radians()))
        })
        .collect()
}

/// The IK on the clip's poulaine at the clip's leg length: every frame's ankles within 1 mm of
/// the poulaine (by the chain's forward kinematics at the solved angles), every angle within
/// its joint limits (the method's own guarantees), and the hip flexion and knee against the
/// clip's own (eq. 7, mean of both legs, rad) as a snapshot, reviewed when it changes (Table 2
/// reports 0.05 and 0.02 for the paper's subjects; no published value holds klaw's chain on
/// this clip).
#[test]
fn the_ik_follows_deepmimics_poulaine_and_recovers_its_knee() {
    let poulaine = Trajectory::read_csv(Path::new(POULAINE)).unwrap();
    assert_eq!(poulaine.time.len(), 38);
    let body = Body::standard(HEIGHT, 23.0 * HEIGHT * HEIGHT).unwrap();
    let ik = Ik::new(&body);
    assert!((ik.chain.leg_length() - CLIP_LEG).abs() < 1e-3 * CLIP_LEG);
    let truth = clip_angles(poulaine.time.len());
    let r = recover(&ik, &poulaine, &truth).unwrap();
    for (theta, target) in r.angles.iter().zip(poulaine.targets()) {
        let error = (ik.chain.ankles(theta) - target).amax();
        assert!(error <= 1e-3, "ankle error {error} m");
    }
    assert!(r.within_limits);
    let (hip, knee) = (r.table2("hip_flexion"), r.table2("knee_flexion"));
    eprintln!(
        "DeepMimic: hip flexion {hip:.4}, knee {knee:.4} rad; {:?}",
        r.rms
    );
    insta::assert_snapshot!(format!(
        "RMS against the clip (rad): hip flexion {hip:.3}, knee {knee:.3}"
    ));
}

/// Nothing is lost to the task or to the bodies' difference: klaw's chain at H 1.724 m is not
/// the clip's (thigh 0.408 against 0.422 m, shank 0.423 against 0.410, hips 0.173 against
/// 0.170 m apart), so the clip's own angles miss its poulaine by up to 1.6 cm; yet with f3
/// pulling towards them at each frame and no kinetic term, the IK on the poulaine gives every
/// angle back within 0.01 rad (measured: 0.007 at worst, hip flexion), as on klaw's walks
/// (`tests/ik_validation.rs`). The errors of the default solve are the secondary tasks' choice
/// in the null space.
#[test]
fn the_clips_own_angles_as_reference_come_back() {
    let poulaine = Trajectory::read_csv(Path::new(POULAINE)).unwrap();
    let body = Body::standard(HEIGHT, 23.0 * HEIGHT * HEIGHT).unwrap();
    let truth = clip_angles(poulaine.time.len());
    let mut ik = Ik::new(&body);
    let miss = truth
        .iter()
        .zip(poulaine.targets())
        .map(|(t, x)| (ik.chain.ankles(t) - x).amax())
        .fold(0.0, f64::max);
    assert!(
        miss > 0.01,
        "the clip's angles miss klaw's ankles by {miss} m"
    );
    ik.model.weights.energy = 0.0;
    let r = recover_referenced(&ik, &poulaine, &truth, Some(&truth)).unwrap();
    assert!(r.rms.iter().all(|&e| e < 0.01), "{:?}", r.rms);
    assert!(r.within_limits && r.residual <= 1e-3);
}

/// klaw's frame CSV reader (`klaw evaluate`) reads the angles file, its `#` source lines
/// skipped, to the same angles as this file's own reader.
#[test]
fn klaws_reader_reads_the_commented_angles_file() {
    use klaw::analysis::criteria::CriteriaParameters;
    use klaw::export::read::read_motion;
    use klaw::poulaine::validate::chain_angles;
    let body = Body::standard(HEIGHT, 23.0 * HEIGHT * HEIGHT).unwrap();
    let file = read_motion(Path::new(ANGLES), &body, &CriteriaParameters::default()).unwrap();
    assert_eq!(file.motion.frames.len(), 4 * 38);
    for (frame, mine) in file.motion.frames.iter().zip(clip_angles(4 * 38)) {
        assert!((chain_angles(frame) - mine).amax() < 1e-12);
    }
}
