//! Bounding volume hierarchy over a triangle mesh's triangles (owned by TriMesh).
//!
//! A binary tree in one flat array, built top-down by splitting the
//! primitives at the median centroid along the longest axis of their
//! centroid bounds. Nodes are in depth-first order: an inner node's first
//! child follows it, its second child sits at `offset`. Leaves hold at most
//! `MAX_LEAF_SIZE` primitives, a contiguous run of `primitives`. A query
//! walks the tree with a fixed stack array, so it never allocates.

use serde::{Deserialize, Serialize};

use super::aabb::Aabb;

/// Most primitives in one leaf.
pub const MAX_LEAF_SIZE: usize = 4;

/// Deepest traversal the query stack holds. A median split halves the
/// primitive count at each level, so 64 levels bound any u32 mesh.
const STACK_SIZE: usize = 64;

/// One node, 32 bytes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BvhNode {
    pub aabb: Aabb,
    /// Leaf: index of its first entry in `Bvh::primitives`. Inner node:
    /// index of its second child (the first one is the next node).
    pub offset: u32,
    /// Leaf: number of primitives (> 0). Inner node: 0.
    pub count: u32,
}

impl BvhNode {
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }
}

/// A BVH over primitives given by their bounding boxes.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Bvh {
    nodes: Vec<BvhNode>,
    /// Primitive indices, leaf by leaf.
    primitives: Vec<u32>,
    /// Bounding box of each entry of `primitives` (same order), so a leaf
    /// test reads memory in sequence.
    boxes: Vec<Aabb>,
}

impl Bvh {
    /// Builds the tree over `boxes` (primitive i has box `boxes[i]`).
    pub fn build(boxes: &[Aabb]) -> Bvh {
        let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * boxes.len() / MAX_LEAF_SIZE + 1);
        if !boxes.is_empty() {
            build_node(boxes, &mut order, 0, &mut nodes);
        }
        let sorted = order.iter().map(|&i| boxes[i as usize]).collect();
        Bvh {
            nodes,
            primitives: order,
            boxes: sorted,
        }
    }

    pub fn nodes(&self) -> &[BvhNode] {
        &self.nodes
    }

    /// Primitive indices in leaf order.
    pub fn primitives(&self) -> &[u32] {
        &self.primitives
    }

    /// Box around everything (empty for an empty tree).
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.aabb)
    }

    /// Calls `visit` with every primitive whose box overlaps `aabb`, until
    /// `visit` returns true; returns whether it did.
    pub fn query_until(&self, aabb: &Aabb, mut visit: impl FnMut(u32) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack = [0u32; STACK_SIZE];
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let mut index = stack[len] as usize;
            loop {
                let node = &self.nodes[index];
                if !node.aabb.overlaps(aabb) {
                    break;
                }
                if node.is_leaf() {
                    let range = node.offset as usize..(node.offset + node.count) as usize;
                    for (&p, b) in self.primitives[range.clone()]
                        .iter()
                        .zip(&self.boxes[range])
                    {
                        if b.overlaps(aabb) && visit(p) {
                            return true;
                        }
                    }
                    break;
                }
                // Go left now, come back for the right child later.
                if len < STACK_SIZE {
                    stack[len] = node.offset;
                    len += 1;
                } else if self.query_subtree_until(node.offset as usize, aabb, &mut visit) {
                    return true;
                }
                index += 1;
            }
        }
        false
    }

    /// Calls `visit` with every primitive whose box overlaps `aabb`.
    #[inline]
    pub fn query(&self, aabb: &Aabb, mut visit: impl FnMut(u32)) {
        self.query_until(aabb, |p| {
            visit(p);
            false
        });
    }

    /// Recursive walk used only if a (pathological) tree is deeper than the stack.
    fn query_subtree_until(
        &self,
        index: usize,
        aabb: &Aabb,
        visit: &mut impl FnMut(u32) -> bool,
    ) -> bool {
        let node = &self.nodes[index];
        if !node.aabb.overlaps(aabb) {
            return false;
        }
        if node.is_leaf() {
            let range = node.offset as usize..(node.offset + node.count) as usize;
            return self.primitives[range.clone()]
                .iter()
                .zip(&self.boxes[range])
                .any(|(&p, b)| b.overlaps(aabb) && visit(p));
        }
        self.query_subtree_until(index + 1, aabb, visit)
            || self.query_subtree_until(node.offset as usize, aabb, visit)
    }
}

