//! The benchmark scene for web/bench: the scene file UP's wasm builds, and
//! everything Rapier needs that the wasm API does not expose (mass
//! properties, forces, the parameters matched to UP's), computed here so that
//! the native and the Node harness use the same numbers. Poses measured in
//! Node come back through `read_poses` and `measure::measure_frames`.

use std::path::Path;

use anyhow::{bail, Context, Result};
use serde::Serialize;
use up_geom::{Pose, Quat, Vec3};

use crate::measure::POSE_BUDGET;
use crate::rapier_engine::{integration_parameters, mass_properties, sleep_speed};
use crate::run::default_steps;
use crate::scene_data::SceneData;

/// Floats per pose in a poses file: x, y, z, qx, qy, qz, qw (little-endian f32).
pub const POSE_FLOATS: usize = 7;

#[derive(Serialize)]
pub struct ExportedScene {
    pub balloons: u64,
    pub seed: u64,
    pub room_width_m: f32,
    pub pile_layers: f32,
    /// Steps a run takes by default (`run::default_steps`).
    pub default_steps: u64,
    /// Most poses a run records for the overlap measure (`measure::measure_every`).
    pub pose_budget: u64,
    /// The scene file (JSON) for `up_world_from_json`.
    pub scene: serde_json::Value,
    pub rapier: RapierSetup,
}

/// What a Rapier world needs to match UP's (all SI, body frame = UP's mesh frame).
#[derive(Serialize)]
pub struct RapierSetup {
    pub dt: f32,
    /// `integrationParameters.numSolverIterations` (UP's substeps).
    pub num_solver_iterations: usize,
    pub num_internal_pgs_iterations: usize,
    pub contact_natural_frequency: f32,
    pub contact_damping_ratio: f32,
    pub friction: f32,
    pub restitution: f32,
    pub angular_damping: f32,
    pub ccd: bool,
    pub can_sleep: bool,
    /// m/s: the sleep threshold on a body's fastest point.
    pub sleep_speed: f32,
    pub time_until_sleep: f32,
    /// kg: the balloon's mass plus its added mass.
    pub mass: f32,
    pub center_of_mass: [f32; 3],
    /// kg·m², principal moments, and the rotation (x, y, z, w) of their axes in the body frame.
    pub principal_inertia: [f32; 3],
    pub inertia_frame: [f32; 4],
    /// N, at the centre of mass.
    pub weight: [f32; 3],
    /// N, at the centre of buoyancy.
    pub buoyancy: [f32; 3],
    pub center_of_buoyancy: [f32; 3],
    /// kg/m: drag F = −k·|v|·v.
    pub drag_factor: f32,
    /// The balloon's balls: x, y, z, radius (body frame, m).
    pub leaves: Vec<[f32; 4]>,
}

pub fn export(data: &SceneData, balloons: u64, seed: u64) -> Result<ExportedScene> {
    let def = &data.def;
    let params = integration_parameters(data);
    let mass = mass_properties(data);
    let frame = mass.principal_inertia_local_frame;
    let inertia = mass.principal_inertia();
    let scene = serde_json::to_value(&data.scene).context("the scene as JSON")?;
    Ok(ExportedScene {
        balloons,
        seed,
        room_width_m: data.layout.room_width_m,
        pile_layers: data.layout.pile_layers,
        default_steps: default_steps(
            data.layout.wall_height_m + data.layout.apex_height_m,
            def.dt,
        ),
        pose_budget: POSE_BUDGET,
        scene,
        rapier: RapierSetup {
            dt: params.dt,
            num_solver_iterations: params.num_solver_iterations,
            num_internal_pgs_iterations: params.num_internal_pgs_iterations,
            contact_natural_frequency: params.contact_softness.natural_frequency,
            contact_damping_ratio: params.contact_softness.damping_ratio,
            friction: def.friction,
            restitution: def.restitution,
            angular_damping: def.angular_damping,
            ccd: def.enable_continuous,
            can_sleep: def.enable_sleep,
            sleep_speed: sleep_speed(data),
            time_until_sleep: def.time_to_sleep,
            mass: mass.mass(),
            center_of_mass: data.shape.center_of_mass.to_array(),
            principal_inertia: [inertia.x, inertia.y, inertia.z],
            inertia_frame: [frame.x, frame.y, frame.z, frame.w],
            weight: data.weight().to_array(),
            buoyancy: data.buoyancy().to_array(),
            center_of_buoyancy: data.shape.center_of_buoyancy.to_array(),
            drag_factor: data.drag_factor(),
            leaves: data
                .leaves
                .iter()
                .map(|s| [s.center.x, s.center.y, s.center.z, s.radius])
                .collect(),
        },
    })
}

/// Poses from a file of little-endian f32, `POSE_FLOATS` per balloon, frame
/// after frame of `balloons` poses each.
pub fn read_poses(path: &Path, balloons: usize) -> Result<Vec<Vec<Pose>>> {
    let bytes = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
    let frame_bytes = balloons * POSE_FLOATS * 4;
    if balloons == 0 || bytes.is_empty() || bytes.len() % frame_bytes != 0 {
        bail!(
            "{}: expected frames of {balloons} poses ({frame_bytes} bytes each), found {} bytes",
            path.display(),
            bytes.len()
        );
    }
    let floats: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    Ok(floats
        .chunks_exact(balloons * POSE_FLOATS)
        .map(|frame| {
            frame
                .chunks_exact(POSE_FLOATS)
                .map(|p| {
                    Pose::new(
                        Vec3::new(p[0], p[1], p[2]),
                        Quat::from_xyzw(p[3], p[4], p[5], p[6]),
                    )
                })
                .collect()
        })
        .collect())
}
