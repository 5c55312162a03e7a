//! Moving air as the page sees it: the sources drawn in the room (one row of
//! floats a source), the field sampled on a coarse grid of the room or at
//! given points (for "show air" and the balloon card), and the commands of
//! the panel's air tools (`AirCommand`: add a fan, set its speed, remove it,
//! open the door for a while), applied to the running world. The field and
//! its sources are the engine's (`up_physics::air`); nothing here models air.
//!
//! Fans are named by their index among the world's jets (fans and vents
//! together, in the order `write_sources` lists them); removing one moves
//! the later ones down by one.

use glam::Vec3;
use serde::{Deserialize, Serialize};
use tsify_next::Tsify;
use up_physics::air::{Draught, Jet, JetKind, Schedule, Sweep, SPIN_UP_S};
use up_physics::World;
use up_scene::scene::{DraughtSpec, JetSpec};

use crate::error::{finite, WasmError};
use crate::loaded::Loaded;

/// Floats per source row: kind (`SOURCE_FAN`, `SOURCE_VENT`,
/// `SOURCE_DRAUGHT`), outlet x y z (m), aim now x y z (unit), outlet speed
/// now (m/s, its schedule applied), full outlet speed (m/s), outlet diameter
/// (m), total sweep (rad), sweep period (s; 0 without a sweep).
pub const AIR_SOURCE_FLOATS: usize = 12;
/// `kind` of a source row.
pub const SOURCE_FAN: f32 = 0.0;
pub const SOURCE_VENT: f32 = 1.0;
pub const SOURCE_DRAUGHT: f32 = 2.0;
/// Floats per cell of the sampled grid: ux, uy, uz (m/s), |u|.
pub const AIR_GRID_FLOATS: usize = 4;
/// Most cells along one axis of the sampled grid: 64³ cells is 4 MiB of
/// floats, past anything a coarse picture of the room needs.
pub const MAX_AIR_GRID_AXIS: u32 = 64;
/// Most points one `write_air_at` samples.
pub const MAX_AIR_POINTS: usize = 100_000;
/// Most fans, vents and draughts the page's world holds: each is drawn and
/// summed at every drag, so a room of them would only cost.
pub const MAX_AIR_SOURCES: usize = 32;

/// The page's door: an opening in the middle of the wall at +z, this wide
/// and high (m, at most nine tenths of the wall), letting air in at this
/// speed (m/s): a gentle draught through an open door is 0.5 to 1 m/s.
pub const DOOR_WIDTH_M: f32 = 0.9;
pub const DOOR_HEIGHT_M: f32 = 2.0;
pub const DOOR_SPEED_M_S: f32 = 0.8;
/// The opening's depth along the wall's normal, m (the draught's box).
const DOOR_DEPTH_M: f32 = 0.1;
/// Longest the page's door stays open, s.
pub const MAX_DOOR_S: f32 = 600.0;

/// Fastest and widest a fan may be, as a scene's fan (`Jet::validate`).
pub const MAX_FAN_SPEED_M_S: f32 = 30.0;
pub const MIN_FAN_DIAMETER_M: f32 = 0.05;
pub const MAX_FAN_DIAMETER_M: f32 = 3.0;
pub const MAX_FAN_SWEEP_DEG: f32 = 180.0;

/// The air's strides and limits, for the page (`constants().air`).
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
pub struct AirLimits {
    /// Floats per source row (`write_air_sources`).
    pub source_stride: u32,
    /// Floats per grid cell (`write_air_grid`).
    pub grid_stride: u32,
    pub max_grid_axis: u32,
    pub max_sources: u32,
    /// A fan's outlet speed, m/s, [0, max].
    pub max_fan_speed_m_s: f32,
    /// A fan's outlet diameter, m, (min, max].
    pub min_fan_diameter_m: f32,
    pub max_fan_diameter_m: f32,
    /// A fan's total sweep, degrees, [0, max].
    pub max_fan_sweep_deg: f32,
    /// The page's door: how long it stays open at most, s, and how fast the air comes in, m/s.
    pub max_door_s: f32,
    pub door_speed_m_s: f32,
}

impl AirLimits {
    pub fn get() -> AirLimits {
        AirLimits {
            source_stride: AIR_SOURCE_FLOATS as u32,
            grid_stride: AIR_GRID_FLOATS as u32,
            max_grid_axis: MAX_AIR_GRID_AXIS,
            max_sources: MAX_AIR_SOURCES as u32,
            max_fan_speed_m_s: MAX_FAN_SPEED_M_S,
            min_fan_diameter_m: MIN_FAN_DIAMETER_M,
            max_fan_diameter_m: MAX_FAN_DIAMETER_M,
            max_fan_sweep_deg: MAX_FAN_SWEEP_DEG,
            max_door_s: MAX_DOOR_S,
            door_speed_m_s: DOOR_SPEED_M_S,
        }
    }
}

