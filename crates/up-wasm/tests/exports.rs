//! Every class of bad call through the `extern "C"` exports themselves: no
//! world yet, NaN and infinite numbers, out-of-range indices and points,
//! too fast, past the capacity, bad buffers. Each must answer a status code
//! and a message that names the export, and leave the world as it was.
//! (Each test runs on its own thread, so each starts with no world.)

use up_wasm::*;

const NO_WORLD: i32 = 1;
const BAD_ARGUMENT: i32 = 2;
const OUT_OF_RANGE: i32 = 3;
const FULL: i32 = 4;
const SCENE: i32 = 5;
const ENCODING: i32 = 7;

fn last_error() -> String {
    let ptr = up_last_error_ptr();
    let len = up_last_error_len();
    // SAFETY: the module keeps `len` bytes of UTF-8 at `ptr` until the next error.
    let bytes = unsafe { std::slice::from_raw_parts(ptr, len) };
    String::from_utf8(bytes.to_vec()).expect("the message is UTF-8")
}

fn output() -> String {
    // SAFETY: as for `last_error`, until the next call.
    let bytes = unsafe { std::slice::from_raw_parts(up_output_ptr(), up_output_len()) };
    String::from_utf8(bytes.to_vec()).expect("the output is UTF-8")
}

/// Asserts `code` is `expected` and the message starts with `export`.
#[track_caller]
fn refused(code: i32, expected: i32, export: &str) {
    assert_eq!(code, expected, "{export}: {}", last_error());
    let message = last_error();
    assert!(
        message.starts_with(&format!("{export}: ")),
        "the message names {export}: {message}"
    );
}

/// Loads `json` through the same path as the page (up_alloc, copy, load, up_free).
fn load_json(json: &str) -> i32 {
    let ptr = up_alloc(json.len());
    assert!(!ptr.is_null());
    // SAFETY: `ptr` holds `json.len()` bytes from up_alloc.
    unsafe { ptr.copy_from(json.as_ptr(), json.len()) };
    let code = up_world_from_json(ptr, json.len());
    assert_eq!(up_free(ptr, json.len()), 0);
    code
}

fn poses() -> Vec<f32> {
    assert_eq!(up_write_poses(), 0);
    let n = up_body_count() as usize * POSE_FLOATS;
    // SAFETY: up_write_poses wrote n floats at up_poses_ptr.
    unsafe { std::slice::from_raw_parts(up_poses_ptr(), n) }.to_vec()
}

fn contacts() -> Vec<f32> {
    let n = up_contact_count() as usize * CONTACT_FLOATS;
    // SAFETY: up_write_contacts wrote n floats at up_contacts_ptr.
    unsafe { std::slice::from_raw_parts(up_contacts_ptr(), n) }.to_vec()
}

