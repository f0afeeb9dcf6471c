//! BVH (Biovision hierarchy) export, parser and forward kinematics (issue item 7).
//!
//! File axes: Y up, +Z forward (the walking direction), +X to the figure's left, metres; a klaw
//! world vector (x forward, y up, z right) is written as (−z, y, x). The rest pose is the
//! anatomical zero of [`crate::figure::skeleton`] (legs vertical, soles flat, arms hanging), so every
//! joint channel is ± a clinical angle (`docs/export.md` has the table).
//!
//! Hierarchy: `Hips` (root, the pelvis centre) → `Spine` (the lumbar joint, at the pelvis centre)
//! → `Chest` → `Neck` → `Head`; `Chest` → `{Left,Right}Shoulder` → `Arm` → `ForeArm` → `Hand`;
//! `Hips` → `{Left,Right}UpLeg` → `Leg` → `Foot` → `ToeBase` → End Site (the toe tip). Offsets
//! from the body table: hips ±l0/2, knee l3 below the hip, ankle l4 below the knee, mtp
//! √(l12² − l9²) ahead of and l9 below the ankle, toe tip l13 ahead of the mtp; the spine
//! (hip-joint level to shoulder level) is split in two equal halves (`Spine` → `Chest` →
//! `Neck`), shoulders ±shoulder_width/2, then neck, head, upper arm, forearm, hand.
//!
//! Channels: the root has `Xposition Yposition Zposition Yrotation Zrotation Xrotation` and
//! `Spine` `Yrotation Zrotation Xrotation` (the order of the pelvis and lumbar angles of
//! [`crate::figure::Landmarks`], so these channels are exactly the landmarks' angles); every other
//! joint has `Xrotation Zrotation Yrotation` (flexion, ab/adduction, axial rotation). A joint's
//! rotation is the product of its channels in file order, each about the parent's (rest) axes;
//! the joint sits at its offset in the parent's frame.
use std::io::{self, Write};
use std::num::ParseFloatError;
use std::path::Path;

use glam::{DMat3, DVec3};

use super::{ExportError, FrameData, RowError, RowWriter};
use crate::figure::euler::{yxz_angles, zxy_angles};
use crate::figure::skeleton::{LENGTH_TOLERANCE, Side, Skeleton};
use crate::model::InputError;
use crate::model::body::Body;

/// A klaw world vector (x forward, y up, z right) in BVH axes (X left, Y up, Z forward).
pub fn to_bvh(v: DVec3) -> DVec3 {
    DVec3::new(-v.z, v.y, v.x)
}

/// A BVH vector in klaw world axes; the inverse of [`to_bvh`].
pub fn from_bvh(v: DVec3) -> DVec3 {
    DVec3::new(v.z, v.y, -v.x)
}

/// A BVH channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channel {
    /// Translation along X (left), file units.
    Xposition,
    /// Translation along Y (up), file units.
    Yposition,
    /// Translation along Z (forward), file units.
    Zposition,
    /// Rotation about X (left), degrees.
    Xrotation,
    /// Rotation about Y (up), degrees.
    Yrotation,
    /// Rotation about Z (forward), degrees.
    Zrotation,
}

impl Channel {
    fn name(self) -> &'static str {
        match self {
            Channel::Xposition => "Xposition",
            Channel::Yposition => "Yposition",
            Channel::Zposition => "Zposition",
            Channel::Xrotation => "Xrotation",
            Channel::Yrotation => "Yrotation",
            Channel::Zrotation => "Zrotation",
        }
    }

    fn parse(s: &str) -> Option<Channel> {
        Some(match s {
            "Xposition" => Channel::Xposition,
            "Yposition" => Channel::Yposition,
            "Zposition" => Channel::Zposition,
            "Xrotation" => Channel::Xrotation,
            "Yrotation" => Channel::Yrotation,
            "Zrotation" => Channel::Zrotation,
            _ => return None,
        })
    }
}

use Channel::*;

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
        Motion::Fixed,
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
        // + 0.0 turns −0.0 (from negating a zero) into 0.0
        let o = to_bvh(j.offset) + DVec3::ZERO;
        writeln!(out, "{pad}{kind} {}", j.name)?;
        writeln!(out, "{pad}{{")?;
        writeln!(out, "{pad}\tOFFSET {:.6} {:.6} {:.6}", o.x, o.y, o.z)?;
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
            let e = to_bvh(end) + DVec3::ZERO;
            writeln!(out, "{pad}\tEnd Site")?;
            writeln!(out, "{pad}\t{{")?;
            writeln!(out, "{pad}\t\tOFFSET {:.6} {:.6} {:.6}", e.x, e.y, e.z)?;
            writeln!(out, "{pad}\t}}")?;
        }
        writeln!(out, "{pad}}}")
    }
}

