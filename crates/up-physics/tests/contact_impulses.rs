//! The impulses each contact reports (`ContactInfo`): at rest they carry the
//! body's net weight; in a collision, the momentum each body changed by.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::{BalloonShape, BodyId, World, WorldDef};

/// The contacts' impulses on `id` over the last step, N·s, world frame:
/// normal and friction, with the sign of the side it is on.
fn impulse_on(world: &World, id: BodyId) -> Vec3 {
    world
        .contact_points()
        .map(|c| {
            // A takes −λ·n plus its friction; B the opposite.
            let on_a = -c.normal_impulse * c.normal + c.tangent_impulse;
            if c.body_a == id {
                on_a
            } else if c.body_b == Some(id) {
                -on_a
            } else {
                Vec3::ZERO
            }
        })
        .sum()
}

/// The room's push on a balloon resting against it, averaged over a second
/// after it settled, against its net weight (weight − buoyancy).
fn rest_against_room(shape_def: BalloonShape, start: Vec3) -> (Vec3, Vec3) {
    let def = WorldDef {
        room: Some(room(2.0, 2.0, 2.5, None)),
        enable_sleep: false,
        ..WorldDef::default()
    };
    let air = def.atmosphere.air_density();
    let g = def.gravity;
    let mut world = World::new(def).unwrap();
    let net_weight = shape_def.mass * g - air * shape_def.volume * g;
    let shape = world.add_shape(shape_def).unwrap();
    let id = add(&mut world, shape, start, Quat::IDENTITY);
    for _ in 0..600 {
        world.step();
    }
    let steps = 60;
    let mut push = Vec3::ZERO;
    for _ in 0..steps {
        world.step();
        push += impulse_on(&world, id);
    }
    let speed = world.linear_velocity(id).unwrap().length();
    assert!(speed < 1e-3, "not at rest: {speed} m/s");
    (push / (steps as f32 * world.def().dt), net_weight)
}

#[test]
fn the_floor_carries_an_air_filled_balloons_net_weight() {
    let heavy = BalloonShape {
        mass: 0.02,
        ..reference_balloon()
    };
    let (push, net_weight) = rest_against_room(heavy, Vec3::new(0.0, 0.5, 0.0));
    assert!(net_weight.y < 0.0, "the balloon should be heavier than air");
    let error = (push + net_weight).length() / net_weight.length();
    assert!(error < 0.01, "push {push} N against net weight {net_weight} N");
}

#[test]
fn the_ceiling_holds_a_helium_balloons_net_lift() {
    let (push, net_weight) = rest_against_room(reference_balloon(), Vec3::new(0.0, 1.5, 0.0));
    assert!(net_weight.y > 0.0, "the balloon should lift");
    let error = (push + net_weight).length() / net_weight.length();
    assert!(error < 0.01, "push {push} N against net lift {} N", -net_weight);
}

#[test]
fn a_head_on_collision_s_impulses_are_the_momentum_each_balloon_changed_by() {
    let (mut world, shape) = world_with(free_space());
    let a = add(&mut world, shape, Vec3::new(-0.5, 1.0, 0.0), Quat::IDENTITY);
    let b = add(&mut world, shape, Vec3::new(0.5, 1.0, 0.0), Quat::IDENTITY);
    world.set_velocity(a, Vec3::new(2.0, 0.0, 0.0), Vec3::ZERO).unwrap();
    world.set_velocity(b, Vec3::new(-2.0, 0.0, 0.0), Vec3::ZERO).unwrap();
    let mass = world.effective_mass(a).unwrap();
    let v0 = world.linear_velocity(a).unwrap();
    let (mut on_a, mut on_b, mut peak, mut peak_total) = (Vec3::ZERO, Vec3::ZERO, 0.0f32, 0.0f32);
    for _ in 0..60 {
        world.step();
        on_a += impulse_on(&world, a);
        on_b += impulse_on(&world, b);
        for c in world.contact_points() {
            assert!(c.normal_impulse >= 0.0 && c.max_normal_impulse >= 0.0);
            assert!(c.max_normal_impulse <= c.normal_impulse * (1.0 + 1e-6));
            if c.max_normal_impulse > peak {
                (peak, peak_total) = (c.max_normal_impulse, c.normal_impulse);
            }
        }
    }
    let change = mass * (world.linear_velocity(a).unwrap() - v0);
    assert!(change.x < -0.5 * mass * 2.0, "no bounce: Δp {change}");
    assert!(
        (on_a - change).length() < 0.01 * change.length(),
        "impulses {on_a} N·s against Δp {change} N·s"
    );
    assert!((on_a + on_b).length() < 1e-6, "{on_a} vs {on_b}");
    // The impact's peak substep carries at least its share of the step's push.
    let substeps = world.def().substeps as f32;
    assert!(peak >= peak_total / substeps, "{peak} of {peak_total}");
    assert!((world.substep_dt() * substeps - world.def().dt).abs() < 1e-9);
}
