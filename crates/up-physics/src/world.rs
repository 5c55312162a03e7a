//! The world: bodies, the static room, and `step()`.

use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};
use thiserror::Error;
use up_geom::norm::{distance, Norm};
use up_geom::query::toi_sphere_trimesh::{sweep_may_hit, toi_sphere_trimesh_new_contact};
use up_geom::{Pose, Sphere, TriMesh};

use crate::body::{BalloonShape, Bodies, BodyDef, BodyId, HandleMap, ShapeData, ShapeId};
use crate::broad_phase::BroadPhase;
use crate::contact::{ResumeFrom, StoredImpulse, WarmStartCache, STATIC_BODY};
use crate::counters::{Counters, Stopwatch};
use crate::forces::atmosphere::Atmosphere;
use crate::forces::buoyancy::buoyancy_force;
use crate::forces::drag::{added_mass, drag_factor};
use crate::forces::gravity::gravity_force;
use crate::grab::{Grab, GRAB_DAMPING_RATIO, GRAB_HERTZ, GRAB_MAX_WEIGHTS};
use crate::hash::Fnv1a;
use crate::narrow_phase::{add_knocks, NarrowInput, NarrowPhase, StepMotion};
use crate::quarantine::{self, QuarantinedBody, MAX_QUARANTINE_REPORTS};
use crate::sleep::{SleepingIslands, UnionFind};
use crate::snapshot::{self, SnapshotError};
use crate::solver::body_state::{world_inverse_inertia, BodyState};
use crate::solver::contact_constraint;
#[cfg(feature = "parallel")]
use crate::solver::contact_constraint::PreparedContact;
use crate::solver::integrate::{BodyForces, GrabSpring};
use crate::solver::{SolveParams, Solver, Stabilization};
#[cfg(feature = "parallel")]
use crate::tasks::worth_splitting;
use crate::tasks::{collect_in_order, fill_chunks, for_each_run, Ragged};

/// Bodies one task takes in a pass over the bodies (placing them, their
/// solver states, finishing their motion, their sleep clocks...).
const PLACE_CHUNK: usize = 512;

/// Awake bodies one task sweeps.
const SWEEP_CHUNK: usize = 256;

/// Contacts one task prepares.
#[cfg(feature = "parallel")]
const PREPARE_CHUNK: usize = 1024;

/// Everything that defines a world, with documented defaults (`Default`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct WorldDef {
    /// m/s²; (0, −9.81, 0).
    pub gravity: Vec3,
    /// The room's air: densities for buoyancy, drag and added mass follow from it.
    pub atmosphere: Atmosphere,
    /// s per step; 1/60.
    pub dt: f32,
    /// Solver substeps per step; 4.
    pub substeps: u32,
    /// Gauss-Seidel passes over the contacts per substep; 2. More converge
    /// chains of balloons (pile → ceiling) faster, at a proportional cost.
    /// With one, the contact impulses of a settling pile swing by 10–25 %
    /// from step to step; groups frozen at different steps then hold
    /// impulses that do not balance, jolt when woken, and wake the next in
    /// cascades: the 10,000-balloon bench pile fell asleep whole at 21–27 s
    /// with one pass, at 14.5–19 s with two, and the bench's run got faster
    /// (Rapier, given the same second pass, gained more: docs/benchmarks.md).
    pub solve_iterations: u32,
    /// Overlap the position pass leaves alone, m; 0.0005. Deeper overlap is removed
    /// after each step, so balloons never sink into each other.
    pub stabilization_slop: f32,
    /// Passes of the position pass per step, at least; 4 (0 turns it off),
    /// twice that in a step with an impact: a contact that closed faster than
    /// `speculative_distance` in the step, and pushed.
    /// Cheap next to the solve; 2 let a 1,000-balloon pile reach 1.8 mm of overlap
    /// once the solve ran colour by colour, 4 hold it to 1.3 mm; doubling them for
    /// impacts took a stirred 2,000-balloon soak from 1.36 to 0.92 mm.
    pub stabilization_iterations: u32,
    /// More passes, up to this many in all, while a pass still finds overlap
    /// deeper than `stabilization_target`; 32. A crowd pressed into the apex
    /// is a long chain that a few passes cannot straighten: the 10,000-balloon
    /// bench pile reached 1.97 mm in its arrival with 4 (8 after an impact),
    /// 1.2–1.5 mm with up to 16, 0.96 mm with up to 32 (and the knocks).
    pub stabilization_max_iterations: u32,
    /// Overlap that calls for another position pass, m; 0.001.
    pub stabilization_target: f32,
    /// Contact stiffness, Hz; 60, a quarter of the substep rate at 4 substeps of a
    /// 60 Hz step (higher is clamped to that). Box2D and Rapier use 30; balloons
    /// pressed up by a crowd need the stiffer contact to stay within 1 mm.
    pub contact_hertz: f32,
    /// Contact damping ratio, dimensionless; 10 (heavily damped, as Box2D and Rapier).
    pub contact_damping_ratio: f32,
    /// Fastest speed at which overlap is pushed apart, m/s; 1.
    pub max_push_out: f32,
    /// Coulomb friction coefficient, latex on latex and on walls; 0.5 (a guess: 0.3–0.8).
    pub friction: f32,
    /// Coefficient of restitution; 0.4 (a guess: 0.3–0.6).
    pub restitution: f32,
    /// Approach speed below which contacts do not bounce, m/s; 0.1.
    pub restitution_threshold: f32,
    /// Drag coefficient C_D; 0.95 (fits the measured ascent of pilot balloons).
    pub drag_coefficient: f32,
    /// Added-mass coefficient C_a; 0.5 (sphere).
    pub added_mass_coefficient: f32,
    /// Angular damping rate, 1/s; 2 (rotational air drag, tunable: see the physics reference).
    pub angular_damping: f32,
    /// Contacts are found this far before surfaces touch, m; 0.01.
    pub speculative_distance: f32,
    /// Whether settled balloons go to sleep; true.
    pub enable_sleep: bool,
    /// A body slower than this is a candidate for sleep, m/s; 0.005.
    pub sleep_linear_speed: f32,
    /// ... and turning slower than this, rad/s; 0.05.
    pub sleep_angular_speed: f32,
    /// Seconds a body must stay slow before it may sleep; 0.5 (see `sleep.rs`).
    pub time_to_sleep: f32,
    /// Sweep fast bodies against the room with time of impact; true.
    pub enable_continuous: bool,
    /// The static room, one-sided, normals pointing into the room. `None`: free space.
    pub room: Option<TriMesh>,
}

impl Default for WorldDef {
    fn default() -> Self {
        Self {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            atmosphere: Atmosphere::default(),
            dt: 1.0 / 60.0,
            substeps: 4,
            solve_iterations: 2,
            stabilization_slop: 0.0005,
            stabilization_iterations: 4,
            stabilization_max_iterations: 32,
            stabilization_target: 0.001,
            contact_hertz: 60.0,
            contact_damping_ratio: 10.0,
            max_push_out: 1.0,
            friction: 0.5,
            restitution: 0.4,
            restitution_threshold: 0.1,
            drag_coefficient: 0.95,
            added_mass_coefficient: 0.5,
            angular_damping: 2.0,
            speculative_distance: 0.01,
            enable_sleep: true,
            sleep_linear_speed: 0.005,
            sleep_angular_speed: 0.05,
            time_to_sleep: 0.5,
            enable_continuous: true,
            room: None,
        }
    }
}

