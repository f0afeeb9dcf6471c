//! Lower-body kinematics: pure geometry of the figure around the dynamic models (KLAW 1989 §4.2
//! "cosmetics"): the foot's shape and rolling, the two-link leg, the knee's prescribed curve after
//! heel-off, the determinants of gait, and the virtual stance leg that completes each stance.
pub(crate) mod arc;
pub mod error;
pub mod foot;
pub mod knee_curve;
pub mod leg;
pub mod pelvis;
pub mod stance_leg;

pub use error::GeometryError;
