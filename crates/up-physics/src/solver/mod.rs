//! The soft-step solver (Box2D v3, Box3D, Rapier ≥ 0.29), in named stages:
//!
//! 1. prepare: contact constraints from the narrowphase, warm-start impulses
//!    from the last step, forces for each body; then the constraints are
//!    sorted by colour (`coloring`), so that each pass can run a colour's
//!    constraints on several threads (`parallel`);
//! 2. per substep: integrate velocities (forces), warm start, solve (soft
//!    push-out of overlap), integrate positions, relax (no push-out, so the
//!    push-out's velocity does not linger as jitter);
//! 3. restitution (bounces), and store impulses for the next step;
//! 4. stabilise: overlap beyond a slop is removed from the positions directly.

pub(crate) mod body_state;
pub(crate) mod coloring;
pub(crate) mod contact_constraint;
pub(crate) mod integrate;
pub(crate) mod parallel;
pub(crate) mod softness;

use body_state::BodyState;
use coloring::Coloring;
use contact_constraint::{Bias, ContactConstraint};
use integrate::{BodyForces, GrabSpring};
use parallel::{for_each_body, for_each_colored, for_each_constraint};

/// Buffers reused from step to step.
#[derive(Clone, Debug, Default)]
pub(crate) struct Solver {
    /// One per body (dense order) plus the static room at the end.
    pub states: Vec<BodyState>,
    pub forces: Vec<BodyForces>,
    /// Sorted by colour once prepared (`coloring.position` maps back).
    pub constraints: Vec<ContactConstraint>,
    pub coloring: Coloring,
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
    /// Orders the prepared constraints by colour; call once they are all pushed.
    pub fn color(&mut self) {
        self.coloring.sort(&mut self.constraints, &self.states);
    }

    /// The constraint built from the narrowphase's `i`-th contact.
    pub fn constraint(&self, i: usize) -> &ContactConstraint {
        &self.constraints[self.coloring.position[i] as usize]
    }

    /// Runs the substeps over prepared `states`, `forces` and coloured `constraints`.
    pub fn solve(&mut self, p: &SolveParams, grab: Option<&GrabSpring>) {
        let h = p.dt / p.substeps as f32;
        let inv_h = 1.0 / h;
        // Stiffer than a quarter of the substep rate would ring.
        let hertz = p.contact_hertz.min(0.25 * inv_h);
        let soft = softness::Softness::new(hertz, p.contact_damping_ratio, h);
        let bias = |use_bias| Bias {
            soft,
            inv_h,
            max_push_out: p.max_push_out,
            use_bias,
        };
        let (push, relax) = (bias(true), bias(false));
        let ranges = &self.coloring.ranges;
        for _ in 0..p.substeps {
            integrate::integrate_velocities(
                &mut self.states,
                &self.forces,
                &self.awake,
                p.angular_damping,
                grab,
                h,
            );
            for_each_colored(
                ranges,
                &mut self.constraints,
                &mut self.states,
                contact_constraint::warm_start,
            );
            for _ in 0..p.iterations {
                for_each_colored(
                    ranges,
                    &mut self.constraints,
                    &mut self.states,
                    |c, a, b| contact_constraint::solve(c, a, b, &push),
                );
            }
            for_each_body(&self.awake, &mut self.states, |_, s| {
                s.integrate_position(h)
            });
            for_each_constraint(&mut self.constraints, &self.states, |c, a, b| {
                contact_constraint::refresh(c, a, b)
            });
            for_each_colored(
                ranges,
                &mut self.constraints,
                &mut self.states,
                |c, a, b| contact_constraint::solve(c, a, b, &relax),
            );
        }
    }

    pub fn restitution(&mut self, threshold: f32) {
        let ranges = &self.coloring.ranges;
        for_each_colored(
            ranges,
            &mut self.constraints,
            &mut self.states,
            |c, a, b| contact_constraint::apply_restitution(c, a, b, threshold),
        );
    }

    /// Removes overlap deeper than `slop` from the positions, `iterations` passes.
    pub fn stabilize(&mut self, slop: f32, iterations: u32) {
        let ranges = &self.coloring.ranges;
        for _ in 0..iterations {
            for_each_colored(
                ranges,
                &mut self.constraints,
                &mut self.states,
                |c, a, b| contact_constraint::stabilize(c, a, b, slop),
            );
        }
    }
}
