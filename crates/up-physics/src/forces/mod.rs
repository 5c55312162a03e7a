//! The forces on a balloon: gravity on its full mass, buoyancy at its centre
//! of buoyancy, quadratic drag, added mass, angular damping, and whatever
//! force fields the scene adds. Each physical law is a small pure function;
//! `body_forces` assembles them once a step and `solver::integrate` applies
//! them per substep.

pub mod atmosphere;
pub(crate) mod body_forces;
pub mod buoyancy;
pub mod drag;
pub mod field;
pub mod gravity;

pub(crate) use body_forces::BodyForces;
