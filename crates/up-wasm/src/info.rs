//! What the page reads as plain objects rather than as views of memory: the
//! contract's constants, a built world's summary, the step's stats. Each is
//! a Rust struct whose TypeScript type tsify writes into the module's
//! `.d.ts`, so the page's types come from here.

use serde::Serialize;
use tsify_next::Tsify;
use up_scene::scene::{
    self as limits, DEFAULT_COLORS, DEFAULT_DIAMETER_M, MAX_SCENE_BYTES, METRES_PER_INCH,
};

use crate::contacts::{CONTACT_FLOATS, MAX_CONTACTS};
use crate::error::ERROR_KINDS;
use crate::gas::MAX_ADVANCE_S;
use crate::limits::{CAPACITY, MAX_SPEED, MAX_SPIN, MAX_STEPS_PER_CALL, POSE_FLOATS, TREE_FLOATS};
use crate::live::{LiveRange, LiveSetting};
use crate::model_mesh::MESH_VERTEX_FLOATS;
use crate::ribbons::{MAX_RIBBON_LENGTH_M, RIBBON_POINT_FLOATS};

/// A colour a scene may name, with its RGB in 0–1.
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
pub struct NamedColor {
    pub name: String,
    pub rgb: [f32; 3],
}

/// The accepted range of a `[sim]` key (`up_physics::limits`, which the
/// engine and the scene's checks read too).
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
pub struct SimLimit {
    /// The key under `sim` in a scene.
    pub key: String,
    pub min: f32,
    pub max: f32,
    /// Whether `min` itself is refused.
    pub min_exclusive: bool,
    pub unit: String,
}

/// Limits of a scene, from up-scene's validation (the page offers no more).
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
pub struct SceneLimits {
    pub max_total_balloons: f64,
    pub max_balloon_groups: u32,
    pub max_group_colors: u32,
    pub max_leaves: u32,
    /// Room width, depth and wall height, m.
    pub min_room_size_m: f32,
    pub max_room_size_m: f32,
    /// Balloon diameter, m.
    pub min_balloon_diameter_m: f32,
    pub max_balloon_diameter_m: f32,
    /// 2⁵³ − 1: exact as a JavaScript number.
    pub max_seed: f64,
    /// Largest scene text, bytes.
    pub max_scene_bytes: f64,
    /// A group's diameter when it names none, m.
    pub default_diameter_m: f32,
    pub metres_per_inch: f32,
    /// A group's colours when it names none.
    pub default_colors: Vec<String>,
    /// The ranges of the `[sim]` keys.
    pub sim: Vec<SimLimit>,
}

/// Every number and name the page and the engine must agree on, defined
/// once here (or in up-scene) and read by the page when the module starts.
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
#[tsify(into_wasm_abi)]
pub struct Constants {
    /// Floats per pose: x, y, z, qx, qy, qz, qw of the balloon's mesh frame.
    pub pose_stride: u32,
    /// Floats per contact: x, y, z, nx, ny, nz, separation, kind (1 balloon, 0 room).
    pub contact_stride: u32,
    /// Floats per sphere-tree node: cx, cy, cz, radius, depth, leaf (0/1).
    pub tree_stride: u32,
    /// Floats per ribbon point: x, y, z.
    pub ribbon_point_stride: u32,
    /// Floats per vertex of a model's surface (position or normal): x, y, z.
    pub mesh_vertex_stride: u32,
    /// Floats per probed body's forces (`forces.rs`).
    pub force_floats: u32,
    /// Width of the ribbon drawn, m (the engine's ribbon, 5 mm curling ribbon).
    pub ribbon_width_m: f32,
    /// Radius of a weight at a ribbon's free end, m (as it collides).
    pub weight_radius_m: f32,
    /// Longest ribbon `apply_live` ties, m.
    pub max_ribbon_length_m: f32,
    /// Most balloons the page's world holds.
    pub capacity: u32,
    /// Most contacts one `write_contacts` writes.
    pub max_contacts: u32,
    /// Most steps one `step` or `advance` call takes.
    pub max_steps_per_call: u32,
    /// Most simulated seconds one `advance` call covers.
    pub max_advance_s: f64,
    /// Fastest a balloon may be set moving, m/s, and spinning, rad/s.
    pub max_speed: f32,
    pub max_spin: f32,
    /// The colours a scene may name (besides `#rrggbb`), in palette order.
    pub colors: Vec<NamedColor>,
    /// The `name` of every error a refused call throws.
    pub error_kinds: Vec<String>,
    pub scene: SceneLimits,
    /// Each live control's accepted values (`Engine::apply_live`).
    pub live: Vec<LiveRange>,
    /// The air's strides and the ranges of the air tools (`air.rs`).
    pub air: crate::air::AirLimits,
}

