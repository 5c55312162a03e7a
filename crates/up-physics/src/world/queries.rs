//! Reading the world's bodies: poses, velocities, masses, what the last step
//! measured.

use glam::Vec3;
use up_geom::{Pose, TriMesh};

use super::{StepStats, World};
use crate::body::{BodyId, ShapeId};
use crate::counters::Counters;

impl World {
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Handles in dense order (the order of `write_poses`).
    pub fn body_ids(&self) -> &[BodyId] {
        &self.bodies.id
    }

    pub fn contains(&self, id: BodyId) -> bool {
        self.handles.dense(id).is_some()
    }

    /// Pose of the body frame (the mesh frame).
    pub fn pose(&self, id: BodyId) -> Option<Pose> {
        self.handles.dense(id).map(|i| self.pose_at(i))
    }

    fn pose_at(&self, i: usize) -> Pose {
        let q = self.bodies.rotation[i];
        let com = self.shapes[self.bodies.shape[i] as usize]
            .def
            .center_of_mass
            * self.bodies.size[i].scale;
        Pose::new(self.bodies.center[i] - q * com, q)
    }

    /// All poses, dense order.
    pub fn poses(&self) -> impl Iterator<Item = (BodyId, Pose)> + '_ {
        (0..self.bodies.len()).map(|i| (self.bodies.id[i], self.pose_at(i)))
    }

    /// Writes x, y, z, qx, qy, qz, qw of each body frame, dense order, into
    /// `out` (7 floats per body; extra bodies or room are left untouched).
    pub fn write_poses(&self, out: &mut [f32]) {
        for (i, chunk) in out.chunks_exact_mut(7).take(self.bodies.len()).enumerate() {
            let p = self.pose_at(i);
            chunk.copy_from_slice(&[
                p.position.x,
                p.position.y,
                p.position.z,
                p.rotation.x,
                p.rotation.y,
                p.rotation.z,
                p.rotation.w,
            ]);
        }
    }

    pub fn center_of_mass(&self, id: BodyId) -> Option<Vec3> {
        self.handles.dense(id).map(|i| self.bodies.center[i])
    }

    pub fn linear_velocity(&self, id: BodyId) -> Option<Vec3> {
        self.handles
            .dense(id)
            .map(|i| self.bodies.linear_velocity[i])
    }

    pub fn angular_velocity(&self, id: BodyId) -> Option<Vec3> {
        self.handles
            .dense(id)
            .map(|i| self.bodies.angular_velocity[i])
    }

    pub fn user_data(&self, id: BodyId) -> Option<u32> {
        self.handles.dense(id).map(|i| self.bodies.user_data[i])
    }

    pub fn shape_of(&self, id: BodyId) -> Option<ShapeId> {
        self.handles
            .dense(id)
            .map(|i| ShapeId(self.bodies.shape[i]))
    }

    pub fn is_awake(&self, id: BodyId) -> Option<bool> {
        self.handles.dense(id).map(|i| self.bodies.awake[i])
    }

    /// Mass used for momentum: body mass plus added mass, kg.
    pub fn effective_mass(&self, id: BodyId) -> Option<f32> {
        let i = self.handles.dense(id)?;
        Some(1.0 / self.bodies.inv_mass[i])
    }

    /// World-frame inertia about the centre of mass, kg·m².
    pub fn world_inertia(&self, id: BodyId) -> Option<glam::Mat3> {
        let i = self.handles.dense(id)?;
        let r = glam::Mat3::from_quat(self.bodies.rotation[i]);
        let factor = self.bodies.inertia_factor[i];
        let local = self.shapes[self.bodies.shape[i] as usize].def.inertia * (1.0 / factor);
        Some(r * local * r.transpose())
    }

    /// Simulated seconds since the world was made.
    pub fn time(&self) -> f64 {
        self.time
    }

    pub fn step_count(&self) -> u64 {
        self.step_count
    }

    pub fn stats(&self) -> &StepStats {
        &self.stats
    }

    pub fn counters(&self) -> &Counters {
        &self.counters
    }

    pub fn room(&self) -> Option<&TriMesh> {
        self.def.room.as_ref()
    }

    /// ½·m_eff·v² + ½·ωᵀ·I·ω summed over all bodies, J (added mass included: the air moves too).
    pub fn kinetic_energy(&self) -> f32 {
        (0..self.bodies.len())
            .map(|i| {
                let shape = &self.shapes[self.bodies.shape[i] as usize];
                let v = self.bodies.linear_velocity[i];
                let w = self.bodies.angular_velocity[i];
                let r = glam::Mat3::from_quat(self.bodies.rotation[i]);
                let local = shape.def.inertia * (1.0 / self.bodies.inertia_factor[i]);
                let inertia = r * local * r.transpose();
                0.5 * v.length_squared() / self.bodies.inv_mass[i] + 0.5 * w.dot(inertia * w)
            })
            .sum()
    }
}
