//! The floor seen from above, shared by the footprint figure ([`crate::plot::footprints`]) and
//! the top view of a scenario's animation ([`crate::plot::animation`]).
//!
//! Top-view coordinates (u, v) = (x, −z): the viewer looks down the world's −y, x to the right
//! and −z up (x × −z = y points at the viewer, so the picture is not mirrored). A figure facing
//! heading 0 (+x) has its left (−z) above its right. A heading d (rad, + left, about +y) points
//! along (x, z) = (cos d, −sin d), i.e. (u, v) = (cos d, sin d): a positive heading turns the
//! arrow counter-clockwise on the page.
//!
//! A foot is drawn as an outline from the heel l8 behind the ankle to the toe tip l13 beyond
//! the metatarsal joint, itself √(l12² − l9²) ahead of the ankle (the flat foot of
//! [`crate::figure::skeleton`]), of breadth `FOOT_BREADTH_PER_LENGTH` times that length, widest
//! at the ball and with the big toe (the longest) on the medial side, so that a left and a
//! right print differ in shape as well as in colour.
use plotters::prelude::*;

use crate::figure::Landmarks;
use crate::figure::skeleton::{Side, Skeleton};
use crate::model::body::Body;
use crate::plot::{Chart, Drawn, LEFT_COLOR, RIGHT_COLOR, msg};
use crate::scenario::Footprint;

/// Foot breadth over foot length: 0.055 H / 0.152 H, Drillis & Contini (1966) as drawn in Winter,
/// *Biomechanics and Motor Control of Human Movement* (4th ed., 2009), Fig. 4.1 (the body table
/// has no foot breadth; the figure only draws it).
pub const FOOT_BREADTH_PER_LENGTH: f64 = 0.055 / 0.152;

/// The gaze arrows' colour.
pub(crate) const GAZE_COLOR: RGBColor = RGBColor(44, 160, 44);

/// The outline of a foot: (fraction of the foot's length from the heel, fraction of its breadth
/// towards the medial side), going round from the heel along the lateral side.
const OUTLINE: [(f64, f64); 18] = [
    (0.00, 0.00),
    (0.02, -0.26),
    (0.08, -0.36),
    (0.20, -0.40),
    (0.45, -0.44),
    (0.68, -0.50),
    (0.80, -0.46),
    (0.87, -0.36),
    (0.93, -0.16),
    (0.98, 0.06),
    (1.00, 0.22),
    (0.98, 0.38),
    (0.92, 0.46),
    (0.72, 0.50),
    (0.50, 0.30),
    (0.30, 0.26),
    (0.12, 0.30),
    (0.03, 0.24),
];

/// The top-view point (u, v) of the floor point (x, z).
pub fn top(x: f64, z: f64) -> (f64, f64) {
    (x, -z)
}

/// The top-view unit vector (u, v) of heading `direction` (rad, + left).
pub fn heading_vector(direction: f64) -> (f64, f64) {
    (direction.cos(), direction.sin())
}

/// The side's colour, in every figure.
pub(crate) fn side_color(side: Side) -> RGBColor {
    match side {
        Side::Right => RIGHT_COLOR,
        Side::Left => LEFT_COLOR,
    }
}

/// The outline of `side`'s flat foot with its ankle over the floor point `ankle` (x, z) and
/// heading `direction` (rad, + left), in top-view coordinates (m).
pub fn foot_outline(body: &Body, side: Side, ankle: [f64; 2], direction: f64) -> Vec<(f64, f64)> {
    let length = body.l8 + body.ankle_to_metatarsal_horizontal() + body.l13;
    let breadth = FOOT_BREADTH_PER_LENGTH * length;
    let (a_u, a_v) = top(ankle[0], ankle[1]);
    let (fu, fv) = heading_vector(direction);
    // the foot's left is the forward vector turned a quarter counter-clockwise; the medial side
    // is the right foot's left and the left foot's right (Side::sign: +1 right)
    let (mu, mv) = (-fv * side.sign(), fu * side.sign());
    OUTLINE
        .iter()
        .map(|&(f, w)| {
            let along = f * length - body.l8;
            let across = w * breadth;
            (
                a_u + fu * along + mu * across,
                a_v + fv * along + mv * across,
            )
        })
        .collect()
}

/// The heading (rad, + left) the head faces: its forward (x) axis projected on the floor.
pub(crate) fn gaze_heading(sk: &Skeleton) -> f64 {
    let forward = sk.head.axes.x_axis;
    (-forward.z).atan2(forward.x)
}

/// The top-view point under the pelvis centre.
pub(crate) fn pelvis_point(lm: &Landmarks) -> (f64, f64) {
    top(lm.pelvis[0], lm.pelvis[2])
}

/// The extent (u range, v range) of the footprints' outlines and the pelvis path, padded by
/// `pad` m on every side.
pub(crate) fn extent(
    footprints: &[Footprint],
    frames: &[Landmarks],
    body: &Body,
    pad: f64,
) -> ((f64, f64), (f64, f64)) {
    let points = footprints
        .iter()
        .flat_map(|f| foot_outline(body, f.side, f.ankle, f.direction))
        .chain(frames.iter().map(pelvis_point))
        .filter(|(u, v)| u.is_finite() && v.is_finite());
    let (mut u, mut v) = ((0.0, 0.0), (0.0, 0.0));
    for (i, (pu, pv)) in points.enumerate() {
        if i == 0 {
            (u, v) = ((pu, pu), (pv, pv));
        }
        u = (u.0.min(pu), u.1.max(pu));
        v = (v.0.min(pv), v.1.max(pv));
    }
    ((u.0 - pad, u.1 + pad), (v.0 - pad, v.1 + pad))
}

