//! Time of impact of a linearly moving sphere with a static mesh.
//!
//! The swept sphere's bounding box selects candidate triangles through the
//! BVH; each is solved with `toi_sphere_triangle` and the earliest wins
//! (ties go to the lower triangle index, so the result is deterministic).
//! The normal at impact is that of the contact query at that position, with
//! the same internal-edge rules: crossing the seam of two coplanar triangles
//! gives the face normal.

use glam::Vec3;

use super::contact_sphere_triangle::triangle_unit_normal;
use super::mesh_feature::mesh_contact_direction;
use super::toi_sphere_triangle::{toi_sphere_triangle, FAR_SLACK};
use crate::{closest_point_triangle, Aabb, Sphere, TriMesh};

/// Earliest time of impact of a sphere moving linearly over t ∈ [0, 1] with a
/// static mesh: (t, triangle index, contact normal pointing from sphere to mesh).
///
/// `v` is the displacement over the step (m). Zero-area triangles are skipped.
pub fn toi_sphere_trimesh(s: Sphere, v: Vec3, mesh: &TriMesh) -> Option<(f32, u32, Vec3)> {
    earliest_impact(s, v, mesh, false)
}

/// As [`toi_sphere_trimesh`], over the triangles the sphere does not touch
/// at the start: the first *new* contact, the one a continuous sweep must
/// stop at (contacts it starts in belong to the contact solver).
pub fn toi_sphere_trimesh_new_contact(
    s: Sphere,
    v: Vec3,
    mesh: &TriMesh,
) -> Option<(f32, u32, Vec3)> {
    earliest_impact(s, v, mesh, true)
}

/// Slack (m) on top of `FAR_SLACK` for `sweep_may_hit`: more than the
/// rounding by which a height measured from the bound's centre may differ
/// from one measured from a sphere inside it, at room scale.
const BOUND_SLACK: f32 = 1e-3;

/// Whether a sphere moving inside `bound` may hit the mesh. False only when
/// every triangle near `bound` has the whole of `bound` in front of its
/// plane, farther than `toi_sphere_triangle`'s own early exit asks: then any
/// sphere whose straight path, radius included, stays inside `bound` gets
/// `None` from `toi_sphere_trimesh` and `toi_sphere_trimesh_new_contact`.
/// One look for several spheres that move together (a balloon's cores).
pub fn sweep_may_hit(bound: Sphere, mesh: &TriMesh) -> bool {
    let clear = bound.radius + FAR_SLACK + BOUND_SLACK;
    mesh.query_aabb_until(&Aabb::from_sphere(bound.center, bound.radius), |tri| {
        if mesh.is_degenerate(tri) {
            return false;
        }
        let [a, b, c] = mesh.triangle(tri);
        // The normal as `toi_sphere_triangle` takes it, bit for bit.
        triangle_unit_normal(a, b, c).is_none_or(|n| (bound.center - a).dot(n) <= clear)
    })
}

