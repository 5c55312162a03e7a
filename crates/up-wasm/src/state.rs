//! The world the exports act on and the buffers the page reads from it:
//! loading, stepping, adding and holding balloons, and one thin method per
//! feature, which hands the feature file (`forces.rs`, `gas.rs`,
//! `ribbons.rs`, `squash.rs`, `live.rs`, ...) the `Loaded` world and its own
//! buffer. Safe Rust with `Result`s, tested natively; `lib.rs` only marshals.

use glam::{Quat, Vec3};
use up_geom::Pose;
use up_physics::{BodyDef, BodyId, ShapeId, World};
use up_scene::build::{build_world, color_index, group_index, user_data_for};
use up_scene::float_census::FloatCensus;
use up_scene::scene::Scene;

use crate::contacts::write_contacts;
use crate::error::{finite, WasmError};
use crate::export::ExportRing;
use crate::gas::{AdvanceReport, FloatCounts};
use crate::info::{EngineStats, WorldSummary};
use crate::live::LiveSetting;
use crate::loaded::{body_at, Loaded};
use crate::model_mesh::MeshBuffers;
use crate::ribbons::RibbonTables;
use crate::squash::SquashBuffers;
use crate::stats::StageSums;
use crate::{air, forces, gas, live, model_mesh, ribbons};

pub use crate::limits::{
    CAPACITY, MAX_SPEED, MAX_SPIN, MAX_STEPS_PER_CALL, POSE_FLOATS, TREE_FLOATS,
};

/// How far from a balloon's bounding sphere a grab point may lie, as a
/// fraction of its radius: the picked point is on the surface, give or take.
const GRAB_SLACK: f32 = 0.5;
/// Gap left between a placed balloon and the floor, m.
const FLOOR_GAP: f32 = 0.005;
/// Name of scenes that come from the page.
const WEB_SOURCE: &str = "scene";

/// Everything that lives between calls.
#[derive(Default)]
pub struct State {
    pub loaded: Option<Loaded>,
    pub poses: Vec<f32>,
    pub colors: Vec<u32>,
    pub models: Vec<u32>,
    pub tree: Vec<f32>,
    pub room_vertices: Vec<f32>,
    pub room_triangles: Vec<u32>,
    /// Contacts of the last step for the debug view (`contacts.rs` layout).
    pub contacts: Vec<f32>,
    /// How many contacts the last step had, written or not.
    pub contact_total: usize,
    /// Stage milliseconds over the steps since the last `stats` (`stats.rs`).
    stage_sums: StageSums,
    /// The ribbons' points and tables for the page (`ribbons.rs`).
    pub ribbons: RibbonTables,
    /// Each body's size over its shape's, dense order.
    pub scales: Vec<f32>,
    /// How high each balloon has been, for where it floats (`gas.rs`); made afresh with each world.
    pub census: Option<FloatCensus>,
    /// The surface `write_model_mesh` wrote last (`model_mesh.rs`).
    pub mesh: MeshBuffers,
    /// The probed forces `write_forces` wrote last (`forces.rs`).
    pub forces: Vec<f32>,
    /// Each body's deepest dent since the page last read it, and what it read (`squash.rs`).
    pub squash: SquashBuffers,
    /// The frames sent lately, for the page's glTF export (`export.rs`).
    pub export: ExportRing,
    /// The air's sources and samples the page read last (`air.rs`).
    pub air: air::AirBuffers,
}

/// `Ok` when a velocity stays within `MAX_SPEED` and `MAX_SPIN`, else why not.
fn speed_limits(linear: Vec3, angular: Vec3) -> Result<(), String> {
    if linear.length() > MAX_SPEED {
        return Err(format!(
            "speed {} m/s: expected at most {MAX_SPEED} m/s",
            linear.length()
        ));
    }
    if angular.length() > MAX_SPIN {
        return Err(format!(
            "spin {} rad/s: expected at most {MAX_SPIN} rad/s",
            angular.length()
        ));
    }
    Ok(())
}

