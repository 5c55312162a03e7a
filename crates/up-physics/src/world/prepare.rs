//! Stage 3, preparing the solve: each awake body's solver state and forces,
//! the contact constraints (coloured, in groups of four, warm-started), the
//! joints, and the grab spring.

use glam::{Quat, Vec3};

use super::{World, PLACE_CHUNK};
use crate::contact::{ResumeFrom, StoredImpulse, STATIC_BODY};
use crate::forces::body_forces::{BodyLoad, ForceInput};
use crate::forces::BodyForces;
use crate::grab::{GRAB_DAMPING_RATIO, GRAB_HERTZ, GRAB_MAX_WEIGHTS};
use crate::joint::End;
use crate::solver::body_state::{world_inverse_inertia, BodyState};
use crate::solver::contact_constraint;
#[cfg(feature = "parallel")]
use crate::solver::contact_constraint::PreparedContact;
use crate::solver::integrate::GrabSpring;
use crate::solver::joint_constraint::PreparedJoint;
#[cfg(feature = "parallel")]
use crate::solver::zones::zone_bodies;
use crate::solver::Solver;
use crate::threading::tasks::for_each_run;
#[cfg(feature = "parallel")]
use crate::threading::tasks::{fill_chunks, threads_here, worth_splitting};

/// Contacts one task prepares.
#[cfg(feature = "parallel")]
const PREPARE_CHUNK: usize = 1024;

/// The solve's buffers.
#[derive(Clone, Debug, Default)]
pub(crate) struct SolverStage {
    pub solver: Solver,
    /// The contacts prepared in tasks, before they are written into their groups.
    #[cfg(feature = "parallel")]
    pub prepared: Vec<PreparedContact>,
}

impl SolverStage {
    /// Gives back the capacity this step's constraints left unused (`spare`).
    pub fn release_spare(&mut self) {
        #[cfg(feature = "parallel")]
        crate::threading::spare::release_spare(
            &mut self.prepared,
            crate::threading::spare::BUFFER_FLOOR,
        );
        self.solver.release_spare();
    }
}

impl World {
    /// Each body's solver state and forces for this step's solve, and the
    /// room's static state after them; then the contacts
    /// (`prepare_contacts`), the joints (`prepare_joints`) and the grab
    /// spring (`grab_spring`), stages of their own.
    pub(super) fn prepare_bodies(&mut self) {
        let n = self.bodies.len();
        let solver = &mut self.stages.solve.solver;
        solver.awake.clear();
        solver
            .awake
            .extend((0..n as u32).filter(|&i| self.bodies.awake[i as usize]));
        // Every body's entries are written below: only the lengths matter here.
        solver.states.resize(n, BodyState::STATIC);
        solver.forces.resize(n, BodyForces::default());
        let (bodies, shapes) = (&self.bodies, &self.shapes);
        let input = ForceInput {
            air_density: self.air.air_density(),
            gravity: self.def.gravity,
            drag_coefficient: self.def.drag_coefficient,
            fields: &self.fields,
            time: self.time,
        };
        // The air is sampled only at the awake bodies, and only when it moves.
        let air = (!self.air_flow.is_still()).then_some(&self.stages.air_now);
        let parts = (&mut solver.states[..n], &mut solver.forces[..n]);
        for_each_run(n, PLACE_CHUNK, parts, |first, (states, forces)| {
            for (k, (state, forces)) in states.iter_mut().zip(forces).enumerate() {
                let i = first + k;
                let q = bodies.rotation[i];
                if !bodies.awake[i] {
                    *state = BodyState {
                        q,
                        ..BodyState::STATIC
                    };
                    *forces = BodyForces::default();
                    continue;
                }
                let shape = &shapes[bodies.shape[i] as usize];
                *state = BodyState {
                    v: bodies.linear_velocity[i],
                    w: bodies.angular_velocity[i],
                    dp: Vec3::ZERO,
                    dq: Quat::IDENTITY,
                    q,
                    inv_mass: bodies.inv_mass[i],
                    inv_inertia: world_inverse_inertia(
                        q,
                        shape.inv_inertia_local * bodies.inertia_factor[i],
                    ),
                    runaway: false,
                };
                let load = BodyLoad {
                    center: bodies.center[i],
                    velocity: bodies.linear_velocity[i],
                    user_data: bodies.user_data[i],
                    force: bodies.force[i],
                    torque: bodies.torque[i],
                    air: air.map_or(Vec3::ZERO, |a| a.velocity_at(bodies.center[i])),
                };
                *forces = BodyForces::assemble(&input, shape, bodies.size[i], &load);
            }
        });
        // Ordering the constraints by zone pays only where threads share the solve.
        solver.zones.clear();
        #[cfg(feature = "parallel")]
        if threads_here() > 1 {
            zone_bodies(&bodies.center, &mut solver.zones);
        }
        // The room: one static state after the bodies.
        solver.room = n as u32;
        solver.states.push(BodyState::STATIC);
    }

