//! A thin WebAssembly layer over up-physics and up-scene for the web app.
//!
//! The contract with the page is written here once and crosses through
//! wasm-bindgen: `wasm-bindgen --target web` writes the JS glue and a `.d.ts`
//! from these exports, and tsify writes the TypeScript types of the scene
//! (up-scene's structs) and of every object returned here into that `.d.ts`.
//!
//! - `constants()` returns every number and name the page must agree with:
//!   strides of the bulk views, capacity and limits, the named colours with
//!   their RGB, the error kinds, the scene limits of up-scene's validation.
//!   The page reads it at start instead of keeping copies.
//!   The strides are also TypeScript literal types (`PoseStride`, ...) in the
//!   `.d.ts`, so a page whose constants differ does not compile.
//! - `validate_scene(json)` reads and checks a scene exactly as
//!   `Engine::load_scene_json` would, without building it: the page's only
//!   scene validation.
//! - `Engine` owns one world. A refused call throws a JS `Error` whose
//!   `name` is one of `constants().error_kinds` and whose message starts
//!   with the method's name (scene errors name the scene and key instead);
//!   a refused call leaves the world as it was. Bad arguments (NaN, out of
//!   range, too fast, too many) are errors, never traps.
//! - Bulk data (poses, colours, contacts, the room, trees, a model's
//!   surface) are read as views of wasm memory, one view per array, never
//!   one call per body: a `write_*` call fills the array and returns its
//!   length (floats of poses, bodies, contacts, tree nodes or mesh vertices:
//!   see each), the room's arrays have
//!   `*_len()`, and the view is that many elements (times the stride) at
//!   `*_ptr()` in the module's `memory`. A view is valid until the next call
//!   (memory may grow and move).
//! - The stage timers of up-physics read `up_now_ms() -> f64` (ms,
//!   monotonic), which `clock.rs` defines on the host's `performance.now()`.
//! - A live panel control is one `LiveSetting` (`live.rs`) given to
//!   `Engine::apply_live`; the page forwards it untouched.
//!
//! The files depend one way: `lib.rs` (the exports) → `state.rs` (the world
//! and the page's buffers; one thin method per call) → the feature files
//! (`export`, `forces`, `gas`, `live`, `model_mesh`, `ribbons`, `squash`, `contacts`,
//! `stats`), each free functions or a small buffer struct of its own on a
//! `&World` or `&Loaded` (`loaded.rs`; `ribbon_links` on the page's own copy
//! of the ribbons' points, needing no world) → up-scene and up-physics. No feature
//! file knows `State`; the numbers they share live in `limits.rs`. Physics
//! models (the squash of a balloon) are up-scene's, so that the CLI can use
//! them; this crate only packs what they give for the page.
//!
//! SI units, Y up, origin at the centre of the floor.

mod air;
mod air_bindings;
mod body_hashes;
#[cfg(target_arch = "wasm32")]
mod clock;
mod contacts;
mod error;
mod export;
mod forces;
mod furniture;
mod gas;
mod info;
mod limits;
mod live;
mod loaded;
mod model_mesh;
mod ribbon_links;
mod ribbons;
mod squash;
mod state;
mod stats;
mod thread_stats;
#[cfg(feature = "threads")]
mod threads;

use glam::Vec3;
use wasm_bindgen::prelude::*;

pub use air::{
    AirCommand, AirGrid, FanDef, AIR_GRID_FLOATS, AIR_SOURCE_FLOATS, MAX_AIR_GRID_AXIS,
    MAX_AIR_SOURCES,
};
pub use contacts::{CONTACT_FLOATS, MAX_CONTACTS};
pub use error::{CallError, WasmError, ERROR_KINDS};
pub use export::EXPORT_SECONDS;
pub use forces::{BodyCard, BodyGas, FORCE_FLOATS, PROBE_ALL, PROBE_OFF};
pub use gas::{AdvanceReport, FloatCounts, GroupFloat, MAX_ADVANCE_S};
pub use info::{Constants, EngineStats, NamedColor, SceneLimits, WorldSummary};
pub use live::{LiveRange, LiveSetting, MAX_LIVE_GRAVITY};
pub use model_mesh::{MeshBuffers, MESH_VERTEX_FLOATS};
pub use ribbon_links::{ribbon_linking, ribbon_links};
pub use ribbons::{pack_rgb, MAX_RIBBON_LENGTH_M, RIBBON_POINT_FLOATS};
pub use squash::{MEMBRANE_OVERPRESSURE_PA, SQUASH_FLOATS};
pub use state::{
    State, CAPACITY, MAX_SPEED, MAX_SPIN, MAX_STEPS_PER_CALL, POSE_FLOATS, TREE_FLOATS,
};

