//! Sphere tree (A) against a static mesh (B).
//!
//! The tree is descended first: an inner node is opened only if some
//! triangle lies within its sphere (plus the margin), found through the BVH
//! with an early exit. Each leaf is then a sphere against the mesh, with the
//! internal-edge filtering and per-leaf deduplication of
//! `contact_sphere_trimesh`. The pending children live in a fixed stack of
//! ranges (one entry per level), so nothing is allocated.

use super::contact_sphere_trimesh::{contact_sphere_trimesh, mesh_within};
use super::contact_tree_tree::PARENT_SLACK;
use crate::{Contact, PlacedTree, Sphere, TriMesh};

/// Tree depth handled without recursion.
const STACK_SIZE: usize = 64;

/// Contacts between a placed sphere tree (A) and a static mesh (B).
/// Appends to `out`; `feature_a` is the leaf's node index, `feature_b` the triangle.
pub fn contact_tree_trimesh(a: PlacedTree, mesh: &TriMesh, margin: f32, out: &mut Vec<Contact>) {
    descend(&a, 0, mesh, margin, out);
}

fn descend(a: &PlacedTree, root: u32, mesh: &TriMesh, margin: f32, out: &mut Vec<Contact>) {
    let mut stack = [(0u32, 0u32); STACK_SIZE];
    let mut len = 0;
    let mut node = Some(root);
    loop {
        if let Some(index) = node.take() {
            let n = &a.tree.nodes()[index as usize];
            let (center, radius) = (a.centers[index as usize], a.radius(index));
            if n.is_leaf() {
                contact_sphere_trimesh(Sphere::new(center, radius), mesh, margin, index, out);
            } else if mesh_within(mesh, center, radius + margin + PARENT_SLACK) {
                let children = (n.first_child, n.first_child + n.child_count);
                if len < STACK_SIZE {
                    stack[len] = children;
                    len += 1;
                } else {
                    for child in children.0..children.1 {
                        descend(a, child, mesh, margin, out);
                    }
                }
            }
        }
        if len == 0 {
            return;
        }
        let top = &mut stack[len - 1];
        node = Some(top.0);
        top.0 += 1;
        if top.0 >= top.1 {
            len -= 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::contact_sphere_trimesh::sphere_mesh_triangle;
    use crate::test_meshes::{box_mesh, wall};
    use crate::{Pose, SphereTree, Vec3};
    use proptest::prelude::*;

    /// A room [0, size]³ with normals pointing in.
    fn room(size: f32) -> TriMesh {
        box_mesh(Vec3::splat(size), true)
    }

    fn single(radius: f32) -> SphereTree {
        SphereTree::from_root_and_leaves(Sphere::new(Vec3::ZERO, radius), &[]).unwrap()
    }

    fn contacts_of(tree: &SphereTree, pose: Pose, mesh: &TriMesh, margin: f32) -> Vec<Contact> {
        let mut centers = vec![Vec3::ZERO; tree.nodes().len()];
        tree.place(&pose, &mut centers);
        let mut out = Vec::new();
        contact_tree_trimesh(PlacedTree::new(tree, &centers), mesh, margin, &mut out);
        out
    }

    #[test]
    fn sphere_sliding_across_wall_seam_keeps_face_normal() {
        let mesh = wall();
        let radius = 0.25;
        let tree = single(radius);
        // Across the diagonal x = y, at several heights (touching, resting,
        // sunk in), including positions exactly on the seam.
        for height in [0.25f32, 0.2, 0.1, 0.01, 0.28] {
            for step in 0..=400 {
                let s = step as f32 / 400.0;
                let center = Vec3::new(0.6 + 0.8 * s, 1.4 - 0.8 * s, height);
                let out = contacts_of(&tree, Pose::from_position(center), &mesh, 0.05);
                assert_eq!(out.len(), 1, "one contact at {center}: {out:?}");
                let c = out[0];
                assert_eq!(c.normal, -Vec3::Z, "normal at {center}");
                assert!(
                    (c.separation - (height - radius)).abs() < 1e-6,
                    "depth at {center}"
                );
                assert_eq!(c.feature_a, 0);
            }
        }
        // Exactly on the seam, where both triangles report the shared edge.
        for i in 1..20 {
            let t = i as f32 * 0.1;
            let out = contacts_of(&tree, Pose::from_position(Vec3::new(t, t, 0.2)), &mesh, 0.0);
            assert_eq!(out.len(), 1);
            assert_eq!(out[0].normal, -Vec3::Z);
        }
    }

    #[test]
    fn wall_border_is_a_rounded_edge() {
        let mesh = wall();
        let out = contacts_of(
            &single(0.5),
            Pose::from_position(Vec3::new(2.3, 1.0, 0.4)),
            &mesh,
            0.0,
        );
        assert_eq!(out.len(), 1);
        assert!(out[0].normal.distance(Vec3::new(-0.6, 0.0, -0.8)) < 1e-5);
        assert!(out[0].separation.abs() < 1e-6);
    }

    #[test]
    fn room_corner_gives_face_contacts_only() {
        let mesh = room(4.0);
        let radius = 0.3;
        // Near the corner where the wall x = 0 meets the ceiling y = 4.
        for (x, y) in [
            (0.2f32, 3.8f32),
            (0.29, 3.71),
            (0.1, 3.9),
            (0.3, 3.7),
            (0.2, 3.95),
        ] {
            let center = Vec3::new(x, y, 2.0);
            let out = contacts_of(&single(radius), Pose::from_position(center), &mesh, 0.0);
            let mut normals: Vec<Vec3> = out.iter().map(|c| c.normal).collect();
            normals.sort_by(|a, b| a.x.total_cmp(&b.x));
            assert_eq!(normals, vec![-Vec3::X, Vec3::Y], "at {center}: {out:?}");
            for c in &out {
                let expected = if c.normal == -Vec3::X {
                    x - radius
                } else {
                    4.0 - y - radius
                };
                assert!((c.separation - expected).abs() < 1e-5);
            }
        }
        // Into the three-wall corner at the origin: floor, and walls x = 0, z = 0.
        let out = contacts_of(
            &single(radius),
            Pose::from_position(Vec3::splat(0.2)),
            &mesh,
            0.0,
        );
        assert_eq!(out.len(), 3, "{out:?}");
        for c in &out {
            assert!([-Vec3::X, -Vec3::Y, -Vec3::Z].contains(&c.normal));
            assert!((c.separation + 0.1).abs() < 1e-5);
        }
    }

    #[test]
    fn sphere_in_the_middle_of_the_room_touches_nothing() {
        let out = contacts_of(
            &single(0.3),
            Pose::from_position(Vec3::splat(2.0)),
            &room(4.0),
            0.1,
        );
        assert!(out.is_empty());
    }

    #[test]
    fn convex_box_edge_gives_a_rounded_normal() {
        // The room seen from outside is a box with convex edges.
        let v: Vec<Vec3> = room(1.0).vertices().to_vec();
        let t: Vec<[u32; 3]> = room(1.0)
            .triangles()
            .iter()
            .map(|t| [t[0], t[2], t[1]])
            .collect();
        let boxed = TriMesh::new(v, t).unwrap();
        // Above the top edge y = 1, x = 1, on the diagonal.
        let center = Vec3::new(1.2, 1.2, 0.5);
        let out = contacts_of(&single(0.3), Pose::from_position(center), &boxed, 0.0);
        assert_eq!(out.len(), 1, "{out:?}");
        let expected = -Vec3::new(1.0, 1.0, 0.0).normalize();
        assert!(out[0].normal.distance(expected) < 1e-5);
        assert!((out[0].separation - (0.2f32 * 2f32.sqrt() - 0.3)).abs() < 1e-5);
        // Above the top face near that edge: the face alone.
        let out = contacts_of(
            &single(0.3),
            Pose::from_position(Vec3::new(0.9, 1.2, 0.5)),
            &boxed,
            0.0,
        );
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].normal, -Vec3::Y);
    }

    #[test]
    fn leaves_carry_their_node_index() {
        let leaves = [
            Sphere::new(Vec3::new(-0.5, 0.0, 0.0), 0.2),
            Sphere::new(Vec3::new(0.5, 0.0, 0.0), 0.2),
        ];
        let tree = SphereTree::from_root_and_leaves(Sphere::new(Vec3::ZERO, 0.7), &leaves).unwrap();
        let out = contacts_of(
            &tree,
            Pose::from_position(Vec3::new(1.0, 1.0, 0.15)),
            &wall(),
            0.0,
        );
        assert_eq!(out.len(), 2);
        let mut features: Vec<u32> = out.iter().map(|c| c.feature_a).collect();
        features.sort_unstable();
        assert_eq!(features, vec![1, 2]);
    }

    fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
        (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Descent finds the same leaves as testing every leaf, and within a
        /// leaf no two contacts share a normal.
        #[test]
        fn descent_equals_every_leaf_and_normals_are_unique(
            leaves in prop::collection::vec((vec3(0.5), 0.05f32..0.3), 1..8),
            at in vec3(4.5), margin in 0.0f32..0.1
        ) {
            let mesh = room(4.0);
            let spheres: Vec<Sphere> = leaves.iter().map(|&(c, r)| Sphere::new(c, r)).collect();
            let root_r = spheres.iter().map(|s| s.center.length() + s.radius).fold(0.0, f32::max);
            let tree = SphereTree::from_root_and_leaves(Sphere::new(Vec3::ZERO, root_r + 1e-5), &spheres).unwrap();
            let pose = Pose::from_position(at + Vec3::splat(2.0));
            let got = contacts_of(&tree, pose, &mesh, margin);
            let mut centers = vec![Vec3::ZERO; tree.nodes().len()];
            tree.place(&pose, &mut centers);
            let mut expected = Vec::new();
            for &leaf in tree.leaves() {
                let sphere = Sphere::new(centers[leaf as usize], tree.nodes()[leaf as usize].radius);
                contact_sphere_trimesh(sphere, &mesh, margin, leaf, &mut expected);
            }
            prop_assert_eq!(&got, &expected);
            for (i, c) in got.iter().enumerate() {
                for d in &got[i + 1..] {
                    prop_assert!(c.feature_a != d.feature_a || c.normal.dot(d.normal) < 0.999);
                }
                prop_assert!(c.separation <= margin);
                prop_assert!((c.normal.length() - 1.0).abs() < 1e-5);
                // Inside the room the only normals are the six wall normals.
                prop_assert!(c.normal.abs().max_element() > 0.99999, "{:?}", c);
            }
        }

        /// Every contact's depth matches the brute-force one for its triangle.
        #[test]
        fn contact_depth_matches_the_triangle_query(center in vec3(1.999), radius in 0.05f32..0.5) {
            let mesh = room(4.0);
            let center = center + Vec3::splat(2.0);
            let mut out = Vec::new();
            contact_sphere_trimesh(Sphere::new(center, radius), &mesh, 0.0, 7, &mut out);
            for c in &out {
                let direct = sphere_mesh_triangle(Sphere::new(center, radius), &mesh, c.feature_b, 0.0, 7).unwrap();
                prop_assert_eq!(*c, direct);
                // A face contact in a box room: the depth is the wall distance.
                let wall_distance = (center - c.point_b).length();
                prop_assert!((wall_distance - radius - c.separation).abs() < 1e-4);
            }
            // Inside the room, every wall within the radius gives a contact.
            let walls_touched = (0..3).map(|k| {
                (center[k] < radius) as usize + (4.0 - center[k] < radius) as usize
            }).sum::<usize>();
            prop_assert_eq!(out.len(), walls_touched);
        }
    }
}
