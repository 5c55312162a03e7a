//! Sleeping: a settled group of touching balloons stops costing anything.
//!
//! A body is rested once it has been slow for `time_to_sleep` (a balloon
//! hovering on its ribbon, touching nothing, once slow by a finer measure
//! along gravity: it may be creeping down, `rest`). Each step the
//! rested bodies that no restless body reaches fall asleep, in groups of
//! touching or joined ones (union-find over contacts and joints); those a
//! restless body reaches or is joined to stay awake between it and the
//! sleepers (`rest`). A sleeping body is static to its awake neighbours. A
//! slow restless body wakes only the sleepers it touches, and they keep their
//! rest time (so a slow shuffle in a big pile wakes just what it moves); a
//! fast one (an impact: faster than the restitution threshold) wakes whole
//! the groups of all it can reach this step, as the user does (an impulse, a
//! grab, a removal next door), and so does a restless body's pull on a joint
//! (`wake`). A group keeps its contacts' impulses while it sleeps, so it
//! wakes without a jolt. Moving air (`crate::air`) keeps the bodies it
//! pushes awake and wakes the sleepers it reaches (`world::air_step` has
//! the rule).

mod islands;
mod rest;
mod wake;

use glam::Vec3;

use crate::body::{HandleMap, ShapeData};
use crate::contact::ContactPoint;
use crate::narrow_phase::StepMotion;

pub(crate) use islands::{SleepingIslands, UnionFind};
pub(crate) use rest::update_sleep;
pub(crate) use wake::{wake_island, wake_neighbours_of, wake_touched_bodies};

/// When bodies sleep and wake (from `WorldDef`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SleepRules {
    pub enabled: bool,
    /// s.
    pub dt: f32,
    /// s slow before a body is rested.
    pub time_to_sleep: f32,
    /// m/s and rad/s under which a body is slow.
    pub linear_speed: f32,
    /// The unit vector against gravity (zero without gravity): a hovering
    /// balloon's creep is along it (`rest`).
    pub up: Vec3,
    pub angular_speed: f32,
    /// m: the reach of a restless body (and of contacts that hold a group).
    pub speculative_distance: f32,
    /// m/s: a surface faster than this is an impact.
    pub restitution_threshold: f32,
}

/// What the sleep passes read of the world and of this step.
pub(crate) struct SleepInput<'a> {
    pub rules: SleepRules,
    pub shapes: &'a [ShapeData],
    pub handles: &'a HandleMap,
    /// The broadphase's pairs, dense indices.
    pub pairs: &'a [(u32, u32)],
    /// Bodies' bounding centres as placed this step (`Placement`).
    pub bound_center: &'a [Vec3],
    pub motion: &'a [StepMotion],
    /// Pairs of bodies held by a joint, dense indices.
    pub joined: &'a [(u32, u32)],
    /// The step's contact points (they hold groups falling asleep together).
    pub contacts: &'a [ContactPoint],
    /// Per body: its ribbon still moves, or moving air pushes it or its
    /// ribbon (`world::air_step`): it may not rest. Empty in the wake pass,
    /// which runs before the ribbons have moved.
    pub kept_awake: &'a [bool],
    /// The ribbons solved this step (their balloons' dense indices).
    pub awake_ribbons: &'a [crate::ribbon::solve::ActiveRibbon],
}

/// The sleep passes' buffers.
#[derive(Clone, Debug, Default)]
pub(crate) struct SleepBuffers {
    pub islands: UnionFind,
    /// Per body, in `update_sleep`: which stay awake, then which fall asleep.
    pub stays_awake: Vec<bool>,
    /// Which bodies were awake before `wake_touched_bodies`.
    pub was_awake: Vec<bool>,
    pub wake: Vec<u32>,
    pub wake_islands: Vec<u32>,
    /// Per group root in `update_sleep`: the island it sleeps in.
    pub island_of_root: Vec<u32>,
    /// Per body, in `update_sleep`: it hangs on its ribbon touching nothing.
    pub hovering: Vec<bool>,
}