impl RowWriter for BvhWriter {
    fn row(&mut self, out: &mut dyn Write, frame: &FrameData) -> Result<(), RowError> {
        let lm = frame.landmarks;
        let sk = &frame.skeleton;
        if frame.index == 0 {
            self.first_time = lm.time;
        }
        let expected = self.first_time + frame.index as f64 / self.fps;
        if (lm.time - expected).abs() > 1e-3 / self.fps + 1e-9 {
            return Err(RowError::Frame(ExportError::FrameTime {
                frame: frame.index,
                time: lm.time,
                fps: self.fps,
                first: self.first_time,
                expected,
            }));
        }
        let (err, name) = sk.length_error(lm, &self.body);
        if err.is_nan() || err > LENGTH_TOLERANCE {
            return Err(RowError::Frame(ExportError::SegmentLength {
                time: lm.time,
                landmark: name,
                distance: err,
                tolerance: LENGTH_TOLERANCE,
            }));
        }
        let mut first = true;
        let mut put = |out: &mut dyn Write, v: f64| -> io::Result<()> {
            let sep = if first { "" } else { " " };
            first = false;
            write!(out, "{sep}{:.6}", v + 0.0)
        };
        for j in &self.joints {
            match j.motion {
                Motion::Root => {
                    let mut p = to_bvh(sk.pelvis.origin);
                    if self.in_place {
                        p.z = 0.0;
                    }
                    for v in p.to_array() {
                        put(out, v)?;
                    }
                    for v in rotation_channels(&j.channels[3..], &sk.pelvis.axes) {
                        put(out, v)?;
                    }
                }
                Motion::Relative(parent, child) => {
                    let rel = axes(sk, parent).transpose() * axes(sk, child);
                    for v in rotation_channels(j.channels, &rel) {
                        put(out, v)?;
                    }
                }
                Motion::Fixed => {
                    for _ in j.channels {
                        put(out, 0.0)?;
                    }
                }
            }
        }
        writeln!(out)?;
        Ok(())
    }

    fn header(&self, out: &mut dyn Write, rows: usize) -> io::Result<()> {
        writeln!(out, "HIERARCHY")?;
        self.write_joint(out, 0, 0)?;
        writeln!(out, "MOTION")?;
        writeln!(out, "Frames: {rows}")?;
        writeln!(out, "Frame Time: {:.9}", 1.0 / self.fps)
    }
}

/// A joint of a parsed BVH file.
#[derive(Clone, Debug, PartialEq)]
pub struct BvhJoint {
    /// The joint's name, e.g. `LeftUpLeg`.
    pub name: String,
    /// Index of the parent joint in [`Bvh::joints`], `None` for the root.
    pub parent: Option<usize>,
    /// In the parent's frame, file axes.
    pub offset: DVec3,
    /// The joint's channels, in file order (the order the rotations compose in).
    pub channels: Vec<Channel>,
    /// Index of this joint's first channel in a frame's values.
    pub first_channel: usize,
    /// The End Site's offset in the joint's frame (file axes), if the joint has one.
    pub end_site: Option<DVec3>,
}

/// A parsed BVH file. Joints are in file order (parents before children).
#[derive(Clone, Debug, PartialEq)]
pub struct Bvh {
    /// The hierarchy's joints.
    pub joints: Vec<BvhJoint>,
    /// Time between frames (s).
    pub frame_time: f64,
    /// One row of channel values per frame (positions in file units, rotations in degrees).
    pub frames: Vec<Vec<f64>>,
}

/// A joint's world pose in one frame (file axes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointPose {
    /// The joint's position.
    pub position: DVec3,
    /// The joint's orientation: its axes as the columns.
    pub rotation: DMat3,
    /// The End Site, if the joint has one.
    pub end_site: Option<DVec3>,
}

