//! The world: bodies, joints, the static room, and their step.
//!
//! This file holds the `World` and its buffers; the public calls are in
//! `bodies` (adding and removing), `actions` (pushing, grabbing, waking),
//! `queries` (reading the state), `joints`, `ribbons`, `gas`, `probe` and
//! `state` (hash, snapshots).
//! The step is `step.rs`: a list of named stages, each timed under its own
//! name (`crate::counters::Stage`), each in a file of its own here or in the
//! crate (`gas_step`, `place`, `contacts`, `prepare`, `ribbons_step`,
//! `probe_step`, the solver, `finish`, `crate::continuous`, `crate::sleep`),
//! each stage owning its buffers.

mod actions;
mod air_step;
mod bodies;
mod contacts;
mod def;
mod error;
mod finish;
mod gas;
mod gas_step;
mod joints;
pub mod limits;
mod place;
mod prepare;
mod probe;
mod probe_step;
mod queries;
mod ribbons;
mod ribbons_step;
mod state;
mod step;

use serde::{Deserialize, Serialize};

use crate::body::{Bodies, HandleMap, ShapeData};
use crate::broad_phase::BroadPhase;
use crate::contact::WarmStartCache;
use crate::continuous::SweepBuffers;
use crate::counters::Counters;
use crate::forces::field::ForceFields;
use crate::grab::Grab;
use crate::joint::Joints;
use crate::narrow_phase::NarrowPhase;
use crate::quarantine::{FaultBuffers, QuarantinedBody};
use crate::ribbon::solve::RibbonStage;
use crate::ribbon::Ribbons;
use crate::sleep::{SleepBuffers, SleepInput, SleepRules, SleepingIslands};

pub use contacts::ContactInfo;
pub use def::WorldDef;
pub use error::PhysicsError;
pub use gas::{
    Advance, MAX_JUMP_S, WAKE_GROWTH, WAKE_LIFT_CHANGE, WAKE_LIFT_FLOOR, WAKE_LIFT_HOVER,
    WAKE_LIFT_KNEE, WAKE_SHRINK,
};
pub use probe::{ForceBreakdown, ForceProbe};
pub use step::StepStats;

pub(crate) use place::roots_within;
use place::Placement;
use prepare::SolverStage;

/// Bodies one task takes in a pass over the bodies (placing them, their
/// solver states, finishing their motion, their sleep clocks...).
pub(crate) const PLACE_CHUNK: usize = 512;

/// The most bodies a world holds (handles and buffers are sized by u32).
pub const MAX_BODIES: usize = 4_000_000;

/// Each stage's buffers, rebuilt every step; never part of the state.
#[derive(Clone, Debug, Default)]
struct Stages {
    place: Placement,
    broad: BroadPhase,
    narrow: NarrowPhase,
    solve: SolverStage,
    sweep: SweepBuffers,
    sleep: SleepBuffers,
    faults: FaultBuffers,
    ribbons: RibbonStage,
    /// Pairs of bodies held by a joint, dense indices (`joints`).
    joined: Vec<(u32, u32)>,
    /// Islands whose gas woke them (`gas`).
    gas_woken: Vec<u32>,
    /// Awake bodies whose gas moved this step (`gas`).
    gas_moved: Vec<u32>,
    /// The awake bodies whose gas moved and the sleepers it woke (with
    /// the island woken), in body order, and each task's share (`gas`).
    gas_aged: Vec<(u32, Option<u32>)>,
    gas_task_aged: Vec<Vec<(u32, Option<u32>)>>,
    /// The solver's constraints are the found contacts' (`contacts`): a
    /// measurement's narrowphase since the step replaced them.
    solved: bool,
    /// The force probe's setting and records (`probe`).
    probe: probe::ProbeStage,
    /// The moving air's sources as they blow this step (`air_step`).
    air_now: crate::air::AirNow,
    /// Islands the moving air woke (`air_step`).
    air_woken: Vec<u32>,
    /// Every body has been checked for non-finite state once (`bodies`):
    /// later steps check the bodies they moved.
    checked_all: bool,
    /// The step's clock's box for each thread's times, between timed steps
    /// (`counters::StageClock`).
    thread_times: Option<Box<crate::counters::ThreadCounters>>,
}

