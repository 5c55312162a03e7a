//! Adding, removing, grabbing and reading ribbons (`crate::ribbon`), and the
//! ribbons' part of the step: taken out for the solve, handed back after.

use glam::Vec3;
use up_geom::norm::Norm;
use up_geom::Aabb;

use super::{PhysicsError, World};
use crate::body::BodyId;
use crate::ribbon::collide::NearTriangle;
use crate::ribbon::solve::ActiveRibbon;
use crate::ribbon::{
    Ribbon, RibbonDef, RibbonId, GRAB_MAX_SPEED, MAX_SEGMENTS, MIN_SEGMENTS, RIBBON_RADIUS,
    WEIGHT_RADIUS,
};

/// A ribbon point held by the pointer.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct RibbonGrab {
    pub ribbon: RibbonId,
    pub point: u32,
    pub target: Vec3,
}

impl World {
    /// Ties a ribbon to a balloon's knot; wakes the balloon. The ribbon
    /// starts hanging straight down from the knot, along the floor where it
    /// reaches it. Refused, naming why: a body that does not exist or already
    /// has a ribbon, a length or mass per metre not finite and > 0, segments
    /// outside [2, 128], a weight not finite and ≥ 0.
    pub fn add_ribbon(&mut self, def: &RibbonDef) -> Result<RibbonId, PhysicsError> {
        let bad = |why: String| Err(PhysicsError::BadRibbon(why));
        if !(def.length.is_finite() && def.length > 0.0) {
            return bad(format!("length {} m: expected finite and > 0", def.length));
        }
        if !(def.mass_per_length.is_finite() && def.mass_per_length > 0.0) {
            return bad(format!(
                "mass per metre {} kg/m: expected finite and > 0",
                def.mass_per_length
            ));
        }
        if !(MIN_SEGMENTS..=MAX_SEGMENTS).contains(&def.segments) {
            return bad(format!(
                "{} segments: expected {MIN_SEGMENTS} to {MAX_SEGMENTS}",
                def.segments
            ));
        }
        if !(def.end_mass.is_finite() && def.end_mass >= 0.0) {
            return bad(format!(
                "weight {} kg: expected finite and ≥ 0",
                def.end_mass
            ));
        }
        if !def.knot.is_finite() {
            return Err(PhysicsError::NonFinite { what: "knot" });
        }
        let i = self.dense(def.body)?;
        if self.ribbons.on(def.body).is_some() {
            return bad(format!("body {:?} already has a ribbon", def.body));
        }
        let center_of_mass = self.shapes[self.bodies.shape[i] as usize]
            .def
            .center_of_mass;
        // At the shape's size: the knot moves in as its balloon shrinks.
        let arm = def.knot - center_of_mass;
        let knot =
            self.bodies.center[i] + self.bodies.rotation[i] * (arm * self.bodies.size[i].scale);
        let segments = def.segments as usize;
        let segment_length = def.length / segments as f32;
        let point_mass = def.mass_per_length * segment_length;
        let mut ribbon = Ribbon {
            body: def.body,
            arm,
            segment_length,
            point_mass,
            end_mass: point_mass + def.end_mass,
            weight: def.end_mass,
            points: Vec::new(),
            velocities: vec![Vec3::ZERO; segments + 1],
            pull: Vec3::ZERO,
        };
        ribbon.points = self.hang(knot, &ribbon, segments);
        self.wake(def.body)?;
        Ok(self.ribbons.add(ribbon))
    }

    /// Points straight down from `knot` (along gravity), turning along the
    /// floor toward the room's middle where they reach it, and round its
    /// walls: a ribbon laid out inside the room.
    fn hang(&self, knot: Vec3, ribbon: &Ribbon, n: usize) -> Vec<Vec3> {
        let down = self.def.gravity.try_normalize().unwrap_or(Vec3::NEG_Y);
        let bounds = self.def.room.as_ref().map(|room| {
            let end_radius = if ribbon.weight > 0.0 {
                WEIGHT_RADIUS
            } else {
                RIBBON_RADIUS
            };
            let margin = end_radius + 1e-3;
            let b = room.aabb();
            (b.min + margin, b.max - margin)
        });
        let mut points = vec![knot];
        let mut direction = down;
        for _ in 0..n {
            let last = *points.last().unwrap_or(&knot);
            let mut next = last + direction * ribbon.segment_length;
            if let Some((lo, hi)) = bounds {
                if next.clamp(lo, hi) != next {
                    // Along the floor toward the room's middle, or round a wall.
                    let middle = 0.5 * (lo + hi);
                    let toward = (middle - last) - (middle - last).dot(down) * down;
                    direction = if direction == down {
                        toward.try_normalize().unwrap_or(Vec3::X)
                    } else {
                        down.cross(direction)
                    };
                    next = (last + direction * ribbon.segment_length).clamp(lo, hi);
                }
            }
            points.push(next);
        }
        points
    }

