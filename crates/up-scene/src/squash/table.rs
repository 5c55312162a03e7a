//! Each body's deepest dent since the table was last read, by dense index.

use glam::Vec3;
use up_physics::{BodyId, World};

use super::membrane::{
    contact_depth, membrane_stiffness, Membrane, MAX_SQUASH_FRACTION, MEMBRANE_OVERPRESSURE_PA,
    MIN_SQUASH_M, SQUASH_FLOATS,
};

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

/// Each body's deepest dent since the table was last read.
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

    /// The table, then cleared: `body_count` bodies' dents since
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
