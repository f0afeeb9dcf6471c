//! The BVH writer: the exported hierarchy of a body and one row of channel values per frame.
use std::io::{self, Write};

use glam::{DMat3, DVec3};

use super::Channel::{self, *};
use super::to_bvh;
use crate::export::number::{Number, push_f64};
use crate::export::{ExportError, FrameData, RowWriter};
use crate::figure::euler::{nearest_turn, yxz_angles, zxy_angles};
use crate::figure::skeleton::{LENGTH_TOLERANCE, Side, Skeleton};
use crate::model::body::Body;

const ROOT_CHANNELS: [Channel; 6] = [
    Xposition, Yposition, Zposition, Yrotation, Zrotation, Xrotation,
];
const YZX: [Channel; 3] = [Yrotation, Zrotation, Xrotation];
const XZY: [Channel; 3] = [Xrotation, Zrotation, Yrotation];

/// Where a joint's rotation comes from.
#[derive(Clone, Copy)]
enum Seg {
    Pelvis,
    Thorax,
    Thigh(Side),
    Shank(Side),
    Foot(Side),
    Toe(Side),
    UpperArm(Side),
    Forearm(Side),
    Hand(Side),
}

fn axes(sk: &Skeleton, seg: Seg) -> DMat3 {
    match seg {
        Seg::Pelvis => sk.pelvis.axes,
        Seg::Thorax => sk.thorax.axes,
        Seg::Thigh(s) => sk.leg(s).thigh.axes,
        Seg::Shank(s) => sk.leg(s).shank.axes,
        Seg::Foot(s) => sk.leg(s).foot.axes,
        Seg::Toe(s) => sk.leg(s).toe.axes,
        Seg::UpperArm(s) => sk.arm(s).upper_arm.axes,
        Seg::Forearm(s) => sk.arm(s).forearm.axes,
        Seg::Hand(s) => sk.arm(s).hand.axes,
    }
}

/// The rotation a joint's channels carry.
#[derive(Clone, Copy)]
enum Motion {
    /// Pelvis in the world, plus the root translation.
    Root,
    /// The child segment in the parent segment.
    Relative(Seg, Seg),
    /// The head in the thorax, as the skeleton made it (`R_y(neck_rotation)`: the channels are
    /// 0, 0 and the neck rotation, without the round-off of `R_thoraxᵀ · R_head`).
    Neck,
    /// Rigid: all channels zero.
    Fixed,
}

struct JointDef {
    name: String,
    parent: Option<usize>,
    /// klaw world axes, rest pose.
    offset: DVec3,
    channels: &'static [Channel],
    motion: Motion,
    end_site: Option<DVec3>,
}