    /// Unties and removes a ribbon; wakes its balloon.
    pub fn remove_ribbon(&mut self, id: RibbonId) -> Result<(), PhysicsError> {
        let ribbon = self
            .ribbons
            .remove(id)
            .ok_or(PhysicsError::StaleRibbon(id))?;
        if self.ribbon_grab.is_some_and(|g| g.ribbon == id) {
            self.ribbon_grab = None;
        }
        self.wake(ribbon.body)
    }

    /// Removes the ribbon of a body being removed.
    pub(super) fn remove_ribbon_on(&mut self, body: BodyId) {
        if let Some(id) = self.ribbons.on(body) {
            let _ = self.remove_ribbon(id);
        }
    }

    pub fn ribbon_count(&self) -> usize {
        self.ribbons.len()
    }

    /// The ribbons, in a stable order (the solver's).
    pub fn ribbon_ids(&self) -> Vec<RibbonId> {
        self.ribbons.iter().map(|(id, _)| id).collect()
    }

    /// The ribbon tied to `body`.
    pub fn ribbon_of(&self, body: BodyId) -> Option<RibbonId> {
        self.ribbons.on(body)
    }

    /// The balloon a ribbon is tied to.
    pub fn ribbon_body(&self, id: RibbonId) -> Option<BodyId> {
        self.ribbons.get(id).map(|r| r.body)
    }

    /// A ribbon's points, world frame, m: the knot first, the free end last.
    pub fn ribbon_points(&self, id: RibbonId) -> Option<&[Vec3]> {
        self.ribbons.get(id).map(|r| &r.points[..])
    }

    /// Its points' velocities, m/s, in the same order.
    pub fn ribbon_velocities(&self, id: RibbonId) -> Option<&[Vec3]> {
        self.ribbons.get(id).map(|r| &r.velocities[..])
    }

    /// Points of all ribbons together (each ribbon has its segments + 1).
    pub fn ribbon_point_count(&self) -> usize {
        self.ribbons.iter().map(|(_, r)| r.points.len()).sum()
    }

    /// Writes every ribbon's points, ribbon after ribbon in `ribbon_ids`
    /// order, as x, y, z floats into `out` (3 × `ribbon_point_count`).
    pub fn write_ribbon_points(&self, out: &mut [f32]) {
        let points = self.ribbons.iter().flat_map(|(_, r)| r.points.iter());
        for (chunk, p) in out.chunks_exact_mut(3).zip(points) {
            chunk.copy_from_slice(&p.to_array());
        }
    }

    /// What the ribbon pulls its knot with, N, world frame: the mean over the
    /// last step its balloon was awake.
    pub fn ribbon_pull(&self, id: RibbonId) -> Option<Vec3> {
        self.ribbons.get(id).map(|r| r.pull)
    }

    /// Its length along its points over its length, less one: now.
    pub fn ribbon_stretch(&self, id: RibbonId) -> Option<f32> {
        self.ribbons.get(id).map(Ribbon::stretch)
    }

    /// The largest stretch any ribbon ended a step with since the world was made.
    pub fn ribbon_max_stretch(&self) -> f32 {
        self.ribbons.max_stretch
    }

    /// Its length, m, and mass with its weight, kg.
    pub fn ribbon_length_and_mass(&self, id: RibbonId) -> Option<(f32, f32)> {
        self.ribbons.get(id).map(|r| (r.length(), r.total_mass()))
    }

    /// Starts carrying point `point` of a ribbon (the free end is its
    /// segment count) toward `set_grab_target`'s target, at up to
    /// `GRAB_MAX_SPEED`; its balloon follows on the ribbon. Replaces any grab.
    pub fn grab_ribbon(
        &mut self,
        id: RibbonId,
        point: usize,
        target: Vec3,
    ) -> Result<(), PhysicsError> {
        if !target.is_finite() {
            return Err(PhysicsError::NonFinite {
                what: "grab target",
            });
        }
        let ribbon = self.ribbons.get(id).ok_or(PhysicsError::StaleRibbon(id))?;
        if point == 0 || point > ribbon.segments() {
            return Err(PhysicsError::BadRibbon(format!(
                "point {point}: expected 1 to {} (0 is the knot)",
                ribbon.segments()
            )));
        }
        let body = ribbon.body;
        self.wake(body)?;
        self.grab = None;
        self.ribbon_grab = Some(RibbonGrab {
            ribbon: id,
            point: point as u32,
            target,
        });
        Ok(())
    }

