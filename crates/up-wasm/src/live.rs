//! Live settings: what a panel control changes in the running world without
//! rebuilding it. One enum, written to the page by tsify as
//! `{ control: "gravity", value: 1.62 } | …`, crosses the page untouched
//! (panel → bridge → worker → `Engine::apply_live`) and is matched here,
//! the only place that knows what each does. Each also writes itself into
//! the loaded scene, so that `scene_json` (the share link) carries it.
//!
//! A new live control is a variant, its range in `range` and its arm in
//! `apply` here, and its line in the page's panel (`web/src/ui/panel.ts`).
//! Controls that need a new world (the room, the balloons' count) are scene
//! edits instead: the page rebuilds the world from the edited scene.

use glam::Vec3;
use serde::{Deserialize, Serialize};
use tsify_next::Tsify;

use crate::error::{finite, WasmError};
use crate::loaded::Loaded;
use crate::ribbons::{set_ribbon_length, MAX_RIBBON_LENGTH_M};

/// Strongest gravity the page may set, m/s²: twice Jupiter's 24.8, past
/// anything a room could be asked to show.
pub const MAX_LIVE_GRAVITY: f32 = 50.0;

/// A setting the running world takes as it is.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, Tsify)]
#[serde(tag = "control", content = "value", rename_all = "snake_case")]
pub enum LiveSetting {
    /// Every balloon's ribbon, m (0: none): re-tied on every balloon, and
    /// on each added later, the scene's other ribbon keys kept.
    RibbonLength(f32),
    /// The room's gravity, m/s², straight down: 9.81 on Earth, 1.62 on the
    /// Moon. Buoyancy follows it (ρ_air·V·g), so a balloon's net lift does.
    Gravity(f32),
}

/// The values a live control accepts, by its name (`control` in the JSON).
#[derive(Clone, Debug, PartialEq, Serialize, Tsify)]
pub struct LiveRange {
    pub control: String,
    pub min: f32,
    pub max: f32,
}

impl LiveSetting {
    /// One of each, for the ranges the page reads (`constants().live`).
    pub const ALL: [LiveSetting; 2] = [LiveSetting::RibbonLength(0.0), LiveSetting::Gravity(0.0)];

    /// Its name, as `control` in the JSON.
    pub fn control(&self) -> &'static str {
        match self {
            LiveSetting::RibbonLength(_) => "ribbon_length",
            LiveSetting::Gravity(_) => "gravity",
        }
    }

    pub fn value(&self) -> f32 {
        match *self {
            LiveSetting::RibbonLength(v) | LiveSetting::Gravity(v) => v,
        }
    }

    /// The values it accepts, inclusive.
    pub fn range(&self) -> (f32, f32) {
        match self {
            LiveSetting::RibbonLength(_) => (0.0, MAX_RIBBON_LENGTH_M),
            LiveSetting::Gravity(_) => (0.0, MAX_LIVE_GRAVITY),
        }
    }

    /// Every control's range.
    pub fn ranges() -> Vec<LiveRange> {
        Self::ALL
            .iter()
            .map(|s| {
                let (min, max) = s.range();
                LiveRange {
                    control: s.control().to_string(),
                    min,
                    max,
                }
            })
            .collect()
    }
}

/// Applies `setting` to the loaded world and its scene; refused, with
/// nothing changed, when not a number (`BadArgument`) or outside its range
/// (`OutOfRange`).
pub fn apply(loaded: &mut Loaded, setting: LiveSetting) -> Result<(), WasmError> {
    let (min, max) = setting.range();
    let value = setting.value();
    finite(setting.control(), &[value])?;
    if !(min..=max).contains(&value) {
        return Err(WasmError::OutOfRange(format!(
            "{} {value}: expected {min} to {max}",
            setting.control()
        )));
    }
    match setting {
        LiveSetting::RibbonLength(length) => set_ribbon_length(loaded, length),
        LiveSetting::Gravity(g) => {
            let gravity = Vec3::new(0.0, -g, 0.0);
            loaded.built.world.set_gravity(gravity)?;
            loaded.scene.sim.gravity = gravity.to_array();
            Ok(())
        }
    }
}

#[cfg(test)]
#[path = "live_tests.rs"]
mod tests;