fn earliest_impact(
    s: Sphere,
    v: Vec3,
    mesh: &TriMesh,
    skip_touching: bool,
) -> Option<(f32, u32, Vec3)> {
    let swept =
        Aabb::from_sphere(s.center, s.radius).union(Aabb::from_sphere(s.center + v, s.radius));
    let mut best: Option<(f32, u32)> = None;
    mesh.query_aabb(&swept, |tri| {
        if mesh.is_degenerate(tri) {
            return;
        }
        if let Some((t, _)) = toi_sphere_triangle(s, v, &mesh.triangle(tri)) {
            if skip_touching && t == 0.0 {
                return;
            }
            let better = match best {
                None => true,
                Some((bt, bi)) => t < bt || (t == bt && tri < bi),
            };
            if better {
                best = Some((t, tri));
            }
        }
    });
    let (t, tri) = best?;
    let center = s.center + v * t;
    let [a, b, c] = mesh.triangle(tri);
    let (closest, region) = closest_point_triangle(center, a, b, c);
    let normal = match mesh_contact_direction(mesh, tri, region, center, closest) {
        Some((m, _)) => -m,
        // Another feature owns this contact; the raw direction is still exact.
        None => (closest - center)
            .try_normalize()
            .unwrap_or(-mesh.normal(tri)),
    };
    Some((t, tri, normal))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::toi_bisect::toi_sphere_triangle_bisect;
    use crate::test_meshes::wall;
    use proptest::prelude::*;

    #[test]
    fn hits_the_wall_face() {
        let (t, tri, n) = toi_sphere_trimesh(
            Sphere::new(Vec3::new(1.5, 0.5, 2.0), 0.5),
            -Vec3::Z * 3.0,
            &wall(),
        )
        .unwrap();
        assert!((t - 0.5).abs() < 1e-6);
        assert_eq!(tri, 0);
        assert_eq!(n, -Vec3::Z);
    }

    #[test]
    fn hitting_the_seam_gives_the_face_normal() {
        for i in 1..10 {
            let x = i as f32 * 0.2;
            let (t, _, n) =
                toi_sphere_trimesh(Sphere::new(Vec3::new(x, x, 1.0), 0.25), -Vec3::Z, &wall())
                    .unwrap();
            assert!((t - 0.75).abs() < 1e-6);
            assert_eq!(n, -Vec3::Z);
        }
    }

    #[test]
    fn passing_beside_the_wall_misses() {
        let s = Sphere::new(Vec3::new(3.0, 1.0, 2.0), 0.5);
        assert!(toi_sphere_trimesh(s, -Vec3::Z * 4.0, &wall()).is_none());
        // Sliding into the wall's border edge, in its plane.
        let s = Sphere::new(Vec3::new(4.0, 1.0, 0.0), 0.5);
        let (t, _, n) = toi_sphere_trimesh(s, -Vec3::X * 3.0, &wall()).unwrap();
        assert!((t - 0.5).abs() < 1e-6);
        assert!(n.distance(-Vec3::X) < 1e-6);
    }

    #[test]
    fn new_contact_skips_the_triangle_touched_at_the_start() {
        // A floor the sphere rests in, and a wall ahead of it.
        let v = vec![
            Vec3::new(-5.0, 0.0, -5.0),
            Vec3::new(-5.0, 0.0, 5.0),
            Vec3::new(5.0, 0.0, 5.0),
            Vec3::new(1.0, 0.0, -5.0),
            Vec3::new(1.0, 3.0, -5.0),
            Vec3::new(1.0, 0.0, 5.0),
        ];
        let mesh = TriMesh::new(v, vec![[0, 1, 2], [3, 5, 4]]).unwrap();
        let s = Sphere::new(Vec3::new(0.0, 0.2, 0.0), 0.5);
        let motion = Vec3::X * 2.0;
        assert_eq!(
            toi_sphere_trimesh(s, motion, &mesh).map(|h| (h.0, h.1)),
            Some((0.0, 0))
        );
        let (t, tri, n) = toi_sphere_trimesh_new_contact(s, motion, &mesh).unwrap();
        assert!((t - 0.25).abs() < 1e-6, "t = {t}");
        assert_eq!(tri, 1);
        assert!(n.distance(Vec3::X) < 1e-6);
        // Nothing new ahead: no impact at all.
        assert!(toi_sphere_trimesh_new_contact(s, -motion, &mesh).is_none());
    }

    /// A sloping ceiling (two triangles facing down and in, as the room's
    /// pyramid does), bounds just above and just below the height at which
    /// `sweep_may_hit` lets them go, and spheres moving inside each bound,
    /// many of them from and to its lowest point: a bound let go holds no
    /// sphere that touches the ceiling, and both answers occur.
    #[test]
    fn a_bound_let_go_holds_no_sphere_that_hits() {
        let normal = Vec3::new(0.3, -1.0, 0.2).normalize();
        let (u, w) = (
            normal.any_orthonormal_vector(),
            normal.cross(normal.any_orthonormal_vector()),
        );
        let corner = |a: f32, b: f32| Vec3::new(20.0, 8.0, 20.0) + 30.0 * (a * u + b * w);
        let ceiling = TriMesh::new(
            vec![
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap();
        assert!(
            ceiling.normal(0).dot(normal) > 0.999,
            "the ceiling must face the bounds"
        );
        let mut rng = crate::SplitMix64::new(7);
        let mut random = move || rng.unit();
        let (mut let_go, mut looked_at) = (0, 0);
        for _ in 0..4000 {
            let radius = 0.05 + 0.4 * random();
            let above = radius + FAR_SLACK + BOUND_SLACK + 0.004 * (random() - 0.5);
            let at = corner(random() - 0.5, random() - 0.5) + above * normal;
            let bound = Sphere::new(at, radius);
            let core = radius * (0.05 + 0.9 * random());
            let inside = |random: &mut dyn FnMut() -> f32| {
                let lowest = random() < 0.5;
                let d = if lowest {
                    -normal
                } else {
                    Vec3::new(random() - 0.5, random() - 0.5, random() - 0.5).normalize_or_zero()
                };
                at + d * (radius - core) * if lowest { 1.0 } else { random() }
            };
            let (from, to) = (inside(&mut random), inside(&mut random));
            let hit = toi_sphere_trimesh(Sphere::new(from, core), to - from, &ceiling);
            if sweep_may_hit(bound, &ceiling) {
                looked_at += 1;
            } else {
                let_go += 1;
                assert_eq!(hit, None, "{bound:?}: a core from {from} to {to} hits");
            }
        }
        assert!(
            let_go > 1000 && looked_at > 1000,
            "{let_go} let go, {looked_at} looked at"
        );
    }

    fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
        (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn earliest_hit_over_all_triangles(
            points in prop::collection::vec(vec3(2.0), 3..30),
            start in vec3(3.0), v in vec3(4.0), radius in 0.05f32..0.5
        ) {
            let n = points.len() as u32 / 3;
            let mesh = TriMesh::new(points, (0..n).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect()).unwrap();
            let s = Sphere::new(start, radius);
            let hit = toi_sphere_trimesh(s, v, &mesh);
            let brute = (0..n)
                .filter(|&i| !mesh.is_degenerate(i))
                .filter_map(|i| toi_sphere_triangle(s, v, &mesh.triangle(i)).map(|(t, _)| t))
                .fold(None, |best: Option<f32>, t| Some(best.map_or(t, |b| b.min(t))));
            prop_assert_eq!(hit.map(|h| h.0), brute);
            if let Some((t, tri, normal)) = hit {
                prop_assert!((normal.length() - 1.0).abs() < 1e-4);
                if let Some(tb) = toi_sphere_triangle_bisect(s, v, &mesh.triangle(tri), 1e-6) {
                    prop_assert!((t - tb).abs() < 1e-3 || t < tb);
                }
            }
        }
    }
}
