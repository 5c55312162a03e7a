//! One measurement for both engines, from poses alone and with UP's geometry:
//! the deepest overlap between balloons' leaf spheres or with the room, and
//! how many balloons have left the room. Rapier's poses and UP's go through
//! the very same code.

use anyhow::{Context, Result};
use up_geom::Pose;
use up_physics::{BodyDef, World};

use crate::scene_data::SceneData;

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
