//! The flat outlines foil balloons are cut from: a disc, a heart, a star and
//! the digits 0–9, each as a signed distance in the sheet's plane (positive
//! inside, metres), at the size the balloon is sold as (its height, the
//! disc's diameter).
//!
//! Heart and star are polygons: the heart the classic curve
//! `x = 16 sin³t, y = 13 cos t − 5 cos 2t − 2 cos 3t − cos 4t`, the star five
//! points with the inner corners at `STAR_INNER` of the tips' radius, its tips
//! rounded by the same offset that rounds a real sealed rim (2 % of the
//! height). The digits are drawn here, not taken from a font: each is a few
//! strokes (polylines; arcs as 24-point polygons) in a 0.6 × 1 box, drawn
//! with a round pen of radius 0.13 and scaled to the size — the chunky,
//! rounded numerals number balloons are. A point's distance is the pen radius less its distance to the
//! nearest stroke.

use std::f32::consts::{PI, TAU};

use glam::Vec2;

use crate::balloon::mesh::cos_sin;

/// Which outline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutlineKind {
    Disc,
    Heart,
    Star,
    /// 0..=9.
    Digit(u8),
}

/// Radius of the pen the digits are drawn with, in units of their height.
pub const DIGIT_PEN: f32 = 0.13;
/// Rounding of the heart's and star's corners, in units of their height.
const CORNER_ROUNDING: f32 = 0.02;

/// An outline at its size: a signed distance (positive inside) in metres.
#[derive(Clone, Debug)]
pub struct Outline {
    /// Closed polygons (even–odd), minus `rounding` (Minkowski-rounded corners).
    polygons: Vec<Vec<Vec2>>,
    /// Open or closed polylines drawn with a round pen of radius `pen`.
    strokes: Vec<Vec<Vec2>>,
    pen: f32,
    rounding: f32,
}

fn distance_to_segment(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
    p.distance(a + ab * t)
}

/// Points on the arc about `c` of radii `r` from angle `a0` to `a1` (degrees).
fn arc(c: Vec2, r: Vec2, a0: f32, a1: f32) -> Vec<Vec2> {
    (0..=24)
        .map(|i| {
            let a = (a0 + (a1 - a0) * i as f32 / 24.0).to_radians();
            let (cos, sin) = cos_sin(a);
            c + Vec2::new(r.x * cos, r.y * sin)
        })
        .collect()
}

fn v(x: f32, y: f32) -> Vec2 {
    Vec2::new(x, y)
}

/// The strokes of digit `d` in a box 0.6 wide, 1 high, origin at the bottom
/// middle; a closed loop repeats its first point.
fn digit_strokes(d: u8) -> Vec<Vec<Vec2>> {
    let join = |parts: &[Vec<Vec2>]| parts.concat();
    match d {
        0 => vec![arc(v(0.0, 0.5), v(0.2, 0.38), 0.0, 360.0)],
        1 => vec![vec![v(-0.14, 0.72), v(0.04, 0.88), v(0.04, 0.12)]],
        2 => vec![join(&[
            arc(v(0.0, 0.66), v(0.19, 0.2), 160.0, -35.0),
            vec![v(-0.19, 0.12), v(0.2, 0.12)],
        ])],
        3 => vec![join(&[
            arc(v(0.0, 0.7), v(0.17, 0.17), 150.0, -90.0),
            arc(v(0.0, 0.32), v(0.19, 0.2), 90.0, -150.0),
        ])],
        4 => vec![vec![
            v(0.1, 0.12),
            v(0.1, 0.88),
            v(-0.2, 0.34),
            v(0.22, 0.34),
        ]],
        5 => vec![join(&[
            vec![v(0.18, 0.88), v(-0.14, 0.88), v(-0.17, 0.55)],
            arc(v(0.0, 0.34), v(0.19, 0.22), 125.0, -145.0),
        ])],
        6 => vec![
            arc(v(0.0, 0.32), v(0.19, 0.2), 0.0, 360.0),
            join(&[
                arc(v(0.03, 0.58), v(0.22, 0.3), 75.0, 180.0),
                vec![v(-0.19, 0.32)],
            ]),
        ],
        7 => vec![vec![v(-0.2, 0.88), v(0.2, 0.88), v(-0.06, 0.12)]],
        8 => vec![
            arc(v(0.0, 0.71), v(0.15, 0.17), 0.0, 360.0),
            arc(v(0.0, 0.3), v(0.19, 0.19), 0.0, 360.0),
        ],
        _ => digit_strokes(6)
            .into_iter()
            .map(|s| s.into_iter().map(|p| v(-p.x, 1.0 - p.y)).collect())
            .collect(),
    }
}

fn heart(height: f32) -> Vec<Vec2> {
    let raw: Vec<Vec2> = (0..128)
        .map(|i| {
            let t = TAU * i as f32 / 128.0;
            let (c1, s1) = cos_sin(t);
            let c2 = cos_sin(2.0 * t).0;
            let c3 = cos_sin(3.0 * t).0;
            let c4 = cos_sin(4.0 * t).0;
            v(16.0 * s1 * s1 * s1, 13.0 * c1 - 5.0 * c2 - 2.0 * c3 - c4)
        })
        .collect();
    normalised(raw, height)
}

/// The star's inner corners over its tips' radius: a guess from pictures of
/// foil stars (their points are short and broad), set where the 19″ star
/// holds about what a shop chart gives (10.6 L against 0.4 ft³, 11.3 L;
/// docs/scene-format.md).
const STAR_INNER: f32 = 0.65;

