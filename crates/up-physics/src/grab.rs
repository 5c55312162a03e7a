//! Grabbing a balloon with the mouse: a soft spring from a point on the body
//! to a target the user moves. Releasing leaves the body with whatever
//! velocity the drag gave it, which is how a balloon is thrown.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::body::BodyId;

/// Spring frequency, Hz: brisk but well below the substep rate.
pub(crate) const GRAB_HERTZ: f32 = 4.0;
/// Spring damping ratio.
pub(crate) const GRAB_DAMPING_RATIO: f32 = 0.7;
/// Strongest pull, as a multiple of the body's weight.
pub(crate) const GRAB_MAX_WEIGHTS: f32 = 200.0;

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct Grab {
    pub body: BodyId,
    /// The grabbed point, from the centre of mass, body frame.
    pub anchor: Vec3,
    /// Where the user wants that point, world frame, m.
    pub target: Vec3,
}
