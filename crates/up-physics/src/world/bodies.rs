//! Adding balloon shapes and bodies, removing bodies, and taking out those
//! whose state stopped being finite.

use super::{PhysicsError, World, MAX_BODIES};
use crate::body::{BalloonShape, BodyDef, BodyId, ShapeData, ShapeId};
use crate::forces::drag::added_mass;
use crate::quarantine::{self, QuarantinedBody, MAX_QUARANTINE_REPORTS};

impl World {
    /// Registers a kind of balloon; its derived constants use this world's air.
    pub fn add_shape(&mut self, shape: BalloonShape) -> Result<ShapeId, PhysicsError> {
        let bad = |why: &str| Err(PhysicsError::BadShape(why.to_string()));
        if !(shape.mass.is_finite() && shape.mass > 0.0) {
            return bad("mass must be finite and > 0 kg");
        }
        if !(shape.volume.is_finite() && shape.volume >= 0.0) {
            return bad("volume must be finite and ≥ 0 m³");
        }
        if !(shape.reference_area.is_finite() && shape.reference_area >= 0.0) {
            return bad("reference_area must be finite and ≥ 0 m²");
        }
        if !(shape.center_of_mass.is_finite() && shape.center_of_buoyancy.is_finite()) {
            return bad("centre of mass and centre of buoyancy must be finite");
        }
        let inertia = shape.inertia;
        if !inertia.is_finite() || inertia.determinant() <= 0.0 {
            return bad("inertia must be finite and positive definite");
        }
        let air = self.def.atmosphere.air_density();
        let added_mass = added_mass(self.def.added_mass_coefficient, air, shape.volume);
        let tree = shape.tree.translated(-shape.center_of_mass);
        let root = *tree.root();
        let bound_radius = root.center.length() + root.radius;
        let min_leaf_radius = tree
            .leaf_spheres()
            .map(|s| s.radius)
            .fold(f32::INFINITY, f32::min);
        let data = ShapeData {
            inv_mass_translational: 1.0 / (shape.mass + added_mass),
            inv_inertia_local: inertia.inverse(),
            buoyancy_arm: shape.center_of_buoyancy - shape.center_of_mass,
            bound_radius,
            min_leaf_radius,
            added_mass,
            tree,
            def: shape,
        };
        self.shapes.push(data);
        Ok(ShapeId(self.shapes.len() as u32 - 1))
    }

    pub fn shape(&self, id: ShapeId) -> Option<&BalloonShape> {
        self.shapes.get(id.0 as usize).map(|s| &s.def)
    }

    /// Added mass of a shape in this world's air, kg.
    pub fn added_mass(&self, id: ShapeId) -> Option<f32> {
        self.shapes.get(id.0 as usize).map(|s| s.added_mass)
    }

    pub fn add_body(&mut self, def: &BodyDef) -> Result<BodyId, PhysicsError> {
        let shape = self
            .shapes
            .get(def.shape.0 as usize)
            .ok_or(PhysicsError::UnknownShape(def.shape.0))?;
        if !def.pose.position.is_finite() || !def.pose.rotation.is_finite() {
            return Err(PhysicsError::NonFinite { what: "pose" });
        }
        if def.pose.rotation.length_squared() < 1e-6 {
            return Err(PhysicsError::NonFinite {
                what: "rotation (zero quaternion)",
            });
        }
        if !def.linear_velocity.is_finite() || !def.angular_velocity.is_finite() {
            return Err(PhysicsError::NonFinite { what: "velocity" });
        }
        if self.bodies.len() >= MAX_BODIES {
            return Err(PhysicsError::Full(MAX_BODIES));
        }
        let rotation = def.pose.rotation.normalize();
        let center = def.pose.position + rotation * shape.def.center_of_mass;
        let size = shape.own_size();
        let ca = self.def.added_mass_coefficient;
        let inv_mass = shape.inv_mass(size, ca, self.air.air_density());
        let dense = self.bodies.len() as u32;
        let id = self.handles.allocate(dense);
        self.bodies.push(
            id,
            def.shape.0,
            def.user_data,
            center,
            rotation,
            def.linear_velocity,
            def.angular_velocity,
            size,
            inv_mass,
        );
        Ok(id)
    }

    pub fn remove_body(&mut self, id: BodyId) -> Result<(), PhysicsError> {
        let i = self.dense(id)?;
        // Whatever it held up, or held, must be free to move.
        self.wake_neighbours_of(i);
        if !self.bodies.awake[i] {
            self.wake_island(self.bodies.island[i]);
        }
        for partner in self.joint_partners(id) {
            self.wake(partner)?;
        }
        self.joints.remove_on(id);
        self.remove_ribbon_on(id);
        if self.grab.is_some_and(|g| g.body == id) {
            self.grab = None;
        }
        // Dense indices shift: last step's contacts no longer describe this
        // world, nor do the placed nodes of the sleepers.
        self.stages.narrow.found.clear();
        self.stages.place.placed_asleep.clear();
        self.stages.ribbons.nearby.centers.clear();
        // Its handle index may be given to a new body: forget its pairs' impulses.
        self.warm.forget(id.index);
        self.sleeping.impulses.forget(id.index);
        let last = self.bodies.len() - 1;
        self.bodies.swap_remove(i);
        self.handles.release(id);
        if i != last {
            let moved = self.bodies.id[i];
            self.handles.set_dense(moved, i as u32);
        }
        Ok(())
    }

    /// Takes out every body whose state is no longer finite or whose motion ran
    /// away, and reports it.
    pub(super) fn quarantine_non_finite(&mut self) {
        // Runaways found by the solve are already listed.
        let faults = &mut self.stages.faults;
        let mut bad = std::mem::take(&mut faults.non_finite);
        // Only the bodies the step moved (awake when it prepared them) can
        // have gone wrong in it: a sleeper is written by nothing. Every body
        // on a world's first step (made or restored).
        let among = self
            .stages
            .checked_all
            .then_some(&self.stages.solve.solver.awake[..]);
        quarantine::find_faulty(&self.bodies, among, &mut faults.task_faulty, &mut bad);
        self.stages.checked_all = true;
        for &i in &bad {
            let (id, user_data) = (self.bodies.id[i], self.bodies.user_data[i]);
            // The body is still registered: removal cannot fail.
            let _ = self.remove_body(id);
            if self.quarantined.len() == MAX_QUARANTINE_REPORTS {
                self.quarantined.remove(0);
            }
            self.quarantined.push(QuarantinedBody {
                id,
                user_data,
                step: self.step_count + 1,
            });
            self.stats.quarantined_count += 1;
        }
        self.stages.faults.non_finite = bad;
    }

    /// Bodies taken out of the world because their state stopped being finite
    /// since the last call (at most `MAX_QUARANTINE_REPORTS`), oldest first.
    pub fn take_quarantined(&mut self) -> Vec<QuarantinedBody> {
        std::mem::take(&mut self.quarantined)
    }

    pub(super) fn dense(&self, id: BodyId) -> Result<usize, PhysicsError> {
        self.handles.dense(id).ok_or(PhysicsError::StaleBody(id))
    }
}
