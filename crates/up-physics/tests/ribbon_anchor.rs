//! A ribbon whose free end is tied to a fixed point (`RibbonDef::anchor`):
//! the balloon floats at the ribbon's length above it, with or without a
//! rope joint doing the same; anchors out of reach are refused.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::ribbon::RibbonDef;
use up_physics::{
    DistanceJointDef, DistanceLimit, JointAnchor, PhysicsError, RibbonId, World, WorldDef,
};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);
const LENGTH: f32 = 1.0;
const SEGMENTS: u32 = 16;

/// A room 6 m square and 4 m high, one balloon at (0, 2, 0) on a 1 m
/// ribbon tied to `anchor`, and a rope joint of the same length from its
/// knot to the anchor if `rope`.
fn anchored(anchor: Vec3, rope: bool) -> (World, RibbonId) {
    let def = WorldDef {
        room: Some(room(6.0, 6.0, 4.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let id = add(&mut world, shape, Vec3::new(0.0, 2.0, 0.0), Quat::IDENTITY);
    let ribbon = world
        .add_ribbon(&RibbonDef {
            anchor: Some(anchor),
            ..RibbonDef::new(id, KNOT, LENGTH, SEGMENTS)
        })
        .expect("an anchor within reach");
    if rope {
        world
            .add_distance_joint(&DistanceJointDef {
                a: JointAnchor::Body {
                    body: id,
                    point: KNOT,
                },
                b: JointAnchor::Fixed(anchor),
                length: LENGTH,
                limit: DistanceLimit::Rope,
                compliance: 0.0,
            })
            .unwrap();
    }
    (world, ribbon)
}

fn floats_a_ribbon_length_above_its_anchor(rope: bool) {
    // Off to the side and below: the balloon rises and swings over it.
    let anchor = Vec3::new(0.3, 1.0, 0.2);
    let (mut world, ribbon) = anchored(anchor, rope);
    let start = world.ribbon_points(ribbon).unwrap().to_vec();
    assert_eq!(start[SEGMENTS as usize], anchor);
    assert!(world.ribbon_stretch(ribbon).unwrap().abs() < 1e-4);
    for _ in 0..(30 * 60) {
        world.step();
    }
    let points = world.ribbon_points(ribbon).unwrap();
    let (knot, end) = (points[0], points[SEGMENTS as usize]);
    let segment = LENGTH / SEGMENTS as f32;
    println!(
        "rope {rope}: knot at {knot}, anchor {anchor}, end {end}, stretch {}",
        world.ribbon_stretch(ribbon).unwrap()
    );
    assert_eq!(end, anchor, "the end left its anchor");
    let above = anchor + Vec3::Y * LENGTH;
    assert!(
        knot.distance(above) < segment,
        "knot at {knot}, expected within {segment} m of {above}"
    );
    // Taut: at its length, to within the chain solve's tolerance (2e-3 of
    // each segment a substep) with the balloon's whole lift on it.
    let stretch = world.ribbon_stretch(ribbon).unwrap();
    assert!(stretch.abs() < 2.5e-3, "stretch {stretch}");
    assert!(knot.distance(anchor) > LENGTH - 0.01 * LENGTH);
    let pull = world.ribbon_pull(ribbon).unwrap();
    assert!(pull.y < 0.0, "the ribbon holds the balloon down: {pull}");
}

#[test]
fn a_balloon_on_an_anchored_ribbon_floats_its_length_above_the_anchor() {
    floats_a_ribbon_length_above_its_anchor(false);
}

#[test]
fn the_same_with_a_rope_joint_to_the_anchor() {
    floats_a_ribbon_length_above_its_anchor(true);
}

#[test]
fn an_anchor_out_of_reach_or_not_finite_is_refused_and_the_tied_end_cannot_be_grabbed() {
    let (mut world, shape) = world_with(free_space());
    let id = add(&mut world, shape, Vec3::new(0.0, 2.0, 0.0), Quat::IDENTITY);
    let def = |anchor| RibbonDef {
        anchor: Some(anchor),
        ..RibbonDef::new(id, KNOT, LENGTH, SEGMENTS)
    };
    let far = world.add_ribbon(&def(Vec3::new(0.0, 0.0, 0.0)));
    assert!(
        matches!(&far, Err(PhysicsError::BadRibbon(why)) if why.contains("beyond")),
        "{far:?}"
    );
    let nan = world.add_ribbon(&def(Vec3::NAN));
    assert!(
        matches!(nan, Err(PhysicsError::NonFinite { .. })),
        "{nan:?}"
    );
    let ribbon = world.add_ribbon(&def(Vec3::new(0.0, 1.5, 0.0))).unwrap();
    let end = SEGMENTS as usize;
    assert!(world.grab_ribbon(ribbon, end, Vec3::ZERO).is_err());
    assert!(world.grab_ribbon(ribbon, end - 1, Vec3::ZERO).is_ok());
}
