//! Sphere tree against sphere tree, by simultaneous descent.
//!
//! A pair of nodes is opened only while their spheres overlap (within the
//! margin); the bigger inner node of a pair is split. Leaf pairs give
//! sphere–sphere contacts. The pending work is a fixed stack of "node of one
//! tree × remaining children of a node of the other", so the stack grows with
//! the trees' depths, not their widths, and nothing is allocated.
//!
//! Two flat trees (a root over leaves, as fitted balloons are) skip the
//! stack: each tree's leaves within reach of the other's root, then the
//! pairs of those (`flat_pairs`), with the same contacts in the same order.

use super::contact_sphere_sphere::contact_sphere_sphere;
use crate::{Contact, PlacedTree, Sphere, Vec3};

/// Depth of pending pairs held without recursion (sum of both trees' depths).
const STACK_SIZE: usize = 64;

/// Extra reach (m) for inner nodes: a child may poke out of its parent by
/// `BOUND_TOLERANCE` (1e-5 m) per level, so ancestors are tested a little
/// wider than their radius to never lose a leaf pair.
pub(crate) const PARENT_SLACK: f32 = 1e-4;

#[derive(Clone, Copy, Default)]
struct Pending {
    /// The node kept whole.
    fixed: u32,
    /// Next child to pair with `fixed`, and the end of the children.
    next: u32,
    end: u32,
    /// Whether the children are A's (and `fixed` is B's).
    children_of_a: bool,
}

/// Most leaves a flat tree may have for `flat_pairs` (more take `descend`).
const FLAT_LEAVES: usize = 16;

/// Leaf–leaf contacts between two placed sphere trees by hierarchical descent
/// (two flat trees: `flat_pairs`). Appends to `out`; `feature_a`/`feature_b`
/// are node indices.
pub fn contact_tree_tree(a: PlacedTree, b: PlacedTree, margin: f32, out: &mut Vec<Contact>) {
    if !nodes_touch(&a, 0, &b, 0, margin) {
        return;
    }
    if is_flat(&a) && is_flat(&b) {
        flat_pairs(&a, &b, margin, out);
    } else {
        descend(&a, &b, 0, 0, margin, out);
    }
}

/// A root whose children are all leaves (a fitted balloon's tree), few enough for `flat_pairs`.
#[inline]
fn is_flat(t: &PlacedTree) -> bool {
    let nodes = t.tree.nodes();
    let root = &nodes[0];
    let children = root.first_child as usize..(root.first_child + root.child_count) as usize;
    !root.is_leaf() && children.len() <= FLAT_LEAVES && nodes[children].iter().all(|n| n.is_leaf())
}

/// `descend` for two flat trees whose roots touch, without its stack: each
/// tree's leaves that reach the other's root, then the pairs of those. A
/// leaf pair within the margin has both leaves within reach of the other's
/// root (a valid tree's leaf pokes out of its root by at most
/// `BOUND_TOLERANCE`, well inside `PARENT_SLACK` with the rounding of room-scale
/// coordinates: the descent's own pruning rests on the same), so the second
/// filter loses no pair, and the contacts come out as `descend` gives them:
/// the bigger root's leaves in the outer loop. The leaves' spheres are read
/// once, into `Reaching`, and a pair's test is the sphere contact's own
/// (`descend` tests the pair, then the contact repeats that test).
fn flat_pairs(a: &PlacedTree, b: &PlacedTree, margin: f32, out: &mut Vec<Contact>) {
    let near_a = Reaching::of(a, b, margin);
    let near_b = Reaching::of(b, a, margin);
    let touch = |la: &Leaf, lb: &Leaf, out: &mut Vec<Contact>| {
        if let Some(mut c) = contact_sphere_sphere(la.sphere, lb.sphere, margin) {
            c.feature_a = la.node;
            c.feature_b = lb.node;
            out.push(c);
        }
    };
    if a.radius(0) >= b.radius(0) {
        for la in near_a.leaves() {
            for lb in near_b.leaves() {
                touch(la, lb, out);
            }
        }
    } else {
        for lb in near_b.leaves() {
            for la in near_a.leaves() {
                touch(la, lb, out);
            }
        }
    }
}

