//! The gas stage, first in the step (`gas`): the air of the moment, every
//! gas a step on, the sleepers it has moved too far woken, and the sizes and
//! masses the bodies take from their gas. `World::advance`'s jumps age the
//! gas the same way.

use super::gas::{
    WAKE_GROWTH, WAKE_LIFT_CHANGE, WAKE_LIFT_FLOOR, WAKE_LIFT_HOVER, WAKE_LIFT_KNEE, WAKE_SHRINK,
};
use super::World;
use crate::body::BodySize;
use crate::forces::atmosphere::Atmosphere;
use crate::gas::Gas;
use crate::threading::tasks::for_each_run_collect;

/// A balloon's gas is advanced (and a sleeper's thresholds checked) once
/// this many seconds of it have gathered, not every step: 10,000 balloons'
/// gas every step would cost a few per cent of the step, and in a second
/// an 11″ balloon shrinks by a few micrometres.
const GAS_INTERVAL_S: f64 = 1.0;

/// Bodies whose gas one task takes on.
const GAS_CHUNK: usize = 1024;

impl World {
    /// The gas stage, first in the step: the air at this step, every gas
    /// on (a second at a time), the sleepers their gas has moved too far
    /// woken, and the sizes of the awake bodies whose gas moved (of all of
    /// them while the temperature changes).
    pub(super) fn update_gas(&mut self) {
        let scheduled = !self.def.temperature_schedule.is_empty();
        if !(self.has_gas || scheduled) {
            return;
        }
        self.air = self.air_at(self.time);
        let air = self.air;
        self.age_gas(f64::from(self.def.dt), &air, GAS_INTERVAL_S);
        if scheduled {
            for i in 0..self.bodies.len() {
                if self.bodies.awake[i] {
                    self.take_gas_size(i);
                }
            }
        }
    }

    /// Every gas `seconds` on in `air`, each once `interval` s of it have
    /// gathered; the sleepers it has moved too far woken; the bodies awake
    /// whose gas moved, and those it woke, take its size.
    pub(super) fn age_gas(&mut self, seconds: f64, air: &Atmosphere, interval: f64) {
        let mut woken = std::mem::take(&mut self.stages.gas_woken);
        let mut moved = std::mem::take(&mut self.stages.gas_moved);
        let mut aged = std::mem::take(&mut self.stages.gas_aged);
        woken.clear();
        moved.clear();
        aged.clear();
        let b = &mut self.bodies;
        let (awake, size, shape, island, id) = (&b.awake, &b.size, &b.shape, &b.island, &b.id);
        let (shapes, ribbons) = (&self.shapes, &self.ribbons);
        let lists = &mut self.stages.gas_task_aged;
        // Each gas on in tasks; what moved and what woke listed in body order.
        for_each_run_collect(
            b.len(),
            GAS_CHUNK,
            &mut b.gas[..],
            lists,
            &mut aged,
            |first, gases, aged| {
                for (k, gas) in gases.iter_mut().enumerate() {
                    let i = first + k;
                    let Some(gas) = gas.as_mut() else {
                        continue;
                    };
                    gas.owed_s += seconds;
                    if gas.owed_s < interval {
                        continue;
                    }
                    let owed = std::mem::take(&mut gas.owed_s);
                    gas.advance(owed, air);
                    if awake[i] {
                        aged.push((i as u32, None));
                        continue;
                    }
                    let shape = &shapes[shape[i] as usize];
                    // Only a balloon on a ribbon hovers: the finer threshold
                    // is looked up only once it is passed.
                    let wakes = match moved_too_far(gas, size[i], shape.def.volume, air) {
                        Wake::No => false,
                        Wake::Yes => true,
                        Wake::IfHovering => ribbons.on(id[i]).is_some(),
                    };
                    if wakes {
                        aged.push((i as u32, Some(island[i])));
                    }
                }
            },
        );
        for &(i, woke) in &aged {
            moved.push(i);
            woken.extend(woke);
        }
        woken.sort_unstable();
        woken.dedup();
        for &island in &woken {
            self.wake_island(island);
        }
        for &i in &moved {
            self.take_gas_size(i as usize);
        }
        self.stages.gas_woken = woken;
        self.stages.gas_moved = moved;
        self.stages.gas_aged = aged;
    }

    /// Body `i` takes the size and mass of its gas (its shape's without),
    /// and the inverse mass and inertia that go with them in the air now.
    pub(super) fn take_gas_size(&mut self, i: usize) {
        let b = &mut self.bodies;
        let shape = &self.shapes[b.shape[i] as usize];
        let size = match &b.gas[i] {
            Some(gas) => BodySize {
                scale: gas.scale(&self.air),
                mass: gas.mass() as f32,
            },
            None => shape.own_size(),
        };
        b.size[i] = size;
        let (ca, density) = (self.def.added_mass_coefficient, self.air.air_density());
        b.inv_mass[i] = shape.inv_mass(size, ca, density);
        b.inertia_factor[i] = shape.inverse_inertia_factor(size);
    }
}

/// Whether a sleeper's gas has moved it far enough to wake.
enum Wake {
    No,
    Yes,
    /// Past the finer threshold of a balloon that may hover on its ribbon
    /// (`WAKE_LIFT_KNEE`), not the coarse one.
    IfHovering,
}

/// Whether a sleeper's gas has moved it past a wake threshold from `size`,
/// the size it sleeps with: `volume` m³ is its shape's.
fn moved_too_far(gas: &Gas, size: BodySize, volume: f32, air: &Atmosphere) -> Wake {
    let scale = f64::from(gas.scale(air));
    let slept = f64::from(size.scale);
    if scale > slept * (1.0 + WAKE_GROWTH) || scale < slept * (1.0 - WAKE_SHRINK) {
        return Wake::Yes;
    }
    let s3 = slept * slept * slept;
    let lift_slept = f64::from(air.air_density()) * f64::from(volume) * s3 - f64::from(size.mass);
    let change = (gas.free_lift_kg(air) - lift_slept).abs();
    if change > WAKE_LIFT_CHANGE * lift_slept.abs() + WAKE_LIFT_FLOOR {
        Wake::Yes
    } else if lift_slept > 0.0 && change > hover_lift_change(lift_slept) {
        Wake::IfHovering
    } else {
        Wake::No
    }
}

/// kg: the change of free lift from `lift` kg (> 0) that wakes a sleeper
/// on a ribbon.
fn hover_lift_change(lift: f64) -> f64 {
    WAKE_LIFT_CHANGE * lift * (lift / WAKE_LIFT_KNEE).min(1.0) + WAKE_LIFT_HOVER
}
