//! Stage 1, placing: every body's sphere tree at its pose, its bounding
//! sphere widened by how far it may move this step (its velocity and the
//! knocks its pairs may give it), and the broadphase's pairs of those bounds.

use glam::Vec3;
use up_geom::norm::{distance, unit_or_zero, Norm};
use up_geom::Pose;

use super::{World, PLACE_CHUNK};
use crate::body::{Bodies, ShapeData};
use crate::knocks::{add_knocks, KnockLists};
use crate::narrow_phase::StepMotion;
use crate::threading::tasks::{for_each_run, Ragged};

/// The placing stage's buffers: per body unless said otherwise.
#[derive(Clone, Debug, Default)]
pub(crate) struct Placement {
    /// World centres of every body's sphere-tree nodes, back to back.
    pub node_centers: Vec<Vec3>,
    /// Where each body's nodes start in `node_centers`.
    pub node_start: Vec<u32>,
    pub bound_center: Vec<Vec3>,
    /// Root radius plus the speculative margin and this step's reach, m.
    pub bound_radius: Vec<f32>,
    /// Asleep, and its nodes placed since it fell asleep.
    pub placed_asleep: Vec<bool>,
    /// How far it moves this step (zero for sleepers).
    pub motion: Vec<StepMotion>,
    /// The knocking pairs, in a step whose knocks are found in tasks
    /// (`add_knocks`).
    pub knocks: KnockLists,
    /// Handle index of each body (the narrowphase keys pairs by them).
    pub handle: Vec<u32>,
}

impl Placement {
    /// Gives back the capacity the knocks' lists left unused (`spare`).
    pub fn release_spare(&mut self) {
        self.knocks.release_spare();
    }
}

/// Whether the root spheres of bodies `a` and `b`, placed at `centers`, are
/// within `gap` of touching.
pub(crate) fn roots_within(
    shapes: &[ShapeData],
    bodies: &Bodies,
    centers: &[Vec3],
    a: usize,
    b: usize,
    gap: f32,
) -> bool {
    let root =
        |i: usize| shapes[bodies.shape[i] as usize].tree.root().radius * bodies.size[i].scale;
    distance(centers[a], centers[b]) < root(a) + root(b) + gap
}

impl World {
    /// World centres of every node of every body, bounding spheres and speculative margins.
    pub(super) fn place_bodies(&mut self, at_rest: bool) {
        let n = self.bodies.len();
        let s = &mut self.stages.place;
        // The bodies' node counts change only where bodies come or go (a
        // removal clears `placed_asleep`; bodies are added at the end).
        if s.placed_asleep.len() != n || s.node_start.len() != n {
            s.node_start.clear();
            let mut total = 0u32;
            for i in 0..n {
                s.node_start.push(total);
                total += self.shapes[self.bodies.shape[i] as usize]
                    .tree
                    .nodes()
                    .len() as u32;
            }
            // Every body's entries are written below (a sleeper's nodes stay
            // where they were placed): only the lengths matter here.
            s.node_centers.resize(total as usize, Vec3::ZERO);
        }
        s.placed_asleep.resize(n, false);
        s.motion.resize(n, StepMotion::default());
        s.bound_center.resize(n, Vec3::ZERO);
        s.bound_radius.resize(n, 0.0);
        s.handle.resize(n, 0);
        let (bodies, shapes, dt) = (&self.bodies, &self.shapes, self.def.dt);
        let speculative_distance = self.def.speculative_distance;
        let parts = (
            Ragged::new(&mut s.node_centers, &s.node_start),
            &mut s.placed_asleep[..],
            &mut s.motion[..],
            &mut s.bound_center[..],
            &mut s.bound_radius[..],
            &mut s.handle[..],
        );
        for_each_run(n, PLACE_CHUNK, parts, |first, run| {
            let (mut nodes, placed_asleep, motions, bound_center, bound_radius, handle) = run;
            for k in 0..placed_asleep.len() {
                let i = first + k;
                // A sleeper does not move: placed once, its nodes and bounds
                // stay as they are (its size too, while it sleeps); only the
                // knock the last step's pairs gave it is cleared.
                let asleep = !bodies.awake[i];
                if asleep && placed_asleep[k] {
                    motions[k] = StepMotion::default();
                    continue;
                }
                let shape = &shapes[bodies.shape[i] as usize];
                let scale = bodies.size[i].scale;
                let nodes = nodes.item(k);
                let pose = Pose::new(bodies.center[i], bodies.rotation[i]);
                shape.tree.place_scaled(&pose, scale, nodes);
                placed_asleep[k] = asleep;
                let motion = if at_rest || asleep {
                    StepMotion::default()
                } else {
                    let rate = bodies.angular_velocity[i].norm();
                    StepMotion {
                        linear: bodies.linear_velocity[i] * dt,
                        spin: rate * (shape.bound_radius * scale) * dt,
                        turn: rate * dt,
                        ..StepMotion::default()
                    }
                };
                // Wide enough for every pair the narrowphase may find a contact in.
                let margin = speculative_distance + motion.reach();
                motions[k] = motion;
                bound_center[k] = nodes[0];
                bound_radius[k] = shape.tree.root().radius * scale + margin;
                handle[k] = bodies.id[i].index;
            }
        });
    }

    /// Each body's knock, from the broadphase's pairs (`knocks::add_knocks`).
    pub(super) fn add_knocks(&mut self) {
        let s = &mut self.stages.place;
        let (shapes, bodies) = (&self.shapes, &self.bodies);
        let centers = &s.bound_center;
        let towards_within = |a: usize, b: usize, gap| {
            roots_within(shapes, bodies, centers, a, b, gap)
                .then(|| unit_or_zero(centers[b] - centers[a]))
        };
        let inv_mass = |i: usize| bodies.inv_mass[i];
        let bounce = 1.0 + self.def.restitution;
        let share = |a: usize, b: usize| bounce * inv_mass(a) / (inv_mass(a) + inv_mass(b));
        add_knocks(
            &mut s.motion,
            &self.stages.broad.pairs,
            &mut s.knocks,
            towards_within,
            share,
            self.def.speculative_distance,
            // Once a body, not in each of its pairs: the turn its knock may give.
            |i, m| {
                m.knock_turn = if m.knock == Vec3::ZERO {
                    0.0
                } else {
                    let shape = &shapes[bodies.shape[i] as usize];
                    let (factor, scale) = (bodies.inertia_factor[i], bodies.size[i].scale);
                    m.knock.norm() * shape.turn_per_knock(factor, scale, bodies.inv_mass[i])
                };
            },
        );
    }

    /// Cell radius: the largest root sphere plus its margin at a brisk ascent.
    pub(super) fn cell_radius(&self) -> f32 {
        let mut largest = self
            .shapes
            .iter()
            .map(|s| s.tree.root().radius)
            .fold(0.0, f32::max);
        // Balloons the warmth has grown (gas rarely grows one more than a few %).
        if self.has_gas {
            let scale = self.bodies.size.iter().map(|s| s.scale).fold(1.0, f32::max);
            largest *= scale;
        }
        largest + self.def.speculative_distance + 3.0 * self.def.dt
    }

    pub(super) fn find_pairs(&mut self) {
        let cell_radius = self.cell_radius();
        let s = &self.stages.place;
        self.stages.broad.update(
            &s.bound_center,
            &s.bound_radius,
            &self.bodies.awake,
            cell_radius,
        );
    }
}
