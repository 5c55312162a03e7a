//! Force fields: the step's one extension point for what acts inside it, in
//! the manner of Jolt's `PhysicsStepListener` and Rapier's `PhysicsHooks`
//! (a fan, a vent, a draught, a hand waving). A field added to the world
//! (`World::add_force_field`) is asked
//!
//! - once a step, for the force on each awake balloon's centre of mass
//!   (`ForceField::force`), held constant over the step's substeps like
//!   gravity and buoyancy (`forces::body_forces`, in the `prepare_bodies`
//!   stage);
//! - once a substep, for the force on each point of each awake ribbon, the
//!   end's weight included (`ForceField::force_on_point`), where the ribbons
//!   are solved (`ribbon::solve`, in the `solve` stage).
//!
//! Each sample carries the air's drag factor for its body or point, so a
//! field of moving air can push with the drag against its own velocity.
//! With no field the step asks nothing and computes what it would without
//! the slot, bit for bit.
//!
//! A field is code, not state: snapshots do not hold it, so a restored world
//! has none until they are added again.

use std::fmt;
use std::sync::Arc;

use glam::Vec3;

/// What a field sees of one body when the step's forces are assembled.
#[derive(Clone, Copy, Debug)]
pub struct FieldSample {
    /// Centre of mass, world frame, m.
    pub center: Vec3,
    /// Of the centre of mass, m/s.
    pub velocity: Vec3,
    /// The body's `BodyDef::user_data`.
    pub user_data: u32,
    /// The balloon's own mass (gas and knot included), kg.
    pub mass: f32,
    /// Its volume, m³.
    pub volume: f32,
    /// ½·ρ·C_D·A of the balloon in the room's air now, kg/m: the still air's
    /// drag on it is −drag_factor·|v|·v.
    pub drag_factor: f32,
    /// Simulated seconds at the step's start.
    pub time: f64,
}

/// What a field sees of one point of a ribbon in a substep.
#[derive(Clone, Copy, Debug)]
pub struct PointSample {
    /// World frame, m, at the substep's start.
    pub position: Vec3,
    /// m/s, at the substep's start.
    pub velocity: Vec3,
    /// The point's mass (its share of the ribbon; the end's holds the
    /// weight), kg.
    pub mass: f32,
    /// The free end, where a weight hangs if the ribbon has one.
    pub end: bool,
    /// The still air's drag across the ribbon at high speed, ½·ρ·C·A, kg/m
    /// (the weight's added at the end): its drag is about −drag_factor·|v|·v.
    pub drag_factor: f32,
    /// The ribbon's balloon's `BodyDef::user_data`.
    pub user_data: u32,
    /// Simulated seconds at the step's start.
    pub time: f64,
}

/// Forces a scene adds inside the step: on balloons, once a step, and on
/// ribbon points, once a substep. Each must be deterministic (a function of
/// its sample) for the world's results to be. Both default to none, so a
/// field may act on one kind alone.
pub trait ForceField: Send + Sync {
    /// On a balloon's centre of mass, N, world frame; constant over the step.
    fn force(&self, _body: &FieldSample) -> Vec3 {
        Vec3::ZERO
    }

    /// On a ribbon's point (or its end's weight), N, world frame; for one
    /// substep.
    fn force_on_point(&self, _point: &PointSample) -> Vec3 {
        Vec3::ZERO
    }
}

/// The world's fields, summed in the order they were added.
#[derive(Clone, Default)]
pub struct ForceFields(Vec<Arc<dyn ForceField>>);

impl ForceFields {
    pub fn push(&mut self, field: Arc<dyn ForceField>) {
        self.0.push(field);
    }

    pub fn clear(&mut self) {
        self.0.clear();
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    pub(crate) fn force(&self, body: &FieldSample) -> Vec3 {
        self.0.iter().fold(Vec3::ZERO, |sum, f| sum + f.force(body))
    }

    pub(crate) fn force_on_point(&self, point: &PointSample) -> Vec3 {
        self.0
            .iter()
            .fold(Vec3::ZERO, |sum, f| sum + f.force_on_point(point))
    }
}

impl fmt::Debug for ForceFields {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "ForceFields({} fields)", self.0.len())
    }
}
