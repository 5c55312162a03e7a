//! One measurement for both engines, from poses alone and with UP's geometry:
//! the deepest overlap between balloons' leaf spheres or with the room, and
//! how many balloons have left the room. Rapier's poses and UP's go through
//! the very same code.
//!
//! A run records its poses at every step (or every k-th, see
//! [`measure_every`]) and measures them after the timed loop: an arrival's
//! deepest overlap lasts a few steps, which a handful of checkpoints miss,
//! and measuring between the timed steps would evict the engines' data from
//! the caches.

use anyhow::{Context, Result};
use serde::Serialize;
use up_geom::Pose;
use up_physics::{BodyDef, World};

use crate::scene_data::SceneData;

/// Most poses a run records for each engine (about 1 GB at 32 B a pose).
pub const POSE_BUDGET: u64 = 30_000_000;

/// Steps between recorded poses: 1 (every step) when `balloons × steps` poses
/// fit in [`POSE_BUDGET`] (10,000 balloons for 3,000 steps), else the fewest
/// that fit (every 9th step for 100,000 balloons over 2,640 steps).
pub fn measure_every(balloons: u64, steps: u64) -> u64 {
    balloons.saturating_mul(steps).div_ceil(POSE_BUDGET).max(1)
}

/// What the poses recorded over a run measure (`up-bench measure` prints it).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PoseMeasure {
    pub frames: usize,
    /// m: deepest overlap over all frames.
    pub max_penetration_m: f32,
    /// m: in the last frame.
    pub final_penetration_m: f32,
    /// Balloons outside the room in the last frame.
    pub escaped: usize,
}

/// Measures recorded frames, the run's last step last.
pub fn measure_frames(data: &SceneData, frames: &[Vec<Pose>]) -> Result<PoseMeasure> {
    let mut deepest = 0.0f32;
    let mut last = 0.0f32;
    for frame in frames {
        last = max_penetration(data, frame)?;
        deepest = deepest.max(last);
    }
    Ok(PoseMeasure {
        frames: frames.len(),
        max_penetration_m: deepest,
        final_penetration_m: last,
        escaped: frames.last().map_or(0, |f| escaped(data, f)),
    })
}

/// m: the deepest overlap of the balloons placed at `poses` (body frames),
/// balloon–balloon or balloon–room, as UP's narrowphase finds it on a fresh
/// world holding only these poses (`World::max_penetration_now`).
pub fn max_penetration(data: &SceneData, poses: &[Pose]) -> Result<f32> {
    let mut world = World::new(data.def.clone()).context("probe world")?;
    let shape = world
        .add_shape(data.shape.clone())
        .context("probe world: the balloon")?;
    for pose in poses {
        world
            .add_body(&BodyDef::new(shape, *pose))
            .context("probe world: a balloon")?;
    }
    Ok(world.max_penetration_now())
}

/// Balloons whose centre of mass is outside the room (or not finite).
pub fn escaped(data: &SceneData, poses: &[Pose]) -> usize {
    poses
        .iter()
        .filter(|pose| {
            let com = pose.transform_point(data.shape.center_of_mass);
            !data.room.contains_point(com)
        })
        .count()
}

#[cfg(test)]
mod tests {
    use up_geom::Vec3;

    use super::*;

    #[test]
    fn every_step_is_recorded_until_the_budget_is_spent() {
        assert_eq!(measure_every(10_000, 917), 1);
        assert_eq!(measure_every(10_000, 3_000), 1);
        assert_eq!(measure_every(100_000, 2_640), 9);
        assert_eq!(measure_every(0, 600), 1);
        assert!(100_000 * 2_640 / measure_every(100_000, 2_640) <= POSE_BUDGET);
    }

    #[test]
    fn the_deepest_frame_counts_not_only_the_last() {
        let (data, built) = SceneData::build(2, 1).unwrap();
        let apart: Vec<Pose> = built.world.poses().map(|(_, pose)| pose).collect();
        assert_eq!(apart.len(), 2);
        // Both upright at the room's middle, 27 cm apart: their biggest
        // leaves (the heads, 14.27 cm) overlap by 1.54 cm.
        let height = apart[0].position.y;
        let at = |x: f32| Pose {
            position: Vec3::new(x, height, 0.0),
            rotation: up_geom::Quat::IDENTITY,
        };
        let touching = vec![at(-0.135), at(0.135)];
        let head = data
            .shape
            .tree
            .leaf_spheres()
            .map(|s| s.radius)
            .fold(0.0, f32::max);
        let expected = 2.0 * head - 0.27;

        let m = measure_frames(&data, &[apart.clone(), touching, apart]).unwrap();
        assert_eq!(m.frames, 3);
        assert!(
            (m.max_penetration_m - expected).abs() < 1e-4,
            "deepest {} m, expected {expected} m",
            m.max_penetration_m
        );
        assert_eq!(m.final_penetration_m, 0.0);
        assert_eq!(m.escaped, 0);
    }
}
