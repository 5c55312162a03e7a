//! Balloons that lose their gas, in the world: the lift a held balloon keeps
//! against the gas model's closed form, Charles's law through a temperature
//! schedule, a shrinking pile that keeps its overlap bound and its order, a
//! balloon sinking on its ribbon as the ribbon's weight takes over, and the
//! time-lapse against plain stepping (leaving the ceiling, coming down on a
//! ribbon).

mod common;

use common::*;
use glam::{Quat, Vec3};
use up_physics::gas::model::HELIUM_MOLAR_MASS;
use up_physics::ribbon::{RibbonDef, RibbonId};
use up_physics::{
    BodyId, EnvelopeDef, PhysicsError, TemperatureSchedule, World, WorldDef, WAKE_GROWTH,
    WAKE_SHRINK,
};

const HOUR: f64 = 3600.0;
const G: f32 = 9.81;
const KNOT: Vec3 = Vec3::new(0.0, -0.2, 0.0);

/// The reference balloon's envelope (3 g of latex over 0.289 m², a 0.5 g
/// knot), its permeance times `faster`.
fn envelope(faster: f64) -> EnvelopeDef {
    let mut def = EnvelopeDef::latex(0.0035, 0.003, 0.289, 1.0, 1.0);
    def.helium_permeance *= faster;
    def
}

