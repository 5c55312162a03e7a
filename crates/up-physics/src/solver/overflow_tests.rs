//! Constraints past the 64 colours run in levels (`coloring`), four to a
//! group and several groups at once: each body meets them in the given order,
//! so the passes must end bit for bit as running them one at a time would.

use glam::{Mat3, Quat, Vec3};

use super::body_state::BodyState;
use super::test_support::{bits, solve_bounce_stabilize, sphere_contact, RADIUS};
use super::Solver;
use crate::forces::BodyForces;
use crate::hash::uniform;

const HUBS: usize = 20;
const SPOKES: usize = 100;

/// `HUBS` balloons each touched by `SPOKES` others (more contacts than
/// colours), the spokes in a chain touching each other, every seventh spoke
/// asleep, every fifth on the room; the overflow run in levels, or serially.
fn hubs_and_spokes(seed: u64, serial_overflow: bool) -> Solver {
    let mut random = uniform(seed);
    let mut signed = move || 2.0 * random() - 1.0;
    let mut centers = Vec::new();
    let mut states = Vec::new();
    let mut awake = Vec::new();
    let mut contacts = Vec::new();
    let room = (HUBS * (SPOKES + 1)) as u32;
    for h in 0..HUBS {
        let hub = states.len() as u32;
        let hub_center = Vec3::new(h as f32 * 3.0, 0.0, 0.0);
        centers.push(hub_center);
        states.push(moving_state(&mut signed));
        awake.push(hub);
        for s in 0..SPOKES {
            let spoke = states.len() as u32;
            let direction = Vec3::new(signed(), signed(), signed()).normalize_or(Vec3::X);
            centers.push(hub_center + direction * (2.0 * RADIUS + 0.002 * signed()));
            if s % 7 == 3 {
                states.push(BodyState {
                    q: Quat::from_rotation_y(signed()),
                    ..BodyState::STATIC
                });
            } else {
                states.push(moving_state(&mut signed));
                awake.push(spoke);
            }
            contacts.push((hub, spoke));
            if s > 0 {
                contacts.push((spoke - 1, spoke));
            }
            if s % 5 == 0 && !states[spoke as usize].is_fixed() {
                contacts.push((spoke, room));
            }
        }
    }
    states.push(BodyState::STATIC);
    let mut solver = Solver {
        forces: vec![BodyForces::default(); states.len()],
        states,
        awake,
        room,
        ..Solver::default()
    };
    solver.coloring.serial_overflow = serial_overflow;
    solver.begin_constraints(contacts.iter().copied());
    for (k, &(a, b)) in contacts.iter().enumerate() {
        let ca = centers[a as usize];
        let on_room = b == room;
        let cb = if on_room {
            ca - Vec3::Y * (RADIUS + 0.002 * signed())
        } else {
            centers[b as usize]
        };
        let normal = (cb - ca).normalize();
        let c = sphere_contact((a, ca), (b, cb), room, normal, 0.01 * (signed() + 1.0));
        solver.set_constraint(k, &c);
    }
    solver
}

fn moving_state(signed: &mut impl FnMut() -> f32) -> BodyState {
    let inertia = Mat3::from_diagonal(Vec3::new(1.0 + 0.5 * signed(), 1.0, 1.0));
    BodyState {
        v: 0.05 * Vec3::new(signed(), signed(), signed()),
        w: 0.5 * Vec3::new(signed(), signed(), signed()),
        inv_mass: 1.0 + 0.5 * signed(),
        inv_inertia: inertia,
        q: Quat::from_rotation_x(signed()),
        ..BodyState::STATIC
    }
}

#[test]
fn levels_solve_as_the_overflow_one_at_a_time() {
    // Four threads, so that the colours' blocks run in stages (`parallel`).
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap();
    for seed in 1..=3 {
        let mut levels = hubs_and_spokes(seed, false);
        let mut serial = hubs_and_spokes(seed, true);
        // Levels after the colours and nothing left serial; or the overflow all serial.
        let serial_rest = |s: &Solver| {
            let last = s.coloring.ranges.last().unwrap();
            last.end - last.start
        };
        assert_eq!(serial_rest(&levels), 0, "seed {seed}");
        assert!(
            serial_rest(&serial) as usize >= HUBS * (SPOKES - 64),
            "seed {seed}"
        );
        let before = bits(&levels);
        pool.install(|| {
            for solver in [&mut levels, &mut serial] {
                solve_bounce_stabilize(solver);
            }
        });
        assert_ne!(bits(&levels), before, "seed {seed}: nothing moved");
        assert_eq!(bits(&levels), bits(&serial), "seed {seed}");
    }
}
