//! Time of impact of a linearly moving sphere with a one-sided triangle.
//!
//! Centre c(t) = c + v·t, radius r, triangle with unit normal n and height
//! h(t) = (c(t) − a)·n. The first contact is the earliest of:
//! - touching now: the sphere already reaches the triangle at t = 0 (or at
//!   the moment its centre comes round to the front), t = that moment;
//! - the face: when approaching (v·n < 0) from h(0) ≥ r, the plane is
//!   reached at t = (h(0) − r) / (−v·n), if c(t) − r·n lies inside the triangle;
//! - an edge p0→p1 (unit direction ê): the centre reaches distance r from the
//!   edge's line when |w⊥ + v⊥·t|² = r², with w⊥ and v⊥ the parts of c − p0
//!   and v perpendicular to ê; solved like two spheres
//!   (`toi_sphere_sphere`), accepted if the foot of the centre on the line
//!   lies between p0 and p1;
//! - a vertex: a moving sphere against a point.
//!
//! Contacts whose centre is behind the plane (by more than `BOUNDARY_SLACK`)
//! are ignored (one-sided). A zero-area triangle has no face and no back:
//! only edges and vertices.

use crate::norm::{try_unit, unit_or_zero, Norm};
use glam::Vec3;

use super::closest_point_triangle::closest_point_triangle;
use super::contact_sphere_triangle::triangle_unit_normal;
use super::toi_sphere_sphere::toi_moving_point_sphere;
use crate::{Sphere, TriangleRegion};

/// Slack (m) on "behind the plane" and "inside the segment" tests, so a
/// contact exactly on a boundary is not lost to rounding.
pub(crate) const BOUNDARY_SLACK: f32 = 1e-6;

/// Clearance (m) beyond the radius that the early "too far from the plane"
/// exit asks for: well above the rounding of the exact tests it skips at
/// room scale (coordinates of tens of metres; ~10⁻⁵ m).
pub(crate) const FAR_SLACK: f32 = 1e-4;

/// Analytic time of impact of a sphere moving linearly over t ∈ [0, 1] with a one-sided triangle.
///
/// Returns the time and the triangle region touched first; `(0.0, region)`
/// when the sphere already touches the triangle from the front.
pub fn toi_sphere_triangle(
    s: Sphere,
    v: Vec3,
    triangle: &[Vec3; 3],
) -> Option<(f32, TriangleRegion)> {
    let [a, b, c] = *triangle;
    let normal = triangle_unit_normal(a, b, c);
    let height0 = normal.map_or(0.0, |n| (s.center - a).dot(n));
    let approach = normal.map_or(0.0, |n| v.dot(n));
    // Farther than its radius from the plane all the way (straight path):
    // it never reaches the triangle, in the plane. Most of the candidates a
    // box finds below a sloping ceiling end here.
    if normal.is_some() && height0.min(height0 + approach) > s.radius + FAR_SLACK {
        return None;
    }
    let in_front = |t: f32| height0 + approach * t >= -BOUNDARY_SLACK;
    let touching = |t: f32| {
        let center = s.center + v * t;
        let (closest, region) = closest_point_triangle(center, a, b, c);
        (center.distance_squared(closest) <= s.radius * s.radius).then_some(region)
    };

    // Already touching, or touching when the centre crosses to the front
    // (by the same slack as `in_front`, so a path that lies in the plane
    // within rounding is in front all along, not at a moment rounding picks).
    let behind = -BOUNDARY_SLACK - height0;
    let start = if behind <= 0.0 {
        0.0
    } else if approach > 0.0 && behind <= approach {
        behind / approach
    } else {
        return None;
    };
    if let Some(region) = touching(start) {
        return Some((start, region));
    }

    let mut best: Option<(f32, TriangleRegion)> = None;
    let mut consider = |t: f32, region: TriangleRegion| {
        let earlier = match best {
            None => true,
            Some((bt, _)) => t < bt,
        };
        if earlier && t >= start && t <= 1.0 && in_front(t) {
            best = Some((t, region));
        }
    };

    if let Some(n) = normal {
        if approach < 0.0 && height0 >= s.radius {
            let t = (height0 - s.radius) / -approach;
            if t <= 1.0 {
                let foot = s.center + v * t - n * s.radius;
                if inside_triangle(foot, a, b, c, n) {
                    consider(t, TriangleRegion::Face);
                }
            }
        }
    }

    let corners = [a, b, c];
    for k in 0..3 {
        let (p0, p1) = (corners[k], corners[(k + 1) % 3]);
        if let Some(t) = toi_sphere_line_segment(s, v, p0, p1) {
            consider(t, TriangleRegion::Edge(k as u8));
        }
        if let Some(t) = toi_moving_point_sphere(s.center - p0, v, s.radius) {
            consider(t, TriangleRegion::Vertex(k as u8));
        }
    }
    best
}

