//! Time spent in each stage of a step, for the CLI and the web HUD: one
//! counter per stage that `World::step` runs, under the stage's own name.

use serde::{Deserialize, Serialize};

use crate::threading::thread_times::{self, Reading};
pub use crate::threading::thread_times::{ThreadCounters, ThreadTime};

macro_rules! stages {
    ($($(#[$doc:meta])* $stage:ident = $name:literal in $phase:ident,)*) => {
        /// A stage of the step, in the order the step runs them
        /// (`world/step.rs`); its name is its counter's.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
        pub enum Stage {
            $($(#[$doc])* $stage,)*
        }

        impl Stage {
            /// Every stage, in step order.
            pub const ALL: [Stage; Stage::COUNT] = [$(Stage::$stage,)*];
            pub const COUNT: usize = [$(Stage::$stage,)*].len();

            /// Its counter's name (snake case).
            pub fn name(self) -> &'static str {
                match self {
                    $(Stage::$stage => $name,)*
                }
            }

            /// The phase of the step it belongs to, for a short summary.
            pub fn phase(self) -> Phase {
                match self {
                    $(Stage::$stage => Phase::$phase,)*
                }
            }
        }
    };
}

stages! {
    /// The room's air and every balloon's gas a step on; sizes that moved.
    Gas = "gas" in Gas,
    /// The moving air's sources as they blow now; sleepers it reaches woken.
    Air = "air" in Air,
    /// Pairs of bodies held by a joint, for the sleep islands.
    Joined = "joined" in Joints,
    /// Balloons woken whose sleeping ribbons a moving balloon reaches.
    WakeRibbons = "wake_ribbons" in Ribbons,
    /// Sphere trees at their poses, bounds widened by the step's motion.
    Place = "place" in Broadphase,
    /// The broadphase's pairs of bounds.
    Pairs = "pairs" in Broadphase,
    /// Sleepers that restless bodies reach, woken.
    WakeBodies = "wake_bodies" in Broadphase,
    /// The pairs of the bodies just woken (zero when none woke).
    PairWoken = "pair_woken" in Broadphase,
    /// How far each pair may knock its bodies this step.
    Knocks = "knocks" in Broadphase,
    /// The narrowphase: contact points of the pairs.
    Contacts = "contacts" in Narrowphase,
    /// Solver states and forces of the awake bodies.
    PrepareBodies = "prepare_bodies" in Prepare,
    /// Contact constraints: coloured, in groups of four, warm-started.
    PrepareContacts = "prepare_contacts" in Prepare,
    /// The joints with an awake body.
    PrepareJoints = "prepare_joints" in Joints,
    /// The spring of a held balloon.
    GrabSpring = "grab_spring" in Prepare,
    /// The awake ribbons' points taken out, with the room and balloons near each.
    PrepareRibbons = "prepare_ribbons" in Ribbons,
    /// The probed bodies and their constant forces (nothing when off).
    BeginProbe = "begin_probe" in Probe,
    /// The substeps: forces, contacts, joints, ribbons, relax.
    Solve = "solve" in Solve,
    /// Restitution's bounces.
    Bounce = "bounce" in Finish,
    /// Contact impulses kept for the next step's warm start.
    StoreImpulses = "store_impulses" in Finish,
    /// Joint tensions kept.
    StoreTensions = "store_tensions" in Joints,
    /// Position passes: overlap beyond the slop removed.
    RemoveOverlap = "remove_overlap" in Finish,
    /// The solver's results back to the bodies.
    FinishMotion = "finish_motion" in Finish,
    /// The probed bodies' velocities before the sweep (nothing when off).
    ProbeBeforeSweep = "probe_before_sweep" in Probe,
    /// Fast bodies swept against the room.
    Sweep = "sweep" in Continuous,
    /// The ribbons' points handed back; which still move.
    FinishRibbons = "finish_ribbons" in Ribbons,
    /// The probed bodies' force breakdowns (nothing when off).
    FinishProbe = "finish_probe" in Probe,
    /// Rest clocks; groups that fall asleep.
    Sleep = "sleep" in Sleep,
    /// Bodies gone non-finite taken out.
    Quarantine = "quarantine" in Sleep,
    /// Spare buffer capacity given back.
    ReleaseSpare = "release_spare" in Sleep,
}

/// A group of stages for a short summary (`Counters::phases`): what kind of
/// work they do, not where they run (the ribbons' three stages are spread
/// over the step).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Phase {
    Gas,
    Air,
    Joints,
    Ribbons,
    Broadphase,
    Narrowphase,
    Prepare,
    Probe,
    Solve,
    Finish,
    Continuous,
    Sleep,
}

impl Phase {
    pub fn name(self) -> &'static str {
        match self {
            Phase::Gas => "gas",
            Phase::Air => "air",
            Phase::Joints => "joints",
            Phase::Ribbons => "ribbons",
            Phase::Broadphase => "broadphase",
            Phase::Narrowphase => "narrowphase",
            Phase::Prepare => "prepare",
            Phase::Probe => "probe",
            Phase::Solve => "solve",
            Phase::Finish => "finish",
            Phase::Continuous => "continuous",
            Phase::Sleep => "sleep",
        }
    }
}

/// Milliseconds spent in each stage of the last step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Counters {
    /// Per stage, in `Stage::ALL` order (serde derives arrays of up to 32).
    ms: [f64; Stage::COUNT],
    /// The whole step: the stages summed.
    total_ms: f64,
    /// Each thread's part of each stage, when timed (`set_thread_timing`).
    #[serde(skip)]
    threads: ThreadCounters,
}

