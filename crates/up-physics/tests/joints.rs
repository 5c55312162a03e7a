//! Joints solved with the balloons: a tethered balloon, two balloons on a
//! rod, and joints kept by snapshots and dropped with their bodies; and a
//! force field that a scene adds.

mod common;

use std::sync::Arc;

use common::*;
use glam::{Quat, Vec3};
use up_physics::forces::buoyancy::buoyancy_force;
use up_physics::forces::gravity::gravity_force;
use up_physics::{
    DistanceJointDef, DistanceLimit, FieldSample, ForceField, JointAnchor, PhysicsError, World,
    WorldDef,
};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);

/// Buoyancy less weight of the reference balloon in `def`'s air, N (> 0: it rises).
fn net_lift(def: &WorldDef) -> f32 {
    let b = reference_balloon();
    let air = def.atmosphere.air_density();
    (buoyancy_force(air, b.volume, def.gravity) + gravity_force(b.mass, def.gravity)).y
}

/// A balloon tied by its knot to a fixed point `length` below the knot's
/// start, tilted 30° so that it swings as it pulls.
fn tethered(length: f32) -> (World, up_physics::BodyId, up_physics::JointId) {
    let (mut world, shape) = world_with(WorldDef::default());
    let tilt = Quat::from_rotation_z(30f32.to_radians());
    let id = add(&mut world, shape, Vec3::new(0.0, 2.0, 0.0), tilt);
    let knot = world.pose(id).unwrap().transform_point(KNOT);
    let joint = world
        .add_distance_joint(&DistanceJointDef {
            a: JointAnchor::Body {
                body: id,
                point: KNOT,
            },
            b: JointAnchor::Fixed(knot - Vec3::Y * length),
            length,
            limit: DistanceLimit::Rope,
            compliance: 0.0,
        })
        .expect("valid tether");
    (world, id, joint)
}

#[test]
fn tethered_balloon_holds_the_tether_length_and_pulls_with_its_net_lift() {
    let length = 1.0;
    let (mut world, id, joint) = tethered(length);
    let mut taut_steps = 0;
    for step in 0..(10 * 60) {
        world.step();
        let [knot, anchor] = world.joint_ends(joint).unwrap();
        let stretch = (knot - anchor).length() / length - 1.0;
        if stretch > -1e-4 {
            taut_steps += 1;
        }
        assert!(
            stretch <= 0.001,
            "step {step}: stretched {:.4} %",
            100.0 * stretch
        );
    }
    // It swung upright, still swaying a little (still air damps a slow
    // swing slowly), and pulls on the tether with its net lift.
    assert!(
        tilt_degrees(&world, id) < 2.0,
        "{}",
        tilt_degrees(&world, id)
    );
    let lift = net_lift(world.def());
    let tension = world.joint_tension(joint).unwrap();
    assert!(
        (tension - lift).abs() <= 0.01 * lift,
        "tension {tension} N, net lift {lift} N"
    );
    // A real tether, taut nearly all along, not a slack one.
    assert!(lift > 0.1, "{lift}");
    assert!(taut_steps > 550, "taut in {taut_steps} steps of 600");
}

#[test]
fn a_rod_between_two_tumbling_balloons_keeps_its_length_and_their_momentum() {
    let (mut world, shape) = world_with(free_space());
    let a = add(&mut world, shape, Vec3::ZERO, Quat::IDENTITY);
    let b = add(&mut world, shape, Vec3::new(0.6, 0.1, 0.0), Quat::IDENTITY);
    world
        .set_velocity(a, Vec3::new(0.0, 1.0, 0.3), Vec3::new(0.0, 0.0, 4.0))
        .unwrap();
    world
        .set_velocity(b, Vec3::new(0.5, -1.0, 0.0), Vec3::new(3.0, 0.0, 0.0))
        .unwrap();
    let pa = world.pose(a).unwrap();
    let pb = world.pose(b).unwrap();
    let length = (pa.transform_point(KNOT) - pb.transform_point(KNOT)).length();
    let joint = world
        .add_distance_joint(&DistanceJointDef {
            a: JointAnchor::Body {
                body: a,
                point: KNOT,
            },
            b: JointAnchor::Body {
                body: b,
                point: KNOT,
            },
            length,
            limit: DistanceLimit::Rod,
            compliance: 0.0,
        })
        .unwrap();
    let momentum = |w: &World| {
        [a, b]
            .iter()
            .map(|&id| w.effective_mass(id).unwrap() * w.linear_velocity(id).unwrap())
            .sum::<Vec3>()
    };
    let before = momentum(&world);
    for step in 0..240 {
        world.step();
        let [ka, kb] = world.joint_ends(joint).unwrap();
        let error = ((ka - kb).length() / length - 1.0).abs();
        assert!(
            error <= 0.001,
            "step {step}: length off by {:.4} %",
            100.0 * error
        );
    }
    let after = momentum(&world);
    assert!(
        (after - before).length() <= 1e-3 * before.length(),
        "momentum {before} -> {after}"
    );
    // The rod did work: both balloons turned into a shared motion.
    assert!(world.joint_tension(joint).unwrap().abs() > 0.0);
}

