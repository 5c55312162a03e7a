//! Time spent in each stage of a step, for the CLI and the web HUD.

use serde::{Deserialize, Serialize};

/// Milliseconds spent in each stage of the last step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Counters {
    /// Placing sphere trees and finding candidate pairs on the grid.
    pub broadphase_ms: f64,
    /// Sphere-tree descent against other balloons and the room; warm-start matching.
    pub narrowphase_ms: f64,
    /// Building constraints: anchors, effective masses, warm-start impulses.
    pub prepare_ms: f64,
    /// The substeps: forces, warm start, solve, integrate positions, relax.
    pub solve_ms: f64,
    /// Restitution and storing impulses for the next step.
    pub restitution_ms: f64,
    /// Sweeping fast balloons against the room.
    pub continuous_ms: f64,
    /// Islands and sleep.
    pub sleep_ms: f64,
    /// The whole step.
    pub total_ms: f64,
}

impl Counters {
    /// Stage names and times, in the order the step runs them.
    pub fn stages(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("broadphase", self.broadphase_ms),
            ("narrowphase", self.narrowphase_ms),
            ("prepare", self.prepare_ms),
            ("solve", self.solve_ms),
            ("restitution", self.restitution_ms),
            ("continuous", self.continuous_ms),
            ("sleep", self.sleep_ms),
            ("total", self.total_ms),
        ]
    }
}

/// A monotonic clock in milliseconds. Native builds use `std::time::Instant`;
/// `wasm32-unknown-unknown` has no clock of its own, so the crate that builds
/// the module defines `up_now_ms` (up-wasm: the host's `performance.now`).
#[cfg(not(target_arch = "wasm32"))]
pub(crate) fn now_ms() -> f64 {
    use std::sync::OnceLock;
    use std::time::Instant;
    static START: OnceLock<Instant> = OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_secs_f64() * 1000.0
}

#[cfg(target_arch = "wasm32")]
pub(crate) fn now_ms() -> f64 {
    extern "C" {
        fn up_now_ms() -> f64;
    }
    // SAFETY: a pure function without arguments or memory access.
    unsafe { up_now_ms() }
}

/// Measures consecutive stages: `lap()` returns the milliseconds since the last lap.
pub(crate) struct Stopwatch {
    last: f64,
}

impl Stopwatch {
    pub fn start() -> Self {
        Self { last: now_ms() }
    }

    pub fn lap(&mut self) -> f64 {
        let now = now_ms();
        let dt = now - self.last;
        self.last = now;
        dt
    }
}
