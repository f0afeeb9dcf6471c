//! Where the figure is on the floor (issue 15, item 10 "Heading"): a [`Placement`] puts a walk,
//! simulated in its own frame (along +x from the origin, [`crate::figure`]'s world frame), at a
//! floor point and a heading of the world frame. It is a rigid motion of the floor: a rotation
//! about the vertical (+y) followed by a horizontal translation, so it changes where the figure
//! is and which way it faces, and no joint angle.
//!
//! ```
//! use std::f64::consts::FRAC_PI_2;
//! use klaw::Simulation;
//! use klaw::export::{self, Format, Options};
//! use klaw::figure::placement::Placement;
//!
//! let walk = Simulation::default().steps(2).run()?;
//! // start 2 m ahead and 1 m to the left of the world origin, walking to the left (−z)
//! let at = Placement::new([2.0, -1.0], FRAC_PI_2);
//! let frames: Vec<_> = walk.frames(100.0)?.iter().map(|lm| at.apply(lm)).collect();
//! let last = frames.last().unwrap();
//! assert!(last.pelvis[2] < -2.0 && (last.pelvis[0] - 2.0).abs() < 0.1);
//! let path = std::env::temp_dir().join(format!("klaw-placed-{}.bvh", std::process::id()));
//! export::write(&path, Format::Bvh, walk.body(), 100.0, frames, &Options::default())?;
//! # std::fs::remove_file(&path).unwrap();
//! # Ok::<(), klaw::Error>(())
//! ```
use crate::figure::{Landmarks, LegPoints};
use crate::numerics::trig::{atan2, sin_cos};

/// A rigid motion of the floor: a point p of the figure's own frame is put at
/// `R_y(heading) · p + (origin[0], 0, origin[1])` of the world frame.
///
/// `R_y(h)` turns (x, y, z) to (x cos h + z sin h, y, −x sin h + z cos h): a positive heading
/// turns the figure to its left (its forward +x towards −z), the sense of
/// [`Landmarks::pelvis_rotation`]. The pelvis orientation `R_y(rotation) · R_x(−list) ·
/// R_z(−tilt)` becomes `R_y(heading) · R_y(rotation) · … = R_y(heading + rotation) · …`, so a
/// placement adds its heading to the pelvis rotation and changes nothing else of the figure's
/// angles (the thorax, head and arms are placed relative to the pelvis).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Placement {
    /// The floor point (x, z) of the world (m) where the figure's own origin goes.
    pub origin: [f64; 2],
    /// The heading (rad): the figure's own +x turned about the vertical by this, + to the left.
    pub heading: f64,
}

/// The unit floor vector of `heading`: `R_y(heading) · (1, 0, 0) = (cos h, 0, −sin h)` (0 along
/// +x, π/2 along −z, the figure's left).
pub fn direction(heading: f64) -> [f64; 3] {
    let (s, c) = sin_cos(heading);
    [c, 0.0, -s]
}

/// The heading of a floor direction `v` (its y is ignored), in (−π, π]: the inverse of
/// [`direction`]. A zero horizontal part has heading 0.
pub fn heading_of(v: [f64; 3]) -> f64 {
    atan2(-v[2], v[0])
}

impl Placement {
    /// The figure where it was simulated: no turn, no shift.
    pub const IDENTITY: Placement = Placement {
        origin: [0.0, 0.0],
        heading: 0.0,
    };

    /// The placement at floor point `origin` (x, z) with `heading` (rad).
    pub fn new(origin: [f64; 2], heading: f64) -> Self {
        Placement { origin, heading }
    }

    /// `R_y(heading) · v`: a direction of the figure's own frame in the world.
    pub fn direction(&self, v: [f64; 3]) -> [f64; 3] {
        turn(sin_cos(self.heading), v)
    }

    /// A point of the figure's own frame in the world: `R_y(heading) · p + (origin[0], 0,
    /// origin[1])`.
    pub fn to_world(&self, p: [f64; 3]) -> [f64; 3] {
        self.shift(turn(sin_cos(self.heading), p))
    }