/// A leaf of a flat tree: its node and its placed sphere.
#[derive(Clone, Copy)]
struct Leaf {
    node: u32,
    sphere: Sphere,
}

impl Leaf {
    const NONE: Leaf = Leaf {
        node: 0,
        sphere: Sphere {
            center: Vec3::ZERO,
            radius: 0.0,
        },
    };
}

/// The leaves of a flat tree within reach of another tree's root, in order.
struct Reaching {
    leaves: [Leaf; FLAT_LEAVES],
    len: usize,
}

impl Reaching {
    /// The leaves of flat tree `t` that touch `other`'s root within `margin`
    /// (`nodes_touch`, with its slack for an inner node, bit for bit).
    #[inline]
    fn of(t: &PlacedTree, other: &PlacedTree, margin: f32) -> Reaching {
        let root = &t.tree.nodes()[0];
        let other_radius = other.radius(0);
        let other_center = other.centers[0];
        let mut near = Reaching {
            leaves: [Leaf::NONE; FLAT_LEAVES],
            len: 0,
        };
        for node in root.first_child..root.first_child + root.child_count {
            let sphere = Sphere::new(t.centers[node as usize], t.radius(node));
            let reach = sphere.radius + other_radius + margin + PARENT_SLACK;
            if sphere.center.distance_squared(other_center) <= reach * reach {
                near.leaves[near.len] = Leaf { node, sphere };
                near.len += 1;
            }
        }
        near
    }

    fn leaves(&self) -> &[Leaf] {
        &self.leaves[..self.len]
    }
}

/// The contact of leaves `ia` and `ib` (whose spheres touch within the margin), if any.
#[inline]
fn leaf_contact(
    a: &PlacedTree,
    b: &PlacedTree,
    ia: u32,
    ib: u32,
    margin: f32,
    out: &mut Vec<Contact>,
) {
    let sa = Sphere::new(a.centers[ia as usize], a.radius(ia));
    let sb = Sphere::new(b.centers[ib as usize], b.radius(ib));
    if let Some(mut c) = contact_sphere_sphere(sa, sb, margin) {
        c.feature_a = ia;
        c.feature_b = ib;
        out.push(c);
    }
}

#[inline]
fn nodes_touch(a: &PlacedTree, ia: u32, b: &PlacedTree, ib: u32, margin: f32) -> bool {
    let (na, nb) = (&a.tree.nodes()[ia as usize], &b.tree.nodes()[ib as usize]);
    let slack = if na.is_leaf() && nb.is_leaf() {
        0.0
    } else {
        PARENT_SLACK
    };
    let reach = a.radius(ia) + b.radius(ib) + margin + slack;
    a.centers[ia as usize].distance_squared(b.centers[ib as usize]) <= reach * reach
}

