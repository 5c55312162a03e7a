//! Ribbons against physics: the pull of a hanging ribbon, the height at which
//! a balloon hovers on a ribbon lying on the floor, the stretch of a ribbon
//! jerked by a thrown balloon, the terminal ascent with a ribbon, a balloon
//! on a weight, and ribbons that never leave the room.

mod common;

use std::sync::Arc;

use common::*;
use glam::{Quat, Vec3};
use up_physics::divergence::lockstep_with;
use up_physics::forces::buoyancy::buoyancy_force;
use up_physics::forces::drag::drag_factor;
use up_physics::forces::gravity::gravity_force;
use up_physics::ribbon::{
    RibbonDef, DEFAULT_MASS_PER_LENGTH, RIBBON_RADIUS, RIBBON_WIDTH, TANGENT_DRAG_COEFFICIENT,
    WEIGHT_RADIUS,
};
use up_physics::{BodyId, FieldSample, ForceField, PhysicsError, RibbonId, World, WorldDef};

/// The reference balloon's knot, in its mesh frame.
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);
const G: f32 = 9.81;

/// Buoyancy less weight of the reference balloon in `def`'s air, N.
fn net_lift(def: &WorldDef) -> f32 {
    let b = reference_balloon();
    let air = def.atmosphere.air_density();
    (buoyancy_force(air, b.volume, def.gravity) + gravity_force(b.mass, def.gravity)).y
}