/// Why BVH text cannot be parsed (tokens are counted from 1).
#[derive(Debug, thiserror::Error)]
pub enum ParseError {
    /// The text ends inside the hierarchy.
    #[error("unexpected end of file")]
    UnexpectedEnd,
    /// A token other than the one the hierarchy needs.
    #[error("expected `{want}`, found `{found}` (token {token})")]
    Expected {
        /// The token needed.
        want: &'static str,
        /// The token found.
        found: String,
        /// Its place, from 1.
        token: usize,
    },
    /// A token that is not a finite number where one is needed.
    #[error("expected a number, found `{found}` (token {token})")]
    NotANumber {
        /// The token found.
        found: String,
        /// Its place, from 1.
        token: usize,
    },
    /// A channel count that is not a whole number from 0 to 6.
    #[error("joint {joint}: channel count {count} is not 0…6")]
    ChannelCount {
        /// The joint's name.
        joint: String,
        /// The count given.
        count: f64,
    },
    /// A channel name that is not a position or rotation axis.
    #[error("joint {joint}: unknown channel `{channel}`")]
    UnknownChannel {
        /// The joint's name.
        joint: String,
        /// The channel's name.
        channel: String,
    },
    /// A token in a joint that is neither `JOINT`, `End` nor `}`.
    #[error("joint {joint}: unexpected `{found}` (token {token})")]
    InJoint {
        /// The joint's name.
        joint: String,
        /// The token found.
        found: String,
        /// Its place, from 1.
        token: usize,
    },
    /// No `MOTION` in the text.
    #[error("no MOTION section")]
    NoMotion,
    /// Tokens between the root joint's end and `MOTION`.
    #[error("unexpected `{found}` after the root joint")]
    AfterRoot {
        /// The first of them.
        found: String,
    },
    /// Nothing after `MOTION`.
    #[error("no `Frames:` line")]
    NoFrameCount,
    /// A `Frames:` line without a whole number.
    #[error("bad frame count line `{line}`")]
    FrameCount {
        /// The line.
        line: String,
    },
    /// No line after the `Frames:` line.
    #[error("no `Frame Time:` line")]
    NoFrameTime,
    /// A `Frame Time:` line without a positive finite number.
    #[error("bad frame time line `{line}`")]
    FrameTime {
        /// The line.
        line: String,
    },
    /// A frame value that is not a number.
    #[error("frame {frame}: {source}")]
    Value {
        /// The frame's index, from 0.
        frame: usize,
        /// The number parser's error.
        source: ParseFloatError,
    },
    /// A frame with another number of values than the hierarchy has channels.
    #[error("frame {frame}: {values} values where the hierarchy has {channels} channels")]
    FrameWidth {
        /// The frame's index, from 0.
        frame: usize,
        /// Its number of values.
        values: usize,
        /// The hierarchy's channels.
        channels: usize,
    },
    /// Another number of frame lines than `Frames:` declares.
    #[error("`Frames: {declared}` but {found} frame lines")]
    FrameLines {
        /// The frames declared.
        declared: usize,
        /// The frame lines found.
        found: usize,
    },
}

struct Tokens<'a> {
    items: Vec<&'a str>,
    pos: usize,
}

impl<'a> Tokens<'a> {
    fn next(&mut self) -> Result<&'a str, ParseError> {
        let t = self
            .items
            .get(self.pos)
            .copied()
            .ok_or(ParseError::UnexpectedEnd)?;
        self.pos += 1;
        Ok(t)
    }

    fn expect(&mut self, want: &'static str) -> Result<(), ParseError> {
        let t = self.next()?;
        if t == want {
            Ok(())
        } else {
            Err(ParseError::Expected {
                want,
                found: t.to_string(),
                token: self.pos,
            })
        }
    }

    fn number(&mut self) -> Result<f64, ParseError> {
        let t = self.next()?;
        match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(ParseError::NotANumber {
                found: t.to_string(),
                token: self.pos,
            }),
        }
    }

    fn vec3(&mut self) -> Result<DVec3, ParseError> {
        Ok(DVec3::new(self.number()?, self.number()?, self.number()?))
    }
}

fn parse_joint(
    tok: &mut Tokens,
    joints: &mut Vec<BvhJoint>,
    parent: Option<usize>,
    channels_so_far: &mut usize,
) -> Result<(), ParseError> {
    let name = tok.next()?.to_string();
    tok.expect("{")?;
    tok.expect("OFFSET")?;
    let offset = tok.vec3()?;
    tok.expect("CHANNELS")?;
    let n = tok.number()?;
    if n.fract() != 0.0 || !(0.0..=6.0).contains(&n) {
        return Err(ParseError::ChannelCount {
            joint: name,
            count: n,
        });
    }
    let mut channels = Vec::new();
    for _ in 0..n as usize {
        let c = tok.next()?;
        channels.push(Channel::parse(c).ok_or_else(|| ParseError::UnknownChannel {
            joint: name.clone(),
            channel: c.to_string(),
        })?);
    }
    let index = joints.len();
    joints.push(BvhJoint {
        name: name.clone(),
        parent,
        offset,
        first_channel: *channels_so_far,
        channels,
        end_site: None,
    });
    *channels_so_far += n as usize;
    loop {
        match tok.next()? {
            "JOINT" => parse_joint(tok, joints, Some(index), channels_so_far)?,
            "End" => {
                tok.expect("Site")?;
                tok.expect("{")?;
                tok.expect("OFFSET")?;
                joints[index].end_site = Some(tok.vec3()?);
                tok.expect("}")?;
            }
            "}" => return Ok(()),
            t => {
                return Err(ParseError::InJoint {
                    joint: name,
                    found: t.to_string(),
                    token: tok.pos,
                });
            }
        }
    }
}

