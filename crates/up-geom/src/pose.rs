//! A rigid pose: rotation then translation, body frame to world frame.

use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};

/// Body-to-world transform: `world = rotation * local + position`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    pub position: Vec3,
    pub rotation: Quat,
}

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Pose {
    pub const IDENTITY: Pose = Pose {
        position: Vec3::ZERO,
        rotation: Quat::IDENTITY,
    };

    pub fn new(position: Vec3, rotation: Quat) -> Self {
        Self { position, rotation }
    }

    pub fn from_position(position: Vec3) -> Self {
        Self {
            position,
            rotation: Quat::IDENTITY,
        }
    }

    /// Maps a body-frame point to the world frame.
    #[inline]
    pub fn transform_point(&self, local: Vec3) -> Vec3 {
        self.rotation * local + self.position
    }

    /// Maps a body-frame direction to the world frame.
    #[inline]
    pub fn transform_vector(&self, local: Vec3) -> Vec3 {
        self.rotation * local
    }

    /// Maps a world point to the body frame.
    #[inline]
    pub fn inverse_transform_point(&self, world: Vec3) -> Vec3 {
        self.rotation.inverse() * (world - self.position)
    }
}
