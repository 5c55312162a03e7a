//! A ribbon's weight on the floor against Coulomb's law: pulled sideways
//! through its ribbon by its balloon (a constant force on the balloon, as a
//! gentle air jet gives), it holds below μ times the floor's normal force and
//! slides at the closed form's acceleration above it.

mod common;

use std::sync::Arc;

use common::*;
use glam::{Quat, Vec3};
use up_physics::ribbon::{RibbonDef, ROOM_FRICTION, WEIGHT_RADIUS};
use up_physics::{BodyId, FieldSample, ForceField, RibbonId, World, WorldDef};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);
/// The weight at the ribbon's end, kg (a foil balloon weight).
const WEIGHT: f32 = 0.035;
/// The ribbon, m, and its segments: 16 mg a point against the weight's
/// 35 g, as the bouquet's (a ribbon of 8 mg points under this pull jumps
/// its weight off the floor within a second, friction or none: a matter of
/// the chain's solve, not of the floor's).
const LENGTH: f32 = 0.5;
const SEGMENTS: u32 = 8;
/// The balloon's upward pull, N, about an 11-inch balloon's free lift: its
/// own weight and buoyancy are taken off and this put in their place, so
/// that the floor's normal force on the weight is known.
const LIFT: f32 = 0.1;
/// The sideways force grows from nothing to its full value over this, s, so
/// that the balloon leans over to it without swinging.
const RAMP_SECONDS: f64 = 2.0;

/// On the balloon: `LIFT` up in place of its weight and buoyancy, and
/// `side` N along +x, ramped.
struct Pull {
    side: f32,
    gravity: Vec3,
    air_density: f32,
}

impl ForceField for Pull {
    fn force(&self, body: &FieldSample) -> Vec3 {
        let ramp = (body.time / RAMP_SECONDS).min(1.0) as f32;
        lift_in_place_of_weight(body, self.gravity, self.air_density, LIFT)
            + ramp * self.side * Vec3::X
    }
}

/// A balloon on its ribbon over its weight, which rests on the floor of a
/// 6 m room at x = -2 m; no drag or added mass on the balloon (the closed
/// form is friction's alone), no sleep (a sleeping weight holds for free).
fn weight_on_the_floor() -> (World, BodyId, RibbonId) {
    let def = WorldDef {
        room: Some(room(6.0, 6.0, 3.0, None)),
        drag_coefficient: 0.0,
        added_mass_coefficient: 0.0,
        enable_sleep: false,
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    // The weight hangs a few millimetres over the floor and drops onto it.
    let knot = Vec3::new(-2.0, WEIGHT_RADIUS + LENGTH + 0.005, 0.0);
    let id = add(&mut world, shape, knot - KNOT, Quat::IDENTITY);
    let ribbon = world
        .add_ribbon(&RibbonDef {
            end_mass: WEIGHT,
            ..RibbonDef::new(id, KNOT, LENGTH, SEGMENTS)
        })
        .unwrap();
    (world, id, ribbon)
}

/// The floor's normal force on the weight, N: the ribbon's and weight's
/// weight less the balloon's pull.
fn normal_force(world: &World, ribbon: RibbonId) -> f32 {
    let mass = world.ribbon_length_and_mass(ribbon).unwrap().1;
    mass * world.def().gravity.length() - LIFT
}

/// Where the pulled weight and the whole (balloon, ribbon and weight) are
/// along x at the end of each step, m.
struct Track {
    weight: Vec<f32>,
    whole: Vec<f32>,
    dt: f32,
    /// The floor's normal force, N, and the mass of the whole, kg.
    normal: f32,
    mass: f32,
}

impl Track {
    /// The index of the step that ends at `t`, s.
    fn at(&self, t: f32) -> usize {
        (t / self.dt).round() as usize - 1
    }
}

/// Pulls the balloon sideways with `fraction` of μ times the floor's normal
/// force on the weight, for `seconds`.
fn pulled(fraction: f32, seconds: f32) -> Track {
    let (mut world, balloon, ribbon) = weight_on_the_floor();
    let def = world.def().clone();
    let normal = normal_force(&world, ribbon);
    assert!(normal > 0.0, "the weight rests: {normal} N");
    world.add_force_field(Arc::new(Pull {
        side: fraction * ROOM_FRICTION * normal,
        gravity: def.gravity,
        air_density: def.atmosphere.air_density(),
    }));
    let balloon_mass = reference_balloon().mass;
    // The ribbon's quarter gram taken with its weight.
    let hanging = world.ribbon_length_and_mass(ribbon).unwrap().1;
    let mass = balloon_mass + hanging;
    let steps = (seconds / def.dt).round() as usize;
    let mut track = Track {
        weight: Vec::with_capacity(steps),
        whole: Vec::with_capacity(steps),
        dt: def.dt,
        normal,
        mass,
    };
    for step in 0..steps {
        world.step();
        let end = *world.ribbon_points(ribbon).unwrap().last().unwrap();
        let landed = step as f32 * def.dt > 0.5;
        assert!(
            !landed || end.y < WEIGHT_RADIUS + 5e-3,
            "the weight lifts: {end}"
        );
        let centre = world.center_of_mass(balloon).unwrap();
        track.weight.push(end.x);
        track
            .whole
            .push((balloon_mass * centre.x + hanging * end.x) / mass);
    }
    track
}

#[test]
fn a_weight_pulled_below_static_friction_holds() {
    let seconds = 10.0;
    let track = pulled(0.5, RAMP_SECONDS as f32 + seconds);
    let x = &track.weight;
    let ramped = track.at(RAMP_SECONDS as f32);
    let drift = (x[x.len() - 1] - x[ramped]).abs();
    let worst = x.iter().map(|&p| (p - x[0]).abs()).fold(0.0f32, f32::max);
    println!(
        "at 0.5 μN: {:.4} mm over the {seconds} s after the ramp, at most {:.4} mm from the start",
        drift * 1e3,
        worst * 1e3
    );
    assert!(drift < 1e-3, "crept {} mm over {seconds} s", drift * 1e3);
}

#[test]
fn a_weight_pulled_above_friction_slides_at_the_kinetic_rate() {
    let track = pulled(1.5, RAMP_SECONDS as f32 + 1.0);
    let side = 1.5 * ROOM_FRICTION * track.normal;
    // Pulled forward by the side force, held back by kinetic friction: the
    // whole's centre of mass (the balloon swings over the weight, the
    // whole does not).
    let expected = (side - ROOM_FRICTION * track.normal) / track.mass;
    // Its acceleration over the second after the ramp, from three positions
    // half a second apart.
    let t0 = RAMP_SECONDS as f32;
    let [a, b, c] = [t0, t0 + 0.5, t0 + 1.0].map(|t| track.whole[track.at(t)]);
    let measured = (c - 2.0 * b + a) / 0.25;
    println!(
        "at 1.5 μN: {measured:.4} m/s², expected {expected:.4} m/s² (normal force {:.4} N); \
         the weight slid {:.3} m",
        track.normal,
        track.weight[track.weight.len() - 1] - track.weight[0]
    );
    assert!(
        (measured - expected).abs() < 0.2 * expected,
        "{measured} m/s², expected {expected} m/s²"
    );
}