impl State {
    pub(crate) fn loaded(&self) -> Result<&Loaded, WasmError> {
        self.loaded.as_ref().ok_or(WasmError::NoWorld)
    }

    fn loaded_mut(&mut self) -> Result<&mut Loaded, WasmError> {
        self.loaded.as_mut().ok_or(WasmError::NoWorld)
    }

    pub fn world(&self) -> Result<&World, WasmError> {
        Ok(&self.loaded()?.built.world)
    }

    fn world_mut(&mut self) -> Result<&mut World, WasmError> {
        Ok(&mut self.loaded_mut()?.built.world)
    }

    /// Builds `scene` and makes it the world. On error the old world stays.
    pub fn load(&mut self, scene: Scene) -> Result<(), WasmError> {
        check_for_browser(&scene)?;
        let built = build_world(&scene)?;
        // Models were added as shapes in group order, one each, before any other.
        let shapes = (0..built.balloon_models.len() as u32)
            .map(ShapeId)
            .collect();
        self.room_vertices = built
            .room
            .vertices()
            .iter()
            .flat_map(|v| v.to_array())
            .collect();
        self.room_triangles = built.room.triangles().iter().flatten().copied().collect();
        self.loaded = Some(Loaded {
            scene,
            built,
            shapes,
        });
        self.census = None;
        self.export.clear();
        Ok(())
    }

    /// Records the world now into the export's ring.
    pub fn record_export_frame(&mut self) -> Result<(), WasmError> {
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        self.export.record(loaded);
        Ok(())
    }

    pub fn load_json(&mut self, text: &str) -> Result<(), WasmError> {
        self.load(Scene::from_json_str(text, WEB_SOURCE)?)
    }

    pub fn load_toml(&mut self, text: &str) -> Result<(), WasmError> {
        self.load(Scene::from_toml_str(text, WEB_SOURCE)?)
    }

    pub fn load_default(&mut self) -> Result<(), WasmError> {
        self.load(Scene::default())
    }

    /// The loaded scene as JSON, every default written out.
    pub fn scene_json(&self) -> Result<String, WasmError> {
        Ok(self.loaded()?.scene.to_json_string()?)
    }

    pub fn step(&mut self, n: u32) -> Result<(), WasmError> {
        if n > MAX_STEPS_PER_CALL {
            return Err(WasmError::BadArgument(format!(
                "{n} steps at once: expected at most {MAX_STEPS_PER_CALL}"
            )));
        }
        let loaded = self.loaded.as_mut().ok_or(WasmError::NoWorld)?;
        for _ in 0..n {
            loaded.built.world.step();
            self.stage_sums.add(&loaded.built.world);
            self.squash.record(loaded);
        }
        Ok(())
    }

    /// Advances `seconds` of simulated time with `World::advance`: fixed
    /// steps while anything moves, jumps of the gas alone while everything
    /// sleeps, at most `max_steps` steps.
    pub fn advance(&mut self, seconds: f64, max_steps: u32) -> Result<AdvanceReport, WasmError> {
        gas::check_advance(seconds, max_steps)?;
        let loaded = self.loaded.as_mut().ok_or(WasmError::NoWorld)?;
        let done = loaded.built.world.advance(seconds, u64::from(max_steps));
        if done.steps > 0 {
            // The stats average per step; the call's last step stands for its steps.
            self.stage_sums.add(&loaded.built.world);
            self.squash.record(loaded);
        }
        Ok(done.into())
    }

    pub fn body_count(&self) -> usize {
        self.loaded
            .as_ref()
            .map_or(0, |l| l.built.world.body_count())
    }

    fn body_at(&self, index: u32) -> Result<BodyId, WasmError> {
        body_at(self.world()?, index)
    }

    pub fn write_poses(&mut self) -> Result<(), WasmError> {
        let n = self.body_count();
        self.poses.resize(n * POSE_FLOATS, 0.0);
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        loaded.built.world.write_poses(&mut self.poses);
        Ok(())
    }

