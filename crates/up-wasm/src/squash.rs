//! Squash on impact, for drawing only: how far each balloon's membrane is
//! dented by the hardest contact it had since the page last looked, and along
//! which normal. The physics stays rigid (docs/physics.md, "Squash is drawn");
//! nothing here feeds back into the world.
//!
//! A pressed membrane carries F ≈ Δp·π·a² over a patch of a² ≈ 2·R·δ: a
//! contact stiffness k = 2π·R·Δp (physics reference, "Latex contact and
//! squash"). Two loads dent it:
//!
//! - an impact: a mass m meeting a spring k at speed v compresses it by
//!   v·√(m/k), under a peak force v·√(k·m). The approach momentum m·v is
//!   read from the contact's impulses: over the step the impact gives
//!   J = (1 + e)·m·v (the approach and the bounce), so d = J / ((1 + e)·√(k·m)).
//!   A steady load gives J too, F·dt each step, which that would read as a
//!   far harder hit; but it spreads over the substeps, where an impact's
//!   approach is stopped within one: the largest impulse of one substep, P,
//!   is at least m·v in an impact (the bounce is counted in the last
//!   substep, so up to (1 + e)·m·v) and only F·dt/substeps under a load.
//!   The approach momentum is taken as the smaller of J/(1 + e) and P;
//! - a steady load F = J / dt (a balloon pressed into a pile or a wall):
//!   d = F / k.
//!
//! The dent is the larger of the two. m is the effective mass (with the added
//! mass: the air moves with the balloon). Against another balloon the two
//! membranes are springs in series (k_s = k_a·k_b/(k_a + k_b)) and m the
//! pair's reduced mass; the force dents each membrane by F/k_own. A steady
//! load also shows in P (F times the substep), as F·h·√(k/m): 1.5 times its
//! F/k at 4 substeps, a fraction of a millimetre for the tenth of a newton a
//! balloon in a pile bears, under `MIN_SQUASH_M`, so a pile at rest stays
//! round.
//!
//! Per body (dense order) the table holds `SQUASH_FLOATS` floats: the unit
//! normal times the dent depth (x, y, z, m, world frame, pointing from the
//! balloon toward what it touches) and the reach: how far the balloon's
//! surface (its model's mesh, at its size and pose now) extends from the
//! body's origin along that normal, m. The page flattens the drawn balloon
//! against the plane that far out less the depth. Zero: no dent. The reach
//! is the mesh's, not the contact point's: the collision spheres only
//! approximate the surface, and a plane set by them would cut the drawn
//! balloon too deep or not at all.
//! Each step keeps, per body, its deepest dent since the table was last read.

use glam::Vec3;
use up_physics::{BodyId, World};

/// Floats per body in the squash table: nx·d, ny·d, nz·d, reach.
pub const SQUASH_FLOATS: usize = 4;
/// Overpressure of an inflated balloon, Pa: the middle of the physics
/// reference's 1–3 kPa. With it an 11″ balloon thrown at 5 m/s into a wall
/// dents ≈ 1.4 cm (≈ 2 cm at 1 kPa).
pub const MEMBRANE_OVERPRESSURE_PA: f32 = 2000.0;
/// Deepest dent drawn, as a fraction of the balloon's radius: past that the
/// small-dent stiffness no longer holds, and a flattened quarter reads as a
/// squash already.
pub const MAX_SQUASH_FRACTION: f32 = 0.25;
/// Shallowest dent written, m: under a millimetre nothing shows on a 28 cm
/// balloon, and a pile at rest stays exactly round.
pub const MIN_SQUASH_M: f32 = 0.001;

/// Contact stiffness of a balloon's membrane, N/m: 2π·R·Δp (R m, Δp Pa).
pub fn membrane_stiffness(radius: f32, overpressure: f32) -> f32 {
    std::f32::consts::TAU * radius * overpressure
}