/// The page's views of the air, refilled by each call.
#[derive(Default)]
pub struct AirBuffers {
    /// `AIR_SOURCE_FLOATS` a source (`write_sources`).
    pub sources: Vec<f32>,
    /// `AIR_GRID_FLOATS` a cell (`write_grid`).
    pub grid: Vec<f32>,
    /// x, y, z a point (`write_at`).
    pub points: Vec<f32>,
}

/// A fan the page places, as the fan tool makes it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, Tsify)]
pub struct FanDef {
    /// The outlet's centre, m.
    pub position: [f32; 3],
    /// Where it blows (normalised by the engine).
    pub direction: [f32; 3],
    /// Outlet diameter, m, (0.05, 3].
    pub diameter_m: f32,
    /// Outlet speed, m/s, [0, 30].
    pub speed_m_s: f32,
    /// Total swing about the vertical, degrees, [0, 180] (0: it does not sweep).
    pub sweep_deg: f32,
    /// One swing there and back, s, (0, 600] when it sweeps.
    pub sweep_period_s: f32,
}

/// What the panel's air tools ask of the running world; written to the page
/// by tsify as `{ command: "add_fan", fan: {…} } | { command: "set_fan_speed", … } | …`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, Tsify)]
#[serde(tag = "command", rename_all = "snake_case")]
pub enum AirCommand {
    /// Adds a fan (at the end of the jets), on from now.
    AddFan { fan: FanDef },
    /// Sets jet `fan`'s full outlet speed, m/s.
    SetFanSpeed { fan: u32, speed_m_s: f32 },
    /// Removes jet `fan`.
    RemoveFan { fan: u32 },
    /// Opens the page's door (`DOOR_*`) for `seconds` from now: a draught
    /// that spins up and down over `SPIN_UP_S`.
    OpenDoor { seconds: f32 },
}

/// Where and how finely `write_grid` sampled the field.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Tsify)]
#[tsify(into_wasm_abi)]
pub struct AirGrid {
    /// Cells along x, y, z; x runs fastest, then y, then z.
    pub dims: [u32; 3],
    /// The box the cells tile (the room's bounds), m; cell (i, j, k)'s
    /// centre is min + ((i, j, k) + ½)·(max − min)/dims.
    pub min: [f32; 3],
    pub max: [f32; 3],
    /// Simulated time of the sample, s.
    pub time_s: f64,
    /// Whether the room has any source at all (without one the field is zero).
    pub moving: bool,
}

/// Applies `command` to the loaded world; refused, with nothing changed,
/// when an argument is not a number, out of its range, or names no fan.
pub fn apply(loaded: &mut Loaded, command: AirCommand) -> Result<(), WasmError> {
    let world = &mut loaded.built.world;
    let mut flow = world.air_flow().clone();
    // The scene mirrors every change, so that a rebuilt world and a share
    // link keep the page's fans: its jets list fans then vents, as the
    // world's do (`up_scene::build::air`).
    let scene = &mut loaded.scene;
    let scene_fans = scene.fans.len();
    let count = flow.jets.len() + flow.draughts.len();
    match command {
        AirCommand::AddFan { fan } => {
            if count >= MAX_AIR_SOURCES {
                return Err(WasmError::Full(format!(
                    "add_fan: the room has {count} air sources, the page's most"
                )));
            }
            let jet = fan_jet(&fan, loaded.built.room.bounds())?;
            flow.jets.insert(scene_fans, jet);
            scene.fans.push(fan_spec(&fan));
        }
        AirCommand::SetFanSpeed { fan, speed_m_s } => {
            finite("set_fan_speed", &[speed_m_s])?;
            let jet = jet_mut(&mut flow.jets, fan)?;
            jet.speed = speed_m_s;
            // The scene's own range (`Jet::validate`), named as the page knows it.
            jet.validate()
                .map_err(|e| WasmError::OutOfRange(format!("set_fan_speed: {e}")))?;
            if let Some(spec) = scene_jet(scene, fan) {
                spec.speed_m_s = Some(speed_m_s);
            }
        }
        AirCommand::RemoveFan { fan } => {
            jet_mut(&mut flow.jets, fan)?;
            flow.jets.remove(fan as usize);
            let i = fan as usize;
            if i < scene_fans {
                scene.fans.remove(i);
            } else if i - scene_fans < scene.vents.len() {
                scene.vents.remove(i - scene_fans);
            }
        }
        AirCommand::OpenDoor { seconds } => {
            finite("open_door", &[seconds])?;
            if !(seconds > 0.0 && seconds <= MAX_DOOR_S) {
                return Err(WasmError::OutOfRange(format!(
                    "open_door: {seconds} s: expected (0, {MAX_DOOR_S}]"
                )));
            }
            let now = world.time();
            // Draughts that have stopped for good blow nothing; a page that
            // opens the door often would otherwise pile them up.
            flow.draughts.retain(|d| !has_ended(&d.schedule, now));
            if flow.jets.len() + flow.draughts.len() >= MAX_AIR_SOURCES {
                return Err(WasmError::Full(format!(
                    "open_door: the room has {count} air sources, the page's most"
                )));
            }
            let door = door(&scene.room, loaded.built.room.bounds(), now, seconds);
            scene
                .draughts
                .retain(|d| !has_ended(&Schedule { on: d.on.clone() }, now));
            scene.draughts.push(DraughtSpec {
                min: door.min.to_array(),
                max: door.max.to_array(),
                velocity_m_s: door.velocity.to_array(),
                on: door.schedule.on.clone(),
            });
            flow.draughts.push(door);
        }
    }
    world.set_air_flow(flow);
    Ok(())
}

