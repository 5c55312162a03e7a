//! Whether a point in a triangle's plane lies within a distance of the
//! triangle, decided from its three edge lines where the answer is sure, so
//! that the closest point (`closest_point_triangle`) is sought only within
//! that distance of an edge.
//!
//! A point at least `margin` inside every edge line is on the triangle (its
//! closest point is itself, up to rounding); a point more than the distance
//! and `margin` outside any edge line is farther than the distance (the
//! triangle lies wholly on the inner side of each of its edge lines).
//! `margin` is far wider than the rounding of both tests and of the closest
//! point's own arithmetic, so each sure answer is the one that arithmetic
//! gives; between the two, and for a triangle too thin or too far out for
//! that to hold, there is no sure answer.

use glam::Vec3;

/// The margin's floor, m: a tenth of a millimetre.
const MIN_MARGIN: f32 = 1e-4;
/// The margin's share of the triangle's largest coordinate, in units of
/// f32's epsilon: a few dot products' rounding, many times over.
const MARGIN_EPSILONS: f32 = 32.0;
/// A triangle lower than this many margins over any of its edges gets no
/// sure answers (a sliver: its closest point falls back to its edges).
const MIN_HEIGHT_MARGINS: f32 = 100.0;
/// Largest coordinate of a triangle that gets sure answers, m: beyond, the
/// closest point's own rounding nears a ribbon's radius.
const MAX_COORDINATE: f32 = 1000.0;

/// A triangle's edge lines in its plane, for `within`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleReach {
    /// Per edge `k` (corner `k` to corner `k + 1`): its unit normal in the
    /// plane, pointing into the triangle.
    inward: [Vec3; 3],
    /// Per edge: `inward[k]` · corner `k`.
    offset: [f32; 3],
    /// m; infinite where no answer is sure.
    margin: f32,
}

impl TriangleReach {
    /// The edge lines of triangle `corners` whose plane has unit normal
    /// `normal` (either side).
    pub fn new(corners: [Vec3; 3], normal: Vec3) -> TriangleReach {
        let scale = corners
            .iter()
            .fold(0.0f32, |m, c| m.max(c.abs().max_element()));
        let mut reach = TriangleReach {
            inward: [Vec3::ZERO; 3],
            offset: [0.0; 3],
            margin: MIN_MARGIN + MARGIN_EPSILONS * f32::EPSILON * scale,
        };
        let mut lowest = f32::INFINITY;
        for k in 0..3 {
            let (from, to, opposite) = (corners[k], corners[(k + 1) % 3], corners[(k + 2) % 3]);
            let across = normal.cross(to - from).normalize_or_zero();
            let height = across.dot(opposite - from);
            let inward = if height < 0.0 { -across } else { across };
            reach.inward[k] = inward;
            reach.offset[k] = inward.dot(from);
            lowest = lowest.min(height.abs());
        }
        let usable = scale <= MAX_COORDINATE
            && (normal.length_squared() - 1.0).abs() < 1e-4
            && lowest >= MIN_HEIGHT_MARGINS * reach.margin;
        if !usable {
            reach.margin = f32::INFINITY;
        }
        reach
    }

    /// Its edge lines: per edge, the unit normal in the plane pointing into
    /// the triangle and that normal's dot product with the edge's first
    /// corner; and the margin (infinite where no answer is sure). For a test
    /// of several points at once that must answer as `within` does.
    pub fn lines(&self) -> ([Vec3; 3], [f32; 3], f32) {
        (self.inward, self.offset, self.margin)
    }

    /// Whether `point`, in the triangle's plane, is within `distance` of
    /// the triangle, where that is sure: `Some(true)` on it, `Some(false)`
    /// farther, `None` unsure (near an edge, a thin triangle, a NaN).
    #[inline]
    pub fn within(&self, point: Vec3, distance: f32) -> Option<bool> {
        let m = self.margin;
        let s0 = point.dot(self.inward[0]) - self.offset[0];
        let s1 = point.dot(self.inward[1]) - self.offset[1];
        let s2 = point.dot(self.inward[2]) - self.offset[2];
        if s0 >= m && s1 >= m && s2 >= m {
            return Some(true);
        }
        let out = -(distance + m);
        if s0 < out || s1 < out || s2 < out {
            return Some(false);
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::closest_point_triangle;
    use crate::SplitMix64;

    /// Random triangles (room-sized, small, long and thin, slivers) and
    /// points in their planes around them, at and near their edges: every
    /// sure answer is the closest point's.
    #[test]
    fn sure_answers_agree_with_the_closest_point() {
        let mut rng = SplitMix64::new(7);
        let mut next = move || rng.range(-1.0, 1.0);
        let (mut sure, mut total) = (0, 0);
        for round in 0..3000 {
            let size = [6.0, 0.05, 40.0, 900.0][round % 4];
            let origin = Vec3::new(next(), next(), next()) * [0.0, 3.0, 200.0, 100.0][round % 4];
            let mut corner = || origin + Vec3::new(next(), next(), next()) * size;
            let (a, b) = (corner(), corner());
            let c = if round % 7 == 0 {
                // A sliver: the third corner nearly on the first edge.
                a.lerp(b, 0.3) + Vec3::new(next(), next(), next()) * size * 1e-4
            } else {
                corner()
            };
            let normal = (b - a).cross(c - a).normalize_or_zero();
            if normal == Vec3::ZERO {
                continue;
            }
            let reach = TriangleReach::new([a, b, c], normal);
            for _ in 0..40 {
                let radius = [0.0025, 0.025][total % 2];
                // Around the triangle, and a radius or so off its edges.
                let w = Vec3::new(next(), next(), next()) * 1.2 + 0.4;
                let mut p = (a * w.x + b * w.y + c * w.z) / (w.x + w.y + w.z);
                let edge = total % 3;
                let (e0, e1) = [(a, b), (b, c), (c, a)][edge];
                if total % 2 == 0 {
                    let along = e0.lerp(e1, next() * 0.6 + 0.5);
                    let off = normal.cross(e1 - e0).normalize_or_zero();
                    p = along + off * radius * (next() * 1.5);
                }
                p -= (p - a).dot(normal) * normal;
                let (closest, _) = closest_point_triangle(p, a, b, c);
                let within = closest.distance_squared(p) <= radius * radius;
                if let Some(answer) = reach.within(p, radius) {
                    assert_eq!(answer, within, "round {round}: {p} against {a} {b} {c}");
                    sure += 1;
                }
                total += 1;
            }
        }
        assert!(sure > total / 2 && sure < total, "{sure} of {total} sure");
    }

    #[test]
    fn a_nan_point_or_a_sliver_gets_no_sure_answer() {
        let (a, b, c) = (Vec3::ZERO, Vec3::X, Vec3::Z);
        let reach = TriangleReach::new([a, b, c], Vec3::Y);
        assert_eq!(reach.within(Vec3::new(0.2, 0.0, 0.2), 0.01), Some(true));
        assert_eq!(reach.within(Vec3::new(2.0, 0.0, 0.2), 0.01), Some(false));
        assert_eq!(reach.within(Vec3::new(0.5, 0.0, -0.005), 0.01), None);
        assert_eq!(reach.within(Vec3::NAN, 0.01), None);
        let sliver = TriangleReach::new([a, b, Vec3::new(0.5, 0.0, 1e-3)], Vec3::Y);
        assert_eq!(sliver.within(Vec3::new(0.5, 0.0, 5e-4), 0.01), None);
        assert_eq!(sliver.within(Vec3::new(0.5, 0.0, 3.0), 0.01), None);
    }
}