/// The exported hierarchy for `body`, depth-first (the file's joint and channel order).
fn hierarchy(body: &Body) -> Vec<JointDef> {
    let f = &body.figure;
    let mut j: Vec<JointDef> = Vec::new();
    let mut add = |name: String,
                   parent: Option<usize>,
                   offset: DVec3,
                   channels: &'static [Channel],
                   motion: Motion,
                   end_site: Option<DVec3>| {
        j.push(JointDef {
            name,
            parent,
            offset,
            channels,
            motion,
            end_site,
        });
        j.len() - 1
    };
    let up = |d: f64| DVec3::new(0.0, d, 0.0);
    let hips = add(
        "Hips".into(),
        None,
        DVec3::ZERO,
        &ROOT_CHANNELS,
        Motion::Root,
        None,
    );
    let spine = add(
        "Spine".into(),
        Some(hips),
        DVec3::ZERO,
        &YZX,
        Motion::Relative(Seg::Pelvis, Seg::Thorax),
        None,
    );
    let chest = add(
        "Chest".into(),
        Some(spine),
        up(f.spine / 2.0),
        &XZY,
        Motion::Fixed,
        None,
    );
    let neck = add(
        "Neck".into(),
        Some(chest),
        up(f.spine / 2.0),
        &XZY,
        Motion::Neck,
        None,
    );
    add(
        "Head".into(),
        Some(neck),
        up(f.neck),
        &XZY,
        Motion::Fixed,
        Some(up(f.head)),
    );
    for side in [Side::Left, Side::Right] {
        let n = match side {
            Side::Left => "Left",
            Side::Right => "Right",
        };
        let lateral = DVec3::new(0.0, 0.0, side.sign());
        let shoulder = add(
            format!("{n}Shoulder"),
            Some(chest),
            up(f.spine / 2.0),
            &XZY,
            Motion::Fixed,
            None,
        );
        let arm = add(
            format!("{n}Arm"),
            Some(shoulder),
            lateral * (f.shoulder_width / 2.0),
            &XZY,
            Motion::Relative(Seg::Thorax, Seg::UpperArm(side)),
            None,
        );
        let forearm = add(
            format!("{n}ForeArm"),
            Some(arm),
            up(-f.upper_arm),
            &XZY,
            Motion::Relative(Seg::UpperArm(side), Seg::Forearm(side)),
            None,
        );
        add(
            format!("{n}Hand"),
            Some(forearm),
            up(-f.forearm),
            &XZY,
            Motion::Relative(Seg::Forearm(side), Seg::Hand(side)),
            Some(up(-f.hand)),
        );
    }
    for side in [Side::Left, Side::Right] {
        let n = match side {
            Side::Left => "Left",
            Side::Right => "Right",
        };
        let upleg = add(
            format!("{n}UpLeg"),
            Some(hips),
            DVec3::new(0.0, 0.0, side.sign() * body.l0 / 2.0),
            &XZY,
            Motion::Relative(Seg::Pelvis, Seg::Thigh(side)),
            None,
        );
        let leg = add(
            format!("{n}Leg"),
            Some(upleg),
            up(-body.l3),
            &XZY,
            Motion::Relative(Seg::Thigh(side), Seg::Shank(side)),
            None,
        );
        let foot = add(
            format!("{n}Foot"),
            Some(leg),
            up(-body.l4),
            &XZY,
            Motion::Relative(Seg::Shank(side), Seg::Foot(side)),
            None,
        );
        add(
            format!("{n}ToeBase"),
            Some(foot),
            DVec3::new(body.ankle_to_metatarsal_horizontal(), -body.l9, 0.0),
            &XZY,
            Motion::Relative(Seg::Foot(side), Seg::Toe(side)),
            Some(DVec3::new(body.l13, 0.0, 0.0)),
        );
    }
    j
}

/// Channel values (degrees) of a relative rotation, in the joint's channel order.
///
/// With `R = R_z(a)·R_x(b)·R_y(c)` in klaw axes, the BVH axes (X = −z, Y = y, Z = x) give
/// `R = R_X(−a)·R_Z(b)·R_Y(c)`: `Xrotation Zrotation Yrotation` = (−a, b, c). With
/// `R = R_y(r)·R_x(p)·R_z(q)`: `R_Y(r)·R_Z(p)·R_X(−q)`, `Yrotation Zrotation Xrotation` =
/// (r, p, −q).
fn rotation_channels(order: &[Channel], rel: &DMat3) -> [f64; 3] {
    if order == YZX {
        let [r, p, q] = yxz_angles(rel);
        [r, p, -q].map(f64::to_degrees)
    } else {
        let [a, b, c] = zxy_angles(rel);
        [-a, b, c].map(f64::to_degrees)
    }
}

/// The BVH writer.
pub(crate) struct BvhWriter {
    body: Body,
    fps: f64,
    in_place: bool,
    joints: Vec<JointDef>,
    first_time: f64,
}

impl BvhWriter {
    pub(crate) fn new(body: &Body, fps: f64, in_place: bool) -> Self {
        BvhWriter {
            body: *body,
            fps,
            in_place,
            joints: hierarchy(body),
            first_time: 0.0,
        }
    }

