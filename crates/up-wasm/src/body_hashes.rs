//! The world's per-body state hashes, for the native = WebAssembly
//! determinism check (web/determinism/check.mjs): when the end hashes
//! differ, it steps the engine one step at a time and compares this line
//! with the one `up run --body-hashes` wrote for the same step, to name the
//! first step and body where the builds part.

use wasm_bindgen::prelude::*;

use crate::error::named;
use crate::{CallError, Engine};

#[wasm_bindgen]
impl Engine {
    /// `up_physics::divergence::body_hash_line` of the world now: the step,
    /// the state hash, then each body's `index.generation/user_data:` and
    /// field hashes (the header `up run --body-hashes` writes names them).
    pub fn body_hash_line(&self) -> Result<String, CallError> {
        named(
            "body_hash_line",
            self.state
                .world()
                .map(up_physics::divergence::body_hash_line),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "[[balloons]]\ncount = 3\n[balloons.ribbon]\nlength_m = 0.5\n";

    #[test]
    fn a_line_of_the_world_now_or_an_error_without_one() {
        let mut engine = Engine::new();
        let err = engine.body_hash_line().unwrap_err();
        assert!(err.message.starts_with("body_hash_line"), "{err}");
        engine.load_scene_toml(SCENE).unwrap();
        let start = engine.body_hash_line().unwrap();
        assert!(start.starts_with("0 "), "{start}");
        assert_eq!(start.split(' ').count(), 2 + 3, "{start}");
        engine.step(2).unwrap();
        let line = engine.body_hash_line().unwrap();
        let state_hash = format!("{:016x}", engine.state_hash());
        assert_eq!(
            line.split(' ').take(2).collect::<Vec<_>>(),
            ["2", &state_hash]
        );
    }
}
