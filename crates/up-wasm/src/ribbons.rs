//! The ribbons the page draws and grabs: every ribbon's points in one array
//! a frame (like the poses), and, when ribbons come or go, which balloon each
//! hangs from, where its points start in that array and its colour. Ribbons
//! are tied as the scene ties them (`up_scene::ribbons::tie_ribbon`, at the
//! model's knot, with its group's ribbon); the ribbon length the page sets
//! is written into every group's ribbon and re-ties them all, and a balloon
//! added later gets its group's.

use std::collections::HashMap;

use glam::Vec3;
use up_physics::{BodyId, RibbonId, World};
use up_scene::ribbons::{ribbon_rgb, tie_ribbon, GroupRibbon};
use up_scene::scene::RibbonSpec;

use crate::error::{finite, WasmError};
use crate::loaded::{group_of, Loaded};

/// Floats per ribbon point: x, y, z.
pub const RIBBON_POINT_FLOATS: usize = 3;
/// Longest ribbon the page may tie, m (a scene's `ribbon.length_m` range).
pub use up_scene::scene::MAX_RIBBON_LENGTH_M;

/// Packs an RGB of 0–1 (display sRGB, as the palette is) into 0xRRGGBB.
pub fn pack_rgb(rgb: [f32; 3]) -> u32 {
    rgb.iter().fold(0, |packed, &c| {
        (packed << 8) | (c.clamp(0.0, 1.0) * 255.0).round() as u32
    })
}

/// What the page needs besides the points: one entry per ribbon, in the
/// world's ribbon order (`World::ribbon_ids`).
#[derive(Default)]
pub struct RibbonTables {
    pub points: Vec<f32>,
    /// First point of each ribbon in `points` (in points, not floats), then
    /// the total: ribbons + 1 entries.
    pub offsets: Vec<u32>,
    /// Dense index of the balloon each ribbon is tied to.
    pub bodies: Vec<u32>,
    /// Colour of each ribbon, 0xRRGGBB (sRGB).
    pub colors: Vec<u32>,
    /// The weight tied to each ribbon's free end, kg (0: none).
    pub weights: Vec<f32>,
}

/// Ties group `group`'s ribbon, if it has one, to `body`, a balloon of that group.
fn tie(loaded: &mut Loaded, body: BodyId, group: usize) -> Result<Option<RibbonId>, WasmError> {
    let built = &mut loaded.built;
    let (Some(Some(ribbon)), Some(model)) = (
        built.group_ribbons.get(group),
        built.balloon_models.get(group),
    ) else {
        return Ok(None);
    };
    Ok(tie_ribbon(&mut built.world, body, model, &ribbon.spec)?)
}

/// The weight at the free end of the ribbon of a balloon of `group`, kg.
fn weight_of(loaded: &Loaded, group: usize) -> f32 {
    match loaded.built.group_ribbons.get(group) {
        Some(Some(ribbon)) => ribbon.spec.weight_g * 1e-3,
        _ => 0.0,
    }
}

/// The colour of the ribbon of a balloon of `group`, 0xRRGGBB.
fn color_of(loaded: &Loaded, group: usize) -> u32 {
    let rgb = match loaded.built.group_ribbons.get(group) {
        Some(Some(ribbon)) => ribbon.rgb,
        _ => ribbon_rgb(&RibbonSpec::default()),
    };
    pack_rgb(rgb)
}

impl RibbonTables {
    /// Every ribbon's points, ribbon after ribbon, `RIBBON_POINT_FLOATS` each.
    pub fn write_points(&mut self, world: &World) {
        self.points
            .resize(world.ribbon_point_count() * RIBBON_POINT_FLOATS, 0.0);
        world.write_ribbon_points(&mut self.points);
    }

