//! Where two runs part: the state of two worlds compared body by body, so
//! that a determinism check that fails names the first step and the first
//! body that differ, and what of it, rather than only that two end hashes do.
//!
//! Each body's state is hashed field by field (`BodyHash`) with the bytes
//! the state hash writes for it (`World::state_hash`: FNV-1a over the bits
//! of the centre of mass, rotation, velocities and sleep flag, then its
//! ribbon's points and velocities and its gas). Two worlds in one process
//! are compared with `compare`, or stepped together with `lockstep`; two
//! builds (native and WebAssembly) compare `body_hash_line`s, one a step,
//! which `up run --body-hashes` and the wasm engine both write.
//! Reads the world through its public calls: a tool for tests, never on the
//! step's path.

use std::fmt;

use crate::hash::{fold32, hash_f32s, Fnv1a};
use crate::{BodyId, World};

/// What of a body's state differs; the order is the order compared in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Field {
    /// The bodies themselves: their number, or the handle at a dense index.
    Bodies,
    /// The centre of mass.
    Position,
    Rotation,
    LinearVelocity,
    AngularVelocity,
    /// Awake or asleep.
    Awake,
    /// The points and velocities of the ribbon tied to the body.
    Ribbon,
    /// The gas inside, and the size and mass it gives.
    Gas,
    /// No body differs, but the moving air's sources do (`World::air_flow`).
    Air,
    /// No body differs, but the state hash does: the clock, the room's air
    /// (its temperature) or a body's sleep timer (which the world does not
    /// show body by body).
    Rest,
}

impl Field {
    /// The fields a `BodyHash` holds, in its order.
    pub const HASHED: [Field; 7] = [
        Field::Position,
        Field::Rotation,
        Field::LinearVelocity,
        Field::AngularVelocity,
        Field::Awake,
        Field::Ribbon,
        Field::Gas,
    ];

    /// The field's name in reports and in `body_hash_line`'s header.
    pub fn name(self) -> &'static str {
        match self {
            Field::Bodies => "bodies",
            Field::Position => "position",
            Field::Rotation => "rotation",
            Field::LinearVelocity => "linear_velocity",
            Field::AngularVelocity => "angular_velocity",
            Field::Awake => "awake",
            Field::Ribbon => "ribbon",
            Field::Gas => "gas",
            Field::Air => "air",
            Field::Rest => "rest",
        }
    }
}

/// One body's state, hashed field by field (`Field::HASHED` order).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BodyHash {
    pub id: BodyId,
    pub user_data: u32,
    pub fields: [u64; Field::HASHED.len()],
}

impl BodyHash {
    /// The body `id` of `world` now; None if the world has no such body.
    pub fn of(world: &World, id: BodyId) -> Option<BodyHash> {
        let center = world.center_of_mass(id)?;
        let q = world.pose(id)?.rotation;
        let v = world.linear_velocity(id)?;
        let w = world.angular_velocity(id)?;
        let awake = world.is_awake(id)?;
        let mut awake_hash = Fnv1a::new();
        awake_hash.write_u32(awake as u32);
        Some(BodyHash {
            id,
            user_data: world.user_data(id)?,
            fields: [
                hash_f32s(center.to_array()),
                hash_f32s([q.x, q.y, q.z, q.w]),
                hash_f32s(v.to_array()),
                hash_f32s(w.to_array()),
                awake_hash.finish(),
                ribbon_hash(world, id),
                gas_hash(world, id),
            ],
        })
    }

    /// The first field in which `self` and `other` differ.
    pub fn first_difference(&self, other: &BodyHash) -> Option<Field> {
        (0..Field::HASHED.len())
            .find(|&k| self.fields[k] != other.fields[k])
            .map(|k| Field::HASHED[k])
    }
}

/// The ribbon's handle, then each point and its velocity (as the state hash
/// writes them); the empty hash when the body has none.
fn ribbon_hash(world: &World, id: BodyId) -> u64 {
    let mut h = Fnv1a::new();
    let Some(ribbon) = world.ribbon_of(id) else {
        return h.finish();
    };
    h.write_u32(ribbon.index);
    h.write_u32(ribbon.generation);
    let points = world.ribbon_points(ribbon).unwrap_or_default();
    let velocities = world.ribbon_velocities(ribbon).unwrap_or_default();
    for (p, v) in points.iter().zip(velocities) {
        for x in [p.x, p.y, p.z, v.x, v.y, v.z] {
            h.write_f32(x);
        }
    }
    h.finish()
}

/// Helium and air in mol, then the size and mass they give (as the state
/// hash writes them); the empty hash when the body has no gas.
fn gas_hash(world: &World, id: BodyId) -> u64 {
    let mut h = Fnv1a::new();
    if let Some(gas) = world.gas(id) {
        h.write_bytes(&gas.helium_mol.to_le_bytes());
        h.write_bytes(&gas.air_mol.to_le_bytes());
        h.write_f32(world.body_scale(id).unwrap_or(0.0));
        h.write_f32(world.body_mass(id).unwrap_or(0.0));
    }
    h.finish()
}

