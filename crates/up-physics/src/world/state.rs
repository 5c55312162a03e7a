//! The world as data: its state hash, snapshots and their checks.

use super::World;
use crate::hash::Fnv1a;
use crate::snapshot::{self, SnapshotError};

impl World {
    /// FNV-1a over every body's handle, pose, velocity and sleep state, in
    /// dense order, then every ribbon's points and their velocities, then
    /// the gas of the balloons that have one and the clock, then the moving
    /// air's sources (as snapshots encode them) when there are any.
    /// A world without ribbons, gas or moving air hashes as it did before
    /// there were any.
    pub fn state_hash(&self) -> u64 {
        let mut h = Fnv1a::new();
        h.write_u32(self.bodies.len() as u32);
        h.write_bytes(&self.step_count.to_le_bytes());
        for i in 0..self.bodies.len() {
            let b = &self.bodies;
            h.write_u32(b.id[i].index);
            h.write_u32(b.id[i].generation);
            for v in [b.center[i], b.linear_velocity[i], b.angular_velocity[i]] {
                h.write_f32(v.x);
                h.write_f32(v.y);
                h.write_f32(v.z);
            }
            let q = b.rotation[i];
            for x in [q.x, q.y, q.z, q.w, b.sleep_time[i]] {
                h.write_f32(x);
            }
            h.write_u32(b.awake[i] as u32);
        }
        for (id, ribbon) in self.ribbons.iter() {
            h.write_u32(id.index);
            h.write_u32(id.generation);
            for (p, v) in ribbon.points.iter().zip(&ribbon.velocities) {
                for x in [p.x, p.y, p.z, v.x, v.y, v.z] {
                    h.write_f32(x);
                }
            }
        }
        if self.has_gas {
            h.write_bytes(&self.time.to_le_bytes());
            h.write_f32(self.air.temperature_k);
            for (i, gas) in self.bodies.gas.iter().enumerate() {
                if let Some(gas) = gas {
                    h.write_u32(i as u32);
                    h.write_bytes(&gas.helium_mol.to_le_bytes());
                    h.write_bytes(&gas.air_mol.to_le_bytes());
                    h.write_f32(self.bodies.size[i].scale);
                    h.write_f32(self.bodies.size[i].mass);
                }
            }
        }
        if !self.air_flow.is_still() {
            // Plain data into a Vec cannot fail to encode.
            h.write_bytes(&postcard::to_stdvec(&self.air_flow).unwrap_or_default());
        }
        h.finish()
    }

    /// The whole world as bytes; `World::restore` gives it back exactly.
    pub fn snapshot(&self) -> Vec<u8> {
        snapshot::encode(self)
    }

    pub fn restore(bytes: &[u8]) -> Result<World, SnapshotError> {
        let mut world: World = snapshot::decode(bytes)?;
        world
            .def
            .validate()
            .map_err(|e| SnapshotError::Invalid(e.to_string()))?;
        world.check_consistency().map_err(SnapshotError::Invalid)?;
        world
            .air_flow
            .validate()
            .map_err(|e| SnapshotError::Invalid(format!("air: {e}")))?;
        world.warm.index();
        world.sleeping.impulses.index();
        Ok(world)
    }

    fn check_consistency(&self) -> Result<(), String> {
        let n = self.bodies.len();
        let b = &self.bodies;
        let lens = [
            b.shape.len(),
            b.user_data.len(),
            b.center.len(),
            b.rotation.len(),
            b.linear_velocity.len(),
            b.angular_velocity.len(),
            b.force.len(),
            b.torque.len(),
            b.sleep_time.len(),
            b.awake.len(),
            b.island.len(),
            b.size.len(),
            b.inv_mass.len(),
            b.inertia_factor.len(),
            b.gas.len(),
        ];
        if lens.iter().any(|&l| l != n) {
            return Err("body arrays of different lengths".into());
        }
        for i in 0..n {
            if b.shape[i] as usize >= self.shapes.len() {
                return Err(format!("body {i} has unknown shape {}", b.shape[i]));
            }
            if self.handles.dense(b.id[i]) != Some(i) {
                return Err(format!("body {i}: handle table does not point back"));
            }
            let size = b.size[i];
            if !(size.scale.is_finite() && size.scale > 0.0 && size.mass > 0.0) {
                return Err(format!("body {i} has size {size:?}"));
            }
            if !b.awake[i] && self.sleeping.members.get(b.island[i] as usize).is_none() {
                return Err(format!("body {i} sleeps in a missing island"));
            }
        }
        for (id, joint) in self.joints.iter() {
            for body in joint.ends.iter().filter_map(|e| e.body()) {
                if self.handles.dense(body).is_none() {
                    return Err(format!("joint {id:?} holds a removed body"));
                }
            }
        }
        for (id, ribbon) in self.ribbons.iter() {
            if self.handles.dense(ribbon.body).is_none() {
                return Err(format!("ribbon {id:?} is tied to a removed body"));
            }
            let n = ribbon.points.len();
            if !(crate::ribbon::MIN_SEGMENTS as usize + 1
                ..=crate::ribbon::MAX_SEGMENTS as usize + 1)
                .contains(&n)
                || ribbon.velocities.len() != n
            {
                return Err(format!("ribbon {id:?} has {n} points"));
            }
        }
        for (island, members) in self.sleeping.members.iter().enumerate() {
            for &id in members {
                let Some(i) = self.handles.dense(id) else {
                    return Err(format!("island {island} holds a removed body"));
                };
                if b.awake[i] || b.island[i] as usize != island {
                    return Err(format!("island {island} disagrees with body {i}"));
                }
            }
        }
        Ok(())
    }
}
