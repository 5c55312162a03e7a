//! Force fields, the step's extension point, on ribbons: a field's force on
//! each ribbon point (and on the weight at its end) acts in the substeps
//! where the ribbons are solved, against a closed form.

mod common;

use std::sync::Arc;

use common::*;
use glam::{Quat, Vec3};
use up_physics::forces::buoyancy::buoyancy_force;
use up_physics::forces::gravity::gravity_force;
use up_physics::ribbon::RibbonDef;
use up_physics::{FieldSample, ForceField, PointSample, WorldDef};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);

/// Damping rate of the ribbon's swing, 1/s.
const POINT_DAMPING: f32 = 2.0;

/// Holds each balloon where it started against its net lift (a stiff,
/// damped spring), and pushes every ribbon point sideways with `side` m/s²
/// times its mass (and damps its swing): with gravity, a uniform field of acceleration, in which
/// a chain hangs straight at atan(side / g) from the vertical.
struct SidewaysOnRibbons {
    at: Vec3,
    air_density: f32,
    gravity: Vec3,
    side: f32,
}

impl ForceField for SidewaysOnRibbons {
    fn force(&self, body: &FieldSample) -> Vec3 {
        let lift = gravity_force(body.mass, self.gravity)
            + buoyancy_force(self.air_density, body.volume, self.gravity);
        let (stiffness, damping) = (20.0, 1.0);
        -lift - stiffness * (body.center - self.at) - damping * body.velocity
    }

    fn force_on_point(&self, point: &PointSample) -> Vec3 {
        // Damped in proportion to the mass too, which stills the swing
        // without moving where it comes to rest.
        point.mass * (self.side * Vec3::X - POINT_DAMPING * point.velocity)
    }
}

#[test]
fn a_sideways_field_on_the_points_tilts_a_hanging_ribbon_and_its_weight_by_its_angle() {
    let (mut world, shape) = world_with(WorldDef::default());
    let id = add(&mut world, shape, Vec3::new(0.0, 5.0, 0.0), Quat::IDENTITY);
    let (length, segments) = (1.0, 16);
    let ribbon = world
        .add_ribbon(&RibbonDef {
            end_mass: 0.002,
            ..RibbonDef::new(id, KNOT, length, segments)
        })
        .unwrap();
    let def = world.def().clone();
    let g = def.gravity.length();
    let angle = 15f32.to_radians();
    world.add_force_field(Arc::new(SidewaysOnRibbons {
        at: world.center_of_mass(id).unwrap(),
        air_density: def.atmosphere.air_density(),
        gravity: def.gravity,
        side: g * angle.tan(),
    }));
    for _ in 0..(20 * 60) {
        world.step();
    }
    let points = world.ribbon_points(ribbon).unwrap();
    let (knot, end) = (points[0], points[segments as usize]);
    let along = end - knot;
    let tilt = along.x.atan2(-along.y);
    println!(
        "ribbon at {:.3}° from the vertical, expected {:.3}°",
        tilt.to_degrees(),
        angle.to_degrees()
    );
    assert!(
        (tilt - angle).abs() < 0.1f32.to_radians(),
        "tilted {}°, expected {}°",
        tilt.to_degrees(),
        angle.to_degrees()
    );
    assert!(along.z.abs() < 1e-3, "out of the plane: {along}");
    // Straight: every point on the line from the knot to the end.
    let line = along.normalize();
    for p in points {
        let off = (*p - knot) - (*p - knot).dot(line) * line;
        assert!(
            off.length() < 2e-3,
            "{p} is {} m off the line",
            off.length()
        );
    }
    assert!(world.ribbon_stretch(ribbon).unwrap().abs() < 1e-3);
    // The knot carries the ribbon's weight and its sideways push.
    let pull = world.ribbon_pull(ribbon).unwrap();
    let mass = world.ribbon_length_and_mass(ribbon).unwrap().1;
    let expected = mass * Vec3::new(g * angle.tan(), -g, 0.0);
    assert!(
        (pull - expected).length() < 0.02 * expected.length(),
        "pull {pull} N, expected {expected} N"
    );
}

#[test]
fn without_a_force_on_points_a_field_leaves_the_ribbon_hanging_straight_down() {
    /// The balloon held, nothing on the ribbon (the trait's default).
    struct HoldOnly(SidewaysOnRibbons);
    impl ForceField for HoldOnly {
        fn force(&self, body: &FieldSample) -> Vec3 {
            self.0.force(body)
        }
    }
    let (mut world, shape) = world_with(WorldDef::default());
    let id = add(&mut world, shape, Vec3::new(0.0, 5.0, 0.0), Quat::IDENTITY);
    let ribbon = world
        .add_ribbon(&RibbonDef::new(id, KNOT, 1.0, 16))
        .unwrap();
    let def = world.def().clone();
    world.add_force_field(Arc::new(HoldOnly(SidewaysOnRibbons {
        at: world.center_of_mass(id).unwrap(),
        air_density: def.atmosphere.air_density(),
        gravity: def.gravity,
        side: 5.0,
    })));
    for _ in 0..(10 * 60) {
        world.step();
    }
    let points = world.ribbon_points(ribbon).unwrap();
    let along = points[16] - points[0];
    assert!(along.x.hypot(along.z) < 1e-3 * along.length(), "{along}");
}
