//! What a run ends with: the numbers of `up run --json`, and the table.

use glam::Vec3;
use serde::Serialize;
use up_physics::World;
use up_scene::room::RoomMesh;

/// The last line of `up run --json`. Units in the names; SI throughout.
#[derive(Clone, Debug, Serialize)]
pub struct RunSummary {
    /// The scene file, or `default (the original room)`.
    pub scene: String,
    pub balloons: usize,
    pub steps: u64,
    /// Simulated time at the end, s.
    pub sim_seconds: f64,
    /// Wall-clock time spent stepping, s.
    pub wall_seconds: f64,
    /// Mean wall-clock time per step, ms.
    pub ms_per_step: f64,
    /// Deepest overlap any step found (balloon–balloon or balloon–room), m.
    pub max_penetration_m: f32,
    /// Bodies whose origin is outside the room at the end.
    pub escaped: usize,
    /// Bodies with a non-finite position or rotation at the end.
    pub nan_bodies: usize,
    /// `World::state_hash()` at the end, 16 lowercase hex digits (a u64; a
    /// string because JSON numbers lose bits past 2⁵³).
    pub state_hash: String,
    /// Mean height of the bodies' origins above the floor, m.
    pub mean_height_m: f32,
    /// Largest angle between a body's +Y and the world's +Y, degrees.
    pub max_tilt_deg: f32,
    /// Total kinetic energy (added mass included), J.
    pub kinetic_energy_j: f32,
    /// Bodies awake after the last step.
    pub awake: u32,
}

/// Measures the end state of `world`.
pub fn measure(world: &World, room: &RoomMesh) -> EndState {
    let mut end = EndState::default();
    let mut height_sum = 0.0f64;
    let mut finite = 0usize;
    for (_, pose) in world.poses() {
        let ok = pose.position.is_finite() && pose.rotation.is_finite();
        if !ok {
            end.nan_bodies += 1;
            continue;
        }
        finite += 1;
        if !room.contains_point(pose.position) {
            end.escaped += 1;
        }
        height_sum += f64::from(pose.position.y);
        let up = pose.rotation * Vec3::Y;
        let tilt = up.angle_between(Vec3::Y).to_degrees();
        end.max_tilt_deg = end.max_tilt_deg.max(tilt);
    }
    if finite > 0 {
        end.mean_height_m = (height_sum / finite as f64) as f32;
    }
    end
}

/// Per-body measures of the end state.
#[derive(Clone, Copy, Debug, Default)]
pub struct EndState {
    pub escaped: usize,
    pub nan_bodies: usize,
    pub mean_height_m: f32,
    pub max_tilt_deg: f32,
}

/// Prints `label  value` rows aligned, with a title.
pub fn print_table(title: &str, rows: &[(&str, String)]) {
    let width = rows
        .iter()
        .map(|(label, _)| label.chars().count())
        .max()
        .unwrap_or(0);
    println!("{title}");
    for (label, value) in rows {
        println!("  {label:<width$}  {value}");
    }
}

impl RunSummary {
    pub fn rows(&self) -> Vec<(&'static str, String)> {
        vec![
            ("scene", self.scene.clone()),
            ("balloons", self.balloons.to_string()),
            ("steps", self.steps.to_string()),
            ("simulated", format!("{:.3} s", self.sim_seconds)),
            ("wall clock", format!("{:.3} s", self.wall_seconds)),
            ("per step", format!("{:.3} ms", self.ms_per_step)),
            (
                "max penetration",
                format!("{:.2} mm", self.max_penetration_m * 1000.0),
            ),
            ("escaped", self.escaped.to_string()),
            ("non-finite bodies", self.nan_bodies.to_string()),
            ("mean height", format!("{:.3} m", self.mean_height_m)),
            ("max tilt", format!("{:.1}°", self.max_tilt_deg)),
            ("kinetic energy", format!("{:.3e} J", self.kinetic_energy_j)),
            ("awake", self.awake.to_string()),
            ("state hash", self.state_hash.clone()),
        ]
    }
}