    /// The contact constraints, each warm-started from its impulse last
    /// step. With several threads the contacts are prepared in tasks (in the
    /// narrowphase's order, one lookup a pair), then written into their
    /// groups' lanes in tasks; on one, each goes straight to its slot.
    pub(super) fn prepare_contacts(&mut self) {
        let found = &self.stages.narrow.found;
        let room_state = self.stages.solve.solver.room;
        let state_of = |body: u32| {
            if body == STATIC_BODY {
                room_state
            } else {
                body
            }
        };
        // A pair with a sleeper just woken resumes from its impulses when it fell asleep.
        let resume = ResumeFrom {
            fresh: &self.warm,
            kept: &self.sleeping.impulses,
        };
        let place = &self.stages.place;
        let (nodes, node_start) = (&place.node_centers, &place.node_start);
        let center = &self.bodies.center;
        let prepare = |i: usize, previous: &[StoredImpulse]| {
            let c = &found.contacts[i];
            let (a, b) = (c.body_a, state_of(c.body_b));
            let sphere_a = nodes[node_start[a as usize] as usize + c.feature.leaf_a as usize];
            let (center_b, sphere_b) = if c.body_b == STATIC_BODY {
                (c.point_b, c.point_b)
            } else {
                (
                    center[b as usize],
                    nodes[node_start[b as usize] as usize + c.feature.part_b as usize],
                )
            };
            contact_constraint::prepare(
                c,
                (a, b),
                (center[a as usize], center_b),
                (sphere_a, sphere_b),
                previous,
            )
        };
        let pairs = found
            .contacts
            .iter()
            .map(|c| (c.body_a, state_of(c.body_b)));
        let stage = &mut self.stages.solve;
        let (count, solver) = (found.contacts.len(), &mut stage.solver);
        #[cfg(feature = "parallel")]
        if worth_splitting(count, PREPARE_CHUNK) {
            let prepared = &mut stage.prepared;
            prepared.resize(count, PreparedContact::default());
            solver.set_constraints(pairs, prepared, |prepared| {
                fill_chunks(prepared, PREPARE_CHUNK, |first, out| {
                    resume.each(&found.runs, first..first + out.len(), |i, previous| {
                        out[i - first] = prepare(i, previous);
                    });
                })
            });
            return;
        }
        // Unused this step: its length must say so (`spare`).
        #[cfg(feature = "parallel")]
        stage.prepared.clear();
        // The runs cover the contacts in order: coloured in the order prepared below.
        solver.begin_constraints(pairs);
        resume.each(&found.runs, 0..count, |i, previous| {
            solver.set_constraint(i, &prepare(i, previous));
        });
    }

    /// The joints with an awake body, each end at its body's pose at the
    /// step's start (a sleeping body's state is static, so its end holds
    /// still). A joint between sleepers is left out and keeps its tension.
    pub(super) fn prepare_joints(&mut self) {
        let (bodies, handles) = (&self.bodies, &self.handles);
        let solver = &mut self.stages.solve.solver;
        let room = solver.room;
        let end = |e: &End| match *e {
            End::Fixed(point) => Some((room, point, Vec3::ZERO, false)),
            End::Body { body, arm } => {
                let i = handles.dense(body)?;
                let q = bodies.rotation[i];
                Some((i as u32, bodies.center[i], q * arm, bodies.awake[i]))
            }
        };
        let joints = self.joints.iter().filter_map(|(id, joint)| {
            let (sa, oa, ra, awake_a) = end(&joint.ends[0])?;
            let (sb, ob, rb, awake_b) = end(&joint.ends[1])?;
            if !(awake_a || awake_b) {
                return None;
            }
            Some(PreparedJoint {
                slot: id.index,
                states: [sa, sb],
                origin: [oa, ob],
                arm: [ra, rb],
                length: joint.length,
                limit: joint.limit,
                compliance: joint.compliance,
                tension: joint.tension,
            })
        });
        solver.set_joints(joints);
    }

    /// The soft spring that pulls a held body toward the pointer.
    pub(super) fn grab_spring(&self) -> Option<GrabSpring> {
        let grab = self.grab?;
        let i = self.handles.dense(grab.body)?;
        if !self.bodies.awake[i] {
            return None;
        }
        let mass = 1.0 / self.bodies.inv_mass[i];
        let omega = 2.0 * std::f32::consts::PI * GRAB_HERTZ;
        let g = self.def.gravity;
        Some(GrabSpring {
            state: i as u32,
            anchor: self.bodies.rotation[i] * grab.anchor,
            center0: self.bodies.center[i],
            target: grab.target,
            stiffness: mass * omega * omega,
            damping: 2.0 * mass * GRAB_DAMPING_RATIO * omega,
            max_force: GRAB_MAX_WEIGHTS * self.bodies.size[i].mass * g.length(),
        })
    }
}
