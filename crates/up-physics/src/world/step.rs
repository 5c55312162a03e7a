//! The step, as the list of its stages. Each stage is a method or a module
//! of its own, owning its buffers, and is timed under its own name
//! (`crate::counters::Stage`, in this order):
//!
//! 1. `gas`: the room's air and every balloon's gas a step on, the sleepers
//!    it moved too far woken, sizes taken (`gas_step`);
//! 2. `air`: the moving air's sources as they blow now, and the sleepers it
//!    reaches woken (`air_step`; nothing in still air);
//! 3. `joined`: the pairs of bodies a joint holds, for the sleep islands
//!    (`joints`);
//! 4. `wake_ribbons`: the balloons woken whose sleeping ribbons an awake one
//!    reaches (`ribbons_step`);
//! 5. broadphase: `place` the bodies' trees and bounds (`place`), `pairs` of
//!    bounds, `wake_bodies` that restless bodies reach (`sleep::wake`),
//!    `pair_woken` (the pairs of those), `knocks` each pair may give;
//! 6. `contacts`: the narrowphase's contact points (`contacts`);
//! 7. prepare: `prepare_bodies` (solver states, forces and the force fields'
//!    on balloons, the air's velocity at each, `forces::body_forces`),
//!    `prepare_contacts`,
//!    `prepare_joints`, `grab_spring` (`prepare`), `prepare_ribbons` (the
//!    awake ribbons taken out, `ribbons_step`), `begin_probe` (`probe_step`);
//! 8. `solve`: the substeps (`solver`), the ribbons in them as the solver's
//!    `ribbons` part (`ribbon::solve`, where the force fields act on their
//!    points and the air is sampled at them);
//! 9. finish: `bounce` (restitution), `store_impulses`, `store_tensions`,
//!    `remove_overlap` (position passes), `finish_motion` (results back to
//!    the bodies) (`finish`);
//! 10. `probe_before_sweep`, `sweep` (fast bodies swept against the room,
//!     `crate::continuous`), `finish_ribbons` (points handed back,
//!     `ribbons_step`; the bodies the air pushes kept from resting,
//!     `air_step`), `finish_probe` (`probe_step`);
//! 11. `sleep` (rest clocks, groups falling asleep: `sleep::rest`),
//!     `quarantine` (bodies gone non-finite taken out), `release_spare`
//!     (spare capacity given back).

use serde::{Deserialize, Serialize};

use super::World;
use crate::continuous::{sweep_fast_bodies, SweepInput};
use crate::counters::{Stage, StageClock};
use crate::ribbon::solve::{RibbonSubsteps, SubstepInput};
use crate::sleep::{self, SleepRules};
use crate::solver::integrate::GrabSpring;
use crate::solver::{SolveParams, Stabilization, SubstepParts};
#[cfg(feature = "parallel")]
use crate::threading::keep_awake::with_threads_kept_awake;
#[cfg(feature = "parallel")]
use crate::threading::tasks::alone;

/// Awake bodies (in the last step) above which a step is shared among the
/// pool's threads: the smallest of the passes' tasks (the ribbons', 64 a
/// task) is then more than one.
#[cfg(feature = "parallel")]
const POOL_AWAKE_BODIES: u32 = 64;
/// Contact points (in the last step) above which a step is shared: the
/// solver's groups then fill more than one task.
#[cfg(feature = "parallel")]
const POOL_CONTACTS: u32 = 256;

/// What the last step measured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StepStats {
    /// Deepest overlap found by the last narrowphase (balloon–balloon or balloon–room), m.
    pub max_penetration: f32,
    pub pair_count: u32,
    pub contact_count: u32,
    pub awake_count: u32,
    /// Bodies quarantined (taken out as non-finite) since the world was made.
    pub quarantined_count: u64,
    /// Position passes the step ran: `stabilization_iterations` (twice that
    /// after an impact), more (up to `stabilization_max_iterations`) while
    /// overlap deeper than `stabilization_target` remained.
    pub position_passes: u32,
}

impl World {
    /// Advances the world by `def.dt` seconds.
    pub fn step(&mut self) {
        #[cfg(feature = "parallel")]
        {
            // A small step runs on the calling thread, its passes whole: the
            // pool would cost it more in hand-overs than it could share.
            if !self.worth_the_pool() {
                return alone(|| self.step_here());
            }
            // Called from outside rayon's pool, the whole step moves onto one
            // of its threads: otherwise every parallel pass (hundreds a step)
            // would hand its work across threads and put this one to sleep
            // until done. There the pool's other threads stay awake until the
            // step ends.
            if rayon::current_thread_index().is_none() {
                rayon::scope(|_| with_threads_kept_awake(|| self.step_here()))
            } else {
                with_threads_kept_awake(|| self.step_here())
            }
        }
        #[cfg(not(feature = "parallel"))]
        self.step_here()
    }