    /// The last step's contacts, at most `max` of them, for the debug view.
    pub fn write_contacts(&mut self, max: u32) -> Result<(), WasmError> {
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        self.contact_total = write_contacts(&loaded.built.world, max as usize, &mut self.contacts);
        Ok(())
    }

    /// Colour index (into the palette) and model index (the group) of every body.
    pub fn write_user_data(&mut self) -> Result<(), WasmError> {
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        let world = &loaded.built.world;
        self.colors.clear();
        self.models.clear();
        for &id in world.body_ids() {
            let user = world.user_data(id).unwrap_or(0);
            self.colors.push(color_index(user) as u32);
            self.models.push(group_index(user) as u32);
        }
        Ok(())
    }

    /// Adds a balloon of model `model` with its mesh frame at `position`, upright.
    pub fn add_balloon(&mut self, position: Vec3, color: u32, model: u32) -> Result<(), WasmError> {
        finite("balloon position", &position.to_array())?;
        if self.body_count() >= CAPACITY {
            return Err(WasmError::Full(format!(
                "the room is full: at most {CAPACITY} balloons in the browser"
            )));
        }
        let loaded = self.loaded_mut()?;
        let bounds = loaded.built.room.bounds();
        if position.cmplt(bounds.min).any() || position.cmpgt(bounds.max).any() {
            return Err(WasmError::OutOfRange(format!(
                "balloon position {position}: expected a point inside the room, from {} to {} m",
                bounds.min, bounds.max
            )));
        }
        let shape = *loaded.shapes.get(model as usize).ok_or_else(|| {
            WasmError::OutOfRange(format!(
                "balloon model {model}: the scene has {} models",
                loaded.shapes.len()
            ))
        })?;
        if color as usize >= loaded.built.colors.len() {
            return Err(WasmError::OutOfRange(format!(
                "colour {color}: the palette has {} colours",
                loaded.built.colors.len()
            )));
        }
        let mut def = BodyDef::new(shape, Pose::new(position, Quat::IDENTITY));
        def.user_data = user_data_for(model as usize, color as usize);
        let body = loaded.built.world.add_body(&def)?;
        // Filled before its ribbon is tied: the ribbon hangs from the balloon as its gas makes it.
        let group = model as usize;
        let filled = gas::fill_added(loaded, body, group);
        if let Err(e) = filled.and_then(|()| ribbons::tie_added(loaded, body, group)) {
            // A balloon the page cannot fill or give its ribbon is not added.
            let _ = loaded.built.world.remove_body(body);
            return Err(e);
        }
        Ok(())
    }

    /// Adds a balloon of the first model standing on the floor (y = 0) at (x, z).
    pub fn add_balloon_on_floor(&mut self, x: f32, z: f32, color: u32) -> Result<(), WasmError> {
        finite("floor point", &[x, z])?;
        let loaded = self.loaded()?;
        let model = loaded.built.balloon_models.first().ok_or_else(|| {
            WasmError::OutOfRange("the scene has no balloon model to add".to_string())
        })?;
        // Lowest point of the collision spheres, mesh frame, upright.
        let bottom = model
            .shape
            .tree
            .leaf_spheres()
            .map(|s| s.center.y - s.radius)
            .fold(f32::INFINITY, f32::min);
        let bounds = loaded.built.room.bounds();
        let inside = x > bounds.min.x && x < bounds.max.x && z > bounds.min.z && z < bounds.max.z;
        if !inside {
            return Err(WasmError::OutOfRange(format!(
                "floor point ({x}, {z}) lies outside the room ({} to {} m along x, {} to {} along z)",
                bounds.min.x, bounds.max.x, bounds.min.z, bounds.max.z
            )));
        }
        let y = bounds.min.y - bottom + FLOOR_GAP;
        self.add_balloon(Vec3::new(x, y, z), color, 0)
    }

    pub fn remove(&mut self, index: u32) -> Result<(), WasmError> {
        let id = self.body_at(index)?;
        self.world_mut()?.remove_body(id)?;
        Ok(())
    }

