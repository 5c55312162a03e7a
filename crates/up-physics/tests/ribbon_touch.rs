//! Ribbons touching ribbons (`ribbon::touch`), physics against physics: a
//! ribbon dropped across a taut one hangs over it; the same with the
//! contacts off falls through it.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::ribbon::{RibbonContact, RibbonDef};
use up_physics::{DistanceJointDef, DistanceLimit, JointAnchor, RibbonId, World, WorldDef};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);
const SEGMENTS: u32 = 24;

/// A balloon whose knot is held at `knot` by a short rope (its lift pulls
/// it up against the rope), with a ribbon of `length` m tied to `anchor`
/// if given.
fn held_ribbon(
    world: &mut World,
    shape: up_physics::ShapeId,
    knot: Vec3,
    length: f32,
    anchor: Option<Vec3>,
) -> RibbonId {
    let body = add(world, shape, knot - KNOT, Quat::IDENTITY);
    world
        .add_distance_joint(&DistanceJointDef {
            a: JointAnchor::Body { body, point: KNOT },
            b: JointAnchor::Fixed(knot),
            length: 0.001,
            limit: DistanceLimit::Rope,
            compliance: 0.0,
        })
        .unwrap();
    world
        .add_ribbon(&RibbonDef {
            anchor,
            ..RibbonDef::new(body, KNOT, length, SEGMENTS)
        })
        .unwrap()
}

/// Height of the taut ribbon's middle (it runs along z at x = 0, laid
/// sagging at its length between its ends at 1.5 and 1.45 m).
const TAUT_HEIGHT: f32 = 1.418;