fn star(height: f32) -> Vec<Vec2> {
    let raw: Vec<Vec2> = (0..10)
        .map(|i| {
            let r = if i % 2 == 0 { 1.0 } else { STAR_INNER };
            let (cos, sin) = cos_sin(PI / 2.0 + PI * i as f32 / 5.0);
            v(r * cos, r * sin)
        })
        .collect();
    normalised(raw, height)
}

/// Scaled to `height` tall, centred across, the bottom at y = 0;
/// counter-clockwise.
fn normalised(mut points: Vec<Vec2>, height: f32) -> Vec<Vec2> {
    let (lo, hi) = points.iter().fold((Vec2::MAX, Vec2::MIN), |(lo, hi), &p| {
        (lo.min(p), hi.max(p))
    });
    let scale = height / (hi.y - lo.y);
    for p in &mut points {
        *p = v((p.x - 0.5 * (lo.x + hi.x)) * scale, (p.y - lo.y) * scale);
    }
    let twice_area: f32 = points
        .iter()
        .zip(points.iter().cycle().skip(1))
        .map(|(a, b)| a.perp_dot(*b))
        .sum();
    if twice_area < 0.0 {
        points.reverse();
    }
    points
}

impl Outline {
    /// One polygon drawn `rounding` in from the outline, raised by it so the
    /// rounded outline still starts at y = 0.
    fn rounded(polygon: Vec<Vec2>, rounding: f32) -> Self {
        Self {
            polygons: vec![polygon.into_iter().map(|p| p + v(0.0, rounding)).collect()],
            strokes: vec![],
            pen: 0.0,
            rounding,
        }
    }

    /// `kind` at `size` m (its height; the disc's diameter).
    pub fn new(kind: OutlineKind, size: f32) -> Self {
        let rounding = CORNER_ROUNDING * size;
        match kind {
            OutlineKind::Disc => Self {
                polygons: vec![],
                strokes: vec![vec![v(0.0, 0.5 * size)]],
                pen: 0.5 * size,
                rounding: 0.0,
            },
            OutlineKind::Heart => Self::rounded(heart(size - 2.0 * rounding), rounding),
            OutlineKind::Star => Self::rounded(star(size - 2.0 * rounding), rounding),
            OutlineKind::Digit(d) => {
                // Scaled so the strokes with the pen are `size` tall.
                let strokes = digit_strokes(d.min(9));
                let (lo, hi) = strokes
                    .iter()
                    .flatten()
                    .fold((f32::MAX, f32::MIN), |(lo, hi), p| {
                        (lo.min(p.y), hi.max(p.y))
                    });
                let scale = size / (hi - lo + 2.0 * DIGIT_PEN);
                let shift = v(0.0, DIGIT_PEN - lo);
                Self {
                    polygons: vec![],
                    strokes: strokes
                        .into_iter()
                        .map(|s| s.into_iter().map(|p| (p + shift) * scale).collect())
                        .collect(),
                    pen: DIGIT_PEN * scale,
                    rounding: 0.0,
                }
            }
        }
    }

    /// m: signed distance of `p` from the outline, positive inside.
    pub fn distance(&self, p: Vec2) -> f32 {
        let mut best = f32::NEG_INFINITY;
        for poly in &self.polygons {
            let mut inside = false;
            let mut edge = f32::INFINITY;
            for (i, &a) in poly.iter().enumerate() {
                let b = poly[(i + 1) % poly.len()];
                edge = edge.min(distance_to_segment(p, a, b));
                if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x)
                {
                    inside = !inside;
                }
            }
            best = best.max(if inside { edge } else { -edge } + self.rounding);
        }
        for stroke in &self.strokes {
            let near = match stroke.len() {
                1 => p.distance(stroke[0]),
                _ => stroke
                    .windows(2)
                    .map(|w| distance_to_segment(p, w[0], w[1]))
                    .fold(f32::INFINITY, f32::min),
            };
            best = best.max(self.pen - near);
        }
        best
    }

    /// (min, max) corners of a box holding the outline, m.
    pub fn bounds(&self) -> (Vec2, Vec2) {
        let pad = Vec2::splat(self.pen + self.rounding);
        self.polygons
            .iter()
            .chain(&self.strokes)
            .flatten()
            .fold((Vec2::MAX, Vec2::MIN), |(lo, hi), &p| {
                (lo.min(p - pad), hi.max(p + pad))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_disc_is_its_radius_less_the_distance_from_its_centre() {
        let o = Outline::new(OutlineKind::Disc, 0.4);
        assert!((o.distance(v(0.0, 0.2)) - 0.2).abs() < 1e-6);
        assert!((o.distance(v(0.3, 0.2)) + 0.1).abs() < 1e-6);
    }

    #[test]
    fn every_outline_is_as_tall_as_its_size_and_inside_at_its_middle() {
        for kind in [OutlineKind::Heart, OutlineKind::Star]
            .into_iter()
            .chain((0..10).map(OutlineKind::Digit))
        {
            let o = Outline::new(kind, 1.0);
            let (lo, hi) = o.bounds();
            assert!(
                (lo.y - 0.0).abs() < 0.05 && (hi.y - 1.0).abs() < 0.05,
                "{kind:?}"
            );
            // Some point inside, and nothing inside far off.
            assert!(o.distance(v(0.0, 0.5)) > 0.0 || o.distance(v(0.15, 0.5)) > 0.0);
            assert!(o.distance(v(2.0, 0.5)) < 0.0, "{kind:?}");
        }
        // The 0 has a hole, the 8 two.
        assert!(Outline::new(OutlineKind::Digit(0), 1.0).distance(v(0.0, 0.5)) < 0.0);
        assert!(Outline::new(OutlineKind::Digit(8), 1.0).distance(v(0.0, 0.3)) < 0.0);
    }
}