pub use thread_stats::{set_thread_timing, StageThreadTimes};
#[cfg(feature = "threads")]
pub use threads::{init_thread_pool, init_thread_pool_here, set_keep_threads_awake, thread_count};

use error::named;

/// The strides as literal types in the `.d.ts`: the page's own stride
/// constants are typed with them, so they cannot drift from these (the test
/// below holds this text to the Rust constants).
#[allow(dead_code)] // read at compile time by the custom section below, and by the test
const STRIDE_TYPES: &str = r#"
/** Floats per pose: x, y, z, qx, qy, qz, qw (`constants().pose_stride`). */
export type PoseStride = 7;
/** Floats per contact: x, y, z, nx, ny, nz, separation, kind (`constants().contact_stride`). */
export type ContactStride = 8;
/** Floats per sphere-tree node: cx, cy, cz, radius, depth, leaf (`constants().tree_stride`). */
export type TreeStride = 6;
/** Floats per ribbon point: x, y, z (`constants().ribbon_point_stride`). */
export type RibbonPointStride = 3;
/** Floats per mesh vertex position or normal: x, y, z (`constants().mesh_vertex_stride`). */
export type MeshVertexStride = 3;
/** Floats per probed body: index, 6 forces, 3 points, xyz each (`constants().force_floats`). */
export type ForceStride = 28;
/** Floats per body of the squash table: nx·d, ny·d, nz·d, reach (`write_body_squash`). */
export type SquashStride = 4;
/** Floats per air source: kind, outlet xyz, aim xyz, speed now, full speed, diameter, sweep rad, sweep period s (`write_air_sources`). */
export type AirSourceStride = 12;
/** Floats per cell of the sampled air: ux, uy, uz, |u| (`write_air_grid`). */
export type AirGridStride = 4;
"#;

#[wasm_bindgen(typescript_custom_section)]
const STRIDE_TYPES_TS: &str = STRIDE_TYPES;

/// Every number and name the page and the engine must agree on.
#[wasm_bindgen]
pub fn constants() -> Constants {
    Constants::get()
}

/// Reads and checks a scene in JSON as `Engine::load_scene_json` does,
/// without building it; throws the engine's message when it is refused.
#[wasm_bindgen]
pub fn validate_scene(json: &str) -> Result<(), CallError> {
    named("validate_scene", state::validate_json(json))
}

/// The default scene (the original UP room) as JSON, every default written out.
#[wasm_bindgen]
pub fn default_scene_json() -> Result<String, CallError> {
    named(
        "default_scene_json",
        up_scene::scene::Scene::default()
            .to_json_string()
            .map_err(WasmError::from),
    )
}

/// One simulated room and what the page reads from it.
#[wasm_bindgen]
#[derive(Default)]
pub struct Engine {
    state: State,
}