impl Counters {
    /// Milliseconds `stage` took in the last step.
    pub fn ms(&self, stage: Stage) -> f64 {
        self.ms[stage as usize]
    }

    /// The whole last step, ms.
    pub fn total_ms(&self) -> f64 {
        self.total_ms
    }

    /// Each thread's busy, barrier and idle time in each stage of the last
    /// step, and the barriers each crossed: empty (no threads) unless the
    /// timing was on (`set_thread_timing`).
    pub fn threads(&self) -> &ThreadCounters {
        &self.threads
    }

    /// A step's counters made up of one stage's time and the threads' figures.
    #[cfg(test)]
    pub(crate) fn made_up(stage: Stage, ms: f64, threads: ThreadCounters) -> Counters {
        let mut counters = Counters {
            threads,
            ..Counters::default()
        };
        counters.ms[stage as usize] = ms;
        counters.total_ms = ms;
        counters
    }

    /// Stage names and times, in the order the step runs them, then "total".
    pub fn stages(&self) -> Vec<(&'static str, f64)> {
        let stages = Stage::ALL.iter().map(|&s| (s.name(), self.ms(s)));
        stages.chain([("total", self.total_ms)]).collect()
    }

    /// Phase names and their stages' times summed, each phase where its
    /// first stage runs, then "total".
    pub fn phases(&self) -> Vec<(&'static str, f64)> {
        let mut phases: Vec<(Phase, f64)> = Vec::new();
        for stage in Stage::ALL {
            match phases.iter_mut().find(|(p, _)| *p == stage.phase()) {
                Some((_, ms)) => *ms += self.ms(stage),
                None => phases.push((stage.phase(), self.ms(stage))),
            }
        }
        let phases = phases.into_iter().map(|(p, ms)| (p.name(), ms));
        phases.chain([("total", self.total_ms)]).collect()
    }
}

/// Times the stages of one step into `Counters`: `lap(stage)` gives the
/// stage the milliseconds since the last lap. A clock read a stage, no
/// allocation once warm; the threads' part (ten kilobytes) is filled and
/// copied only while the threads are timed, in a box the world keeps
/// between steps, since made or moved every step it would cost a step of
/// one awake balloon a tenth of its time.
pub(crate) struct StageClock {
    last: f64,
    ms: [f64; Stage::COUNT],
    threads: Option<ThreadClock>,
}

/// The clock's part when the threads are timed: the step's thread's slot,
/// the slots' reading at the last lap, the guard marking this thread's
/// steps, and each thread's part so far.
struct ThreadClock {
    owner: usize,
    last: Reading,
    _stepping: thread_times::Stepping,
    timed: Box<ThreadCounters>,
}

impl StageClock {
    /// Starts the step's clock; `threads`: the threads its passes may share;
    /// `spare`: the box the last timed step's `finish` gave back.
    pub fn start(threads: usize, spare: &mut Option<Box<ThreadCounters>>) -> Self {
        let threads = if thread_times::timing() {
            let (timed, owner) = ThreadCounters::begin(threads);
            let mut boxed = spare.take().unwrap_or_default();
            *boxed = timed;
            Some(ThreadClock {
                owner,
                last: Reading::now(),
                _stepping: thread_times::Stepping::enter(),
                timed: boxed,
            })
        } else {
            None
        };
        Self {
            last: now_ms(),
            ms: [0.0; Stage::COUNT],
            threads,
        }
    }

