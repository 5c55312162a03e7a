//! A ribbon lying still on the floor rests (its still tail held, its
//! substeps stopped at the first point of it) until the chain pulls that
//! point harder than the floor's friction holds it: pulled past its
//! friction by its balloon, the lying part follows as when every point is
//! free, and no segment stretches.

mod common;

use std::sync::Arc;

use common::*;
use glam::{Quat, Vec3};
use up_physics::ribbon::RibbonDef;
use up_physics::{FieldSample, ForceField, WorldDef};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);
/// The balloon's upward pull, N: about half its 1.5 m ribbon's weight
/// (0.375 g), so that the other half lies on the floor.
const LIFT: f32 = 0.002;
/// The sideways pull once the ribbon has settled, N: several times what
/// the floor's friction holds of the lying half.
const SIDE: f32 = 0.004;
/// When the sideways pull starts, s.
const SETTLED: f64 = 6.0;

/// On each balloon: `LIFT` up in place of its weight and buoyancy; and on
/// the one at z = 0 (not the one at z = 1 m) `SIDE` along +x from `SETTLED` on.
struct Pull {
    gravity: Vec3,
    air_density: f32,
}

impl ForceField for Pull {
    fn force(&self, body: &FieldSample) -> Vec3 {
        let pulled = body.time >= SETTLED && body.center.z < 0.5;
        let side = if pulled { SIDE } else { 0.0 };
        lift_in_place_of_weight(body, self.gravity, self.air_density, LIFT) + side * Vec3::X
    }
}

#[test]
fn a_lying_ribbon_rests_and_follows_its_balloon_once_pulled() {
    let def = WorldDef {
        room: Some(room(6.0, 6.0, 3.0, None)),
        enable_sleep: false,
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let def = world.def().clone();
    let id = add(&mut world, shape, Vec3::new(-1.5, 1.0, 0.0), Quat::IDENTITY);
    let ribbon = world
        .add_ribbon(&RibbonDef::new(id, KNOT, 1.5, 16))
        .unwrap();
    // Another in the same lanes, not pulled.
    let other = add(&mut world, shape, Vec3::new(1.5, 1.0, 1.0), Quat::IDENTITY);
    let other = world
        .add_ribbon(&RibbonDef::new(other, KNOT, 1.5, 16))
        .unwrap();
    world.add_force_field(Arc::new(Pull {
        gravity: def.gravity,
        air_density: def.atmosphere.air_density(),
    }));
    let steps = |seconds: f64| (seconds / f64::from(def.dt)).round() as usize;
    let mut worst_stretch = 0.0f32;
    for _ in 0..steps(SETTLED) {
        world.step();
        worst_stretch = worst_stretch.max(world.ribbon_stretch(ribbon).unwrap());
    }
    // Settled: the lying points ended the step exactly still (friction held
    // them), those that rest from here on.
    let lying: Vec<Vec3> = world.ribbon_points(ribbon).unwrap().to_vec();
    let velocities = world.ribbon_velocities(ribbon).unwrap();
    let still = velocities.iter().filter(|v| **v == Vec3::ZERO).count();
    let on_floor = lying.iter().filter(|p| p.y < 0.003).count();
    println!("settled: {on_floor} points on the floor, {still} exactly still");
    assert!(
        on_floor >= 5 && still >= 4,
        "{on_floor} lying, {still} still"
    );
    // Resting, they stay exactly where they lie while nothing pulls.
    for _ in 0..steps(0.5) {
        world.step();
    }
    let end = lying.len() - 1;
    assert_eq!(world.ribbon_points(ribbon).unwrap()[end], lying[end]);
    // Pulled sideways: the lying part follows, its free end last.
    let mut moved_at = None;
    let both = |world: &up_physics::World| {
        let mut points = world.ribbon_points(ribbon).unwrap().to_vec();
        points.extend_from_slice(world.ribbon_points(other).unwrap());
        points
    };
    let mut before = both(&world);
    let mut fastest = 0.0f32;
    for step in 0..steps(8.0) {
        world.step();
        worst_stretch = worst_stretch.max(world.ribbon_stretch(ribbon).unwrap());
        let now = both(&world);
        let moves = now.iter().zip(&before).map(|(p, q)| p.distance(*q));
        fastest = moves.fold(fastest, f32::max);
        before = now;
        let points = world.ribbon_points(ribbon).unwrap();
        if moved_at.is_none() && (points[end].x - lying[end].x) > 0.05 {
            moved_at = Some(step);
        }
    }
    let points = world.ribbon_points(ribbon).unwrap();
    println!(
        "free end moved 5 cm after {moved_at:?} steps of the pull; {:.3} m in all; \
         worst stretch {worst_stretch}; fastest point {fastest} m a step",
        points[end].x - lying[end].x
    );
    assert!(moved_at.is_some(), "the lying end never followed");
    // As far as it goes with every point free (1.19 m): a held tail let go
    // only once its neighbour moved slides about half as far.
    assert!(
        points[end].x - lying[end].x > 1.0,
        "the lying end followed only {} m",
        points[end].x - lying[end].x
    );
    assert!(worst_stretch < 0.01, "stretched {worst_stretch}");
    // No point of either jumps (2 cm a step at most with every point free;
    // a point whose start was not kept when its lanes' substeps reached it
    // again flew a metre in a step).
    assert!(fastest < 0.05, "a point moved {fastest} m in a step");
}
