//! The force probe (`World::probed_forces`) against physics: a balloon at
//! terminal speed feels no net force, buoyancy is ρ·V·g, the floor carries a
//! resting balloon's net weight, a ribbon pulls with the weight it holds up,
//! and `terminal_speed` is the speed a balloon reaches. Probing changes nothing.

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::ribbon::{RibbonDef, DEFAULT_MASS_PER_LENGTH};
use up_physics::{BalloonShape, BodyId, ForceProbe, World, WorldDef};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);

/// A world with a 2 m square room `height` high, no sleep, and one balloon of `shape` at `at`.
fn one_balloon(shape: BalloonShape, height: f32, at: Vec3) -> (World, BodyId) {
    let def = WorldDef {
        room: Some(room(2.0, 2.0, height, None)),
        enable_sleep: false,
        ..WorldDef::default()
    };
    let mut world = World::new(def).unwrap();
    let shape = world.add_shape(shape).unwrap();
    let id = add(&mut world, shape, at, Quat::IDENTITY);
    (world, id)
}

fn steps(world: &mut World, n: usize) {
    for _ in 0..n {
        world.step();
    }
}

#[test]
fn a_balloon_rising_at_terminal_speed_feels_no_net_force() {
    let (mut world, id) = one_balloon(reference_balloon(), 40.0, Vec3::new(0.0, 1.0, 0.0));
    world.set_force_probe(ForceProbe::One(id));
    steps(&mut world, 6 * 60);
    let f = world.probed_forces(id).expect("probed");
    let weight = f.weight.length();
    let b = reference_balloon();
    let g = world.def().gravity;
    assert!((f.weight - b.mass * g).length() <= 1e-6 * weight);
    let rho = world.air().air_density();
    let expected = -rho * b.volume * g;
    assert!(
        (f.buoyancy - expected).length() <= 1e-5 * expected.length(),
        "buoyancy {} N, ρ·V·g {expected} N",
        f.buoyancy
    );
    assert_eq!(f.contact, Vec3::ZERO, "it touches nothing");
    assert_eq!((f.ribbon, f.other, f.knot), (Vec3::ZERO, Vec3::ZERO, None));
    assert!(f.drag.y < 0.0, "drag holds it back: {}", f.drag);
    assert!(
        f.total().length() <= 0.01 * weight,
        "net {} N at {} m/s (weight {weight} N)",
        f.total(),
        world.linear_velocity(id).unwrap()
    );
    // Where they act: the centre of mass, and the head's centre above it.
    let com = world.center_of_mass(id).unwrap();
    assert_eq!(f.center_of_mass, com);
    assert!(f.center_of_buoyancy.y > com.y);
    // Another body is not probed; off, nothing is.
    world.set_force_probe(ForceProbe::Off);
    world.step();
    assert_eq!(world.probed_forces(id), None);
}

#[test]
fn terminal_speed_is_the_speed_a_balloon_reaches() {
    let (mut world, id) = one_balloon(reference_balloon(), 40.0, Vec3::new(0.0, 1.0, 0.0));
    let predicted = world.terminal_speed(id).unwrap();
    steps(&mut world, 6 * 60);
    let y0 = world.center_of_mass(id).unwrap().y;
    steps(&mut world, 2 * 60);
    let measured = (world.center_of_mass(id).unwrap().y - y0) / 2.0;
    assert!(
        (measured - predicted).abs() <= 0.01 * predicted,
        "rose at {measured} m/s, terminal speed {predicted} m/s"
    );
}

#[test]
fn the_floor_carries_a_resting_balloons_net_weight_awake_or_asleep() {
    let heavy = BalloonShape {
        mass: 0.02,
        ..reference_balloon()
    };
    let (mut world, id) = one_balloon(heavy.clone(), 2.5, Vec3::new(0.0, 0.5, 0.0));
    world.set_force_probe(ForceProbe::All);
    steps(&mut world, 10 * 60);
    let f = world.probed_forces(id).unwrap();
    let net_weight = (f.weight + f.buoyancy).length();
    assert!(f.contact.y > 0.0);
    assert!(
        (f.contact + f.weight + f.buoyancy).length() <= 0.01 * net_weight,
        "contact {} N, weight {} N, buoyancy {} N",
        f.contact,
        f.weight,
        f.buoyancy
    );
    assert!(f.drag.length() <= 1e-3 * net_weight);

    // Asleep it is at rest: the floor carries the same.
    let def = WorldDef {
        room: Some(room(2.0, 2.0, 2.5, None)),
        ..WorldDef::default()
    };
    let mut world = World::new(def).unwrap();
    let shape = world.add_shape(heavy).unwrap();
    let id = add(&mut world, shape, Vec3::new(0.0, 0.5, 0.0), Quat::IDENTITY);
    world.set_force_probe(ForceProbe::One(id));
    steps(&mut world, 10 * 60);
    assert_eq!(world.is_awake(id), Some(false), "it fell asleep");
    let asleep = world.probed_forces(id).unwrap();
    assert!((asleep.contact - f.contact).length() <= 0.01 * net_weight);
    assert_eq!(asleep.total(), Vec3::ZERO);
}

