//! Each body's forces for one step, assembled once before the substeps:
//! gravity and buoyancy, the user's force and torque, the scene's force
//! fields (`field`), and the drag factor the substeps apply implicitly,
//! with the air's velocity at the body (`crate::air`) that the drag acts
//! against.

use glam::Vec3;

use super::buoyancy::{buoyancy_force, buoyancy_torque};
use super::drag::{drag_factor, drag_force};
use super::field::{FieldSample, ForceFields};
use super::gravity::gravity_force;
use crate::body::{BodySize, ShapeData};

/// Per-body forces for one step. 64 bytes.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct BodyForces {
    /// Gravity + buoyancy + the user's and the fields' forces, N (all constant
    /// over the step).
    pub force: Vec3,
    /// Buoyancy alone, N: it also turns the body, about the centre of buoyancy.
    pub buoyancy: Vec3,
    /// Centre of buoyancy from the centre of mass, body frame, m.
    pub buoyancy_arm: Vec3,
    /// The user's torque, N·m.
    pub torque: Vec3,
    /// ½·ρ·C_D·A, kg/m.
    pub drag_factor: f32,
    /// The air's velocity at the centre of mass, sampled once a step, m/s:
    /// the drag is −k·|v − u|·(v − u). Zero in still air.
    pub air: Vec3,
}

/// The air and gravity the forces come from.
pub(crate) struct ForceInput<'a> {
    /// kg/m³.
    pub air_density: f32,
    /// m/s².
    pub gravity: Vec3,
    pub drag_coefficient: f32,
    pub fields: &'a ForceFields,
    /// Simulated seconds at the step's start.
    pub time: f64,
}

/// What one body brings to its forces.
pub(crate) struct BodyLoad {
    pub center: Vec3,
    pub velocity: Vec3,
    pub user_data: u32,
    /// Held by the user for this step, N and N·m.
    pub force: Vec3,
    pub torque: Vec3,
    /// The air's velocity at `center`, m/s.
    pub air: Vec3,
}

impl BodyForces {
    /// For a body of `size`: its volume, mass, arm and area follow it.
    pub fn assemble(
        input: &ForceInput,
        shape: &ShapeData,
        size: BodySize,
        load: &BodyLoad,
    ) -> BodyForces {
        let (scale, mass, volume) = (size.scale, size.mass, shape.volume(size.scale));
        let buoyancy = buoyancy_force(input.air_density, volume, input.gravity);
        let mut force = gravity_force(mass, input.gravity) + buoyancy + load.force;
        let drag_factor = drag_factor(
            input.air_density,
            input.drag_coefficient,
            shape.def.reference_area * (scale * scale),
        );
        if !input.fields.is_empty() {
            force += input.fields.force(&FieldSample {
                center: load.center,
                velocity: load.velocity,
                user_data: load.user_data,
                mass,
                volume,
                drag_factor,
                time: input.time,
            });
        }
        BodyForces {
            force,
            buoyancy,
            buoyancy_arm: shape.buoyancy_arm * scale,
            torque: load.torque,
            drag_factor,
            air: load.air,
        }
    }

    /// The torque on a body turned to `q` and moving at `v`: the user's, the
    /// buoyancy's about the centre of mass, and the drag's, which acts at the
    /// centre of buoyancy (the centre of the displaced air) against the
    /// velocity relative to the air, N·m. (v − 0 is v to the bit: still air
    /// turns a body as it did before air moved.)
    #[inline]
    pub fn torque_at(&self, q: glam::Quat, v: Vec3) -> Vec3 {
        let arm = q * self.buoyancy_arm;
        let drag = drag_force(self.drag_factor, v - self.air);
        self.torque + buoyancy_torque(arm, self.buoyancy) + arm.cross(drag)
    }
}