/// One side of a contact: its membrane stiffness (N/m) and effective mass (kg).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Membrane {
    pub stiffness: f32,
    pub mass: f32,
}

/// The dent of membrane `own`, m, from a contact against `other` (None: the
/// room, rigid and immovable) whose impulse over the step of `dt` s was
/// `step_impulse` and whose largest impulse within one substep was
/// `peak_impulse` (N·s), with restitution `restitution`; not capped.
pub fn contact_depth(
    peak_impulse: f32,
    step_impulse: f32,
    restitution: f32,
    dt: f32,
    own: Membrane,
    other: Option<Membrane>,
) -> f32 {
    let (stiffness, mass) = match other {
        None => (own.stiffness, own.mass),
        Some(o) => (
            own.stiffness * o.stiffness / (own.stiffness + o.stiffness),
            own.mass * o.mass / (own.mass + o.mass),
        ),
    };
    if !(stiffness > 0.0 && mass > 0.0 && own.stiffness > 0.0) {
        return 0.0;
    }
    // The approach momentum m·v, and the peak force v·√(k·m).
    let approach = peak_impulse.min(step_impulse / (1.0 + restitution.max(0.0)));
    let impact_force = approach * (stiffness / mass).sqrt();
    let load_force = if dt > 0.0 { step_impulse / dt } else { 0.0 };
    let force = impact_force.max(load_force);
    if force > 0.0 {
        force / own.stiffness
    } else {
        0.0
    }
}

/// A contact as the squash reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Impact {
    pub body_a: BodyId,
    /// None: the room.
    pub body_b: Option<BodyId>,
    /// Unit, from A toward B.
    pub normal: Vec3,
    /// N·s over the step, ≥ 0.
    pub normal_impulse: f32,
    /// N·s: the largest within one substep of the step.
    pub max_normal_impulse: f32,
}

/// Each body's deepest dent since the page last read the table.
#[derive(Default)]
pub struct SquashTable {
    /// `SQUASH_FLOATS` per body, dense order.
    pub values: Vec<f32>,
    /// Depth of each body's dent in `values`, m.
    depths: Vec<f32>,
    /// Dense index by body slot (`BodyId::index`), rebuilt each step.
    dense: Vec<u32>,
}

impl SquashTable {
    /// Reads the dents of `impacts`, one step's contacts of `world`, keeping
    /// each body's deepest; `radius(id)` is a body's radius now, m, and
    /// `reach(id, n)` how far its surface extends from its origin along the
    /// world direction `n`, m.
    pub fn record(
        &mut self,
        world: &World,
        impacts: impl Iterator<Item = Impact>,
        radius: impl Fn(BodyId) -> f32,
        reach: impl Fn(BodyId, Vec3) -> Option<f32>,
    ) {
        let ids = world.body_ids();
        if self.depths.len() != ids.len() {
            self.values.clear();
            self.values.resize(ids.len() * SQUASH_FLOATS, 0.0);
            self.depths.clear();
            self.depths.resize(ids.len(), 0.0);
        }
        self.dense.clear();
        for (i, id) in ids.iter().enumerate() {
            let slot = id.index as usize;
            if slot >= self.dense.len() {
                self.dense.resize(slot + 1, u32::MAX);
            }
            self.dense[slot] = i as u32;
        }
        let (dt, restitution) = (world.def().dt, world.def().restitution);
        let membrane = |id: BodyId| {
            Some(Membrane {
                stiffness: membrane_stiffness(radius(id), MEMBRANE_OVERPRESSURE_PA),
                mass: world.effective_mass(id)?,
            })
        };
        for c in impacts {
            if !(c.normal_impulse > 0.0 || c.max_normal_impulse > 0.0) {
                continue;
            }
            let Some(a) = membrane(c.body_a) else {
                continue;
            };
            let b = match c.body_b {
                Some(id) => match membrane(id) {
                    Some(m) => Some(m),
                    None => continue,
                },
                None => None,
            };
            let (peak, total) = (c.max_normal_impulse, c.normal_impulse);
            let depth_a = contact_depth(peak, total, restitution, dt, a, b);
            self.keep(c.body_a, c.normal, depth_a, &radius, &reach);
            if let (Some(id), Some(b)) = (c.body_b, b) {
                let depth_b = contact_depth(peak, total, restitution, dt, b, Some(a));
                self.keep(id, -c.normal, depth_b, &radius, &reach);
            }
        }
    }

