//! The force probe: the forces on chosen bodies over the last step, as the
//! step integrated them (`ForceBreakdown`), for views that draw forces and
//! for the CLI's probe. Off (the default), the step does nothing for it.
//!
//! Weight, buoyancy and the scene's forces are the step's `BodyForces`; the
//! drag is what the implicit update took off each substep
//! (`solver::probe`), against the velocity relative to the moving air, whose
//! velocity at the centre of mass (as the step sampled it) comes with it; the contacts are their constraints' impulses over the
//! step (`ContactInfo`) and the room's continuous hits; the ribbon's is its
//! mean pull on the knot; the grab spring's is its impulse. Each is a mean
//! over the step: an impulse over `dt`. Joints' corrections (balloons tied
//! to one another) are not in it.

use glam::Vec3;

use super::World;
use crate::body::BodyId;
use crate::forces::buoyancy::buoyancy_force;
use crate::forces::drag::{drag_factor, drag_force, terminal_velocity};
use crate::forces::gravity::gravity_force;

/// The forces on one body over the last step, world frame, N: the values
/// the step integrated (drag as the substeps applied it, averaged over the
/// step; contacts as the solver's impulses over the step / dt).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ForceBreakdown {
    /// m·g, at the centre of mass.
    pub weight: Vec3,
    /// ρ_air·V·g upward, at the centre of buoyancy.
    pub buoyancy: Vec3,
    pub drag: Vec3,
    /// Every contact summed (room and balloons), normal + friction.
    pub contact: Vec3,
    /// The ribbon's pull at the knot; zero without a ribbon.
    pub ribbon: Vec3,
    /// The user's grab and forces, the scene's force fields.
    pub other: Vec3,
    pub center_of_mass: Vec3,
    pub center_of_buoyancy: Vec3,
    pub knot: Option<Vec3>,
    /// The air's velocity at the centre of mass over the step, m/s (zero
    /// in still air): the drag acts on the velocity relative to it.
    pub air: Vec3,
}

impl ForceBreakdown {
    /// All the forces summed, N (`air` is a velocity, not among them).
    pub fn total(&self) -> Vec3 {
        self.weight + self.buoyancy + self.drag + self.contact + self.ribbon + self.other
    }
}

/// Which bodies the step records the forces of.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ForceProbe {
    #[default]
    Off,
    One(BodyId),
    All,
}

/// The probe's setting and buffers; never part of the state.
#[derive(Clone, Debug, Default)]
pub(super) struct ProbeStage {
    pub(super) probe: ForceProbe,
    pub substeps: crate::solver::probe::SubstepProbe,
    /// Per probed body: weight, buoyancy and the other forces, constant over
    /// the step, and the air's velocity at it.
    pub(super) constant: Vec<[Vec3; 4]>,
    /// Per probed body: its velocity before the continuous sweep, m/s.
    pub(super) before_sweep: Vec<Vec3>,
    /// The last step's, in the order of the dense indices it was taken at.
    pub(super) records: Vec<(BodyId, ForceBreakdown)>,
}

impl World {
    /// What the next steps record (`probed_forces`); `Off` costs nothing.
    /// Not kept by snapshots.
    pub fn set_force_probe(&mut self, probe: ForceProbe) {
        let stage = &mut self.stages.probe;
        stage.probe = probe;
        stage.records.clear();
    }

    pub fn force_probe(&self) -> ForceProbe {
        self.stages.probe.probe
    }

