//! The balloons' gas as the page sees it: the room's air, the time-lapse's
//! limits and report (`World::advance`), and where the balloons float
//! (`up_scene::float_census`) for the page's plot. Balloons the page adds
//! are filled like their group's (`BuiltScene::envelopes`).

use serde::Serialize;
use tsify_next::Tsify;
use up_physics::{Advance, BodyId, World};
use up_scene::float_census::FloatCensus;

use crate::error::WasmError;
use crate::limits::MAX_STEPS_PER_CALL;
use crate::loaded::Loaded;

/// Most simulated seconds one `advance` call covers: an hour (a tick at
/// ×3 600 asks for a few minutes; a host asking for more has lost track of time).
pub const MAX_ADVANCE_S: f64 = 3600.0;

/// 0 °C in kelvin.
const ZERO_CELSIUS_K: f32 = 273.15;

/// What one `advance` call did.
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
#[tsify(into_wasm_abi)]
pub struct AdvanceReport {
    /// Simulated seconds advanced: less than asked when `max_steps` ran out.
    pub seconds: f64,
    /// Fixed steps taken (while anything moved).
    pub steps: f64,
    /// Jumps of the gas alone (while everything slept).
    pub jumps: f64,
}

/// How many balloons of a group float where (`up_scene::float_census`'s definition).
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
pub struct GroupFloat {
    pub ceiling: u32,
    pub hovering: u32,
    pub floor: u32,
    /// The gas's lift now over its lift at the fill, averaged over the group's balloons.
    pub mean_lift_fraction: f32,
}

/// Where the balloons float now, per balloon group and in all.
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
#[tsify(into_wasm_abi)]
pub struct FloatCounts {
    /// Simulated seconds since the world was built.
    pub time_s: f64,
    pub ceiling: u32,
    pub hovering: u32,
    pub floor: u32,
    /// Over all balloons (each group's mean weighted by its count).
    pub mean_lift_fraction: f32,
    pub groups: Vec<GroupFloat>,
}

/// `Ok` when `advance` may cover `seconds` in at most `max_steps` steps.
pub fn check_advance(seconds: f64, max_steps: u32) -> Result<(), WasmError> {
    if !seconds.is_finite() || !(0.0..=MAX_ADVANCE_S).contains(&seconds) {
        return Err(WasmError::BadArgument(format!(
            "{seconds} s at once: expected 0 to {MAX_ADVANCE_S} s"
        )));
    }
    if max_steps == 0 || max_steps > MAX_STEPS_PER_CALL {
        return Err(WasmError::BadArgument(format!(
            "at most {max_steps} steps: expected 1 to {MAX_STEPS_PER_CALL}"
        )));
    }
    Ok(())
}

impl From<Advance> for AdvanceReport {
    fn from(done: Advance) -> AdvanceReport {
        AdvanceReport {
            seconds: done.seconds,
            steps: done.steps as f64,
            jumps: done.jumps as f64,
        }
    }
}

/// The room's air temperature now, °C (the scene's schedule applied).
pub fn air_temperature_c(world: &World) -> f32 {
    world.air().temperature_k - ZERO_CELSIUS_K
}

/// Looks at every balloon of `world` now (`census` keeps how high each has
/// been; made on the first look) and counts where they float.
pub fn float_counts(world: &World, census: &mut Option<FloatCensus>) -> FloatCounts {
    let census = census.get_or_insert_with(FloatCensus::new);
    let groups: Vec<GroupFloat> = census
        .observe(world)
        .iter()
        .map(|g| GroupFloat {
            ceiling: g.ceiling,
            hovering: g.hovering,
            floor: g.floor,
            mean_lift_fraction: g.mean_lift_fraction,
        })
        .collect();
    let (mut ceiling, mut hovering, mut floor, mut lift) = (0, 0, 0, 0.0f64);
    for g in &groups {
        ceiling += g.ceiling;
        hovering += g.hovering;
        floor += g.floor;
        let n = g.ceiling + g.hovering + g.floor;
        lift += f64::from(g.mean_lift_fraction) * f64::from(n);
    }
    let total = ceiling + hovering + floor;
    FloatCounts {
        time_s: world.time(),
        ceiling,
        hovering,
        floor,
        mean_lift_fraction: if total > 0 {
            (lift / f64::from(total)) as f32
        } else {
            0.0
        },
        groups,
    }
}

/// Fills an added balloon of group `group` with the gas its group was filled with, fresh (age 0).
pub fn fill_added(loaded: &mut Loaded, body: BodyId, group: usize) -> Result<(), WasmError> {
    if let Some(Some(envelope)) = loaded.built.envelopes.get(group) {
        let envelope = *envelope;
        loaded.built.world.fill(body, &envelope, 0.0)?;
    }
    Ok(())
}

#[cfg(test)]
#[path = "gas_tests.rs"]
mod tests;