    fn write_joint(&self, out: &mut dyn Write, i: usize, depth: usize) -> io::Result<()> {
        let j = &self.joints[i];
        let pad = "\t".repeat(depth);
        let kind = if j.parent.is_none() { "ROOT" } else { "JOINT" };
        let o = to_bvh(j.offset).to_array().map(Number);
        writeln!(out, "{pad}{kind} {}", j.name)?;
        writeln!(out, "{pad}{{")?;
        writeln!(out, "{pad}\tOFFSET {} {} {}", o[0], o[1], o[2])?;
        let names: Vec<&str> = j.channels.iter().map(|c| c.name()).collect();
        writeln!(
            out,
            "{pad}\tCHANNELS {} {}",
            j.channels.len(),
            names.join(" ")
        )?;
        for (k, child) in self.joints.iter().enumerate() {
            if child.parent == Some(i) {
                self.write_joint(out, k, depth + 1)?;
            }
        }
        if let Some(end) = j.end_site {
            let e = to_bvh(end).to_array().map(Number);
            writeln!(out, "{pad}\tEnd Site")?;
            writeln!(out, "{pad}\t{{")?;
            writeln!(out, "{pad}\t\tOFFSET {} {} {}", e[0], e[1], e[2])?;
            writeln!(out, "{pad}\t}}")?;
        }
        writeln!(out, "{pad}}}")
    }
}

impl RowWriter for BvhWriter {
    fn row(&mut self, out: &mut Vec<u8>, frame: &FrameData) -> Result<(), ExportError> {
        let lm = frame.landmarks;
        let sk = &frame.skeleton;
        if frame.index == 0 {
            self.first_time = lm.time;
        }
        let expected = self.first_time + frame.index as f64 / self.fps;
        if (lm.time - expected).abs() > 1e-3 / self.fps + 1e-9 {
            return Err(ExportError::FrameTime {
                frame: frame.index,
                time: lm.time,
                fps: self.fps,
                first: self.first_time,
                expected,
            });
        }
        let (err, name) = sk.length_error(lm, &self.body);
        if err.is_nan() || err > LENGTH_TOLERANCE {
            return Err(ExportError::SegmentLength {
                time: lm.time,
                landmark: name,
                distance: err,
                tolerance: LENGTH_TOLERANCE,
            });
        }
        let start = out.len();
        let put = |out: &mut Vec<u8>, v: f64| {
            if out.len() > start {
                out.push(b' ');
            }
            push_f64(out, v);
        };
        for j in &self.joints {
            match j.motion {
                Motion::Root => {
                    let mut p = to_bvh(sk.pelvis.origin);
                    if self.in_place {
                        p.z = 0.0;
                    }
                    for v in p.to_array() {
                        put(out, v);
                    }
                    let mut r = rotation_channels(&j.channels[3..], &sk.pelvis.axes);
                    if j.channels[3..] == YZX {
                        // Yrotation, the heading: continuous past ±180°
                        let heading = lm.pelvis_rotation.to_degrees();
                        r[0] = nearest_turn(r[0].to_radians(), heading.to_radians()).to_degrees();
                    }
                    for v in r {
                        put(out, v);
                    }
                }
                Motion::Relative(parent, child) => {
                    let rel = axes(sk, parent).transpose() * axes(sk, child);
                    for v in rotation_channels(j.channels, &rel) {
                        put(out, v);
                    }
                }
                Motion::Neck => {
                    for v in rotation_channels(j.channels, &sk.neck) {
                        put(out, v);
                    }
                }
                Motion::Fixed => {
                    for _ in j.channels {
                        put(out, 0.0);
                    }
                }
            }
        }
        out.push(b'\n');
        Ok(())
    }

    fn header(&self, out: &mut dyn Write, rows: usize) -> io::Result<()> {
        writeln!(out, "HIERARCHY")?;
        self.write_joint(out, 0, 0)?;
        writeln!(out, "MOTION")?;
        writeln!(out, "Frames: {rows}")?;
        writeln!(out, "Frame Time: {}", Number(1.0 / self.fps))
    }
}