/// The footprints' outlines, filled pale and edged in their side's colour; `opacity` scales
/// both (the animation draws the footprints fainter than the figure).
pub(crate) fn draw_footprints<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    footprints: &[Footprint],
    body: &Body,
    opacity: f64,
) -> Drawn {
    for f in footprints {
        let outline = foot_outline(body, f.side, f.ankle, f.direction);
        let color = side_color(f.side);
        let mut closed = outline.clone();
        closed.push(outline[0]);
        chart
            .draw_series([
                Polygon::new(outline, color.mix(0.18 * opacity).filled()).into_dyn(),
                PathElement::new(closed, color.mix(opacity).stroke_width(2)).into_dyn(),
            ])
            .map_err(msg)?;
    }
    Ok(())
}

/// An arrow of `length` m from `from` (top-view) along heading `direction`.
pub(crate) fn arrow(from: (f64, f64), direction: f64, length: f64) -> Vec<(f64, f64)> {
    let (du, dv) = heading_vector(direction);
    let tip = (from.0 + length * du, from.1 + length * dv);
    let head = |turn: f64| {
        let (bu, bv) = heading_vector(direction + std::f64::consts::PI + turn);
        (tip.0 + 0.3 * length * bu, tip.1 + 0.3 * length * bv)
    };
    vec![from, tip, head(0.45), tip, head(-0.45)]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> Body {
        Body::standard(1.8, 80.0).unwrap()
    }

    /// The outline's point furthest along the heading, and its mean sideways offset.
    fn toe_and_side(outline: &[(f64, f64)], ankle: (f64, f64), d: f64) -> (f64, f64) {
        let (fu, fv) = heading_vector(d);
        let along = |p: &(f64, f64)| (p.0 - ankle.0) * fu + (p.1 - ankle.1) * fv;
        // the foot's left, a quarter turn counter-clockwise from forward
        let left = |p: &(f64, f64)| -(p.0 - ankle.0) * fv + (p.1 - ankle.1) * fu;
        let toe = outline.iter().map(along).fold(f64::NEG_INFINITY, f64::max);
        let heel = outline.iter().map(along).fold(f64::INFINITY, f64::min);
        assert!(heel < 0.0, "the heel is behind the ankle");
        // the big toe: the point furthest forward, on the medial side
        let tip = outline
            .iter()
            .max_by(|a, b| along(a).total_cmp(&along(b)))
            .unwrap();
        (toe, left(tip))
    }

    #[test]
    fn a_foot_points_along_its_heading_and_spans_the_foot() {
        let b = body();
        let length = b.l8 + b.ankle_to_metatarsal_horizontal() + b.l13;
        for d in [0.0, 0.7, -2.0, std::f64::consts::PI] {
            let o = foot_outline(&b, Side::Right, [1.0, 2.0], d);
            let (toe, _) = toe_and_side(&o, top(1.0, 2.0), d);
            // the toe tip √(l12² − l9²) + l13 ahead of the ankle
            let ahead = b.ankle_to_metatarsal_horizontal() + b.l13;
            assert!((toe - ahead).abs() < 1e-12, "{toe} vs {ahead}");
            // the breadth: the widest cross-section is the breadth ratio of the length
            let (fu, fv) = heading_vector(d);
            let side = |p: &(f64, f64)| -(p.0 - 1.0) * fv + (p.1 + 2.0) * fu;
            let w = o.iter().map(side).fold(f64::NEG_INFINITY, f64::max)
                - o.iter().map(side).fold(f64::INFINITY, f64::min);
            assert!((w - FOOT_BREADTH_PER_LENGTH * length).abs() < 1e-12);
        }
    }

    #[test]
    fn the_big_toe_is_on_the_medial_side() {
        let b = body();
        // heading 0: the figure's left is up (v = −z > 0); the right foot's big toe is on its
        // left, the left foot's on its right
        let (_, right) = toe_and_side(
            &foot_outline(&b, Side::Right, [0.0, 0.0], 0.0),
            (0.0, 0.0),
            0.0,
        );
        let (_, left) = toe_and_side(
            &foot_outline(&b, Side::Left, [0.0, 0.0], 0.0),
            (0.0, 0.0),
            0.0,
        );
        assert!(right > 0.0 && left < 0.0, "{right} {left}");
    }

    #[test]
    fn the_left_is_up_at_heading_zero_and_headings_turn_counter_clockwise() {
        // the world's left at heading 0 is −z: up in the top view
        assert_eq!(top(0.0, -1.0), (0.0, 1.0));
        // a quarter turn left faces −z: up
        let (u, v) = heading_vector(std::f64::consts::FRAC_PI_2);
        assert!(u.abs() < 1e-15 && (v - 1.0).abs() < 1e-15);
    }
}
