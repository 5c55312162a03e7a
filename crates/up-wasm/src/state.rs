//! The world the exports act on, and everything the page reads from it:
//! poses, colours, the room, the balloon models' sphere trees, stats. Safe
//! Rust with `Result`s, tested natively; `lib.rs` only marshals.

use glam::{Quat, Vec3};
use up_geom::Pose;
use up_physics::{BodyDef, BodyId, ShapeId, World};
use up_scene::build::{build_world, color_index, group_index, user_data_for, BuiltScene};
use up_scene::scene::Scene;

use crate::contacts::write_contacts;
use crate::error::{finite, WasmError};
use crate::info::{EngineStats, WorldSummary};
use crate::model_mesh::MeshBuffers;
use crate::ribbons::RibbonTables;
use up_scene::float_census::FloatCensus;

/// Most steps one `step` call takes: a host asking for more has lost track of time.
pub const MAX_STEPS_PER_CALL: u32 = 10_000;
/// Most balloons a page may hold: what a browser can draw and step (the
/// engine itself takes millions). Adding past this is `Full`.
pub const CAPACITY: usize = 50_000;
/// Floats per pose: x, y, z, qx, qy, qz, qw.
pub const POSE_FLOATS: usize = 7;
/// Floats per sphere-tree node for the page: cx, cy, cz, radius, depth, leaf.
pub const TREE_FLOATS: usize = 6;
/// Fastest a balloon may be set moving, m/s: far beyond any throw (a hard
/// throw is 10 to 30 m/s) yet small enough that one step cannot tunnel far.
pub const MAX_SPEED: f32 = 100.0;
/// Fastest a balloon may be set spinning, rad/s (a flicked balloon: about 20).
pub const MAX_SPIN: f32 = 500.0;
/// How far from a balloon's bounding sphere a grab point may lie, as a
/// fraction of its radius: the picked point is on the surface, give or take.
const GRAB_SLACK: f32 = 0.5;
/// Gap left between a placed balloon and the floor, m.
const FLOOR_GAP: f32 = 0.005;
/// Name of scenes that come from the page.
const WEB_SOURCE: &str = "scene";

/// A built world plus what the page needs to draw it.
pub struct Loaded {
    pub scene: Scene,
    pub built: BuiltScene,
    /// Shape of each balloon model (one per group), in group order.
    pub shapes: Vec<ShapeId>,
}

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
    /// Stage milliseconds summed over the steps since the last `stats_json`:
    /// browsers coarsen `performance.now()`, so one step's timings are noisy.
    stage_sums: Vec<(&'static str, f64)>,
    steps_summed: u32,
    /// The ribbons' points and tables for the page (`ribbons.rs`).
    pub ribbons: RibbonTables,
    /// Each body's size over its shape's, dense order (`gas.rs`).
    pub scales: Vec<f32>,
    /// How high each balloon has been, for where it floats (`gas.rs`); made afresh with each world.
    pub census: Option<FloatCensus>,
    /// The surface `write_model_mesh` wrote last (`model_mesh.rs`).
    pub mesh: MeshBuffers,
    /// The probed forces `write_forces` wrote last (`forces.rs`).
    pub forces: Vec<f32>,
    /// Each body's deepest dent since the page last read it, and what it read (`squash.rs`).
    pub squash: crate::squash::SquashTable,
    pub squash_out: Vec<f32>,
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

    pub(crate) fn world_mut(&mut self) -> Result<&mut World, WasmError> {
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
        self.world()?;
        for _ in 0..n {
            self.world_mut()?.step();
            self.sum_last_step();
            self.record_squash();
        }
        Ok(())
    }

    /// Adds the last step's stage times to the sums `stats` averages.
    pub(crate) fn sum_last_step(&mut self) {
        let Some(loaded) = self.loaded.as_ref() else {
            return;
        };
        let stages = loaded.built.world.counters().stages();
        if self.stage_sums.len() != stages.len() {
            self.stage_sums = stages.iter().map(|&(name, _)| (name, 0.0)).collect();
            self.steps_summed = 0;
        }
        for (sum, (_, ms)) in self.stage_sums.iter_mut().zip(&stages) {
            sum.1 += ms;
        }
        self.steps_summed += 1;
    }

    pub fn body_count(&self) -> usize {
        self.loaded
            .as_ref()
            .map_or(0, |l| l.built.world.body_count())
    }

    pub(crate) fn body_at(&self, index: u32) -> Result<BodyId, WasmError> {
        let ids = self.world()?.body_ids();
        ids.get(index as usize).copied().ok_or_else(|| {
            WasmError::OutOfRange(format!(
                "body index {index}: there are {} bodies",
                ids.len()
            ))
        })
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
        let filled = self.fill_added(body, model as usize);
        if let Err(e) = filled.and_then(|()| self.tie_added(body, model as usize)) {
            // A balloon the page cannot fill or give its ribbon is not added.
            let _ = self.world_mut()?.remove_body(body);
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
        let last = *self.world()?.counters();
        let stages = if self.steps_summed > 0 {
            let n = f64::from(self.steps_summed);
            self.stage_sums
                .iter()
                .map(|&(name, sum)| (name.to_string(), sum / n))
                .collect()
        } else {
            last.stages()
                .iter()
                .map(|&(name, ms)| (name.to_string(), ms))
                .collect()
        };
        for sum in &mut self.stage_sums {
            sum.1 = 0.0;
        }
        self.steps_summed = 0;
        let world = self.world()?;
        let s = world.stats();
        Ok(EngineStats {
            stages,
            bodies: world.body_count() as u32,
            awake: s.awake_count,
            pairs: s.pair_count,
            contacts: s.contact_count,
            max_penetration: s.max_penetration,
            ribbons: world.ribbon_count() as u32,
            ribbon_max_stretch: world.ribbon_max_stretch(),
        })
    }
}

/// `Ok` when the page can hold `scene` (what `Scene`'s own validation does
/// not know): at most `CAPACITY` balloons, and a box room (a mesh room names
/// a file the browser cannot read).
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
    Ok(())
}

/// Reads and checks a scene in JSON as `load_json` would, without building it.
pub fn validate_json(text: &str) -> Result<(), WasmError> {
    check_for_browser(&Scene::from_json_str(text, WEB_SOURCE)?)
}

#[cfg(test)]
#[path = "state_tests.rs"]
mod tests;
