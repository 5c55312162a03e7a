//! The soft-step solver (Box2D v3, Box3D, Rapier ≥ 0.29), in named stages:
//!
//! 1. prepare: contact constraints from the narrowphase, warm-start impulses
//!    from the last step, forces for each body;
//! 2. per substep: integrate velocities (forces), warm start, solve (soft
//!    push-out of overlap), integrate positions, relax (no push-out, so the
//!    push-out's velocity does not linger as jitter);
//! 3. restitution (bounces), and store impulses for the next step;
//! 4. stabilise: overlap beyond a slop is removed from the positions directly.

pub(crate) mod body_state;
pub(crate) mod contact_constraint;
pub(crate) mod integrate;
pub(crate) mod softness;

use body_state::BodyState;
use contact_constraint::ContactConstraint;
use integrate::{BodyForces, GrabSpring};

/// Buffers reused from step to step.
#[derive(Clone, Debug, Default)]
pub(crate) struct Solver {
    /// One per body (dense order) plus the static room at the end.
    pub states: Vec<BodyState>,
    pub forces: Vec<BodyForces>,
    pub constraints: Vec<ContactConstraint>,
    /// Dense indices of the awake bodies.
    pub awake: Vec<u32>,
}

/// The parameters of one step's solve.
pub(crate) struct SolveParams {
    pub dt: f32,
    pub substeps: u32,
    pub iterations: u32,
    pub contact_hertz: f32,
    pub contact_damping_ratio: f32,
    pub max_push_out: f32,
    pub restitution_threshold: f32,
    pub angular_damping: f32,
}

impl Solver {
    /// Runs the substeps and restitution over prepared `states`, `forces` and `constraints`.
    pub fn solve(&mut self, p: &SolveParams, grab: Option<&GrabSpring>) {
        let h = p.dt / p.substeps as f32;
        let inv_h = 1.0 / h;
        // Stiffer than a quarter of the substep rate would ring.
        let hertz = p.contact_hertz.min(0.25 * inv_h);
        let soft = softness::Softness::new(hertz, p.contact_damping_ratio, h);
        for _ in 0..p.substeps {
            integrate::integrate_velocities(
                &mut self.states,
                &self.forces,
                &self.awake,
                p.angular_damping,
                grab,
                h,
            );
            contact_constraint::warm_start(&self.constraints, &mut self.states);
            for _ in 0..p.iterations {
                contact_constraint::solve(
                    &mut self.constraints,
                    &mut self.states,
                    soft,
                    inv_h,
                    p.max_push_out,
                    true,
                );
            }
            for &i in &self.awake {
                self.states[i as usize].integrate_position(h);
            }
            contact_constraint::solve(
                &mut self.constraints,
                &mut self.states,
                soft,
                inv_h,
                p.max_push_out,
                false,
            );
        }
    }

    pub fn restitution(&mut self, threshold: f32) {
        contact_constraint::apply_restitution(&mut self.constraints, &mut self.states, threshold);
    }

    /// Removes overlap deeper than `slop` from the positions, `iterations` passes.
    pub fn stabilize(&mut self, slop: f32, iterations: u32) {
        for _ in 0..iterations {
            contact_constraint::stabilize(&self.constraints, &mut self.states, slop);
        }
    }
}
