//! A thin WebAssembly layer over up-physics and up-scene for the web app.
//!
//! Plain `extern "C"` exports over one world that lives in the module (the
//! page runs one simulation), no wasm-bindgen. Conventions:
//!
//! - Every fallible export returns a status code and leaves a message, which
//!   starts with the export's name (scene errors name the scene and key
//!   instead), readable at `up_last_error_ptr()`/`up_last_error_len()`:
//!
//!   | code | name          | when                                                    |
//!   |------|---------------|---------------------------------------------------------|
//!   | 0    | `OK`          | success                                                 |
//!   | 1    | `NoWorld`     | called before a scene was loaded                        |
//!   | 2    | `BadArgument` | NaN or infinite numbers, too fast, too many steps       |
//!   | 3    | `OutOfRange`  | an index, model, colour, point or pointer that is not there |
//!   | 4    | `Full`        | adding past `CAPACITY` balloons                         |
//!   | 5    | `Scene`       | the scene text is malformed or invalid                  |
//!   | 6    | `Physics`     | the engine refused the request                          |
//!   | 7    | `Encoding`    | text that is not UTF-8                                  |
//!   | 8    | `Alloc`       | a buffer larger than 64 MiB, or 128 MiB held at once    |
//!
//!   web/src/sim/engine.ts mirrors the codes. Bad arguments never trap, and a
//!   refused call leaves the world as it was. Exports that return a count
//!   answer 0 without a world; pointer exports answer a valid (maybe empty) view.
//! - Capacity and limits: at most `CAPACITY` (50 000) balloons in the page's
//!   world (`up_capacity()`); at most 10 000 steps per `up_step`; velocities
//!   up to `MAX_SPEED` (100 m/s) and `MAX_SPIN` (500 rad/s); added balloons
//!   inside the room's bounds; grab points on the balloon; drag targets are
//!   clamped into the room; at most `MAX_CONTACTS` (65 536) contacts written.
//! - Text goes in through a buffer from `up_alloc(len)` (freed with `up_free`),
//!   checked against the table of live buffers, and comes out through
//!   `up_output_ptr()`/`up_output_len()`.
//! - Bulk data (poses, colours, contacts, the room, trees) are read as views
//!   of wasm memory: call `up_write_*`, then read at `up_*_ptr()`. A view is
//!   valid until the next call (memory may grow and move).
//! - The stage timers of up-physics import `env.up_now_ms() -> f64` (ms,
//!   monotonic); the page passes `performance.now`.
//!
//! SI units, Y up, origin at the centre of the floor.

mod contacts;
mod memory;
mod state;
mod status;

use std::cell::RefCell;

use glam::Vec3;

pub use contacts::{CONTACT_FLOATS, MAX_CONTACTS};
pub use memory::{MAX_ALLOC, MAX_LIVE};
pub use state::{State, CAPACITY, MAX_SPEED, MAX_SPIN, POSE_FLOATS, TREE_FLOATS};
pub use status::WasmError;

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
    static ALLOCATIONS: RefCell<memory::Allocations> = RefCell::new(memory::Allocations::default());
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Runs `f` on the state for export `name` and turns its result into a status code.
fn with_state(name: &str, f: impl FnOnce(&mut State) -> Result<(), WasmError>) -> i32 {
    let result = STATE.with(|s| match s.try_borrow_mut() {
        Ok(mut state) => f(&mut state),
        // Only after a trap left the state borrowed: the host must re-instantiate.
        Err(_) => Err(WasmError::BadArgument(
            "the module's state is still in use (a call trapped?): reload the module".to_string(),
        )),
    });
    report(name, result)
}

/// The status code of `result`; on error, the message (prefixed with the export's
/// `name`, except for scene errors, which name the scene) goes to `LAST_ERROR`.
fn report(name: &str, result: Result<(), WasmError>) -> i32 {
    match result {
        Ok(()) => status::OK,
        Err(e) => {
            let code = e.code();
            let message = match e {
                WasmError::Scene(m) => m,
                e => format!("{name}: {e}"),
            };
            LAST_ERROR.with(|m| *m.borrow_mut() = message);
            code
        }
    }
}

/// Reads a value from the state (`busy` during a re-entrant call, which cannot happen from JS).
fn read_or<T>(busy: T, f: impl FnOnce(&State) -> T) -> T {
    STATE.with(|s| s.try_borrow().map(|state| f(&state)).unwrap_or(busy))
}

fn read<T: Default>(f: impl FnOnce(&State) -> T) -> T {
    read_or(T::default(), f)
}

fn read_ptr<T>(f: impl FnOnce(&State) -> *const T) -> *const T {
    read_or(std::ptr::null(), f)
}

fn scene_text(
    name: &str,
    ptr: *const u8,
    len: usize,
    load: fn(&mut State, &str) -> Result<(), WasmError>,
) -> i32 {
    let text = ALLOCATIONS.with(|a| a.borrow().text(ptr, len).map(str::to_owned));
    match text {
        Ok(text) => with_state(name, |s| load(s, &text)),
        Err(e) => report(name, Err(e)),
    }
}

