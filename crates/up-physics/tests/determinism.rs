//! The same inputs give the same state, bit for bit; snapshots restore exactly.

mod common;

use common::*;
use glam::{Quat, Vec3};
#[cfg(feature = "parallel")]
use up_physics::divergence::lockstep_with;
#[cfg(feature = "parallel")]
use up_physics::{EnvelopeDef, WorldDef};
use up_physics::{SnapshotError, World};

#[test]
fn two_runs_give_the_same_state_hash() {
    let mut a = sixty_released();
    let mut b = sixty_released();
    for _ in 0..300 {
        a.step();
        b.step();
        assert_eq!(a.state_hash(), b.state_hash());
    }
}

#[test]
fn restored_snapshot_steps_to_the_same_hash() {
    let mut world = sixty_released();
    for _ in 0..200 {
        world.step();
    }
    let bytes = world.snapshot();
    let mut restored = World::restore(&bytes).expect("restores");
    assert_eq!(restored.state_hash(), world.state_hash());
    for _ in 0..200 {
        world.step();
        restored.step();
    }
    assert_eq!(restored.state_hash(), world.state_hash());
}

#[test]
fn corrupted_or_truncated_snapshots_are_rejected() {
    let world = sixty_released();
    let bytes = world.snapshot();
    assert_eq!(
        World::restore(&bytes[..bytes.len() - 3]).unwrap_err(),
        SnapshotError::Truncated {
            expected: bytes.len(),
            found: bytes.len() - 3
        }
    );
    let mut flipped = bytes.clone();
    flipped[40] ^= 0x10;
    assert_eq!(
        World::restore(&flipped).unwrap_err(),
        SnapshotError::Checksum
    );
    assert_eq!(
        World::restore(b"hello").unwrap_err(),
        SnapshotError::BadMagic
    );
    assert!(matches!(
        World::restore(&bytes[..10]),
        Err(SnapshotError::Truncated { .. })
    ));
}

#[test]
fn bodies_added_and_removed_while_running() {
    let mut world = sixty_released();
    let shape = world.shape_of(world.body_ids()[0]).unwrap();
    for _ in 0..100 {
        world.step();
    }
    let gone = world.body_ids()[5];
    world.remove_body(gone).unwrap();
    assert!(!world.contains(gone));
    assert!(world.pose(gone).is_none());
    assert!(
        world.remove_body(gone).is_err(),
        "a stale handle is refused"
    );
    let new = add(&mut world, shape, Vec3::new(0.0, 0.3, 0.0), Quat::IDENTITY);
    assert_ne!(new, gone, "a reused slot gets a new generation");
    for _ in 0..100 {
        world.step();
    }
    assert_eq!(world.body_count(), 60);
    assert!(world.center_of_mass(new).unwrap().y > 1.0);
}

/// A pool of `threads` threads to step a world on.
#[cfg(feature = "parallel")]
fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
}

/// With the `parallel` feature the narrowphase, the preparation of the
/// constraints (in contact order, then gathered group by group), the colours
/// of the solve and the body passes run on rayon's threads (on one thread the
/// constraints go straight to their slots); a crowd large enough to split into many tasks,
/// with sleepers among its awake bodies, must end bit for bit the same on 1, 2 and 4 threads,
/// and when stepped from a thread outside any pool; stepped beside one thread
/// and compared body by body every step, so that a failure names the step and
/// the body where they part.
#[cfg(feature = "parallel")]
#[test]
fn the_state_hash_does_not_depend_on_the_thread_count() {
    let crowd = || {
        // Quick to fall asleep, so that the body passes' runs hold sleepers
        // and awake bodies both.
        let def = WorldDef {
            room: Some(room(4.0, 4.0, 2.5, Some(1.0))),
            sleep_linear_speed: 0.3,
            sleep_angular_speed: 3.0,
            time_to_sleep: 0.2,
            ..WorldDef::default()
        };
        let (mut world, shape) = world_with(def);
        for i in 0..720 {
            let (x, z) = (
                (i % 12) as f32 * 0.32 - 1.76,
                ((i / 12) % 12) as f32 * 0.32 - 1.76,
            );
            let y = 0.3 + 0.45 * (i / 144) as f32;
            let q = Quat::from_rotation_y(i as f32) * Quat::from_rotation_x(0.05 * (i % 5) as f32);
            add(&mut world, shape, Vec3::new(x, y, z), q);
        }
        world
    };
    let one = pool(1);
    // Each thread count stepped beside one thread, compared body by body
    // after every step: a difference names its step and body.
    for threads in [2, 4] {
        let many = pool(threads);
        let (mut a, mut b) = (one.install(crowd), many.install(crowd));
        let mut most_contacts = 0;
        let mut fewest_awake = u32::MAX;
        let parted = lockstep_with(
            &mut a,
            &mut b,
            150,
            |w| {
                one.install(|| w.step());
                most_contacts = most_contacts.max(w.stats().contact_count);
                fewest_awake = fewest_awake.min(w.stats().awake_count);
            },
            |w| many.install(|| w.step()),
        );
        if let Some(parted) = parted {
            panic!("{threads} threads against one: {parted}");
        }
        assert!(
            (1..=600).contains(&fewest_awake),
            "no step with both sleepers and awake bodies: {fewest_awake} awake at the fewest"
        );
        assert!(
            most_contacts > 3 * 1024, // four tasks of preparation, at the busiest
            "too few contacts to split: {most_contacts}"
        );
    }
    // Stepped from outside any pool (as the CLI does): `step` moves onto
    // the global pool's threads.
    let (mut a, mut b) = (one.install(crowd), crowd());
    let parted = lockstep_with(
        &mut a,
        &mut b,
        150,
        |w| one.install(|| w.step()),
        World::step,
    );
    if let Some(parted) = parted {
        panic!("the global pool against one thread: {parted}");
    }
}