/// A flat-ceilinged room `width` square and `height` high with `n` balloons
/// in a row on its floor, each filled with `envelope`.
fn room_of_balloons(
    width: f32,
    height: f32,
    n: usize,
    envelope: &EnvelopeDef,
) -> (World, Vec<BodyId>) {
    let def = WorldDef {
        room: Some(room(width, width, height, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let ids: Vec<BodyId> = (0..n)
        .map(|k| {
            let x = (k as f32 - (n as f32 - 1.0) / 2.0) * 0.4;
            let id = add(&mut world, shape, Vec3::new(x, 0.3, 0.0), Quat::IDENTITY);
            world.fill(id, envelope, 0.0).expect("valid envelope");
            id
        })
        .collect();
    (world, ids)
}

#[test]
fn a_balloon_at_the_ceiling_keeps_the_lift_the_closed_form_gives() {
    // Helium alone through latex: n = n₀/(1 + t/τ)³, τ = 3·n₀/(K·p), and the
    // gas's lift ρ_air·V − m_gas follows n (V ∝ n).
    let mut def = envelope(1.0);
    def.air_ratio = 0.0;
    let (mut world, ids) = room_of_balloons(2.0, 3.0, 1, &def);
    let id = ids[0];
    let gas0 = world.gas(id).unwrap();
    let air = world.air();
    let (n0, lift0) = (gas0.moles(), gas0.gas_lift_kg(&air));
    let p = f64::from(air.pressure_pa + def.overpressure_pa);
    let tau = 3.0 * n0 / (def.helium_permeance * p);
    let mut jumped = 0;
    for hour in 1..=6 {
        jumped += world.advance(HOUR, 10_000).jumps;
        let t = world.time();
        let expected = lift0 / (1.0 + t / tau).powi(3);
        let lift = world.gas(id).unwrap().gas_lift_kg(&world.air());
        let error = (lift - expected).abs() / expected;
        assert!(
            error < 0.01,
            "hour {hour}: lift {lift} kg against {expected} kg"
        );
        // The body weighs what its gas and envelope weigh.
        let m = world.gas(id).unwrap().mass();
        assert!((m - 0.0035 - world.gas(id).unwrap().helium_mol * HELIUM_MOLAR_MASS).abs() < 1e-9);
    }
    assert!(
        jumped > 100,
        "the balloon slept at the ceiling: {jumped} jumps"
    );
    // It sleeps with the size it had when it fell asleep, within the wake thresholds.
    let scale = world.body_scale(id).unwrap();
    let gas_scale = world.gas(id).unwrap().scale(&world.air());
    assert!(scale < 0.97, "shrunk to {scale}");
    let slack = WAKE_SHRINK as f32 + 1e-3;
    assert!(
        (scale / gas_scale - 1.0).abs() <= slack,
        "{scale} against {gas_scale}"
    );
}

#[test]
fn a_warming_room_swells_the_balloons_by_charles_law() {
    // 5 °C to 30 °C over an hour, no leak: V ∝ T.
    let def = WorldDef {
        room: Some(room(2.0, 2.0, 3.0, None)),
        atmosphere: up_physics::Atmosphere {
            temperature_k: 278.15,
            ..Default::default()
        },
        temperature_schedule: TemperatureSchedule {
            points: vec![(0.0, 278.15), (HOUR, 303.15)],
        },
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let id = add(&mut world, shape, Vec3::new(0.0, 0.3, 0.0), Quat::IDENTITY);
    let mut tight = envelope(0.0);
    tight.air_ratio = 0.0;
    world.fill(id, &tight, 0.0).unwrap();
    let v0 = world.gas(id).unwrap().volume(&world.air());
    world.advance(1.5 * HOUR, 100_000);
    assert_eq!(world.air().temperature_k, 303.15);
    let v1 = world.gas(id).unwrap().volume(&world.air());
    let expected = 303.15 / 278.15;
    assert!(
        ((v1 / v0) / expected - 1.0).abs() < 0.005,
        "{} against {expected}",
        v1 / v0
    );
    // The body follows its gas to within a sleeper's growth threshold.
    let s = f64::from(world.body_scale(id).unwrap());
    let gas_scale = (v1 / v0).cbrt();
    assert!(
        s <= gas_scale * (1.0 + 1e-6) && s >= gas_scale * (1.0 - WAKE_GROWTH) - 1e-6,
        "{s} against {gas_scale}"
    );
}

#[test]
fn a_shrinking_column_keeps_its_order_and_its_overlap_bound() {
    // Four balloons stacked in a shaft just wider than one, losing their gas
    // a hundred times faster than real: as they shrink the gaps open and
    // close again by buoyancy, never by a jump through a neighbour.
    let def = WorldDef {
        room: Some(room(0.36, 0.36, 2.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let fast = envelope(100.0);
    let ids: Vec<BodyId> = (0..4)
        .map(|k| {
            let id = add(
                &mut world,
                shape,
                Vec3::new(0.0, 0.3 + 0.45 * k as f32, 0.0),
                Quat::IDENTITY,
            );
            world.fill(id, &fast, 0.0).unwrap();
            id
        })
        .collect();
    let limit = 0.01 * HEAD_RADIUS;
    let heights = |w: &World| -> Vec<f32> {
        ids.iter()
            .map(|&id| w.center_of_mass(id).unwrap().y)
            .collect()
    };
    let mut worst = 0.0f32;
    // 6 simulated minutes: ≈ 10 hours of real leaking, the balloons at a
    // third of their lift.
    for step in 0..(6 * 3600) {
        world.step();
        let p = world.stats().max_penetration;
        worst = worst.max(p);
        assert!(p <= limit, "step {step}: overlap {p} m");
        let h = heights(&world);
        assert!(
            h.windows(2).all(|w| w[0] < w[1]),
            "step {step}: order lost {h:?}"
        );
    }
    let scale = world.body_scale(ids[0]).unwrap();
    assert!(scale < 0.9, "they shrank only to {scale}");
    println!("worst overlap {worst} m, scale {scale}");
}

#[test]
fn a_balloon_losing_lift_sinks_on_its_ribbon_as_the_lifted_ribbon_weighs_its_lift() {
    // 10 g/m, 2 m: the balloon's 11 g of lift holds 1.1 m of the ribbon
    // up and the rest lies on the floor; as the gas goes (50 times faster
    // than real), the knot comes down with F/(λ·g).
    let def = WorldDef {
        room: Some(room(6.0, 6.0, 3.0, None)),
        ..WorldDef::default()
    };
    let (mut world, shape) = world_with(def);
    let id = add(&mut world, shape, Vec3::new(0.0, 1.0, 0.0), Quat::IDENTITY);
    world.fill(id, &envelope(50.0), 0.0).unwrap();
    let (lambda, length, segments) = (0.010, 2.0, 32);
    let ribbon = world
        .add_ribbon(&RibbonDef {
            mass_per_length: lambda,
            ..RibbonDef::new(id, KNOT, length, segments)
        })
        .unwrap();
    let segment = length / segments as f32;
    let mut checked = 0;
    for minute in 1..=20 {
        world.advance(60.0, 100_000);
        let lift = world.free_lift(id).unwrap() * G;
        let expected = lift / (lambda * G);
        let knot = world.ribbon_points(ribbon).unwrap()[0].y;
        println!("minute {minute}: knot {knot} m, F/(λg) {expected} m");
        if expected > 0.3 && expected < length - 0.3 {
            // The chain lifts whole points: its knot rests up to a segment
            // above the balance, and the floor's friction holds a lying
            // point until the pull passes it (a second segment).
            let above = knot - expected;
            assert!(
                (-segment..2.0 * segment).contains(&above),
                "minute {minute}: knot at {knot} m, F/(λg) = {expected} m"
            );
            checked += 1;
        }
    }
    assert!(checked >= 5, "only {checked} minutes hovered");
}

/// Simulated seconds at which each balloon's centre first came 0.3 m below
/// the highest it had been (it left the ceiling): stepping every frame, or
/// by the time-lapse a second at a time.
fn leave_times(world: &mut World, ids: &[BodyId], until: f64, lapse: bool) -> Vec<f64> {
    let mut top = vec![f32::MIN; ids.len()];
    let mut left = vec![f64::NAN; ids.len()];
    while world.time() < until && left.iter().any(|t| t.is_nan()) {
        if lapse {
            world.advance(1.0, u64::MAX);
        } else {
            world.step();
        }
        for (k, &id) in ids.iter().enumerate() {
            let y = world.center_of_mass(id).unwrap().y;
            top[k] = top[k].max(y);
            if left[k].is_nan() && y < top[k] - 0.3 && top[k] > 1.5 {
                left[k] = world.time();
            }
        }
    }
    left
}

#[test]
fn the_time_lapse_agrees_with_plain_stepping() {
    // Six balloons on ribbons, losing their gas 60 times faster than real,
    // leave a 2.5 m ceiling after a few minutes: stepped every frame, and by
    // the time-lapse that jumps while they sleep, they leave within 10 s of
    // each other (10 minutes of leaking at the real rate).
    let build = || {
        let (mut world, ids) = room_of_balloons(3.0, 2.5, 6, &envelope(60.0));
        for &id in &ids {
            world.add_ribbon(&RibbonDef::new(id, KNOT, 1.5, 8)).unwrap();
        }
        (world, ids)
    };
    let until = 30.0 * 60.0;
    let (mut plain, ids) = build();
    let stepped = leave_times(&mut plain, &ids, until, false);
    let (mut lapse, _) = build();
    let lapsed = leave_times(&mut lapse, &ids, until, true);
    for (k, (a, b)) in stepped.iter().zip(&lapsed).enumerate() {
        assert!(
            a.is_finite() && b.is_finite(),
            "balloon {k} never left: {a} / {b}"
        );
        assert!(
            (a - b).abs() <= 10.0,
            "balloon {k}: {a} s stepped against {b} s lapsed"
        );
    }
    println!(
        "left at {stepped:?} s stepped, {lapsed:?} s lapsed; {} steps in all lapsed",
        lapse.step_count()
    );
    assert!(
        lapse.step_count() < plain.step_count() / 2,
        "the time-lapse stepped {} of {}",
        lapse.step_count(),
        plain.step_count()
    );
}

#[test]
fn bad_fills_are_refused_with_the_key() {
    let (mut world, ids) = room_of_balloons(2.0, 3.0, 1, &envelope(1.0));
    let mut bad = envelope(1.0);
    bad.helium_fraction = 1.5;
    match world.fill(ids[0], &bad, 0.0) {
        Err(PhysicsError::BadParameter { key, .. }) => assert_eq!(key, "envelope.helium_fraction"),
        other => panic!("{other:?}"),
    }
    match world.fill(ids[0], &envelope(1.0), -1.0) {
        Err(PhysicsError::BadParameter { key, .. }) => assert_eq!(key, "age_s"),
        other => panic!("{other:?}"),
    }
    let schedule = TemperatureSchedule {
        points: vec![(10.0, 290.0), (5.0, 295.0)],
    };
    let def = WorldDef {
        temperature_schedule: schedule,
        ..WorldDef::default()
    };
    assert!(matches!(World::new(def), Err(PhysicsError::BadSchedule(_))));
}

#[test]
fn a_world_with_gas_restores_from_its_snapshot_and_steps_on_alike() {
    let (mut world, ids) = room_of_balloons(3.0, 2.5, 4, &envelope(60.0));
    world
        .add_ribbon(&RibbonDef::new(ids[0], KNOT, 1.0, 8))
        .unwrap();
    world.advance(90.0, u64::MAX);
    let bytes = world.snapshot();
    let mut restored = World::restore(&bytes).expect("snapshot restores");
    assert_eq!(restored.state_hash(), world.state_hash());
    for _ in 0..3 {
        let a = world.advance(120.0, u64::MAX);
        let b = restored.advance(120.0, u64::MAX);
        assert_eq!(a, b);
        assert_eq!(restored.state_hash(), world.state_hash());
    }
    // The gas is in the hash: a balloon half filled with air hashes apart.
    let (mut other, other_ids) = room_of_balloons(3.0, 2.5, 4, &envelope(60.0));
    let base = other.state_hash();
    let mut half = envelope(60.0);
    half.helium_fraction = 0.5;
    other.fill(other_ids[0], &half, 0.0).unwrap();
    assert_ne!(other.state_hash(), base);
}

/// The knot's height of `ribbon` at the start and after each of `minutes`
/// simulated minutes: stepped every frame, or by the time-lapse.
fn knot_heights(world: &mut World, ribbon: RibbonId, minutes: usize, lapse: bool) -> Vec<f32> {
    let knot = |w: &World| w.ribbon_points(ribbon).unwrap()[0].y;
    let mut heights = vec![knot(world)];
    for _ in 0..minutes {
        if lapse {
            world.advance(60.0, u64::MAX);
        } else {
            (0..3600).for_each(|_| world.step());
        }
        heights.push(knot(world));
    }
    heights
}

/// The first minute at which the knot was 0.3 m below the highest it had
/// been: the balloon left the ceiling.
fn minute_left(heights: &[f32]) -> Option<usize> {
    let mut top = f32::MIN;
    heights.iter().position(|&y| {
        top = top.max(y);
        y < top - 0.3
    })
}

/// The largest change of the knot's height between consecutive minutes
/// from minute `from` on.
fn largest_step(heights: &[f32], from: usize) -> f32 {
    heights[from..]
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(0.0, f32::max)
}

#[test]
fn a_hovering_balloon_comes_down_in_the_time_lapse_as_when_stepped() {
    // One balloon on a 1.5 m, 0.25 g/m ribbon of 16 segments, filled 14.8 h
    // before with 0.44 g of lift left, losing its gas at the real rate: it
    // rises, holds its ribbon up under a 2.5 m ceiling for a few minutes,
    // leaves it as its lift falls below the ribbon's weight, and comes down
    // as the ribbon it lifts weighs its lift (≈ 2 cm a minute), a segment at
    // a time (the floor's friction holds a lying point until the pull passes
    // it). Stepped every frame without sleep (every change of its gas felt at
    // once), and by the time-lapse, its knot written every minute: the
    // time-lapse leaves the ceiling within 10 minutes of the stepped run, and
    // comes down by at most 2 cm more between two minutes than the stepped
    // run's largest (a sleeper wakes once its lift moved by the wake
    // threshold; woken, it creeps until its ribbon has followed it whole).
    let minutes = 60;
    let build = |sleep: bool| {
        let def = WorldDef {
            room: Some(room(3.0, 3.0, 2.5, None)),
            enable_sleep: sleep,
            ..WorldDef::default()
        };
        let (mut world, shape) = world_with(def);
        let id = add(&mut world, shape, Vec3::new(0.0, 0.3, 0.0), Quat::IDENTITY);
        world.fill(id, &envelope(1.0), 14.8 * HOUR).unwrap();
        let ribbon = world
            .add_ribbon(&RibbonDef::new(id, KNOT, 1.5, 16))
            .unwrap();
        (world, ribbon)
    };
    let (mut plain, ribbon) = build(false);
    let stepped = knot_heights(&mut plain, ribbon, minutes, false);
    let (mut lapse, ribbon) = build(true);
    let lapsed = knot_heights(&mut lapse, ribbon, minutes, true);
    println!("stepped {stepped:.3?}\nlapsed {lapsed:.3?}");
    let (Some(left_stepped), Some(left_lapsed)) = (minute_left(&stepped), minute_left(&lapsed))
    else {
        panic!("never left the ceiling: stepped {stepped:?}, lapsed {lapsed:?}");
    };
    assert!(
        left_lapsed.abs_diff(left_stepped) <= 10,
        "left the ceiling at minute {left_stepped} stepped, {left_lapsed} lapsed"
    );
    // From the minute after both have left (the fall from the ceiling
    // itself is one step of a metre or so).
    let from = left_stepped.max(left_lapsed);
    assert!(minutes - from >= 30, "hovered only from minute {from}");
    let (step_stepped, step_lapsed) = (largest_step(&stepped, from), largest_step(&lapsed, from));
    println!(
        "left at minute {left_stepped} stepped, {left_lapsed} lapsed; largest step a minute \
         {step_stepped} m stepped, {step_lapsed} m lapsed; {} steps lapsed",
        lapse.step_count()
    );
    assert!(
        step_lapsed <= step_stepped + 0.02,
        "{step_lapsed} m in a minute lapsed against {step_stepped} m stepped"
    );
    // The time-lapse steps a small share of the hour.
    assert!(
        lapse.step_count() < plain.step_count() / 5,
        "{} steps of {}",
        lapse.step_count(),
        plain.step_count()
    );
}