/// Builds the subtree over `order` (a slice of primitive indices starting at
/// `first` in the final primitive order) and returns its node index.
fn build_node(boxes: &[Aabb], order: &mut [u32], first: usize, nodes: &mut Vec<BvhNode>) -> usize {
    let bounds = order
        .iter()
        .fold(Aabb::EMPTY, |b, &i| b.union(boxes[i as usize]));
    let index = nodes.len();
    nodes.push(BvhNode {
        aabb: bounds,
        offset: first as u32,
        count: order.len() as u32,
    });
    if order.len() <= MAX_LEAF_SIZE {
        return index;
    }
    let centroids = order
        .iter()
        .fold(Aabb::EMPTY, |b, &i| b.including(boxes[i as usize].center()));
    let extent = centroids.extents();
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = order.len() / 2;
    // Ties broken by index so the build does not depend on the sort's internals.
    order.select_nth_unstable_by(mid, |&i, &j| {
        let (ci, cj) = (
            boxes[i as usize].center()[axis],
            boxes[j as usize].center()[axis],
        );
        ci.total_cmp(&cj).then(i.cmp(&j))
    });
    let (left, right) = order.split_at_mut(mid);
    build_node(boxes, left, first, nodes);
    let right_index = build_node(boxes, right, first + mid, nodes);
    nodes[index].offset = right_index as u32;
    nodes[index].count = 0;
    index
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use proptest::prelude::*;

    fn boxes_strategy() -> impl Strategy<Value = Vec<Aabb>> {
        prop::collection::vec(
            (
                (-5.0f32..5.0, -5.0f32..5.0, -5.0f32..5.0),
                (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0),
            ),
            0..200,
        )
        .prop_map(|v| {
            v.into_iter()
                .map(|((x, y, z), (w, h, d))| {
                    let min = Vec3::new(x, y, z);
                    Aabb::new(min, min + Vec3::new(w, h, d))
                })
                .collect()
        })
    }

    #[test]
    fn every_primitive_appears_once_and_leaves_are_small() {
        let boxes: Vec<Aabb> = (0..100)
            .map(|i| Aabb::from_sphere(Vec3::new(i as f32 * 0.37 % 5.0, i as f32, 0.0), 0.5))
            .collect();
        let bvh = Bvh::build(&boxes);
        let mut seen = bvh.primitives().to_vec();
        seen.sort_unstable();
        assert_eq!(seen, (0..100).collect::<Vec<u32>>());
        for node in bvh.nodes() {
            assert!(node.count as usize <= MAX_LEAF_SIZE);
        }
    }

    #[test]
    fn query_until_stops_early() {
        let boxes: Vec<Aabb> = (0..50)
            .map(|i| Aabb::from_sphere(Vec3::new(i as f32, 0.0, 0.0), 0.6))
            .collect();
        let bvh = Bvh::build(&boxes);
        let mut visits = 0;
        let all = Aabb::new(Vec3::splat(-100.0), Vec3::splat(100.0));
        assert!(bvh.query_until(&all, |_| {
            visits += 1;
            true
        }));
        assert_eq!(visits, 1);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn query_equals_brute_force(
            boxes in boxes_strategy(),
            q in ((-6.0f32..6.0, -6.0f32..6.0, -6.0f32..6.0), (0.0f32..4.0, 0.0f32..4.0, 0.0f32..4.0))
        ) {
            let min = Vec3::new(q.0 .0, q.0 .1, q.0 .2);
            let query = Aabb::new(min, min + Vec3::new(q.1 .0, q.1 .1, q.1 .2));
            let bvh = Bvh::build(&boxes);
            let mut found = Vec::new();
            bvh.query(&query, |p| found.push(p));
            found.sort_unstable();
            let expected: Vec<u32> =
                (0..boxes.len() as u32).filter(|&i| boxes[i as usize].overlaps(&query)).collect();
            prop_assert_eq!(found, expected);
        }
    }
}