/// The gas is taken on in tasks: a crowd of more balloons than a task takes,
/// asleep under a low ceiling, leaking an hour's helium a second, so that at
/// each second's gas step every gas moves at once and wakes its sleeper.
/// Stepped on three threads beside one, compared body by body every step.
#[cfg(feature = "parallel")]
#[test]
fn the_gas_taken_on_in_tasks_is_the_same_on_any_thread_count() {
    let crowd = || {
        let def = WorldDef {
            room: Some(room(12.0, 12.0, 0.45, None)),
            sleep_linear_speed: 0.3,
            sleep_angular_speed: 3.0,
            time_to_sleep: 0.2,
            ..WorldDef::default()
        };
        let (mut world, shape) = world_with(def);
        let mut envelope = EnvelopeDef::latex(0.0035, 0.003, 0.289, 1.0, 1.0);
        envelope.helium_permeance *= 3600.0;
        for i in 0..1200 {
            let (x, z) = ((i % 35) as f32 * 0.22 - 3.74, (i / 35) as f32 * 0.22 - 3.74);
            let q = Quat::from_rotation_y(i as f32);
            let id = add(&mut world, shape, Vec3::new(x, 0.25, z), q);
            world.fill(id, &envelope, 0.0).expect("a valid envelope");
        }
        world
    };
    let (one, three) = (pool(1), pool(3));
    let (mut a, mut b) = (one.install(crowd), three.install(crowd));
    let (mut most_asleep, mut woke) = (0, false);
    let parted = lockstep_with(
        &mut a,
        &mut b,
        190,
        |w| {
            let asleep_before = w.body_count() as u32 - w.stats().awake_count;
            one.install(|| w.step());
            let asleep = w.body_count() as u32 - w.stats().awake_count;
            most_asleep = most_asleep.max(asleep);
            woke |= asleep_before > 1024 && asleep + 1024 < asleep_before;
        },
        |w| three.install(|| w.step()),
    );
    if let Some(parted) = parted {
        panic!("3 threads against one: {parted}");
    }
    assert!(most_asleep > 1024, "too few asleep to split: {most_asleep}");
    assert!(woke, "the gas woke no crowd of sleepers in one step");
}

#[test]
fn a_body_driven_to_infinity_is_quarantined_and_the_rest_goes_on() {
    let mut world = sixty_released();
    for _ in 0..120 {
        world.step();
    }
    let victim = world.body_ids()[7];
    let user_data = world.user_data(victim).unwrap();
    // Finite, but absurd: the velocity overflows within a step or two.
    world
        .apply_force_at_point(victim, Vec3::new(3e38, 3e38, 0.0), Vec3::ZERO)
        .expect("a finite force is accepted");
    let before = world.body_count();
    let mut reports = Vec::new();
    for _ in 0..60 {
        world.step();
        reports.extend(world.take_quarantined());
    }
    assert!(
        reports
            .iter()
            .any(|r| r.id == victim && r.user_data == user_data),
        "{reports:?}"
    );
    assert!(!world.contains(victim));
    assert_eq!(world.stats().quarantined_count, reports.len() as u64);
    assert_eq!(world.body_count(), before - reports.len());
    assert_eq!(reports.len(), 1, "the fault spread: {reports:?}");
    for (_, pose) in world.poses() {
        assert!(pose.position.is_finite() && pose.rotation.is_finite());
    }
    assert!(
        world.take_quarantined().is_empty(),
        "reports are handed out once"
    );
}
