//! The force probe's stages of the step (`probe`): `begin_probe` before the
//! substeps, `probe_before_sweep` and `finish_probe` around the continuous
//! sweep. Each does nothing while the probe is off.

use glam::Vec3;

use super::probe::{ForceBreakdown, ForceProbe};
use super::World;
use crate::contact::STATIC_BODY;
use crate::forces::gravity::gravity_force;

impl World {
    /// Before the substeps: the bodies probed this step and their constant forces.
    pub(super) fn begin_probe(&mut self) {
        let stage = &mut self.stages.probe;
        let solver = &self.stages.solve.solver;
        let awake = &solver.awake;
        match stage.probe {
            ForceProbe::Off => {
                if !stage.substeps.is_empty() {
                    stage.substeps.begin(std::iter::empty());
                }
                return;
            }
            ForceProbe::One(id) => {
                let i = self.handles.dense(id).filter(|&i| self.bodies.awake[i]);
                stage.substeps.begin(i.map(|i| i as u32).into_iter());
            }
            ForceProbe::All => stage.substeps.begin(awake.iter().copied()),
        }
        let g = self.def.gravity;
        let no_fields = self.fields.is_empty();
        stage.constant.clear();
        stage
            .constant
            .extend(stage.substeps.bodies.iter().map(|&i| {
                let i = i as usize;
                let f = &solver.forces[i];
                let weight = gravity_force(self.bodies.size[i].mass, g);
                // Without fields the rest is the user's force alone, exactly.
                let other = if no_fields {
                    self.bodies.force[i]
                } else {
                    f.force - weight - f.buoyancy
                };
                [weight, f.buoyancy, other, f.air]
            }));
    }

    /// Before the continuous sweep: the velocities it may change.
    pub(super) fn probe_before_sweep(&mut self) {
        let stage = &mut self.stages.probe;
        stage.before_sweep.clear();
        let v = &self.bodies.linear_velocity;
        let bodies = &stage.substeps.bodies;
        stage
            .before_sweep
            .extend(bodies.iter().map(|&i| v[i as usize]));
    }

    /// After the step's motion: each probed body's breakdown.
    pub(super) fn finish_probe(&mut self) {
        if self.stages.probe.substeps.is_empty() {
            self.stages.probe.records.clear();
            return;
        }
        let dt = self.def.dt;
        let mut contact = vec![Vec3::ZERO; self.stages.probe.substeps.bodies.len()];
        {
            let bodies = &self.stages.probe.substeps.bodies;
            let slot = |body: u32| bodies.binary_search(&body).ok();
            let contacts = &self.stages.narrow.found.contacts;
            let solver = &self.stages.solve.solver;
            for (i, c) in contacts.iter().enumerate() {
                let (ka, kb) = (
                    slot(c.body_a),
                    (c.body_b != STATIC_BODY).then(|| slot(c.body_b)).flatten(),
                );
                if ka.is_none() && kb.is_none() {
                    continue;
                }
                let Some(t) = solver.totals(i, contacts.len()) else {
                    continue;
                };
                // A takes −λ·n and its friction; B the opposite.
                let on_a = -t.normal_impulse * c.normal + t.tangent_impulse;
                if let Some(k) = ka {
                    contact[k] += on_a;
                }
                if let Some(k) = kb {
                    contact[k] -= on_a;
                }
            }
        }
        let mut records = std::mem::take(&mut self.stages.probe.records);
        records.clear();
        let stage = &self.stages.probe;
        for (k, &i) in stage.substeps.bodies.iter().enumerate() {
            let i = i as usize;
            let mass = 1.0 / self.bodies.inv_mass[i];
            // The continuous sweep's bounce off the room is a contact too.
            let swept = mass * (self.bodies.linear_velocity[i] - stage.before_sweep[k]);
            let [weight, buoyancy, other, air] = stage.constant[k];
            let (ribbon, knot) = self.ribbon_on(i);
            let breakdown = ForceBreakdown {
                weight,
                buoyancy,
                drag: stage.substeps.drag[k] / dt,
                contact: (contact[k] + swept) / dt,
                ribbon,
                other: other + stage.substeps.grab[k] / dt,
                center_of_mass: self.bodies.center[i],
                center_of_buoyancy: self.center_of_buoyancy(i),
                knot,
                air,
            };
            records.push((self.bodies.id[i], breakdown));
        }
        self.stages.probe.records = records;
    }
}