#[test]
fn a_ribbon_pulls_its_balloon_with_the_weight_it_holds_up() {
    // 5 g on 1 m of ribbon: the balloon lifts both to the ceiling.
    let (length, end_mass) = (1.0, 0.005);
    let (mut world, id) = one_balloon(reference_balloon(), 3.0, Vec3::new(0.0, 0.9, 0.0));
    world
        .add_ribbon(&RibbonDef {
            end_mass,
            ..RibbonDef::new(id, KNOT, length, 10)
        })
        .unwrap();
    world.set_force_probe(ForceProbe::One(id));
    steps(&mut world, 15 * 60);
    // Averaged over two seconds: the weight still sways a little.
    let (mut ribbon, mut total, n) = (Vec3::ZERO, Vec3::ZERO, 120);
    for _ in 0..n {
        world.step();
        let f = world.probed_forces(id).unwrap();
        ribbon += f.ribbon / n as f32;
        total += f.total() / n as f32;
    }
    let f = world.probed_forces(id).unwrap();
    let g = world.def().gravity;
    let held = (end_mass + DEFAULT_MASS_PER_LENGTH * length) * g;
    println!("ribbon: pull {ribbon} N, ribbon and weight {held} N, net {total} N");
    assert!(
        (ribbon - held).length() <= 0.03 * held.length(),
        "pull {ribbon} N, the ribbon and weight weigh {held} N"
    );
    let knot = f.knot.expect("a ribbon has a knot");
    assert!(knot.y < f.center_of_mass.y, "the knot hangs below: {knot}");
    // At rest against the ceiling the whole breakdown balances.
    assert!(f.contact.y < 0.0);
    assert!(
        total.length() <= 0.01 * f.buoyancy.length(),
        "net {total} N"
    );
}

#[test]
fn probing_changes_nothing_in_the_step() {
    let run = |probe: ForceProbe| {
        let (mut world, shape) = world_with(WorldDef {
            room: Some(room(3.0, 3.0, 3.0, None)),
            ..WorldDef::default()
        });
        let ids: Vec<BodyId> = (0..12)
            .map(|k| {
                let at = Vec3::new(-1.0 + 0.6 * (k % 4) as f32, 0.5 + 0.6 * (k / 4) as f32, 0.0);
                add(&mut world, shape, at, Quat::IDENTITY)
            })
            .collect();
        world.set_force_probe(match probe {
            ForceProbe::One(_) => ForceProbe::One(ids[5]),
            p => p,
        });
        world
            .set_velocity(ids[0], Vec3::new(3.0, 1.0, 0.0), Vec3::ZERO)
            .unwrap();
        world
            .grab(ids[3], world.center_of_mass(ids[3]).unwrap())
            .unwrap();
        steps(&mut world, 120);
        world.state_hash()
    };
    let off = run(ForceProbe::Off);
    assert_eq!(run(ForceProbe::All), off);
    assert_eq!(
        run(ForceProbe::One(BodyId {
            index: 0,
            generation: 0
        })),
        off
    );
}

#[test]
fn a_hand_holding_a_balloon_still_carries_its_net_lift_as_other() {
    let (mut world, id) = one_balloon(reference_balloon(), 3.0, Vec3::new(0.0, 1.5, 0.0));
    let at = world.center_of_mass(id).unwrap();
    world.grab(id, at).unwrap();
    world.set_grab_target(at).unwrap();
    world.set_force_probe(ForceProbe::One(id));
    steps(&mut world, 5 * 60);
    let f = world.probed_forces(id).unwrap();
    let lift = f.weight + f.buoyancy;
    assert!(lift.y > 0.0);
    assert!(
        (f.other + lift).length() <= 0.01 * lift.length(),
        "the hand pulls {} N against a net lift of {lift} N",
        f.other
    );
    assert_eq!(f.contact, Vec3::ZERO);
    // Let go, the hand's share is gone.
    world.release_grab();
    world.step();
    assert_eq!(world.probed_forces(id).unwrap().other, Vec3::ZERO);
}
