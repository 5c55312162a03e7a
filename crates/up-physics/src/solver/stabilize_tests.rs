//! The position passes skip groups that would move nothing (`position_skips`):
//! they must leave every body where passes over every group would, bit for bit.

use glam::{Mat3, Quat, Vec3};

use super::body_lanes::Displacements;
use super::body_state::BodyState;
use super::contact_constraint::{self, PositionPush};
use super::parallel::for_each_group;
use super::test_support::{sphere_contact, RADIUS};
use super::{Poses, Solver, Stabilization};
use crate::hash::uniform;

/// A row of `n` balloons along x, each from 1.5 mm into the next to 1 mm
/// apart (around the slop, so that pushes travel along the row to contacts
/// that were shallow), now and then 3 mm into it or 4 mm apart, and the
/// static room (the last state) under every fourth.
fn pressed_row(n: usize, seed: u64) -> Solver {
    let mut random = uniform(seed);
    let mut x = 0.0;
    let mut centers = Vec::new();
    for i in 0..n {
        centers.push(Vec3::new(x, 0.0, 0.0));
        let gap = match i % 7 {
            3 => 0.004,
            5 => -0.003,
            _ => 0.0025 * random() - 0.0015,
        };
        x += 2.0 * RADIUS + gap;
    }
    // Every eleventh balloon asleep (static), the room last.
    let mut states: Vec<BodyState> = (0..n)
        .map(|i| BodyState {
            inv_mass: if i % 11 == 5 { 0.0 } else { 0.5 + random() },
            inv_inertia: Mat3::IDENTITY,
            q: Quat::IDENTITY,
            ..BodyState::STATIC
        })
        .collect();
    states.push(BodyState::STATIC);
    let room = n as u32;
    let mut solver = Solver {
        states,
        room,
        ..Solver::default()
    };
    let mut contacts = Vec::new();
    for i in 0..n {
        if i % 4 == 0 {
            let floor = Vec3::new(centers[i].x, -RADIUS + 0.002 * random(), 0.0);
            contacts.push((i as u32, room, centers[i], floor, Vec3::NEG_Y));
        }
        for j in [i + 1, i + 2] {
            if j < n {
                let normal = (centers[j] - centers[i]).normalize();
                contacts.push((i as u32, j as u32, centers[i], centers[j], normal));
            }
        }
    }
    solver.begin_constraints(contacts.iter().map(|&(a, b, ..)| (a, b)));
    for (k, &(a, b, ca, cb, normal)) in contacts.iter().enumerate() {
        solver.set_constraint(k, &sphere_contact((a, ca), (b, cb), room, normal, 0.0));
    }
    solver
}

/// The passes as they ran before any were skipped: every group, in order.
fn every_group_every_pass(solver: &mut Solver, s: &Stabilization) -> u32 {
    for_each_group(
        &mut solver.groups,
        &mut solver.anchors,
        &solver.states,
        |_, anchors, a, b| {
            contact_constraint::rotate_to_end(anchors, &Poses::gather(a), &Poses::gather(b))
        },
    );
    let mut passes = 0;
    while passes < s.max_passes.max(s.min_passes) {
        let mut beyond_target = false;
        for (g, anchors) in solver.groups.iter().zip(&solver.anchors) {
            let side = |bodies: [u32; 4]| bodies.map(|i| &solver.states[i as usize]);
            let mut a = Displacements::gather(side(g.a));
            let mut b = Displacements::gather(side(g.b));
            let push: PositionPush =
                contact_constraint::stabilize(g, anchors, &mut a, &mut b, s.slop, s.target);
            beyond_target |= push.beyond_target;
            for (d, bodies) in [(&a, g.a), (&b, g.b)] {
                let scatter = d.scatter();
                for (lane, &i) in bodies.iter().enumerate() {
                    let state = &mut solver.states[i as usize];
                    if state.inv_mass > 0.0 {
                        scatter(lane, state);
                    }
                }
            }
        }
        passes += 1;
        if passes >= s.min_passes && !beyond_target {
            break;
        }
    }
    passes
}

#[test]
fn skipping_quiet_groups_moves_every_body_as_running_them_all() {
    for (seed, target) in [(1, 0.001), (2, 0.0005), (3, 0.002)] {
        let s = Stabilization {
            slop: 0.0005,
            target,
            min_passes: 4,
            max_passes: 32,
        };
        let mut skipping = pressed_row(300, seed);
        let mut reference = skipping.clone();
        let passes = skipping.stabilize(&s);
        assert_eq!(
            passes,
            every_group_every_pass(&mut reference, &s),
            "seed {seed}"
        );
        assert!(
            passes > s.min_passes,
            "seed {seed}: the row was not pressed enough"
        );
        let moved = |solver: &Solver| {
            solver
                .states
                .iter()
                .map(|s| s.dp.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(moved(&skipping), moved(&reference), "seed {seed}");
        assert!(
            skipping.states.iter().any(|s| s.dp != Vec3::ZERO),
            "seed {seed}: nothing moved"
        );
    }
}
