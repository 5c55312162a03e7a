use super::*;

fn default_state() -> State {
    let mut s = State::default();
    s.load_default().expect("the default scene builds");
    s
}

#[test]
fn nothing_works_before_a_world_is_loaded() {
    let mut s = State::default();
    assert_eq!(s.step(1), Err(WasmError::NoWorld));
    assert_eq!(s.write_poses(), Err(WasmError::NoWorld));
    assert_eq!(s.add_balloon_on_floor(0.0, 0.0, 0), Err(WasmError::NoWorld));
    assert_eq!(s.remove(0).unwrap_err().kind(), WasmError::NoWorld.kind());
    assert_eq!(s.body_count(), 0);
}

#[test]
fn default_scene_writes_one_pose_per_balloon_and_balloons_rise() {
    let mut s = default_state();
    let n = s.body_count();
    assert_eq!(n, Scene::default().total_balloons() as usize);
    s.write_poses().unwrap();
    assert_eq!(s.poses.len(), n * POSE_FLOATS);
    let mean_y = |p: &[f32]| p.chunks(POSE_FLOATS).map(|c| c[1]).sum::<f32>() / n as f32;
    let before = mean_y(&s.poses);
    s.step(60).unwrap();
    s.write_poses().unwrap();
    assert!(mean_y(&s.poses) > before + 0.2, "balloons rise in a second");
    for q in s.poses.chunks(POSE_FLOATS) {
        let len = (q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]).sqrt();
        assert!((len - 1.0).abs() < 1e-3);
    }
}

#[test]
fn colours_and_models_follow_the_scene() {
    let mut s = default_state();
    s.write_user_data().unwrap();
    let palette = s.loaded.as_ref().unwrap().built.colors.len() as u32;
    assert_eq!(s.colors.len(), s.body_count());
    assert!(s.colors.iter().all(|&c| c < palette));
    assert!(s.models.iter().all(|&m| m == 0));
    let info = s.world_info().unwrap();
    assert_eq!(info.colors.len(), palette as usize);
    assert_eq!(info.color_names[0], "red");
    assert_eq!(info.diameters, vec![up_scene::scene::DEFAULT_DIAMETER_M]);
}

#[test]
fn placing_on_the_floor_adds_one_upright_balloon_at_that_spot() {
    let mut s = default_state();
    let n = s.body_count();
    s.add_balloon_on_floor(1.25, -0.75, 2).unwrap();
    assert_eq!(s.body_count(), n + 1);
    s.write_poses().unwrap();
    let p = &s.poses[n * POSE_FLOATS..];
    assert_eq!((p[0], p[2]), (1.25, -0.75));
    assert!(
        p[1] > 0.0 && p[1] < 0.5,
        "just above the floor, found y = {}",
        p[1]
    );
    s.write_user_data().unwrap();
    assert_eq!(s.colors[n], 2);
}

#[test]
fn bad_arguments_are_errors_not_panics() {
    let mut s = default_state();
    let n = s.body_count() as u32;
    assert_eq!(
        s.add_balloon_on_floor(f32::NAN, 0.0, 0).unwrap_err().kind(),
        "BadArgument"
    );
    assert_eq!(
        s.add_balloon_on_floor(100.0, 0.0, 0).unwrap_err().kind(),
        "OutOfRange"
    );
    assert_eq!(
        s.add_balloon(Vec3::new(0.0, 1.0, 0.0), 999, 0)
            .unwrap_err()
            .kind(),
        "OutOfRange"
    );
    assert_eq!(
        s.add_balloon(Vec3::new(0.0, 1.0, 0.0), 0, 7)
            .unwrap_err()
            .kind(),
        "OutOfRange"
    );
    assert_eq!(s.remove(n).unwrap_err().kind(), "OutOfRange");
    assert_eq!(s.grab(n + 5, Vec3::ZERO).unwrap_err().kind(), "OutOfRange");
    assert_eq!(
        s.grab(0, Vec3::new(f32::INFINITY, 0.0, 0.0))
            .unwrap_err()
            .kind(),
        "BadArgument"
    );
    assert_eq!(
        s.drag_to(Vec3::new(0.0, f32::NAN, 0.0)).unwrap_err().kind(),
        "BadArgument"
    );
    assert_eq!(
        s.set_velocity(0, Vec3::NAN, Vec3::ZERO).unwrap_err().kind(),
        "BadArgument"
    );
    assert_eq!(
        s.apply_impulse(0, Vec3::ZERO, Vec3::NAN)
            .unwrap_err()
            .kind(),
        "BadArgument"
    );
    assert_eq!(s.step(1_000_000).unwrap_err().kind(), "BadArgument");
    assert_eq!(s.write_tree(3).unwrap_err().kind(), "OutOfRange");
    assert_eq!(s.body_count() as u32, n, "no error changed the world");
}