    /// The placement of `inner` within `self`: `inner` given in the frame `self` places, the
    /// result in the world, so that `self.compose(inner).to_world(p) =
    /// self.to_world(inner.to_world(p))` (headings add; `inner`'s origin is put by `self`).
    pub fn compose(&self, inner: &Placement) -> Placement {
        let [x, _, z] = self.to_world([inner.origin[0], 0.0, inner.origin[1]]);
        Placement {
            origin: [x, z],
            heading: self.heading + inner.heading,
        }
    }

    /// The placement that undoes this one: `self.inverse().to_world(self.to_world(p)) = p`
    /// (heading −h, origin `−R_y(−h) · origin`).
    pub fn inverse(&self) -> Placement {
        let back = Placement::new([0.0, 0.0], -self.heading);
        let [x, _, z] = back.direction([self.origin[0], 0.0, self.origin[1]]);
        Placement {
            origin: [-x, -z],
            heading: -self.heading,
        }
    }

    /// The figure `lm` placed in the world: every leg point (hip, knee, ankle, heel, mtp, toe)
    /// and the pelvis centre by [`Placement::to_world`], the knee axes by
    /// [`Placement::direction`], the heading added to the pelvis rotation; the time, the step,
    /// the pelvic tilt and list, the lumbar, neck and arm angles are kept.
    pub fn apply(&self, lm: &Landmarks) -> Landmarks {
        let sc = sin_cos(self.heading);
        let point = |p: [f64; 3]| self.shift(turn(sc, p));
        let leg = |l: &LegPoints| LegPoints {
            hip: point(l.hip),
            knee: point(l.knee),
            ankle: point(l.ankle),
            heel: point(l.heel),
            mtp: point(l.mtp),
            toe: point(l.toe),
            knee_axis: turn(sc, l.knee_axis),
        };
        Landmarks {
            pelvis: point(lm.pelvis),
            pelvis_rotation: lm.pelvis_rotation + self.heading,
            right: leg(&lm.right),
            left: leg(&lm.left),
            ..*lm
        }
    }

    fn shift(&self, [x, y, z]: [f64; 3]) -> [f64; 3] {
        [x + self.origin[0], y, z + self.origin[1]]
    }
}

