//! OBJ/MTL writing tests: what is written reads back.

use std::path::{Path, PathBuf};

use super::export::*;
use crate::balloon::mesh::BalloonMesh;
use crate::obj::read_obj_mesh;
use crate::palette::color_rgb;

/// A fresh, empty directory under the system temp dir for one test.
fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("up-scene-obj-export-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn balloon_round_trips_through_obj() {
    let dir = scratch("balloon");
    let written = export_balloon_assets(&dir).unwrap();
    assert_eq!(written.len(), 1 + crate::palette::PALETTE.len());
    assert!(written.iter().all(|p| p.exists()));
    let leftovers = std::fs::read_dir(&dir)
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().extension() == Some("tmp".as_ref()))
        .count();
    assert_eq!(leftovers, 0);
    let mesh = read_obj_mesh(&dir.join("balloon.obj")).unwrap();
    let original = BalloonMesh::new(0.28).unwrap();
    assert_eq!(mesh.vertices().len(), original.positions.len());
    assert_eq!(mesh.triangles(), &original.indices[..]);
    assert!(mesh.check_closed().is_ok());
    // tobj reads the material the OBJ names.
    let (models, materials) =
        tobj::load_obj(dir.join("balloon.obj"), &tobj::LoadOptions::default()).unwrap();
    let materials = materials.unwrap();
    assert_eq!(materials[0].name, "balloon");
    assert_eq!(models[0].mesh.material_id, Some(0));
    assert_eq!(materials[0].diffuse, color_rgb("red"));
}

#[test]
fn room_exports_with_inward_face_normals() {
    let dir = scratch("room");
    let room =
        crate::build::room::box_room(6.0, 6.0, 3.0, crate::build::room::Ceiling::Flat).unwrap();
    let written = export_room_obj(&dir, &room).unwrap();
    assert_eq!(written.len(), 2);
    let back = read_obj_mesh(&written[0]).unwrap();
    assert_eq!(back.triangles().len(), room.triangles().len());
    let text = std::fs::read_to_string(&written[0]).unwrap();
    // The floor's normal points up, into the room.
    assert!(text.contains("vn 0.000000 1.000000 0.000000"), "{text}");
}

/// `assets/` holds what `export_balloon_assets` writes. Regenerate with
/// `UP_WRITE_ASSETS=1 cargo test --release -p up-scene committed_assets`.
#[test]
fn committed_assets_match_the_generator() {
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    if std::env::var_os("UP_WRITE_ASSETS").is_some() {
        export_balloon_assets(&assets).unwrap();
    }
    let dir = scratch("assets");
    for fresh in export_balloon_assets(&dir).unwrap() {
        let name = fresh.file_name().unwrap();
        let committed = std::fs::read_to_string(assets.join(name))
            .unwrap_or_else(|e| panic!("assets/{}: {e}", name.to_string_lossy()));
        assert!(
            committed == std::fs::read_to_string(&fresh).unwrap(),
            "assets/{} is stale: regenerate it (see this test's docs)",
            name.to_string_lossy()
        );
    }
}
