//! Ribbons are solved four at a time, a ribbon a SIMD lane: each must come
//! out bit for bit as it does alone (in the first lane, beside spare ones),
//! whatever ribbons share its group, through falls, swings, pushes off the
//! floor and off its own balloon, and a second group of another length; and
//! the same whether the balloons' leaf spheres were placed for all ribbons
//! at once or by each ribbon that needs them.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::ribbon::RibbonDef;
use up_physics::{BodyId, RibbonId, World, WorldDef};

/// Ribbons in the shared world: four of 16 segments (one group) and one of 12.
const RIBBONS: usize = 5;

/// Ribbon `k`: its length, weight and segments differ from the others'.
fn ribbon_def(k: usize, body: BodyId) -> RibbonDef {
    let segments = if k == 4 { 12 } else { 16 };
    let length = 1.2 + 0.1 * k as f32;
    RibbonDef {
        end_mass: if k % 2 == 1 { 0.01 } else { 0.0 },
        ..RibbonDef::new(body, Vec3::new(0.0, -0.2, 0.0), length, segments)
    }
}

/// A wide room with balloons `ks`, each thrown its own way, far apart (no
/// balloon reaches another's ribbon), and `bare` balloons without ribbons
/// far from them all.
fn world_of(ks: &[usize], bare: usize) -> (World, Vec<(BodyId, RibbonId)>) {
    let def = WorldDef {
        room: Some(room(30.0, 30.0, 3.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let mut tied = Vec::new();
    for &k in ks {
        let f = k as f32;
        let at = Vec3::new(-10.0 + 4.0 * f, 1.0 + 0.2 * f, 0.0);
        let id = add(&mut world, shape, at, Quat::from_rotation_z(0.1 * f));
        let (v, w) = (
            Vec3::new(0.6 * f - 1.2, 0.5, 0.3),
            Vec3::new(0.0, 2.0, 1.0 - f),
        );
        world.set_velocity(id, v, w).expect("live body");
        let ribbon = world.add_ribbon(&ribbon_def(k, id)).expect("valid ribbon");
        tied.push((id, ribbon));
    }
    for k in 0..bare {
        add(
            &mut world,
            shape,
            Vec3::new(-10.0 + k as f32, 1.0, 10.0),
            Quat::IDENTITY,
        );
    }
    (world, tied)
}

fn bits(points: &[Vec3]) -> Vec<[u32; 3]> {
    points
        .iter()
        .map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

#[test]
fn ribbons_side_by_side_move_as_each_alone() {
    let steps = 120;
    let all: Vec<usize> = (0..RIBBONS).collect();
    // With more balloons than twice the ribbons, the ribbons place the leaves
    // of the balloons they come near themselves; alone, every balloon's
    // leaves are placed for them: both give the same.
    let (mut together, tied) = world_of(&all, 2 * RIBBONS);
    // Each ribbon's lowest point over the run.
    let mut lowest = [f32::MAX; RIBBONS];
    for _ in 0..steps {
        together.step();
        for (k, &(_, ribbon)) in tied.iter().enumerate() {
            let points = together.ribbon_points(ribbon).unwrap();
            lowest[k] = points.iter().fold(lowest[k], |m, p| m.min(p.y));
        }
    }
    for k in 0..RIBBONS {
        let (mut alone, one) = world_of(&[k], 0);
        for _ in 0..steps {
            alone.step();
        }
        let (ribbon, alone_ribbon) = (tied[k].1, one[0].1);
        let points = together.ribbon_points(ribbon).unwrap();
        assert_eq!(
            bits(points),
            bits(alone.ribbon_points(alone_ribbon).unwrap()),
            "ribbon {k}'s points"
        );
        assert_eq!(
            bits(together.ribbon_velocities(ribbon).unwrap()),
            bits(alone.ribbon_velocities(alone_ribbon).unwrap()),
            "ribbon {k}'s velocities"
        );
        let balloon = [(&together, tied[k].0), (&alone, one[0].0)]
            .map(|(w, id)| bits(&[w.center_of_mass(id).expect("live body")]));
        assert_eq!(balloon[0], balloon[1], "ribbon {k}'s balloon");
        // It lay on the floor at some point (pushes off the room; a weight
        // rests its 2.5 cm radius above it).
        let low = lowest[k];
        assert!(low < 0.03, "ribbon {k} never came down to the floor: {low}");
    }
}
