//! The page's limits and the strides of its views that every other file
//! reads: kept apart so that no file needs `state.rs` for a number.

/// Most steps one `step` call takes: a host asking for more has lost track of time.
pub const MAX_STEPS_PER_CALL: u32 = 10_000;
/// Most balloons a page may hold: what a browser can draw and step (the
/// engine itself takes millions). Adding past this is `Full`.
pub const CAPACITY: usize = 50_000;
/// Floats per pose: x, y, z, qx, qy, qz, qw.
pub const POSE_FLOATS: usize = 7;
/// Floats per sphere-tree node for the page: cx, cy, cz, radius, depth, leaf.
pub const TREE_FLOATS: usize = 6;
/// Fastest a balloon may be set moving, m/s: far beyond any throw (a hard
/// throw is 10 to 30 m/s) yet small enough that one step cannot tunnel far.
pub const MAX_SPEED: f32 = 100.0;
/// Fastest a balloon may be set spinning, rad/s (a flicked balloon: about 20).
pub const MAX_SPIN: f32 = 500.0;
