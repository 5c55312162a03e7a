//! OBJ text through `parse_obj_mesh` (what `read_obj_mesh` runs after its size
//! cap): an error names the file; a mesh has finite vertices and in-range
//! indices; a closed one goes on the way a room (`RoomMesh`) and a balloon
//! shape (`up fit-spheres`) do, and neither may panic.

use std::path::Path;

use up_geom::fit::mesh_integrals::solid_integrals;
use up_geom::fit::{fit_sphere_tree, FitOptions};
use up_scene::obj::parse_obj_mesh;
use up_scene::room::RoomMesh;

/// Fitting is costly; only small closed meshes are fitted, with few leaves.
const MAX_FIT_TRIANGLES: usize = 200;

/// One input: panics when a property fails.
pub fn check(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let mesh = match parse_obj_mesh(text, Path::new("fuzz.obj")) {
        Ok(mesh) => mesh,
        Err(e) => {
            let message = e.to_string();
            assert!(message.starts_with("fuzz.obj"), "{message}");
            return;
        }
    };
    assert!(!mesh.triangles().is_empty());
    assert!(mesh.vertices().iter().all(|v| v.is_finite()));
    let count = mesh.vertices().len() as u32;
    assert!(mesh.triangles().iter().flatten().all(|&i| i < count));
    if mesh.check_closed().is_err() {
        return;
    }
    let (vertices, mut triangles) = mesh.into_parts();
    if triangles.len() <= MAX_FIT_TRIANGLES {
        if let Ok(report) = fit_sphere_tree(&vertices, &triangles, &FitOptions::with_leaves(3)) {
            for node in report.tree.nodes() {
                assert!(node.center.is_finite() && node.radius.is_finite() && node.radius > 0.0);
            }
        }
    }
    // As `room_from_obj`: normals turned inwards, then the room's own checks.
    if solid_integrals(&vertices, &triangles).volume > 0.0 {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    if let Ok(room) = RoomMesh::from_inward_mesh(vertices, triangles, "fuzz.obj") {
        let bounds = room.bounds();
        let _ = room.contains_point((bounds.min + bounds.max) * 0.5);
        let _ = room.to_trimesh();
    }
}
