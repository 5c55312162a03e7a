//! Scenes for UP: the balloon model (procedural mesh, fitted sphere tree, mass
//! properties), the room, and scene files (TOML or JSON) built into a `World`,
//! ribbons tied to the balloons; and the whole scene written out as OBJ.
//!
//! SI units, Y up, origin at the centre of the floor.
//!
//! One folder a concern: `scene/` the scene file (structs, defaults, parsing,
//! validation), `balloon/` the balloon model (mesh, mass, gas fill), `build/`
//! a `World` from a scene (room, spawn, ribbons, the bench scene), `obj/`
//! OBJ read and write.

// Files written whole or not at all.
pub mod atomic_file;

// The scene file, the balloon, building a world, OBJ.
pub mod balloon;
pub mod build;
pub mod obj;
pub mod scene;
pub mod squash;

// What the other modules share: errors, colours, reading a running world.
pub mod error;
pub mod float_census;
pub mod palette;

pub use float_census::{FloatCensus, FloatState, GroupCensus};

// The modules' paths before they were grouped in folders, kept for callers.
pub use balloon::{foil_mesh, gas_fill, mesh as balloon_mesh};
pub use build::{bench_scene, ribbons, room};
pub use obj::{export as obj_export, scene_obj};
