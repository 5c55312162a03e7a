//! The result of every contact query.

use glam::Vec3;

/// One contact point between shape A and shape B.
///
/// `normal` is unit length and points from A towards B. `separation` is the
/// signed distance between the surfaces along the normal: negative when they
/// overlap (penetration), positive for a speculative contact found within the
/// query's margin. `point_a` and `point_b` are the closest points on the two
/// surfaces, in the world frame. `feature_a` and `feature_b` identify what
/// touched (a sphere-tree node index, a triangle index) so that a solver can
/// match contacts from one step to the next for warm starting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    pub point_a: Vec3,
    pub point_b: Vec3,
    pub normal: Vec3,
    pub separation: f32,
    pub feature_a: u32,
    pub feature_b: u32,
}

impl Contact {
    /// Penetration depth, never negative.
    #[inline]
    pub fn depth(&self) -> f32 {
        (-self.separation).max(0.0)
    }

    /// The same contact seen from B: normal flipped, points and features swapped.
    pub fn flipped(&self) -> Contact {
        Contact {
            point_a: self.point_b,
            point_b: self.point_a,
            normal: -self.normal,
            separation: self.separation,
            feature_a: self.feature_b,
            feature_b: self.feature_a,
        }
    }
}
