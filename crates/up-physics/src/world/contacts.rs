//! Stage 2, contacts: the narrowphase over the placed bodies' pairs, and the
//! contact points it found, for debug views and tests.

use glam::Vec3;

use super::{StepStats, World};
use crate::body::BodyId;
use crate::contact::STATIC_BODY;
use crate::narrow_phase::NarrowInput;

impl World {
    /// Stage 2, the narrowphase: the contact points of this step's pairs
    /// (with `all`, of every pair, awake or not: a measurement, not a step).
    pub(super) fn find_contacts(&mut self, all: bool) {
        let cell_radius = self.cell_radius();
        let (s, broad, narrow) = (
            &self.stages.place,
            &mut self.stages.broad,
            &mut self.stages.narrow,
        );
        let every;
        let awake = if all {
            every = vec![true; self.bodies.len()];
            broad.update(&s.bound_center, &s.bound_radius, &every, cell_radius);
            &every
        } else {
            &self.bodies.awake
        };
        let input = NarrowInput {
            shapes: &self.shapes,
            shape: &self.bodies.shape,
            size: &self.bodies.size,
            node_centers: &s.node_centers,
            node_start: &s.node_start,
            handle: &s.handle,
            awake,
            motion: &s.motion,
            speculative_distance: self.def.speculative_distance,
        };
        narrow.update(&input, &broad.pairs, self.def.room.as_ref());
        self.stages.solved = false;
        if all {
            return;
        }
        self.stats = StepStats {
            max_penetration: narrow.found.max_penetration,
            pair_count: broad.pairs.len() as u32,
            contact_count: narrow.found.contacts.len() as u32,
            awake_count: self.bodies.awake.iter().filter(|&&a| a).count() as u32,
            quarantined_count: self.stats.quarantined_count,
            position_passes: 0,
        };
    }

    /// A fresh narrowphase over the current state: the deepest overlap now, m.
    pub fn max_penetration_now(&mut self) -> f32 {
        self.place_bodies(true);
        self.find_contacts(true);
        self.stages.narrow.found.max_penetration
    }
}

/// A contact point found by the last step (for debug views and tests).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactInfo {
    pub body_a: BodyId,
    /// `None` for the room.
    pub body_b: Option<BodyId>,
    /// Midpoint of the two surface points, world frame, m.
    pub point: Vec3,
    /// Unit, from A to B.
    pub normal: Vec3,
    /// Negative when overlapping, m.
    pub separation: f32,
    /// Total impulse along the normal that the contact gave over the last
    /// step (all substeps and the bounce), N·s, ≥ 0: over the step's `dt`,
    /// the mean force.
    pub normal_impulse: f32,
    /// Largest normal impulse the contact applied within one substep of the
    /// last step, N·s (an impact's peak; over `World::substep_dt`, its force).
    pub max_normal_impulse: f32,
    /// Total friction impulse on body A over the last step, world frame, N·s.
    pub tangent_impulse: Vec3,
}

impl World {
    /// The contact points of the last step (empty after a body was removed
    /// since); after `max_penetration_now`, that measurement's, with no impulses.
    pub fn contact_points(&self) -> impl Iterator<Item = ContactInfo> + '_ {
        let n = self.bodies.len();
        let contacts = &self.stages.narrow.found.contacts;
        let solver = &self.stages.solve.solver;
        let solved = self.stages.solved;
        let valid = contacts.iter().all(|c| {
            (c.body_a as usize) < n && (c.body_b == STATIC_BODY || (c.body_b as usize) < n)
        });
        contacts
            .iter()
            .take(if valid { contacts.len() } else { 0 })
            .enumerate()
            .map(move |(i, c)| {
                let totals = solved
                    .then(|| solver.totals(i, contacts.len()))
                    .flatten()
                    .unwrap_or_default();
                ContactInfo {
                    body_a: self.bodies.id[c.body_a as usize],
                    body_b: (c.body_b != STATIC_BODY).then(|| self.bodies.id[c.body_b as usize]),
                    point: 0.5 * (c.point_a + c.point_b),
                    normal: c.normal,
                    separation: c.separation,
                    normal_impulse: totals.normal_impulse,
                    max_normal_impulse: totals.max_normal_impulse,
                    tangent_impulse: totals.tangent_impulse,
                }
            })
    }

    /// The solver's substep, s: the step's `dt` over its substeps.
    pub fn substep_dt(&self) -> f32 {
        self.def.dt / self.def.substeps as f32
    }
}