/// Handles the touching pair (ia, ib) and everything below it.
fn descend(a: &PlacedTree, b: &PlacedTree, ia: u32, ib: u32, margin: f32, out: &mut Vec<Contact>) {
    let mut stack = [Pending::default(); STACK_SIZE];
    let mut len = 0;
    let mut pair = Some((ia, ib));
    loop {
        if let Some((ia, ib)) = pair.take() {
            let (na, nb) = (&a.tree.nodes()[ia as usize], &b.tree.nodes()[ib as usize]);
            if na.is_leaf() && nb.is_leaf() {
                leaf_contact(a, b, ia, ib, margin, out);
            } else {
                let children_of_a = !na.is_leaf() && (nb.is_leaf() || a.radius(ia) >= b.radius(ib));
                let (fixed, parent) = if children_of_a { (ib, na) } else { (ia, nb) };
                let pending = Pending {
                    fixed,
                    next: parent.first_child,
                    end: parent.first_child + parent.child_count,
                    children_of_a,
                };
                if len < STACK_SIZE {
                    stack[len] = pending;
                    len += 1;
                } else {
                    // Deeper than the stack: finish this subtree by recursion.
                    for child in pending.next..pending.end {
                        let (ca, cb) = if children_of_a {
                            (child, fixed)
                        } else {
                            (fixed, child)
                        };
                        if nodes_touch(a, ca, b, cb, margin) {
                            descend(a, b, ca, cb, margin, out);
                        }
                    }
                }
            }
        }
        if len == 0 {
            return;
        }
        let top = &mut stack[len - 1];
        let child = top.next;
        top.next += 1;
        let (ca, cb) = if top.children_of_a {
            (child, top.fixed)
        } else {
            (top.fixed, child)
        };
        if top.next >= top.end {
            len -= 1;
        }
        if nodes_touch(a, ca, b, cb, margin) {
            pair = Some((ca, cb));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Pose, Quat, SphereNode, SphereTree, Vec3};
    use proptest::prelude::*;

    /// A three-level tree: root, `groups` inner nodes, each with `per` leaves
    /// scattered around it; every sphere bounds its children.
    fn tree(seed: &[(Vec3, f32)], groups: usize, per: usize) -> SphereTree {
        let mut nodes = vec![SphereNode {
            center: Vec3::ZERO,
            radius: 1.0,
            first_child: 1,
            child_count: groups as u32,
        }];
        let mut leaves = Vec::new();
        for g in 0..groups {
            let gc = seed[g % seed.len()].0 * 0.5;
            let mut group_leaves = Vec::new();
            for l in 0..per {
                let (offset, r) = seed[(g * per + l + 1) % seed.len()];
                group_leaves.push(Sphere::new(gc + offset * 0.3, r * 0.2 + 0.02));
            }
            let gr = group_leaves
                .iter()
                .map(|s| s.center.distance(gc) + s.radius)
                .fold(0.0, f32::max);
            nodes.push(SphereNode {
                center: gc,
                radius: gr + 1e-6,
                first_child: 0,
                child_count: per as u32,
            });
            leaves.push(group_leaves);
        }
        let mut next = nodes.len() as u32;
        for (g, group) in leaves.iter().enumerate() {
            nodes[g + 1].first_child = next;
            for s in group {
                nodes.push(SphereNode {
                    center: s.center,
                    radius: s.radius,
                    first_child: 0,
                    child_count: 0,
                });
                next += 1;
            }
        }
        let root_r = nodes[1..]
            .iter()
            .map(|n| n.center.length() + n.radius)
            .fold(0.0, f32::max);
        nodes[0].radius = root_r + 1e-6;
        SphereTree::new(nodes).unwrap()
    }

    fn placed(t: &SphereTree, pose: Pose) -> Vec<Vec3> {
        let mut c = vec![Vec3::ZERO; t.nodes().len()];
        t.place(&pose, &mut c);
        c
    }

    fn brute_force(a: PlacedTree, b: PlacedTree, margin: f32) -> Vec<Contact> {
        let mut out = Vec::new();
        for &ia in a.tree.leaves() {
            for &ib in b.tree.leaves() {
                let sa = Sphere::new(a.centers[ia as usize], a.tree.nodes()[ia as usize].radius);
                let sb = Sphere::new(b.centers[ib as usize], b.tree.nodes()[ib as usize].radius);
                if let Some(mut c) = contact_sphere_sphere(sa, sb, margin) {
                    c.feature_a = ia;
                    c.feature_b = ib;
                    out.push(c);
                }
            }
        }
        out
    }

    fn key(c: &Contact) -> (u32, u32) {
        (c.feature_a, c.feature_b)
    }

    #[test]
    fn two_single_spheres_touching() {
        let t = SphereTree::from_root_and_leaves(Sphere::new(Vec3::ZERO, 0.5), &[]).unwrap();
        let (ca, cb) = ([Vec3::ZERO], [Vec3::new(1.0, 0.0, 0.0)]);
        let mut out = Vec::new();
        contact_tree_tree(
            PlacedTree::new(&t, &ca),
            PlacedTree::new(&t, &cb),
            0.0,
            &mut out,
        );
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].separation, 0.0);
        assert_eq!(key(&out[0]), (0, 0));
    }

    #[test]
    fn far_apart_trees_give_nothing() {
        let seed = [(Vec3::X, 0.5), (Vec3::Y, 0.3), (Vec3::Z, 0.2)];
        let t = tree(&seed, 3, 4);
        let ca = placed(&t, Pose::IDENTITY);
        let cb = placed(&t, Pose::from_position(Vec3::new(10.0, 0.0, 0.0)));
        let mut out = Vec::new();
        contact_tree_tree(
            PlacedTree::new(&t, &ca),
            PlacedTree::new(&t, &cb),
            0.1,
            &mut out,
        );
        assert!(out.is_empty());
    }

    fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
        (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    /// A root and `leaves` leaves (a balloon's shape), overlapping like a
    /// balloon's, scaled by `scale`.
    fn flat_tree(seed: &[(Vec3, f32)], leaves: usize, scale: f32) -> SphereTree {
        let spheres: Vec<Sphere> = (0..leaves)
            .map(|l| {
                let (offset, r) = seed[l % seed.len()];
                Sphere::new(offset * 0.3 * scale, (r * 0.2 + 0.02) * scale)
            })
            .collect();
        let reach = spheres
            .iter()
            .map(|s| s.center.length() + s.radius)
            .fold(0.0, f32::max);
        SphereTree::from_root_and_leaves(Sphere::new(Vec3::ZERO, reach + 1e-6), &spheres).unwrap()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Two flat trees take `flat_pairs`: the contacts `descend` gives, in its order.
        #[test]
        fn flat_pairs_equal_the_descent_in_order(
            seed in prop::collection::vec((vec3(1.0), 0.0f32..1.0), 4..20),
            leaves_a in 1usize..8, leaves_b in 1usize..8, scale_b in 0.5f32..2.0,
            offset in vec3(1.2), axis in vec3(1.0), angle in 0.0f32..6.3, margin in 0.0f32..0.1
        ) {
            let ta = flat_tree(&seed, leaves_a, 1.0);
            let tb = flat_tree(&seed[1..], leaves_b, scale_b);
            let rotation = Quat::from_axis_angle(axis.try_normalize().unwrap_or(Vec3::Y), angle);
            let ca = placed(&ta, Pose::IDENTITY);
            let cb = placed(&tb, Pose::new(offset, rotation));
            let (pa, pb) = (PlacedTree::new(&ta, &ca), PlacedTree::new(&tb, &cb));
            prop_assert!(is_flat(&pa) && is_flat(&pb));
            let mut got = Vec::new();
            contact_tree_tree(pa, pb, margin, &mut got);
            let mut descended = Vec::new();
            if nodes_touch(&pa, 0, &pb, 0, margin) {
                descend(&pa, &pb, 0, 0, margin, &mut descended);
            }
            prop_assert_eq!(&got, &descended);
            let mut expected = brute_force(pa, pb, margin);
            got.sort_by_key(key);
            expected.sort_by_key(key);
            prop_assert_eq!(got, expected);
        }

        #[test]
        fn descent_equals_all_leaf_pairs(
            seed in prop::collection::vec((vec3(1.0), 0.0f32..1.0), 4..20),
            groups_a in 1usize..5, per_a in 1usize..6, groups_b in 1usize..5, per_b in 1usize..6,
            offset in vec3(1.6), axis in vec3(1.0), angle in 0.0f32..6.3, margin in 0.0f32..0.1
        ) {
            let ta = tree(&seed, groups_a, per_a);
            let tb = tree(&seed[1..], groups_b, per_b);
            let rotation = Quat::from_axis_angle(axis.try_normalize().unwrap_or(Vec3::Y), angle);
            let ca = placed(&ta, Pose::IDENTITY);
            let cb = placed(&tb, Pose::new(offset, rotation));
            let (pa, pb) = (PlacedTree::new(&ta, &ca), PlacedTree::new(&tb, &cb));
            let mut got = Vec::new();
            contact_tree_tree(pa, pb, margin, &mut got);
            let mut expected = brute_force(pa, pb, margin);
            got.sort_by_key(key);
            expected.sort_by_key(key);
            prop_assert_eq!(got, expected);
        }
    }
}
