//! Reads a built scene's world after a step into the squash table: each
//! body's radius from its balloon model's diameter and its size now, and the
//! reach of its model's mesh along a dent's normal.

use glam::Vec3;
use up_physics::{BodyId, World};

use super::table::{Impact, SquashTable};
use crate::balloon::BalloonModel;
use crate::build::group_index;

/// Reads the last step's contacts of `world` into `table`, keeping each
/// body's deepest dent; `models` are the balloon models by group
/// (`BuiltScene::balloon_models`), a body's group read from its user data.
pub fn record_step(table: &mut SquashTable, world: &World, models: &[BalloonModel]) {
    let model = |id: BodyId| models.get(world.user_data(id).map_or(0, group_index));
    let radius = |id: BodyId| {
        let diameter = model(id).map_or(0.0, |m| m.spec.diameter_m);
        0.5 * diameter * world.body_scale(id).unwrap_or(1.0)
    };
    // Only for the few dents deep enough to draw: a pass over the model's vertices.
    let reach = |id: BodyId, n: Vec3| {
        let mesh = &model(id)?.mesh;
        let local = world.pose(id)?.rotation.inverse() * n;
        let support = mesh
            .positions
            .iter()
            .map(|p| p.dot(local))
            .fold(f32::MIN, f32::max);
        Some(support * world.body_scale(id)?)
    };
    let impacts = world.contact_points().map(|c| Impact {
        body_a: c.body_a,
        body_b: c.body_b,
        normal: c.normal,
        normal_impulse: c.normal_impulse,
        max_normal_impulse: c.max_normal_impulse,
    });
    table.record(world, impacts, radius, reach);
}