    /// Whether this step is worth sharing among the pool's threads: there
    /// are several, and the last step had enough awake bodies or contacts
    /// that its passes split into more than one task (a step that wakes a
    /// crowd runs alone once, the next one shares it).
    #[cfg(feature = "parallel")]
    fn worth_the_pool(&self) -> bool {
        rayon::current_num_threads() > 1
            && (self.stats.awake_count > POOL_AWAKE_BODIES
                || self.stats.contact_count > POOL_CONTACTS)
    }

    /// `step`, on the calling thread.
    fn step_here(&mut self) {
        #[cfg(feature = "parallel")]
        let threads = crate::threading::tasks::threads_here();
        #[cfg(not(feature = "parallel"))]
        let threads = 1;
        let mut clock = StageClock::start(threads, &mut self.stages.thread_times);

        self.update_gas();
        clock.lap(Stage::Gas);
        self.wake_in_air();
        clock.lap(Stage::Air);
        self.find_joined();
        clock.lap(Stage::Joined);
        self.wake_touched_ribbons();
        clock.lap(Stage::WakeRibbons);
        self.place_bodies(false);
        clock.lap(Stage::Place);
        self.find_pairs();
        clock.lap(Stage::Pairs);
        let woke = self.wake_touched_bodies();
        clock.lap(Stage::WakeBodies);
        if woke {
            self.pair_woken_bodies();
        }
        clock.lap(Stage::PairWoken);
        self.add_knocks();
        clock.lap(Stage::Knocks);

        self.find_contacts(false);
        clock.lap(Stage::Contacts);

        self.prepare_bodies();
        clock.lap(Stage::PrepareBodies);
        self.prepare_contacts();
        clock.lap(Stage::PrepareContacts);
        self.prepare_joints();
        clock.lap(Stage::PrepareJoints);
        let grab = self.grab_spring();
        clock.lap(Stage::GrabSpring);
        self.prepare_ribbons();
        clock.lap(Stage::PrepareRibbons);
        self.begin_probe();
        clock.lap(Stage::BeginProbe);

        self.solve(grab.as_ref());
        self.stages.solved = true;
        clock.lap(Stage::Solve);

        self.bounce();
        clock.lap(Stage::Bounce);
        self.store_impulses();
        clock.lap(Stage::StoreImpulses);
        self.store_tensions();
        clock.lap(Stage::StoreTensions);
        self.remove_overlap();
        clock.lap(Stage::RemoveOverlap);
        self.finish_motion();
        clock.lap(Stage::FinishMotion);

        self.probe_before_sweep();
        clock.lap(Stage::ProbeBeforeSweep);
        self.sweep_fast_bodies();
        clock.lap(Stage::Sweep);
        self.finish_ribbons();
        self.keep_awake_in_air();
        clock.lap(Stage::FinishRibbons);
        self.finish_probe();
        clock.lap(Stage::FinishProbe);

        self.update_sleep();
        clock.lap(Stage::Sleep);
        self.quarantine_non_finite();
        clock.lap(Stage::Quarantine);
        self.release_spare();
        clock.lap(Stage::ReleaseSpare);

        self.time += self.def.dt as f64;
        self.step_count += 1;
        clock.finish(&mut self.counters, &mut self.stages.thread_times);
    }

    /// The substeps: velocities, contacts, joints (`solver`), and the awake
    /// ribbons in the solver's `ribbons` slot (`ribbon::solve`).
    fn solve(&mut self, grab: Option<&GrabSpring>) {
        let params = self.solve_params();
        let stages = &mut self.stages;
        let probe = &mut stages.probe.substeps;
        let probe = (!probe.is_empty()).then_some(probe);
        let ribbons = &mut stages.ribbons;
        let mut ribbons = RibbonSubsteps {
            active: &mut ribbons.lanes,
            touch: &mut ribbons.touch,
            input: SubstepInput {
                h: params.dt / params.substeps as f32,
                gravity: self.def.gravity,
                centers: &self.bodies.center,
                shape_of: &self.bodies.shape,
                size: &self.bodies.size,
                shapes: &self.shapes,
                triangles: &ribbons.near.triangles,
                bodies: &ribbons.near.bodies,
                fields: &self.fields,
                time: self.time,
                air: (!self.air_flow.is_still()).then_some(&stages.air_now),
            },
        };
        let parts = SubstepParts {
            ribbons: (!ribbons.active.is_empty()).then_some(&mut ribbons as _),
        };
        stages.solve.solver.solve(&params, grab, probe, parts);
    }

