//! Scene files: the room, groups of balloons, the air (still, or moved by
//! fans, vents and draughts) and the simulation settings, in TOML or JSON
//! with one schema (docs/scene-format.md).
//!
//! Every section and every key may be left out and takes its default (but
//! where a fan or vent is, and a draught's opening and velocity); the
//! defaults are the original project's scene: a 6 m × 6 m room with 3 m walls
//! and a pyramidal ceiling, 50 balloons in six colours released from the floor,
//! each on a 1.5 m ribbon.
//! Unknown keys are errors, and so is a file of nothing but whitespace (what a
//! failed write leaves). After parsing, `validate` checks every number is
//! finite and within its documented range; errors name the file, the key path
//! and the line. The key path of a parse error is serde's own
//! (`serde_path_to_error`), its line the parser's.
//!
//! One concern a file: the structs (`spec`), their defaults (`defaults`),
//! reading text (`parse`) and files (`file`), the ranges (`validate`), the
//! line of each key for messages (`lines`), `[about]` (`about`), and the
//! sources of moving air with their defaults and ranges (`air_sources`),
//! and the furniture standing in the room (`furniture`).

mod about;
mod air_sources;
mod defaults;
mod file;
mod furniture;
mod lines;
mod parse;
pub mod shapes;
mod spec;
mod validate;

pub use crate::palette::parse_color;
pub use about::{AboutSpec, MAX_CAPTION_CHARS, MAX_TITLE_CHARS};
pub use air_sources::{
    DraughtSpec, JetSource, JetSpec, ResolvedJet, DEFAULT_FAN_DIAMETER_M, DEFAULT_FAN_DIRECTION,
    DEFAULT_FAN_SPEED_M_S, DEFAULT_SWEEP_PERIOD_S, DEFAULT_VENT_DIAMETER_M, DEFAULT_VENT_DIRECTION,
    DEFAULT_VENT_SPEED_M_S, MAX_AIR_SOURCES, MAX_AIR_SPEED_M_S, MAX_JET_DIAMETER_M,
    MAX_ON_INTERVALS, MAX_SWEEP_DEG, MAX_SWEEP_PERIOD_S, MIN_JET_DIAMETER_M,
};
pub use defaults::{
    DEFAULT_COLORS, DEFAULT_DIAMETER_M, DEFAULT_ENVELOPE_MASS_G_11IN, DEFAULT_FOIL_DIAMETER_M,
    DEFAULT_FOIL_ENVELOPE_MASS_G_18IN, DEFAULT_FOIL_VALVE_MASS_G, DEFAULT_KNOT_MASS_G,
    DEFAULT_RIBBON_COLOR, DEFAULT_RIBBON_LENGTH_M, DEFAULT_RIBBON_MASS_PER_M_G,
    DEFAULT_RIBBON_SEGMENTS, DEFAULT_SOURCE_NAME, METRES_PER_INCH,
};
pub use file::MAX_SCENE_BYTES;
pub use furniture::{
    FurnitureKind, FurnitureSpec, DEFAULT_CHAIR_SIZE_M, DEFAULT_TABLE_SIZE_M, MAX_FURNITURE,
    MAX_FURNITURE_SIZE_M, MIN_FURNITURE_SIZE_M,
};
pub use lines::KeyLines;
pub use shapes::{group_surface, BalloonShape};
pub use spec::{
    AirSpec, BalloonGroup, BalloonKind, CeilingKind, Finish, GasKind, RibbonSpec, RoomSpec, Scene,
    SceneSource, SimSpec, SpawnBox, Treatment,
};
pub use validate::{
    MAX_BALLOON_DIAMETER_M, MAX_BALLOON_GROUPS, MAX_FILLED_HOURS_BEFORE, MAX_GROUP_COLORS,
    MAX_RIBBON_LENGTH_M, MAX_RIBBON_MASS_PER_M_G, MAX_RIBBON_WEIGHT_G, MAX_ROOM_SIZE_M,
    MAX_SCENE_LEAVES, MAX_SCHEDULE_HOURS, MAX_SCHEDULE_POINTS, MAX_SEED, MAX_TOTAL_BALLOONS,
    MIN_BALLOON_DIAMETER_M, MIN_ROOM_SIZE_M,
};

#[cfg(test)]
mod air_sources_tests;
#[cfg(test)]
mod file_tests;
#[cfg(test)]
mod gas_tests;
#[cfg(test)]
mod parse_tests;
#[cfg(test)]
mod ribbon_tests;
#[cfg(test)]
mod shapes_tests;
#[cfg(test)]
mod test_support;
#[cfg(test)]
mod validate_tests;
