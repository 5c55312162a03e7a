//! What a user does to bodies: wake, push, set moving, grab and throw; and
//! to the room: its gravity.

use glam::Vec3;

use super::{PhysicsError, World};
use crate::body::BodyId;
use crate::grab::Grab;
use crate::sleep;
use crate::solver::body_state::world_inverse_inertia;

impl World {
    pub fn wake(&mut self, id: BodyId) -> Result<(), PhysicsError> {
        let i = self.dense(id)?;
        if !self.bodies.awake[i] {
            self.wake_island(self.bodies.island[i]);
        }
        self.bodies.sleep_time[i] = 0.0;
        Ok(())
    }

    pub fn set_velocity(
        &mut self,
        id: BodyId,
        linear: Vec3,
        angular: Vec3,
    ) -> Result<(), PhysicsError> {
        if !linear.is_finite() || !angular.is_finite() {
            return Err(PhysicsError::NonFinite { what: "velocity" });
        }
        self.wake(id)?;
        let i = self.dense(id)?;
        self.bodies.linear_velocity[i] = linear;
        self.bodies.angular_velocity[i] = angular;
        Ok(())
    }

    /// An instantaneous impulse (N·s) at a world point; wakes the body.
    pub fn apply_impulse_at_point(
        &mut self,
        id: BodyId,
        impulse: Vec3,
        point: Vec3,
    ) -> Result<(), PhysicsError> {
        if !impulse.is_finite() || !point.is_finite() {
            return Err(PhysicsError::NonFinite { what: "impulse" });
        }
        self.wake(id)?;
        let i = self.dense(id)?;
        let shape = &self.shapes[self.bodies.shape[i] as usize];
        let r = point - self.bodies.center[i];
        let local = shape.inv_inertia_local * self.bodies.inertia_factor[i];
        let inv_inertia = world_inverse_inertia(self.bodies.rotation[i], local);
        self.bodies.linear_velocity[i] += self.bodies.inv_mass[i] * impulse;
        self.bodies.angular_velocity[i] += inv_inertia * r.cross(impulse);
        Ok(())
    }

    /// A force (N) at a world point, held for the next step only; wakes the body.
    pub fn apply_force_at_point(
        &mut self,
        id: BodyId,
        force: Vec3,
        point: Vec3,
    ) -> Result<(), PhysicsError> {
        if !force.is_finite() || !point.is_finite() {
            return Err(PhysicsError::NonFinite { what: "force" });
        }
        self.wake(id)?;
        let i = self.dense(id)?;
        self.bodies.force[i] += force;
        self.bodies.torque[i] += (point - self.bodies.center[i]).cross(force);
        Ok(())
    }

    /// Starts dragging the body by a world point (the mouse); see `set_grab_target`.
    pub fn grab(&mut self, id: BodyId, point: Vec3) -> Result<(), PhysicsError> {
        if !point.is_finite() {
            return Err(PhysicsError::NonFinite { what: "grab point" });
        }
        self.wake(id)?;
        let i = self.dense(id)?;
        let anchor = self.bodies.rotation[i].inverse() * (point - self.bodies.center[i]);
        self.ribbon_grab = None;
        self.grab = Some(Grab {
            body: id,
            anchor,
            target: point,
        });
        Ok(())
    }

    /// Moves the point the grabbed body is pulled toward, m.
    pub fn set_grab_target(&mut self, target: Vec3) -> Result<(), PhysicsError> {
        if !target.is_finite() {
            return Err(PhysicsError::NonFinite {
                what: "grab target",
            });
        }
        if let Some(g) = &mut self.grab {
            g.target = target;
        }
        if let Some(g) = &mut self.ribbon_grab {
            g.target = target;
        }
        Ok(())
    }

    /// Lets go; the body keeps its velocity (a throw). Returns the body that
    /// was held, or whose ribbon was.
    pub fn release_grab(&mut self) -> Option<BodyId> {
        let ribbon = self.ribbon_grab.take();
        let ribbon_body = ribbon.and_then(|g| self.ribbon_body(g.ribbon));
        self.grab.take().map(|g| g.body).or(ribbon_body)
    }

    pub fn grabbed(&self) -> Option<BodyId> {
        self.grab.map(|g| g.body)
    }

    /// Sets gravity, m/s² (a room on the Moon: (0, −1.62, 0)), and wakes
    /// every body: each step reads it afresh, so the next one feels it.
    pub fn set_gravity(&mut self, gravity: Vec3) -> Result<(), PhysicsError> {
        if !gravity.is_finite() {
            return Err(PhysicsError::NonFinite { what: "gravity" });
        }
        self.def.gravity = gravity;
        self.wake_all();
        Ok(())
    }

    /// Wakes every sleeping body.
    pub(super) fn wake_all(&mut self) {
        let b = &self.bodies;
        let mut islands: Vec<u32> = (0..b.len())
            .filter(|&i| !b.awake[i])
            .map(|i| b.island[i])
            .collect();
        islands.sort_unstable();
        islands.dedup();
        for island in islands {
            self.wake_island(island);
        }
    }

    /// Wakes every body of a sleeping island.
    pub(super) fn wake_island(&mut self, island: u32) {
        sleep::wake_island(&mut self.bodies, &self.handles, &mut self.sleeping, island);
    }

    /// Wakes the sleeping bodies whose bounding spheres touch body `i`'s.
    pub(super) fn wake_neighbours_of(&mut self, i: usize) {
        sleep::wake_neighbours_of(
            i,
            self.def.speculative_distance,
            &self.shapes,
            &mut self.bodies,
            &self.handles,
            &mut self.sleeping,
            &mut self.stages.sleep,
        );
    }
}