impl World {
    /// Every body's `BodyHash`, in dense order (the order of `body_ids`).
    pub fn body_hashes(&self) -> Vec<BodyHash> {
        self.body_ids()
            .iter()
            .filter_map(|&id| BodyHash::of(self, id))
            .collect()
    }
}

/// Where two runs part: the step, the body (None when it is no one body's
/// state: `Field::Rest`, or a body count) and what of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Divergence {
    /// The first world's step count when they were found to differ.
    pub step: u64,
    pub body: Option<BodyId>,
    /// The body's user data (the scene's balloon number), in the first world.
    pub user_data: Option<u32>,
    pub field: Field,
}

impl fmt::Display for Divergence {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "the runs part at step {}", self.step)?;
        if let Some(id) = self.body {
            write!(f, ", body {} (generation {}", id.index, id.generation)?;
            if let Some(user_data) = self.user_data {
                write!(f, ", user data {user_data}")?;
            }
            write!(f, ")")?;
        }
        match self.field {
            Field::Bodies => write!(f, ": the bodies differ (their number or handles)"),
            Field::Air => write!(f, ": the moving air's sources differ"),
            Field::Rest => write!(
                f,
                ": the state hash differs in no body's fields (the clock, the air or a sleep timer)"
            ),
            field => write!(f, ": {} differs", field.name()),
        }
    }
}

/// The first difference between `a` and `b` as they are now, body by body in
/// dense order; None when their states are equal (state hash included).
pub fn compare(a: &World, b: &World) -> Option<Divergence> {
    let at = |body: Option<BodyId>, user_data: Option<u32>, field| Divergence {
        step: a.step_count(),
        body,
        user_data,
        field,
    };
    let (ids_a, ids_b) = (a.body_ids(), b.body_ids());
    for i in 0..ids_a.len().max(ids_b.len()) {
        let (id_a, id_b) = (ids_a.get(i), ids_b.get(i));
        if id_a != id_b {
            let id = *id_a.or(id_b).expect("one of the two has a body at i");
            let world = if id_a.is_some() { a } else { b };
            return Some(at(Some(id), world.user_data(id), Field::Bodies));
        }
        let id = ids_a[i];
        let (Some(ha), Some(hb)) = (BodyHash::of(a, id), BodyHash::of(b, id)) else {
            continue;
        };
        if let Some(field) = ha.first_difference(&hb) {
            return Some(at(Some(id), Some(ha.user_data), field));
        }
    }
    if a.air_flow() != b.air_flow() {
        return Some(at(None, None, Field::Air));
    }
    (a.state_hash() != b.state_hash()).then(|| at(None, None, Field::Rest))
}

/// Steps `a` with `step_a` and `b` with `step_b`, `steps` times, comparing
/// them before the first step and after each: the first `Divergence`, or
/// None when they agree throughout. The stepping functions are where each
/// world's thread pool is chosen (`|w| pool.install(|| w.step())`).
pub fn lockstep_with(
    a: &mut World,
    b: &mut World,
    steps: u64,
    mut step_a: impl FnMut(&mut World),
    mut step_b: impl FnMut(&mut World),
) -> Option<Divergence> {
    if let Some(parted) = compare(a, b) {
        return Some(parted);
    }
    for _ in 0..steps {
        step_a(a);
        step_b(b);
        if let Some(parted) = compare(a, b) {
            return Some(parted);
        }
    }
    None
}

/// `lockstep_with`, each world stepped by `World::step`.
pub fn lockstep(a: &mut World, b: &mut World, steps: u64) -> Option<Divergence> {
    lockstep_with(a, b, steps, World::step, World::step)
}

/// The header of a file of `body_hash_line`s: what a line holds.
pub fn body_hash_header() -> String {
    let fields: Vec<&str> = Field::HASHED.iter().map(|f| f.name()).collect();
    format!(
        "# up body hashes: step state_hash, then per body index.generation/user_data:{}",
        fields.join(",")
    )
}

/// The world now as one line of text, the same from every build: the step,
/// the state hash (16 hex digits), then per body, dense order,
/// `index.generation/user_data:` and its field hashes folded to 8 hex digits
/// each, comma-separated (`Field::HASHED` order). Two builds' lines for the
/// same step are equal when their states are; where not, the first token
/// that differs names the body, and the place in it the field.
pub fn body_hash_line(world: &World) -> String {
    use fmt::Write as _;
    let mut line = format!("{} {:016x}", world.step_count(), world.state_hash());
    for hash in world.body_hashes() {
        let _ = write!(
            line,
            " {}.{}/{}:",
            hash.id.index, hash.id.generation, hash.user_data
        );
        for (k, field) in hash.fields.iter().enumerate() {
            let comma = if k == 0 { "" } else { "," };
            let _ = write!(line, "{comma}{:08x}", fold32(*field));
        }
    }
    line
}
