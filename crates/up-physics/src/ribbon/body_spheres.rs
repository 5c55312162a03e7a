//! The bodies as the ribbons' pushes see them at a substep's pose: each
//! one's bounding sphere (its tree's root), centre, turn, move over the
//! substep and shape (`NearBalloon`), for every body, or, with few ribbons
//! among many bodies, only the ribbons' candidates. Placed once a substep
//! for all the ribbons: a body near several ribbons is read from here by
//! each, not placed again by each. A point within a bound is tested against
//! the balloon's leaves in its own frame (`collide`), so no leaf is placed
//! here.

use glam::{Quat, Vec3};
use up_geom::Sphere;

use super::collide::NearBalloon;
use super::leaf_capsule::{LeafCapsule, PlacedCapsule};
use super::solve::SubstepInput;
use crate::solver::body_state::BodyState;
use crate::threading::tasks::fill_chunks;

/// Bodies one task places.
const BODY_CHUNK: usize = 1024;

/// What a body not placed this substep holds (no ribbon reads it).
const UNPLACED: NearBalloon = NearBalloon {
    state: u32::MAX,
    bound: Sphere {
        center: Vec3::ZERO,
        radius: 0.0,
    },
    moved: Vec3::ZERO,
    center: Vec3::ZERO,
    rotation: Quat::IDENTITY,
    tree: 0,
    scale: 0.0,
    capsule: PlacedCapsule::ANYWHERE,
};

/// The bodies at this substep's pose.
#[derive(Clone, Debug, Default)]
pub(crate) struct BodySpheres {
    /// Per body (dense).
    pub placed: Vec<NearBalloon>,
    /// Per shape, the capsule holding its tree's leaves (shapes are only
    /// added, so those found stay right).
    pub capsules: Vec<LeafCapsule>,
}

impl BodySpheres {
    /// Places the bodies the ribbons may touch (every body, or only those
    /// in `input.bodies` when they are few) at `states`' poses.
    pub fn place(&mut self, input: &SubstepInput, states: &[BodyState]) {
        // The bodies (the states may hold more: the solver keeps its buffers).
        let n = input.centers.len();
        let known = self.capsules.len();
        self.capsules.extend(
            input.shapes[known..]
                .iter()
                .map(|s| LeafCapsule::of(&s.tree)),
        );
        self.placed.resize(n, UNPLACED);
        let capsules = &self.capsules;
        // With few ribbons among many bodies (a lone balloon awake in a
        // time-lapse) a point rarely comes within another balloon's bound:
        // the capsules are not placed, and every such point is pushed exactly.
        let few = 2 * input.bodies.len() < n;
        let place_body = |b: usize| {
            let s = &states[b];
            let center = input.centers[b] + s.dp;
            let tree = input.shape_of[b];
            let root = input.shapes[tree as usize].tree.root();
            let scale = input.size[b].scale;
            NearBalloon {
                state: b as u32,
                bound: Sphere::new(center + s.q * (root.center * scale), root.radius * scale),
                moved: s.v * input.h,
                center,
                rotation: s.q,
                tree,
                scale,
                capsule: match few {
                    true => PlacedCapsule::ANYWHERE,
                    false => capsules[tree as usize].placed(center, s.q, scale),
                },
            }
        };
        if few {
            // Only the ribbons' candidates are read: a few ribbons among
            // many bodies (a lone balloon awake in a time-lapse) place few.
            for &b in input.bodies {
                self.placed[b as usize] = place_body(b as usize);
            }
            return;
        }
        fill_chunks(&mut self.placed, BODY_CHUNK, |first, run| {
            for (k, out) in run.iter_mut().enumerate() {
                *out = place_body(first + k);
            }
        });
    }
}