impl Stages {
    /// What the sleep passes read of this step, and their buffers.
    fn for_sleep<'a>(
        &'a mut self,
        rules: SleepRules,
        shapes: &'a [ShapeData],
        handles: &'a HandleMap,
    ) -> (SleepInput<'a>, &'a mut SleepBuffers) {
        let input = SleepInput {
            rules,
            shapes,
            handles,
            pairs: &self.broad.pairs,
            bound_center: &self.place.bound_center,
            motion: &self.place.motion,
            joined: &self.joined,
            contacts: &self.narrow.found.contacts,
            kept_awake: &self.ribbons.moving,
            awake_ribbons: &self.ribbons.active[..self.ribbons.awake],
        };
        (input, &mut self.sleep)
    }
}

/// A world of balloons in a room. See the crate docs for conventions.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct World {
    def: WorldDef,
    shapes: Vec<ShapeData>,
    bodies: Bodies,
    handles: HandleMap,
    joints: Joints,
    ribbons: Ribbons,
    warm: WarmStartCache,
    sleeping: SleepingIslands,
    grab: Option<Grab>,
    ribbon_grab: Option<ribbons::RibbonGrab>,
    /// The room's air now (`gas::air_at`): the atmosphere at the schedule's temperature.
    air: crate::Atmosphere,
    /// Whether any body was ever filled with gas (the gas stage runs).
    has_gas: bool,
    time: f64,
    step_count: u64,
    stats: StepStats,
    /// Reports of bodies taken out as non-finite, not yet collected (events, not state).
    #[serde(skip)]
    quarantined: Vec<QuarantinedBody>,
    /// Code, not state (`forces::field`).
    #[serde(skip)]
    fields: ForceFields,
    /// The room's moving air (`air`): still unless a scene sets sources.
    air_flow: crate::AirFlow,
    #[serde(skip)]
    counters: Counters,
    #[serde(skip)]
    stages: Stages,
}

impl World {
    pub fn new(def: WorldDef) -> Result<World, PhysicsError> {
        def.validate()?;
        let mut air = def.atmosphere;
        if let Some(k) = def.temperature_schedule.at(0.0) {
            air.temperature_k = k;
        }
        Ok(World {
            air,
            has_gas: false,
            def,
            shapes: Vec::new(),
            bodies: Bodies::default(),
            handles: HandleMap::default(),
            joints: Joints::default(),
            ribbons: Ribbons::default(),
            warm: WarmStartCache::default(),
            sleeping: SleepingIslands::default(),
            grab: None,
            ribbon_grab: None,
            time: 0.0,
            step_count: 0,
            stats: StepStats::default(),
            quarantined: Vec::new(),
            fields: ForceFields::default(),
            air_flow: crate::AirFlow::default(),
            counters: Counters::default(),
            stages: Stages::default(),
        })
    }

    pub fn def(&self) -> &WorldDef {
        &self.def
    }

    /// Adds a force field (`forces::field`, the step's extension point):
    /// from the next step on, its forces act on every awake balloon (once a
    /// step) and every awake ribbon's points (once a substep); the sleepers
    /// wake, since the forces that held them changed. Not kept by snapshots.
    pub fn add_force_field(&mut self, field: std::sync::Arc<dyn crate::ForceField>) {
        self.fields.push(field);
        self.wake_all();
    }

    /// Sets the room's moving air (`air`): from the next step on, every drag
    /// acts against it; the sleepers wake. Kept by snapshots and in the
    /// state hash (still air hashes as a world that never had any).
    pub fn set_air_flow(&mut self, air_flow: crate::AirFlow) {
        self.air_flow = air_flow;
        self.wake_all();
    }

    /// The room's moving air.
    pub fn air_flow(&self) -> &crate::AirFlow {
        &self.air_flow
    }

    /// The air's velocity at `p` now, m/s.
    pub fn air_velocity_at(&self, p: glam::Vec3) -> glam::Vec3 {
        self.air_flow.velocity_at(p, self.time)
    }

    /// Removes every force field; the sleepers wake.
    pub fn clear_force_fields(&mut self) {
        self.fields.clear();
        self.wake_all();
    }
}