/// The jet of a placed fan, checked as a scene's fan is.
fn fan_jet(fan: &FanDef, bounds: up_geom::Aabb) -> Result<Jet, WasmError> {
    let numbers = [
        fan.position.as_slice(),
        fan.direction.as_slice(),
        &[
            fan.diameter_m,
            fan.speed_m_s,
            fan.sweep_deg,
            fan.sweep_period_s,
        ],
    ]
    .concat();
    finite("add_fan", &numbers)?;
    let position = Vec3::from(fan.position);
    if position.cmplt(bounds.min).any() || position.cmpgt(bounds.max).any() {
        return Err(WasmError::OutOfRange(format!(
            "add_fan: position {position}: expected a point inside the room, from {} to {} m",
            bounds.min, bounds.max
        )));
    }
    let mut jet = Jet::new(
        JetKind::Fan,
        position,
        Vec3::from(fan.direction),
        fan.diameter_m,
        fan.speed_m_s,
    );
    jet.sweep = Sweep {
        angle_rad: fan.sweep_deg.to_radians(),
        period_s: fan.sweep_period_s,
    };
    jet.validate()
        .map_err(|e| WasmError::OutOfRange(format!("add_fan: {e}")))?;
    Ok(jet)
}

/// A placed fan as the scene writes it.
fn fan_spec(fan: &FanDef) -> JetSpec {
    JetSpec {
        position: fan.position,
        direction: Some(fan.direction),
        diameter_m: Some(fan.diameter_m),
        speed_m_s: Some(fan.speed_m_s),
        sweep_deg: fan.sweep_deg,
        sweep_period_s: fan.sweep_period_s,
        on: Vec::new(),
    }
}

/// The scene's entry of the world's jet `fan`, if the scene lists it.
fn scene_jet(scene: &mut up_scene::scene::Scene, fan: u32) -> Option<&mut JetSpec> {
    let (i, fans) = (fan as usize, scene.fans.len());
    if i < fans {
        scene.fans.get_mut(i)
    } else {
        scene.vents.get_mut(i - fans)
    }
}

/// Jet `fan`, or `OutOfRange` naming how many there are.
fn jet_mut(jets: &mut [Jet], fan: u32) -> Result<&mut Jet, WasmError> {
    let n = jets.len();
    jets.get_mut(fan as usize)
        .ok_or_else(|| WasmError::OutOfRange(format!("fan {fan}: the room has {n} fans and vents")))
}

/// Whether every interval of `schedule` ended, its run-down included, before `now`.
fn has_ended(schedule: &Schedule, now: f64) -> bool {
    !schedule.on.is_empty() && schedule.on.iter().all(|&[_, end]| end + SPIN_UP_S < now)
}

