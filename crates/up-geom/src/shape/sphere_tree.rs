//! Sphere trees: a hierarchy of spheres of any depth in the body frame.
//!
//! The root (node 0) bounds everything; the leaves are the collision spheres.
//! Nodes are stored flat, children of a node contiguous and after their parent,
//! so a descent is a walk over one small array (the report's section 4.2).

use glam::Vec3;
use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::sphere::Sphere;
use crate::pose::Pose;

/// One node: a sphere in the body frame and the range of its children.
/// A node with `child_count == 0` is a leaf. 24 bytes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SphereNode {
    pub center: Vec3,
    /// m
    pub radius: f32,
    pub first_child: u32,
    pub child_count: u32,
}

impl SphereNode {
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.child_count == 0
    }

    #[inline]
    pub fn sphere(&self) -> Sphere {
        Sphere::new(self.center, self.radius)
    }

    #[inline]
    pub fn children(&self) -> std::ops::Range<usize> {
        self.first_child as usize..(self.first_child + self.child_count) as usize
    }
}

#[derive(Debug, Error, PartialEq)]
pub enum SphereTreeError {
    #[error("a sphere tree needs at least one node")]
    Empty,
    #[error("node {node}: radius {radius} must be finite and > 0")]
    BadRadius { node: usize, radius: f32 },
    #[error("node {node}: centre must be finite")]
    BadCenter { node: usize },
    #[error("node {node}: children {first}..{end} must lie after the node and inside the tree of {len} nodes")]
    BadChildren {
        node: usize,
        first: usize,
        end: usize,
        len: usize,
    },
    #[error("node {node} is the child of more than one parent, or of none")]
    BadParent { node: usize },
    #[error("node {child} pokes out of its parent {parent} by {excess} m")]
    NotBounded {
        parent: usize,
        child: usize,
        excess: f32,
    },
}

/// A validated sphere tree. See the module docs for the layout.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SphereTree {
    nodes: Vec<SphereNode>,
    leaves: Vec<u32>,
}

/// How far a child may poke out of its parent and still count as bounded (m).
pub const BOUND_TOLERANCE: f32 = 1e-5;

impl SphereTree {
    /// Validates and builds a tree from flat nodes (root first).
    pub fn new(nodes: Vec<SphereNode>) -> Result<Self, SphereTreeError> {
        if nodes.is_empty() {
            return Err(SphereTreeError::Empty);
        }
        let len = nodes.len();
        let mut parent_count = vec![0u32; len];
        for (i, n) in nodes.iter().enumerate() {
            if !(n.radius.is_finite() && n.radius > 0.0) {
                return Err(SphereTreeError::BadRadius {
                    node: i,
                    radius: n.radius,
                });
            }
            if !n.center.is_finite() {
                return Err(SphereTreeError::BadCenter { node: i });
            }
            let (first, end) = (
                n.first_child as usize,
                n.first_child as usize + n.child_count as usize,
            );
            if n.child_count > 0 && (first <= i || end > len) {
                return Err(SphereTreeError::BadChildren {
                    node: i,
                    first,
                    end,
                    len,
                });
            }
            for c in n.children() {
                parent_count[c] += 1;
                let excess = n.center.distance(nodes[c].center) + nodes[c].radius - n.radius;
                if excess > BOUND_TOLERANCE {
                    return Err(SphereTreeError::NotBounded {
                        parent: i,
                        child: c,
                        excess,
                    });
                }
            }
        }
        if let Some(bad) = (1..len).find(|&i| parent_count[i] != 1) {
            return Err(SphereTreeError::BadParent { node: bad });
        }
        let leaves = (0..len as u32)
            .filter(|&i| nodes[i as usize].is_leaf())
            .collect();
        Ok(Self { nodes, leaves })
    }

    /// A two-level tree: a root that bounds the given leaves.
    pub fn from_root_and_leaves(root: Sphere, leaves: &[Sphere]) -> Result<Self, SphereTreeError> {
        let mut nodes = vec![SphereNode {
            center: root.center,
            radius: root.radius,
            first_child: 1,
            child_count: leaves.len() as u32,
        }];
        if leaves.is_empty() {
            nodes[0].first_child = 0;
        }
        nodes.extend(leaves.iter().map(|s| SphereNode {
            center: s.center,
            radius: s.radius,
            first_child: 0,
            child_count: 0,
        }));
        Self::new(nodes)
    }

    #[inline]
    pub fn nodes(&self) -> &[SphereNode] {
        &self.nodes
    }

    #[inline]
    pub fn root(&self) -> &SphereNode {
        &self.nodes[0]
    }

    /// Node indices of the leaves, in increasing order.
    #[inline]
    pub fn leaves(&self) -> &[u32] {
        &self.leaves
    }

    pub fn leaf_spheres(&self) -> impl Iterator<Item = Sphere> + '_ {
        self.leaves.iter().map(|&i| self.nodes[i as usize].sphere())
    }

    /// Writes the world-space centre of every node for `pose` into `out`
    /// (which must hold `nodes().len()` entries).
    pub fn place(&self, pose: &Pose, out: &mut [Vec3]) {
        self.place_scaled(pose, 1.0, out);
    }

    /// `place` for the tree grown by `scale` about its origin (a balloon
    /// that shrinks as it loses gas); scale 1 places it exactly as `place`.
    pub fn place_scaled(&self, pose: &Pose, scale: f32, out: &mut [Vec3]) {
        for (o, n) in out.iter_mut().zip(&self.nodes) {
            *o = pose.transform_point(n.center * scale);
        }
    }

    /// The same tree with every centre moved by `-offset` (to re-centre it
    /// on a body's centre of mass, say).
    pub fn translated(&self, offset: Vec3) -> SphereTree {
        let mut t = self.clone();
        for n in &mut t.nodes {
            n.center += offset;
        }
        t
    }
}

/// A sphere tree together with the world-space centres of its nodes:
/// what the contact queries take.
#[derive(Clone, Copy, Debug)]
pub struct PlacedTree<'a> {
    pub tree: &'a SphereTree,
    /// World-space centre of each node, indexed like `tree.nodes()`.
    pub centers: &'a [Vec3],
    /// The tree's size over its own: every radius is multiplied by it (the
    /// centres were placed with it, `SphereTree::place_scaled`).
    pub scale: f32,
}

impl<'a> PlacedTree<'a> {
    /// The tree at its own size.
    pub fn new(tree: &'a SphereTree, centers: &'a [Vec3]) -> Self {
        Self {
            tree,
            centers,
            scale: 1.0,
        }
    }

    /// Radius of node `i` as placed, m.
    #[inline]
    pub fn radius(&self, i: u32) -> f32 {
        self.tree.nodes()[i as usize].radius * self.scale
    }
}
