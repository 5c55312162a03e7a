//! The bodies' spheres at a substep's pose, as the ribbons' pushes see them:
//! every body's bounding sphere (its tree's root), and, when the awake
//! ribbons are many for the bodies, every body's leaf spheres, placed once a
//! substep for all the ribbons (a balloon's leaves are wanted by a few
//! ribbons each substep in a crowd: placing them per ribbon would place
//! each several times). With few ribbons each ribbon places the leaves of
//! the balloons its points come within (`LaneGroup::push_point_out`). Both
//! place a sphere with the same operations: the results are the same.

use glam::{Quat, Vec3};
use up_geom::{Sphere, SphereTree};

use super::collide::NearBalloon;
use super::solve::SubstepInput;
use crate::solver::body_state::BodyState;
use crate::threading::tasks::{fill_chunks, for_each_run, Ragged};

/// Bodies one task places.
const BODY_CHUNK: usize = 1024;

/// A body's bounding sphere (its tree's root) at this substep's pose.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Bound {
    pub center: Vec3,
    pub radius: f32,
}

/// The bodies' spheres at this substep's pose.
#[derive(Clone, Debug, Default)]
pub(crate) struct BodySpheres {
    /// Per body (dense).
    pub bounds: Vec<Bound>,
    /// Body `b`'s leaves are `leaves[leaf_start[b]..leaf_start[b + 1]]`,
    /// when `all_leaves`.
    pub leaves: Vec<Sphere>,
    pub leaf_start: Vec<u32>,
    pub all_leaves: bool,
}

/// Places `b`'s leaf spheres at its pose in `b`, after those in `out`.
pub(crate) fn place_leaves(b: &NearBalloon, input: &SubstepInput, out: &mut Vec<Sphere>) {
    let tree = &input.shapes[b.tree as usize].tree;
    let scale = input.size[b.state as usize].scale;
    out.extend(leaf_spheres(tree, b.center, b.rotation, scale));
}

/// `tree`'s leaf spheres for a body whose centre of mass is at `center`,
/// turned by `rotation`, its tree scaled by `scale`: the one placement both
/// ways of placing leaves use, so their results agree bit for bit.
fn leaf_spheres(
    tree: &SphereTree,
    center: Vec3,
    rotation: Quat,
    scale: f32,
) -> impl Iterator<Item = Sphere> + '_ {
    let nodes = tree.nodes();
    tree.leaves().iter().map(move |&leaf| {
        let node = &nodes[leaf as usize];
        Sphere::new(
            center + rotation * (node.center * scale),
            node.radius * scale,
        )
    })
}

impl BodySpheres {
    /// Places the bounds of the bodies the ribbons may touch (every body's,
    /// or only those in `input.bodies` when they are few) at `states`'
    /// poses, and every body's leaves too if `all_leaves`.
    pub fn place(&mut self, input: &SubstepInput, states: &[BodyState], all_leaves: bool) {
        // The bodies (the states may hold more: the solver keeps its buffers).
        let n = input.centers.len();
        self.bounds.resize(n, Bound::default());
        self.all_leaves = all_leaves;
        let tree = |b: usize| &input.shapes[input.shape_of[b] as usize].tree;
        let bound = |b: usize| {
            let s = &states[b];
            let center = input.centers[b] + s.dp;
            let (root, scale) = (tree(b).root(), input.size[b].scale);
            Bound {
                center: center + s.q * (root.center * scale),
                radius: root.radius * scale,
            }
        };
        if !all_leaves && 2 * input.bodies.len() < n {
            // Only the ribbons' candidates are read: a few ribbons among
            // many bodies (a lone balloon awake in a time-lapse) place few.
            for &b in input.bodies {
                self.bounds[b as usize] = bound(b as usize);
            }
            return;
        }
        if !all_leaves {
            fill_chunks(&mut self.bounds, BODY_CHUNK, |first, run| {
                for (k, out) in run.iter_mut().enumerate() {
                    *out = bound(first + k);
                }
            });
            return;
        }
        self.leaf_start.clear();
        let mut total = 0u32;
        for b in 0..n {
            self.leaf_start.push(total);
            total += tree(b).leaves().len() as u32;
        }
        self.leaf_start.push(total);
        self.leaves
            .resize(total as usize, Sphere::new(Vec3::ZERO, 0.0));
        let leaves = Ragged::new(&mut self.leaves, &self.leaf_start[..n]);
        let parts = (&mut self.bounds[..], leaves);
        for_each_run(n, BODY_CHUNK, parts, |first, (bounds, mut leaves)| {
            for (k, out) in bounds.iter_mut().enumerate() {
                let b = first + k;
                *out = bound(b);
                let s = &states[b];
                let placed =
                    leaf_spheres(tree(b), input.centers[b] + s.dp, s.q, input.size[b].scale);
                for (sphere, placed) in leaves.item(k).iter_mut().zip(placed) {
                    *sphere = placed;
                }
            }
        });
    }

    /// Where `b`'s placed leaves are in `leaves` ((0, 0): not placed).
    pub fn leaves_of(&self, b: u32) -> (u32, u32) {
        if self.all_leaves {
            let b = b as usize;
            (self.leaf_start[b], self.leaf_start[b + 1])
        } else {
            (0, 0)
        }
    }
}
