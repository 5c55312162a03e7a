//! Contact queries from arbitrary finite inputs (positions within ±64 m,
//! radii 1 mm to 8 m). Every contact is finite, its normal unit length, its
//! separation within the margin and consistent with its points; a query
//! that finds nothing really is that far; the tree descents find exactly
//! the contacts of testing every leaf, at any size of the trees (a shrunk
//! or grown balloon's).

use crate::numbers::{distance64, face_normal, is_sliver, is_unit, Numbers};
use glam::Vec3;
use up_geom::{
    closest_point_triangle, contact_sphere_sphere, contact_sphere_triangle, contact_sphere_trimesh,
    contact_tree_tree, contact_tree_trimesh, Contact, PlacedTree, Pose, Sphere, SphereTree,
    TriMesh,
};

const SPAN: f32 = 64.0;
const MAX_RADIUS: f32 = 8.0;
const MIN_RADIUS: f32 = 1e-3;
/// f32 results against f64 references: relative to the scale of the inputs.
const RELATIVE_TOLERANCE: f64 = 1e-4;

/// One input: panics when a property fails.
pub fn check(data: &[u8]) {
    let mut n = Numbers::new(data);
    match n.byte() % 4 {
        0 => sphere_sphere(&mut n),
        1 => sphere_triangle(&mut n),
        2 => tree_trimesh(&mut n),
        _ => tree_tree(&mut n),
    }
}

fn margin(n: &mut Numbers) -> f32 {
    n.f32_within(0.5).abs()
}

fn check_contact(c: &Contact, margin: f32, tolerance: f64, inputs: &dyn std::fmt::Debug) {
    assert!(
        c.point_a.is_finite() && c.point_b.is_finite() && c.normal.is_finite(),
        "{c:?}"
    );
    assert!(c.separation.is_finite(), "{c:?}");
    assert!(is_unit(c.normal), "normal not unit: {c:?} from {inputs:?}");
    assert!(
        f64::from(c.separation) <= f64::from(margin) + tolerance,
        "{c:?}"
    );
    assert!(c.depth() >= 0.0);
}

fn sphere_sphere(n: &mut Numbers) {
    let a = Sphere::new(n.vec3(SPAN), n.radius(MIN_RADIUS, MAX_RADIUS));
    let b = Sphere::new(n.vec3(SPAN), n.radius(MIN_RADIUS, MAX_RADIUS));
    let margin = margin(n);
    let scale = f64::from(a.center.abs().max(b.center.abs()).max_element() + a.radius + b.radius);
    let tolerance = RELATIVE_TOLERANCE * scale.max(1.0);
    let gap = distance64(a.center, b.center) - f64::from(a.radius) - f64::from(b.radius);
    match contact_sphere_sphere(a, b, margin) {
        Some(c) => {
            check_contact(&c, margin, tolerance, &(a, b));
            assert!(
                (f64::from(c.separation) - gap).abs() <= tolerance,
                "{c:?} gap {gap}"
            );
            assert!(distance64(c.point_a, a.center + c.normal * a.radius) <= tolerance);
            assert!(distance64(c.point_b, b.center - c.normal * b.radius) <= tolerance);
        }
        None => assert!(gap >= f64::from(margin) - tolerance, "missed: gap {gap}"),
    }
}

