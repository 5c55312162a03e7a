//! The forces of a balloon in still air: gravity on its full mass, buoyancy at
//! its centre of buoyancy, quadratic drag, added mass, angular damping.
//! Each is a small pure function; `solver::integrate` applies them per substep.

pub mod atmosphere;
pub mod buoyancy;
pub mod drag;
pub mod gravity;
