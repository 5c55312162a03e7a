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
use crate::state::{Loaded, State};

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

fn group_of(world: &World, body: BodyId) -> usize {
    world
        .user_data(body)
        .map_or(0, up_scene::build::group_index)
}

impl State {
    /// Ribbons in the world (0 without one).
    pub fn ribbon_count(&self) -> usize {
        self.world().map_or(0, World::ribbon_count)
    }

    /// Every ribbon's points, ribbon after ribbon, `RIBBON_POINT_FLOATS` each.
    pub fn write_ribbon_points(&mut self) -> Result<(), WasmError> {
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        let world = &loaded.built.world;
        let points = &mut self.ribbons.points;
        points.resize(world.ribbon_point_count() * RIBBON_POINT_FLOATS, 0.0);
        world.write_ribbon_points(points);
        Ok(())
    }

    /// Each ribbon's first point, balloon, colour and end weight (`RibbonTables`).
    pub fn write_ribbon_tables(&mut self) -> Result<(), WasmError> {
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        let world = &loaded.built.world;
        let dense: HashMap<BodyId, u32> = world
            .body_ids()
            .iter()
            .enumerate()
            .map(|(i, &id)| (id, i as u32))
            .collect();
        let t = &mut self.ribbons;
        t.offsets.clear();
        t.bodies.clear();
        t.colors.clear();
        t.weights.clear();
        let mut first = 0u32;
        for id in world.ribbon_ids() {
            let body = world.ribbon_body(id);
            let points = world.ribbon_points(id).map_or(0, <[Vec3]>::len);
            t.offsets.push(first);
            first += points as u32;
            t.bodies.push(
                body.and_then(|b| dense.get(&b).copied())
                    .unwrap_or(u32::MAX),
            );
            let group = body.map_or(0, |b| group_of(world, b));
            t.colors.push(color_of(loaded, group));
            t.weights.push(weight_of(loaded, group));
        }
        t.offsets.push(first);
        Ok(())
    }

    /// The first group's ribbon length, m (0: none): what the page shows.
    pub fn ribbon_length(&self) -> f32 {
        self.loaded
            .as_ref()
            .and_then(|l| l.scene.balloons.first())
            .and_then(|g| g.tied_ribbon())
            .map_or(0.0, |r| r.length_m)
    }

    /// Writes `length` m (0: none) into every group's ribbon, in the scene
    /// (so that `scene_json` has it) and in the world: unties every ribbon
    /// and ties the new ones; balloons added later get theirs. A group
    /// without a ribbon gets the default ribbon (`RibbonSpec::default`).
    pub fn set_ribbon_length(&mut self, length: f32) -> Result<(), WasmError> {
        finite("ribbon length", &[length])?;
        if !(0.0..=MAX_RIBBON_LENGTH_M).contains(&length) {
            return Err(WasmError::OutOfRange(format!(
                "ribbon length {length} m: expected 0 (none) to {MAX_RIBBON_LENGTH_M} m"
            )));
        }
        let loaded = self.loaded.as_mut().ok_or(WasmError::NoWorld)?;
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
    pub(crate) fn tie_added(&mut self, body: BodyId, group: usize) -> Result<(), WasmError> {
        let loaded = self.loaded.as_mut().ok_or(WasmError::NoWorld)?;
        tie(loaded, body, group)?;
        Ok(())
    }

    /// The ribbon at `index` in the world's ribbon order.
    fn ribbon_at(&self, index: u32) -> Result<RibbonId, WasmError> {
        let ids = self.world()?.ribbon_ids();
        ids.get(index as usize).copied().ok_or_else(|| {
            WasmError::OutOfRange(format!("ribbon {index}: there are {} ribbons", ids.len()))
        })
    }

    /// Holds point `point` of ribbon `index` (its free end is its segment
    /// count; 0, the knot, is its balloon's) and carries it toward `target`,
    /// then toward each `drag_to`; its balloon follows on the ribbon.
    pub fn grab_ribbon(&mut self, index: u32, point: u32, target: Vec3) -> Result<(), WasmError> {
        finite("grab target", &target.to_array())?;
        let id = self.ribbon_at(index)?;
        let world = self.world()?;
        let points = world.ribbon_points(id).map_or(0, <[Vec3]>::len);
        if point == 0 || point as usize >= points {
            return Err(WasmError::OutOfRange(format!(
                "point {point} of ribbon {index}: expected 1 to {} (0 is the knot)",
                points.saturating_sub(1)
            )));
        }
        let bounds = self.loaded()?.built.room.bounds();
        let target = target.clamp(bounds.min, bounds.max);
        self.world_mut()?.grab_ribbon(id, point as usize, target)?;
        Ok(())
    }
}
