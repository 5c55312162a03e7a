//! The scene's fans, vents and draughts as the world's moving air
//! (`up_physics::AirFlow`): fans first, then vents, in the file's order,
//! each with its kind's defaults for what the file leaves out.

use glam::Vec3;
use up_physics::air::{Draught, Jet, JetKind, Schedule, Sweep};
use up_physics::AirFlow;

use super::room::RoomMesh;
use crate::error::SceneError;
use crate::scene::{JetSource, Scene};

/// How far past the outlet a jet's air must be inside the room, m: a vent
/// set in the ceiling has its outlet on the ceiling's surface.
const OUTLET_REACH_M: f32 = 0.01;

/// Every source of moving air the scene lists; still air when it lists none.
pub fn air_flow(scene: &Scene) -> AirFlow {
    let jets = scene
        .jets()
        .map(|(_, source, spec)| {
            let resolved = spec.resolved(source);
            let kind = match source {
                JetSource::Fan => JetKind::Fan,
                JetSource::Vent => JetKind::Vent,
            };
            let mut jet = Jet::new(
                kind,
                Vec3::from_array(resolved.position),
                Vec3::from_array(resolved.direction),
                resolved.diameter_m,
                resolved.speed_m_s,
            );
            jet.sweep = Sweep {
                angle_rad: spec.sweep_deg.to_radians(),
                period_s: spec.sweep_period_s,
            };
            jet.schedule = Schedule {
                on: spec.on.clone(),
            };
            jet
        })
        .collect();
    let draughts = scene
        .draughts
        .iter()
        .map(|d| Draught {
            min: Vec3::from_array(d.min),
            max: Vec3::from_array(d.max),
            velocity: Vec3::from_array(d.velocity_m_s),
            schedule: Schedule { on: d.on.clone() },
        })
        .collect();
    AirFlow { jets, draughts }
}

/// Every outlet within `room`'s bounds with the air just past it inside
/// the room (a vent set in the ceiling blows into the room, not out of it),
/// and every draught's opening within the bounds: validation checks a box
/// room's box, this the room as built (a pyramid's slopes, a mesh).
pub fn check_air_in(scene: &Scene, room: &RoomMesh) -> Result<(), SceneError> {
    let bounds = room.bounds();
    for (at, source, spec) in scene.jets() {
        let resolved = spec.resolved(source);
        let outlet = Vec3::from_array(resolved.position);
        let aim = Vec3::from_array(resolved.direction).normalize_or_zero();
        let first_air = outlet + OUTLET_REACH_M * aim;
        if !(bounds.contains_point(outlet) && room.contains_point(first_air)) {
            return Err(SceneError::Invalid {
                at: scene.locate(&format!("{at}.position")),
                expected: "an outlet in the room, blowing into it (the air 1 cm past it inside)"
                    .into(),
                found: format!("{:?}", resolved.position),
            });
        }
    }
    let bounds = room.bounds();
    for (i, draught) in scene.draughts.iter().enumerate() {
        for (key, corner) in [("min", draught.min), ("max", draught.max)] {
            let p = Vec3::from_array(corner);
            if p.cmplt(bounds.min).any() || p.cmpgt(bounds.max).any() {
                return Err(SceneError::Invalid {
                    at: scene.locate(&format!("draughts[{i}].{key}")),
                    expected: format!(
                        "a corner inside the room's bounds, from {} to {} m",
                        bounds.min, bounds.max
                    ),
                    found: format!("{corner:?}"),
                });
            }
        }
    }
    Ok(())
}