fn sphere_triangle(n: &mut Numbers) {
    let sphere = Sphere::new(n.vec3(SPAN), n.radius(MIN_RADIUS, MAX_RADIUS));
    let tri = [n.vec3(SPAN), n.vec3(SPAN), n.vec3(SPAN)];
    let margin = margin(n);
    let scale = tri
        .iter()
        .fold(sphere.center.abs(), |m, v| m.max(v.abs()))
        .max_element()
        + sphere.radius;
    let tolerance = RELATIVE_TOLERANCE * f64::from(scale).max(1.0);
    // Points of the triangle: an upper bound on its distance from the centre.
    let samples = [
        tri[0],
        tri[1],
        tri[2],
        (tri[0] + tri[1]) * 0.5,
        (tri[1] + tri[2]) * 0.5,
        (tri[2] + tri[0]) * 0.5,
        (tri[0] + tri[1] + tri[2]) / 3.0,
    ];
    let nearest_sample = samples
        .iter()
        .map(|&p| distance64(p, sphere.center))
        .fold(f64::INFINITY, f64::min);
    // A sliver has a normal too rounded to measure heights against: there
    // the contact is checked against the triangle's own points only (never
    // farther than the nearest of them).
    if is_sliver(&tri) {
        if let Some((c, _)) = contact_sphere_triangle(sphere, &tri, margin) {
            check_contact(&c, margin, tolerance, &(sphere, tri));
            let reach = f64::from(c.separation) + f64::from(sphere.radius);
            assert!(
                reach <= nearest_sample + tolerance,
                "{c:?} nearest {nearest_sample}"
            );
        }
        return;
    }
    let normal = face_normal(&tri);
    let height = normal.map(|n| f64::from((sphere.center - tri[0]).dot(n)));
    match contact_sphere_triangle(sphere, &tri, margin) {
        Some((c, _region)) => {
            check_contact(&c, margin, tolerance, &(sphere, tri));
            // point_b lies on the triangle, at |separation + r| from the centre.
            let (on, _) = closest_point_triangle(c.point_b, tri[0], tri[1], tri[2]);
            assert!(distance64(on, c.point_b) <= tolerance, "{c:?}");
            let reach = f64::from(c.separation) + f64::from(sphere.radius);
            let to_b = distance64(sphere.center, c.point_b);
            assert!(
                (to_b - reach.abs()).abs() <= tolerance,
                "{c:?} reach {reach} to_b {to_b}"
            );
            if let Some(h) = height.filter(|&h| h >= 0.0) {
                assert!(
                    reach >= h - tolerance,
                    "closer than the plane: {c:?} height {h}"
                );
                assert!(
                    reach <= nearest_sample + tolerance,
                    "{c:?} nearest {nearest_sample}"
                );
            }
        }
        None => {
            // In front of (or level with) the plane, a triangle point within reach means contact.
            if height.is_none_or(|h| h >= tolerance) {
                let reach = f64::from(sphere.radius) + f64::from(margin);
                assert!(
                    nearest_sample >= reach - tolerance,
                    "missed: nearest {nearest_sample}, height {height:?}, {sphere:?} {tri:?} margin {margin}"
                );
            }
        }
    }
}

/// 1 to 8 leaves and a root around them, in the body frame.
fn tree(n: &mut Numbers) -> Option<SphereTree> {
    let count = 1 + usize::from(n.byte() % 8);
    let leaves: Vec<Sphere> = (0..count)
        .map(|_| Sphere::new(n.vec3(1.0), n.radius(MIN_RADIUS, 0.5)))
        .collect();
    let center = leaves.iter().map(|s| s.center).sum::<Vec3>() / count as f32;
    let radius = leaves
        .iter()
        .map(|s| s.center.distance(center) + s.radius)
        .fold(0.0, f32::max);
    SphereTree::from_root_and_leaves(Sphere::new(center, radius * (1.0 + 1e-5) + 1e-5), &leaves)
        .ok()
}

/// A tree's size over its own (a balloon shrinking as it loses gas, or
/// grown by warm air): read last, so that an input without the byte (the
/// corpus from before scales) places its trees at their own size.
fn scale(n: &mut Numbers) -> f32 {
    match n.byte() {
        0 => 1.0,
        b => 0.25 + 1.5 * f32::from(b) / 255.0,
    }
}

fn placed_centers(tree: &SphereTree, pose: &Pose, scale: f32) -> Vec<Vec3> {
    let mut centers = vec![Vec3::ZERO; tree.nodes().len()];
    tree.place_scaled(pose, scale, &mut centers);
    centers
}