#[derive(Debug, Error, PartialEq)]
pub enum PhysicsError {
    #[error("invalid world parameter `{key}` = {value}: expected {expected}")]
    BadParameter {
        key: &'static str,
        value: f32,
        expected: &'static str,
    },
    #[error("invalid balloon shape: {0}")]
    BadShape(String),
    #[error("unknown shape {0}")]
    UnknownShape(u32),
    #[error("body {0:?} does not exist (removed, or from another world)")]
    StaleBody(BodyId),
    #[error("non-finite {what}")]
    NonFinite { what: &'static str },
    #[error("the world is full: at most {0} bodies")]
    Full(usize),
}

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

/// The most bodies a world holds (handles and buffers are sized by u32).
pub const MAX_BODIES: usize = 4_000_000;

/// Buffers rebuilt every step; never part of the state.
#[derive(Clone, Debug, Default)]
struct Scratch {
    node_centers: Vec<Vec3>,
    node_start: Vec<u32>,
    bound_center: Vec<Vec3>,
    bound_radius: Vec<f32>,
    /// Per body: asleep, and its nodes placed since it fell asleep.
    placed_asleep: Vec<bool>,
    /// Per body: how far it moves this step (zero for sleepers).
    motion: Vec<StepMotion>,
    /// Per broadphase pair, in a step whose knocks are found in tasks: the
    /// knocks it gives its bodies (`add_knocks`); empty otherwise.
    thrown: Vec<Option<[Vec3; 2]>>,
    handle: Vec<u32>,
    broad: BroadPhase,
    narrow: NarrowPhase,
    /// The contacts prepared in tasks, before they are gathered into groups.
    #[cfg(feature = "parallel")]
    prepared: Vec<PreparedContact>,
    solver: Solver,
    islands: UnionFind,
    /// Per body, in `update_sleep`: which stay awake, then which fall asleep.
    stays_awake: Vec<bool>,
    /// Which bodies were awake before `wake_touched_bodies`.
    was_awake: Vec<bool>,
    wake: Vec<u32>,
    wake_islands: Vec<u32>,
    /// Continuous sweeps: (body, time of impact, normal) of the bodies that
    /// hit the room, and each task's hits.
    sweep_hits: Vec<(u32, f32, Vec3)>,
    task_hits: Vec<Vec<(u32, f32, Vec3)>>,
    non_finite: Vec<usize>,
    task_faulty: Vec<Vec<usize>>,
}

/// A world of balloons in a room. See the crate docs for conventions.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct World {
    def: WorldDef,
    shapes: Vec<ShapeData>,
    bodies: Bodies,
    handles: HandleMap,
    warm: WarmStartCache,
    sleeping: SleepingIslands,
    grab: Option<Grab>,
    time: f64,
    step_count: u64,
    stats: StepStats,
    /// Reports of bodies taken out as non-finite, not yet collected (events, not state).
    #[serde(skip)]
    quarantined: Vec<QuarantinedBody>,
    #[serde(skip)]
    counters: Counters,
    #[serde(skip)]
    scratch: Scratch,
}

fn check(
    ok: bool,
    key: &'static str,
    value: f32,
    expected: &'static str,
) -> Result<(), PhysicsError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(PhysicsError::BadParameter {
            key,
            value,
            expected,
        })
    }
}

impl WorldDef {
    /// Checks every parameter against its accepted range.
    pub fn validate(&self) -> Result<(), PhysicsError> {
        if !self.gravity.is_finite() {
            return Err(PhysicsError::NonFinite { what: "gravity" });
        }
        let a = &self.atmosphere;
        check(
            a.temperature_k > 0.0,
            "atmosphere.temperature_k",
            a.temperature_k,
            "> 0 K",
        )?;
        check(
            a.pressure_pa > 0.0,
            "atmosphere.pressure_pa",
            a.pressure_pa,
            "> 0 Pa",
        )?;
        check(
            self.dt > 0.0 && self.dt <= 0.1,
            "dt",
            self.dt,
            "0 < dt ≤ 0.1 s",
        )?;
        let substeps = self.substeps as f32;
        check(
            (1..=64).contains(&self.substeps),
            "substeps",
            substeps,
            "1 to 64",
        )?;
        let slop = self.stabilization_slop;
        check(slop >= 0.0, "stabilization_slop", slop, "≥ 0 m")?;
        let passes = self.stabilization_iterations as f32;
        check(
            self.stabilization_iterations <= 32,
            "stabilization_iterations",
            passes,
            "0 to 32",
        )?;
        let most = self.stabilization_max_iterations;
        check(
            (self.stabilization_iterations..=64).contains(&most),
            "stabilization_max_iterations",
            most as f32,
            "stabilization_iterations to 64",
        )?;
        let target = self.stabilization_target;
        check(
            target >= slop,
            "stabilization_target",
            target,
            "≥ stabilization_slop",
        )?;
        let iterations = self.solve_iterations as f32;
        check(
            (1..=32).contains(&self.solve_iterations),
            "solve_iterations",
            iterations,
            "1 to 32",
        )?;
        check(
            self.contact_hertz >= 0.0,
            "contact_hertz",
            self.contact_hertz,
            "≥ 0 Hz",
        )?;
        let zeta = self.contact_damping_ratio;
        check(zeta >= 0.0, "contact_damping_ratio", zeta, "≥ 0")?;
        check(
            self.max_push_out > 0.0,
            "max_push_out",
            self.max_push_out,
            "> 0 m/s",
        )?;
        check(self.friction >= 0.0, "friction", self.friction, "≥ 0")?;
        let e = self.restitution;
        check((0.0..=1.0).contains(&e), "restitution", e, "0 to 1")?;
        let th = self.restitution_threshold;
        check(th >= 0.0, "restitution_threshold", th, "≥ 0 m/s")?;
        let cd = self.drag_coefficient;
        check(cd >= 0.0, "drag_coefficient", cd, "≥ 0")?;
        let ca = self.added_mass_coefficient;
        check(ca >= 0.0, "added_mass_coefficient", ca, "≥ 0")?;
        let ad = self.angular_damping;
        check(ad >= 0.0, "angular_damping", ad, "≥ 0 1/s")?;
        let sd = self.speculative_distance;
        check(sd >= 0.0, "speculative_distance", sd, "≥ 0 m")?;
        let sl = self.sleep_linear_speed;
        check(sl >= 0.0, "sleep_linear_speed", sl, "≥ 0 m/s")?;
        let sa = self.sleep_angular_speed;
        check(sa >= 0.0, "sleep_angular_speed", sa, "≥ 0 rad/s")?;
        let ts = self.time_to_sleep;
        check(ts >= 0.0, "time_to_sleep", ts, "≥ 0 s")?;
        Ok(())
    }
}

impl World {
    pub fn new(def: WorldDef) -> Result<World, PhysicsError> {
        def.validate()?;
        Ok(World {
            def,
            shapes: Vec::new(),
            bodies: Bodies::default(),
            handles: HandleMap::default(),
            warm: WarmStartCache::default(),
            sleeping: SleepingIslands::default(),
            grab: None,
            time: 0.0,
            step_count: 0,
            stats: StepStats::default(),
            quarantined: Vec::new(),
            counters: Counters::default(),
            scratch: Scratch::default(),
        })
    }

    pub fn def(&self) -> &WorldDef {
        &self.def
    }