impl Constants {
    pub fn get() -> Constants {
        let colors = up_scene::palette::PALETTE
            .iter()
            .map(|c| NamedColor {
                name: c.name.to_string(),
                rgb: c.rgb,
            })
            .collect();
        let strings = |v: &[&str]| v.iter().map(|s| s.to_string()).collect();
        Constants {
            pose_stride: POSE_FLOATS as u32,
            contact_stride: CONTACT_FLOATS as u32,
            tree_stride: TREE_FLOATS as u32,
            ribbon_point_stride: RIBBON_POINT_FLOATS as u32,
            mesh_vertex_stride: MESH_VERTEX_FLOATS as u32,
            force_floats: crate::forces::FORCE_FLOATS as u32,
            ribbon_width_m: up_physics::ribbon::RIBBON_WIDTH,
            weight_radius_m: up_physics::ribbon::WEIGHT_RADIUS,
            max_ribbon_length_m: MAX_RIBBON_LENGTH_M,
            capacity: CAPACITY as u32,
            max_contacts: MAX_CONTACTS as u32,
            max_steps_per_call: MAX_STEPS_PER_CALL,
            max_advance_s: MAX_ADVANCE_S,
            max_speed: MAX_SPEED,
            max_spin: MAX_SPIN,
            colors,
            error_kinds: strings(&ERROR_KINDS),
            live: LiveSetting::ranges(),
            air: crate::air::AirLimits::get(),
            scene: SceneLimits {
                max_total_balloons: limits::MAX_TOTAL_BALLOONS as f64,
                max_balloon_groups: limits::MAX_BALLOON_GROUPS as u32,
                max_group_colors: limits::MAX_GROUP_COLORS as u32,
                max_leaves: limits::MAX_SCENE_LEAVES,
                min_room_size_m: limits::MIN_ROOM_SIZE_M,
                max_room_size_m: limits::MAX_ROOM_SIZE_M,
                min_balloon_diameter_m: limits::MIN_BALLOON_DIAMETER_M,
                max_balloon_diameter_m: limits::MAX_BALLOON_DIAMETER_M,
                max_seed: limits::MAX_SEED as f64,
                max_scene_bytes: MAX_SCENE_BYTES as f64,
                default_diameter_m: DEFAULT_DIAMETER_M,
                metres_per_inch: METRES_PER_INCH,
                default_colors: strings(&DEFAULT_COLORS),
                sim: up_physics::limits::SIM_LIMITS
                    .iter()
                    .map(|(key, l)| SimLimit {
                        key: key.to_string(),
                        min: l.min,
                        max: l.max,
                        min_exclusive: l.min_exclusive,
                        unit: l.unit.to_string(),
                    })
                    .collect(),
            },
        }
    }
}

/// What a built world holds besides its bodies.
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
#[tsify(into_wasm_abi)]
pub struct WorldSummary {
    /// Linear RGB 0–1 of each colour index.
    pub colors: Vec<[f32; 3]>,
    /// Names of the colours as written in the scene (`red`, `#10a0ff`).
    pub color_names: Vec<String>,
    /// Diameter of each balloon model, m.
    pub diameters: Vec<f32>,
    /// Whether each balloon model is foil (drawn with `write_model_mesh`'s surface).
    pub foil: Vec<bool>,
    /// How each balloon model is drawn (`"latex"`, `"pearl"`, `"foil"`).
    pub finishes: Vec<up_scene::scene::Finish>,
    /// s per step.
    pub dt: f32,
}

/// Stage times and counts of the world's last steps.
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
#[tsify(into_wasm_abi)]
pub struct EngineStats {
    /// Stage name and milliseconds per step, in step order ("total" last).
    pub stages: Vec<(String, f64)>,
    pub bodies: u32,
    pub awake: u32,
    pub pairs: u32,
    pub contacts: u32,
    /// m
    pub max_penetration: f32,
    pub ribbons: u32,
    /// Largest relative stretch any ribbon ended a step with since the world was built.
    pub ribbon_max_stretch: f32,
    /// Each thread's busy, barrier and idle ms a step in each stage over the
    /// same steps, "total" last: empty unless `set_thread_timing(true)`.
    pub threads: Vec<crate::thread_stats::StageThreadTimes>,
}