    /// Applies `impulse` (N·s) at `point` (m); refused, with nothing changed,
    /// when it would leave the body faster than `MAX_SPEED` or `MAX_SPIN`.
    pub fn apply_impulse(
        &mut self,
        index: u32,
        impulse: Vec3,
        point: Vec3,
    ) -> Result<(), WasmError> {
        finite("impulse", &impulse.to_array())?;
        finite("impulse point", &point.to_array())?;
        let id = self.body_at(index)?;
        let world = self.world_mut()?;
        let before = (world.linear_velocity(id), world.angular_velocity(id));
        world.apply_impulse_at_point(id, impulse, point)?;
        let after = (world.linear_velocity(id), world.angular_velocity(id));
        if let ((Some(v0), Some(w0)), (Some(v), Some(w))) = (before, after) {
            if let Err(e) = speed_limits(v, w) {
                world.set_velocity(id, v0, w0)?;
                return Err(WasmError::BadArgument(format!(
                    "impulse {impulse} N·s at {point}: {e}"
                )));
            }
        }
        Ok(())
    }

    pub fn set_velocity(
        &mut self,
        index: u32,
        linear: Vec3,
        angular: Vec3,
    ) -> Result<(), WasmError> {
        finite("linear velocity", &linear.to_array())?;
        finite("angular velocity", &angular.to_array())?;
        speed_limits(linear, angular).map_err(WasmError::BadArgument)?;
        let id = self.body_at(index)?;
        self.world_mut()?.set_velocity(id, linear, angular)?;
        Ok(())
    }

    /// Holds the body at `index` by `point`, which must lie on it (within its
    /// bounding sphere, give or take `GRAB_SLACK`).
    pub fn grab(&mut self, index: u32, point: Vec3) -> Result<(), WasmError> {
        finite("grab point", &point.to_array())?;
        let id = self.body_at(index)?;
        let loaded = self.loaded()?;
        let world = &loaded.built.world;
        let model = world.user_data(id).map_or(0, group_index);
        let root = loaded
            .built
            .balloon_models
            .get(model)
            .map(|m| *m.shape.tree.root());
        if let (Some(root), Some(pose)) = (root, world.pose(id)) {
            let center = pose.position + pose.rotation * root.center;
            let reach = root.radius * (1.0 + GRAB_SLACK);
            let distance = point.distance(center);
            if distance > reach {
                return Err(WasmError::OutOfRange(format!(
                    "grab point {point} is {distance:.3} m from the centre of balloon {index}: \
                     expected a point on it (within {reach:.3} m)"
                )));
            }
        }
        self.world_mut()?.grab(id, point)?;
        Ok(())
    }

    /// Moves the grab target, clamped into the room: the balloon cannot
    /// leave it, and a ray that grazes the drag plane lands far away.
    pub fn drag_to(&mut self, target: Vec3) -> Result<(), WasmError> {
        finite("grab target", &target.to_array())?;
        let bounds = self.loaded()?.built.room.bounds();
        let target = target.clamp(bounds.min, bounds.max);
        self.world_mut()?.set_grab_target(target)?;
        Ok(())
    }

    pub fn release(&mut self) -> Result<(), WasmError> {
        self.world_mut()?.release_grab();
        Ok(())
    }

    /// Writes model `model`'s sphere tree (root first) into `tree`; returns the node count.
    pub fn write_tree(&mut self, model: u32) -> Result<usize, WasmError> {
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        let m = loaded
            .built
            .balloon_models
            .get(model as usize)
            .ok_or_else(|| {
                WasmError::OutOfRange(format!(
                    "balloon model {model}: the scene has {} models",
                    loaded.built.balloon_models.len()
                ))
            })?;
        let nodes = m.shape.tree.nodes();
        // Depth of each node: children come after their parent, so one pass fills it.
        let mut depth = vec![0u32; nodes.len()];
        for (i, n) in nodes.iter().enumerate() {
            let child_depth = depth[i] + 1;
            for c in n.children() {
                if let Some(d) = depth.get_mut(c) {
                    *d = child_depth;
                }
            }
        }
        self.tree.clear();
        for (n, d) in nodes.iter().zip(&depth) {
            let leaf = if n.is_leaf() { 1.0 } else { 0.0 };
            self.tree.extend_from_slice(&[
                n.center.x, n.center.y, n.center.z, n.radius, *d as f32, leaf,
            ]);
        }
        Ok(nodes.len())
    }

