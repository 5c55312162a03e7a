//! Groups whose constraints all have a fixed side (the room, a sleeper) run
//! the passes without that side (`coloring::Moving`): they must leave every
//! body and every constraint as the passes over both sides would, bit for bit.

use glam::{Mat3, Quat, Vec3};

use super::body_state::BodyState;
use super::coloring::Moving;
use super::contact_constraint::{self, PreparedContact};
use super::integrate::BodyForces;
use super::{SolveParams, Solver, Stabilization};
use crate::hash::uniform;

const RADIUS: f32 = 0.1;

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
        let on_room = b == room;
        let c = PreparedContact {
            a,
            b,
            normal,
            tangent: contact_constraint::tangents(normal),
            radius_a: RADIUS,
            radius_b: if on_room { 0.0 } else { RADIUS },
            center_offset: if on_room { Vec3::ZERO } else { cb - ca },
            r_b: if on_room { cb } else { Vec3::ZERO },
            normal_impulse: 0.01 * random(),
            ..PreparedContact::default()
        };
        solver.set_constraint(k, &c);
    }
    solver
}

/// Every bit of every state and of what every constraint hands on.
pub(super) fn bits(solver: &Solver) -> (Vec<Vec<u32>>, Vec<Vec<u32>>) {
    let states = solver
        .states
        .iter()
        .map(|s| {
            let (v, w, dp) = (s.v.to_array(), s.w.to_array(), s.dp.to_array());
            let (dq, q) = (s.dq.to_array(), s.q.to_array());
            [&v[..], &w, &dp, &dq, &q]
                .concat()
                .iter()
                .map(|x| x.to_bits())
                .collect()
        })
        .collect();
    let stored = (0..solver.coloring.slot.len())
        .map(|i| {
            let s = solver.stored(i);
            [s.normal, s.tangent.x, s.tangent.y, s.tangent.z]
                .map(f32::to_bits)
                .to_vec()
        })
        .collect();
    (states, stored)
}

#[test]
fn one_sided_groups_solve_as_groups_of_both_sides() {
    let params = SolveParams {
        dt: 1.0 / 60.0,
        substeps: 4,
        iterations: 2,
        contact_hertz: 60.0,
        contact_damping_ratio: 10.0,
        max_push_out: 3.0,
        friction: 0.5,
        angular_damping: 2.0,
    };
    let stabilization = Stabilization {
        slop: 0.0005,
        target: 0.001,
        min_passes: 2,
        max_passes: 16,
    };
    for seed in 1..=3 {
        let mut one_sided = drifting_row(200, seed);
        let kinds =
            |s: &Solver, m: Moving| s.coloring.ranges.iter().filter(|r| r.moving == m).count();
        assert!(kinds(&one_sided, Moving::A) > 0 && kinds(&one_sided, Moving::B) > 0);
        let mut both = one_sided.clone();
        both.coloring.treat_every_side_as_moving();
        let before = bits(&one_sided);
        for solver in [&mut one_sided, &mut both] {
            solver.solve(&params, None);
            solver.restitution(0.4, 0.01);
            solver.stabilize(&stabilization);
        }
        assert_ne!(bits(&one_sided), before, "seed {seed}: nothing moved");
        assert_eq!(bits(&one_sided), bits(&both), "seed {seed}");
    }
}