    /// Each ribbon's first point, balloon, colour and end weight.
    pub fn write_tables(&mut self, loaded: &Loaded) {
        let world = &loaded.built.world;
        let dense: HashMap<BodyId, u32> = world
            .body_ids()
            .iter()
            .enumerate()
            .map(|(i, &id)| (id, i as u32))
            .collect();
        self.offsets.clear();
        self.bodies.clear();
        self.colors.clear();
        self.weights.clear();
        let mut first = 0u32;
        for id in world.ribbon_ids() {
            let body = world.ribbon_body(id);
            let points = world.ribbon_points(id).map_or(0, <[Vec3]>::len);
            self.offsets.push(first);
            first += points as u32;
            self.bodies.push(
                body.and_then(|b| dense.get(&b).copied())
                    .unwrap_or(u32::MAX),
            );
            let group = body.map_or(0, |b| group_of(world, b));
            self.colors.push(color_of(loaded, group));
            self.weights.push(weight_of(loaded, group));
        }
        self.offsets.push(first);
    }
}

/// The first group's ribbon length, m (0: none): what the page shows.
pub fn ribbon_length(loaded: &Loaded) -> f32 {
    loaded
        .scene
        .balloons
        .first()
        .and_then(|g| g.tied_ribbon())
        .map_or(0.0, |r| r.length_m)
}

/// Writes `length` m (0: none) into every group's ribbon, in the scene (so
/// that `scene_json` has it) and in the world: unties every ribbon and ties
/// the new ones; balloons added later get theirs. A group without a ribbon
/// gets the default ribbon (`RibbonSpec::default`).
pub fn set_ribbon_length(loaded: &mut Loaded, length: f32) -> Result<(), WasmError> {
    finite("ribbon length", &[length])?;
    if !(0.0..=MAX_RIBBON_LENGTH_M).contains(&length) {
        return Err(WasmError::OutOfRange(format!(
            "ribbon length {length} m: expected 0 (none) to {MAX_RIBBON_LENGTH_M} m"
        )));
    }
    for (group, ribbon) in loaded
        .scene
        .balloons
        .iter_mut()
        .zip(&mut loaded.built.group_ribbons)
    {
        if length > 0.0 || group.ribbon.is_some() {
            let spec = group.ribbon.get_or_insert_with(RibbonSpec::default);
            spec.length_m = length;
            *ribbon = GroupRibbon::new(spec);
        }
    }
    let world = &mut loaded.built.world;
    for id in world.ribbon_ids() {
        world.remove_ribbon(id)?;
    }
    let bodies = loaded.built.world.body_ids().to_vec();
    for body in bodies {
        let group = group_of(&loaded.built.world, body);
        tie(loaded, body, group)?;
    }
    Ok(())
}

/// Ties its group's ribbon to a balloon just added (none when the group has none).
pub fn tie_added(loaded: &mut Loaded, body: BodyId, group: usize) -> Result<(), WasmError> {
    tie(loaded, body, group)?;
    Ok(())
}

/// Holds point `point` of ribbon `index` (world ribbon order; its free end
/// is its segment count; 0, the knot, is its balloon's) and carries it
/// toward `target`, then toward each `drag_to`; its balloon follows.
pub fn grab_ribbon(
    loaded: &mut Loaded,
    index: u32,
    point: u32,
    target: Vec3,
) -> Result<(), WasmError> {
    finite("grab target", &target.to_array())?;
    let world = &mut loaded.built.world;
    let ids = world.ribbon_ids();
    let id = ids.get(index as usize).copied().ok_or_else(|| {
        WasmError::OutOfRange(format!("ribbon {index}: there are {} ribbons", ids.len()))
    })?;
    let points = world.ribbon_points(id).map_or(0, <[Vec3]>::len);
    if point == 0 || point as usize >= points {
        return Err(WasmError::OutOfRange(format!(
            "point {point} of ribbon {index}: expected 1 to {} (0 is the knot)",
            points.saturating_sub(1)
        )));
    }
    let bounds = loaded.built.room.bounds();
    let target = target.clamp(bounds.min, bounds.max);
    world.grab_ribbon(id, point as usize, target)?;
    Ok(())
}