/// The page's door in the wall at +z of `room` (its `bounds`), open from
/// `now` for `seconds`, air coming in along −z.
fn door(
    room: &up_scene::scene::RoomSpec,
    bounds: up_geom::Aabb,
    now: f64,
    seconds: f32,
) -> Draught {
    let width = DOOR_WIDTH_M.min(0.9 * (bounds.max.x - bounds.min.x));
    let height = DOOR_HEIGHT_M.min(0.9 * room.wall_height.min(bounds.max.y - bounds.min.y));
    let x = 0.5 * (bounds.min.x + bounds.max.x);
    Draught {
        min: Vec3::new(x - 0.5 * width, bounds.min.y, bounds.max.z - DOOR_DEPTH_M),
        max: Vec3::new(x + 0.5 * width, bounds.min.y + height, bounds.max.z),
        velocity: Vec3::new(0.0, 0.0, -DOOR_SPEED_M_S),
        schedule: Schedule {
            on: vec![[now, now + f64::from(seconds)]],
        },
    }
}

/// Writes one row (`AIR_SOURCE_FLOATS`) per source of `world`'s air, jets
/// first (fans and vents, in their order), then draughts; returns how many.
pub fn write_sources(world: &World, out: &mut Vec<f32>) -> usize {
    out.clear();
    let t = world.time();
    let flow = world.air_flow();
    for jet in &flow.jets {
        let kind = match jet.kind {
            JetKind::Fan => SOURCE_FAN,
            JetKind::Vent => SOURCE_VENT,
        };
        push_row(out, kind, jet, jet.aim_at(t), jet.speed_at(t), jet.speed);
    }
    for draught in &flow.draughts {
        let jet = draught.jet();
        let level = draught.schedule.level_at(t);
        push_row(
            out,
            SOURCE_DRAUGHT,
            &jet,
            jet.direction,
            jet.speed * level,
            jet.speed,
        );
    }
    out.len() / AIR_SOURCE_FLOATS
}

fn push_row(out: &mut Vec<f32>, kind: f32, jet: &Jet, aim: Vec3, speed: f32, full: f32) {
    out.push(kind);
    out.extend_from_slice(&jet.outlet.to_array());
    out.extend_from_slice(&aim.to_array());
    out.extend_from_slice(&[
        speed,
        full,
        jet.diameter,
        jet.sweep.angle_rad,
        jet.sweep.period_s,
    ]);
}

/// Samples `world`'s air now at the centres of `dims` cells tiling `bounds`
/// (`AIR_GRID_FLOATS` a cell, x fastest) into `out`.
pub fn write_grid(
    world: &World,
    bounds: up_geom::Aabb,
    dims: [u32; 3],
    out: &mut Vec<f32>,
) -> Result<AirGrid, WasmError> {
    if dims.iter().any(|&n| n == 0 || n > MAX_AIR_GRID_AXIS) {
        return Err(WasmError::OutOfRange(format!(
            "write_air_grid: {dims:?} cells: expected 1 to {MAX_AIR_GRID_AXIS} along each axis"
        )));
    }
    let [nx, ny, nz] = dims;
    let cell = (bounds.max - bounds.min) / Vec3::new(nx as f32, ny as f32, nz as f32);
    out.clear();
    out.reserve((nx * ny * nz) as usize * AIR_GRID_FLOATS);
    let flow = world.air_flow();
    let moving = !flow.is_still();
    let t = world.time();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let u = if moving {
                    let index = Vec3::new(i as f32, j as f32, k as f32) + 0.5;
                    flow.velocity_at(bounds.min + index * cell, t)
                } else {
                    Vec3::ZERO
                };
                out.extend_from_slice(&[u.x, u.y, u.z, u.length()]);
            }
        }
    }
    Ok(AirGrid {
        dims,
        min: bounds.min.to_array(),
        max: bounds.max.to_array(),
        time_s: t,
        moving,
    })
}

/// The air's velocity now at each point of `points` (x, y, z each, m) into
/// `out` (x, y, z each, m/s); returns how many points.
pub fn write_at(world: &World, points: &[f32], out: &mut Vec<f32>) -> Result<usize, WasmError> {
    if !points.len().is_multiple_of(3) || points.len() / 3 > MAX_AIR_POINTS {
        return Err(WasmError::BadArgument(format!(
            "write_air_at: {} floats: expected x, y, z per point, at most {MAX_AIR_POINTS} points",
            points.len()
        )));
    }
    finite("write_air_at", points)?;
    out.clear();
    for p in points.chunks_exact(3) {
        let u = world.air_velocity_at(Vec3::new(p[0], p[1], p[2]));
        out.extend_from_slice(&u.to_array());
    }
    Ok(out.len() / 3)
}

#[cfg(test)]
#[path = "air_tests.rs"]
mod tests;
