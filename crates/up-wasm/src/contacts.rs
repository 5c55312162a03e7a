//! The contact points of the last step, packed for the page's debug view:
//! one flat `f32` array the page reads as a single `Float32Array` view.

use up_physics::World;

/// Floats per contact: x, y, z (the contact point, m), nx, ny, nz (unit
/// normal from the balloon toward what it touches), separation (m, negative
/// when overlapping; typically a few mm either way), kind (1 another balloon,
/// 0 the room).
pub const CONTACT_FLOATS: usize = 8;
/// Most contacts written per call: 65 536 × 32 bytes = 2 MiB of view. A
/// 5,000-balloon pile has about 20 000; beyond the cap the rest are counted
/// but not written.
pub const MAX_CONTACTS: usize = 65_536;

/// Writes at most `max` (and at most `MAX_CONTACTS`) contacts of `world`'s
/// last step into `out`, replacing its contents; returns how many the step
/// has in all.
pub fn write_contacts(world: &World, max: usize, out: &mut Vec<f32>) -> usize {
    let max = max.min(MAX_CONTACTS);
    out.clear();
    let mut total = 0;
    for c in world.contact_points() {
        total += 1;
        if total > max {
            continue;
        }
        let kind = if c.body_b.is_some() { 1.0 } else { 0.0 };
        out.extend_from_slice(&[
            c.point.x,
            c.point.y,
            c.point.z,
            c.normal.x,
            c.normal.y,
            c.normal.z,
            c.separation,
            kind,
        ]);
    }
    total
}