    /// Keeps `depth` along `normal` (toward what `id` touches) when it is the
    /// body's deepest, capped at `MAX_SQUASH_FRACTION` of its radius.
    fn keep(
        &mut self,
        id: BodyId,
        normal: Vec3,
        depth: f32,
        radius: &impl Fn(BodyId) -> f32,
        reach: &impl Fn(BodyId, Vec3) -> Option<f32>,
    ) {
        let Some(&i) = self.dense.get(id.index as usize) else {
            return;
        };
        let i = i as usize;
        let depth = depth.min(MAX_SQUASH_FRACTION * radius(id));
        if depth.is_nan()
            || depth < MIN_SQUASH_M
            || i >= self.depths.len()
            || depth <= self.depths[i]
        {
            return;
        }
        let Some(reach) = reach(id, normal).filter(|r| r.is_finite()) else {
            return;
        };
        if !normal.is_finite() {
            return;
        }
        self.depths[i] = depth;
        let n = normal * depth;
        self.values[i * SQUASH_FLOATS..(i + 1) * SQUASH_FLOATS]
            .copy_from_slice(&[n.x, n.y, n.z, reach]);
    }

    /// The table for the page, then cleared: `body_count` bodies' dents since
    /// the last call (zeros where none).
    pub fn take(&mut self, body_count: usize, out: &mut Vec<f32>) {
        out.clear();
        out.resize(body_count * SQUASH_FLOATS, 0.0);
        if self.depths.len() == body_count {
            out.copy_from_slice(&self.values);
        }
        self.values.iter_mut().for_each(|v| *v = 0.0);
        self.depths.iter_mut().for_each(|d| *d = 0.0);
    }
}

#[cfg(test)]
#[path = "squash_tests.rs"]
mod tests;

impl crate::state::State {
    /// Reads the last step's contacts into the squash table (after every step).
    pub(crate) fn record_squash(&mut self) {
        let Some(loaded) = self.loaded.as_ref() else {
            return;
        };
        let world = &loaded.built.world;
        let groups = &loaded.scene.balloons;
        let models = &loaded.built.balloon_models;
        let group = |id: BodyId| world.user_data(id).map_or(0, up_scene::build::group_index);
        let radius = |id: BodyId| {
            let diameter = groups.get(group(id)).map_or(0.0, |g| g.diameter());
            0.5 * diameter * world.body_scale(id).unwrap_or(1.0)
        };
        // Only for the few dents deep enough to draw: a pass over the model's vertices.
        let reach = |id: BodyId, n: Vec3| {
            let mesh = &models.get(group(id))?.mesh;
            let local = world.pose(id)?.rotation.inverse() * n;
            let support = mesh
                .positions
                .iter()
                .map(|p| p.dot(local))
                .fold(f32::MIN, f32::max);
            Some(support * world.body_scale(id)?)
        };
        let impacts = world.contact_points().map(|c| Impact {
            body_a: c.body_a,
            body_b: c.body_b,
            normal: c.normal,
            normal_impulse: c.normal_impulse,
            max_normal_impulse: c.max_normal_impulse,
        });
        self.squash.record(world, impacts, radius, reach);
    }

    /// Each body's deepest dent since the last call into `squash_out`, then forgotten.
    pub fn write_body_squash(&mut self) -> Result<(), crate::error::WasmError> {
        let count = self.world()?.body_count();
        self.squash.take(count, &mut self.squash_out);
        Ok(())
    }
}
