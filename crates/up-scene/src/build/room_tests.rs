//! Room tests: the box room, OBJ rooms, and what is written reads back.

use glam::Vec3;

use super::room::*;
use up_geom::fit::check_closed;

fn original() -> RoomMesh {
    box_room(6.0, 6.0, 3.0, Ceiling::Pyramid { apex_height: 1.5 }).unwrap()
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("up-scene-room-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn original_room_has_the_figure_1_triangles_and_126_cubic_metres() {
    let room = original();
    // Floor 2 + walls 4 × 2 + pyramid 4.
    assert_eq!(room.triangles().len(), 14);
    assert!(check_closed(room.vertices(), room.triangles()).is_ok());
    assert!((room.volume() - 126.0).abs() < 1e-3, "{}", room.volume());
    let b = room.bounds();
    assert_eq!(b.min, Vec3::new(-3.0, 0.0, -3.0));
    assert_eq!(b.max, Vec3::new(3.0, 4.5, 3.0));
}

#[test]
fn flat_room_is_a_box() {
    let room = box_room(4.0, 5.0, 2.5, Ceiling::Flat).unwrap();
    assert_eq!(room.triangles().len(), 12);
    assert!((room.volume() - 50.0).abs() < 1e-3);
    assert!(check_closed(room.vertices(), room.triangles()).is_ok());
}

#[test]
fn every_normal_points_into_the_room() {
    for room in [original(), box_room(6.0, 6.0, 3.0, Ceiling::Flat).unwrap()] {
        let inside = Vec3::new(0.3, 1.2, -0.4);
        let mesh = room.trimesh();
        for i in 0..mesh.triangles().len() as u32 {
            let [a, b, c] = mesh.triangle(i);
            let n = (b - a).cross(c - a);
            assert!(n.dot(inside - a) > 0.0, "triangle {i} faces out");
        }
        // The floor faces up.
        let [a, b, c] = mesh.triangle(0);
        assert!((b - a).cross(c - a).normalize().dot(Vec3::Y) > 0.999);
    }
}

#[test]
fn contains_point_tells_inside_from_outside() {
    let room = original();
    assert!(room.contains_point(Vec3::new(0.0, 1.0, 0.0)));
    assert!(room.contains_point(Vec3::new(2.9, 0.1, -2.9)));
    // Under the apex, above the walls.
    assert!(room.contains_point(Vec3::new(0.0, 4.4, 0.0)));
    // Above the walls near a corner is outside the pyramid.
    assert!(!room.contains_point(Vec3::new(2.8, 4.0, 2.8)));
    assert!(!room.contains_point(Vec3::new(0.0, -0.1, 0.0)));
    assert!(!room.contains_point(Vec3::new(3.1, 1.0, 0.0)));
    assert!(!room.contains_point(Vec3::new(0.0, 4.6, 0.0)));
    assert!(!room.contains_point(Vec3::NAN));
}

#[test]
fn bad_dimensions_are_errors_naming_the_key() {
    let e = box_room(0.0, 6.0, 3.0, Ceiling::Flat).unwrap_err();
    assert_eq!(
        e.to_string(),
        "room width: expected metres in (0, 10000], got 0"
    );
    assert!(matches!(
        box_room(6.0, f32::NAN, 3.0, Ceiling::Flat),
        Err(RoomError::BadDimension { key: "depth", .. })
    ));
    assert!(matches!(
        box_room(6.0, 6.0, -3.0, Ceiling::Flat),
        Err(RoomError::BadDimension {
            key: "wall_height",
            ..
        })
    ));
    assert!(matches!(
        box_room(6.0, 6.0, 3.0, Ceiling::Pyramid { apex_height: 0.0 }),
        Err(RoomError::BadDimension {
            key: "apex_height",
            ..
        })
    ));
}

/// Each triangle's corners, in winding order (the reader may renumber vertices).
fn corners(room: &RoomMesh) -> Vec<[Vec3; 3]> {
    room.triangles()
        .iter()
        .map(|t| t.map(|i| room.vertices()[i as usize]))
        .collect()
}

#[test]
fn obj_room_with_outward_normals_is_flipped_inward() {
    let dir = scratch("flip");
    let original = original();
    // Write the room with its winding reversed (normals out), read it back.
    let outward: Vec<[u32; 3]> = original
        .triangles()
        .iter()
        .map(|t| [t[0], t[2], t[1]])
        .collect();
    let text =
        crate::obj::export::flat_obj_text("hall", original.vertices(), &outward, "x.mtl", "x");
    let path = dir.join("hall.obj");
    std::fs::write(&path, text).unwrap();
    let room = room_from_obj(&path).unwrap();
    assert!((room.volume() - 126.0).abs() < 1e-3);
    assert_eq!(corners(&room), corners(&original));
    assert!(room.contains_point(Vec3::new(0.0, 1.0, 0.0)));

    // Already inward: kept as it is.
    crate::obj::export::export_room_obj(&dir, &original).unwrap();
    let again = room_from_obj(&dir.join("room.obj")).unwrap();
    assert_eq!(corners(&again), corners(&original));
}

#[test]
fn obj_room_must_be_closed() {
    let dir = scratch("open");
    let path = dir.join("open.obj");
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n",
    )
    .unwrap();
    let e = room_from_obj(&path).unwrap_err();
    assert!(
        e.to_string().contains("open.obj: the mesh is not closed"),
        "{e}"
    );
    let e = room_from_obj(&dir.join("missing.obj")).unwrap_err();
    assert!(
        e.to_string().ends_with("missing.obj: file not found"),
        "{e}"
    );
}