// ---- memory and errors ----

/// A zeroed buffer of `len` bytes for the host to write into; 0 on failure.
#[no_mangle]
pub extern "C" fn up_alloc(len: usize) -> *mut u8 {
    match ALLOCATIONS.with(|a| a.borrow_mut().alloc(len)) {
        Ok(ptr) => ptr,
        Err(e) => {
            report("up_alloc", Err(e));
            std::ptr::null_mut()
        }
    }
}

/// Frees a buffer from `up_alloc` (`len` is accepted for symmetry and ignored).
#[no_mangle]
pub extern "C" fn up_free(ptr: *mut u8, _len: usize) -> i32 {
    report("up_free", ALLOCATIONS.with(|a| a.borrow_mut().free(ptr)))
}

#[no_mangle]
pub extern "C" fn up_last_error_ptr() -> *const u8 {
    LAST_ERROR.with(|m| m.borrow().as_ptr())
}

#[no_mangle]
pub extern "C" fn up_last_error_len() -> usize {
    LAST_ERROR.with(|m| m.borrow().len())
}

#[no_mangle]
pub extern "C" fn up_output_ptr() -> *const u8 {
    read_ptr(|s| s.output.as_ptr())
}

#[no_mangle]
pub extern "C" fn up_output_len() -> usize {
    read(|s| s.output.len())
}

// ---- building a world ----

/// Builds the world from a scene in JSON at `ptr..ptr+len` (from `up_alloc`).
#[no_mangle]
pub extern "C" fn up_world_from_json(ptr: *const u8, len: usize) -> i32 {
    scene_text("up_world_from_json", ptr, len, State::load_json)
}

/// Builds the world from a scene in TOML at `ptr..ptr+len` (from `up_alloc`).
#[no_mangle]
pub extern "C" fn up_world_from_toml(ptr: *const u8, len: usize) -> i32 {
    scene_text("up_world_from_toml", ptr, len, State::load_toml)
}

/// Builds the default scene (the original UP room).
#[no_mangle]
pub extern "C" fn up_world_default() -> i32 {
    with_state("up_world_default", State::load_default)
}

/// The loaded scene as JSON, in the output buffer.
#[no_mangle]
pub extern "C" fn up_scene_json() -> i32 {
    with_state("up_scene_json", State::scene_json)
}

/// The default scene as JSON, in the output buffer (no world needed).
#[no_mangle]
pub extern "C" fn up_default_scene_json() -> i32 {
    with_state("up_default_scene_json", State::default_scene_json)
}

/// Palette, colour names, model diameters and dt, as JSON in the output buffer.
#[no_mangle]
pub extern "C" fn up_world_info_json() -> i32 {
    with_state("up_world_info_json", State::world_info_json)
}

// ---- stepping and reading ----

/// Takes `n` fixed steps (at most 10 000 per call).
#[no_mangle]
pub extern "C" fn up_step(n: u32) -> i32 {
    with_state("up_step", |s| s.step(n))
}

#[no_mangle]
pub extern "C" fn up_body_count() -> u32 {
    read(|s| s.body_count() as u32)
}

/// Most balloons the page's world accepts.
#[no_mangle]
pub extern "C" fn up_capacity() -> u32 {
    CAPACITY as u32
}

/// Writes every pose (x, y, z, qx, qy, qz, qw; dense order) for `up_poses_ptr`.
#[no_mangle]
pub extern "C" fn up_write_poses() -> i32 {
    with_state("up_write_poses", State::write_poses)
}

#[no_mangle]
pub extern "C" fn up_poses_ptr() -> *const f32 {
    read_ptr(|s| s.poses.as_ptr())
}

/// Writes every body's colour index and model index for `up_colors_ptr`/`up_models_ptr`.
#[no_mangle]
pub extern "C" fn up_write_colors() -> i32 {
    with_state("up_write_colors", State::write_user_data)
}

#[no_mangle]
pub extern "C" fn up_colors_ptr() -> *const u32 {
    read_ptr(|s| s.colors.as_ptr())
}

/// Same as `up_write_colors` (one pass fills both).
#[no_mangle]
pub extern "C" fn up_write_models() -> i32 {
    with_state("up_write_models", State::write_user_data)
}

#[no_mangle]
pub extern "C" fn up_models_ptr() -> *const u32 {
    read_ptr(|s| s.models.as_ptr())
}

/// Writes the last step's contact points for `up_contacts_ptr`, at most
/// `max` of them (and at most `MAX_CONTACTS`), `CONTACT_FLOATS` floats each:
/// x, y, z (m), nx, ny, nz (unit, from the balloon toward what it touches),
/// separation (m, negative when overlapping), kind (1 balloon, 0 room).
#[no_mangle]
pub extern "C" fn up_write_contacts(max: u32) -> i32 {
    with_state("up_write_contacts", |s| s.write_contacts(max))
}

#[no_mangle]
pub extern "C" fn up_contacts_ptr() -> *const f32 {
    read_ptr(|s| s.contacts.as_ptr())
}