fn parse_text(text: &str) -> Result<Bvh, ParseError> {
    let (hierarchy, motion) = text.split_once("MOTION").ok_or(ParseError::NoMotion)?;
    let mut tok = Tokens {
        items: hierarchy.split_whitespace().collect(),
        pos: 0,
    };
    tok.expect("HIERARCHY")?;
    tok.expect("ROOT")?;
    let mut joints = Vec::new();
    let mut channels = 0;
    parse_joint(&mut tok, &mut joints, None, &mut channels)?;
    if tok.pos != tok.items.len() {
        return Err(ParseError::AfterRoot {
            found: tok.items[tok.pos].to_string(),
        });
    }
    let mut lines = motion.lines().filter(|l| !l.trim().is_empty());
    let frames_line = lines.next().ok_or(ParseError::NoFrameCount)?;
    let n = frames_line
        .trim()
        .strip_prefix("Frames:")
        .and_then(|s| s.trim().parse::<usize>().ok())
        .ok_or_else(|| ParseError::FrameCount {
            line: frames_line.to_string(),
        })?;
    let time_line = lines.next().ok_or(ParseError::NoFrameTime)?;
    let frame_time = time_line
        .trim()
        .strip_prefix("Frame Time:")
        .and_then(|s| s.trim().parse::<f64>().ok())
        .filter(|t| t.is_finite() && *t > 0.0)
        .ok_or_else(|| ParseError::FrameTime {
            line: time_line.to_string(),
        })?;
    let mut frames = Vec::with_capacity(n);
    for (i, line) in lines.enumerate() {
        let values: Result<Vec<f64>, _> = line.split_whitespace().map(str::parse::<f64>).collect();
        let values = values.map_err(|source| ParseError::Value { frame: i, source })?;
        if values.len() != channels {
            return Err(ParseError::FrameWidth {
                frame: i,
                values: values.len(),
                channels,
            });
        }
        frames.push(values);
    }
    if frames.len() != n {
        return Err(ParseError::FrameLines {
            declared: n,
            found: frames.len(),
        });
    }
    Ok(Bvh {
        joints,
        frame_time,
        frames,
    })
}

/// Parse BVH text; `path` only names the source in errors ([`InputError::Malformed`] with a
/// [`ParseError`]).
pub fn parse(text: &str, path: &Path) -> Result<Bvh, InputError> {
    parse_text(text).map_err(|e| InputError::malformed("BVH file", path, e))
}

impl Bvh {
    /// The index of the joint named `name`.
    pub fn joint(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }

    /// Forward kinematics of frame `frame` (None if there is no such frame): every joint's world
    /// pose in file axes. A joint's local transform is its offset plus its position channels,
    /// and the product of its rotation channels in file order (`Xrotation` a rotation about X by
    /// the value in degrees, right-handed); world = parent world · local.
    pub fn pose(&self, frame: usize) -> Option<Vec<JointPose>> {
        let values = self.frames.get(frame)?;
        let mut poses: Vec<JointPose> = Vec::with_capacity(self.joints.len());
        for j in &self.joints {
            let mut t = j.offset;
            let mut r = DMat3::IDENTITY;
            for (k, c) in j.channels.iter().enumerate() {
                let v = values[j.first_channel + k];
                match c {
                    Xposition => t.x += v,
                    Yposition => t.y += v,
                    Zposition => t.z += v,
                    Xrotation => r *= DMat3::from_rotation_x(v.to_radians()),
                    Yrotation => r *= DMat3::from_rotation_y(v.to_radians()),
                    Zrotation => r *= DMat3::from_rotation_z(v.to_radians()),
                }
            }
            let (pp, pr) = match j.parent {
                Some(p) => (poses[p].position, poses[p].rotation),
                None => (DVec3::ZERO, DMat3::IDENTITY),
            };
            let position = pp + pr * t;
            let rotation = pr * r;
            poses.push(JointPose {
                position,
                rotation,
                end_site: j.end_site.map(|e| position + rotation * e),
            });
        }
        Some(poses)
    }
}