    /// The ribbon and point held, if a ribbon is.
    pub fn grabbed_ribbon(&self) -> Option<(RibbonId, usize)> {
        self.ribbon_grab.map(|g| (g.ribbon, g.point as usize))
    }

    /// Wakes the balloons whose sleeping ribbons a moving balloon reaches
    /// (its bounding sphere, widened by its motion this step, meets a point),
    /// so that the ribbon is pushed aside instead of passed through. Before
    /// the broadphase, from where the last step left the bodies.
    pub(super) fn wake_touched_ribbons(&mut self) {
        let b = &self.bodies;
        let stage = &mut self.stages.ribbons;
        stage.bound_center.clear();
        stage.bound_radius.clear();
        stage.awake_bodies.clear();
        // A balloon slower than the sleep speed pushes no ribbon aside to
        // speak of: waking a ribbon for it would keep a pile awake for ever,
        // each group woken by its neighbours as it falls asleep.
        let (slow, turning) = (self.def.sleep_linear_speed, self.def.sleep_angular_speed);
        let restless = |i: usize| {
            b.awake[i]
                && (b.linear_velocity[i].norm() >= slow || b.angular_velocity[i].norm() >= turning)
        };
        for i in (0..b.len()).filter(|&i| restless(i)) {
            let shape = &self.shapes[b.shape[i] as usize];
            let reach = b.linear_velocity[i].norm() * self.def.dt + self.def.speculative_distance;
            stage.bound_center.push(b.center[i]);
            stage
                .bound_radius
                .push(shape.bound_radius * b.size[i].scale + reach);
            stage.awake_bodies.push(i as u32);
        }
        let asleep = |body| self.handles.dense(body).is_some_and(|i| !b.awake[i]);
        if stage.awake_bodies.is_empty() || !self.ribbons.iter().any(|(_, r)| asleep(r.body)) {
            return;
        }
        stage.nearby.build(&stage.bound_center, &stage.bound_radius);
        let mut touched = std::mem::take(&mut stage.touched);
        let found = &mut stage.found;
        touched.clear();
        for (_, ribbon) in self.ribbons.iter() {
            let Some(i) = self.handles.dense(ribbon.body) else {
                continue;
            };
            if b.awake[i] {
                continue;
            }
            let aabb = Aabb::from_points(&ribbon.points).expanded(ribbon.radius(ribbon.segments()));
            found.clear();
            stage
                .nearby
                .query(&aabb, &stage.bound_center, &stage.bound_radius, found);
            let reached = found.iter().any(|&k| {
                let (c, r) = (
                    stage.bound_center[k as usize],
                    stage.bound_radius[k as usize],
                );
                let other = stage.awake_bodies[k as usize] as usize;
                other != i
                    && ribbon.points.iter().enumerate().any(|(p, point)| {
                        point.distance_squared(c) < (r + ribbon.radius(p)).powi(2)
                    })
            });
            if reached {
                touched.push(ribbon.body);
            }
        }
        for &body in &touched {
            // A ribbon's body exists while the ribbon does.
            let _ = self.wake(body);
        }
        self.stages.ribbons.touched = touched;
    }