    /// Bounces, for contacts that closed faster than the restitution threshold.
    fn bounce(&mut self) {
        let (restitution, threshold) = (self.def.restitution, self.def.restitution_threshold);
        self.stages.solve.solver.restitution(restitution, threshold);
    }

    fn solve_params(&self) -> SolveParams {
        SolveParams {
            dt: self.def.dt,
            substeps: self.def.substeps,
            iterations: self.def.solve_iterations,
            contact_hertz: self.def.contact_hertz,
            contact_damping_ratio: self.def.contact_damping_ratio,
            max_push_out: self.def.max_push_out,
            friction: self.def.friction,
            angular_damping: self.def.angular_damping,
        }
    }

    /// Woken bodies sleep where they were placed, with a sleeper's margin (no
    /// velocity): only their pairs with other sleepers are new, unless the
    /// broadphase cannot add them in place.
    fn pair_woken_bodies(&mut self) {
        let (s, awake) = (&self.stages.place, &self.bodies.awake);
        let was_awake = &self.stages.sleep.was_awake;
        let broad = &mut self.stages.broad;
        if !broad.add_woken_pairs(&s.bound_center, &s.bound_radius, was_awake, awake) {
            self.place_bodies(false);
            self.find_pairs();
        }
    }

    /// The position passes: overlap beyond the slop removed from the
    /// positions directly, twice as many passes after an impact (a contact
    /// that closed faster than the speculative distance a step, and pushed),
    /// which crushes balloons between others. Bodies that are merely fast
    /// (rising side by side, or drifting free) do not count.
    fn remove_overlap(&mut self) {
        let solver = &mut self.stages.solve.solver;
        let mut min_passes = self.def.stabilization_iterations;
        let impact_speed = self.def.speculative_distance / self.def.dt;
        if solver.any_impact(impact_speed) {
            min_passes *= 2;
        }
        self.stats.position_passes = solver.stabilize(&Stabilization {
            slop: self.def.stabilization_slop,
            target: self.def.stabilization_target,
            min_passes,
            max_passes: self.def.stabilization_max_iterations,
        });
    }

    fn sweep_fast_bodies(&mut self) {
        let Some(room) = self
            .def
            .room
            .as_ref()
            .filter(|_| self.def.enable_continuous)
        else {
            return;
        };
        let input = SweepInput {
            room,
            shapes: &self.shapes,
            solver: &self.stages.solve.solver,
            dt: self.def.dt,
            restitution: self.def.restitution,
        };
        sweep_fast_bodies(&input, &mut self.bodies, &mut self.stages.sweep);
    }

    fn sleep_rules(&self) -> SleepRules {
        let d = &self.def;
        SleepRules {
            enabled: d.enable_sleep,
            dt: d.dt,
            time_to_sleep: d.time_to_sleep,
            linear_speed: d.sleep_linear_speed,
            up: -d.gravity.normalize_or_zero(),
            angular_speed: d.sleep_angular_speed,
            speculative_distance: d.speculative_distance,
            restitution_threshold: d.restitution_threshold,
        }
    }

    fn wake_touched_bodies(&mut self) -> bool {
        let rules = self.sleep_rules();
        let (input, buffers) = self.stages.for_sleep(rules, &self.shapes, &self.handles);
        sleep::wake_touched_bodies(&input, &mut self.bodies, &mut self.sleeping, buffers)
    }

    fn update_sleep(&mut self) {
        // A balloon held, or held by its ribbon, does not rest.
        let held = self.grab.map(|g| g.body);
        let held = held.or_else(|| self.ribbon_grab.and_then(|g| self.ribbon_body(g.ribbon)));
        let grabbed = held.and_then(|body| self.handles.dense(body));
        let rules = self.sleep_rules();
        let (input, buffers) = self.stages.for_sleep(rules, &self.shapes, &self.handles);
        let (bodies, sleeping) = (&mut self.bodies, &mut self.sleeping);
        sleep::update_sleep(&input, grabbed, &self.warm, bodies, sleeping, buffers);
    }

    /// Gives back the capacity that the buffers sized by the contacts did
    /// not use this step, once it is four times the use (`spare`): a pile
    /// asleep after a stir holds what it held asleep before.
    fn release_spare(&mut self) {
        let s = &mut self.stages;
        s.broad.release_spare();
        s.narrow.release_spare();
        s.place.release_spare();
        s.faults.release_spare();
        s.solve.release_spare();
        self.warm.release_spare();
        self.sleeping.release_spare();
    }
}
