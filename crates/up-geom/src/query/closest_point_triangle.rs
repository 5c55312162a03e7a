//! Closest point on a triangle, by Voronoi regions (Ericson, *Real-Time
//! Collision Detection*, §5.1.5).
//!
//! The vertex and edge regions are tested first with dot products only; the
//! face case projects onto the plane. When the triangle's area is zero or
//! too small to trust (collinear or coincident corners, slivers), the triangle
//! is treated as its three edges and the nearest segment point wins, so the
//! result is always a finite point on the triangle.

use glam::Vec3;

/// Where on a triangle a closest point lies. Edge k runs from vertex k to
/// vertex (k + 1) % 3.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TriangleRegion {
    Face,
    Edge(u8),
    Vertex(u8),
}

/// Below this ratio of the squared double area to `|ab|²·|ac|²` (the sine
/// squared of the corner angle at `a`) the face formula is not trusted.
const SLIVER_SIN2: f32 = 1e-10;

/// Closest point to `p` on triangle `abc`, and the Voronoi region it lies in.
pub fn closest_point_triangle(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> (Vec3, TriangleRegion) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, TriangleRegion::Vertex(0));
    }

    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, TriangleRegion::Vertex(1));
    }

    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, TriangleRegion::Vertex(2));
    }

    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let t = d1 / (d1 - d3);
        if t.is_finite() {
            return (a + ab * t.clamp(0.0, 1.0), TriangleRegion::Edge(0));
        }
    }

    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let t = d2 / (d2 - d6);
        if t.is_finite() {
            return (a + ac * t.clamp(0.0, 1.0), TriangleRegion::Edge(2));
        }
    }

    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        if t.is_finite() {
            return (b + (c - b) * t.clamp(0.0, 1.0), TriangleRegion::Edge(1));
        }
    }

    // Face region by elimination. Project onto the plane with the normal
    // computed directly (the sum va + vb + vc equals |n|² only in exact
    // arithmetic and cancels badly for slivers), then confirm the projection
    // is inside; if rounding put it outside, the edge fallback is exact.
    let n = ab.cross(ac);
    let nn = n.length_squared();
    if nn > SLIVER_SIN2 * ab.length_squared() * ac.length_squared() {
        let q = p - n * (ap.dot(n) / nn);
        let inside = (b - a).cross(q - a).dot(n) >= 0.0
            && (c - b).cross(q - b).dot(n) >= 0.0
            && (a - c).cross(q - c).dot(n) >= 0.0;
        if inside && q.is_finite() {
            return (q, TriangleRegion::Face);
        }
    }
    closest_point_on_edges(p, [a, b, c])
}

