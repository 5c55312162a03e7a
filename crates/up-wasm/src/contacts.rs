//! The contact points of the last step, packed for the page's debug view:
//! one flat `f32` array the page reads as a single `Float32Array` view. The
//! balloons' contacts come first, then where ribbons touch each other.

use up_physics::World;

/// Floats per contact: x, y, z (the contact point, m), nx, ny, nz (unit
/// normal from the balloon toward what it touches, or from one ribbon toward
/// the other), separation (m, negative when overlapping; typically a few mm
/// either way), kind (`KIND_BALLOON`, `KIND_ROOM` or `KIND_RIBBONS`).
pub const CONTACT_FLOATS: usize = 8;
/// Most contacts written per call: 65 536 × 32 bytes = 2 MiB of view. A
/// 5,000-balloon pile has about 20 000; beyond the cap the rest are counted
/// but not written.
pub const MAX_CONTACTS: usize = 65_536;

/// A balloon against another balloon.
pub const KIND_BALLOON: f32 = 1.0;
/// A balloon against the room.
pub const KIND_ROOM: f32 = 0.0;
/// A ribbon against another ribbon (or itself), with ribbon contacts on.
pub const KIND_RIBBONS: f32 = 2.0;

/// Writes at most `max` (and at most `MAX_CONTACTS`) contacts of `world`'s
/// last step into `out`, replacing its contents; returns how many the step
/// has in all.
pub fn write_contacts(world: &World, max: usize, out: &mut Vec<f32>) -> usize {
    let max = max.min(MAX_CONTACTS);
    out.clear();
    let balloons = world.contact_points().map(|c| {
        let kind = if c.body_b.is_some() {
            KIND_BALLOON
        } else {
            KIND_ROOM
        };
        (c.point, c.normal, c.separation, kind)
    });
    let ribbons = world
        .ribbon_contacts()
        .iter()
        .map(|c| (c.point, c.normal, c.separation, KIND_RIBBONS));
    let mut total = 0;
    for (point, normal, separation, kind) in balloons.chain(ribbons) {
        total += 1;
        if total > max {
            continue;
        }
        out.extend_from_slice(&[
            point.x, point.y, point.z, normal.x, normal.y, normal.z, separation, kind,
        ]);
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bouquet's scene, its ribbons laid on one spot at their weights
    /// (touching there in the first steps, till they spread):
    /// `write_contacts` after `steps` steps, with ribbon contacts or without.
    fn bouquet_contacts(ribbon_contacts: bool, steps: u32) -> Vec<f32> {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/scenes/bouquet.toml"
        );
        let text = std::fs::read_to_string(path).expect("the bouquet scene");
        let text = text.replace(
            "ribbon_contacts = true",
            &format!("ribbon_contacts = {ribbon_contacts}"),
        );
        let mut state = crate::State::default();
        state.load_toml(&text).expect("the bouquet loads");
        state.step(steps).unwrap();
        let mut out = Vec::new();
        let total = write_contacts(state.world().unwrap(), MAX_CONTACTS, &mut out);
        assert_eq!(out.len(), total * CONTACT_FLOATS);
        out
    }

    fn of_kind(out: &[f32], kind: f32) -> Vec<&[f32]> {
        out.chunks(CONTACT_FLOATS)
            .filter(|c| c[7] == kind)
            .collect()
    }

    /// Where ribbons touch comes after the balloons' contacts, each a point
    /// with a unit normal and a separation within the millimetre listed;
    /// none with ribbon contacts off.
    #[test]
    fn ribbons_touching_are_written_after_the_balloons_contacts() {
        let on = bouquet_contacts(true, 2);
        let ribbons = of_kind(&on, KIND_RIBBONS);
        assert!(
            !ribbons.is_empty(),
            "no ribbon touches another in the bouquet"
        );
        let first = on
            .chunks(CONTACT_FLOATS)
            .position(|c| c[7] == KIND_RIBBONS)
            .unwrap();
        assert!(on
            .chunks(CONTACT_FLOATS)
            .skip(first)
            .all(|c| c[7] == KIND_RIBBONS));
        for c in ribbons {
            let normal = glam::Vec3::new(c[3], c[4], c[5]);
            assert!((normal.length() - 1.0).abs() < 1e-4, "{c:?}");
            assert!(c[6] <= 1e-3 && c[6] > -0.05, "{c:?}");
        }
        let off = bouquet_contacts(false, 2);
        assert!(of_kind(&off, KIND_RIBBONS).is_empty());
    }
}