fn sort_contacts(contacts: &mut [Contact]) {
    contacts.sort_by(|a, b| {
        (a.feature_a, a.feature_b)
            .cmp(&(b.feature_a, b.feature_b))
            .then(a.separation.total_cmp(&b.separation))
    });
}

fn tree_trimesh(n: &mut Numbers) {
    let Some(tree) = tree(n) else { return };
    let pose = Pose::new(n.vec3(4.0), n.rotation());
    let vertex_count = 3 + usize::from(n.byte() % 10);
    // Coordinates under 1 µm are snapped to 0: `TriMesh` normals of triangles
    // whose cross product squares to a subnormal come out short of unit
    // length (reported; up-geom shape/trimesh.rs).
    let snap = |x: f32| if x.abs() < 1e-6 { 0.0 } else { x };
    let vertices: Vec<Vec3> = (0..vertex_count)
        .map(|_| {
            let v = n.vec3(4.0);
            Vec3::new(snap(v.x), snap(v.y), snap(v.z))
        })
        .collect();
    let triangle_count = 1 + usize::from(n.byte() % 12);
    let triangles: Vec<[u32; 3]> = (0..triangle_count)
        .map(|_| [0, 0, 0].map(|_: u32| u32::from(n.byte()) % vertex_count as u32))
        .collect();
    let margin = margin(n);
    let Ok(mesh) = TriMesh::new(vertices, triangles) else {
        return;
    };
    let scale = scale(n);
    let centers = placed_centers(&tree, &pose, scale);
    let placed = PlacedTree {
        tree: &tree,
        centers: &centers,
        scale,
    };
    let mut got = Vec::new();
    contact_tree_trimesh(placed, &mesh, margin, &mut got);
    let mut every_leaf = Vec::new();
    for &leaf in tree.leaves() {
        let sphere = Sphere::new(centers[leaf as usize], placed.radius(leaf));
        contact_sphere_trimesh(sphere, &mesh, margin, leaf, &mut every_leaf);
    }
    for c in &got {
        check_contact(c, margin, 1e-3, &(&tree, pose, &mesh));
        assert!(tree.leaves().contains(&c.feature_a), "{c:?}");
        assert!((c.feature_b as usize) < mesh.triangle_count(), "{c:?}");
    }
    sort_contacts(&mut got);
    sort_contacts(&mut every_leaf);
    assert_eq!(got, every_leaf, "the descent lost or added contacts");
}

fn tree_tree(n: &mut Numbers) {
    let (Some(ta), Some(tb)) = (tree(n), tree(n)) else {
        return;
    };
    let pa = Pose::new(n.vec3(2.0), n.rotation());
    let pb = Pose::new(n.vec3(2.0), n.rotation());
    let margin = margin(n);
    let (scale_a, scale_b) = (scale(n), scale(n));
    let (ca, cb) = (
        placed_centers(&ta, &pa, scale_a),
        placed_centers(&tb, &pb, scale_b),
    );
    let placed_a = PlacedTree {
        tree: &ta,
        centers: &ca,
        scale: scale_a,
    };
    let placed_b = PlacedTree {
        tree: &tb,
        centers: &cb,
        scale: scale_b,
    };
    let mut got = Vec::new();
    contact_tree_tree(placed_a, placed_b, margin, &mut got);
    let mut every_pair = Vec::new();
    for &la in ta.leaves() {
        for &lb in tb.leaves() {
            let sa = Sphere::new(ca[la as usize], placed_a.radius(la));
            let sb = Sphere::new(cb[lb as usize], placed_b.radius(lb));
            if let Some(mut c) = contact_sphere_sphere(sa, sb, margin) {
                c.feature_a = la;
                c.feature_b = lb;
                every_pair.push(c);
            }
        }
    }
    for c in &got {
        check_contact(c, margin, 1e-3, &(&ta, pa, &tb, pb));
    }
    sort_contacts(&mut got);
    sort_contacts(&mut every_pair);
    assert_eq!(got, every_pair, "the descent lost or added leaf pairs");
}