#[wasm_bindgen]
impl Engine {
    /// An engine without a world: load a scene first.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Engine {
        Engine::default()
    }

    // ---- building a world ----

    /// Builds the world from a scene in JSON; on error the old world stays.
    pub fn load_scene_json(&mut self, json: &str) -> Result<(), CallError> {
        named("load_scene_json", self.state.load_json(json))
    }

    /// Builds the world from a scene in TOML; on error the old world stays.
    pub fn load_scene_toml(&mut self, toml: &str) -> Result<(), CallError> {
        named("load_scene_toml", self.state.load_toml(toml))
    }

    /// Builds the default scene (the original UP room).
    pub fn load_default_scene(&mut self) -> Result<(), CallError> {
        named("load_default_scene", self.state.load_default())
    }

    /// The loaded scene as JSON, every default written out.
    pub fn scene_json(&self) -> Result<String, CallError> {
        named("scene_json", self.state.scene_json())
    }

    /// Palette, colour names, model diameters and dt of the loaded world.
    pub fn world_info(&self) -> Result<WorldSummary, CallError> {
        named("world_info", self.state.world_info())
    }

    // ---- stepping and reading ----

    /// Takes `n` fixed steps (at most `MAX_STEPS_PER_CALL`).
    pub fn step(&mut self, n: u32) -> Result<(), CallError> {
        named("step", self.state.step(n))
    }

    /// Advances `seconds` of simulated time (at most `MAX_ADVANCE_S`), taking
    /// fixed steps while anything moves and jumping the gas alone while
    /// everything sleeps, in at most `max_steps` steps (at most
    /// `MAX_STEPS_PER_CALL`); says how far it got. Deterministic.
    pub fn advance(&mut self, seconds: f64, max_steps: u32) -> Result<AdvanceReport, CallError> {
        named("advance", self.state.advance(seconds, max_steps))
    }

    /// Simulated seconds since the world was built (0 without one).
    pub fn sim_time(&self) -> f64 {
        self.state.sim_time()
    }

    /// The room's air temperature now, °C (a scene's schedule applied).
    pub fn air_temperature_c(&self) -> Result<f32, CallError> {
        named("air_temperature_c", self.state.air_temperature_c())
    }

    /// Writes every body's size over its shape's (1 for a body without gas),
    /// dense order, for `body_scales_ptr`; returns how many bodies.
    pub fn write_body_scales(&mut self) -> Result<u32, CallError> {
        named("write_body_scales", self.state.write_body_scales())?;
        Ok(self.state.scales.len() as u32)
    }

    pub fn body_scales_ptr(&self) -> *const f32 {
        self.state.scales.as_ptr()
    }

    /// Writes each body's deepest dent since the last call, `SQUASH_FLOATS`
    /// per body, dense order (`squash.rs`), for `body_squash_ptr`; returns
    /// how many bodies. Drawing only: the physics stays rigid.
    pub fn write_body_squash(&mut self) -> Result<u32, CallError> {
        named("write_body_squash", self.state.write_body_squash())?;
        Ok((self.state.squash.out.len() / SQUASH_FLOATS) as u32)
    }

    pub fn body_squash_ptr(&self) -> *const f32 {
        self.state.squash.out.as_ptr()
    }

    /// Where the balloons float now (at the ceiling, hovering, on the floor),
    /// per group and in all; each call is a look the census remembers (how
    /// high each balloon has been), so call it at a steady pace.
    pub fn float_counts(&mut self) -> Result<FloatCounts, CallError> {
        named("float_counts", self.state.float_counts())
    }

    /// Bodies in the world (0 without one).
    pub fn body_count(&self) -> u32 {
        self.state.body_count() as u32
    }

    /// Writes every pose (`POSE_FLOATS` each, dense order) for `poses_ptr`;
    /// returns how many floats were written.
    pub fn write_poses(&mut self) -> Result<u32, CallError> {
        named("write_poses", self.state.write_poses())?;
        Ok(self.state.poses.len() as u32)
    }

    pub fn poses_ptr(&self) -> *const f32 {
        self.state.poses.as_ptr()
    }

    /// Writes every body's colour index and model index for
    /// `colors_ptr`/`models_ptr`; returns how many bodies.
    pub fn write_colors_and_models(&mut self) -> Result<u32, CallError> {
        named("write_colors_and_models", self.state.write_user_data())?;
        Ok(self.state.colors.len() as u32)
    }

    pub fn colors_ptr(&self) -> *const u32 {
        self.state.colors.as_ptr()
    }

    pub fn models_ptr(&self) -> *const u32 {
        self.state.models.as_ptr()
    }

    /// Writes the last step's contact points for `contacts_ptr`, at most
    /// `max` of them (and at most `MAX_CONTACTS`), `CONTACT_FLOATS` each;
    /// returns how many were written (`contact_total` counts them all).
    pub fn write_contacts(&mut self, max: u32) -> Result<u32, CallError> {
        named("write_contacts", self.state.write_contacts(max))?;
        Ok((self.state.contacts.len() / CONTACT_FLOATS) as u32)
    }

    pub fn contacts_ptr(&self) -> *const f32 {
        self.state.contacts.as_ptr()
    }

    /// Contacts the last step had in all when `write_contacts` ran (written or not).
    pub fn contact_total(&self) -> u32 {
        self.state.contact_total as u32
    }

    /// FNV-1a of the whole body state (determinism checks); 0 without a world.
    pub fn state_hash(&self) -> u64 {
        self.state.world().map_or(0, |w| w.state_hash())
    }

    /// Per-stage milliseconds averaged over the steps since the last call, and counts.
    pub fn stats(&mut self) -> Result<EngineStats, CallError> {
        named("stats", self.state.stats())
    }

    // ---- changing the world ----

    /// Applies a live setting (`{ control, value }`: `LiveSetting`) to the
    /// running world, and writes it into the scene `scene_json` returns;
    /// refused outside `constants().live`'s range for it.
    pub fn apply_live(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "LiveSetting")] setting: JsValue,
    ) -> Result<(), CallError> {
        // Read here rather than by tsify's conversion, so that a setting the
        // engine does not know is refused like any bad argument.
        let setting = serde_wasm_bindgen::from_value::<LiveSetting>(setting)
            .map_err(|e| WasmError::BadArgument(format!("live setting: {e}")));
        named("apply_live", setting.and_then(|s| self.state.apply_live(s)))
    }

    /// Adds an upright balloon of model `model` with its mesh frame at (x, y, z), m.
    pub fn add_balloon(
        &mut self,
        x: f32,
        y: f32,
        z: f32,
        color: u32,
        model: u32,
    ) -> Result<(), CallError> {
        named(
            "add_balloon",
            self.state.add_balloon(Vec3::new(x, y, z), color, model),
        )
    }

    /// Adds a balloon of the first model standing on the floor at (x, z), m.
    pub fn add_balloon_on_floor(&mut self, x: f32, z: f32, color: u32) -> Result<(), CallError> {
        named(
            "add_balloon_on_floor",
            self.state.add_balloon_on_floor(x, z, color),
        )
    }

    /// Pops the body at dense `index`: the last body takes its place.
    pub fn remove(&mut self, index: u32) -> Result<(), CallError> {
        named("remove", self.state.remove(index))
    }

    /// Applies an impulse (N·s) at a world point (m) to the body at dense `index`.
    #[allow(clippy::too_many_arguments)]
    pub fn apply_impulse(
        &mut self,
        index: u32,
        ix: f32,
        iy: f32,
        iz: f32,
        px: f32,
        py: f32,
        pz: f32,
    ) -> Result<(), CallError> {
        named(
            "apply_impulse",
            self.state
                .apply_impulse(index, Vec3::new(ix, iy, iz), Vec3::new(px, py, pz)),
        )
    }

    /// Sets the velocity (m/s) and angular velocity (rad/s) of the body at dense `index`.
    #[allow(clippy::too_many_arguments)]
    pub fn set_velocity(
        &mut self,
        index: u32,
        vx: f32,
        vy: f32,
        vz: f32,
        wx: f32,
        wy: f32,
        wz: f32,
    ) -> Result<(), CallError> {
        named(
            "set_velocity",
            self.state
                .set_velocity(index, Vec3::new(vx, vy, vz), Vec3::new(wx, wy, wz)),
        )
    }

    /// Ribbons in the world (0 without one).
    pub fn ribbon_count(&self) -> u32 {
        self.state.ribbon_count() as u32
    }

    /// Points of all ribbons together (floats at `ribbon_points_ptr` after
    /// `write_ribbon_points`: this times `RIBBON_POINT_FLOATS`).
    pub fn ribbon_point_count(&self) -> u32 {
        self.state
            .world()
            .map_or(0, |w| w.ribbon_point_count() as u32)
    }

    /// Writes every ribbon's points (`RIBBON_POINT_FLOATS` each, ribbon after
    /// ribbon, the knot first) for `ribbon_points_ptr`; returns how many floats.
    pub fn write_ribbon_points(&mut self) -> Result<u32, CallError> {
        named("write_ribbon_points", self.state.write_ribbon_points())?;
        Ok(self.state.ribbons.points.len() as u32)
    }

    pub fn ribbon_points_ptr(&self) -> *const f32 {
        self.state.ribbons.points.as_ptr()
    }

    /// Writes, per ribbon in the order of the points: its first point
    /// (`ribbon_offsets_ptr`, one more entry at the end: the total), the
    /// dense index of its balloon (`ribbon_bodies_ptr`), its colour,
    /// 0xRRGGBB sRGB (`ribbon_colors_ptr`) and the weight at its free end, kg,
    /// 0 for none (`ribbon_weights_ptr`); returns the ribbon count.
    pub fn write_ribbons(&mut self) -> Result<u32, CallError> {
        named("write_ribbons", self.state.write_ribbon_tables())?;
        Ok(self.state.ribbons.bodies.len() as u32)
    }

    pub fn ribbon_offsets_ptr(&self) -> *const u32 {
        self.state.ribbons.offsets.as_ptr()
    }

    pub fn ribbon_bodies_ptr(&self) -> *const u32 {
        self.state.ribbons.bodies.as_ptr()
    }

    pub fn ribbon_colors_ptr(&self) -> *const u32 {
        self.state.ribbons.colors.as_ptr()
    }

    pub fn ribbon_weights_ptr(&self) -> *const f32 {
        self.state.ribbons.weights.as_ptr()
    }

    /// The first group's ribbon length, m (0: none), as the scene or
    /// `apply_live` set it.
    pub fn ribbon_length(&self) -> f32 {
        self.state.ribbon_length()
    }

    /// Holds point `point` of ribbon `ribbon` (ribbon order; its free end is
    /// its point count less one) and pulls it toward (x, y, z), m, then
    /// toward each `drag_to`; `release` lets go. Its balloon follows.
    pub fn grab_ribbon(
        &mut self,
        ribbon: u32,
        point: u32,
        x: f32,
        y: f32,
        z: f32,
    ) -> Result<(), CallError> {
        named(
            "grab_ribbon",
            self.state.grab_ribbon(ribbon, point, Vec3::new(x, y, z)),
        )
    }

    /// Holds the body at dense `index` by the world point (x, y, z) on it, m.
    pub fn grab(&mut self, index: u32, x: f32, y: f32, z: f32) -> Result<(), CallError> {
        named("grab", self.state.grab(index, Vec3::new(x, y, z)))
    }

    /// Moves the grab target, m (no effect when nothing is held).
    pub fn drag_to(&mut self, x: f32, y: f32, z: f32) -> Result<(), CallError> {
        named("drag_to", self.state.drag_to(Vec3::new(x, y, z)))
    }

    /// Lets go of the held body, which keeps its velocity (a throw).
    pub fn release(&mut self) -> Result<(), CallError> {
        named("release", self.state.release())
    }

    // ---- the glTF export (`export.rs`) ----

    /// Records the world now into the export's ring (the last
    /// `EXPORT_SECONDS` of simulated time): the worker calls it for each frame it sends.
    pub fn record_export_frame(&mut self) -> Result<(), CallError> {
        named("record_export_frame", self.state.record_export_frame())
    }

    /// The ring's frames as an animated glTF 2.0 binary (`.glb`), as `up export-gltf` writes one.
    pub fn export_gltf(&self) -> Result<Vec<u8>, CallError> {
        named("export_gltf", self.state.export.glb())
    }

    // ---- the force probe (`forces.rs`) ----

    /// What the next steps record for `write_forces`: -1 no body (the
    /// default, at no cost to the step), -2 every body, otherwise one
    /// body's dense index in the current frame's order.
    pub fn set_force_probe(&mut self, which: i32) -> Result<(), CallError> {
        named("set_force_probe", self.state.set_force_probe(which))
    }

    /// Writes the last step's forces on the probed bodies for `forces_ptr`,
    /// `FORCE_FLOATS` each (`constants().force_floats`); returns how many bodies.
    pub fn write_forces(&mut self) -> Result<u32, CallError> {
        named("write_forces", self.state.write_forces()).map(|n| n as u32)
    }

    pub fn forces_ptr(&self) -> *const f32 {
        self.state.forces.as_ptr()
    }

    /// The figures of the balloon at dense index `index`, now.
    pub fn body_card(&self, index: u32) -> Result<BodyCard, CallError> {
        named("body_card", self.state.body_card(index))
    }

    // ---- static data: room and balloon models ----

    /// Floats at `room_vertices_ptr`: x, y, z per vertex.
    pub fn room_vertices_len(&self) -> u32 {
        self.state.room_vertices.len() as u32
    }

    pub fn room_vertices_ptr(&self) -> *const f32 {
        self.state.room_vertices.as_ptr()
    }

    /// Indices at `room_triangles_ptr`: three per triangle, counter-clockwise seen from inside.
    pub fn room_triangles_len(&self) -> u32 {
        self.state.room_triangles.len() as u32
    }

    pub fn room_triangles_ptr(&self) -> *const u32 {
        self.state.room_triangles.as_ptr()
    }

    /// Balloon models (one per group) of the loaded world.
    pub fn model_count(&self) -> u32 {
        self.state.model_count() as u32
    }

    /// Writes model `model`'s sphere tree (root first, `TREE_FLOATS` per
    /// node) for `tree_ptr`; returns the node count.
    pub fn write_model_tree(&mut self, model: u32) -> Result<u32, CallError> {
        named("write_model_tree", self.state.write_tree(model)).map(|n| n as u32)
    }

    pub fn tree_ptr(&self) -> *const f32 {
        self.state.tree.as_ptr()
    }

    /// Writes model `model`'s surface, body frame, for `mesh_positions_ptr`
    /// and `mesh_normals_ptr` (`MESH_VERTEX_FLOATS` per vertex) and
    /// `mesh_indices_ptr` (three per triangle, counter-clockwise seen from
    /// outside, `mesh_index_len` of them); returns the vertex count. The page
    /// draws foil models (`world_info().foil`) with it.
    pub fn write_model_mesh(&mut self, model: u32) -> Result<u32, CallError> {
        named("write_model_mesh", self.state.write_model_mesh(model)).map(|n| n as u32)
    }

    pub fn mesh_positions_ptr(&self) -> *const f32 {
        self.state.mesh.positions.as_ptr()
    }

    pub fn mesh_normals_ptr(&self) -> *const f32 {
        self.state.mesh.normals.as_ptr()
    }

    /// Indices at `mesh_indices_ptr` after `write_model_mesh`.
    pub fn mesh_index_len(&self) -> u32 {
        self.state.mesh.indices.len() as u32
    }

    pub fn mesh_indices_ptr(&self) -> *const u32 {
        self.state.mesh.indices.as_ptr()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stride_types_are_the_rust_constants() {
        for (name, value) in [
            ("PoseStride", POSE_FLOATS),
            ("ContactStride", CONTACT_FLOATS),
            ("ForceStride", FORCE_FLOATS),
            ("TreeStride", TREE_FLOATS),
            ("RibbonPointStride", RIBBON_POINT_FLOATS),
            ("MeshVertexStride", MESH_VERTEX_FLOATS),
            ("SquashStride", SQUASH_FLOATS),
            ("AirSourceStride", AIR_SOURCE_FLOATS),
            ("AirGridStride", AIR_GRID_FLOATS),
        ] {
            let line = format!("export type {name} = {value};");
            assert!(STRIDE_TYPES.contains(&line), "{line} in {STRIDE_TYPES}");
        }
    }
}
