//! A lane group's points pushed out of the balloons near its ribbons and out
//! of the room (`collide`), lane by lane where there is something to push
//! against: the balloons whose bounds a ribbon's box meets, lined up across
//! the lanes so that each point is tested against them four ribbons at a
//! time, and the pushes themselves (rare) made point by point.

use glam::Vec3;
use up_geom::Sphere;

use super::body_spheres::BodySpheres;
use super::collide::{push_out_of_balloon, NearTriangle};
use super::lane_group::LaneGroup;
use super::leaf_capsule::CapsuleLanes;
use super::solve::SubstepInput;
use super::{BALLOON_FRICTION, RIBBON_RADIUS};
use crate::solver::body_state::BodyState;
use crate::solver::lanes::{set, F4, LANES, V4};

/// The `k`th near balloon of each lane: its bounding sphere, the capsule
/// that holds its leaves, and the lanes that have a `k`th (bit `l` for lane
/// `l`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct NearSlot {
    center: V4,
    radius: F4,
    capsules: CapsuleLanes,
    lanes: u32,
}

/// What the pushes out of balloons read.
#[derive(Clone, Copy)]
pub(crate) struct NearInput<'a> {
    pub input: &'a SubstepInput<'a>,
    pub states: &'a [BodyState],
    pub bodies: &'a BodySpheres,
}

impl LaneGroup {
    /// Radius of point `i` in each lane, m.
    pub(super) fn radius(&self, i: usize) -> F4 {
        if i == self.points.len() - 1 {
            self.end_radius
        } else {
            F4::splat(RIBBON_RADIUS)
        }
    }

    /// Pushes each ribbon's points (as they fell) out of the balloons near
    /// it, at this substep's poses; keeps the pushes back and the touched
    /// points' normals.
    pub(super) fn push_out_of_balloons(&mut self, near: &NearInput) {
        self.touched = false;
        let (mut lo, mut hi) = (self.points[1], self.points[1]);
        // Points past `active` rest: nothing pushes them.
        for p in &self.points[2..self.active] {
            lo = V4::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z));
            hi = V4::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z));
        }
        let mut most = 0;
        for l in 0..self.live {
            self.find_near(l, (lo.lane(l), hi.lane(l)), near);
            self.lanes[l].reactions.clear();
            most = most.max(self.lanes[l].near.len());
        }
        if most == 0 {
            return;
        }
        self.near_slots.clear();
        for k in 0..most {
            let mut slot = NearSlot::default();
            for (l, lane) in self.lanes[..self.live].iter().enumerate() {
                if let Some(b) = lane.near.get(k) {
                    slot.center.set_lane(l, b.bound.center);
                    set(&mut slot.radius, l, b.bound.radius);
                    slot.capsules.set_lane(l, &b.capsule);
                    slot.lanes |= 1 << l;
                }
            }
            self.near_slots.push(slot);
        }
        for i in 1..self.active {
            let movable = self.inv_mass[i].simd_gt(F4::ZERO).to_bitmask();
            let radius = self.radius(i);
            for k in 0..most {
                let slot = &self.near_slots[k];
                let away = self.points[i] - slot.center;
                let reach = slot.radius + radius;
                // Not `<`: a NaN point is taken as within, as it would be
                // one ribbon at a time.
                let outside = away.dot(away).simd_ge(reach * reach).to_bitmask();
                let mut within = !outside & slot.lanes & movable;
                if within != 0 {
                    // Most points within the bound are clear of the leaves.
                    within &= slot.capsules.may_touch(self.points[i], radius);
                }
                while within != 0 {
                    let l = within.trailing_zeros() as usize;
                    within &= within - 1;
                    self.push_point_out(l, i, k, near);
                }
            }
        }
    }

    /// Pushes lane `l`'s point `i` out of its `k`th near balloon, whose bound
    /// it is within.
    fn push_point_out(&mut self, l: usize, i: usize, k: usize, near: &NearInput) {
        let input = near.input;
        let radius = self.radius(i).as_array()[l];
        let (start, mut point) = (self.start[i].lane(l), self.points[i].lane(l));
        let lane = &mut self.lanes[l];
        let b = &lane.near[k];
        let tree = &input.shapes[b.tree as usize].tree;
        let mu = BALLOON_FRICTION;
        let moved = push_out_of_balloon(&mut point, start, radius, mu, b, tree);
        self.points[i].set_lane(l, point);
        let Some(moved) = moved else { return };
        // The point's momentum change, the other way, where it touched.
        let mass = 1.0 / self.inv_mass[i].as_array()[l];
        lane.reactions
            .push((b.state, -mass * moved, point - b.center));
        if !self.touched {
            self.touched = true;
            self.touch_normal.fill(V4::ZERO);
            self.touch_velocity.fill(V4::ZERO);
        }
        self.touch_normal[i].set_lane(l, moved.normalize_or_zero());
        self.touch_velocity[i].set_lane(l, b.moved / input.h);
    }

    /// Lane `l`'s near balloons: those of its candidates whose roots reach
    /// its points' box `(lo, hi)` (the knot's left out), at this substep's
    /// poses.
    fn find_near(&mut self, l: usize, (lo, hi): (Vec3, Vec3), near: &NearInput) {
        let lane = &mut self.lanes[l];
        lane.near.clear();
        let bodies = &near.input.bodies[lane.bodies.start as usize..lane.bodies.end as usize];
        if bodies.is_empty() {
            return;
        }
        let reach = RIBBON_RADIUS.max(self.end_radius.as_array()[l]);
        for &b in bodies {
            let placed = &near.bodies.placed[b as usize];
            let Sphere { center, radius } = placed.bound;
            let closest = center.clamp(lo, hi);
            if closest.distance_squared(center) > (radius + reach).powi(2) {
                continue;
            }
            lane.near.push(*placed);
        }
    }

    /// Pushes each ribbon's movable points out of the room's triangles near
    /// it, those that may touch it (`near_room`), four lanes at once
    /// (`lane_room`); `first`: the step's first push, its friction from
    /// nothing yet.
    pub(super) fn push_out_of_room(&mut self, triangles: &[NearTriangle], first: bool) {
        if first {
            self.line_up_room(triangles);
            if self.room_lanes != 0 {
                self.grip_left.fill(V4::ZERO);
                self.grip_anchor.copy_from_slice(&self.start);
            }
        }
        if self.room_lanes == 0 {
            return;
        }
        // Each lane's triangles, sliced once for all its points.
        let near_of: [&[NearTriangle]; LANES] = std::array::from_fn(|l| match self.lanes.get(l) {
            Some(lane) if l < self.live => {
                &triangles[lane.triangles.start as usize..lane.triangles.end as usize]
            }
            _ => &[],
        });
        for i in 1..self.active {
            let lanes = self.near_room(i);
            if lanes != 0 {
                self.push_point_out_of_room(i, lanes, &near_of);
            }
        }
    }
}
