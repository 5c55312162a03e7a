//! The forces on the balloons as the page sees them: the engine's force
//! probe (`up_physics::ForceBreakdown`, the values the step integrated)
//! packed into one flat `f32` array, and a selected balloon's card of
//! figures. Bodies are named by their dense index in the current frame's
//! order (as `write_poses`).

use glam::Vec3;
use serde::Serialize;
use tsify_next::Tsify;
use up_physics::{BodyId, ForceBreakdown, ForceProbe, World};

use crate::error::WasmError;
use crate::loaded::body_at;

/// Floats per probed body: index, then x, y, z of weight, buoyancy, drag,
/// contact, ribbon, other (N), centre of mass, centre of buoyancy and knot
/// (m; NaN without a ribbon).
pub const FORCE_FLOATS: usize = 28;

/// `set_force_probe`'s argument for no body.
pub const PROBE_OFF: i32 = -1;
/// `set_force_probe`'s argument for every body.
pub const PROBE_ALL: i32 = -2;

/// A helium fraction above this is helium; below one less than it, air.
const PURE: f64 = 0.99;

/// What a balloon is filled with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Tsify)]
#[serde(rename_all = "lowercase")]
pub enum BodyGas {
    Helium,
    Air,
    Mixed,
}

/// A balloon's figures now, for the page's card.
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
#[tsify(into_wasm_abi)]
pub struct BodyCard {
    /// Dense index, as `write_poses` orders the bodies.
    pub index: u32,
    /// Envelope, knot and gas, kg.
    pub mass_kg: f32,
    pub volume_m3: f32,
    /// Its gas, mol (0 and 0 for a balloon without a gas of its own).
    pub helium_mol: f64,
    pub air_mol: f64,
    /// Helium's share of the moles (without gas: 1 if it lifts, else 0).
    pub helium_fraction: f64,
    /// Buoyancy − weight, N; and as grams it would hold up.
    pub net_lift_n: f32,
    pub net_lift_g: f32,
    pub speed_m_s: f32,
    /// Up is positive.
    pub vertical_speed_m_s: f32,
    /// Of the centre of mass above the floor, m.
    pub height_m: f32,
    /// The balloon's axis from vertical, degrees.
    pub tilt_deg: f32,
    /// Where drag balances the net lift (`World::terminal_speed`), m/s.
    pub terminal_speed_m_s: f32,
    pub gas: BodyGas,
    /// The room's air at the centre of mass now (`World::air_velocity_at`), m/s.
    pub air_velocity_m_s: [f32; 3],
    pub air_speed_m_s: f32,
    /// The balloon's speed through that air, |v − u|, m/s: what its drag acts against.
    pub speed_through_air_m_s: f32,
}

/// What the next steps of `world` record: `PROBE_OFF`, `PROBE_ALL`, or one
/// body's dense index.
pub fn set_force_probe(world: &mut World, which: i32) -> Result<(), WasmError> {
    let probe = match which {
        PROBE_OFF => ForceProbe::Off,
        PROBE_ALL => ForceProbe::All,
        i if i >= 0 => ForceProbe::One(body_at(world, i as u32)?),
        _ => {
            return Err(WasmError::OutOfRange(format!(
                "probe {which}: expected {PROBE_OFF} (off), {PROBE_ALL} (all) or a body index"
            )))
        }
    };
    world.set_force_probe(probe);
    Ok(())
}

/// Writes the last step's probed forces of `world` (`FORCE_FLOATS` a body,
/// dense order) into `out`; returns how many bodies.
pub fn write_forces(world: &World, out: &mut Vec<f32>) -> usize {
    out.clear();
    let bodies: Box<dyn Iterator<Item = (usize, BodyId)>> = match world.force_probe() {
        ForceProbe::Off => Box::new(std::iter::empty()),
        ForceProbe::One(id) => Box::new(
            world
                .body_ids()
                .iter()
                .position(|&b| b == id)
                .map(|i| (i, id))
                .into_iter(),
        ),
        ForceProbe::All => Box::new(world.body_ids().iter().copied().enumerate()),
    };
    for (i, id) in bodies {
        if let Some(f) = world.probed_forces(id) {
            pack(i, &f, out);
        }
    }
    out.len() / FORCE_FLOATS
}

/// The card of the balloon at dense index `index`.
pub fn body_card(world: &World, index: u32) -> Result<BodyCard, WasmError> {
    let id = body_at(world, index)?;
    card(world, id, index).ok_or(WasmError::NoWorld)
}

/// Appends one body's floats.
fn pack(index: usize, f: &ForceBreakdown, out: &mut Vec<f32>) {
    out.push(index as f32);
    let knot = f.knot.unwrap_or(Vec3::NAN);
    for v in [
        f.weight,
        f.buoyancy,
        f.drag,
        f.contact,
        f.ribbon,
        f.other,
        f.center_of_mass,
        f.center_of_buoyancy,
        knot,
    ] {
        out.extend_from_slice(&v.to_array());
    }
}

/// Body `id`'s card, `index` its dense index.
pub fn card(world: &World, id: BodyId, index: u32) -> Option<BodyCard> {
    let mass = world.body_mass(id)?;
    let volume = world.body_volume(id)?;
    let g = world.def().gravity;
    let air = world.air().air_density();
    // Buoyancy − weight along up.
    let net_lift_n = (air * volume - mass) * g.length();
    let v = world.linear_velocity(id)?;
    let pose = world.pose(id)?;
    let up = -g.normalize_or(Vec3::NEG_Y);
    let axis = pose.rotation * Vec3::Y;
    let floor = world.room().map_or(0.0, |r| r.aabb().min.y);
    let center = world.center_of_mass(id)?;
    let air_velocity = world.air_velocity_at(center);
    let (helium_mol, air_mol, helium_fraction) = match world.gas(id) {
        Some(gas) => (gas.helium_mol, gas.air_mol, gas.helium_mol / gas.moles()),
        None => (0.0, 0.0, if net_lift_n > 0.0 { 1.0 } else { 0.0 }),
    };
    let gas = if helium_fraction > PURE {
        BodyGas::Helium
    } else if helium_fraction < 1.0 - PURE {
        BodyGas::Air
    } else {
        BodyGas::Mixed
    };
    Some(BodyCard {
        index,
        mass_kg: mass,
        volume_m3: volume,
        helium_mol,
        air_mol,
        helium_fraction,
        net_lift_n,
        net_lift_g: net_lift_n / g.length() * 1000.0,
        speed_m_s: v.length(),
        vertical_speed_m_s: v.dot(up),
        height_m: center.y - floor,
        tilt_deg: axis.dot(up).clamp(-1.0, 1.0).acos().to_degrees(),
        terminal_speed_m_s: world.terminal_speed(id)?,
        gas,
        air_velocity_m_s: air_velocity.to_array(),
        air_speed_m_s: air_velocity.length(),
        speed_through_air_m_s: (v - air_velocity).length(),
    })
}

#[cfg(test)]
#[path = "forces_tests.rs"]
mod tests;