    pub fn model_count(&self) -> usize {
        self.loaded
            .as_ref()
            .map_or(0, |l| l.built.balloon_models.len())
    }

    /// Palette, colour names, model diameters and the time step.
    pub fn world_info(&self) -> Result<WorldSummary, WasmError> {
        let loaded = self.loaded()?;
        Ok(WorldSummary {
            colors: loaded.built.colors.clone(),
            color_names: loaded.built.color_names.clone(),
            diameters: loaded.scene.balloons.iter().map(|g| g.diameter()).collect(),
            foil: self.model_foil()?,
            finishes: loaded.scene.balloons.iter().map(|g| g.finish()).collect(),
            dt: loaded.built.world.def().dt,
        })
    }

    /// Per-stage milliseconds per step, averaged over the steps since the last
    /// call (the last step's when none), and the last step's counts.
    pub fn stats(&mut self) -> Result<EngineStats, WasmError> {
        let world = &self.loaded.as_ref().ok_or(WasmError::NoWorld)?.built.world;
        Ok(self.stage_sums.take(world))
    }

    // ---- the features, each in its own file ----

    /// Applies a live setting to the running world (`live.rs`).
    pub fn apply_live(&mut self, setting: LiveSetting) -> Result<(), WasmError> {
        live::apply(self.loaded_mut()?, setting)
    }

    /// Writes every body's size over its shape's (1 without gas), dense order, into `scales`.
    pub fn write_body_scales(&mut self) -> Result<(), WasmError> {
        let n = self.body_count();
        self.scales.resize(n, 1.0);
        let world = &self.loaded.as_ref().ok_or(WasmError::NoWorld)?.built.world;
        world.write_body_scales(&mut self.scales);
        Ok(())
    }

    /// Simulated seconds since the world was built (jumps included).
    pub fn sim_time(&self) -> f64 {
        self.world().map_or(0.0, |w| w.time())
    }

    /// The room's air temperature now, °C (the scene's schedule applied).
    pub fn air_temperature_c(&self) -> Result<f32, WasmError> {
        Ok(gas::air_temperature_c(self.world()?))
    }

    /// Looks at every balloon now (the census keeps how high each has been) and counts where they float.
    pub fn float_counts(&mut self) -> Result<FloatCounts, WasmError> {
        let world = &self.loaded.as_ref().ok_or(WasmError::NoWorld)?.built.world;
        Ok(gas::float_counts(world, &mut self.census))
    }

    /// What the next steps record: `PROBE_OFF`, `PROBE_ALL`, or one body's dense index.
    pub fn set_force_probe(&mut self, which: i32) -> Result<(), WasmError> {
        forces::set_force_probe(self.world_mut()?, which)
    }

    /// Writes the last step's probed forces into `forces`; returns how many bodies.
    pub fn write_forces(&mut self) -> Result<usize, WasmError> {
        let world = &self.loaded.as_ref().ok_or(WasmError::NoWorld)?.built.world;
        Ok(forces::write_forces(world, &mut self.forces))
    }

    /// The card of the balloon at dense index `index`.
    pub fn body_card(&self, index: u32) -> Result<forces::BodyCard, WasmError> {
        forces::body_card(self.world()?, index)
    }

    /// Each body's deepest dent since the last call into `squash.out`, then forgotten.
    pub fn write_body_squash(&mut self) -> Result<(), WasmError> {
        let count = self.world()?.body_count();
        self.squash.write(count);
        Ok(())
    }