    /// Takes the awake ribbons' points for the solve, and finds the room's
    /// triangles and the balloons near each. Ribbons of sleepers stay still
    /// (one that a moving balloon reached was woken before the broadphase).
    pub(super) fn prepare_ribbons(&mut self) {
        let stage = &mut self.stages.ribbons;
        stage.awake = 0;
        stage.triangles.clear();
        stage.bodies.clear();
        let b = &self.bodies;
        let awake = |body| self.handles.dense(body).is_some_and(|i| b.awake[i]);
        if !self.ribbons.iter().any(|(_, r)| awake(r.body)) {
            return; // every ribbon sleeps, or there are none
        }
        let n = self.bodies.len();
        let dt = self.def.dt;
        let fall = 0.5 * self.def.gravity.norm() * dt * dt;
        let margin = self.def.speculative_distance + fall;
        stage.bound_center.clear();
        stage.bound_radius.clear();
        for i in 0..n {
            let shape = &self.shapes[b.shape[i] as usize];
            stage.bound_center.push(b.center[i]);
            let reach = if b.awake[i] {
                b.linear_velocity[i].norm() * dt
            } else {
                0.0
            };
            stage
                .bound_radius
                .push(shape.bound_radius * b.size[i].scale + reach + margin);
        }
        stage.nearby.build(&stage.bound_center, &stage.bound_radius);
        let air_density = self.air.air_density();
        let grab = self.ribbon_grab;
        let room = self.def.room.as_ref();
        let mut count = 0;
        for (slot, ribbon) in self.ribbons.slots_mut().enumerate() {
            let Some(ribbon) = ribbon else { continue };
            let Some(i) = self.handles.dense(ribbon.body) else {
                continue;
            };
            // A sleeper's ribbon keeps its points and the (sleep-slow)
            // velocities it fell asleep with, as they are, until it wakes.
            if !b.awake[i] {
                continue;
            }
            if stage.active.len() == count {
                stage.active.push(ActiveRibbon::default());
            }
            let r = &mut stage.active[count];
            count += 1;
            r.slot = slot as u32;
            r.state = i as u32;
            r.origin = b.center[i];
            r.arm0 = b.rotation[i] * (ribbon.arm * b.size[i].scale);
            r.grab = grab
                .filter(|g| g.ribbon.index as usize == slot)
                .map(|g| (g.point as usize, g.target));
            if let Some((k, target)) = r.grab {
                let distance = target.distance(ribbon.points[k]);
                r.grab_speed = (distance / dt).min(GRAB_MAX_SPEED);
            }
            let speed = ribbon
                .velocities
                .iter()
                .fold(0.0f32, |m, v| m.max(v.norm()));
            let reach = speed * dt + margin + ribbon.radius(ribbon.segments());
            let aabb = Aabb::from_points(&ribbon.points).expanded(reach);
            r.take(ribbon, air_density);
            if let Some((k, _)) = r.grab {
                r.inv_mass[k] = 0.0; // carried, not pushed
            }
            let first = stage.bodies.len() as u32;
            stage.nearby.query(
                &aabb,
                &stage.bound_center,
                &stage.bound_radius,
                &mut stage.bodies,
            );
            r.bodies = first..stage.bodies.len() as u32;
            let first = stage.triangles.len() as u32;
            if let Some(room) = room {
                room.query_aabb(&aabb, |t| {
                    if !room.is_degenerate(t) {
                        stage.triangles.push(NearTriangle {
                            corners: room.triangle(t),
                            normal: room.normal(t),
                        });
                    }
                });
            }
            r.triangles = first..stage.triangles.len() as u32;
        }
        stage.awake = count;
    }

    /// Hands the points back to the ribbons, each knot where its balloon
    /// ended the step; keeps the largest stretch; marks the balloons whose
    /// ribbons still move as a whole (their points' root-mean-square speed:
    /// a free end's millimetre sway alone keeps no pile awake) — those may
    /// not sleep yet — and those whose ribbons
    /// went non-finite (quarantined with them).
    pub(super) fn finish_ribbons(&mut self) {
        let stage = &mut self.stages.ribbons;
        let n = self.bodies.len();
        stage.moving.clear();
        stage.moving.resize(n, false);
        if self.ribbons.is_empty() {
            return;
        }
        let slow = self.def.sleep_linear_speed;
        let mut max_stretch = self.ribbons.max_stretch;
        for r in &mut stage.active[..stage.awake] {
            let Some(ribbon) = self.ribbons.slot_mut(r.slot) else {
                continue;
            };
            r.give_back(ribbon);
            let i = r.state as usize;
            let arm = self.bodies.rotation[i] * (ribbon.arm * self.bodies.size[i].scale);
            ribbon.points[0] = self.bodies.center[i] + arm;
            ribbon.velocities[0] =
                self.bodies.linear_velocity[i] + self.bodies.angular_velocity[i].cross(arm);
            if !ribbon.points.iter().all(|p| p.is_finite()) {
                self.stages.faults.non_finite.push(i);
                continue;
            }
            stage.moving[i] = ribbon.rms_speed() >= slow;
            max_stretch = max_stretch.max(ribbon.stretch());
        }
        self.ribbons.max_stretch = max_stretch;
    }
}