    /// Registers a kind of balloon; its derived constants use this world's air.
    pub fn add_shape(&mut self, shape: BalloonShape) -> Result<ShapeId, PhysicsError> {
        let bad = |why: &str| Err(PhysicsError::BadShape(why.to_string()));
        if !(shape.mass.is_finite() && shape.mass > 0.0) {
            return bad("mass must be finite and > 0 kg");
        }
        if !(shape.volume.is_finite() && shape.volume >= 0.0) {
            return bad("volume must be finite and ≥ 0 m³");
        }
        if !(shape.reference_area.is_finite() && shape.reference_area >= 0.0) {
            return bad("reference_area must be finite and ≥ 0 m²");
        }
        if !(shape.center_of_mass.is_finite() && shape.center_of_buoyancy.is_finite()) {
            return bad("centre of mass and centre of buoyancy must be finite");
        }
        let inertia = shape.inertia;
        if !inertia.is_finite() || inertia.determinant() <= 0.0 {
            return bad("inertia must be finite and positive definite");
        }
        let air = self.def.atmosphere.air_density();
        let added_mass = added_mass(self.def.added_mass_coefficient, air, shape.volume);
        let tree = shape.tree.translated(-shape.center_of_mass);
        let root = *tree.root();
        let bound_radius = root.center.length() + root.radius;
        let min_leaf_radius = tree
            .leaf_spheres()
            .map(|s| s.radius)
            .fold(f32::INFINITY, f32::min);
        let data = ShapeData {
            inv_mass_translational: 1.0 / (shape.mass + added_mass),
            inv_inertia_local: inertia.inverse(),
            buoyancy_arm: shape.center_of_buoyancy - shape.center_of_mass,
            bound_radius,
            min_leaf_radius,
            added_mass,
            tree,
            def: shape,
        };
        self.shapes.push(data);
        Ok(ShapeId(self.shapes.len() as u32 - 1))
    }

    pub fn shape(&self, id: ShapeId) -> Option<&BalloonShape> {
        self.shapes.get(id.0 as usize).map(|s| &s.def)
    }

    /// Added mass of a shape in this world's air, kg.
    pub fn added_mass(&self, id: ShapeId) -> Option<f32> {
        self.shapes.get(id.0 as usize).map(|s| s.added_mass)
    }

    pub fn add_body(&mut self, def: &BodyDef) -> Result<BodyId, PhysicsError> {
        let shape = self
            .shapes
            .get(def.shape.0 as usize)
            .ok_or(PhysicsError::UnknownShape(def.shape.0))?;
        if !def.pose.position.is_finite() || !def.pose.rotation.is_finite() {
            return Err(PhysicsError::NonFinite { what: "pose" });
        }
        if def.pose.rotation.length_squared() < 1e-6 {
            return Err(PhysicsError::NonFinite {
                what: "rotation (zero quaternion)",
            });
        }
        if !def.linear_velocity.is_finite() || !def.angular_velocity.is_finite() {
            return Err(PhysicsError::NonFinite { what: "velocity" });
        }
        if self.bodies.len() >= MAX_BODIES {
            return Err(PhysicsError::Full(MAX_BODIES));
        }
        let rotation = def.pose.rotation.normalize();
        let center = def.pose.position + rotation * shape.def.center_of_mass;
        let dense = self.bodies.len() as u32;
        let id = self.handles.allocate(dense);
        self.bodies.push(
            id,
            def.shape.0,
            def.user_data,
            center,
            rotation,
            def.linear_velocity,
            def.angular_velocity,
        );
        Ok(id)
    }

    pub fn remove_body(&mut self, id: BodyId) -> Result<(), PhysicsError> {
        let i = self.dense(id)?;
        // Whatever it held up must be free to move.
        self.wake_neighbours_of(i);
        if !self.bodies.awake[i] {
            self.wake_island(self.bodies.island[i]);
        }
        if self.grab.is_some_and(|g| g.body == id) {
            self.grab = None;
        }
        // Dense indices shift: last step's contacts no longer describe this
        // world, nor do the placed nodes of the sleepers.
        self.scratch.narrow.found.clear();
        self.scratch.placed_asleep.clear();
        // Its handle index may be given to a new body: forget its pairs' impulses.
        self.warm.forget(id.index);
        self.sleeping.impulses.forget(id.index);
        let last = self.bodies.len() - 1;
        self.bodies.swap_remove(i);
        self.handles.release(id);
        if i != last {
            let moved = self.bodies.id[i];
            self.handles.set_dense(moved, i as u32);
        }
        Ok(())
    }

    /// Takes out every body whose state is no longer finite or whose motion ran
    /// away, and reports it.
    fn quarantine_non_finite(&mut self) {
        // Runaways found by the solve are already listed.
        let mut bad = std::mem::take(&mut self.scratch.non_finite);
        quarantine::find_faulty(&self.bodies, &mut self.scratch.task_faulty, &mut bad);
        for &i in &bad {
            let (id, user_data) = (self.bodies.id[i], self.bodies.user_data[i]);
            // The body is still registered: removal cannot fail.
            let _ = self.remove_body(id);
            if self.quarantined.len() == MAX_QUARANTINE_REPORTS {
                self.quarantined.remove(0);
            }
            self.quarantined.push(QuarantinedBody {
                id,
                user_data,
                step: self.step_count + 1,
            });
            self.stats.quarantined_count += 1;
        }
        self.scratch.non_finite = bad;
    }

    /// Bodies taken out of the world because their state stopped being finite
    /// since the last call (at most `MAX_QUARANTINE_REPORTS`), oldest first.
    pub fn take_quarantined(&mut self) -> Vec<QuarantinedBody> {
        std::mem::take(&mut self.quarantined)
    }

    fn dense(&self, id: BodyId) -> Result<usize, PhysicsError> {
        self.handles.dense(id).ok_or(PhysicsError::StaleBody(id))
    }

    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Handles in dense order (the order of `write_poses`).
    pub fn body_ids(&self) -> &[BodyId] {
        &self.bodies.id
    }

    pub fn contains(&self, id: BodyId) -> bool {
        self.handles.dense(id).is_some()
    }

    /// Pose of the body frame (the mesh frame).
    pub fn pose(&self, id: BodyId) -> Option<Pose> {
        self.handles.dense(id).map(|i| self.pose_at(i))
    }

    fn pose_at(&self, i: usize) -> Pose {
        let q = self.bodies.rotation[i];
        let com = self.shapes[self.bodies.shape[i] as usize]
            .def
            .center_of_mass;
        Pose::new(self.bodies.center[i] - q * com, q)
    }

