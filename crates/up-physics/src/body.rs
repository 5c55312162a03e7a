//! Bodies: handles, shapes and the struct-of-arrays storage of their state.

use glam::{Mat3, Quat, Vec3};
use serde::{Deserialize, Serialize};
use up_geom::{Pose, SphereTree};

use crate::forces::drag::added_mass;
use crate::gas::Gas;

/// A generational handle to a body: stale handles are detected, never reused silently.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct BodyId {
    pub index: u32,
    pub generation: u32,
}

/// Index of a shape registered with `World::add_shape`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct ShapeId(pub u32);

/// Everything the world needs to know about one kind of balloon.
/// All quantities in the body frame (the mesh frame), SI units.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BalloonShape {
    /// Collision spheres, body frame.
    pub tree: SphereTree,
    /// kg: envelope + knot + gas; ≈ 5.4 g for an 11″ latex balloon.
    pub mass: f32,
    /// Body frame, m. Lies below the centre of buoyancy (the knot is heavy).
    pub center_of_mass: Vec3,
    /// kg·m², about the centre of mass, body axes; ≈ 1e-4 for 11″.
    pub inertia: Mat3,
    /// m³ of displaced air; ≈ 0.0142 for 11″.
    pub volume: f32,
    /// Body frame, m: the centroid of the displaced volume, where buoyancy acts.
    pub center_of_buoyancy: Vec3,
    /// m²: frontal area for drag; ≈ 0.0708 for 11″ (equivalent sphere d = 0.30 m).
    pub reference_area: f32,
}

/// How to create a body.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BodyDef {
    pub shape: ShapeId,
    /// Pose of the body frame (the mesh frame, not the centre of mass).
    pub pose: Pose,
    /// m/s, of the centre of mass.
    pub linear_velocity: Vec3,
    /// rad/s, world frame.
    pub angular_velocity: Vec3,
    /// Free for the caller (the colour index, say); carried along, never read.
    pub user_data: u32,
}

impl BodyDef {
    pub fn new(shape: ShapeId, pose: Pose) -> Self {
        Self {
            shape,
            pose,
            linear_velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            user_data: 0,
        }
    }
}

/// Per-shape constants the step reads, derived once from `BalloonShape`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub(crate) struct ShapeData {
    pub def: BalloonShape,
    /// The tree re-centred on the centre of mass.
    pub tree: SphereTree,
    /// 1 / (mass + added mass), kg⁻¹.
    pub inv_mass_translational: f32,
    /// Inverse inertia about the centre of mass, body axes.
    pub inv_inertia_local: Mat3,
    /// Centre of buoyancy relative to the centre of mass, body axes.
    pub buoyancy_arm: Vec3,
    /// Root bounding radius about the centre of mass, m.
    pub bound_radius: f32,
    /// Smallest leaf radius, m: the scale for continuous collision.
    pub min_leaf_radius: f32,
    /// Added mass C_a·ρ_air·V, kg.
    pub added_mass: f32,
}

/// What a body's gas makes of its shape: its size and mass now. A body
/// without gas keeps its shape's (`ShapeData::own_size`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct BodySize {
    /// Linear size over the shape's; the tree, the centre of mass's offset
    /// and the centre of buoyancy's grow with it about the mesh origin.
    pub scale: f32,
    /// kg: envelope, knot and gas.
    pub mass: f32,
}

impl ShapeData {
    /// The shape's own size and mass.
    pub fn own_size(&self) -> BodySize {
        BodySize {
            scale: 1.0,
            mass: self.def.mass,
        }
    }

    /// m³ of air displaced at `scale`.
    #[inline]
    pub fn volume(&self, scale: f32) -> f32 {
        self.def.volume * (scale * scale * scale)
    }

    /// 1 / (mass + added mass) of a body of `size`, in air of `air_density`
    /// kg/m³ with added-mass coefficient `ca`; the shape's own
    /// `inv_mass_translational` at its own size in the world's air.
    pub fn inv_mass(&self, size: BodySize, ca: f32, air_density: f32) -> f32 {
        1.0 / (size.mass + added_mass(ca, air_density, self.volume(size.scale)))
    }

    /// What the inverse inertia is multiplied by at `size`: the envelope and
    /// the gas both lie at radii that grow with the scale, so the inertia
    /// goes as mass · scale²; 1 at the shape's own size.
    pub fn inverse_inertia_factor(&self, size: BodySize) -> f32 {
        self.def.mass / size.mass / (size.scale * size.scale)
    }

    /// The most a knock (`StepMotion::knock`, m) can turn the body, rad per
    /// metre: the impulse behind it, `k / inv_mass_translational` per step,
    /// applied at the bound radius, through the largest inverse inertia
    /// (bounded by its largest row sum, which the world frame's rotation
    /// does not change).
    /// For a body of another size, `inverse_inertia_factor`, `scale` and
    /// `inv_mass` are its own.
    pub fn turn_per_knock(&self, inertia_factor: f32, scale: f32, inv_mass: f32) -> f32 {
        let m = &self.inv_inertia_local;
        let row = |r: usize| m.row(r).abs().element_sum();
        // Compared, not `f32::max`: that is a call in WebAssembly.
        let largest = [row(1), row(2)]
            .into_iter()
            .fold(row(0), |a, b| if b > a { b } else { a });
        largest * inertia_factor * (self.bound_radius * scale) / inv_mass
    }
}

