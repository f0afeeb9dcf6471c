//! Lower-body kinematics: pure functions of the dynamic state (KLAW 1989 §4.2 "cosmetics"):
//! the foot's shape and rolling, and the kinematic completion of the hind leg's stance.
pub mod foot;
pub mod pelvis;
pub mod stance_leg;
