//! Spheres.

use glam::Vec3;
use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sphere {
    pub center: Vec3,
    /// m
    pub radius: f32,
}

impl Sphere {
    pub fn new(center: Vec3, radius: f32) -> Self {
        Self { center, radius }
    }

    /// True when `other` lies entirely inside `self`, within `tolerance` metres.
    pub fn contains_sphere(&self, other: &Sphere, tolerance: f32) -> bool {
        self.center.distance(other.center) + other.radius <= self.radius + tolerance
    }

    pub fn volume(&self) -> f32 {
        4.0 / 3.0 * std::f32::consts::PI * self.radius * self.radius * self.radius
    }
}
