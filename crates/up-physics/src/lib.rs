//! UP's physics world: rigid balloons made of sphere trees, a static
//! triangle-mesh room, a substepped soft contact solver with friction and
//! restitution, joints solved in the same substeps, and the forces of air
//! (buoyancy, drag, added mass) and of the scene's force fields, which act on
//! balloons and ribbons alike (`forces::field`, the step's extension point).
//!
//! Conventions, stated once: SI units (m, kg, s, N), right-handed, Y up.
//! Deterministic: the same inputs give bit-identical states on every run and
//! on every platform (no fast-math, libm for transcendental functions, no
//! hash-map iteration on the step's path).

// Threads in WebAssembly need a nightly std built with atomics; on it, a
// thread waiting at a stage's barrier sleeps on the count (`threading::staged`).
#![cfg_attr(
    all(target_arch = "wasm32", target_feature = "atomics"),
    feature(stdarch_wasm_atomic_wait)
)]

pub mod air;
mod body;
mod broad_phase;
mod contact;
mod continuous;
mod counters;
pub mod divergence;
pub mod forces;
pub mod gas;
mod grab;
mod hash;
mod joint;
mod knocks;
mod narrow_phase;
mod quarantine;
pub mod ribbon;
mod sleep;
mod slots;
mod snapshot;
mod solver;
mod threading;
mod world;

pub use air::AirFlow;
pub use body::{BalloonShape, BodyDef, BodyId, ShapeId};
pub use counters::{set_thread_timing, Counters, Phase, Stage, ThreadCounters, ThreadTime};
pub use forces::atmosphere::Atmosphere;
pub use forces::field::{FieldSample, ForceField, PointSample};
pub use gas::{EnvelopeDef, EnvelopeKind, Gas, TemperatureSchedule};
pub use joint::{DistanceJointDef, DistanceLimit, JointAnchor, JointId};
pub use quarantine::{QuarantinedBody, MAX_QUARANTINE_REPORTS};
pub use ribbon::{RibbonDef, RibbonId};
pub use snapshot::SnapshotError;
pub use threading::keep_awake_switch::set_keep_threads_awake;
pub use threading::thread_sums::{StageThreadMeans, ThreadSums};
pub use up_geom;
pub use world::limits;
pub use world::{
    Advance, ContactInfo, ForceBreakdown, ForceProbe, PhysicsError, StepStats, World, WorldDef,
    MAX_BODIES, MAX_JUMP_S, WAKE_GROWTH, WAKE_LIFT_CHANGE, WAKE_LIFT_FLOOR, WAKE_LIFT_HOVER,
    WAKE_LIFT_KNEE, WAKE_SHRINK,
};
