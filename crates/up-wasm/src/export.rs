//! The page's "Export last 10 s (.glb)": the engine records each frame the
//! worker sends into a ring of the last `EXPORT_SECONDS` of simulated time
//! (`up_export::Recording`, the same recording `up export-gltf` fills) and
//! writes it as a `.glb` on request. Frames closer together than
//! `MIN_INTERVAL_S` are skipped, and more still in a large world, so that
//! the ring stays within `RING_BYTES`. A new world, or balloons and ribbons
//! added or removed, start the ring afresh.

use up_export::{Recording, SceneLooks};

use crate::error::WasmError;
use crate::loaded::Loaded;

/// Simulated seconds the export holds.
pub const EXPORT_SECONDS: f64 = 10.0;
/// Closest two recorded frames, s: 60 a second, the engine's step.
const MIN_INTERVAL_S: f64 = 1.0 / 60.0;
/// Most bytes the ring's frames may take.
const RING_BYTES: f64 = 96.0 * 1024.0 * 1024.0;
/// Bytes a frame takes per balloon (pose and size) and per ribbon point.
const BYTES_PER_BALLOON: f64 = 32.0;
const BYTES_PER_POINT: f64 = 12.0;

/// The frames the page was sent, the last `EXPORT_SECONDS` of them.
#[derive(Default)]
pub struct ExportRing {
    recording: Option<Recording>,
    /// Closest two frames for this world's size, s.
    interval: f64,
}

impl ExportRing {
    /// Forgets everything (a new world).
    pub fn clear(&mut self) {
        self.recording = None;
    }

    /// Records the world as it is now, unless it is within the interval of
    /// the last frame recorded.
    pub fn record(&mut self, loaded: &Loaded) {
        let world = &loaded.built.world;
        let time = world.time();
        let stale = self
            .recording
            .as_ref()
            .is_none_or(|r| !r.matches(world) || r.frames().last().is_some_and(|f| f.time > time));
        if stale {
            let looks = SceneLooks::of(&loaded.scene, &loaded.built);
            let points: usize = looks.ribbons.iter().map(|r| r.points).sum();
            let frame_bytes =
                looks.balloons.len() as f64 * BYTES_PER_BALLOON + points as f64 * BYTES_PER_POINT;
            self.interval = MIN_INTERVAL_S.max(EXPORT_SECONDS * frame_bytes / RING_BYTES);
            self.recording = Some(Recording::new(looks, Some(EXPORT_SECONDS)));
        }
        let Some(recording) = &mut self.recording else {
            return;
        };
        // Half a step's slack: the world's clock sums f32 steps.
        let due = recording.frames().last().is_none_or(|f| {
            time == f.time || time - f.time >= self.interval - 0.5 * MIN_INTERVAL_S
        });
        if due {
            // The world was just checked to match.
            let _ = recording.record(world);
        }
    }

    /// Frames held now.
    pub fn frame_count(&self) -> usize {
        self.recording.as_ref().map_or(0, Recording::frame_count)
    }

    /// The ring as a `.glb`.
    pub fn glb(&self) -> Result<Vec<u8>, WasmError> {
        let recording = self
            .recording
            .as_ref()
            .ok_or_else(|| WasmError::OutOfRange("nothing was recorded yet".into()))?;
        up_export::glb(recording).map_err(|e| WasmError::OutOfRange(e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::state::State;

    #[test]
    fn the_ring_keeps_the_last_ten_seconds_and_writes_a_glb() {
        let mut state = State::default();
        state
            .load_toml("[[balloons]]\ncount = 2\n[balloons.ribbon]\nlength_m = 0.5\nsegments = 4\n")
            .unwrap();
        let mut ring = ExportRing::default();
        ring.record(state.loaded().unwrap());
        for _ in 0..(12 * 30) {
            state.step(2).unwrap();
            ring.record(state.loaded().unwrap());
            // A frame sent again without a step changes nothing.
            ring.record(state.loaded().unwrap());
        }
        let frames: Vec<f64> = ring
            .recording
            .as_ref()
            .unwrap()
            .frames()
            .map(|f| f.time)
            .collect();
        let span = frames[frames.len() - 1] - frames[0];
        assert!((span - EXPORT_SECONDS).abs() < 0.05, "{span} s");
        assert!(frames.windows(2).all(|w| w[1] > w[0]));
        let glb = ring.glb().unwrap();
        assert_eq!(&glb[0..4], b"glTF");
        // A new world starts the ring afresh.
        state.load_toml("[[balloons]]\ncount = 1\n").unwrap();
        ring.record(state.loaded().unwrap());
        assert_eq!(ring.frame_count(), 1);
    }
}
