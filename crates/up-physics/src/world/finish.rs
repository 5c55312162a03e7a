//! Stage 4, finishing: the solver's results back to the bodies, the
//! contacts' impulses kept for the next step, the joints' tensions.

use glam::Vec3;

use super::{World, PLACE_CHUNK};
use crate::contact::StoredImpulse;
use crate::solver::body_state::world_inverse_inertia;
use crate::threading::tasks::for_each_run_collect;

impl World {
    /// What each contact hands to the next step's warm start.
    pub(super) fn store_impulses(&mut self) {
        // One impulse per contact, in order: the runs stay as they are.
        let found = &self.stages.narrow.found;
        self.warm.runs.clone_from(&found.runs);
        self.warm
            .impulses
            .resize(found.contacts.len(), StoredImpulse::default());
        let solver = &self.stages.solve.solver;
        self.warm
            .fill_and_index(|impulses| solver.store_all(impulses));
    }

    /// Copies the solver's results back to the bodies; clears held forces.
    pub(super) fn finish_motion(&mut self) {
        let solver = &self.stages.solve.solver;
        // The runaways are left where the step found them (only an awake
        // body's state can run away) and quarantined at the step's end.
        let faults = &mut self.stages.faults;
        faults.non_finite.clear();
        let b = &mut self.bodies;
        let (n, shapes, shape, awake) = (b.len(), &self.shapes, &b.shape, &b.awake);
        let inertia_factor = &b.inertia_factor;
        let parts = (
            &mut b.center[..],
            &mut b.rotation[..],
            &mut b.linear_velocity[..],
            &mut b.angular_velocity[..],
            &mut b.force[..],
            &mut b.torque[..],
        );
        let (lists, runaways) = (&mut faults.task_faulty, &mut faults.non_finite);
        for_each_run_collect(
            n,
            PLACE_CHUNK,
            parts,
            lists,
            runaways,
            |first, run, runaways| {
                let (center, rotation, linear_velocity, angular_velocity, force, torque) = run;
                for k in 0..center.len() {
                    let i = first + k;
                    force[k] = Vec3::ZERO;
                    torque[k] = Vec3::ZERO;
                    let s = &solver.states[i];
                    if s.runaway {
                        runaways.push(i);
                    }
                    if !awake[i] || s.runaway {
                        continue;
                    }
                    center[k] += s.dp;
                    rotation[k] = s.q;
                    linear_velocity[k] = s.v;
                    // Keep angular momentum L = I·ω across the rotation (the gyroscopic
                    // effect): the solve used the inertia at the step's start.
                    let momentum = s.inv_inertia.inverse() * s.w;
                    let inv_inertia_local =
                        shapes[shape[i] as usize].inv_inertia_local * inertia_factor[i];
                    let w = world_inverse_inertia(s.q, inv_inertia_local) * momentum;
                    angular_velocity[k] = if w.is_finite() { w } else { s.w };
                }
            },
        );
    }

    /// Each joint keeps the tension its last substep took.
    pub(super) fn store_tensions(&mut self) {
        for joint in &self.stages.solve.solver.joints {
            self.joints.set_tension(joint.slot, joint.tension);
        }
    }
}
