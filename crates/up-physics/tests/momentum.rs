//! Collisions between two balloons conserve momentum.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::{BodyId, World};

fn momenta(world: &World, ids: &[BodyId]) -> (Vec3, Vec3) {
    let mut p = Vec3::ZERO;
    let mut l = Vec3::ZERO;
    for &id in ids {
        let m = world.effective_mass(id).unwrap();
        let v = world.linear_velocity(id).unwrap();
        let c = world.center_of_mass(id).unwrap();
        let w = world.angular_velocity(id).unwrap();
        p += m * v;
        l += c.cross(m * v) + world.world_inertia(id).unwrap() * w;
    }
    (p, l)
}

#[test]
fn off_centre_collision_conserves_linear_and_angular_momentum() {
    let (mut world, shape) = world_with(free_space());
    let a = add(&mut world, shape, Vec3::new(-0.5, 1.0, 0.0), Quat::IDENTITY);
    let b = add(
        &mut world,
        shape,
        Vec3::new(0.5, 1.08, 0.03),
        Quat::from_rotation_z(0.3),
    );
    world
        .set_velocity(a, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0))
        .unwrap();
    world
        .set_velocity(b, Vec3::new(-1.0, 0.0, 0.2), Vec3::ZERO)
        .unwrap();
    let (p0, l0) = momenta(&world, &[a, b]);
    let mut touched = false;
    for _ in 0..120 {
        world.step();
        touched |= world.stats().contact_count > 0;
    }
    assert!(touched, "the balloons never met");
    let (p1, l1) = momenta(&world, &[a, b]);
    let va = world.linear_velocity(a).unwrap();
    assert!(va.x < 1.5, "A was not slowed by the collision: {va}");
    assert!((p1 - p0).length() <= 1e-4 * p0.length(), "p {p0} -> {p1}");
    assert!(
        (l1 - l0).length() <= 1e-4 * l0.length().max(p0.length() * 0.1),
        "L {l0} -> {l1}"
    );
    let w = world.angular_velocity(b).unwrap();
    assert!(w.length() > 1e-3, "an off-centre hit spins B: {w}");
}