#[test]
fn popping_removes_exactly_one_body() {
    let mut s = default_state();
    let n = s.body_count();
    s.remove(0).unwrap();
    s.remove((n - 2) as u32).unwrap();
    assert_eq!(s.body_count(), n - 2);
    s.step(2).unwrap();
}

#[test]
fn grab_drag_and_release_move_the_balloon() {
    let mut s = default_state();
    s.write_poses().unwrap();
    let start = Vec3::new(s.poses[0], s.poses[1], s.poses[2]);
    s.grab(0, start).unwrap();
    s.drag_to(start + Vec3::new(0.0, 0.0, 1.0)).unwrap();
    s.step(30).unwrap();
    s.release().unwrap();
    s.write_poses().unwrap();
    // The body at index 0 may have moved in dense order only if something was removed; nothing was.
    assert!(
        s.poses[2] > start.z + 0.3,
        "dragged towards +z, found z = {}",
        s.poses[2]
    );
    s.release().unwrap();
    s.drag_to(Vec3::ZERO).unwrap();
}

#[test]
fn scenes_load_from_json_and_toml_and_bad_ones_keep_the_old_world() {
    let mut s = default_state();
    s.load_json(r##"{"balloons":[{"count":7,"colors":["#10a0ff","red"]}]}"##)
        .unwrap();
    assert_eq!(s.body_count(), 7);
    s.load_toml("[[balloons]]\ncount = 3\n").unwrap();
    assert_eq!(s.body_count(), 3);
    let err = s.load_json(r#"{"room":{"width":-2}}"#).unwrap_err();
    assert_eq!(err.kind(), "Scene");
    assert!(err.to_string().contains("room.width"), "{err}");
    assert_eq!(s.load_json("{not json").unwrap_err().kind(), "Scene");
    assert_eq!(
        s.load_json(r#"{"room":{"mesh":"room.obj"}}"#)
            .unwrap_err()
            .kind(),
        "Scene"
    );
    let too_many = format!(
        r#"{{"room":{{"width":100,"depth":100}},"balloons":[{{"count":{}}}]}}"#,
        CAPACITY + 1
    );
    assert_eq!(s.load_json(&too_many).unwrap_err().kind(), "Full");
    assert_eq!(
        s.body_count(),
        3,
        "a refused scene leaves the world as it was"
    );
    assert!(s.scene_json().unwrap().contains("\"count\": 3"));
}

#[test]
fn trees_room_and_stats_are_readable() {
    let mut s = default_state();
    let nodes = s.write_tree(0).unwrap();
    assert!(nodes >= 2);
    assert_eq!(s.tree.len(), nodes * TREE_FLOATS);
    assert_eq!(s.tree[4], 0.0, "the root has depth 0");
    assert!(s.tree.chunks(TREE_FLOATS).skip(1).all(|n| n[4] >= 1.0));
    assert!(
        s.tree.chunks(TREE_FLOATS).any(|n| n[5] == 1.0),
        "some node is a leaf"
    );
    assert!(!s.room_vertices.is_empty() && s.room_triangles.len().is_multiple_of(3));
    let nv = (s.room_vertices.len() / 3) as u32;
    assert!(s.room_triangles.iter().all(|&i| i < nv));
    s.step(1).unwrap();
    let stats = s.stats().unwrap();
    assert_eq!(stats.stages.last().map(|st| st.0.as_str()), Some("total"));
}

#[test]
fn stage_times_are_averaged_over_the_steps_since_the_last_read() {
    let mut s = default_state();
    s.step(5).unwrap();
    let first = s.stats().unwrap();
    assert!(first.stages.iter().any(|st| st.0 == "solve"), "{first:?}");
    assert_eq!(s.stage_sums.steps(), 0, "reading resets the sums");
    // No step since: the last step's own times are reported.
    let again = s.stats().unwrap();
    assert_eq!(again.bodies, 50);
    assert_eq!(again.stages.len(), first.stages.len());
}

#[test]
fn a_ribbon_length_ties_one_ribbon_to_every_balloon_and_to_those_added() {
    let mut s = default_state();
    let n = s.body_count();
    s.apply_live(LiveSetting::RibbonLength(1.5)).unwrap();
    assert_eq!(s.ribbon_count(), n);
    assert_eq!(s.ribbon_length(), 1.5);
    s.write_ribbon_tables().unwrap();
    s.write_ribbon_points().unwrap();
    let t = &s.ribbons;
    assert_eq!(t.offsets.len(), n + 1);
    assert_eq!(t.offsets[0], 0);
    assert_eq!(*t.offsets.last().unwrap() as usize * 3, t.points.len());
    // Each ribbon's first point is its balloon's knot: below the balloon's centre, near it.
    s.write_poses().unwrap();
    let mut bodies = s.ribbons.bodies.clone();
    bodies.sort_unstable();
    assert_eq!(
        bodies,
        (0..n as u32).collect::<Vec<_>>(),
        "one ribbon per balloon"
    );
    for (r, &b) in s.ribbons.bodies.iter().enumerate() {
        let first = s.ribbons.offsets[r] as usize * 3;
        let knot = Vec3::from_slice(&s.ribbons.points[first..first + 3]);
        let pose = Vec3::from_slice(&s.poses[b as usize * POSE_FLOATS..][..3]);
        assert!(
            knot.y < pose.y && knot.distance(pose) < 0.4,
            "knot {knot} of balloon at {pose}"
        );
        let count = (s.ribbons.offsets[r + 1] - s.ribbons.offsets[r]) as usize;
        let points: Vec<Vec3> = s.ribbons.points[first..first + 3 * count]
            .chunks(3)
            .map(Vec3::from_slice)
            .collect();
        let along: f32 = points.windows(2).map(|p| p[0].distance(p[1])).sum();
        assert!((along - 1.5).abs() < 0.015, "ribbon {r} is {along} m long");
    }
    assert!(s.ribbons.colors.iter().all(|&c| c <= 0xffffff));
    s.add_balloon_on_floor(0.5, 0.5, 0).unwrap();
    assert_eq!(
        s.ribbon_count(),
        n + 1,
        "a balloon added later gets its ribbon"
    );
    s.step(30).unwrap();
    let stats = s.stats().unwrap();
    assert_eq!(stats.ribbons, n as u32 + 1);
    let stretch = s.world().unwrap().ribbon_max_stretch();
    assert_eq!(stats.ribbon_max_stretch, stretch);
    assert!(stretch.is_finite() && stretch >= 0.0, "{stretch}");
    s.apply_live(LiveSetting::RibbonLength(0.0)).unwrap();
    assert_eq!(s.ribbon_count(), 0);
    s.add_balloon_on_floor(-0.5, 0.5, 0).unwrap();
    assert_eq!(s.ribbon_count(), 0, "length 0: no ribbon");
}

#[test]
fn a_bad_ribbon_length_or_grab_is_refused_and_changes_nothing() {
    let mut s = default_state();
    s.apply_live(LiveSetting::RibbonLength(1.0)).unwrap();
    let hash = s.world().unwrap().state_hash();
    for bad in [f32::NAN, -1.0, crate::ribbons::MAX_RIBBON_LENGTH_M + 1.0] {
        assert!(
            s.apply_live(LiveSetting::RibbonLength(bad)).is_err(),
            "{bad}"
        );
    }
    let ribbons = s.ribbon_count() as u32;
    assert_eq!(
        s.grab_ribbon(ribbons, 1, Vec3::ONE).unwrap_err().kind(),
        "OutOfRange"
    );
    assert_eq!(
        s.grab_ribbon(0, 0, Vec3::ONE).unwrap_err().kind(),
        "OutOfRange"
    );
    assert_eq!(
        s.grab_ribbon(0, 17, Vec3::ONE).unwrap_err().kind(),
        "OutOfRange"
    );
    assert_eq!(
        s.grab_ribbon(0, 16, Vec3::NAN).unwrap_err().kind(),
        "BadArgument"
    );
    assert_eq!(s.world().unwrap().state_hash(), hash);
    assert_eq!(s.ribbon_length(), 1.0);
}

#[test]
fn pulling_a_ribbon_end_down_brings_its_balloon_down() {
    let mut s = default_state();
    s.step(600).unwrap(); // the balloons reach the ceiling
    s.apply_live(LiveSetting::RibbonLength(1.0)).unwrap();
    s.step(60).unwrap();
    s.write_ribbon_tables().unwrap();
    let body = s.ribbons.bodies[0] as usize;
    let end = s.ribbons.offsets[1] - s.ribbons.offsets[0] - 1;
    s.write_poses().unwrap();
    let before = s.poses[body * POSE_FLOATS + 1];
    s.write_ribbon_points().unwrap();
    let tip = Vec3::from_slice(&s.ribbons.points[end as usize * 3..][..3]);
    s.grab_ribbon(0, end, tip).unwrap();
    s.drag_to(Vec3::new(tip.x, 0.3, tip.z)).unwrap();
    s.step(120).unwrap();
    s.write_poses().unwrap();
    let after = s.poses[body * POSE_FLOATS + 1];
    assert!(
        after < before - 1.0,
        "the balloon came down from {before} to {after} m"
    );
    s.release().unwrap();
    s.step(1).unwrap();
}

#[test]
fn popping_a_balloon_takes_its_ribbon_and_the_tables_follow() {
    let mut s = default_state();
    s.apply_live(LiveSetting::RibbonLength(0.5)).unwrap();
    let n = s.body_count();
    s.remove(0).unwrap();
    assert_eq!(s.ribbon_count(), n - 1);
    s.write_ribbon_tables().unwrap();
    assert!(s.ribbons.bodies.iter().all(|&b| (b as usize) < n - 1));
}

#[test]
fn the_scene_ties_its_ribbons_and_the_page_length_is_written_into_the_scene() {
    let mut s = State::default();
    let text = r##"{"balloons": [
        {"count": 3, "ribbon": {"length_m": 0.9, "segments": 6, "color": "#ff00ff"}},
        {"count": 2}
    ]}"##;
    s.load_json(text).unwrap();
    assert_eq!(s.ribbon_count(), 3, "only the group with a ribbon table");
    assert_eq!(s.ribbon_length(), 0.9);
    s.write_ribbon_tables().unwrap();
    assert!(s.ribbons.colors.iter().all(|&c| c == 0xff00ff));
    assert_eq!(s.ribbons.weights, vec![0.0; 3]);
    assert!(s.ribbons.offsets.windows(2).all(|w| w[1] - w[0] == 7));
    // A balloon added to the first model gets that group's ribbon.
    s.add_balloon(Vec3::new(0.0, 1.0, 0.0), 0, 0).unwrap();
    assert_eq!(s.ribbon_count(), 4);
    s.add_balloon(Vec3::new(0.5, 1.0, 0.0), 0, 1).unwrap();
    assert_eq!(s.ribbon_count(), 4, "the second group has none");

    s.apply_live(LiveSetting::RibbonLength(1.25)).unwrap();
    assert_eq!(s.ribbon_count(), s.body_count(), "every group gets one");
    let scene = Scene::from_json_str(&s.scene_json().unwrap(), "t").unwrap();
    let ribbons: Vec<_> = scene
        .balloons
        .iter()
        .map(|g| g.ribbon.clone().unwrap())
        .collect();
    assert_eq!(ribbons[0].length_m, 1.25);
    assert_eq!(ribbons[0].color, "#ff00ff", "its other keys kept");
    assert_eq!(ribbons[0].segments, 6);
    assert_eq!(ribbons[1].length_m, 1.25);
    // What the page shares is a scene the engine builds the same.
    let again = s.scene_json().unwrap();
    let mut t = State::default();
    t.load_json(&again).unwrap();
    assert_eq!(t.ribbon_count(), t.body_count());

    s.apply_live(LiveSetting::RibbonLength(0.0)).unwrap();
    assert_eq!(s.ribbon_count(), 0);
    let scene = Scene::from_json_str(&s.scene_json().unwrap(), "t").unwrap();
    assert_eq!(scene.balloons[0].ribbon.as_ref().unwrap().length_m, 0.0);
}

#[test]
fn each_ribbon_says_the_weight_at_its_end() {
    let mut s = State::default();
    let text = r##"{"balloons": [
        {"count": 2, "ribbon": {"length_m": 1.0, "weight_g": 12}},
        {"count": 1, "ribbon": {"length_m": 1.0}}
    ]}"##;
    s.load_json(text).unwrap();
    s.write_ribbon_tables().unwrap();
    let mut weights = s.ribbons.weights.clone();
    weights.sort_by(f32::total_cmp);
    assert_eq!(weights, vec![0.0, 0.012, 0.012]);
    assert_eq!(s.ribbons.weights.len(), s.ribbons.bodies.len());
}