/// Contacts written by the last `up_write_contacts`.
#[no_mangle]
pub extern "C" fn up_contact_count() -> u32 {
    read(|s| (s.contacts.len() / CONTACT_FLOATS) as u32)
}

/// Contacts the last step had in all when `up_write_contacts` ran (written or not).
#[no_mangle]
pub extern "C" fn up_contact_total() -> u32 {
    read(|s| s.contact_total as u32)
}

/// The most contacts `up_write_contacts` writes.
#[no_mangle]
pub extern "C" fn up_max_contacts() -> u32 {
    MAX_CONTACTS as u32
}

/// FNV-1a of the whole body state (determinism checks); 0 without a world.
#[no_mangle]
pub extern "C" fn up_state_hash() -> u64 {
    read(|s| s.world().map_or(0, |w| w.state_hash()))
}

/// Per-stage milliseconds of the last step and its counts, as JSON in the output buffer.
#[no_mangle]
pub extern "C" fn up_stats_json() -> i32 {
    with_state("up_stats_json", State::stats_json)
}

// ---- changing the world ----

/// Adds an upright balloon of model `model` with its mesh frame at (x, y, z), m.
#[no_mangle]
pub extern "C" fn up_add_balloon(x: f32, y: f32, z: f32, color: u32, model: u32) -> i32 {
    with_state("up_add_balloon", |s| {
        s.add_balloon(Vec3::new(x, y, z), color, model)
    })
}

/// Adds a balloon of the first model standing on the floor at (x, z), m.
#[no_mangle]
pub extern "C" fn up_add_balloon_on_floor(x: f32, z: f32, color: u32) -> i32 {
    with_state("up_add_balloon_on_floor", |s| {
        s.add_balloon_on_floor(x, z, color)
    })
}

/// Pops the body at dense `index`: the last body takes its place.
#[no_mangle]
pub extern "C" fn up_remove(index: u32) -> i32 {
    with_state("up_remove", |s| s.remove(index))
}

/// Applies an impulse (N·s) at a world point (m) to the body at dense `index`.
#[no_mangle]
pub extern "C" fn up_apply_impulse(
    index: u32,
    ix: f32,
    iy: f32,
    iz: f32,
    px: f32,
    py: f32,
    pz: f32,
) -> i32 {
    with_state("up_apply_impulse", |s| {
        s.apply_impulse(index, Vec3::new(ix, iy, iz), Vec3::new(px, py, pz))
    })
}

/// Sets the velocity (m/s) and angular velocity (rad/s) of the body at dense `index`.
#[no_mangle]
pub extern "C" fn up_set_velocity(
    index: u32,
    vx: f32,
    vy: f32,
    vz: f32,
    wx: f32,
    wy: f32,
    wz: f32,
) -> i32 {
    with_state("up_set_velocity", |s| {
        s.set_velocity(index, Vec3::new(vx, vy, vz), Vec3::new(wx, wy, wz))
    })
}

/// Holds the body at dense `index` by the world point (x, y, z) on it, m.
#[no_mangle]
pub extern "C" fn up_grab(index: u32, x: f32, y: f32, z: f32) -> i32 {
    with_state("up_grab", |s| s.grab(index, Vec3::new(x, y, z)))
}

/// Moves the grab target, m (no effect when nothing is held).
#[no_mangle]
pub extern "C" fn up_drag_to(x: f32, y: f32, z: f32) -> i32 {
    with_state("up_drag_to", |s| s.drag_to(Vec3::new(x, y, z)))
}

/// Lets go of the held body, which keeps its velocity (a throw).
#[no_mangle]
pub extern "C" fn up_release() -> i32 {
    with_state("up_release", State::release)
}

// ---- static data: room and balloon models ----

#[no_mangle]
pub extern "C" fn up_room_vertex_count() -> u32 {
    read(|s| (s.room_vertices.len() / 3) as u32)
}

/// x, y, z per vertex.
#[no_mangle]
pub extern "C" fn up_room_vertices_ptr() -> *const f32 {
    read_ptr(|s| s.room_vertices.as_ptr())
}

#[no_mangle]
pub extern "C" fn up_room_triangle_count() -> u32 {
    read(|s| (s.room_triangles.len() / 3) as u32)
}

/// Three vertex indices per triangle, counter-clockwise seen from inside the room.
#[no_mangle]
pub extern "C" fn up_room_triangles_ptr() -> *const u32 {
    read_ptr(|s| s.room_triangles.as_ptr())
}

#[no_mangle]
pub extern "C" fn up_model_count() -> u32 {
    read(|s| s.model_count() as u32)
}

/// Writes model `model`'s sphere tree for `up_tree_ptr`: per node cx, cy, cz, radius, depth, leaf.
#[no_mangle]
pub extern "C" fn up_model_tree(model: u32) -> i32 {
    with_state("up_model_tree", |s| s.write_tree(model).map(|_| ()))
}

#[no_mangle]
pub extern "C" fn up_tree_ptr() -> *const f32 {
    read_ptr(|s| s.tree.as_ptr())
}

#[no_mangle]
pub extern "C" fn up_tree_node_count() -> u32 {
    read(|s| (s.tree.len() / TREE_FLOATS) as u32)
}