    pub fn lap(&mut self, stage: Stage) {
        let now = now_ms();
        let wall = now - self.last;
        self.ms[stage as usize] = wall;
        if let Some(t) = &mut self.threads {
            let reading = Reading::now();
            t.timed.record(stage, wall, t.owner, &t.last, &reading);
            t.last = reading;
        }
        // The readings are not the stages' time: the next stage starts after them.
        self.last = if self.threads.is_some() {
            now_ms()
        } else {
            now
        };
    }

    /// Writes the step's times, with the total, into `counters`; gives the
    /// threads' box back to `spare`.
    pub fn finish(self, counters: &mut Counters, spare: &mut Option<Box<ThreadCounters>>) {
        counters.ms = self.ms;
        counters.total_ms = self.ms.iter().sum();
        match self.threads {
            Some(t) => {
                counters.threads = *t.timed;
                *spare = Some(t.timed);
            }
            // Cleared once, when the timing went off.
            None if counters.threads.threads() > 0 => counters.threads = ThreadCounters::default(),
            None => {}
        }
    }
}

/// Turns on or off the timing of each thread's part of every stage
/// (`Counters::threads`) for every world stepped in this process from
/// now on: two clock reads per task of a parallel pass while on.
pub fn set_thread_timing(on: bool) {
    thread_times::set_timing(on);
}

/// A monotonic clock in milliseconds. Native builds read the processor's
/// time-stamp counter through `quanta` (calibrated against the system's
/// clock once a process, which it falls back on where the counter is not
/// steady): a step reads it at every stage's end, and a time-lapse's small
/// steps spent a twentieth of their time in the system's clock;
/// `wasm32-unknown-unknown` has no clock of its own, so the crate that builds
/// the module defines `up_now_ms` (up-wasm: the host's `performance.now`).
#[cfg(not(target_arch = "wasm32"))]
pub(crate) fn now_ms() -> f64 {
    use quanta::Instant;
    use std::sync::OnceLock;
    static START: OnceLock<Instant> = OnceLock::new();
    let start = *START.get_or_init(Instant::now);
    Instant::now().duration_since(start).as_secs_f64() * 1000.0
}

#[cfg(target_arch = "wasm32")]
pub(crate) fn now_ms() -> f64 {
    extern "C" {
        fn up_now_ms() -> f64;
    }
    // SAFETY: a pure function without arguments or memory access.
    unsafe { up_now_ms() }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_stage_has_a_name_of_its_own_and_total_comes_last() {
        let names: Vec<&str> = Counters::default()
            .stages()
            .iter()
            .map(|&(n, _)| n)
            .collect();
        assert_eq!(names.len(), Stage::COUNT + 1);
        assert_eq!(names.last(), Some(&"total"));
        let mut unique = names.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), names.len(), "{names:?}");
    }

    #[test]
    fn the_phases_sum_to_the_stages() {
        let mut clock = StageClock::start(1, &mut None);
        for stage in Stage::ALL {
            clock.lap(stage);
        }
        let mut counters = Counters::default();
        clock.finish(&mut counters, &mut None);
        for (k, ms) in counters.ms.iter_mut().enumerate() {
            *ms = (k + 1) as f64;
        }
        counters.total_ms = counters.ms.iter().sum();
        let phases: f64 = counters.phases()[..]
            .split_last()
            .unwrap()
            .1
            .iter()
            .map(|p| p.1)
            .sum();
        assert_eq!(phases, counters.total_ms());
        assert_eq!(counters.ms(Stage::Gas), 1.0);
        assert_eq!(counters.phases()[0], ("gas", 1.0));
    }

    /// Timed, the clock hands each thread's part over and keeps its box for
    /// the next step; untimed again, the part is cleared.
    #[test]
    fn the_threads_part_is_handed_over_while_timed_and_cleared_after() {
        let (mut spare, mut counters) = (None, Counters::default());
        set_thread_timing(true);
        let mut clock = StageClock::start(1, &mut spare);
        clock.lap(Stage::Gas);
        clock.finish(&mut counters, &mut spare);
        set_thread_timing(false);
        assert_eq!(counters.threads().threads(), 1);
        assert!(spare.is_some());
        StageClock::start(1, &mut spare).finish(&mut counters, &mut spare);
        assert_eq!(counters.threads().threads(), 0);
    }
}