/// Closest point to `p` on the segment `a`–`b` and its parameter in [0, 1].
#[inline]
pub fn closest_point_segment(p: Vec3, a: Vec3, b: Vec3) -> (Vec3, f32) {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 <= f32::MIN_POSITIVE {
        return (a, 0.0);
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    (a + ab * t, t)
}

/// Fallback for degenerate triangles: the nearest point over the three edges.
fn closest_point_on_edges(p: Vec3, corners: [Vec3; 3]) -> (Vec3, TriangleRegion) {
    let mut best = (corners[0], TriangleRegion::Vertex(0));
    let mut best_d2 = f32::INFINITY;
    for k in 0..3u8 {
        let (a, b) = (corners[k as usize], corners[(k as usize + 1) % 3]);
        let (q, t) = closest_point_segment(p, a, b);
        let d2 = (p - q).length_squared();
        if d2 < best_d2 {
            best_d2 = d2;
            let region = if t <= 0.0 {
                TriangleRegion::Vertex(k)
            } else if t >= 1.0 {
                TriangleRegion::Vertex((k + 1) % 3)
            } else {
                TriangleRegion::Edge(k)
            };
            best = (q, region);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const A: Vec3 = Vec3::new(0.0, 0.0, 0.0);
    const B: Vec3 = Vec3::new(2.0, 0.0, 0.0);
    const C: Vec3 = Vec3::new(0.0, 2.0, 0.0);

    fn check(p: Vec3, expected: Vec3, region: TriangleRegion) {
        let (q, r) = closest_point_triangle(p, A, B, C);
        assert_eq!(r, region, "region for {p}");
        assert!(
            q.distance(expected) < 1e-6,
            "point for {p}: {q} vs {expected}"
        );
    }

    #[test]
    fn face_region_projects_onto_the_plane() {
        check(
            Vec3::new(0.5, 0.5, 3.0),
            Vec3::new(0.5, 0.5, 0.0),
            TriangleRegion::Face,
        );
        check(
            Vec3::new(0.5, 0.5, -3.0),
            Vec3::new(0.5, 0.5, 0.0),
            TriangleRegion::Face,
        );
    }

    #[test]
    fn vertex_regions() {
        check(Vec3::new(-1.0, -1.0, 1.0), A, TriangleRegion::Vertex(0));
        check(Vec3::new(3.0, -1.0, 0.0), B, TriangleRegion::Vertex(1));
        check(Vec3::new(-0.5, 3.0, 0.5), C, TriangleRegion::Vertex(2));
    }

    #[test]
    fn edge_regions() {
        check(
            Vec3::new(1.0, -1.0, 1.0),
            Vec3::new(1.0, 0.0, 0.0),
            TriangleRegion::Edge(0),
        );
        check(
            Vec3::new(2.0, 2.0, -1.0),
            Vec3::new(1.0, 1.0, 0.0),
            TriangleRegion::Edge(1),
        );
        check(
            Vec3::new(-1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            TriangleRegion::Edge(2),
        );
    }

    #[test]
    fn coincident_corners_give_that_point() {
        let p = Vec3::new(1.0, 2.0, 3.0);
        let v = Vec3::new(0.5, 0.5, 0.5);
        let (q, r) = closest_point_triangle(p, v, v, v);
        assert_eq!(q, v);
        assert!(matches!(r, TriangleRegion::Vertex(_)));
    }

    #[test]
    fn collinear_corners_behave_like_a_segment() {
        let (a, b, c) = (
            Vec3::ZERO,
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
        );
        for p in [
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(0.5, 0.0, -2.0),
            Vec3::new(-1.0, 1.0, 1.0),
        ] {
            let (q, _) = closest_point_triangle(p, a, b, c);
            let expected = Vec3::new(p.x.clamp(0.0, 3.0), 0.0, 0.0);
            assert!(q.distance(expected) < 1e-6, "{p}: {q}");
        }
    }

    #[test]
    fn point_in_the_plane_inside_is_itself() {
        let p = Vec3::new(0.3, 0.4, 0.0);
        let (q, r) = closest_point_triangle(p, A, B, C);
        assert_eq!(r, TriangleRegion::Face);
        assert!(q.distance(p) < 1e-7);
    }

    fn brute_force_distance(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> f32 {
        const N: usize = 120;
        let mut best = f32::INFINITY;
        for i in 0..=N {
            for j in 0..=(N - i) {
                let (u, v) = (i as f32 / N as f32, j as f32 / N as f32);
                let q = a + (b - a) * u + (c - a) * v;
                best = best.min(p.distance(q));
            }
        }
        best
    }

    /// Distance from `q` to the triangle, by the segment fallback and the
    /// plane: zero when `q` lies on the triangle.
    fn distance_to_triangle_exact(q: Vec3, a: Vec3, b: Vec3, c: Vec3) -> f64 {
        let (qd, ad, bd, cd) = (q.as_dvec3(), a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
        let n = (bd - ad).cross(cd - ad);
        let seg = |p0: glam::DVec3, p1: glam::DVec3| {
            let e = p1 - p0;
            let l = e.length_squared();
            let t = if l > 0.0 {
                ((qd - p0).dot(e) / l).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (qd - (p0 + e * t)).length()
        };
        let edges = seg(ad, bd).min(seg(bd, cd)).min(seg(cd, ad));
        if n.length_squared() > 1e-20 {
            let inside = [(ad, bd), (bd, cd), (cd, ad)]
                .iter()
                .all(|&(p0, p1)| (p1 - p0).cross(qd - p0).dot(n) >= 0.0);
            if inside {
                return (qd - ad).dot(n.normalize()).abs();
            }
        }
        edges
    }

    fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
        (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        #[test]
        fn matches_dense_barycentric_sampling(
            p in vec3(3.0), a in vec3(1.0), b in vec3(1.0), c in vec3(1.0)
        ) {
            let (q, _) = closest_point_triangle(p, a, b, c);
            prop_assert!(q.is_finite());
            // The sampling grid is at most ~2/120 from any triangle point.
            let brute = brute_force_distance(p, a, b, c);
            prop_assert!(p.distance(q) <= brute + 1e-4, "{} vs {}", p.distance(q), brute);
            prop_assert!(distance_to_triangle_exact(q, a, b, c) < 1e-4);
        }

        #[test]
        fn degenerate_triangles_give_a_point_on_them(
            p in vec3(3.0), a in vec3(1.0), d in vec3(1.0), s in -2.0f32..2.0, pick in 0usize..3
        ) {
            // Collinear (c on the line ab) or coincident corners.
            let b = a + d;
            let c = if pick == 0 { a + d * s } else if pick == 1 { a } else { b };
            let (q, _) = closest_point_triangle(p, a, b, c);
            prop_assert!(q.is_finite());
            prop_assert!(distance_to_triangle_exact(q, a, b, c) < 1e-4);
            let brute = brute_force_distance(p, a, b, c);
            prop_assert!(p.distance(q) <= brute + 1e-4);
        }

        #[test]
        fn slivers_give_a_point_on_them(
            p in vec3(3.0), a in vec3(1.0), d in vec3(1.0), s in -2.0f32..2.0, off in vec3(1e-5)
        ) {
            let (b, c) = (a + d, a + d * s + off);
            let (q, _) = closest_point_triangle(p, a, b, c);
            prop_assert!(q.is_finite());
            prop_assert!(distance_to_triangle_exact(q, a, b, c) < 1e-4);
            let brute = brute_force_distance(p, a, b, c);
            prop_assert!(p.distance(q) <= brute + 1e-4);
        }
    }
}
