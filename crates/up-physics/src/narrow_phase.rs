//! Narrowphase: contact points for the broadphase's pairs (sphere tree
//! against sphere tree) and for every awake body against the room (sphere
//! tree against triangle mesh), with a speculative margin that grows with the
//! bodies' motion so that fast bodies meet what lies in their way this step.

use glam::Vec3;
use up_geom::query::contact_tree_tree::contact_tree_tree;
use up_geom::query::contact_tree_trimesh::contact_tree_trimesh;
use up_geom::{Contact, PlacedTree, TriMesh};

use crate::body::ShapeData;

use crate::contact::{pair_key, ContactPoint, STATIC_BODY};

/// What the narrowphase reads about the bodies (all dense-indexed).
pub(crate) struct NarrowInput<'a> {
    pub shapes: &'a [ShapeData],
    pub shape: &'a [u32],
    pub node_centers: &'a [Vec3],
    pub node_start: &'a [u32],
    pub handle: &'a [u32],
    pub awake: &'a [bool],
    /// Speculative margin of each body for this step, m.
    pub margin: &'a [f32],
}

impl NarrowInput<'_> {
    fn placed(&self, i: usize) -> PlacedTree<'_> {
        let tree = &self.shapes[self.shape[i] as usize].tree;
        let start = self.node_start[i] as usize;
        PlacedTree {
            tree,
            centers: &self.node_centers[start..start + tree.nodes().len()],
        }
    }
}

#[derive(Clone, Debug, Default)]
pub(crate) struct NarrowPhase {
    scratch: Vec<Contact>,
    /// Output: contact points, grouped by pair.
    pub contacts: Vec<ContactPoint>,
    /// Output: (pair key, first contact, count), one per pair with contacts.
    pub runs: Vec<(u64, u32, u32)>,
    /// Output: deepest overlap, m.
    pub max_penetration: f32,
}

impl NarrowPhase {
    pub fn update(&mut self, input: &NarrowInput, pairs: &[(u32, u32)], room: Option<&TriMesh>) {
        self.contacts.clear();
        self.runs.clear();
        self.max_penetration = 0.0;

        // The room first: it anchors the pile, and Gauss-Seidel converges
        // fastest from the anchor outwards.
        if let Some(room) = room {
            for a in 0..input.awake.len() {
                if !input.awake[a] {
                    continue;
                }
                self.scratch.clear();
                contact_tree_trimesh(input.placed(a), room, input.margin[a], &mut self.scratch);
                let key = pair_key(input.handle[a], STATIC_BODY);
                self.push_run(key, a as u32, STATIC_BODY);
            }
        }

        for &(i, j) in pairs {
            // Order each pair by handle index: the warm-start key must not
            // depend on dense order, which removal changes.
            let (a, b) = if input.handle[i as usize] < input.handle[j as usize] {
                (i, j)
            } else {
                (j, i)
            };
            let margin = input.margin[a as usize] + input.margin[b as usize];
            self.scratch.clear();
            contact_tree_tree(
                input.placed(a as usize),
                input.placed(b as usize),
                margin,
                &mut self.scratch,
            );
            let key = pair_key(input.handle[a as usize], input.handle[b as usize]);
            self.push_run(key, a, b);
        }
    }

    fn push_run(&mut self, key: u64, a: u32, b: u32) {
        if self.scratch.is_empty() {
            return;
        }
        let start = self.contacts.len() as u32;
        for c in &self.scratch {
            self.max_penetration = self.max_penetration.max(c.depth());
            self.contacts.push(ContactPoint {
                body_a: a,
                body_b: b,
                normal: c.normal,
                point_a: c.point_a,
                point_b: c.point_b,
                separation: c.separation,
                feature: ((c.feature_a as u64) << 32) | c.feature_b as u64,
            });
        }
        self.runs.push((key, start, self.scratch.len() as u32));
    }
}