    /// All poses, dense order.
    pub fn poses(&self) -> impl Iterator<Item = (BodyId, Pose)> + '_ {
        (0..self.bodies.len()).map(|i| (self.bodies.id[i], self.pose_at(i)))
    }

    /// Writes x, y, z, qx, qy, qz, qw of each body frame, dense order, into
    /// `out` (7 floats per body; extra bodies or room are left untouched).
    pub fn write_poses(&self, out: &mut [f32]) {
        for (i, chunk) in out.chunks_exact_mut(7).take(self.bodies.len()).enumerate() {
            let p = self.pose_at(i);
            chunk.copy_from_slice(&[
                p.position.x,
                p.position.y,
                p.position.z,
                p.rotation.x,
                p.rotation.y,
                p.rotation.z,
                p.rotation.w,
            ]);
        }
    }

    pub fn center_of_mass(&self, id: BodyId) -> Option<Vec3> {
        self.handles.dense(id).map(|i| self.bodies.center[i])
    }

    pub fn linear_velocity(&self, id: BodyId) -> Option<Vec3> {
        self.handles
            .dense(id)
            .map(|i| self.bodies.linear_velocity[i])
    }

    pub fn angular_velocity(&self, id: BodyId) -> Option<Vec3> {
        self.handles
            .dense(id)
            .map(|i| self.bodies.angular_velocity[i])
    }

    pub fn user_data(&self, id: BodyId) -> Option<u32> {
        self.handles.dense(id).map(|i| self.bodies.user_data[i])
    }

    pub fn shape_of(&self, id: BodyId) -> Option<ShapeId> {
        self.handles
            .dense(id)
            .map(|i| ShapeId(self.bodies.shape[i]))
    }

    pub fn is_awake(&self, id: BodyId) -> Option<bool> {
        self.handles.dense(id).map(|i| self.bodies.awake[i])
    }

    /// Mass used for momentum: body mass plus added mass, kg.
    pub fn effective_mass(&self, id: BodyId) -> Option<f32> {
        let i = self.handles.dense(id)?;
        Some(1.0 / self.shapes[self.bodies.shape[i] as usize].inv_mass_translational)
    }

    /// World-frame inertia about the centre of mass, kg·m².
    pub fn world_inertia(&self, id: BodyId) -> Option<glam::Mat3> {
        let i = self.handles.dense(id)?;
        let r = glam::Mat3::from_quat(self.bodies.rotation[i]);
        let local = self.shapes[self.bodies.shape[i] as usize].def.inertia;
        Some(r * local * r.transpose())
    }

    pub fn wake(&mut self, id: BodyId) -> Result<(), PhysicsError> {
        let i = self.dense(id)?;
        if !self.bodies.awake[i] {
            self.wake_island(self.bodies.island[i]);
        }
        self.bodies.sleep_time[i] = 0.0;
        Ok(())
    }

    pub fn set_velocity(
        &mut self,
        id: BodyId,
        linear: Vec3,
        angular: Vec3,
    ) -> Result<(), PhysicsError> {
        if !linear.is_finite() || !angular.is_finite() {
            return Err(PhysicsError::NonFinite { what: "velocity" });
        }
        self.wake(id)?;
        let i = self.dense(id)?;
        self.bodies.linear_velocity[i] = linear;
        self.bodies.angular_velocity[i] = angular;
        Ok(())
    }

    /// An instantaneous impulse (N·s) at a world point; wakes the body.
    pub fn apply_impulse_at_point(
        &mut self,
        id: BodyId,
        impulse: Vec3,
        point: Vec3,
    ) -> Result<(), PhysicsError> {
        if !impulse.is_finite() || !point.is_finite() {
            return Err(PhysicsError::NonFinite { what: "impulse" });
        }
        self.wake(id)?;
        let i = self.dense(id)?;
        let shape = &self.shapes[self.bodies.shape[i] as usize];
        let r = point - self.bodies.center[i];
        let inv_inertia = world_inverse_inertia(self.bodies.rotation[i], shape.inv_inertia_local);
        self.bodies.linear_velocity[i] += shape.inv_mass_translational * impulse;
        self.bodies.angular_velocity[i] += inv_inertia * r.cross(impulse);
        Ok(())
    }

    /// A force (N) at a world point, held for the next step only; wakes the body.
    pub fn apply_force_at_point(
        &mut self,
        id: BodyId,
        force: Vec3,
        point: Vec3,
    ) -> Result<(), PhysicsError> {
        if !force.is_finite() || !point.is_finite() {
            return Err(PhysicsError::NonFinite { what: "force" });
        }
        self.wake(id)?;
        let i = self.dense(id)?;
        self.bodies.force[i] += force;
        self.bodies.torque[i] += (point - self.bodies.center[i]).cross(force);
        Ok(())
    }

    /// Starts dragging the body by a world point (the mouse); see `set_grab_target`.
    pub fn grab(&mut self, id: BodyId, point: Vec3) -> Result<(), PhysicsError> {
        if !point.is_finite() {
            return Err(PhysicsError::NonFinite { what: "grab point" });
        }
        self.wake(id)?;
        let i = self.dense(id)?;
        let anchor = self.bodies.rotation[i].inverse() * (point - self.bodies.center[i]);
        self.grab = Some(Grab {
            body: id,
            anchor,
            target: point,
        });
        Ok(())
    }

    /// Moves the point the grabbed body is pulled toward, m.
    pub fn set_grab_target(&mut self, target: Vec3) -> Result<(), PhysicsError> {
        if !target.is_finite() {
            return Err(PhysicsError::NonFinite {
                what: "grab target",
            });
        }
        if let Some(g) = &mut self.grab {
            g.target = target;
        }
        Ok(())
    }

    /// Lets go; the body keeps its velocity (a throw). Returns the body that was held.
    pub fn release_grab(&mut self) -> Option<BodyId> {
        self.grab.take().map(|g| g.body)
    }

    pub fn grabbed(&self) -> Option<BodyId> {
        self.grab.map(|g| g.body)
    }

    /// Simulated seconds since the world was made.
    pub fn time(&self) -> f64 {
        self.time
    }

    pub fn step_count(&self) -> u64 {
        self.step_count
    }

    pub fn stats(&self) -> &StepStats {
        &self.stats
    }

    pub fn counters(&self) -> &Counters {
        &self.counters
    }

    pub fn room(&self) -> Option<&TriMesh> {
        self.def.room.as_ref()
    }

    /// ½·m_eff·v² + ½·ωᵀ·I·ω summed over all bodies, J (added mass included: the air moves too).
    pub fn kinetic_energy(&self) -> f32 {
        (0..self.bodies.len())
            .map(|i| {
                let shape = &self.shapes[self.bodies.shape[i] as usize];
                let v = self.bodies.linear_velocity[i];
                let w = self.bodies.angular_velocity[i];
                let r = glam::Mat3::from_quat(self.bodies.rotation[i]);
                let inertia = r * shape.def.inertia * r.transpose();
                0.5 * v.length_squared() / shape.inv_mass_translational + 0.5 * w.dot(inertia * w)
            })
            .sum()
    }

    /// A fresh narrowphase over the current state: the deepest overlap now, m.
    pub fn max_penetration_now(&mut self) -> f32 {
        self.place_bodies(true);
        self.find_contacts(true);
        self.scratch.narrow.found.max_penetration
    }

    /// FNV-1a over every body's handle, pose, velocity and sleep state, in dense order.
    pub fn state_hash(&self) -> u64 {
        let mut h = Fnv1a::new();
        h.write_u32(self.bodies.len() as u32);
        h.write_bytes(&self.step_count.to_le_bytes());
        for i in 0..self.bodies.len() {
            let b = &self.bodies;
            h.write_u32(b.id[i].index);
            h.write_u32(b.id[i].generation);
            for v in [b.center[i], b.linear_velocity[i], b.angular_velocity[i]] {
                h.write_f32(v.x);
                h.write_f32(v.y);
                h.write_f32(v.z);
            }
            let q = b.rotation[i];
            for x in [q.x, q.y, q.z, q.w, b.sleep_time[i]] {
                h.write_f32(x);
            }
            h.write_u32(b.awake[i] as u32);
        }
        h.finish()
    }

    /// The whole world as bytes; `World::restore` gives it back exactly.
    pub fn snapshot(&self) -> Vec<u8> {
        snapshot::encode(self)
    }

    pub fn restore(bytes: &[u8]) -> Result<World, SnapshotError> {
        let mut world: World = snapshot::decode(bytes)?;
        world
            .def
            .validate()
            .map_err(|e| SnapshotError::Invalid(e.to_string()))?;
        world.check_consistency().map_err(SnapshotError::Invalid)?;
        world.warm.index();
        world.sleeping.impulses.index();
        Ok(world)
    }

    fn check_consistency(&self) -> Result<(), String> {
        let n = self.bodies.len();
        let b = &self.bodies;
        let lens = [
            b.shape.len(),
            b.user_data.len(),
            b.center.len(),
            b.rotation.len(),
            b.linear_velocity.len(),
            b.angular_velocity.len(),
            b.force.len(),
            b.torque.len(),
            b.sleep_time.len(),
            b.awake.len(),
            b.island.len(),
        ];
        if lens.iter().any(|&l| l != n) {
            return Err("body arrays of different lengths".into());
        }
        for i in 0..n {
            if b.shape[i] as usize >= self.shapes.len() {
                return Err(format!("body {i} has unknown shape {}", b.shape[i]));
            }
            if self.handles.dense(b.id[i]) != Some(i) {
                return Err(format!("body {i}: handle table does not point back"));
            }
            if !b.awake[i] && self.sleeping.members.get(b.island[i] as usize).is_none() {
                return Err(format!("body {i} sleeps in a missing island"));
            }
        }
        for (island, members) in self.sleeping.members.iter().enumerate() {
            for &id in members {
                let Some(i) = self.handles.dense(id) else {
                    return Err(format!("island {island} holds a removed body"));
                };
                if b.awake[i] || b.island[i] as usize != island {
                    return Err(format!("island {island} disagrees with body {i}"));
                }
            }
        }
        Ok(())
    }
}