    /// The last step's forces on `id`, if it is probed. A body asleep is at
    /// rest: its contacts hold what its weight, buoyancy and ribbon do not.
    pub fn probed_forces(&self, id: BodyId) -> Option<ForceBreakdown> {
        let stage = &self.stages.probe;
        match stage.probe {
            ForceProbe::Off => return None,
            ForceProbe::One(probed) if probed != id => return None,
            _ => {}
        }
        let i = self.handles.dense(id)?;
        if !self.bodies.awake[i] {
            return Some(self.at_rest(i));
        }
        let records = &stage.records;
        // Looked up by its dense index, unless a removal has moved it since.
        let near = records.binary_search_by_key(&(i as u32), |(b, _)| {
            self.handles.dense(*b).map_or(u32::MAX, |d| d as u32)
        });
        match near {
            Ok(k) if records[k].0 == id => Some(records[k].1),
            _ => records.iter().find(|(b, _)| *b == id).map(|(_, f)| *f),
        }
    }

    /// √(2·|buoyancy − weight| / (ρ·C_D·A)) for body `id` now, m/s: the
    /// speed at which drag balances its net lift (or net weight).
    pub fn terminal_speed(&self, id: BodyId) -> Option<f32> {
        let i = self.handles.dense(id)?;
        let shape = &self.shapes[self.bodies.shape[i] as usize];
        let size = self.bodies.size[i];
        let v = terminal_velocity(
            self.def.gravity.length(),
            self.air.air_density(),
            shape.volume(size.scale),
            size.mass,
            self.def.drag_coefficient,
            shape.def.reference_area * size.scale * size.scale,
        );
        Some(v.abs())
    }

    /// Body `id`'s mass now (gas, envelope and knot), kg.
    pub fn body_mass(&self, id: BodyId) -> Option<f32> {
        self.handles.dense(id).map(|i| self.bodies.size[i].mass)
    }

    /// Body `id`'s volume now, m³.
    pub fn body_volume(&self, id: BodyId) -> Option<f32> {
        let i = self.handles.dense(id)?;
        let shape = &self.shapes[self.bodies.shape[i] as usize];
        Some(shape.volume(self.bodies.size[i].scale))
    }

    /// The centre of buoyancy of the body at dense index `i`, world frame.
    pub(super) fn center_of_buoyancy(&self, i: usize) -> Vec3 {
        let shape = &self.shapes[self.bodies.shape[i] as usize];
        let arm = shape.buoyancy_arm * self.bodies.size[i].scale;
        self.bodies.center[i] + self.bodies.rotation[i] * arm
    }

    /// The ribbon's pull on the body at dense index `i`, and its knot.
    pub(super) fn ribbon_on(&self, i: usize) -> (Vec3, Option<Vec3>) {
        let ribbon = self.ribbons.on(self.bodies.id[i]);
        match ribbon.and_then(|r| self.ribbons.get(r)) {
            Some(r) => (r.pull, r.points.first().copied()),
            None => (Vec3::ZERO, None),
        }
    }

    /// A sleeper's forces: at rest, the contacts balance the rest (the
    /// drag of any air too slow to wake it included).
    fn at_rest(&self, i: usize) -> ForceBreakdown {
        let g = self.def.gravity;
        let scale = self.bodies.size[i].scale;
        let weight = gravity_force(self.bodies.size[i].mass, g);
        let shape = &self.shapes[self.bodies.shape[i] as usize];
        let volume = shape.volume(scale);
        let density = self.air.air_density();
        let buoyancy = buoyancy_force(density, volume, g);
        let (ribbon, knot) = self.ribbon_on(i);
        let air = self.air_velocity_at(self.bodies.center[i]);
        let area = shape.def.reference_area * scale * scale;
        let k = drag_factor(density, self.def.drag_coefficient, area);
        let (drag, contact) = if air == Vec3::ZERO {
            (Vec3::ZERO, -(weight + buoyancy + ribbon))
        } else {
            let drag = drag_force(k, -air);
            (drag, -(weight + buoyancy + ribbon + drag))
        };
        ForceBreakdown {
            weight,
            buoyancy,
            drag,
            contact,
            ribbon,
            air,
            center_of_mass: self.bodies.center[i],
            center_of_buoyancy: self.center_of_buoyancy(i),
            knot,
            ..ForceBreakdown::default()
        }
    }
}
