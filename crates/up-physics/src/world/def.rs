//! `WorldDef`: every parameter of a world, its unit, default and accepted range.

use glam::Vec3;
use serde::{Deserialize, Serialize};
use up_geom::TriMesh;

use super::limits::{self, Limit};
use super::PhysicsError;
use crate::forces::atmosphere::Atmosphere;
use crate::gas::TemperatureSchedule;

/// Everything that defines a world, with documented defaults (`Default`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct WorldDef {
    /// m/s²; (0, −9.81, 0).
    pub gravity: Vec3,
    /// The room's air: densities for buoyancy, drag and added mass follow from it.
    pub atmosphere: Atmosphere,
    /// The room's temperature over the run, (s, K) points, linear between;
    /// empty (the default): the atmosphere's temperature throughout.
    #[serde(default)]
    pub temperature_schedule: TemperatureSchedule,
    /// s per step; 1/60.
    pub dt: f32,
    /// Solver substeps per step; 4.
    pub substeps: u32,
    /// Gauss-Seidel passes over the contacts per substep; 2. More converge
    /// chains of balloons (pile → ceiling) faster, at a proportional cost; with
    /// one, a settling pile's impulses swing from step to step and groups woken
    /// with unbalanced impulses wake their neighbours in cascades
    /// (docs/perf-log.md).
    pub solve_iterations: u32,
    /// Overlap the position pass leaves alone, m; 0.0005. Deeper overlap is removed
    /// after each step, so balloons never sink into each other.
    pub stabilization_slop: f32,
    /// Passes of the position pass per step, at least; 4 (0 turns it off),
    /// twice that in a step with an impact: a contact that closed faster than
    /// `speculative_distance` in the step, and pushed. Cheap next to the solve;
    /// fewer let a big pile's overlap pass 1 mm (docs/perf-log.md).
    pub stabilization_iterations: u32,
    /// More passes, up to this many in all, while a pass still finds overlap
    /// deeper than `stabilization_target`; 32. A crowd pressed into the apex
    /// is a long chain that a few passes cannot straighten (docs/perf-log.md).
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
    /// Whether ribbons touch each other and themselves (`ribbon::touch`);
    /// false. Off, they pass through each other: with ten thousand ribbons
    /// laid crossing on the floor the contacts still cost twice the ribbons'
    /// own solve, so a scene asks for them (a bouquet's are cheap).
    #[serde(default)]
    pub ribbon_contacts: bool,
    /// Friction of a ribbon on a ribbon; `RIBBON_ON_RIBBON_FRICTION` (0.4, a guess).
    #[serde(default = "ribbon_on_ribbon_friction")]
    pub ribbon_friction: f32,
}

fn ribbon_on_ribbon_friction() -> f32 {
    crate::ribbon::RIBBON_ON_RIBBON_FRICTION
}

impl Default for WorldDef {
    fn default() -> Self {
        Self {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            atmosphere: Atmosphere::default(),
            temperature_schedule: TemperatureSchedule::default(),
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
            ribbon_contacts: false,
            ribbon_friction: crate::ribbon::RIBBON_ON_RIBBON_FRICTION,
        }
    }
}

fn check(ok: bool, key: &'static str, value: f32, expected: &str) -> Result<(), PhysicsError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(PhysicsError::BadParameter {
            key,
            value,
            expected: expected.to_string(),
        })
    }
}

/// The parameter `key` inside its shared limit (`limits`).
pub(super) fn within(limit: &Limit, key: &'static str, value: f32) -> Result<(), PhysicsError> {
    if limit.contains(value) {
        return Ok(());
    }
    check(false, key, value, &limit.describe())
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
        if let Some(problem) = self.temperature_schedule.problem() {
            return Err(PhysicsError::BadSchedule(problem));
        }
        within(&limits::DT, "dt", self.dt)?;
        let substeps = self.substeps as f32;
        within(&limits::SUBSTEPS, "substeps", substeps)?;
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
        within(&limits::CONTACT_HERTZ, "contact_hertz", self.contact_hertz)?;
        let zeta = self.contact_damping_ratio;
        within(
            &limits::CONTACT_DAMPING_RATIO,
            "contact_damping_ratio",
            zeta,
        )?;
        check(
            self.max_push_out > 0.0,
            "max_push_out",
            self.max_push_out,
            "> 0 m/s",
        )?;
        within(&limits::FRICTION, "friction", self.friction)?;
        within(&limits::FRICTION, "ribbon_friction", self.ribbon_friction)?;
        let e = self.restitution;
        within(&limits::RESTITUTION, "restitution", e)?;
        let th = self.restitution_threshold;
        check(th >= 0.0, "restitution_threshold", th, "≥ 0 m/s")?;
        let cd = self.drag_coefficient;
        within(&limits::DRAG_COEFFICIENT, "drag_coefficient", cd)?;
        let ca = self.added_mass_coefficient;
        within(
            &limits::ADDED_MASS_COEFFICIENT,
            "added_mass_coefficient",
            ca,
        )?;
        let ad = self.angular_damping;
        within(&limits::ANGULAR_DAMPING, "angular_damping", ad)?;
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
