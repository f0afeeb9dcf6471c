//! The BVH parser and forward kinematics: a file's hierarchy and frames, and every joint's world
//! pose in a frame.
use std::num::ParseFloatError;
use std::path::Path;

use glam::{DMat3, DVec3};

use super::Channel::{self, *};
use crate::model::InputError;

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
