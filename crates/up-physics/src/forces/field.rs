//! Force fields: forces a scene adds to every awake balloon, each step (a
//! fan, a draught, a hand waving), in the manner of Jolt's step listeners.
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
    /// Simulated seconds at the step's start.
    pub time: f64,
}

/// A force the scene adds at a body's centre of mass, constant over a step.
/// It must be deterministic (a function of its sample) for the world's
/// results to be.
pub trait ForceField: Send + Sync {
    /// N, world frame.
    fn force(&self, body: &FieldSample) -> Vec3;
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
}

impl fmt::Debug for ForceFields {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "ForceFields({} fields)", self.0.len())
    }
}
