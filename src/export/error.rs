//! Motion that cannot be exported as asked.
use std::path::PathBuf;

/// An export that cannot be written as asked: its format, its frames or, for BVH, a frame the
/// format cannot represent.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A path whose extension names no motion format.
    #[error("{path}: unknown output format; the extension must be .csv, .mot, .sto or .bvh")]
    UnknownFormat {
        /// The path given.
        path: PathBuf,
    },
    /// Frame `frame`'s time (s) is not after the previous frame's.
    #[error("frame {frame}: time {time} s does not follow the previous frame's {previous} s")]
    OutOfOrder {
        /// The frame's index, from 0.
        frame: usize,
        /// The frame's time (in s).
        time: f64,
        /// The previous frame's time (in s).
        previous: f64,
    },
    /// No frame was given.
    #[error("{path}: no frames to export")]
    NoFrames {
        /// The path to export to.
        path: PathBuf,
    },
    /// A BVH frame is not 1/fps after the previous one: BVH has one frame time.
    #[error(
        "BVH frame {frame}: time {time} s, but frames 1/{fps} s apart from {first} s put it at {expected} s"
    )]
    FrameTime {
        /// The frame's index, from 0.
        frame: usize,
        /// The frame's time (in s).
        time: f64,
        /// The frame rate (in frames/s).
        fps: f64,
        /// The first frame's time (in s).
        first: f64,
        /// The time one frame time per frame after `first` gives it (in s).
        expected: f64,
    },
    /// A landmark is `distance` (m) from where the body's segment lengths, BVH's fixed offsets,
    /// put it (more than `tolerance`, m).
    #[error(
        "frame at t = {time} s: landmark {landmark} is {:.3} mm from where the body's segment \
         lengths put it (the BVH offsets are those lengths; tolerance {} mm)",
        distance * 1e3,
        tolerance * 1e3
    )]
    SegmentLength {
        /// The frame's time (in s).
        time: f64,
        /// The landmark farthest from its place.
        landmark: String,
        /// Its distance from where the segment lengths put it (in m).
        distance: f64,
        /// The largest distance allowed (in m).
        tolerance: f64,
    },
    /// An animation needs between 1 and `max` frames.
    #[error("{path}: {frames} frames to animate; between 1 and {max} are needed")]
    FrameCount {
        /// The animation's path.
        path: PathBuf,
        /// The number of frames given.
        frames: usize,
        /// The most frames an animation may have.
        max: usize,
    },
}
