//! The step, as the list of its stages. Each stage is a method or a module
//! of its own, owning its buffers:
//!
//! 1. broadphase: wake the balloons whose sleeping ribbons an awake one
//!    reaches (`ribbons`), place the bodies (`place`), pair their bounds, wake what
//!    restless bodies reach (`sleep::wake`), and each pair's knocks;
//! 2. narrowphase: the contact points of the pairs (`contacts`);
//! 3. prepare: solver states, forces (`forces::body_forces`), contact
//!    constraints and joints (`prepare`), the awake ribbons (`ribbons`);
//! 4. solve: the substeps (`solver`), the ribbons' in them (`ribbon::solve`);
//! 5. restitution and position: bounces, impulses kept for the next step,
//!    overlap removed, results back to the bodies (`finish`);
//! 6. continuous: fast bodies swept against the room (`continuous`); the
//!    ribbons' points handed back (`ribbons`); the probed bodies' forces
//!    (`probe`);
//! 7. sleep: rest clocks and groups falling asleep (`sleep::rest`), bodies
//!    gone non-finite taken out, spare capacity given back.
//!
//! Each stage is timed into `Counters`.

use serde::{Deserialize, Serialize};

use super::World;
use crate::continuous::{sweep_fast_bodies, SweepInput};
use crate::counters::{Counters, Stopwatch};
#[cfg(feature = "parallel")]
use crate::keep_awake::with_threads_kept_awake;
use crate::ribbon;
use crate::ribbon::solve::SubstepInput;
use crate::sleep::{self, SleepRules};
use crate::solver::body_state::BodyState;
use crate::solver::integrate::GrabSpring;
use crate::solver::{SolveParams, Stabilization};

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
        // Called from outside rayon's pool, the whole step moves onto one of
        // its threads: otherwise every parallel pass (hundreds a step) would
        // hand its work across threads and put this one to sleep until done.
        // There the pool's other threads stay awake until the step ends.
        #[cfg(feature = "parallel")]
        if rayon::current_thread_index().is_none() {
            rayon::scope(|_| with_threads_kept_awake(|| self.step_here()))
        } else {
            with_threads_kept_awake(|| self.step_here())
        }
        #[cfg(not(feature = "parallel"))]
        self.step_here()
    }

    /// `step`, on the calling thread.
    fn step_here(&mut self) {
        let mut clock = Stopwatch::start();
        let mut counters = Counters::default();

        self.update_gas();
        self.find_joined();
        self.wake_touched_ribbons();
        self.place_bodies(false);
        self.find_pairs();
        if self.wake_touched_bodies() {
            self.pair_woken_bodies();
        }
        self.add_knocks();
        counters.broadphase_ms = clock.lap();

        self.find_contacts(false);
        counters.narrowphase_ms = clock.lap();

        let grab = self.prepare_solver();
        self.prepare_ribbons();
        self.begin_probe();
        counters.prepare_ms = clock.lap();

        self.solve(grab.as_ref());
        self.stages.solved = true;
        counters.solve_ms = clock.lap();

        self.bounce();
        self.store_impulses();
        self.store_tensions();
        self.remove_overlap();
        self.finish_motion();
        counters.restitution_ms = clock.lap();

        self.probe_before_sweep();
        self.sweep_fast_bodies();
        self.finish_ribbons();
        self.finish_probe();
        counters.continuous_ms = clock.lap();

        self.update_sleep();
        self.quarantine_non_finite();
        self.release_spare();
        counters.sleep_ms = clock.lap();

        self.time += self.def.dt as f64;
        self.step_count += 1;
        counters.total_ms = counters.broadphase_ms
            + counters.narrowphase_ms
            + counters.prepare_ms
            + counters.solve_ms
            + counters.restitution_ms
            + counters.continuous_ms
            + counters.sleep_ms;
        self.counters = counters;
    }

    /// The substeps: velocities, contacts, joints and ribbons (`solver`,
    /// `ribbon::solve`).
    fn solve(&mut self, grab: Option<&GrabSpring>) {
        let params = self.solve_params();
        let stages = &mut self.stages;
        let probe = &mut stages.probe.substeps;
        let probe = (!probe.is_empty()).then_some(probe);
        let ribbons = &mut stages.ribbons;
        let input = SubstepInput {
            h: params.dt / params.substeps as f32,
            gravity: self.def.gravity,
            centers: &self.bodies.center,
            shape_of: &self.bodies.shape,
            size: &self.bodies.size,
            shapes: &self.shapes,
            triangles: &ribbons.triangles,
            bodies: &ribbons.bodies,
        };
        let active = &mut ribbons.active[..ribbons.awake];
        let mut ribbons_substep = |states: &mut [BodyState]| {
            if !active.is_empty() {
                ribbon::solve::substep(active, &input, states);
            }
        };
        stages
            .solve
            .solver
            .solve(&params, grab, probe, &mut ribbons_substep);
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
