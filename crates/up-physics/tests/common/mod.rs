//! Shared fixtures for the scene-level tests: a reference balloon built from
//! the physics reference's worked numbers, and rooms.
#![allow(dead_code)]

use glam::{Mat3, Quat, Vec3};
use up_geom::{Pose, Sphere, SphereTree, TriMesh};
use up_physics::forces::buoyancy::buoyancy_force;
use up_physics::forces::gravity::gravity_force;
use up_physics::{BalloonShape, BodyDef, BodyId, FieldSample, ShapeId, World, WorldDef};

/// Head radius of the reference balloon, m.
pub const HEAD_RADIUS: f32 = 0.14;

/// An 11″ balloon after the physics reference: V 14.2 L, 5.4 g in all,
/// frontal area 0.0708 m². Body frame: head centre at the origin, Y up, the
/// knot at −0.2 m. The report's Figure 2 layout: a bounding sphere, a large
/// head, a thin neck, three fillers between.
pub fn reference_balloon() -> BalloonShape {
    let head = Sphere::new(Vec3::ZERO, HEAD_RADIUS);
    let fillers = [
        Sphere::new(Vec3::new(0.0, -0.07, 0.0), 0.115),
        Sphere::new(Vec3::new(0.0, -0.12, 0.0), 0.075),
        Sphere::new(Vec3::new(0.0, -0.16, 0.0), 0.04),
    ];
    let neck = Sphere::new(Vec3::new(0.0, -0.19, 0.0), 0.015);
    let root = Sphere::new(Vec3::new(0.0, -0.03, 0.0), 0.175);
    let mut leaves = vec![head];
    leaves.extend(fillers);
    leaves.push(neck);
    let tree = SphereTree::from_root_and_leaves(root, &leaves).expect("valid reference tree");
    // Latex (3 g) over a sphere of the head's radius, helium (2.36 g) filling it,
    // the knot (0.5 g — a guess) at the neck: I ≈ 2/3·m·r² + 2/5·m·r² + m_k·d².
    let (shell, gas, knot) = (0.003f32, 0.00236f32, 0.0005f32);
    let mass = shell + gas + knot;
    let knot_y = -0.2f32;
    let com_y = knot * knot_y / mass;
    let r2 = HEAD_RADIUS * HEAD_RADIUS;
    let i_head = 2.0 / 3.0 * shell * r2 + 0.4 * gas * r2;
    let ixx = i_head + (shell + gas) * com_y * com_y + knot * (knot_y - com_y).powi(2);
    BalloonShape {
        tree,
        mass,
        center_of_mass: Vec3::new(0.0, com_y, 0.0),
        inertia: Mat3::from_diagonal(Vec3::new(ixx, i_head, ixx)),
        volume: 0.0142,
        center_of_buoyancy: Vec3::ZERO,
        reference_area: 0.0708,
    }
}

/// A closed box room, floor at y = 0, centred on the y axis; flat ceiling at
/// `height`, or a pyramid with its apex `apex` above the walls. Normals point in.
pub fn room(width: f32, depth: f32, height: f32, apex: Option<f32>) -> TriMesh {
    let (x, z) = (width / 2.0, depth / 2.0);
    let mut v = vec![
        Vec3::new(-x, 0.0, -z),
        Vec3::new(x, 0.0, -z),
        Vec3::new(x, 0.0, z),
        Vec3::new(-x, 0.0, z),
        Vec3::new(-x, height, -z),
        Vec3::new(x, height, -z),
        Vec3::new(x, height, z),
        Vec3::new(-x, height, z),
    ];
    let quad = |a: u32, b: u32, c: u32, d: u32| [[a, b, c], [a, c, d]];
    let mut t = Vec::new();
    t.extend(quad(0, 1, 2, 3)); // floor, normal +y
    t.extend(quad(0, 4, 5, 1)); // z = -z wall, normal +z
    t.extend(quad(1, 5, 6, 2)); // x = +x wall, normal -x
    t.extend(quad(2, 6, 7, 3)); // z = +z wall, normal -z
    t.extend(quad(3, 7, 4, 0)); // x = -x wall, normal +x
    match apex {
        None => t.extend(quad(4, 7, 6, 5)), // ceiling, normal -y
        Some(h) => {
            v.push(Vec3::new(0.0, height + h, 0.0));
            t.extend([[4, 8, 5], [5, 8, 6], [6, 8, 7], [7, 8, 4]]);
        }
    }
    // The room is convex: turn every triangle to face its interior.
    let inside = Vec3::new(0.0, height / 2.0, 0.0);
    for tri in &mut t {
        let [a, b, c] = tri.map(|i| v[i as usize]);
        if (b - a).cross(c - a).dot(inside - (a + b + c) / 3.0) < 0.0 {
            tri.swap(1, 2);
        }
    }
    TriMesh::new(v, t).expect("valid room")
}

/// Inside the box or pyramid room built by `room` (with a small tolerance).
pub fn inside_room(p: Vec3, width: f32, depth: f32, height: f32, apex: Option<f32>) -> bool {
    let eps = 1e-3;
    let (x, z) = (width / 2.0, depth / 2.0);
    if p.x.abs() > x + eps || p.z.abs() > z + eps || p.y < -eps {
        return false;
    }
    let top = match apex {
        None => height,
        Some(h) => height + h * (1.0 - (p.x.abs() / x).max(p.z.abs() / z)),
    };
    p.y <= top + eps
}

/// No room, gravity, drag or damping, no sleep: bodies keep the velocities
/// they are given until they meet.
pub fn free_space() -> WorldDef {
    WorldDef {
        gravity: Vec3::ZERO,
        drag_coefficient: 0.0,
        angular_damping: 0.0,
        enable_sleep: false,
        ..WorldDef::default()
    }
}

pub fn world_with(def: WorldDef) -> (World, ShapeId) {
    let mut world = World::new(def).expect("valid world");
    let shape = world.add_shape(reference_balloon()).expect("valid shape");
    (world, shape)
}

pub fn add(world: &mut World, shape: ShapeId, position: Vec3, rotation: Quat) -> BodyId {
    world
        .add_body(&BodyDef::new(shape, Pose::new(position, rotation)))
        .expect("body added")
}

/// Angle between the body's +Y axis and world +Y, degrees.
pub fn tilt_degrees(world: &World, id: BodyId) -> f32 {
    let up = world.pose(id).expect("live body").rotation * Vec3::Y;
    up.dot(Vec3::Y).clamp(-1.0, 1.0).acos().to_degrees()
}

/// 60 balloons released in a room with a pyramid ceiling, each its own user data.
pub fn sixty_released() -> World {
    let def = WorldDef {
        room: Some(room(3.0, 3.0, 2.5, Some(1.0))),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    for i in 0..60 {
        let (x, z) = ((i % 8) as f32 * 0.33 - 1.2, (i / 8) as f32 * 0.33 - 1.2);
        let q = Quat::from_rotation_y(i as f32) * Quat::from_rotation_x(0.05 * (i % 5) as f32);
        add(&mut world, shape, Vec3::new(x, 0.3, z), q);
    }
    world
}

/// The force that leaves `lift` N straight up on a body in place of its
/// weight and buoyancy, so that what its ribbon or the floor bears is known.
pub fn lift_in_place_of_weight(
    body: &FieldSample,
    gravity: Vec3,
    air_density: f32,
    lift: f32,
) -> Vec3 {
    let own = gravity_force(body.mass, gravity) + buoyancy_force(air_density, body.volume, gravity);
    lift * Vec3::Y - own
}
