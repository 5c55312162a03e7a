use super::*;
use crate::build::build_world;

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "furniture.toml").unwrap_or_else(|e| panic!("{e}"))
}

/// The message of building `text`, which must fail.
fn refused(text: &str) -> (SceneError, String) {
    let e = match Scene::from_toml_str(text, "furniture.toml") {
        Ok(scene) => build_world(&scene).err().expect("refused"),
        Err(e) => e,
    };
    let message = e.to_string();
    (e, message)
}

/// A temporary folder with `name` holding `obj`, and the scene text that
/// stands it at the room's centre.
fn with_mesh(name: &str, obj: &str) -> (std::path::PathBuf, String) {
    let dir = std::env::temp_dir().join(format!("up-furniture-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{name}.obj"));
    std::fs::write(&path, obj).unwrap();
    let text = format!(
        "[[furniture]]\nmesh = {:?}\nposition = [0.5, 0, 0.5]\n",
        path.display().to_string()
    );
    (dir, text)
}

/// A cube 0.4 m on a side standing on its origin, normals outward (or
/// inward, `flip`), its last face left out where `open`.
fn cube_obj(flip: bool, open: bool) -> String {
    let (mut v, mut t) = (Vec::new(), Vec::new());
    let b = YawBox {
        center: Vec3::new(0.0, 0.2, 0.0),
        half: Vec3::splat(0.2),
        yaw: 0.0,
    };
    push_box(&b, &mut v, &mut t);
    if open {
        t.pop();
    }
    let mut out = String::new();
    for p in v {
        out += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    for [a, b, c] in t {
        let (b, c) = if flip { (c, b) } else { (b, c) };
        out += &format!("f {} {} {}\n", a + 1, b + 1, c + 1);
    }
    out
}

#[test]
fn made_boxes_are_closed_and_outward() {
    let b = YawBox {
        center: Vec3::new(1.0, 0.5, -0.3),
        half: Vec3::new(0.3, 0.5, 0.1),
        yaw: 0.7,
    };
    let (mut v, mut t) = (Vec::new(), Vec::new());
    push_box(&b, &mut v, &mut t);
    up_geom::fit::check_closed(&v, &t).unwrap();
    let volume = solid_integrals(&v, &t).volume;
    assert!((volume - 0.6 * 1.0 * 0.2).abs() < 1e-5, "{volume}");
}

#[test]
fn a_table_and_a_chair_are_closed_solids_of_their_size_on_the_floor() {
    let text = "[[furniture]]\nkind = \"table\"\nposition = [0, 0, 0]\n\
                [[furniture]]\nkind = \"chair\"\nposition = [-1.5, 0, 1]\nyaw_deg = 90\n\
                size = [0.5, 1.0, 0.5]\n";
    let built = build_world(&scene(text)).unwrap();
    let [table, chair] = &built.furniture[..] else {
        panic!("two pieces")
    };
    for (piece, parts, size, at) in [
        (table, 5, [1.2, 0.75, 0.8], Vec3::ZERO),
        (chair, 6, [1.0, 1.0, 0.5], Vec3::new(-1.5, 0.0, 1.0)),
    ] {
        assert_eq!(piece.boxes.len(), parts, "{}", piece.label);
        up_geom::fit::check_closed(&piece.vertices, &piece.triangles).unwrap();
        assert!(solid_integrals(&piece.vertices, &piece.triangles).volume > 0.0);
        let (lo, hi) = piece
            .vertices
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        assert!(lo.y.abs() < 1e-6, "{} floats: {lo}", piece.label);
        assert!((hi.y - size[1]).abs() < 1e-6, "{}: {hi}", piece.label);
        let footprint = (hi - lo) * Vec3::new(1.0, 0.0, 1.0);
        let middle = (lo + hi) * 0.5 * Vec3::new(1.0, 0.0, 1.0);
        assert!(middle.distance(at) < 1e-5, "{}: {middle}", piece.label);
        if piece.label == "table" {
            assert!((footprint.x - size[0]).abs() < 1e-5 && (footprint.z - size[2]).abs() < 1e-5);
        } else {
            // Turned a quarter: its width along z, its depth along x.
            assert!((footprint.z - 0.5).abs() < 1e-5 && (footprint.x - 0.5).abs() < 1e-5);
        }
    }
    // The chair's back, turned a quarter counter-clockwise, runs along its −x side.
    let back = chair.boxes[1];
    assert!(
        back.center.x < -1.5 - 0.2 && back.center.y > 0.5,
        "{back:?}"
    );
    // Their triangles join the room's in the world's mesh.
    let room = built.world.room().unwrap();
    let count = built.room.triangles().len() + table.triangles.len() + chair.triangles.len();
    assert_eq!(room.triangle_count(), count);
}

#[test]
fn a_scene_without_furniture_collides_with_the_room_alone() {
    let built = build_world(&scene("[[balloons]]\n")).unwrap();
    assert!(built.furniture.is_empty());
    let room = built.world.room().unwrap();
    assert_eq!(room.vertices(), built.room.vertices());
    assert_eq!(room.triangles(), built.room.triangles());
}

#[test]
fn keys_out_of_range_are_refused_with_their_line_and_path() {
    let cases = [
        (
            "[[furniture]]\nkind = \"sofa\"\nposition = [0, 0, 0]\n",
            "furniture[0].kind",
            "sofa",
        ),
        (
            "[[furniture]]\nkind = \"table\"\n",
            "furniture[0]",
            "position",
        ),
        (
            "[[furniture]]\nposition = [0, 0, 0]\n",
            "furniture[0]",
            "neither",
        ),
        (
            "[[furniture]]\nkind = \"table\"\nmesh = \"t.obj\"\nposition = [0, 0, 0]\n",
            "furniture[0].mesh",
            "not both",
        ),
        (
            "[[furniture]]\nmesh = \"t.obj\"\nposition = [0, 0, 0]\nsize = [1, 1, 1]\n",
            "furniture[0].size",
            "no size for a mesh",
        ),
        (
            "[[furniture]]\nkind = \"chair\"\nposition = [0, 0, 0]\nsize = [0.4, 0.05, 0.4]\n",
            "furniture[0].size[1]",
            "0.05",
        ),
        (
            "[[furniture]]\nkind = \"chair\"\nposition = [0, 0, 0]\nsize = [0.4, 0.9]\n",
            "furniture[0].size",
            "three numbers",
        ),
        (
            "[[furniture]]\nkind = \"chair\"\nposition = [4, 0, 0]\n",
            "furniture[0].position",
            "inside the room",
        ),
        (
            "[[furniture]]\nkind = \"chair\"\nposition = [0, 0, 0]\nyaw_deg = 400\n",
            "furniture[0].yaw_deg",
            "400",
        ),
    ];
    for (text, key, says) in cases {
        let (e, message) = refused(text);
        assert_eq!(e.key(), Some(key), "{message}");
        assert!(e.line().is_some(), "{message}");
        assert!(message.contains(says), "{message}");
    }
}

#[test]
fn a_piece_through_a_wall_or_into_another_is_refused_naming_both() {
    let (e, message) = refused("[[furniture]]\nkind = \"table\"\nposition = [2.7, 0, 0]\n");
    assert_eq!(e.key(), Some("furniture[0].position"), "{message}");
    assert!(
        message.contains("table") && message.contains("wall at x = 3"),
        "{message}"
    );
    // Under the pyramid's apex a tall table stands; its corners near the
    // walls go through the sloping ceiling.
    let tall = |x: f32| {
        format!("[[furniture]]\nkind = \"table\"\nposition = [{x}, 0, 0]\nsize = [1, 3.5, 1]\n")
    };
    assert!(build_world(&scene(&tall(0.0))).is_ok());
    let (_, message) = refused(&tall(2.0));
    assert!(message.contains("the ceiling"), "{message}");
    let (e, message) = refused(
        "[[furniture]]\nkind = \"table\"\nposition = [0, 0, 0]\n\
         [[furniture]]\nkind = \"chair\"\nposition = [0.5, 0, 0.3]\n",
    );
    assert_eq!(e.key(), Some("furniture[1].position"), "{message}");
    assert_eq!(e.line(), Some(6), "{message}");
    assert!(
        message.contains("chair") && message.contains("furniture[0] (a table"),
        "{message}"
    );
    // A low chair pushed in under the top, clear of its boxes: fine.
    let text = "[[furniture]]\nkind = \"table\"\nposition = [0, 0, 0]\n\
                [[furniture]]\nkind = \"chair\"\nposition = [0, 0, -0.5]\nsize = [0.45, 0.7, 0.5]\n";
    assert!(build_world(&scene(text)).is_ok());
}

#[test]
fn a_mesh_piece_stands_where_it_is_put_and_a_bad_one_is_refused_naming_file_and_problem() {
    let (dir, text) = with_mesh("cube", &cube_obj(false, false));
    let built = build_world(&scene(&text)).unwrap();
    let piece = &built.furniture[0];
    assert_eq!(piece.boxes.len(), 1);
    assert!(piece.boxes[0].center.distance(Vec3::new(0.5, 0.2, 0.5)) < 1e-6);
    assert_eq!(piece.triangles.len(), 12);
    std::fs::remove_dir_all(&dir).unwrap();

    let bad = [
        ("open", cube_obj(false, true), "not closed"),
        ("inside-out", cube_obj(true, false), "inside out"),
        (
            "nan",
            cube_obj(false, false).replacen("v -0.2", "v nan", 1),
            "finite",
        ),
    ];
    for (name, obj, problem) in bad {
        let (dir, text) = with_mesh(name, &obj);
        let (e, message) = refused(&text);
        assert_eq!(e.key(), Some("furniture[0].mesh"), "{message}");
        assert!(message.contains(&format!("{name}.obj")), "{message}");
        assert!(message.contains(problem), "{name}: {message}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn balloons_laid_out_over_a_table_start_clear_of_it() {
    // The whole floor's group, spread over the room, keeps out of the
    // table's legs and top; a group given a box over the table's top starts above it.
    let text = "[[furniture]]\nkind = \"table\"\nposition = [0, 0, 0]\nsize = [3, 0.75, 3]\n\
                [[balloons]]\ncount = 60\n\
                [[balloons]]\ncount = 4\nspawn = { min = [-1, 0.3, -1], max = [1, 0.3, 1] }\n";
    let mut built = build_world(&scene(text)).unwrap();
    assert_eq!(
        built.world.max_penetration_now(),
        0.0,
        "overlap at the start"
    );
    let top = built.furniture[0].boxes[0];
    for &body in &built.group_bodies[1] {
        let y = built.world.pose(body).unwrap().position.y;
        assert!(y > top.center.y + top.half.y, "{y}: in or under the top");
    }
}
