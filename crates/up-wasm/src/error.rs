//! The errors a call can answer with. Each kind's name is part of the
//! contract: it is the `name` of the JS `Error` a refused call throws, and
//! `constants().error_kinds` lists them all for the page.

use std::fmt;

/// What went wrong, with a message for people.
#[derive(Clone, Debug, PartialEq)]
pub enum WasmError {
    /// No world has been built yet.
    NoWorld,
    /// An argument is NaN, infinite, or otherwise unusable.
    BadArgument(String),
    /// An index, model, colour or point that is not there.
    OutOfRange(String),
    /// Adding would go past the documented capacity.
    Full(String),
    /// The scene text is malformed or invalid.
    Scene(String),
    /// The physics world refused the request.
    Physics(String),
}

/// Every kind's name, in declaration order (what the page may see as `error.name`).
pub const ERROR_KINDS: [&str; 6] = [
    "NoWorld",
    "BadArgument",
    "OutOfRange",
    "Full",
    "Scene",
    "Physics",
];

impl WasmError {
    /// The kind's name, one of `ERROR_KINDS`.
    pub fn kind(&self) -> &'static str {
        let i = match self {
            WasmError::NoWorld => 0,
            WasmError::BadArgument(_) => 1,
            WasmError::OutOfRange(_) => 2,
            WasmError::Full(_) => 3,
            WasmError::Scene(_) => 4,
            WasmError::Physics(_) => 5,
        };
        ERROR_KINDS[i]
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
            | WasmError::Physics(m) => f.write_str(m),
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

/// A refused call as it reaches JavaScript: an `Error` whose `name` is the
/// kind and whose message starts with the method's name (scene errors name
/// the scene and key instead).
#[derive(Clone, Debug, PartialEq)]
pub struct CallError {
    pub kind: &'static str,
    pub message: String,
}

impl CallError {
    /// `error` as answered by method `method`.
    pub fn new(method: &str, error: WasmError) -> Self {
        let kind = error.kind();
        let message = match error {
            WasmError::Scene(m) => m,
            e => format!("{method}: {e}"),
        };
        CallError { kind, message }
    }
}

impl fmt::Display for CallError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl From<CallError> for wasm_bindgen::JsValue {
    fn from(e: CallError) -> Self {
        let error = js_sys::Error::new(&e.message);
        error.set_name(e.kind);
        error.into()
    }
}

/// `result` with its error, if any, as answered by `method`.
pub fn named<T>(method: &str, result: Result<T, WasmError>) -> Result<T, CallError> {
    result.map_err(|e| CallError::new(method, e))
}
