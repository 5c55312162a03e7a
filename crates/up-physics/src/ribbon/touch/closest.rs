//! Closest points of two segments (Ericson, "Real-Time Collision
//! Detection", 5.1.9), and of a point and a segment.

use glam::Vec3;

/// Below this squared length a segment is taken as a point, m².
const DEGENERATE: f32 = 1e-12;

/// Parameters `(s, t)` in [0, 1] of the closest points `a0 + s·(a1 − a0)`
/// and `b0 + t·(b1 − b0)` of segments `a0a1` and `b0b1`.
pub(super) fn segments(a0: Vec3, a1: Vec3, b0: Vec3, b1: Vec3) -> (f32, f32) {
    let (d1, d2, r) = (a1 - a0, b1 - b0, a0 - b0);
    let (a, e, f) = (d1.dot(d1), d2.dot(d2), d2.dot(r));
    if a <= DEGENERATE && e <= DEGENERATE {
        return (0.0, 0.0);
    }
    if a <= DEGENERATE {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(r);
    if e <= DEGENERATE {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    // Parallel segments: any s will do; 0, then t and s clamped in turn.
    let mut s = if denom > 0.0 {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// Parameter `t` in [0, 1] of the point of segment `b0b1` closest to `p`.
pub(super) fn point_segment(p: Vec3, b0: Vec3, b1: Vec3) -> f32 {
    let d = b1 - b0;
    let e = d.dot(d);
    if e <= DEGENERATE {
        return 0.0;
    }
    ((p - b0).dot(d) / e).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(p0: Vec3, p1: Vec3, s: f32) -> Vec3 {
        p0 + (p1 - p0) * s
    }

    #[test]
    fn crossing_segments_meet_at_their_middles() {
        let (s, t) = segments(
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, -1.0, 0.3),
            Vec3::new(0.0, 1.0, 0.3),
        );
        assert!((s - 0.5).abs() < 1e-6 && (t - 0.5).abs() < 1e-6, "{s} {t}");
    }

    #[test]
    fn the_closest_points_are_no_farther_than_any_sampled_pair() {
        // Segments in many poses, against a brute-force search.
        let mut seed = 1u32;
        let mut next = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1u32 << 24) as f32 - 0.5
        };
        for _ in 0..200 {
            let mut v = || Vec3::new(next(), next(), next());
            let (a0, a1, b0, b1) = (v(), v(), v(), v());
            let (s, t) = segments(a0, a1, b0, b1);
            let found = at(a0, a1, s).distance(at(b0, b1, t));
            let mut best = f32::MAX;
            for i in 0..=50 {
                for j in 0..=50 {
                    let (x, y) = (i as f32 / 50.0, j as f32 / 50.0);
                    best = best.min(at(a0, a1, x).distance(at(b0, b1, y)));
                }
            }
            assert!(found <= best + 1e-5, "{found} > {best}");
        }
    }

    #[test]
    fn a_point_beyond_an_end_is_nearest_that_end() {
        let t = point_segment(Vec3::new(2.0, 1.0, 0.0), Vec3::ZERO, Vec3::X);
        assert_eq!(t, 1.0);
    }
}