/// The taut ribbon along z from (0, 1.5, −0.5) to its anchor at
/// (0, 1.45, 0.49), 1 m long; the other, 0.95 m, held below it at
/// (−0.35, 1.35, 0), its end carried straight up above its knot and over
/// the taut one to (0.3, 2.0, 0) (nearly straight, clear above it), then
/// let go; after `seconds` more: the dropped ribbon's points, their
/// root-mean-square speed, the world's ribbon contacts, and the taut
/// ribbon's root-mean-square speed.
fn drape(contacts: bool, seconds: f32) -> (Vec<Vec3>, f32, Vec<RibbonContact>, f32) {
    let def = WorldDef {
        room: Some(room(4.0, 4.0, 3.0, None)),
        ribbon_contacts: contacts,
        enable_sleep: false,
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let anchor = Vec3::new(0.0, 1.45, 0.49);
    let taut = held_ribbon(
        &mut world,
        shape,
        Vec3::new(0.0, 1.5, -0.5),
        1.0,
        Some(anchor),
    );
    let dropped = held_ribbon(&mut world, shape, Vec3::new(-0.35, 1.35, 0.0), 0.95, None);
    world
        .grab_ribbon(dropped, SEGMENTS as usize, Vec3::new(-0.35, 2.28, 0.05))
        .unwrap();
    for _ in 0..90 {
        world.step();
    }
    world.set_grab_target(Vec3::new(0.3, 2.0, 0.0)).unwrap();
    for _ in 0..90 {
        world.step();
    }
    world.release_grab();
    for _ in 0..(seconds * 60.0) as u32 {
        world.step();
    }
    let rms = |ribbon| {
        let v = world.ribbon_velocities(ribbon).unwrap();
        (v.iter().map(|v| v.length_squared()).sum::<f32>() / v.len() as f32).sqrt()
    };
    (
        world.ribbon_points(dropped).unwrap().to_vec(),
        rms(dropped),
        world.ribbon_contacts().to_vec(),
        rms(taut),
    )
}

/// The highest point of `points` within 3 cm of the taut ribbon's line
/// (x = 0): its index and height.
fn crest(points: &[Vec3]) -> Option<(usize, f32)> {
    points
        .iter()
        .enumerate()
        .filter(|(_, p)| p.x.abs() < 0.03)
        .map(|(i, p)| (i, p.y))
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// The drape: after 10 s the dropped ribbon rests over the taut one, its
/// highest point near the taut ribbon no lower than the taut ribbon's
/// middle, at least three points of each half more than 5 cm below it, and
/// (the closed form) its far half, free at the end, hanging straight down
/// from that point: its end below the crest by the far half's length
/// (segments times segment length) within 2 cm, and within 2 cm of it
/// across; its points' root-mean-square speed under 1 cm/s. Fails if it
/// slips through the taut ribbon (no crest there), slides off either side,
/// or still swings.
#[test]
fn a_ribbon_dropped_across_a_taut_one_hangs_over_it() {
    let (points, rms, contacts, _) = drape(true, 10.0);
    let end = *points.last().unwrap();
    let (top, height) = crest(&points).expect("no point near the taut ribbon");
    let below = |side: &[Vec3]| side.iter().filter(|p| p.y < TAUT_HEIGHT - 0.05).count();
    let (near, far) = (below(&points[..top]), below(&points[top..]));
    let segment = 0.95 / SEGMENTS as f32;
    let hanging = (SEGMENTS as usize - top) as f32 * segment;
    let across = (end - points[top]).with_y(0.0).length();
    println!(
        "draped: resting at {height:.4} m (the taut ribbon at {TAUT_HEIGHT}), point {top}; {near} points below it on the knot's side, {far} on the far side; end at {end}, {:.4} m below the crest (hanging straight: {hanging:.4} m), {across:.4} m across; rms speed {rms:.4} m/s",
        height - end.y
    );
    assert!(
        height > TAUT_HEIGHT - 0.01,
        "fell through: highest near the taut ribbon at {height}"
    );
    assert!(near >= 3 && far >= 3, "halves below: {near} and {far}");
    assert!(
        (height - end.y - hanging).abs() < 0.02 && across < 0.02,
        "the far half does not hang straight down from the crest: end {end}, crest {}",
        points[top]
    );
    assert!(rms < 0.01, "still moving at {rms} m/s after 10 s");
    // What the page marks: the crest rests on the taut ribbon, touching it
    // from above: the contacts listed within 3 cm of it (the fold's two
    // segments on the taut one's flanks, or its point on top), each within
    // half the two ribbons' thickness of touching, hold it up together
    // (their normals, from the taut ribbon, listed first as it was added
    // first, toward the dropped one, sum to within 45° of straight up).
    let on_crest: Vec<_> = contacts
        .iter()
        .filter(|c| c.point.distance(points[top]) < 0.03)
        .collect();
    assert!(
        !on_crest.is_empty(),
        "no contact listed at the crest {}: {contacts:?}",
        points[top]
    );
    for c in &on_crest {
        assert!(c.separation.abs() < 2.5e-3, "{c:?}");
    }
    let up = on_crest.iter().map(|c| c.normal).sum::<Vec3>().normalize();
    assert!(up.y > 0.7, "not on top: {on_crest:?}");
}

#[test]
fn without_contacts_the_dropped_ribbon_falls_through() {
    let (points, _, contacts, _) = drape(false, 10.0);
    assert!(contacts.is_empty(), "contacts listed with contacts off");
    let height = crest(&points).map_or(f32::MIN, |c| c.1);
    println!("contacts off: highest near the taut ribbon {height}");
    assert!(
        height < TAUT_HEIGHT - 0.01,
        "rested on the taut ribbon with contacts off"
    );
}

/// The ribbon that the dropped one lies across comes to rest under it too:
/// after 10 s and after 30 s its points' root-mean-square speed is under
/// 1 cm/s, as the dropped ribbon's is (both balloons are held still; a
/// trembling ribbon would keep its balloon awake).
#[test]
fn the_taut_ribbon_under_a_draped_one_comes_to_rest() {
    for seconds in [10.0, 30.0] {
        let (_, dropped, _, taut) = drape(true, seconds);
        println!("after {seconds} s: the taut ribbon at {taut:.4} m/s, the draped one at {dropped:.4} m/s");
        assert!(
            taut < 0.01,
            "the taut ribbon still moves at {taut} m/s after {seconds} s"
        );
    }
}