/// Whether the root spheres of bodies `a` and `b`, placed at `centers`, are
/// within `gap` of touching.
fn roots_within(
    shapes: &[ShapeData],
    shape: &[u32],
    centers: &[Vec3],
    a: usize,
    b: usize,
    gap: f32,
) -> bool {
    let root = |i: usize| shapes[shape[i] as usize].tree.root().radius;
    distance(centers[a], centers[b]) < root(a) + root(b) + gap
}

/// A fast body's core, swept against the room: this share of each leaf's radius.
const CORE_FRACTION: f32 = 0.5;
/// Bodies that moved more than this share of their smallest leaf radius in a step are swept.
const FAST_FRACTION: f32 = 0.25;

impl World {
    /// Advances the world by `def.dt` seconds.
    pub fn step(&mut self) {
        // Called from outside rayon's pool, the whole step moves onto one of
        // its threads: otherwise every parallel pass (hundreds a step) would
        // hand its work across threads and put this one to sleep until done.
        #[cfg(feature = "parallel")]
        if rayon::current_thread_index().is_none() {
            return rayon::scope(|_| self.step_here());
        }
        self.step_here()
    }

    /// `step`, on the calling thread.
    fn step_here(&mut self) {
        let mut clock = Stopwatch::start();
        let mut counters = Counters::default();

        self.place_bodies(false);
        self.find_pairs();
        if self.wake_touched_bodies() {
            // Woken bodies sleep where they were placed, with a sleeper's
            // margin (no velocity): only their pairs with other sleepers are new.
            let s = &mut self.scratch;
            if !s.broad.add_woken_pairs(
                &s.bound_center,
                &s.bound_radius,
                &s.was_awake,
                &self.bodies.awake,
            ) {
                self.place_bodies(false);
                self.find_pairs();
            }
        }
        self.add_knocks();
        counters.broadphase_ms = clock.lap();

        self.find_contacts(false);
        counters.narrowphase_ms = clock.lap();

        let grab = self.prepare_solver();
        counters.prepare_ms = clock.lap();

        let params = SolveParams {
            dt: self.def.dt,
            substeps: self.def.substeps,
            iterations: self.def.solve_iterations,
            contact_hertz: self.def.contact_hertz,
            contact_damping_ratio: self.def.contact_damping_ratio,
            max_push_out: self.def.max_push_out,
            friction: self.def.friction,
            angular_damping: self.def.angular_damping,
        };
        self.scratch.solver.solve(&params, grab.as_ref());
        counters.solve_ms = clock.lap();

        self.scratch
            .solver
            .restitution(self.def.restitution, self.def.restitution_threshold);
        self.store_impulses();
        let mut min_passes = self.def.stabilization_iterations;
        // An impact (a contact that closed faster than the speculative
        // distance a step, and pushed) crushes balloons between others: twice
        // the passes then. Bodies that are merely fast (rising side by side,
        // or drifting free) do not count.
        let impact_speed = self.def.speculative_distance / self.def.dt;
        if self.scratch.solver.any_impact(impact_speed) {
            min_passes *= 2;
        }
        self.stats.position_passes = self.scratch.solver.stabilize(&Stabilization {
            slop: self.def.stabilization_slop,
            target: self.def.stabilization_target,
            min_passes,
            max_passes: self.def.stabilization_max_iterations,
        });
        self.finish_motion();
        counters.restitution_ms = clock.lap();

        if self.def.enable_continuous {
            self.sweep_fast_bodies();
        }
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

    /// Gives back the capacity that the buffers sized by the contacts did
    /// not use this step, once it is four times the use (`spare`): a pile
    /// asleep after a stir holds what it held asleep before.
    fn release_spare(&mut self) {
        let s = &mut self.scratch;
        s.broad.release_spare();
        s.narrow.release_spare();
        #[cfg(feature = "parallel")]
        crate::spare::release_spare(&mut s.prepared, crate::spare::BUFFER_FLOOR);
        crate::spare::release_spare(&mut s.thrown, crate::spare::BUFFER_FLOOR);
        crate::spare::release_spare_each(&mut s.task_faulty);
        s.solver.release_spare();
        self.warm.release_spare();
        self.sleeping.release_spare();
    }

    /// World centres of every node of every body, bounding spheres and speculative margins.
    fn place_bodies(&mut self, at_rest: bool) {
        let n = self.bodies.len();
        let s = &mut self.scratch;
        s.node_start.clear();
        let mut total = 0u32;
        for i in 0..n {
            s.node_start.push(total);
            total += self.shapes[self.bodies.shape[i] as usize]
                .tree
                .nodes()
                .len() as u32;
        }
        // Every body's entries are written below (a sleeper's nodes stay
        // where they were placed): only the lengths matter here.
        s.node_centers.resize(total as usize, Vec3::ZERO);
        s.placed_asleep.resize(n, false);
        s.motion.resize(n, StepMotion::default());
        s.bound_center.resize(n, Vec3::ZERO);
        s.bound_radius.resize(n, 0.0);
        s.handle.resize(n, 0);
        let (bodies, shapes, dt) = (&self.bodies, &self.shapes, self.def.dt);
        let speculative_distance = self.def.speculative_distance;
        let parts = (
            Ragged::new(&mut s.node_centers, &s.node_start),
            &mut s.placed_asleep[..],
            &mut s.motion[..],
            &mut s.bound_center[..],
            &mut s.bound_radius[..],
            &mut s.handle[..],
        );
        for_each_run(n, PLACE_CHUNK, parts, |first, run| {
            let (mut nodes, placed_asleep, motions, bound_center, bound_radius, handle) = run;
            for k in 0..placed_asleep.len() {
                let i = first + k;
                let shape = &shapes[bodies.shape[i] as usize];
                let nodes = nodes.item(k);
                // A sleeper does not move: placed once, its nodes stay where they are.
                let asleep = !bodies.awake[i];
                if !(asleep && placed_asleep[k]) {
                    let pose = Pose::new(bodies.center[i], bodies.rotation[i]);
                    shape.tree.place(&pose, nodes);
                }
                placed_asleep[k] = asleep;
                let motion = if at_rest || asleep {
                    StepMotion::default()
                } else {
                    let rate = bodies.angular_velocity[i].norm();
                    StepMotion {
                        linear: bodies.linear_velocity[i] * dt,
                        spin: rate * shape.bound_radius * dt,
                        turn: rate * dt,
                        ..StepMotion::default()
                    }
                };
                // Wide enough for every pair the narrowphase may find a contact in.
                let margin = speculative_distance + motion.reach();
                motions[k] = motion;
                bound_center[k] = nodes[0];
                bound_radius[k] = shape.tree.root().radius + margin;
                handle[k] = bodies.id[i].index;
            }
        });
    }

    /// Each body's knock, from the broadphase's pairs (`narrow_phase::add_knocks`).
    fn add_knocks(&mut self) {
        let s = &mut self.scratch;
        let (shapes, shape) = (&self.shapes, &self.bodies.shape);
        let centers = &s.bound_center;
        let within = |a, b, gap| roots_within(shapes, shape, centers, a, b, gap);
        let inv_mass = |i: usize| shapes[shape[i] as usize].inv_mass_translational;
        let bounce = 1.0 + self.def.restitution;
        let share = |a: usize, b: usize| bounce * inv_mass(a) / (inv_mass(a) + inv_mass(b));
        add_knocks(
            &mut s.motion,
            &s.broad.pairs,
            &mut s.thrown,
            |i| centers[i],
            within,
            share,
            self.def.speculative_distance,
        );
        // Once a body, not in each of its pairs: the turn its knock may give.
        fill_chunks(&mut s.motion, PLACE_CHUNK, |first, motions| {
            for (k, m) in motions.iter_mut().enumerate() {
                m.knock_turn = if m.knock == Vec3::ZERO {
                    0.0
                } else {
                    m.knock.norm() * shapes[shape[first + k] as usize].turn_per_knock()
                };
            }
        });
    }

    /// Cell radius: the largest root sphere plus its margin at a brisk ascent.
    fn cell_radius(&self) -> f32 {
        let largest = self
            .shapes
            .iter()
            .map(|s| s.tree.root().radius)
            .fold(0.0, f32::max);
        largest + self.def.speculative_distance + 3.0 * self.def.dt
    }

    fn find_pairs(&mut self) {
        let cell_radius = self.cell_radius();
        let s = &mut self.scratch;
        s.broad.update(
            &s.bound_center,
            &s.bound_radius,
            &self.bodies.awake,
            cell_radius,
        );
    }

    /// Wakes what a restless body's root sphere reaches. A body whose surface
    /// moves faster than the restitution threshold is an impact, whose push
    /// must travel through the pile at once: it wakes the whole island of
    /// every body it can reach this step, as a user action does. A slower one
    /// wakes only the bodies it touches, and they keep their rest time, so
    /// they fall asleep again as soon as nothing restless reaches them (see
    /// `update_sleep`): a sleeping body is static to its awake neighbours,
    /// and a slow shuffle in a big pile wakes only what it moves.
    fn wake_touched_bodies(&mut self) -> bool {
        self.scratch.was_awake.clone_from(&self.bodies.awake);
        let mut woken = std::mem::take(&mut self.scratch.wake);
        woken.clear();
        let mut islands = std::mem::take(&mut self.scratch.wake_islands);
        islands.clear();
        // A surface point at the speed from which contacts bounce: anything
        // slower is a shuffle, which a sleeping neighbour may take standing.
        let impact_motion = self.def.restitution_threshold * self.def.dt;
        for &(a, b) in &self.scratch.broad.pairs {
            let (a, b) = (a as usize, b as usize);
            if self.bodies.awake[a] == self.bodies.awake[b] {
                continue;
            }
            let (awake, asleep) = if self.bodies.awake[a] { (a, b) } else { (b, a) };
            if self.bodies.sleep_time[awake] >= self.def.time_to_sleep {
                continue;
            }
            let motion = self.scratch.motion[awake].reach();
            let impact = motion > impact_motion;
            // A slow body wakes what it touches (root spheres overlap); an
            // impact whatever it can reach this step, which would otherwise
            // stand still for a step as it is struck.
            let reach = if impact {
                self.def.speculative_distance + motion
            } else {
                0.0
            };
            let centers = &self.scratch.bound_center;
            if !roots_within(
                &self.shapes,
                &self.bodies.shape,
                centers,
                awake,
                asleep,
                reach,
            ) {
                continue;
            }
            if impact {
                islands.push(self.bodies.island[asleep]);
            } else {
                woken.push(asleep as u32);
            }
        }
        islands.sort_unstable();
        islands.dedup();
        for &island in &islands {
            self.wake_island(island);
        }
        // Bodies of islands woken whole are awake already.
        woken.retain(|&i| !self.bodies.awake[i as usize]);
        // Awake first; then each island they left keeps only its sleepers.
        for &i in &woken {
            self.bodies.awake[i as usize] = true;
        }
        for w in woken.iter_mut() {
            let i = *w as usize;
            *w = std::mem::replace(&mut self.bodies.island[i], u32::MAX);
        }
        woken.sort_unstable();
        woken.dedup();
        for &island in &woken {
            let (handles, awake) = (&self.handles, &self.bodies.awake);
            self.sleeping
                .retain_members(island, |id| handles.dense(id).is_some_and(|i| !awake[i]));
        }
        let any = !woken.is_empty() || !islands.is_empty();
        self.scratch.wake = woken;
        self.scratch.wake_islands = islands;
        any
    }

    fn wake_island(&mut self, island: u32) {
        if island == u32::MAX || island as usize >= self.sleeping.members.len() {
            return;
        }
        for id in self.sleeping.take(island) {
            if let Some(i) = self.handles.dense(id) {
                self.bodies.awake[i] = true;
                self.bodies.island[i] = u32::MAX;
                self.bodies.sleep_time[i] = 0.0;
            }
        }
    }

    /// Wakes the sleeping bodies whose bounding spheres touch body `i`'s.
    fn wake_neighbours_of(&mut self, i: usize) {
        let ri = self.shapes[self.bodies.shape[i] as usize].bound_radius;
        let ci = self.bodies.center[i];
        let reach = ri + self.def.speculative_distance;
        let mut islands = std::mem::take(&mut self.scratch.wake);
        islands.clear();
        for j in 0..self.bodies.len() {
            if j == i || self.bodies.awake[j] {
                continue;
            }
            let rj = self.shapes[self.bodies.shape[j] as usize].bound_radius;
            if distance(self.bodies.center[j], ci) <= reach + rj {
                islands.push(self.bodies.island[j]);
            }
        }
        for &island in &islands {
            self.wake_island(island);
        }
        self.scratch.wake = islands;
    }

    fn find_contacts(&mut self, all: bool) {
        let cell_radius = self.cell_radius();
        let s = &mut self.scratch;
        if all {
            // Every pair, awake or not (a measurement, not a step).
            let every = vec![true; self.bodies.len()];
            s.broad
                .update(&s.bound_center, &s.bound_radius, &every, cell_radius);
            let input = NarrowInput {
                shapes: &self.shapes,
                shape: &self.bodies.shape,
                node_centers: &s.node_centers,
                node_start: &s.node_start,
                handle: &s.handle,
                awake: &every,
                motion: &s.motion,
                speculative_distance: self.def.speculative_distance,
            };
            s.narrow
                .update(&input, &s.broad.pairs, self.def.room.as_ref());
            return;
        }
        let input = NarrowInput {
            shapes: &self.shapes,
            shape: &self.bodies.shape,
            node_centers: &s.node_centers,
            node_start: &s.node_start,
            handle: &s.handle,
            awake: &self.bodies.awake,
            motion: &s.motion,
            speculative_distance: self.def.speculative_distance,
        };
        s.narrow
            .update(&input, &s.broad.pairs, self.def.room.as_ref());
        self.stats = StepStats {
            max_penetration: s.narrow.found.max_penetration,
            pair_count: s.broad.pairs.len() as u32,
            contact_count: s.narrow.found.contacts.len() as u32,
            awake_count: self.bodies.awake.iter().filter(|&&a| a).count() as u32,
            quarantined_count: self.stats.quarantined_count,
            position_passes: 0,
        };
    }

    /// Body states, forces and contact constraints for this step's solve.
    fn prepare_solver(&mut self) -> Option<GrabSpring> {
        let n = self.bodies.len();
        let air = self.def.atmosphere.air_density();
        let g = self.def.gravity;
        let solver = &mut self.scratch.solver;
        solver.awake.clear();
        solver
            .awake
            .extend((0..n as u32).filter(|&i| self.bodies.awake[i as usize]));
        // Every body's entries are written below: only the lengths matter here.
        solver.states.resize(n, BodyState::STATIC);
        solver.forces.resize(n, BodyForces::default());
        let (bodies, shapes) = (&self.bodies, &self.shapes);
        let drag_coefficient = self.def.drag_coefficient;
        let parts = (&mut solver.states[..n], &mut solver.forces[..n]);
        for_each_run(n, PLACE_CHUNK, parts, |first, (states, forces)| {
            for (k, (state, forces)) in states.iter_mut().zip(forces).enumerate() {
                let i = first + k;
                let q = bodies.rotation[i];
                if !bodies.awake[i] {
                    *state = BodyState {
                        q,
                        ..BodyState::STATIC
                    };
                    *forces = BodyForces::default();
                    continue;
                }
                let shape = &shapes[bodies.shape[i] as usize];
                *state = BodyState {
                    v: bodies.linear_velocity[i],
                    w: bodies.angular_velocity[i],
                    dp: Vec3::ZERO,
                    dq: Quat::IDENTITY,
                    q,
                    inv_mass: shape.inv_mass_translational,
                    inv_inertia: world_inverse_inertia(q, shape.inv_inertia_local),
                    runaway: false,
                };
                let buoyancy = buoyancy_force(air, shape.def.volume, g);
                *forces = BodyForces {
                    force: gravity_force(shape.def.mass, g) + buoyancy + bodies.force[i],
                    buoyancy,
                    buoyancy_arm: shape.buoyancy_arm,
                    torque: bodies.torque[i],
                    drag_factor: drag_factor(air, drag_coefficient, shape.def.reference_area),
                };
            }
        });
        // The room: one static state after the bodies.
        solver.states.push(BodyState::STATIC);
        self.prepare_contacts(n as u32);

        let grab = self.grab?;
        let i = self.handles.dense(grab.body)?;
        if !self.bodies.awake[i] {
            return None;
        }
        let shape = &self.shapes[self.bodies.shape[i] as usize];
        let mass = 1.0 / shape.inv_mass_translational;
        let omega = 2.0 * std::f32::consts::PI * GRAB_HERTZ;
        Some(GrabSpring {
            state: i as u32,
            anchor: self.bodies.rotation[i] * grab.anchor,
            center0: self.bodies.center[i],
            target: grab.target,
            stiffness: mass * omega * omega,
            damping: 2.0 * mass * GRAB_DAMPING_RATIO * omega,
            max_force: GRAB_MAX_WEIGHTS * shape.def.mass * g.length(),
        })
    }

    /// The contact constraints, each warm-started from its impulse last
    /// step; the room is solver state `room_state`. With several threads the
    /// contacts are prepared in tasks (in the narrowphase's order, one lookup
    /// a pair), then gathered into their groups in tasks; on one, each goes
    /// straight to its slot.
    fn prepare_contacts(&mut self, room_state: u32) {
        let found = &self.scratch.narrow.found;
        let state_of = |body: u32| {
            if body == STATIC_BODY {
                room_state
            } else {
                body
            }
        };
        // A pair with a sleeper just woken resumes from its impulses when it fell asleep.
        let resume = ResumeFrom {
            fresh: &self.warm,
            kept: &self.sleeping.impulses,
        };
        let (nodes, node_start) = (&self.scratch.node_centers, &self.scratch.node_start);
        let center = &self.bodies.center;
        let prepare = |i: usize, previous: &[StoredImpulse]| {
            let c = &found.contacts[i];
            let (a, b) = (c.body_a, state_of(c.body_b));
            let (leaf_a, leaf_b) = ((c.feature >> 32) as usize, (c.feature as u32) as usize);
            let sphere_a = nodes[node_start[a as usize] as usize + leaf_a];
            let (center_b, sphere_b) = if c.body_b == STATIC_BODY {
                (c.point_b, c.point_b)
            } else {
                (
                    center[b as usize],
                    nodes[node_start[b as usize] as usize + leaf_b],
                )
            };
            contact_constraint::prepare(
                c,
                (a, b),
                (center[a as usize], center_b),
                (sphere_a, sphere_b),
                previous,
            )
        };
        let pairs = found
            .contacts
            .iter()
            .map(|c| (c.body_a, state_of(c.body_b)));
        let (count, solver) = (found.contacts.len(), &mut self.scratch.solver);
        #[cfg(feature = "parallel")]
        if worth_splitting(count, PREPARE_CHUNK) {
            let prepared = &mut self.scratch.prepared;
            prepared.resize(count, PreparedContact::default());
            fill_chunks(prepared, PREPARE_CHUNK, |first, out| {
                resume.each(&found.runs, first..first + out.len(), |i, previous| {
                    out[i - first] = prepare(i, previous);
                });
            });
            solver.set_constraints(pairs, prepared);
            return;
        }
        // Unused this step: its length must say so (`spare`).
        #[cfg(feature = "parallel")]
        self.scratch.prepared.clear();
        // The runs cover the contacts in order: coloured in the order prepared below.
        solver.begin_constraints(pairs);
        resume.each(&found.runs, 0..count, |i, previous| {
            solver.set_constraint(i, &prepare(i, previous));
        });
    }

    fn store_impulses(&mut self) {
        // One impulse per contact, in order: the runs stay as they are.
        let found = &self.scratch.narrow.found;
        self.warm.runs.clone_from(&found.runs);
        self.warm
            .impulses
            .resize(found.contacts.len(), StoredImpulse::default());
        self.scratch.solver.store_all(&mut self.warm.impulses);
        self.warm.index();
    }

    /// Copies the solver's results back to the bodies; clears held forces.
    fn finish_motion(&mut self) {
        let solver = &self.scratch.solver;
        // Left where the step found them; quarantined at the step's end.
        self.scratch.non_finite.clear();
        self.scratch.non_finite.extend(
            solver
                .awake
                .iter()
                .map(|&i| i as usize)
                .filter(|&i| solver.states[i].runaway),
        );
        let b = &mut self.bodies;
        let (n, shapes, shape, awake) = (b.len(), &self.shapes, &b.shape, &b.awake);
        let parts = (
            &mut b.center[..],
            &mut b.rotation[..],
            &mut b.linear_velocity[..],
            &mut b.angular_velocity[..],
            &mut b.force[..],
            &mut b.torque[..],
        );
        for_each_run(n, PLACE_CHUNK, parts, |first, run| {
            let (center, rotation, linear_velocity, angular_velocity, force, torque) = run;
            for k in 0..center.len() {
                let i = first + k;
                force[k] = Vec3::ZERO;
                torque[k] = Vec3::ZERO;
                let s = &solver.states[i];
                if !awake[i] || s.runaway {
                    continue;
                }
                center[k] += s.dp;
                rotation[k] = s.q;
                linear_velocity[k] = s.v;
                // Keep angular momentum L = I·ω across the rotation (the gyroscopic
                // effect): the solve used the inertia at the step's start.
                let momentum = s.inv_inertia.inverse() * s.w;
                let inv_inertia_local = shapes[shape[i] as usize].inv_inertia_local;
                let w = world_inverse_inertia(s.q, inv_inertia_local) * momentum;
                angular_velocity[k] = if w.is_finite() { w } else { s.w };
            }
        });
    }

    /// Continuous collision against the room: a body that moved far this step
    /// has the core of each leaf swept along its path; on a hit it is moved
    /// back to the time of impact and loses its velocity into the wall.
    fn sweep_fast_bodies(&mut self) {
        let Some(room) = self.def.room.as_ref() else {
            return;
        };
        let solver = &self.scratch.solver;
        let (bodies, shapes, dt) = (&self.bodies, &self.shapes, self.def.dt);
        // The sweeps (read-only, in tasks of awake bodies), then their hits.
        let mut hits = std::mem::take(&mut self.scratch.sweep_hits);
        hits.clear();
        collect_in_order(
            solver.awake.len(),
            SWEEP_CHUNK,
            &mut self.scratch.task_hits,
            &mut hits,
            |range, hits| {
                for &i in &solver.awake[range] {
                    let i = i as usize;
                    let s = &solver.states[i];
                    let shape = &shapes[bodies.shape[i] as usize];
                    let moved = s.dp.norm() + s.w.norm() * shape.bound_radius * dt;
                    if moved <= FAST_FRACTION * shape.min_leaf_radius {
                        continue;
                    }
                    let end = bodies.center[i];
                    let begin = end - s.dp;
                    // Most fast bodies rise through open air, or below a
                    // ceiling they do not reach this step: one look for any
                    // triangle that a sphere holding all their cores' paths
                    // may hit spares a sweep of each core. A core stays
                    // within its offset from the centre, whatever the turn,
                    // and the centre within half its path from the middle.
                    let core_reach = shape
                        .tree
                        .leaf_spheres()
                        .map(|leaf| leaf.center.norm() + leaf.radius * CORE_FRACTION)
                        .fold(0.0, f32::max);
                    let bound = Sphere::new(begin + 0.5 * s.dp, 0.5 * s.dp.norm() + core_reach);
                    if !sweep_may_hit(bound, room) {
                        continue;
                    }
                    let q0 = s.start_rotation();
                    let mut earliest: Option<(f32, Vec3)> = None;
                    for leaf in shape.tree.leaf_spheres() {
                        let from = begin + q0 * leaf.center;
                        let to = end + s.q * leaf.center;
                        let core = Sphere::new(from, leaf.radius * CORE_FRACTION);
                        // Triangles the core is in already are the solver's to push
                        // out of: stopping at them would freeze the body in place,
                        // step after step.
                        if let Some((t, _, normal)) =
                            toi_sphere_trimesh_new_contact(core, to - from, room)
                        {
                            if earliest.is_none_or(|(te, _)| t < te) {
                                earliest = Some((t, normal));
                            }
                        }
                    }
                    if let Some((t, normal)) = earliest {
                        hits.push((i as u32, t, normal));
                    }
                }
            },
        );
        for &(i, t, normal) in &hits {
            let (i, s) = (i as usize, &solver.states[i as usize]);
            let begin = self.bodies.center[i] - s.dp;
            let q0 = s.start_rotation();
            self.bodies.center[i] = begin + t * s.dp;
            self.bodies.rotation[i] = q0.lerp(s.q, t).unit();
            let v = self.bodies.linear_velocity[i];
            let into = v.dot(normal);
            if into > 0.0 {
                self.bodies.linear_velocity[i] = v - (1.0 + self.def.restitution) * into * normal;
            }
        }
        self.scratch.sweep_hits = hits;
    }

    /// Sleep timers, then the rested bodies that fall asleep.
    ///
    /// A body is rested once it has been slow for `time_to_sleep`. Rested
    /// bodies sleep in groups of touching ones, except those a restless body
    /// reaches (root spheres within the speculative distance): they stay
    /// awake as the buffer through which a restless body pushes, and would be
    /// woken at once by the next step's wake test anyway. So a big pile in
    /// which a few balloons still shuffle sleeps everywhere else, where
    /// whole-island sleep would keep all of it awake.
    fn update_sleep(&mut self) {
        let n = self.bodies.len();
        let dt = self.def.dt;
        let grabbed = self.grab.and_then(|g| self.handles.dense(g.body));
        let b = &mut self.bodies;
        let (awake, linear_velocity, angular_velocity) =
            (&b.awake, &b.linear_velocity, &b.angular_velocity);
        let (linear_speed, angular_speed) =
            (self.def.sleep_linear_speed, self.def.sleep_angular_speed);
        fill_chunks(&mut b.sleep_time, PLACE_CHUNK, |first, times| {
            for (k, time) in times.iter_mut().enumerate() {
                let i = first + k;
                if !awake[i] {
                    continue;
                }
                let slow = linear_velocity[i].norm() < linear_speed
                    && angular_velocity[i].norm() < angular_speed;
                if slow && grabbed != Some(i) {
                    *time += dt;
                } else {
                    *time = 0.0;
                }
            }
        });
        if !self.def.enable_sleep {
            return;
        }
        let time_to_sleep = self.def.time_to_sleep;
        let s = &mut self.scratch;
        let awake = &self.bodies.awake;
        let sleep_time = &self.bodies.sleep_time;
        let restless = |i: usize| awake[i] && sleep_time[i] < time_to_sleep;
        let mut stays = std::mem::take(&mut s.stays_awake);
        stays.clear();
        stays.extend((0..n).map(restless));
        for &(a, b) in &s.broad.pairs {
            let (a, b) = (a as usize, b as usize);
            if restless(a) == restless(b) || !awake[a] || !awake[b] {
                continue;
            }
            if roots_within(
                &self.shapes,
                &self.bodies.shape,
                &s.bound_center,
                a,
                b,
                self.def.speculative_distance,
            ) {
                stays[a] = true;
                stays[b] = true;
            }
        }
        // From here `stays` means "falls asleep now".
        for i in 0..n {
            stays[i] = self.bodies.awake[i] && !stays[i];
        }
        let falls_asleep = stays;
        s.islands.reset(n);
        for c in &s.narrow.found.contacts {
            let (a, b) = (c.body_a as usize, c.body_b as usize);
            if c.body_b != STATIC_BODY
                && c.separation < self.def.speculative_distance
                && falls_asleep[a]
                && falls_asleep[b]
            {
                s.islands.union(c.body_a, c.body_b);
            }
        }
        // One pass: each group's root gets an island, each member joins its root's.
        let mut island_of_root = std::mem::take(&mut s.handle);
        island_of_root.clear();
        island_of_root.resize(n, u32::MAX);
        for i in 0..n {
            if !falls_asleep[i] {
                continue;
            }
            let root = s.islands.find(i as u32) as usize;
            if island_of_root[root] == u32::MAX {
                island_of_root[root] = self.sleeping.add(Vec::new());
            }
            let island = island_of_root[root];
            self.sleeping.members[island as usize].push(self.bodies.id[i]);
            self.bodies.island[i] = island;
            self.bodies.awake[i] = false;
            self.bodies.linear_velocity[i] = Vec3::ZERO;
            self.bodies.angular_velocity[i] = Vec3::ZERO;
        }
        s.handle = island_of_root;
        let (handles, awake) = (&self.handles, &self.bodies.awake);
        // The room (`STATIC_BODY`) has no dense index: asleep, never fallen asleep.
        self.sleeping.keep_impulses(
            &self.warm,
            |handle| handle == STATIC_BODY || handles.dense_at(handle).is_some_and(|i| !awake[i]),
            |handle| handles.dense_at(handle).is_some_and(|i| falls_asleep[i]),
        );
        s.stays_awake = falls_asleep;
    }
}

/// A contact point found by the last step (for debug views and tests).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactInfo {
    pub body_a: BodyId,
    /// `None` for the room.
    pub body_b: Option<BodyId>,
    /// Midpoint of the two surface points, world frame, m.
    pub point: Vec3,
    /// Unit, from A to B.
    pub normal: Vec3,
    /// Negative when overlapping, m.
    pub separation: f32,
}

impl World {
    /// The contact points of the last step (empty after a body was removed since).
    pub fn contact_points(&self) -> impl Iterator<Item = ContactInfo> + '_ {
        let n = self.bodies.len();
        let contacts = &self.scratch.narrow.found.contacts;
        let valid = contacts.iter().all(|c| {
            (c.body_a as usize) < n && (c.body_b == STATIC_BODY || (c.body_b as usize) < n)
        });
        contacts
            .iter()
            .take(if valid { contacts.len() } else { 0 })
            .map(move |c| ContactInfo {
                body_a: self.bodies.id[c.body_a as usize],
                body_b: (c.body_b != STATIC_BODY).then(|| self.bodies.id[c.body_b as usize]),
                point: 0.5 * (c.point_a + c.point_b),
                normal: c.normal,
                separation: c.separation,
            })
    }
}
