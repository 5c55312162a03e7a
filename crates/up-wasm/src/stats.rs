//! The step's stage times as the page reads them: summed over the steps
//! between two `stats` calls (browsers coarsen `performance.now()`, so one
//! step's timings are noisy) and averaged when read, with the last step's
//! counts, and each thread's part of each stage when timed (`thread_stats`).

use up_physics::World;

use crate::info::EngineStats;
use crate::thread_stats::ThreadSums;

/// Stage milliseconds summed over the steps since the last `take`.
#[derive(Default)]
pub struct StageSums {
    sums: Vec<(&'static str, f64)>,
    steps: u32,
    threads: ThreadSums,
}

impl StageSums {
    /// Adds `world`'s last step's stage times.
    pub fn add(&mut self, world: &World) {
        let stages = world.counters().stages();
        if self.sums.len() != stages.len() {
            self.sums = stages.iter().map(|&(name, _)| (name, 0.0)).collect();
            self.steps = 0;
        }
        for (sum, (_, ms)) in self.sums.iter_mut().zip(&stages) {
            sum.1 += ms;
        }
        self.steps += 1;
        self.threads.add(world.counters());
    }

    /// Steps summed since the last `take` (for the tests).
    #[cfg(test)]
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Per-stage milliseconds per step, averaged over the steps since the
    /// last call (the last step's when none), and the last step's counts;
    /// the sums start afresh.
    pub fn take(&mut self, world: &World) -> EngineStats {
        let stages = if self.steps > 0 {
            let n = f64::from(self.steps);
            self.sums
                .iter()
                .map(|&(name, sum)| (name.to_string(), sum / n))
                .collect()
        } else {
            world
                .counters()
                .stages()
                .iter()
                .map(|&(name, ms)| (name.to_string(), ms))
                .collect()
        };
        for sum in &mut self.sums {
            sum.1 = 0.0;
        }
        self.steps = 0;
        let s = world.stats();
        EngineStats {
            stages,
            bodies: world.body_count() as u32,
            awake: s.awake_count,
            pairs: s.pair_count,
            contacts: s.contact_count,
            max_penetration: s.max_penetration,
            ribbons: world.ribbon_count() as u32,
            ribbon_max_stretch: world.ribbon_max_stretch(),
            threads: self.threads.take(),
        }
    }
}