/// A world with a flat-ceilinged room `width` square and `height` high (or
/// none), and one upright balloon at `center` with a ribbon.
fn balloon_on_ribbon(
    room_size: Option<(f32, f32)>,
    center: Vec3,
    ribbon: impl FnOnce(BodyId) -> RibbonDef,
) -> (World, BodyId, RibbonId) {
    let def = WorldDef {
        room: room_size.map(|(w, h)| room(w, w, h, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let id = add(&mut world, shape, center, Quat::IDENTITY);
    let ribbon = world.add_ribbon(&ribbon(id)).expect("valid ribbon");
    (world, id, ribbon)
}

/// A hand holding each balloon at where it started: a stiff, critically
/// damped spring that also carries the balloon's net lift.
struct Hand {
    at: Vec3,
    lift: f32,
}

const HAND_STIFFNESS: f32 = 20.0;

impl ForceField for Hand {
    fn force(&self, body: &FieldSample) -> Vec3 {
        let damping = 2.0 * (HAND_STIFFNESS * 0.014f32).sqrt();
        -self.lift * Vec3::Y - HAND_STIFFNESS * (body.center - self.at) - damping * body.velocity
    }
}

#[test]
fn a_hanging_ribbon_pulls_on_the_knot_with_its_weight_straight_down() {
    let (length, segments) = (1.5, 16);
    let (mut world, id, ribbon) = balloon_on_ribbon(None, Vec3::new(0.0, 5.0, 0.0), |body| {
        RibbonDef::new(body, KNOT, length, segments)
    });
    let lift = net_lift(world.def());
    let at = world.center_of_mass(id).unwrap();
    world.add_force_field(Arc::new(Hand { at, lift }));
    // Swing it a little first: the pull must not depend on how it got there.
    world
        .set_velocity(id, Vec3::new(0.3, 0.0, 0.0), Vec3::ZERO)
        .unwrap();
    for _ in 0..(8 * 60) {
        world.step();
    }
    let weight = DEFAULT_MASS_PER_LENGTH * length * G;
    let pull = world.ribbon_pull(ribbon).unwrap();
    println!("hanging: pull {pull} N against λ·L·g = {weight} N");
    assert!(
        (pull.y + weight).abs() <= 0.01 * weight,
        "pull {pull} N, the ribbon weighs {weight} N"
    );
    assert!(
        pull.x.hypot(pull.z) <= 0.01 * weight,
        "not straight down: {pull}"
    );
    assert!(world.ribbon_stretch(ribbon).unwrap().abs() < 1e-3);
}

#[test]
fn a_balloon_on_a_heavy_ribbon_hovers_where_the_lifted_ribbon_weighs_its_lift() {
    // 10 g/m, 2 m: 20 g of ribbon under 11.2 g of lift.
    let (lambda, length, segments) = (0.010, 2.0, 16);
    let (mut world, _, ribbon) =
        balloon_on_ribbon(Some((6.0, 3.0)), Vec3::new(0.0, 1.0, 0.0), |body| {
            RibbonDef {
                mass_per_length: lambda,
                ..RibbonDef::new(body, KNOT, length, segments)
            }
        });
    let expected = net_lift(world.def()) / (lambda * G);
    for _ in 0..(30 * 60) {
        world.step();
    }
    let points = world.ribbon_points(ribbon).unwrap();
    let knot_height = points[0].y;
    let segment = length / segments as f32;
    println!("hover: knot at {knot_height} m, F/(λ·g) = {expected} m");
    assert!(
        (knot_height - expected).abs() <= segment + RIBBON_RADIUS,
        "the knot hovers at {knot_height} m, expected {expected} m"
    );
    // The rest of the ribbon lies on the floor.
    let lying = points.iter().filter(|p| p.y < 2.0 * RIBBON_RADIUS).count();
    let off_floor = (expected / segment).ceil() as usize;
    assert!(
        lying + off_floor >= segments as usize,
        "{lying} points on the floor"
    );
}

#[test]
fn a_ribbon_jerked_by_a_thrown_balloon_stays_within_one_percent() {
    let (mut world, id, ribbon) =
        balloon_on_ribbon(Some((6.0, 3.0)), Vec3::new(-2.0, 1.8, 0.0), |body| {
            RibbonDef::new(body, KNOT, 1.5, 16)
        });
    for _ in 0..60 {
        world.step();
    }
    world
        .set_velocity(id, Vec3::new(5.0, 0.0, 0.0), Vec3::ZERO)
        .unwrap();
    let mut worst = 0.0f32;
    for step in 0..(4 * 60) {
        world.step();
        let stretch = world.ribbon_stretch(ribbon).unwrap();
        worst = worst.max(stretch);
        assert!(stretch <= 0.01, "step {step}: stretch {stretch}");
        // Its own segments hold their length both ways; only the one at the
        // knot may go slack (a ribbon never pushes its balloon).
        let points = world.ribbon_points(ribbon).unwrap();
        for (k, pair) in points.windows(2).enumerate().skip(1) {
            let l = pair[0].distance(pair[1]);
            assert!(
                (l / (1.5 / 16.0) - 1.0).abs() <= 0.01,
                "step {step}: segment {k} is {l} m"
            );
        }
    }
    println!("thrown at 5 m/s: worst stretch {worst}");
    assert!(world.ribbon_max_stretch() >= worst);
    assert!(world.ribbon_max_stretch() <= 0.01);
}

#[test]
fn a_balloon_rises_at_the_terminal_speed_of_balloon_and_ribbon() {
    let (length, segments) = (1.5, 16);
    let (mut world, id, ribbon) = balloon_on_ribbon(None, Vec3::ZERO, |body| {
        RibbonDef::new(body, KNOT, length, segments)
    });
    let def = world.def().clone();
    let air = def.atmosphere.air_density();
    let b = reference_balloon();
    // Balloon: ½ρC_D·A. Ribbon rising along its length: the along-drag of its
    // points (each a segment's share; the end half of one).
    let k_balloon = drag_factor(air, def.drag_coefficient, b.reference_area);
    let segment = length / segments as f32;
    let shares = segments as f32 - 0.5;
    let k_ribbon = 0.5 * air * TANGENT_DRAG_COEFFICIENT * RIBBON_WIDTH * segment * shares;
    let lifted = net_lift(&def) - DEFAULT_MASS_PER_LENGTH * length * G;
    let expected = (lifted / (k_balloon + k_ribbon)).sqrt();
    for _ in 0..(5 * 60) {
        world.step();
    }
    let (y0, t0) = (world.center_of_mass(id).unwrap().y, world.time());
    for _ in 0..(3 * 60) {
        world.step();
    }
    let mean = (world.center_of_mass(id).unwrap().y - y0) / (world.time() - t0) as f32;
    println!("ascent: {mean} m/s, expected {expected} m/s");
    assert!(
        (mean - expected).abs() <= 0.02 * expected,
        "rises at {mean} m/s, expected {expected} m/s"
    );
    // The ribbon trails straight below.
    let points = world.ribbon_points(ribbon).unwrap();
    let end = *points.last().unwrap();
    assert!((points[0] - end).y > 0.99 * length, "{points:?}");
}

#[test]
fn a_balloon_on_a_heavy_weight_floats_at_its_ribbon_length_and_a_light_weight_rises() {
    let (length, segments) = (1.0, 10);
    let heavy = 0.020;
    let (mut world, _, ribbon) =
        balloon_on_ribbon(Some((6.0, 3.0)), Vec3::new(0.0, 0.9, 0.0), |body| {
            RibbonDef {
                end_mass: heavy,
                ..RibbonDef::new(body, KNOT, length, segments)
            }
        });
    for _ in 0..(15 * 60) {
        world.step();
    }
    let points = world.ribbon_points(ribbon).unwrap();
    let (knot, weight) = (points[0], *points.last().unwrap());
    assert!(
        (weight.y - WEIGHT_RADIUS).abs() < 2e-3,
        "the weight is on the floor: {weight}"
    );
    let segment = length / segments as f32;
    assert!(
        (knot.y - weight.y - length).abs() <= segment,
        "the knot floats {} m above the weight",
        knot.y - weight.y
    );
    assert!((knot - weight).normalize().y > 0.999, "taut and straight");
    let lift = net_lift(world.def());
    let pull = world.ribbon_pull(ribbon).unwrap().length();
    println!(
        "weight: knot {} m above it, pull {pull} N, net lift {lift} N",
        knot.y - weight.y
    );
    assert!(
        (pull - lift).abs() <= 0.01 * lift,
        "pull {pull} N, net lift {lift} N"
    );

    // 5 g: lighter than the lift less the ribbon's weight, carried up.
    let light = 0.005;
    let (mut world, id, ribbon) =
        balloon_on_ribbon(Some((6.0, 3.0)), Vec3::new(0.0, 0.9, 0.0), |body| {
            RibbonDef {
                end_mass: light,
                ..RibbonDef::new(body, KNOT, length, segments)
            }
        });
    for _ in 0..(15 * 60) {
        world.step();
    }
    let weight = *world.ribbon_points(ribbon).unwrap().last().unwrap();
    let top = world.center_of_mass(id).unwrap().y + HEAD_RADIUS;
    assert!(top > 2.95, "the balloon is at the ceiling: {top}");
    assert!(weight.y > 1.5, "the weight hangs below it: {weight}");
}

#[test]
fn ribbons_never_leave_the_room() {
    // 500 balloons with 1.5 m ribbons released in the original room (6 m
    // square, 3 m walls, a pyramidal ceiling 1.5 m higher at its apex):
    // every point, every step, inside.
    let (width, height, apex) = (6.0, 3.0, Some(1.5));
    let def = WorldDef {
        room: Some(room(width, width, height, apex)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let mut ribbons = Vec::new();
    let mut next = up_physics::up_geom::SplitMix64::new(11);
    for k in 0..500 {
        let (ix, iz, layer) = (k % 16, (k / 16) % 16, k / 256);
        let x = -2.6 + 0.35 * ix as f32 + 0.02 * (next.unit() - 0.5);
        let z = -2.6 + 0.35 * iz as f32 + 0.02 * (next.unit() - 0.5);
        let y = 0.4 + 0.45 * layer as f32;
        let yaw = Quat::from_rotation_y(6.0 * next.unit());
        let id = add(&mut world, shape, Vec3::new(x, y, z), yaw);
        ribbons.push(
            world
                .add_ribbon(&RibbonDef::new(id, KNOT, 1.5, 16))
                .unwrap(),
        );
    }
    for step in 0..(12 * 60) {
        world.step();
        for &r in &ribbons {
            for p in world.ribbon_points(r).unwrap() {
                let inside = inside_room(*p, width, width, height, apex) && p.y >= 0.0;
                assert!(inside, "step {step}: ribbon {r:?} has a point at {p}");
            }
        }
        assert!(
            world.ribbon_max_stretch() <= 0.01,
            "step {step}: stretch {}",
            world.ribbon_max_stretch()
        );
    }
    println!("500 released: worst stretch {}", world.ribbon_max_stretch());
}

#[test]
fn ribbons_are_deterministic_on_any_number_of_threads_and_kept_by_snapshots() {
    let build = || {
        let def = WorldDef {
            room: Some(room(4.0, 4.0, 3.0, None)),
            ..WorldDef::default()
        };
        let (mut world, shape) = world_with(def);
        for k in 0..300 {
            let p = Vec3::new(
                -1.7 + 0.34 * (k % 11) as f32,
                0.3 + 0.4 * (k / 121) as f32,
                -1.7 + 0.34 * ((k / 11) % 11) as f32,
            );
            let id = add(&mut world, shape, p, Quat::from_rotation_z(0.3));
            world
                .add_ribbon(&RibbonDef::new(id, KNOT, 1.2, 12))
                .unwrap();
        }
        world
    };
    let pool = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    };
    let (one_thread, three_threads) = (pool(1), pool(3));
    let (mut one, mut three) = (one_thread.install(build), three_threads.install(build));
    // Compared body by body (and ribbon by ribbon) after every step: a
    // difference names its step and balloon.
    let parted = lockstep_with(
        &mut one,
        &mut three,
        120,
        |w| one_thread.install(|| w.step()),
        |w| three_threads.install(|| w.step()),
    );
    if let Some(parted) = parted {
        panic!("three threads against one: {parted}");
    }
    assert_eq!(one.state_hash(), three.state_hash());
    let mut restored = World::restore(&one.snapshot()).unwrap();
    let mut original = one;
    for _ in 0..30 {
        original.step();
        restored.step();
    }
    assert_eq!(original.state_hash(), restored.state_hash());
    assert_eq!(restored.ribbon_count(), 300);
}

#[test]
fn bad_ribbons_are_refused_naming_what_is_wrong() {
    let (mut world, shape) = world_with(WorldDef::default());
    let id = add(&mut world, shape, Vec3::ZERO, Quat::IDENTITY);
    let ok = RibbonDef::new(id, KNOT, 1.0, 8);
    let refused = |world: &mut World, def: RibbonDef, says: &str| match world.add_ribbon(&def) {
        Err(PhysicsError::BadRibbon(why)) => assert!(why.contains(says), "{why}"),
        other => panic!("{other:?}"),
    };
    refused(&mut world, RibbonDef { length: 0.0, ..ok }, "length");
    refused(&mut world, RibbonDef { segments: 1, ..ok }, "segments");
    refused(
        &mut world,
        RibbonDef {
            segments: 129,
            ..ok
        },
        "segments",
    );
    refused(
        &mut world,
        RibbonDef {
            mass_per_length: -1.0,
            ..ok
        },
        "mass per metre",
    );
    refused(
        &mut world,
        RibbonDef {
            end_mass: f32::NAN,
            ..ok
        },
        "weight",
    );
    let r = world.add_ribbon(&ok).unwrap();
    refused(&mut world, ok, "already has a ribbon");
    // Removing the balloon removes its ribbon.
    world.remove_body(id).unwrap();
    assert_eq!(world.ribbon_count(), 0);
    assert_eq!(world.ribbon_points(r), None);
}

#[test]
fn balloons_and_their_ribbons_fall_asleep_and_wake_together() {
    // Twenty balloons on ribbons under a flat ceiling.
    let def = WorldDef {
        room: Some(room(3.0, 3.0, 3.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let mut ids = Vec::new();
    for k in 0..20 {
        let p = Vec3::new(
            -1.2 + 0.6 * (k % 5) as f32,
            1.0,
            -0.9 + 0.6 * (k / 5) as f32,
        );
        let id = add(&mut world, shape, p, Quat::IDENTITY);
        world
            .add_ribbon(&RibbonDef::new(id, KNOT, 1.5, 16))
            .unwrap();
        ids.push(id);
    }
    let mut asleep_at = None;
    for step in 0..(60 * 60) {
        world.step();
        if world.stats().awake_count == 0 {
            asleep_at = Some(step);
            break;
        }
    }
    let asleep_at = asleep_at.expect("the pile never fell asleep");
    println!("asleep after {:.1} s", asleep_at as f32 / 60.0);
    // Asleep, nothing moves: not the balloons, not the ribbons.
    let before = world.state_hash();
    let r = world.ribbon_of(ids[7]).unwrap();
    let points: Vec<Vec3> = world.ribbon_points(r).unwrap().to_vec();
    for _ in 0..60 {
        world.step();
    }
    assert_eq!(world.ribbon_points(r).unwrap(), &points[..]);
    assert_ne!(before, world.state_hash(), "the step count moves on");
    // A push on one balloon wakes it, and its ribbon moves with it.
    world
        .apply_impulse_at_point(
            ids[7],
            Vec3::new(0.02, -0.02, 0.0),
            world.center_of_mass(ids[7]).unwrap(),
        )
        .unwrap();
    for _ in 0..30 {
        world.step();
    }
    assert!(world.is_awake(ids[7]).unwrap());
    let moved = world.ribbon_points(r).unwrap()[8].distance(points[8]);
    assert!(moved > 1e-3, "the ribbon stayed put: {moved} m");
}

#[test]
fn a_balloon_does_not_rest_while_its_ribbon_swings() {
    // A balloon resting against the ceiling, its ribbon's end drawn 30 cm
    // aside and let go: the ribbon swings under it, and the balloon may not
    // fall asleep (freezing the ribbon mid-swing) until the swing has died
    // down to about the sleep speed, whatever its knot does meanwhile.
    let (mut world, id, ribbon) =
        balloon_on_ribbon(Some((6.0, 3.0)), Vec3::new(0.0, 2.0, 0.0), |body| {
            RibbonDef::new(body, KNOT, 1.5, 16)
        });
    for _ in 0..(3 * 60) {
        world.step();
    }
    let end = *world.ribbon_points(ribbon).unwrap().last().unwrap();
    world.grab_ribbon(ribbon, 16, end).unwrap();
    for k in 1..=30 {
        world
            .set_grab_target(end + Vec3::new(0.3 * k as f32 / 30.0, 0.0, 0.0))
            .unwrap();
        world.step();
    }
    world.release_grab();
    let dt = world.def().dt;
    let slow = world.def().sleep_linear_speed;
    let mut last: Vec<Vec3> = world.ribbon_points(ribbon).unwrap().to_vec();
    let mut swing = Vec::new();
    for _ in 0..(60 * 60) {
        world.step();
        if world.is_awake(id) == Some(false) {
            break;
        }
        let now = world.ribbon_points(ribbon).unwrap();
        let sum: f32 = now
            .iter()
            .zip(&last)
            .skip(1)
            .map(|(a, b)| (*a - *b).length_squared())
            .sum();
        swing.push((sum / (now.len() - 1) as f32).sqrt() / dt);
        last = now.to_vec();
    }
    assert_eq!(world.is_awake(id), Some(false), "never rested");
    // Over the half second before it rested (the rest clock's), the
    // ribbon's points moved no faster than the sleep speed past what a
    // resting balloon may turn its knot at (its own sleep speeds, the knot
    // 0.2 m from its centre): the swing had died down from tens of cm/s.
    let before = &swing[swing.len().saturating_sub(30)..];
    let fastest = before.iter().fold(0.0f32, |m, &v| m.max(v));
    let at_first = swing.iter().take(60).fold(0.0f32, |m, &v| m.max(v));
    let knot_may = slow + world.def().sleep_angular_speed * KNOT.length();
    println!(
        "swung at {at_first:.3} m/s; rested {:.1} s after the release, the ribbon at most \
         {fastest:.4} m/s the last 0.5 s",
        swing.len() as f32 * dt
    );
    assert!(at_first > 0.1, "the ribbon hardly swung: {at_first} m/s");
    assert!(
        fastest < slow + knot_may,
        "rested while its ribbon swung at {fastest} m/s"
    );
}

#[test]
fn a_balloon_pulled_down_by_its_ribbon_follows_it() {
    let (mut world, id, ribbon) =
        balloon_on_ribbon(Some((6.0, 3.0)), Vec3::new(0.0, 2.0, 0.0), |body| {
            RibbonDef::new(body, KNOT, 1.5, 16)
        });
    for _ in 0..(3 * 60) {
        world.step();
    }
    let top = world.center_of_mass(id).unwrap().y;
    let end = *world.ribbon_points(ribbon).unwrap().last().unwrap();
    world.grab_ribbon(ribbon, 16, end).unwrap();
    assert_eq!(world.grabbed_ribbon(), Some((ribbon, 16)));
    // Drag the end down to 0.3 m above the floor over a second.
    for k in 1..=60 {
        let target = end + (Vec3::new(end.x, 0.3, end.z) - end) * (k as f32 / 60.0);
        world.set_grab_target(target).unwrap();
        world.step();
    }
    for _ in 0..60 {
        world.step();
    }
    let held = world.center_of_mass(id).unwrap().y;
    let points = world.ribbon_points(ribbon).unwrap();
    assert!(
        (points.last().unwrap().y - 0.3).abs() < 0.01,
        "the end is where it is held: {}",
        points.last().unwrap()
    );
    // The balloon floats on its taut ribbon above the hand.
    assert!(held < top - 0.5, "from {top} m down to {held} m");
    assert!(
        (points[0].y - 0.3 - 1.5).abs() < 0.05,
        "knot at {}",
        points[0]
    );
    assert_eq!(world.release_grab(), Some(id));
    for _ in 0..(3 * 60) {
        world.step();
    }
    assert!(
        world.center_of_mass(id).unwrap().y > held + 0.5,
        "it rises again"
    );
}