#[test]
fn before_a_world_every_export_answers_no_world_or_nothing() {
    refused(up_step(1), NO_WORLD, "up_step");
    refused(up_write_poses(), NO_WORLD, "up_write_poses");
    refused(up_write_colors(), NO_WORLD, "up_write_colors");
    refused(up_write_models(), NO_WORLD, "up_write_models");
    refused(up_write_contacts(100), NO_WORLD, "up_write_contacts");
    refused(up_scene_json(), NO_WORLD, "up_scene_json");
    refused(up_world_info_json(), NO_WORLD, "up_world_info_json");
    refused(up_stats_json(), NO_WORLD, "up_stats_json");
    refused(
        up_add_balloon(0.0, 1.0, 0.0, 0, 0),
        NO_WORLD,
        "up_add_balloon",
    );
    refused(
        up_add_balloon_on_floor(0.0, 0.0, 0),
        NO_WORLD,
        "up_add_balloon_on_floor",
    );
    refused(up_remove(0), NO_WORLD, "up_remove");
    refused(
        up_apply_impulse(0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        NO_WORLD,
        "up_apply_impulse",
    );
    refused(
        up_set_velocity(0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        NO_WORLD,
        "up_set_velocity",
    );
    refused(up_grab(0, 0.0, 0.0, 0.0), NO_WORLD, "up_grab");
    refused(up_drag_to(0.0, 1.0, 0.0), NO_WORLD, "up_drag_to");
    refused(up_release(), NO_WORLD, "up_release");
    refused(up_model_tree(0), NO_WORLD, "up_model_tree");
    assert!(last_error().contains("load a scene first"));
    assert_eq!(up_body_count(), 0);
    assert_eq!(up_model_count(), 0);
    assert_eq!(up_room_vertex_count(), 0);
    assert_eq!(up_room_triangle_count(), 0);
    assert_eq!(up_tree_node_count(), 0);
    assert_eq!(up_contact_count(), 0);
    assert_eq!(up_contact_total(), 0);
    assert_eq!(up_state_hash(), 0);
    assert_eq!(up_output_len(), 0);
    for ptr in [
        up_poses_ptr(),
        up_contacts_ptr(),
        up_room_vertices_ptr(),
        up_tree_ptr(),
    ] {
        assert!(!ptr.is_null(), "an empty view, not a null pointer");
    }
    // What needs no world works.
    assert_eq!(up_default_scene_json(), 0);
    assert!(output().contains("balloons"));
    assert_eq!(up_capacity() as usize, CAPACITY);
    assert_eq!(up_max_contacts() as usize, MAX_CONTACTS);
}

#[test]
fn nan_and_infinite_arguments_are_bad_arguments_and_change_nothing() {
    assert_eq!(up_world_default(), 0);
    let hash = up_state_hash();
    let n = up_body_count();
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        refused(
            up_add_balloon(bad, 1.0, 0.0, 0, 0),
            BAD_ARGUMENT,
            "up_add_balloon",
        );
        refused(
            up_add_balloon(0.0, 1.0, bad, 0, 0),
            BAD_ARGUMENT,
            "up_add_balloon",
        );
        refused(
            up_add_balloon_on_floor(0.0, bad, 0),
            BAD_ARGUMENT,
            "up_add_balloon_on_floor",
        );
        refused(
            up_apply_impulse(0, bad, 0.0, 0.0, 0.0, 1.0, 0.0),
            BAD_ARGUMENT,
            "up_apply_impulse",
        );
        refused(
            up_apply_impulse(0, 0.0, 0.0, 0.0, 0.0, bad, 0.0),
            BAD_ARGUMENT,
            "up_apply_impulse",
        );
        refused(
            up_set_velocity(0, 0.0, bad, 0.0, 0.0, 0.0, 0.0),
            BAD_ARGUMENT,
            "up_set_velocity",
        );
        refused(
            up_set_velocity(0, 0.0, 0.0, 0.0, 0.0, 0.0, bad),
            BAD_ARGUMENT,
            "up_set_velocity",
        );
        refused(up_grab(0, 0.0, bad, 0.0), BAD_ARGUMENT, "up_grab");
        refused(up_drag_to(bad, 0.0, 0.0), BAD_ARGUMENT, "up_drag_to");
    }
    assert!(last_error().contains("finite"), "{}", last_error());
    refused(up_step(10_001), BAD_ARGUMENT, "up_step");
    assert_eq!(up_body_count(), n);
    assert_eq!(up_state_hash(), hash, "no refused call changed the world");
    assert_eq!(up_step(1), 0, "the world still steps");
}

#[test]
fn too_fast_is_refused_and_the_old_velocity_kept() {
    assert_eq!(up_world_default(), 0);
    refused(
        up_set_velocity(0, MAX_SPEED * 1.01, 0.0, 0.0, 0.0, 0.0, 0.0),
        BAD_ARGUMENT,
        "up_set_velocity",
    );
    refused(
        up_set_velocity(0, 0.0, 0.0, 0.0, 0.0, MAX_SPIN * 2.0, 0.0),
        BAD_ARGUMENT,
        "up_set_velocity",
    );
    assert_eq!(up_set_velocity(0, 3.0, 0.0, 0.0, 0.0, 0.0, 0.0), 0);
    let hash = up_state_hash();
    let p = poses();
    // A balloon weighs a few grams: 1 N·s would send it at hundreds of m/s.
    refused(
        up_apply_impulse(0, 1.0, 0.0, 0.0, p[0], p[1], p[2]),
        BAD_ARGUMENT,
        "up_apply_impulse",
    );
    assert!(
        last_error().contains("expected at most"),
        "{}",
        last_error()
    );
    assert_eq!(up_state_hash(), hash, "the refused impulse was undone");
    assert_eq!(
        up_apply_impulse(0, 1e-4, 0.0, 0.0, p[0], p[1] + 0.2, p[2]),
        0
    );
    assert_ne!(up_state_hash(), hash, "a gentle impulse is applied");
}

#[test]
fn out_of_range_indices_points_and_models_are_refused() {
    assert_eq!(up_world_default(), 0);
    let n = up_body_count();
    let hash = up_state_hash();
    for index in [n, n + 1, u32::MAX] {
        refused(up_remove(index), OUT_OF_RANGE, "up_remove");
        refused(up_grab(index, 0.0, 1.0, 0.0), OUT_OF_RANGE, "up_grab");
        refused(
            up_set_velocity(index, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            OUT_OF_RANGE,
            "up_set_velocity",
        );
        refused(
            up_apply_impulse(index, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0),
            OUT_OF_RANGE,
            "up_apply_impulse",
        );
    }
    assert!(
        last_error().contains(&format!("there are {n} bodies")),
        "{}",
        last_error()
    );
    refused(up_model_tree(1), OUT_OF_RANGE, "up_model_tree");
    refused(up_model_tree(u32::MAX), OUT_OF_RANGE, "up_model_tree");
    refused(
        up_add_balloon(0.0, 1.0, 0.0, 0, 1),
        OUT_OF_RANGE,
        "up_add_balloon",
    );
    refused(
        up_add_balloon(0.0, 1.0, 0.0, 10_000, 0),
        OUT_OF_RANGE,
        "up_add_balloon",
    );
    // Finite but outside the room.
    refused(
        up_add_balloon(1e30, 1.0, 0.0, 0, 0),
        OUT_OF_RANGE,
        "up_add_balloon",
    );
    refused(
        up_add_balloon(0.0, -1.0, 0.0, 0, 0),
        OUT_OF_RANGE,
        "up_add_balloon",
    );
    refused(
        up_add_balloon_on_floor(50.0, 0.0, 0),
        OUT_OF_RANGE,
        "up_add_balloon_on_floor",
    );
    // A grab point far from the balloon would make a huge lever arm.
    let p = poses();
    refused(up_grab(0, p[0] + 5.0, p[1], p[2]), OUT_OF_RANGE, "up_grab");
    assert_eq!(up_body_count(), n);
    assert_eq!(up_state_hash(), hash, "no refused call changed the world");
    // A drag target outside the room is clamped into it, not refused.
    assert_eq!(up_grab(0, p[0], p[1] + 0.1, p[2]), 0);
    assert_eq!(up_drag_to(1e30, -1e30, 0.0), 0);
    assert_eq!(up_step(5), 0);
    assert!(poses().iter().all(|x| x.is_finite()));
    assert_eq!(up_release(), 0);
}

#[test]
fn adding_past_the_capacity_is_full() {
    let count = CAPACITY - 1;
    let scene = format!(
        r#"{{"room":{{"width":40,"depth":40,"wall_height":8,"ceiling":"flat"}},"balloons":[{{"count":{count}}}]}}"#
    );
    assert_eq!(load_json(&scene), 0, "{}", last_error());
    assert_eq!(up_body_count() as usize, count);
    assert_eq!(up_add_balloon(0.0, 1.0, 0.0, 0, 0), 0);
    refused(up_add_balloon(1.0, 1.0, 0.0, 0, 0), FULL, "up_add_balloon");
    refused(
        up_add_balloon_on_floor(1.0, 1.0, 0),
        FULL,
        "up_add_balloon_on_floor",
    );
    assert!(
        last_error().contains(&CAPACITY.to_string()),
        "{}",
        last_error()
    );
    assert_eq!(up_body_count() as usize, CAPACITY);
    let too_many = scene.replace(&count.to_string(), &(CAPACITY + 1).to_string());
    assert_eq!(load_json(&too_many), FULL);
    assert_eq!(
        up_body_count() as usize,
        CAPACITY,
        "a refused scene keeps the world"
    );
}

#[test]
fn bad_buffers_and_texts_are_refused() {
    assert!(up_alloc(MAX_ALLOC + 1).is_null());
    assert_eq!(last_error().split(':').next(), Some("up_alloc"));
    refused(up_free(std::ptr::null_mut(), 0), OUT_OF_RANGE, "up_free");
    let ptr = up_alloc(4);
    assert_eq!(up_free(ptr, 4), 0);
    refused(up_free(ptr, 4), OUT_OF_RANGE, "up_free");
    // A pointer that up_alloc did not hand out, or a length past the buffer.
    let text = b"{}";
    refused(
        up_world_from_json(text.as_ptr(), 2),
        OUT_OF_RANGE,
        "up_world_from_json",
    );
    let ptr = up_alloc(2);
    refused(
        up_world_from_json(ptr, 3),
        OUT_OF_RANGE,
        "up_world_from_json",
    );
    // SAFETY: `ptr` holds 2 bytes from up_alloc.
    unsafe { ptr.copy_from([0xff, 0xfe].as_ptr(), 2) };
    refused(up_world_from_toml(ptr, 2), ENCODING, "up_world_from_toml");
    assert_eq!(up_free(ptr, 2), 0);
    // Malformed and invalid scenes name the scene and the key instead.
    assert_eq!(load_json(r#"{"room":{"width":-2}}"#), SCENE);
    assert!(last_error().contains("room.width"), "{}", last_error());
    assert_eq!(load_json("{not json"), SCENE);
    assert_eq!(up_body_count(), 0, "still no world");
    // Holding too much at once is an error, not an out-of-memory trap.
    let held: Vec<_> = (0..MAX_LIVE / MAX_ALLOC)
        .map(|_| up_alloc(MAX_ALLOC))
        .collect();
    assert!(held.iter().all(|p| !p.is_null()));
    assert!(up_alloc(1).is_null());
    let message = last_error();
    assert!(
        message.starts_with("up_alloc: ") && message.contains("up_free"),
        "{message}"
    );
    for p in held {
        assert_eq!(up_free(p, MAX_ALLOC), 0);
    }
}

#[test]
fn two_touching_balloons_give_contacts_with_unit_normals() {
    // No gravity or buoyancy to speak of: the two stay together for a step.
    assert_eq!(
        load_json(r#"{"balloons":[{"count":1}]}"#),
        0,
        "{}",
        last_error()
    );
    assert_eq!(up_remove(0), 0);
    assert_eq!(up_add_balloon(0.0, 1.5, 0.0, 0, 0), 0);
    assert_eq!(up_model_tree(0), 0);
    let nodes = up_tree_node_count() as usize;
    // SAFETY: up_model_tree wrote `nodes` nodes at up_tree_ptr.
    let tree = unsafe { std::slice::from_raw_parts(up_tree_ptr(), nodes * TREE_FLOATS) };
    let root_radius = tree[3];
    // Half the balloon's width along x: the widest leaf sphere.
    let half_width = tree
        .chunks(TREE_FLOATS)
        .filter(|n| n[5] == 1.0)
        .map(|n| n[0].abs() + n[3])
        .fold(0.0, f32::max);
    // Side by side, overlapping by a few per cent of their width.
    let gap = 1.94 * half_width;
    assert_eq!(up_add_balloon(gap, 1.5, 0.0, 1, 0), 0);
    assert_eq!(up_step(1), 0);
    assert_eq!(up_write_contacts(u32::MAX), 0);
    let c = contacts();
    let count = up_contact_count() as usize;
    assert!(count >= 1, "touching balloons touch");
    assert_eq!(up_contact_total() as usize, count);
    let between = c
        .chunks(CONTACT_FLOATS)
        .filter(|k| k[7] == 1.0)
        .collect::<Vec<_>>();
    assert!(!between.is_empty(), "a balloon-balloon contact");
    for k in c.chunks(CONTACT_FLOATS) {
        let normal = (k[3] * k[3] + k[4] * k[4] + k[5] * k[5]).sqrt();
        assert!(
            (normal - 1.0).abs() < 1e-3,
            "unit normal, found length {normal}"
        );
        assert!(k[6].abs() < root_radius, "separation {} m", k[6]);
    }
    for k in between {
        assert!(
            k[0] > 0.0 && k[0] < 1.9 * root_radius,
            "between the two: x = {}",
            k[0]
        );
        assert!(
            k[3].abs() > 0.5,
            "the normal points along x: {:?}",
            &k[3..6]
        );
    }
    // The cap bounds what is written, not what is counted.
    assert_eq!(up_write_contacts(0), 0);
    assert_eq!(up_contact_count(), 0);
    assert_eq!(up_contact_total() as usize, count);
}