#[test]
fn snapshots_keep_joints_and_removing_a_body_drops_its_joints() {
    let (mut world, id, joint) = tethered(0.5);
    for _ in 0..30 {
        world.step();
    }
    let mut restored = World::restore(&world.snapshot()).expect("restores");
    assert_eq!(restored.joint_count(), 1);
    for _ in 0..60 {
        world.step();
        restored.step();
    }
    assert_eq!(world.state_hash(), restored.state_hash());
    assert_eq!(world.joint_tension(joint), restored.joint_tension(joint));

    world.remove_body(id).unwrap();
    assert_eq!(world.joint_count(), 0);
    assert_eq!(world.joint_tension(joint), None);
    assert_eq!(
        world.remove_joint(joint),
        Err(PhysicsError::StaleJoint(joint))
    );
}

#[test]
fn bad_joints_are_refused_with_what_is_wrong() {
    let (mut world, shape) = world_with(WorldDef::default());
    let id = add(&mut world, shape, Vec3::ZERO, Quat::IDENTITY);
    let def = DistanceJointDef {
        a: JointAnchor::Body {
            body: id,
            point: KNOT,
        },
        b: JointAnchor::Fixed(Vec3::ZERO),
        length: 1.0,
        limit: DistanceLimit::Rope,
        compliance: 0.0,
    };
    let refused =
        |d: DistanceJointDef, world: &mut World| world.add_distance_joint(&d).unwrap_err();
    let e = refused(DistanceJointDef { length: 0.0, ..def }, &mut world);
    assert!(e.to_string().contains("length"), "{e}");
    let e = refused(
        DistanceJointDef {
            compliance: -1.0,
            ..def
        },
        &mut world,
    );
    assert!(e.to_string().contains("compliance"), "{e}");
    let e = refused(
        DistanceJointDef {
            a: def.b,
            b: def.a,
            ..def
        },
        &mut world,
    );
    assert!(e.to_string().contains("on a body"), "{e}");
    let nan = JointAnchor::Fixed(Vec3::NAN);
    let e = refused(DistanceJointDef { b: nan, ..def }, &mut world);
    assert!(e.to_string().contains("non-finite"), "{e}");
    world.remove_body(id).unwrap();
    assert_eq!(refused(def, &mut world), PhysicsError::StaleBody(id));
    assert_eq!(world.joint_count(), 0);
}

/// Holds every balloon against its own net lift.
struct Counterweight {
    air_density: f32,
    gravity: Vec3,
}

impl ForceField for Counterweight {
    fn force(&self, body: &FieldSample) -> Vec3 {
        let lift = gravity_force(body.mass, self.gravity)
            + buoyancy_force(self.air_density, body.volume, self.gravity);
        -lift
    }
}

#[test]
fn a_force_field_that_cancels_the_lift_holds_a_balloon_in_place() {
    let (mut world, shape) = world_with(WorldDef::default());
    let start = Vec3::new(0.0, 1.0, 0.0);
    let id = add(&mut world, shape, start, Quat::IDENTITY);
    let def = world.def().clone();
    world.add_force_field(Arc::new(Counterweight {
        air_density: def.atmosphere.air_density(),
        gravity: def.gravity,
    }));
    let center = world.center_of_mass(id).unwrap();
    for _ in 0..120 {
        world.step();
    }
    assert_eq!(world.linear_velocity(id).unwrap(), Vec3::ZERO);
    assert_eq!(world.center_of_mass(id).unwrap(), center);
    // Without it, the same balloon rises.
    world.clear_force_fields();
    for _ in 0..60 {
        world.step();
    }
    assert!(world.linear_velocity(id).unwrap().y > 0.5);
}
