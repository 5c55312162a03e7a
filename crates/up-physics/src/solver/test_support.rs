//! What the solver's bit-for-bit tests share: the sphere contacts they
//! prepare, one step's passes with the world's defaults, and every bit they
//! leave behind.

use glam::Vec3;

use super::contact_constraint::{self, PreparedContact};
use super::{SolveParams, Solver, Stabilization, SubstepParts};

/// The balloons' radius in these tests, m.
pub(super) const RADIUS: f32 = 0.1;

/// A prepared contact between spheres of `RADIUS` centred at `ca` and `cb`
/// along `normal`, or, when `b` is the room, between the sphere and the
/// room's point `cb`; warm-started with `normal_impulse`.
pub(super) fn sphere_contact(
    (a, ca): (u32, Vec3),
    (b, cb): (u32, Vec3),
    room: u32,
    normal: Vec3,
    normal_impulse: f32,
) -> PreparedContact {
    let on_room = b == room;
    PreparedContact {
        a,
        b,
        normal,
        tangent: contact_constraint::tangents(normal),
        radius_a: RADIUS,
        radius_b: if on_room { 0.0 } else { RADIUS },
        center_offset: if on_room { Vec3::ZERO } else { cb - ca },
        r_b: if on_room { cb } else { Vec3::ZERO },
        normal_impulse,
        ..PreparedContact::default()
    }
}

/// A step's passes over prepared constraints, as the world runs them by
/// default: the substeps' solve, restitution, then the position passes.
pub(super) fn solve_bounce_stabilize(solver: &mut Solver) {
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
    solver.solve(&params, None, None, SubstepParts::default());
    solver.restitution(0.4, 0.01);
    solver.stabilize(&Stabilization {
        slop: 0.0005,
        target: 0.001,
        min_passes: 2,
        max_passes: 16,
    });
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