    /// Ribbons in the world (0 without one).
    pub fn ribbon_count(&self) -> usize {
        self.world().map_or(0, World::ribbon_count)
    }

    /// Every ribbon's points into `ribbons.points`.
    pub fn write_ribbon_points(&mut self) -> Result<(), WasmError> {
        let world = &self.loaded.as_ref().ok_or(WasmError::NoWorld)?.built.world;
        self.ribbons.write_points(world);
        Ok(())
    }

    /// Each ribbon's first point, balloon, colour and end weight into `ribbons`.
    pub fn write_ribbon_tables(&mut self) -> Result<(), WasmError> {
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        self.ribbons.write_tables(loaded);
        Ok(())
    }

    /// The first group's ribbon length, m (0: none, or no world).
    pub fn ribbon_length(&self) -> f32 {
        self.loaded.as_ref().map_or(0.0, ribbons::ribbon_length)
    }

    /// Holds point `point` of ribbon `index` and carries it toward `target`.
    pub fn grab_ribbon(&mut self, index: u32, point: u32, target: Vec3) -> Result<(), WasmError> {
        ribbons::grab_ribbon(self.loaded_mut()?, index, point, target)
    }

    /// Applies a command of the page's air tools to the running world (`air.rs`).
    pub fn apply_air(&mut self, command: air::AirCommand) -> Result<(), WasmError> {
        air::apply(self.loaded_mut()?, command)
    }

    /// Every air source's row into `air.sources`; returns how many.
    pub fn write_air_sources(&mut self) -> Result<usize, WasmError> {
        let world = &self.loaded.as_ref().ok_or(WasmError::NoWorld)?.built.world;
        Ok(air::write_sources(world, &mut self.air.sources))
    }

    /// The air now on `dims` cells tiling the room into `air.grid`.
    pub fn write_air_grid(&mut self, dims: [u32; 3]) -> Result<air::AirGrid, WasmError> {
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        let bounds = loaded.built.room.bounds();
        air::write_grid(&loaded.built.world, bounds, dims, &mut self.air.grid)
    }

    /// The air now at each of `points` into `air.points`; returns how many.
    pub fn write_air_at(&mut self, points: &[f32]) -> Result<usize, WasmError> {
        let world = &self.loaded.as_ref().ok_or(WasmError::NoWorld)?.built.world;
        air::write_at(world, points, &mut self.air.points)
    }

    /// Whether each balloon model (one per group, in group order) is foil.
    pub fn model_foil(&self) -> Result<Vec<bool>, WasmError> {
        Ok(model_mesh::model_foil(self.loaded()?))
    }

    /// Writes model `model`'s surface into `mesh`; returns the vertex count.
    pub fn write_model_mesh(&mut self, model: u32) -> Result<usize, WasmError> {
        let loaded = self.loaded.as_ref().ok_or(WasmError::NoWorld)?;
        self.mesh.write(loaded, model)
    }
}

/// `Ok` when the page can hold `scene` (what `Scene`'s own validation does
/// not know): at most `CAPACITY` balloons, a box room and furniture made by
/// kind (a mesh room or piece names a file the browser cannot read).
pub fn check_for_browser(scene: &Scene) -> Result<(), WasmError> {
    let total = scene.total_balloons();
    if total > CAPACITY as u64 {
        return Err(WasmError::Full(format!(
            "{}: {total} balloons: the browser holds at most {CAPACITY} (the CLI takes more)",
            scene.source.name
        )));
    }
    if scene.room.mesh.is_some() {
        return Err(WasmError::Scene(format!(
            "{}: room.mesh: a mesh room cannot be read in the browser; expected a box room",
            scene.source.name
        )));
    }
    crate::furniture::check_for_browser(scene)
}

/// Reads and checks a scene in JSON as `load_json` would, without building it.
pub fn validate_json(text: &str) -> Result<(), WasmError> {
    check_for_browser(&Scene::from_json_str(text, WEB_SOURCE)?)
}

#[cfg(test)]
#[path = "state_tests.rs"]
mod tests;
