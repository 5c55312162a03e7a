//! Scenes for UP: the balloon model (procedural mesh, fitted sphere tree, mass
//! properties), the room, and scene files (TOML or JSON) built into a `World`,
//! ribbons tied to the balloons; and the whole scene written out as OBJ.
//!
//! SI units, Y up, origin at the centre of the floor.

// Files written whole or not at all.
pub mod atomic_file;

// The balloon and the room.
pub mod balloon;
pub mod balloon_mesh;
pub mod foil_mesh;
pub mod obj;
pub mod obj_export;
pub mod palette;
pub mod room;
pub mod scene_obj;

// Scene files and building a world from them.
pub mod bench_scene;
pub mod build;
pub mod error;
pub mod float_census;
pub mod gas_fill;
pub mod ribbons;
pub mod scene;
pub mod squash;

pub use float_census::{FloatCensus, FloatState, GroupCensus};