/// Hot and warm body state, struct of arrays, indexed densely (0..len).
/// Removal swaps the last body into the hole, so the arrays stay packed.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub(crate) struct Bodies {
    pub id: Vec<BodyId>,
    pub shape: Vec<u32>,
    pub user_data: Vec<u32>,
    /// World position of the centre of mass.
    pub center: Vec<Vec3>,
    pub rotation: Vec<Quat>,
    pub linear_velocity: Vec<Vec3>,
    pub angular_velocity: Vec<Vec3>,
    /// External force and torque held for the next step (about the centre of mass), N and N·m.
    pub force: Vec<Vec3>,
    pub torque: Vec<Vec3>,
    /// Seconds spent below the sleep thresholds.
    pub sleep_time: Vec<f32>,
    pub awake: Vec<bool>,
    /// Sleeping island this body belongs to, `u32::MAX` when awake.
    pub island: Vec<u32>,
    /// Its size and mass now (its shape's, without gas). A sleeper keeps
    /// the size it fell asleep with while its gas moves on (`world::gas`).
    pub size: Vec<BodySize>,
    /// 1 / (mass + added mass) at that size, kg⁻¹.
    pub inv_mass: Vec<f32>,
    /// `ShapeData::inverse_inertia_factor` at that size.
    pub inertia_factor: Vec<f32>,
    /// Its gas, for a balloon filled by `World::fill`.
    pub gas: Vec<Option<Gas>>,
}

impl Bodies {
    pub fn len(&self) -> usize {
        self.id.len()
    }

    #[allow(clippy::too_many_arguments)] // one argument per array
    pub fn push(
        &mut self,
        id: BodyId,
        shape: u32,
        user_data: u32,
        center: Vec3,
        rotation: Quat,
        v: Vec3,
        w: Vec3,
        size: BodySize,
        inv_mass: f32,
    ) {
        self.id.push(id);
        self.shape.push(shape);
        self.user_data.push(user_data);
        self.center.push(center);
        self.rotation.push(rotation);
        self.linear_velocity.push(v);
        self.angular_velocity.push(w);
        self.force.push(Vec3::ZERO);
        self.torque.push(Vec3::ZERO);
        self.sleep_time.push(0.0);
        self.awake.push(true);
        self.island.push(u32::MAX);
        self.size.push(size);
        self.inv_mass.push(inv_mass);
        self.inertia_factor.push(1.0);
        self.gas.push(None);
    }

    pub fn swap_remove(&mut self, i: usize) {
        self.id.swap_remove(i);
        self.shape.swap_remove(i);
        self.user_data.swap_remove(i);
        self.center.swap_remove(i);
        self.rotation.swap_remove(i);
        self.linear_velocity.swap_remove(i);
        self.angular_velocity.swap_remove(i);
        self.force.swap_remove(i);
        self.torque.swap_remove(i);
        self.sleep_time.swap_remove(i);
        self.awake.swap_remove(i);
        self.island.swap_remove(i);
        self.size.swap_remove(i);
        self.inv_mass.swap_remove(i);
        self.inertia_factor.swap_remove(i);
        self.gas.swap_remove(i);
    }
}

/// Maps handles to dense indices.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub(crate) struct HandleMap {
    /// Per handle index: current generation and dense index (`u32::MAX` when free).
    pub slots: Vec<(u32, u32)>,
    pub free: Vec<u32>,
}

impl HandleMap {
    pub fn allocate(&mut self, dense: u32) -> BodyId {
        if let Some(index) = self.free.pop() {
            let slot = &mut self.slots[index as usize];
            slot.1 = dense;
            BodyId {
                index,
                generation: slot.0,
            }
        } else {
            self.slots.push((0, dense));
            BodyId {
                index: self.slots.len() as u32 - 1,
                generation: 0,
            }
        }
    }

    pub fn dense(&self, id: BodyId) -> Option<usize> {
        let &(generation, _) = self.slots.get(id.index as usize)?;
        if generation != id.generation {
            return None;
        }
        self.dense_at(id.index)
    }

    /// The dense index of the live body holding handle index `index`, if any
    /// (for keys that carry the index without its generation).
    pub fn dense_at(&self, index: u32) -> Option<usize> {
        let &(_, dense) = self.slots.get(index as usize)?;
        (dense != u32::MAX).then_some(dense as usize)
    }

    pub fn release(&mut self, id: BodyId) {
        let slot = &mut self.slots[id.index as usize];
        slot.0 = slot.0.wrapping_add(1);
        slot.1 = u32::MAX;
        self.free.push(id.index);
    }

    pub fn set_dense(&mut self, id: BodyId, dense: u32) {
        self.slots[id.index as usize].1 = dense;
    }
}
