//! Writing Wavefront OBJ and MTL: the balloon and room meshes the web app
//! renders (`up export-obj`). Reading them back is `read`.
//!
//! Every file goes through `atomic_file`: a reader never sees half a file.
//! Asset layout (see `export_balloon_assets`): one `balloon.obj` whose faces
//! use the material `balloon` from `balloon_red.mtl`, and one
//! `balloon_<colour>.mtl` per palette colour, each defining the material
//! `balloon`; a renderer swaps the MTL to recolour.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::Vec3;

use crate::balloon::mesh::BalloonMesh;
use crate::build::room::RoomMesh;
use crate::obj::ObjError;
use crate::palette::PALETTE;

/// Writes `contents` to `path` whole or not at all (`atomic_file`).
fn write_atomically(path: &Path, contents: &str) -> Result<(), ObjError> {
    crate::atomic_file::write_atomically(path, contents.as_bytes()).map_err(|e| ObjError::Write {
        path: path.to_path_buf(),
        source: e.into_io_error(),
    })
}

/// Six decimals: micrometres, plenty for a balloon and stable across runs.
fn push_vec3(out: &mut String, tag: &str, v: Vec3) {
    // Adding zero turns −0 into +0, so the seam does not print "-0.000000".
    let v = v + Vec3::ZERO;
    let _ = writeln!(out, "{tag} {:.6} {:.6} {:.6}", v.x, v.y, v.z);
}

/// OBJ text of a mesh with smooth per-vertex normals.
pub fn balloon_obj_text(mesh: &BalloonMesh, mtllib: &str, material: &str) -> String {
    let mut out = String::with_capacity(mesh.positions.len() * 80 + mesh.indices.len() * 40);
    out.push_str("# UP procedural latex balloon: metres, +Y up, origin at the widest circle\n");
    let _ = writeln!(out, "mtllib {mtllib}\no balloon");
    for &p in &mesh.positions {
        push_vec3(&mut out, "v", p);
    }
    for &n in &mesh.normals {
        push_vec3(&mut out, "vn", n);
    }
    let _ = writeln!(out, "usemtl {material}\ns 1");
    for t in &mesh.indices {
        let [a, b, c] = t.map(|i| i + 1);
        let _ = writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}");
    }
    out
}

/// MTL text of one glossy latex material of colour `rgb` (0..1).
pub fn mtl_text(material: &str, rgb: [f32; 3]) -> String {
    let [r, g, b] = rgb;
    format!(
        "# UP balloon latex\nnewmtl {material}\nKa 0.000 0.000 0.000\nKd {r:.3} {g:.3} {b:.3}\n\
         Ks 0.350 0.350 0.350\nNs 120.0\nd 1.0\nillum 2\n"
    )
}

/// OBJ text of a mesh with flat faces (one normal per triangle, as wound).
pub fn flat_obj_text(
    name: &str,
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    mtllib: &str,
    material: &str,
) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# UP {name}: metres, +Y up\nmtllib {mtllib}\no {name}");
    for &p in vertices {
        push_vec3(&mut out, "v", p);
    }
    for t in triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        push_vec3(&mut out, "vn", (b - a).cross(c - a).normalize_or_zero());
    }
    let _ = writeln!(out, "usemtl {material}\ns off");
    for (k, t) in triangles.iter().enumerate() {
        let [a, b, c] = t.map(|i| i + 1);
        let n = k + 1;
        let _ = writeln!(out, "f {a}//{n} {b}//{n} {c}//{n}");
    }
    out
}

/// Writes `balloon.obj` (the default 11″ balloon) and `balloon_<colour>.mtl`
/// for every named colour into `dir`; returns the paths written.
pub fn export_balloon_assets(dir: &Path) -> Result<Vec<PathBuf>, ObjError> {
    let mesh =
        BalloonMesh::new(crate::balloon::BalloonSpec::default().diameter_m).map_err(|e| {
            ObjError::Load {
                path: dir.join("balloon.obj"),
                message: e.to_string(),
            }
        })?;
    let mut written = Vec::new();
    let obj = dir.join("balloon.obj");
    write_atomically(&obj, &balloon_obj_text(&mesh, "balloon_red.mtl", "balloon"))?;
    written.push(obj);
    for color in PALETTE {
        let path = dir.join(format!("balloon_{}.mtl", color.name));
        write_atomically(&path, &mtl_text("balloon", color.rgb))?;
        written.push(path);
    }
    Ok(written)
}

/// Writes `room.obj` (normals into the room) and `room.mtl` into `dir`.
pub fn export_room_obj(dir: &Path, room: &RoomMesh) -> Result<Vec<PathBuf>, ObjError> {
    let obj = dir.join("room.obj");
    let text = flat_obj_text(
        "room",
        room.vertices(),
        room.triangles(),
        "room.mtl",
        "room",
    );
    write_atomically(&obj, &text)?;
    let mtl = dir.join("room.mtl");
    let wall = "# UP room\nnewmtl room\nKa 0.000 0.000 0.000\nKd 0.850 0.830 0.800\n\
                Ks 0.050 0.050 0.050\nNs 10.0\nd 1.0\nillum 2\n";
    write_atomically(&mtl, wall)?;
    Ok(vec![obj, mtl])
}
