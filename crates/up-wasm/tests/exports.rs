//! Every class of bad call through the exported `Engine` itself: no world
//! yet, NaN and infinite numbers, out-of-range indices and points, too fast,
//! past the capacity, bad scenes. Each must answer an error of the right
//! kind whose message names the method, and leave the world as it was. The
//! same calls in the browser throw these errors as JS `Error`s.

use up_wasm::*;

/// Asserts `result` is refused with `kind` and a message naming `method`; returns the message.
#[track_caller]
fn refused<T: std::fmt::Debug>(result: Result<T, CallError>, kind: &str, method: &str) -> String {
    let e = result.expect_err(method);
    assert_eq!(e.kind, kind, "{method}: {}", e.message);
    assert!(
        e.message.starts_with(&format!("{method}: ")),
        "the message names {method}: {}",
        e.message
    );
    e.message
}

fn default_engine() -> Engine {
    let mut e = Engine::new();
    e.load_default_scene().unwrap();
    e
}

fn poses(e: &mut Engine) -> Vec<f32> {
    let n = e.write_poses().unwrap() as usize;
    assert_eq!(n, e.body_count() as usize * POSE_FLOATS);
    // SAFETY: write_poses wrote n floats at poses_ptr, valid until the next call.
    unsafe { std::slice::from_raw_parts(e.poses_ptr(), n) }.to_vec()
}

