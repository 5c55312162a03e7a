//! Status codes returned by every fallible export, and the error behind them.
//!
//! The codes are part of the ABI: web/src/sim/engine.ts mirrors them.

use std::fmt;

/// What went wrong, with a message for people. `code()` is what crosses the boundary.
#[derive(Clone, Debug, PartialEq)]
pub enum WasmError {
    /// No world has been built yet.
    NoWorld,
    /// An argument is NaN, infinite, or otherwise unusable.
    BadArgument(String),
    /// An index or pointer lies outside what exists.
    OutOfRange(String),
    /// Adding would go past the documented capacity.
    Full(String),
    /// The scene text is malformed or invalid.
    Scene(String),
    /// The physics world refused the request.
    Physics(String),
    /// Text that is not UTF-8.
    Encoding(String),
    /// Memory could not be allocated.
    Alloc(String),
}

pub const OK: i32 = 0;

impl WasmError {
    pub fn code(&self) -> i32 {
        match self {
            WasmError::NoWorld => 1,
            WasmError::BadArgument(_) => 2,
            WasmError::OutOfRange(_) => 3,
            WasmError::Full(_) => 4,
            WasmError::Scene(_) => 5,
            WasmError::Physics(_) => 6,
            WasmError::Encoding(_) => 7,
            WasmError::Alloc(_) => 8,
        }
    }
}

impl fmt::Display for WasmError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WasmError::NoWorld => write!(f, "no world: load a scene first"),
            WasmError::BadArgument(m)
            | WasmError::OutOfRange(m)
            | WasmError::Full(m)
            | WasmError::Scene(m)
            | WasmError::Physics(m)
            | WasmError::Encoding(m)
            | WasmError::Alloc(m) => f.write_str(m),
        }
    }
}

impl From<up_physics::PhysicsError> for WasmError {
    fn from(e: up_physics::PhysicsError) -> Self {
        WasmError::Physics(e.to_string())
    }
}

impl From<up_scene::error::SceneError> for WasmError {
    fn from(e: up_scene::error::SceneError) -> Self {
        WasmError::Scene(e.to_string())
    }
}

/// `Ok` when every value is finite, else a `BadArgument` naming `what`.
pub fn finite(what: &str, values: &[f32]) -> Result<(), WasmError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(WasmError::BadArgument(format!(
            "{what}: expected finite numbers, found {values:?}"
        )))
    }
}
