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
    /// Time-lapse jumps (`World::advance` moving the gas alone while every
    /// balloon sleeps); 0 for a run stepped every frame.
    pub jumps: u64,
    /// Simulated time at the end, s (the world's clock: a world loaded with
    /// `--load-state` starts from its saved time).
    pub sim_seconds: f64,
    /// Simulated time this run covered, s.
    pub sim_time_s: f64,
    /// Wall-clock time spent stepping, s.
    pub wall_seconds: f64,
    /// Mean wall-clock time per step, ms.
    pub ms_per_step: f64,
    /// Deepest overlap any step found (balloon–balloon or balloon–room), m;
    /// with `--hours`, the deepest at the end of each simulated minute.
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
    /// Median of that angle over the bodies, degrees.
    pub median_tilt_deg: f32,
    /// Its 90th percentile, degrees.
    pub p90_tilt_deg: f32,
    /// Total kinetic energy (added mass included), J.
    pub kinetic_energy_j: f32,
    /// Bodies awake after the last step.
    pub awake: u32,
    /// Ribbons tied to the balloons.
    pub ribbons: usize,
    /// Largest relative stretch any ribbon ended a step with, over the world's
    /// life (`World::ribbon_max_stretch`; 0.004 is 0.4 % longer than its
    /// length); a world loaded with `--load-state` keeps its earlier largest.
    pub ribbon_max_stretch: f32,
    /// Mean over the balloons that carry gas of the gas's lift now over its
    /// lift at fill (`Gas::lift_fraction`, in the room's air at the end);
    /// null when no balloon carries gas.
    pub mean_lift_fraction: Option<f64>,
}

/// Measures the end state of `world`.
pub fn measure(world: &World, room: &RoomMesh) -> EndState {
    let mut end = EndState::default();
    let mut height_sum = 0.0f64;
    let mut finite = 0usize;
    let mut tilts = Vec::with_capacity(world.body_count());
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
        let tilt = tilt_deg(pose.rotation);
        end.max_tilt_deg = end.max_tilt_deg.max(tilt);
        tilts.push(tilt);
    }
    if finite > 0 {
        end.mean_height_m = (height_sum / finite as f64) as f32;
    }
    tilts.sort_by(f32::total_cmp);
    end.median_tilt_deg = percentile(&tilts, 50.0);
    end.p90_tilt_deg = percentile(&tilts, 90.0);
    end
}

/// Angle between a body's +Y and the world's +Y, degrees, in [0, 180].
pub fn tilt_deg(rotation: glam::Quat) -> f32 {
    (rotation * Vec3::Y).angle_between(Vec3::Y).to_degrees()
}

/// The `p`-th percentile (0 to 100) of ascending `sorted`, interpolated
/// linearly between ranks (the median of an even count is the mean of the
/// middle two); 0 for none.
pub fn percentile(sorted: &[f32], p: f32) -> f32 {
    let Some(&last) = sorted.last() else {
        return 0.0;
    };
    let rank = (p / 100.0).clamp(0.0, 1.0) * (sorted.len() - 1) as f32;
    let below = rank.floor() as usize;
    match sorted.get(below + 1) {
        Some(&above) => sorted[below] + (above - sorted[below]) * (rank - below as f32),
        None => last,
    }
}

/// Per-body measures of the end state.
#[derive(Clone, Copy, Debug, Default)]
pub struct EndState {
    pub escaped: usize,
    pub nan_bodies: usize,
    pub mean_height_m: f32,
    pub max_tilt_deg: f32,
    pub median_tilt_deg: f32,
    pub p90_tilt_deg: f32,
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
            ("time-lapse jumps", self.jumps.to_string()),
            ("simulated", format!("{:.3} s", self.sim_time_s)),
            ("clock at the end", format!("{:.3} s", self.sim_seconds)),
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
            ("median tilt", format!("{:.1}°", self.median_tilt_deg)),
            ("90th percentile tilt", format!("{:.1}°", self.p90_tilt_deg)),
            ("kinetic energy", format!("{:.3e} J", self.kinetic_energy_j)),
            ("awake", self.awake.to_string()),
            ("ribbons", self.ribbons.to_string()),
            (
                "ribbon max stretch",
                format!("{:.3} %", self.ribbon_max_stretch * 100.0),
            ),
            (
                "mean lift left",
                self.mean_lift_fraction
                    .map_or_else(|| "no gas".to_string(), |f| format!("{:.1} %", f * 100.0)),
            ),
            ("state hash", self.state_hash.clone()),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_interpolate_between_ranks() {
        assert_eq!(percentile(&[], 50.0), 0.0);
        assert_eq!(percentile(&[7.0], 90.0), 7.0);
        let v = [0.0, 10.0, 20.0, 30.0];
        assert_eq!(percentile(&v, 50.0), 15.0);
        assert_eq!(percentile(&v, 0.0), 0.0);
        assert_eq!(percentile(&v, 100.0), 30.0);
        assert!((percentile(&v, 90.0) - 27.0).abs() < 1e-5);
        let odd = [1.0, 2.0, 9.0];
        assert_eq!(percentile(&odd, 50.0), 2.0);
    }

    #[test]
    fn tilt_is_the_angle_from_upright() {
        assert_eq!(tilt_deg(glam::Quat::IDENTITY), 0.0);
        let side = glam::Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
        assert!((tilt_deg(side) - 90.0).abs() < 1e-3);
        let upside_down = glam::Quat::from_rotation_x(std::f32::consts::PI);
        assert!((tilt_deg(upside_down) - 180.0).abs() < 1e-3);
    }
}