/// `R_y(h) · v` for `(sin h, cos h)`.
fn turn((s, c): (f64, f64), [x, y, z]: [f64; 3]) -> [f64; 3] {
    [x * c + z * s, y, z * c - x * s]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DMat3, DVec3};
    use std::f64::consts::{FRAC_PI_2, PI};

    fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    /// A figure with every point and angle distinct (not a pose: `apply` is geometry only).
    fn sample() -> Landmarks {
        let leg = |k: f64| LegPoints {
            hip: [0.1 * k, 0.9, 0.08 * k],
            knee: [0.2 * k, 0.5, 0.09 * k],
            ankle: [0.15, 0.08, 0.1 * k],
            heel: [0.1, 0.01, 0.1 * k],
            mtp: [0.3, 0.0, 0.11 * k],
            toe: [0.35, 0.0, 0.12 * k],
            knee_axis: [0.1, 0.2 * k, 0.97],
        };
        Landmarks {
            time: 0.37,
            step: 3,
            pelvis: [1.2, 0.95, -0.02],
            pelvis_tilt: 0.1,
            pelvis_list: -0.05,
            pelvis_rotation: 0.07,
            lumbar_extension: -0.04,
            lumbar_bending: 0.05,
            lumbar_rotation: -0.12,
            neck_rotation: 0.3,
            right: leg(1.0),
            left: leg(-1.0),
            ..Landmarks::default()
        }
    }

    /// The identity (and the default) leaves the figure exactly as it is.
    #[test]
    fn identity_changes_nothing() {
        let lm = sample();
        assert_eq!(Placement::IDENTITY.apply(&lm), lm);
        assert_eq!(Placement::default(), Placement::IDENTITY);
        let p = [0.3, -1.0, 2.5];
        assert_eq!(Placement::IDENTITY.to_world(p), p);
    }

    /// The rotation is glam's `R_y` (an independent implementation) and a heading of 90° turns
    /// the figure's forward (+x) to the world's −z and its right (+z) to +x: with y up and z to
    /// the right, a quarter turn to the left.
    #[test]
    fn heading_is_a_rotation_about_plus_y() {
        let quarter = Placement::new([0.0, 0.0], FRAC_PI_2);
        assert!(close(
            quarter.direction([1.0, 0.0, 0.0]),
            [0.0, 0.0, -1.0],
            1e-15
        ));
        assert!(close(
            quarter.direction([0.0, 0.0, 1.0]),
            [1.0, 0.0, 0.0],
            1e-15
        ));
        assert!(close(direction(FRAC_PI_2), [0.0, 0.0, -1.0], 1e-15));
        for h in [-3.0, -1.1, 0.4, 2.9, 7.5] {
            let p = Placement::new([0.7, -0.2], h);
            for v in [[1.0, 0.0, 0.0], [0.3, -0.8, 2.0], [-1.5, 0.2, -0.4]] {
                let want = DMat3::from_rotation_y(h) * DVec3::from_array(v);
                assert!(close(p.direction(v), want.to_array(), 1e-15), "{h} {v:?}");
                let w = (want + DVec3::new(0.7, 0.0, -0.2)).to_array();
                assert!(close(p.to_world(v), w, 1e-15));
            }
            let dir = direction(h);
            assert!(close(dir, p.direction([1.0, 0.0, 0.0]), 1e-15));
            let wrapped = heading_of(dir);
            assert!(wrapped > -PI && wrapped <= PI);
            let turns = ((h - wrapped) / (2.0 * PI)).round();
            assert!(
                (h - wrapped - 2.0 * PI * turns).abs() < 1e-12,
                "{h} → {wrapped}"
            );
        }
    }

    /// Composition is the composition of the maps, the inverse undoes, composition with the
    /// inverse is the identity (to round-off), and composition is associative.
    #[test]
    fn compose_and_inverse_are_those_of_the_maps() {
        let a = Placement::new([1.5, -0.3], 0.8);
        let b = Placement::new([-0.4, 2.0], -2.1);
        let c = Placement::new([0.05, 0.6], 3.7);
        let p = [0.3, 1.1, -0.6];
        let ab = a.compose(&b);
        assert!(close(ab.to_world(p), a.to_world(b.to_world(p)), 1e-14));
        assert!(close(a.inverse().to_world(a.to_world(p)), p, 1e-14));
        for id in [a.compose(&a.inverse()), a.inverse().compose(&a)] {
            assert!(id.heading.abs() < 1e-15 && id.origin.iter().all(|x| x.abs() < 1e-15));
        }
        let (left, right) = (ab.compose(&c), a.compose(&b.compose(&c)));
        assert!((left.heading - right.heading).abs() < 1e-15);
        assert!(close(
            [left.origin[0], 0.0, left.origin[1]],
            [right.origin[0], 0.0, right.origin[1]],
            1e-14
        ));
    }

    /// `apply` moves every point as `to_world` does, turns the knee axis, adds the heading to
    /// the pelvis rotation and keeps everything else.
    #[test]
    fn apply_places_points_and_adds_the_heading() {
        let lm = sample();
        let at = Placement::new([-3.0, 4.0], 2.2);
        let placed = at.apply(&lm);
        assert_eq!(placed.pelvis, at.to_world(lm.pelvis));
        for (l, p) in [(&lm.right, &placed.right), (&lm.left, &placed.left)] {
            let pairs = [
                (l.hip, p.hip),
                (l.knee, p.knee),
                (l.ankle, p.ankle),
                (l.heel, p.heel),
                (l.mtp, p.mtp),
                (l.toe, p.toe),
            ];
            for (a, b) in pairs {
                assert_eq!(at.to_world(a), b);
            }
            assert_eq!(at.direction(l.knee_axis), p.knee_axis);
        }
        assert_eq!(placed.pelvis_rotation, lm.pelvis_rotation + 2.2);
        let unturned = Landmarks {
            pelvis: lm.pelvis,
            pelvis_rotation: lm.pelvis_rotation,
            right: lm.right,
            left: lm.left,
            ..placed
        };
        assert_eq!(unturned, lm);
    }
}
