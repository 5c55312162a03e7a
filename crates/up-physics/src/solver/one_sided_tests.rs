//! Groups whose constraints all have a fixed side (the room, a sleeper) run
//! the passes without that side (`coloring::Moving`): they must leave every
//! body and every constraint as the passes over both sides would, bit for bit.

use glam::{Mat3, Quat, Vec3};

use super::body_state::BodyState;
use super::coloring::Moving;
use super::test_support::{bits, solve_bounce_stabilize, sphere_contact, RADIUS};
use super::Solver;
use crate::forces::BodyForces;
use crate::hash::uniform;

/// A row of `n` spinning, drifting balloons along x, from 2 mm into the next
/// to 2 mm apart, every fifth asleep, and the room (the last state) under
/// every third. A pair is written lower index first, so a sleeper is side A
/// of the pair with the balloon after it and side B of the one before.
fn drifting_row(n: usize, seed: u64) -> Solver {
    let mut random = uniform(seed);
    let mut signed = {
        let mut random = uniform(!seed);
        move || 2.0 * random() - 1.0
    };
    let mut x = 0.0;
    let mut centers = Vec::new();
    let mut states = Vec::new();
    let mut awake = Vec::new();
    for i in 0..n {
        centers.push(Vec3::new(x, 0.0, 0.0));
        x += 2.0 * RADIUS + 0.002 * signed();
        let q = Quat::from_rotation_y(signed()) * Quat::from_rotation_x(signed());
        if i % 5 == 2 {
            states.push(BodyState {
                q,
                ..BodyState::STATIC
            });
            continue;
        }
        awake.push(i as u32);
        let inertia = Mat3::from_diagonal(Vec3::new(1.0 + signed(), 1.0, 1.0 + 0.5 * signed()));
        states.push(BodyState {
            v: 0.05 * Vec3::new(signed(), signed(), signed()),
            w: 0.5 * Vec3::new(signed(), signed(), signed()),
            inv_mass: 0.5 + random(),
            inv_inertia: inertia,
            q,
            ..BodyState::STATIC
        });
    }
    states.push(BodyState::STATIC);
    let room = n as u32;
    let mut solver = Solver {
        forces: vec![BodyForces::default(); states.len()],
        states,
        awake,
        room,
        ..Solver::default()
    };
    let mut contacts = Vec::new();
    for i in 0..n {
        if i % 3 == 0 && !solver.states[i].is_fixed() {
            let floor = Vec3::new(centers[i].x, -RADIUS + 0.002 * signed(), 0.0);
            contacts.push((i as u32, room, centers[i], floor, Vec3::NEG_Y));
        }
        if i + 1 < n {
            let normal = (centers[i + 1] - centers[i]).normalize();
            contacts.push((i as u32, i as u32 + 1, centers[i], centers[i + 1], normal));
        }
    }
    solver.begin_constraints(contacts.iter().map(|&(a, b, ..)| (a, b)));
    for (k, &(a, b, ca, cb, normal)) in contacts.iter().enumerate() {
        let c = sphere_contact((a, ca), (b, cb), room, normal, 0.01 * random());
        solver.set_constraint(k, &c);
    }
    solver
}

#[test]
fn one_sided_groups_solve_as_groups_of_both_sides() {
    for seed in 1..=3 {
        let mut one_sided = drifting_row(200, seed);
        let kinds =
            |s: &Solver, m: Moving| s.coloring.ranges.iter().filter(|r| r.moving == m).count();
        assert!(kinds(&one_sided, Moving::A) > 0 && kinds(&one_sided, Moving::B) > 0);
        let mut both = one_sided.clone();
        both.coloring.treat_every_side_as_moving();
        let before = bits(&one_sided);
        for solver in [&mut one_sided, &mut both] {
            solve_bounce_stabilize(solver);
        }
        assert_ne!(bits(&one_sided), before, "seed {seed}: nothing moved");
        assert_eq!(bits(&one_sided), bits(&both), "seed {seed}");
    }
}
