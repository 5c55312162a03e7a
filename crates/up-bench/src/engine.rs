//! What the harness needs from an engine: step it, read its poses.

use glam::Vec3;
use up_geom::Pose;
use up_physics::Counters;

/// One physics engine holding the benchmark scene.
pub trait Engine {
    /// `"up"` or `"rapier"`.
    fn name(&self) -> &'static str;
    /// Advances the world by one step of the scene's `dt` (forces included).
    fn step(&mut self);
    /// Pose of each balloon's body frame (the mesh frame), in creation order.
    fn poses(&self, out: &mut Vec<Pose>);
    /// Balloons in the world.
    fn body_count(&self) -> usize;
    /// Balloons not asleep.
    fn awake_count(&self) -> usize;
    /// kg: the translational mass of all balloons, added mass included.
    fn total_translational_mass(&self) -> f64;
    /// Ribbons tied to the balloons.
    fn ribbon_count(&self) -> usize {
        0
    }
    /// The largest relative stretch of any ribbon now (`ribbons::stretch`),
    /// NaN if any went non-finite; `None` without ribbons. `scratch` is for
    /// the points.
    fn max_ribbon_stretch(&self, _scratch: &mut Vec<Vec3>) -> Option<f32> {
        None
    }
    /// The engine's own timing of its last step's stages (UP's `World::counters`).
    fn counters(&self) -> Option<Counters> {
        None
    }
}

/// Which engines a run compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum EngineKind {
    Up,
    Rapier,
}

impl EngineKind {
    pub fn name(self) -> &'static str {
        match self {
            EngineKind::Up => "up",
            EngineKind::Rapier => "rapier",
        }
    }

    /// `"up"` or `"rapier"`; `None` for anything else.
    pub fn parse(name: &str) -> Option<EngineKind> {
        match name.trim() {
            "up" => Some(EngineKind::Up),
            "rapier" => Some(EngineKind::Rapier),
            _ => None,
        }
    }
}