/// First t ∈ [0, 1] at which the sphere's centre comes within its radius of
/// the segment's interior, reaching it from outside the infinite cylinder.
#[inline]
fn toi_sphere_line_segment(s: Sphere, v: Vec3, p0: Vec3, p1: Vec3) -> Option<f32> {
    let edge = p1 - p0;
    let length = edge.norm();
    let axis = try_unit(edge / length)?;
    let w = s.center - p0;
    let w_perp = w - axis * w.dot(axis);
    let v_perp = v - axis * v.dot(axis);
    // Inside the cylinder already: a first contact would be through an end,
    // which the vertex test finds.
    if w_perp.length_squared() < s.radius * s.radius {
        return None;
    }
    let t = toi_moving_point_sphere(w_perp, v_perp, s.radius)?;
    let along = (w + v * t).dot(axis);
    (along >= -BOUNDARY_SLACK && along <= length + BOUNDARY_SLACK).then_some(t)
}

/// Whether `p`, on the plane of triangle abc with unit normal `n`, lies inside
/// it (edges included, within `BOUNDARY_SLACK`).
#[inline]
fn inside_triangle(p: Vec3, a: Vec3, b: Vec3, c: Vec3, n: Vec3) -> bool {
    let side = |p0: Vec3, p1: Vec3| {
        let edge = p1 - p0;
        let out = unit_or_zero(edge.cross(n));
        (p - p0).dot(out) <= BOUNDARY_SLACK
    };
    side(a, b) && side(b, c) && side(c, a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::toi_bisect::toi_sphere_triangle_bisect;
    use proptest::prelude::*;

    const TRI: [Vec3; 3] = [
        Vec3::ZERO,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    ];

    #[test]
    fn face_edge_and_vertex_hits() {
        let s = |x, y, z| Sphere::new(Vec3::new(x, y, z), 0.5);
        let (t, r) = toi_sphere_triangle(s(0.5, 0.5, 2.5), -Vec3::Z * 4.0, &TRI).unwrap();
        assert_eq!(r, TriangleRegion::Face);
        assert!((t - 0.5).abs() < 1e-6);
        // Sliding in sideways at the height of the plane: the edge y = 0 first.
        let (t, r) = toi_sphere_triangle(s(1.0, -2.5, 0.0), Vec3::Y * 4.0, &TRI).unwrap();
        assert_eq!(r, TriangleRegion::Edge(0));
        assert!((t - 0.5).abs() < 1e-6);
        let (t, r) = toi_sphere_triangle(s(-2.5, 0.0, 0.0), Vec3::X * 4.0, &TRI).unwrap();
        assert!(matches!(r, TriangleRegion::Vertex(0)), "{r:?}");
        assert!((t - 0.5).abs() < 1e-6);
    }

    #[test]
    fn back_side_and_receding_spheres_do_not_hit() {
        // From behind, the sphere counts only once its centre is through the
        // plane (it then overlaps from the front).
        let s = Sphere::new(Vec3::new(0.5, 0.5, -2.5), 0.5);
        let (t, _) = toi_sphere_triangle(s, Vec3::Z * 4.0, &TRI).unwrap();
        assert!((t - 0.625).abs() < 1e-6, "{t}");
        assert_eq!(toi_sphere_triangle(s, Vec3::Z, &TRI), None);
        let s = Sphere::new(Vec3::new(0.5, 0.5, 2.5), 0.5);
        assert_eq!(toi_sphere_triangle(s, Vec3::Z, &TRI), None);
        assert_eq!(toi_sphere_triangle(s, -Vec3::Z, &TRI), None);
    }

    #[test]
    fn touching_now_is_time_zero() {
        let s = Sphere::new(Vec3::new(0.5, 0.5, 0.5), 0.5);
        assert_eq!(
            toi_sphere_triangle(s, -Vec3::Z, &TRI),
            Some((0.0, TriangleRegion::Face))
        );
    }

    #[test]
    fn zero_area_triangle_is_hit_on_its_segment() {
        let seg = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        let s = Sphere::new(Vec3::new(1.5, 0.0, 2.0), 0.5);
        let (t, _) = toi_sphere_triangle(s, -Vec3::Z * 3.0, &seg).unwrap();
        assert!((t - 0.5).abs() < 1e-6);
    }

    /// A fixed pseudo-random sweep (so the count of hits is pinned): the two
    /// methods agree, and the cases cover face, edge and vertex hits.
    #[test]
    fn analytic_agrees_with_bisection_on_a_fixed_sweep() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        let mut point = |scale: f32| Vec3::new(next(), next(), next()) * scale;
        let (mut hits, mut faces, mut edges, mut vertices) = (0, 0, 0, 0);
        for _ in 0..2000 {
            let tri = [point(1.0), point(1.0), point(1.0)];
            let start = point(2.5);
            let target = tri[0]
                + (tri[1] - tri[0]) * 0.6 * (point(1.0).x + 1.0) * 0.5
                + (tri[2] - tri[0]) * 0.6 * (point(1.0).y + 1.0) * 0.5
                + point(0.3);
            let s = Sphere::new(start, 0.05 + 0.3 * (point(1.0).z + 1.0));
            let v = (target - start) * 1.5;
            let analytic = toi_sphere_triangle(s, v, &tri);
            let bisected = toi_sphere_triangle_bisect(s, v, &tri, 1e-6);
            match (analytic, bisected) {
                (Some((ta, region)), Some(tb)) => {
                    assert!((ta - tb).abs() <= 1e-4, "analytic {ta} bisect {tb}");
                    if ta > 0.0 {
                        hits += 1;
                        match region {
                            TriangleRegion::Face => faces += 1,
                            TriangleRegion::Edge(_) => edges += 1,
                            TriangleRegion::Vertex(_) => vertices += 1,
                        }
                    }
                }
                (None, None) => {}
                (a, b) => panic!("one method alone: {a:?} vs {b:?}"),
            }
        }
        assert!(
            hits > 400 && faces > 100 && edges > 50 && vertices > 10,
            "{hits} {faces} {edges} {vertices}"
        );
    }

    fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
        (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    /// Signed one-sided distance in f64 at time t (None when behind).
    fn distance64(s: Sphere, v: Vec3, tri: &[Vec3; 3], t: f32) -> Option<f64> {
        let center = s.center + v * t;
        let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).try_normalize();
        if n.is_some_and(|n| (center - tri[0]).dot(n) < -1e-5) {
            return None;
        }
        let (q, _) = closest_point_triangle(center, tri[0], tri[1], tri[2]);
        Some(center.as_dvec3().distance(q.as_dvec3()) - s.radius as f64)
    }

    /// How far two correct times of impact may differ. 1e-4 in general;
    /// a sphere that starts behind the plane is first counted when its
    /// centre crosses it, a moment known only to within the rounding of the
    /// centre's height (`BOUNDARY_SLACK`) over the rate it crosses at, which
    /// is long when the path all but lies in the plane.
    fn time_tolerance(s: Sphere, v: Vec3, tri: &[Vec3; 3]) -> f32 {
        let crossing = triangle_unit_normal(tri[0], tri[1], tri[2])
            .filter(|&n| (s.center - tri[0]).dot(n) < 0.0)
            .map_or(0.0, |n| 2.0 * BOUNDARY_SLACK / v.dot(n).abs());
        1e-4 + crossing
    }

    /// A centre that slides through the plane at 2 mm a unit of time while
    /// moving 8 m: where it crosses, the height is rounding (±1e-7 m), so
    /// the two methods pick moments 1.7e-4 apart.
    #[test]
    fn grazing_crossing_from_behind_agrees_within_its_conditioning() {
        let a = Vec3::new(0.3517937, 0.9014629, 0.004710043);
        let b = Vec3::new(0.10160588, 0.45220053, -0.8292045);
        let c = Vec3::new(0.20725378, -0.81535417, -0.9894953);
        let tri = [a, b, c];
        let s = Sphere::new(Vec3::new(1.6567243, -2.1425788, 2.4568596), 0.05);
        let v = (a + (b - a) * 0.72160244 - s.center) * 1.8758303;
        let (ta, _) = toi_sphere_triangle(s, v, &tri).unwrap();
        let tb = toi_sphere_triangle_bisect(s, v, &tri, 1e-6).unwrap();
        assert!(
            (ta - tb).abs() > 1e-4,
            "the case no longer shows the rounding: {ta} {tb}"
        );
        assert!(
            (ta - tb).abs() <= time_tolerance(s, v, &tri),
            "analytic {ta} bisect {tb}"
        );
    }

    /// A path in the plane (within rounding) towards an edge: in front all
    /// along by the slack, so both methods find the edge's first touch.
    #[test]
    fn path_in_the_plane_is_in_front() {
        let a = Vec3::new(-0.56304264, -0.19556512, -0.5320421);
        let b = Vec3::new(0.32982478, -0.98319435, -0.9032248);
        let c = Vec3::new(-0.18836781, 0.57735, -0.38832828);
        let tri = [a, b, c];
        let s = Sphere::new(Vec3::new(-1.7289596, -0.07551745, -0.29390296), 0.2849638);
        let v = (a + (b - a) * 1.0261985 - s.center) * 1.612525;
        let (ta, region) = toi_sphere_triangle(s, v, &tri).unwrap();
        let tb = toi_sphere_triangle_bisect(s, v, &tri, 1e-6).unwrap();
        assert!(
            matches!(region, TriangleRegion::Edge(_) | TriangleRegion::Vertex(_)),
            "{region:?}"
        );
        assert!((ta - tb).abs() <= 1e-4, "analytic {ta} bisect {tb}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(600))]

        #[test]
        fn analytic_agrees_with_bisection(
            a in vec3(1.0), b in vec3(1.0), c in vec3(1.0),
            start in vec3(2.5), target_bary in (0.0f32..1.2, 0.0f32..1.2), jitter in vec3(0.4),
            radius in 0.05f32..0.6, overshoot in 0.8f32..2.5, graze in 0usize..3
        ) {
            let tri = [a, b, c];
            // Aim at a point on (or just beside) the triangle, sometimes at a
            // grazing offset of about one radius.
            let (u, w) = target_bary;
            let target = a + (b - a) * u + (c - a) * w + jitter * (graze as f32 * 0.5);
            let s = Sphere::new(start, radius);
            let v = (target - start) * overshoot;
            let analytic = toi_sphere_triangle(s, v, &tri);
            let bisected = toi_sphere_triangle_bisect(s, v, &tri, 1e-6);
            match (analytic, bisected) {
                (Some((ta, _)), Some(tb)) => {
                    let tolerance = time_tolerance(s, v, &tri);
                    prop_assert!((ta - tb).abs() <= tolerance, "analytic {} bisect {} (within {})", ta, tb, tolerance);
                }
                (Some((ta, _)), None) => {
                    // Only a tangent touch may be seen by one method alone.
                    let d = distance64(s, v, &tri, ta).unwrap_or(0.0);
                    prop_assert!(d.abs() < 1e-4, "analytic-only hit at {} with distance {}", ta, d);
                }
                (None, Some(tb)) => {
                    let d = distance64(s, v, &tri, tb).unwrap_or(0.0);
                    prop_assert!(d.abs() < 1e-4 * (1.0 + v.length() as f64), "bisect-only hit at {} with distance {}", tb, d);
                }
                (None, None) => {}
            }
        }
    }
}