#[test]
fn before_a_world_every_method_answers_no_world_or_nothing() {
    let mut e = Engine::new();
    let m = refused(e.step(1), "NoWorld", "step");
    assert!(m.contains("load a scene first"), "{m}");
    refused(e.write_poses(), "NoWorld", "write_poses");
    refused(
        e.write_colors_and_models(),
        "NoWorld",
        "write_colors_and_models",
    );
    refused(e.write_contacts(100), "NoWorld", "write_contacts");
    refused(e.scene_json(), "NoWorld", "scene_json");
    refused(e.world_info(), "NoWorld", "world_info");
    refused(e.stats(), "NoWorld", "stats");
    refused(e.add_balloon(0.0, 1.0, 0.0, 0, 0), "NoWorld", "add_balloon");
    refused(
        e.add_balloon_on_floor(0.0, 0.0, 0),
        "NoWorld",
        "add_balloon_on_floor",
    );
    refused(e.remove(0), "NoWorld", "remove");
    refused(
        e.apply_impulse(0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        "NoWorld",
        "apply_impulse",
    );
    refused(
        e.set_velocity(0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        "NoWorld",
        "set_velocity",
    );
    refused(e.grab(0, 0.0, 0.0, 0.0), "NoWorld", "grab");
    refused(e.drag_to(0.0, 1.0, 0.0), "NoWorld", "drag_to");
    refused(e.release(), "NoWorld", "release");
    refused(e.write_model_tree(0), "NoWorld", "write_model_tree");
    refused(e.write_model_mesh(0), "NoWorld", "write_model_mesh");
    refused(e.advance(1.0, 10), "NoWorld", "advance");
    refused(e.write_body_scales(), "NoWorld", "write_body_scales");
    refused(e.air_temperature_c(), "NoWorld", "air_temperature_c");
    refused(e.float_counts(), "NoWorld", "float_counts");
    assert_eq!(e.sim_time(), 0.0);
    assert_eq!(e.body_count(), 0);
    assert_eq!(e.model_count(), 0);
    assert_eq!(e.room_vertices_len(), 0);
    assert_eq!(e.room_triangles_len(), 0);
    assert_eq!(e.mesh_index_len(), 0);
    assert_eq!(e.contact_total(), 0);
    assert_eq!(e.state_hash(), 0);
    for ptr in [
        e.poses_ptr(),
        e.contacts_ptr(),
        e.room_vertices_ptr(),
        e.tree_ptr(),
        e.body_scales_ptr(),
        e.mesh_positions_ptr(),
        e.mesh_normals_ptr(),
    ] {
        assert!(!ptr.is_null(), "an empty view, not a null pointer");
    }
    // What needs no world works.
    assert!(default_scene_json().unwrap().contains("balloons"));
}

#[test]
fn nan_and_infinite_arguments_are_bad_arguments_and_change_nothing() {
    let mut e = default_engine();
    let hash = e.state_hash();
    let n = e.body_count();
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        refused(
            e.add_balloon(bad, 1.0, 0.0, 0, 0),
            "BadArgument",
            "add_balloon",
        );
        refused(
            e.add_balloon(0.0, 1.0, bad, 0, 0),
            "BadArgument",
            "add_balloon",
        );
        refused(
            e.add_balloon_on_floor(0.0, bad, 0),
            "BadArgument",
            "add_balloon_on_floor",
        );
        refused(
            e.apply_impulse(0, bad, 0.0, 0.0, 0.0, 1.0, 0.0),
            "BadArgument",
            "apply_impulse",
        );
        refused(
            e.apply_impulse(0, 0.0, 0.0, 0.0, 0.0, bad, 0.0),
            "BadArgument",
            "apply_impulse",
        );
        refused(
            e.set_velocity(0, 0.0, bad, 0.0, 0.0, 0.0, 0.0),
            "BadArgument",
            "set_velocity",
        );
        refused(
            e.set_velocity(0, 0.0, 0.0, 0.0, 0.0, 0.0, bad),
            "BadArgument",
            "set_velocity",
        );
        refused(e.grab(0, 0.0, bad, 0.0), "BadArgument", "grab");
        let m = refused(e.drag_to(bad, 0.0, 0.0), "BadArgument", "drag_to");
        assert!(m.contains("finite"), "{m}");
        refused(e.advance(f64::from(bad), 10), "BadArgument", "advance");
    }
    refused(e.advance(MAX_ADVANCE_S + 1.0, 10), "BadArgument", "advance");
    refused(e.advance(1.0, 0), "BadArgument", "advance");
    assert_eq!(e.sim_time(), 0.0, "no refused advance moved the clock");
    refused(e.step(MAX_STEPS_PER_CALL + 1), "BadArgument", "step");
    assert_eq!(e.body_count(), n);
    assert_eq!(e.state_hash(), hash, "no refused call changed the world");
    e.step(1).expect("the world still steps");
}

#[test]
fn too_fast_is_refused_and_the_old_velocity_kept() {
    let mut e = default_engine();
    refused(
        e.set_velocity(0, MAX_SPEED * 1.01, 0.0, 0.0, 0.0, 0.0, 0.0),
        "BadArgument",
        "set_velocity",
    );
    refused(
        e.set_velocity(0, 0.0, 0.0, 0.0, 0.0, MAX_SPIN * 2.0, 0.0),
        "BadArgument",
        "set_velocity",
    );
    e.set_velocity(0, 3.0, 0.0, 0.0, 0.0, 0.0, 0.0).unwrap();
    let hash = e.state_hash();
    let p = poses(&mut e);
    // A balloon weighs a few grams: 1 N·s would send it at hundreds of m/s.
    let m = refused(
        e.apply_impulse(0, 1.0, 0.0, 0.0, p[0], p[1], p[2]),
        "BadArgument",
        "apply_impulse",
    );
    assert!(m.contains("expected at most"), "{m}");
    assert_eq!(e.state_hash(), hash, "the refused impulse was undone");
    e.apply_impulse(0, 1e-4, 0.0, 0.0, p[0], p[1] + 0.2, p[2])
        .unwrap();
    assert_ne!(e.state_hash(), hash, "a gentle impulse is applied");
}

#[test]
fn out_of_range_indices_points_and_models_are_refused() {
    let mut e = default_engine();
    let n = e.body_count();
    let hash = e.state_hash();
    for index in [n, n + 1, u32::MAX] {
        refused(e.remove(index), "OutOfRange", "remove");
        refused(e.grab(index, 0.0, 1.0, 0.0), "OutOfRange", "grab");
        refused(
            e.set_velocity(index, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
            "OutOfRange",
            "set_velocity",
        );
        let m = refused(
            e.apply_impulse(index, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0),
            "OutOfRange",
            "apply_impulse",
        );
        assert!(m.contains(&format!("there are {n} bodies")), "{m}");
    }
    refused(e.write_model_tree(1), "OutOfRange", "write_model_tree");
    refused(
        e.write_model_tree(u32::MAX),
        "OutOfRange",
        "write_model_tree",
    );
    refused(e.write_model_mesh(1), "OutOfRange", "write_model_mesh");
    refused(
        e.add_balloon(0.0, 1.0, 0.0, 0, 1),
        "OutOfRange",
        "add_balloon",
    );
    refused(
        e.add_balloon(0.0, 1.0, 0.0, 10_000, 0),
        "OutOfRange",
        "add_balloon",
    );
    // Finite but outside the room.
    refused(
        e.add_balloon(1e30, 1.0, 0.0, 0, 0),
        "OutOfRange",
        "add_balloon",
    );
    refused(
        e.add_balloon(0.0, -1.0, 0.0, 0, 0),
        "OutOfRange",
        "add_balloon",
    );
    refused(
        e.add_balloon_on_floor(50.0, 0.0, 0),
        "OutOfRange",
        "add_balloon_on_floor",
    );
    // A grab point far from the balloon would make a huge lever arm.
    let p = poses(&mut e);
    refused(e.grab(0, p[0] + 5.0, p[1], p[2]), "OutOfRange", "grab");
    assert_eq!(e.body_count(), n);
    assert_eq!(e.state_hash(), hash, "no refused call changed the world");
    // A drag target outside the room is clamped into it, not refused.
    e.grab(0, p[0], p[1] + 0.1, p[2]).unwrap();
    e.drag_to(1e30, -1e30, 0.0).unwrap();
    e.step(5).unwrap();
    assert!(poses(&mut e).iter().all(|x| x.is_finite()));
    e.release().unwrap();
}

#[test]
fn adding_past_the_capacity_is_full() {
    let count = CAPACITY - 1;
    let scene = format!(
        r#"{{"room":{{"width":40,"depth":40,"wall_height":8,"ceiling":"flat"}},"balloons":[{{"count":{count}}}]}}"#
    );
    let mut e = Engine::new();
    e.load_scene_json(&scene).unwrap();
    assert_eq!(e.body_count() as usize, count);
    e.add_balloon(0.0, 1.0, 0.0, 0, 0).unwrap();
    refused(e.add_balloon(1.0, 1.0, 0.0, 0, 0), "Full", "add_balloon");
    let m = refused(
        e.add_balloon_on_floor(1.0, 1.0, 0),
        "Full",
        "add_balloon_on_floor",
    );
    assert!(m.contains(&CAPACITY.to_string()), "{m}");
    assert_eq!(e.body_count() as usize, CAPACITY);
    let too_many = scene.replace(&count.to_string(), &(CAPACITY + 1).to_string());
    assert_eq!(e.load_scene_json(&too_many).unwrap_err().kind, "Full");
    assert_eq!(validate_scene(&too_many).unwrap_err().kind, "Full");
    assert_eq!(
        e.body_count() as usize,
        CAPACITY,
        "a refused scene keeps the world"
    );
}

#[test]
fn bad_scenes_are_refused_alike_by_validate_and_load() {
    let mut e = Engine::new();
    for (scene, key) in [
        (r#"{"room":{"width":-2}}"#, "room.width"),
        (
            r#"{"balloons":[{"colors":["gold"]}]}"#,
            "balloons[0].colors[0]",
        ),
        (r#"{"room":{"mesh":"room.obj"}}"#, "room.mesh"),
        (r#"{"sim":{"substeps":0}}"#, "sim.substeps"),
        ("{not json", ""),
        ("", ""),
    ] {
        let checked = validate_scene(scene).expect_err(scene);
        let loaded = e.load_scene_json(scene).expect_err(scene);
        assert_eq!(
            checked, loaded,
            "validate_scene answers what loading answers"
        );
        assert_eq!(checked.kind, "Scene");
        assert!(
            checked.message.starts_with("scene"),
            "names the scene: {}",
            checked.message
        );
        assert!(
            checked.message.contains(key),
            "names {key}: {}",
            checked.message
        );
        assert_eq!(e.body_count(), 0, "still no world");
    }
    validate_scene(r##"{"balloons":[{"count":3,"colors":["white","#10a0ff"]}]}"##).unwrap();
    validate_scene(&default_scene_json().unwrap()).unwrap();
    let toml = e.load_scene_toml("[room]\nwidth = \"wide\"\n").unwrap_err();
    assert_eq!(toml.kind, "Scene");
    assert!(toml.message.contains("room.width"), "{}", toml.message);
}

#[test]
fn every_named_colour_is_accepted_and_the_constants_are_the_crate_s() {
    let c = constants();
    assert_eq!(c.pose_stride as usize, POSE_FLOATS);
    assert_eq!(c.contact_stride as usize, CONTACT_FLOATS);
    assert_eq!(c.tree_stride as usize, TREE_FLOATS);
    assert_eq!(c.capacity as usize, CAPACITY);
    assert_eq!(c.max_contacts as usize, MAX_CONTACTS);
    assert_eq!(c.error_kinds, ERROR_KINDS.map(String::from).to_vec());
    assert!(c.colors.len() >= 6);
    let names: Vec<&str> = c.colors.iter().map(|n| n.name.as_str()).collect();
    let scene = format!(
        r#"{{"balloons":[{{"count":{},"colors":{}}}]}}"#,
        names.len(),
        serde_json_list(&names)
    );
    let mut e = Engine::new();
    e.load_scene_json(&scene).unwrap();
    let info = e.world_info().unwrap();
    assert_eq!(info.color_names, names);
    let rgb: Vec<[f32; 3]> = c.colors.iter().map(|n| n.rgb).collect();
    assert_eq!(
        info.colors, rgb,
        "the palette the world draws is the one constants() lists"
    );
    for d in c.scene.default_colors {
        assert!(
            names.contains(&d.as_str()),
            "the default colour {d} is a named one"
        );
    }
}

fn serde_json_list(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
    format!("[{}]", quoted.join(","))
}

#[test]
fn two_touching_balloons_give_contacts_with_unit_normals() {
    let mut e = Engine::new();
    e.load_scene_json(r#"{"balloons":[{"count":1}]}"#).unwrap();
    e.remove(0).unwrap();
    e.add_balloon(0.0, 1.5, 0.0, 0, 0).unwrap();
    let nodes = e.write_model_tree(0).unwrap() as usize;
    // SAFETY: write_model_tree wrote `nodes` nodes at tree_ptr.
    let tree = unsafe { std::slice::from_raw_parts(e.tree_ptr(), nodes * TREE_FLOATS) }.to_vec();
    let root_radius = tree[3];
    // Half the balloon's width along x: the widest leaf sphere.
    let half_width = tree
        .chunks(TREE_FLOATS)
        .filter(|n| n[5] == 1.0)
        .map(|n| n[0].abs() + n[3])
        .fold(0.0, f32::max);
    // Side by side, overlapping by a few per cent of their width.
    e.add_balloon(1.94 * half_width, 1.5, 0.0, 1, 0).unwrap();
    e.step(1).unwrap();
    let count = e.write_contacts(u32::MAX).unwrap() as usize;
    // SAFETY: write_contacts wrote `count` contacts at contacts_ptr.
    let c =
        unsafe { std::slice::from_raw_parts(e.contacts_ptr(), count * CONTACT_FLOATS) }.to_vec();
    assert!(count >= 1, "touching balloons touch");
    assert_eq!(e.contact_total() as usize, count);
    let between: Vec<_> = c.chunks(CONTACT_FLOATS).filter(|k| k[7] == 1.0).collect();
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
    assert_eq!(e.write_contacts(0).unwrap(), 0);
    assert_eq!(e.contact_total() as usize, count);
}
