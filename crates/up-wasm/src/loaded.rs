//! A built world with the scene it came from: what every feature file reads
//! and changes. The feature files take a `&Loaded` or `&World`, never the
//! `State` that holds them.

use up_physics::{BodyId, ShapeId, World};
use up_scene::build::{group_index, BuiltScene};
use up_scene::scene::Scene;

use crate::error::WasmError;

/// A built world plus what the page needs to draw it.
pub struct Loaded {
    pub scene: Scene,
    pub built: BuiltScene,
    /// Shape of each balloon model (one per group), in group order.
    pub shapes: Vec<ShapeId>,
}

/// The body at dense `index` of `world`.
pub fn body_at(world: &World, index: u32) -> Result<BodyId, WasmError> {
    let ids = world.body_ids();
    ids.get(index as usize).copied().ok_or_else(|| {
        WasmError::OutOfRange(format!(
            "body index {index}: there are {} bodies",
            ids.len()
        ))
    })
}

/// The balloon group (and model) of `body`.
pub fn group_of(world: &World, body: BodyId) -> usize {
    world.user_data(body).map_or(0, group_index)
}
