//! The bodies' bounding spheres (their trees' roots) at a substep's pose, as
//! the ribbons' pushes see them: every body's, or, with few ribbons among
//! many bodies, only the ribbons' candidates'. A point within a bound is
//! tested against the balloon's leaves in its own frame (`collide`), so no
//! leaf is placed here.

use glam::Vec3;

use super::solve::SubstepInput;
use crate::solver::body_state::BodyState;
use crate::threading::tasks::fill_chunks;

/// Bodies one task places.
const BODY_CHUNK: usize = 1024;

/// A body's bounding sphere (its tree's root) at this substep's pose.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Bound {
    pub center: Vec3,
    pub radius: f32,
}

/// The bodies' bounds at this substep's pose.
#[derive(Clone, Debug, Default)]
pub(crate) struct BodySpheres {
    /// Per body (dense).
    pub bounds: Vec<Bound>,
}

impl BodySpheres {
    /// Places the bounds of the bodies the ribbons may touch (every body's,
    /// or only those in `input.bodies` when they are few) at `states`' poses.
    pub fn place(&mut self, input: &SubstepInput, states: &[BodyState]) {
        // The bodies (the states may hold more: the solver keeps its buffers).
        let n = input.centers.len();
        self.bounds.resize(n, Bound::default());
        let bound = |b: usize| {
            let s = &states[b];
            let center = input.centers[b] + s.dp;
            let tree = &input.shapes[input.shape_of[b] as usize].tree;
            let (root, scale) = (tree.root(), input.size[b].scale);
            Bound {
                center: center + s.q * (root.center * scale),
                radius: root.radius * scale,
            }
        };
        if 2 * input.bodies.len() < n {
            // Only the ribbons' candidates are read: a few ribbons among
            // many bodies (a lone balloon awake in a time-lapse) place few.
            for &b in input.bodies {
                self.bounds[b as usize] = bound(b as usize);
            }
            return;
        }
        fill_chunks(&mut self.bounds, BODY_CHUNK, |first, run| {
            for (k, out) in run.iter_mut().enumerate() {
                *out = bound(first + k);
            }
        });
    }
}
