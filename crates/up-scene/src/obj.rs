//! Wavefront OBJ and MTL: reading triangle meshes (through tobj) and writing
//! the balloon and room meshes the web app renders.
//!
//! Reading checks each line first, so a bad file is reported with its name,
//! its line and what was expected; tobj then triangulates polygons. Vertices
//! at exactly the same position are welded (exporters often split them per
//! group or per normal), so closedness can be checked on positions alone.
//!
//! Writing goes to `<name>.tmp` first and is renamed when complete: a reader
//! never sees half a file. Asset layout (see `export_balloon_assets`): one
//! `balloon.obj` whose faces use the material `balloon` from
//! `balloon_red.mtl`, and one `balloon_<colour>.mtl` per colour, each defining
//! the material `balloon`; a renderer swaps the MTL to recolour.

use std::fmt::Write as _;
use std::io::{Cursor, Read};
use std::path::{Path, PathBuf};

use glam::Vec3;
use thiserror::Error;
use up_geom::fit::{check_closed, MeshCheck, MeshCheckError};

use crate::balloon_mesh::BalloonMesh;
use crate::room::RoomMesh;

/// Largest OBJ file read, bytes (64 MiB, about a million triangles): a bigger
/// file is refused before it is read whole, and devices that never end
/// (`/dev/zero`) stop there too.
pub const MAX_OBJ_BYTES: u64 = 64 << 20;

/// The named balloon colours, in palette order.
pub const COLOR_NAMES: [&str; 8] = [
    "red", "yellow", "blue", "green", "purple", "orange", "pink", "white",
];

/// Linear-ish sRGB in 0..1 of a named colour (case-insensitive), as party
/// latex looks: saturated, not pure primaries.
pub fn color_rgb(name: &str) -> Option<[f32; 3]> {
    let rgb = match name.to_ascii_lowercase().as_str() {
        "red" => [0.80, 0.06, 0.08],
        "yellow" => [0.98, 0.80, 0.10],
        "blue" => [0.08, 0.30, 0.85],
        "green" => [0.10, 0.62, 0.22],
        "purple" => [0.45, 0.15, 0.65],
        "orange" => [0.98, 0.45, 0.06],
        "pink" => [0.96, 0.45, 0.65],
        "white" => [0.93, 0.93, 0.92],
        _ => return None,
    };
    Some(rgb)
}

#[derive(Debug, Error)]
pub enum ObjError {
    #[error("{path}: file not found")]
    Missing { path: PathBuf },
    #[error("{path}: cannot read: {source}")]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error(
        "{path}: too large: more than {max} bytes (expected an OBJ file of at most {max} bytes, \
         about a million triangles)"
    )]
    TooLarge { path: PathBuf, max: u64 },
    #[error("{path}: not UTF-8 text (expected a Wavefront OBJ text file)")]
    NotText { path: PathBuf },
    #[error("{path}: cannot write: {source}")]
    Write {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{path}:{line}: {message}")]
    Malformed {
        path: PathBuf,
        line: usize,
        message: String,
    },
    #[error("{path}:{line}: vertex coordinates must be finite numbers, got {text:?}")]
    NonFinite {
        path: PathBuf,
        line: usize,
        text: String,
    },
    #[error("{path}:{line}: face refers to vertex {index}, but the file has {count} vertices")]
    IndexOutOfRange {
        path: PathBuf,
        line: usize,
        index: i64,
        count: usize,
    },
    #[error("{path}: no triangles (expected at least one face `f a b c`)")]
    NoTriangles { path: PathBuf },
    #[error("{path}: cannot load: {message}")]
    Load { path: PathBuf, message: String },
    #[error("{path}: {source}")]
    Mesh {
        path: PathBuf,
        source: MeshCheckError,
    },
}

/// A triangle mesh read from an OBJ file, positions welded.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjMesh {
    path: PathBuf,
    vertices: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
}

impl ObjMesh {
    pub fn path(&self) -> &Path {
        &self.path
    }

    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    pub fn into_parts(self) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        (self.vertices, self.triangles)
    }

    /// Closed, manifold and consistently wound (what fitting and rooms need);
    /// the error names the file and the offending edge.
    pub fn check_closed(&self) -> Result<MeshCheck, ObjError> {
        check_closed(&self.vertices, &self.triangles).map_err(|source| ObjError::Mesh {
            path: self.path.clone(),
            source,
        })
    }
}

/// Reads the triangles of an OBJ file (polygons are triangulated; points,
/// lines, normals, texture coordinates and materials are ignored). Files over
/// `MAX_OBJ_BYTES` are refused.
pub fn read_obj_mesh(path: &Path) -> Result<ObjMesh, ObjError> {
    let text = read_capped(path, MAX_OBJ_BYTES)?;
    parse_obj_mesh(&text, path)
}

/// Reads at most `max` bytes of `path` as UTF-8; more is an error, not a truncation.
fn read_capped(path: &Path, max: u64) -> Result<String, ObjError> {
    let io_error = |source: std::io::Error| match source.kind() {
        std::io::ErrorKind::NotFound => ObjError::Missing {
            path: path.to_path_buf(),
        },
        _ => ObjError::Read {
            path: path.to_path_buf(),
            source,
        },
    };
    let file = std::fs::File::open(path).map_err(io_error)?;
    let mut bytes = Vec::new();
    file.take(max + 1)
        .read_to_end(&mut bytes)
        .map_err(io_error)?;
    if bytes.len() as u64 > max {
        return Err(ObjError::TooLarge {
            path: path.to_path_buf(),
            max,
        });
    }
    String::from_utf8(bytes).map_err(|_| ObjError::NotText {
        path: path.to_path_buf(),
    })
}

/// Parses OBJ text as `read_obj_mesh` does; `path` names it in messages.
pub fn parse_obj_mesh(text: &str, path: &Path) -> Result<ObjMesh, ObjError> {
    prescan(path, text)?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) =
        tobj::load_obj_buf(&mut Cursor::new(text.as_bytes()), &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map_err(|e| ObjError::Load {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for model in &models {
        let mesh = &model.mesh;
        let base = vertices.len() as u32;
        vertices.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        let count = mesh.positions.len() / 3;
        for tri in mesh.indices.chunks_exact(3) {
            if let Some(&bad) = tri.iter().find(|&&i| i as usize >= count) {
                return Err(ObjError::Load {
                    path: path.to_path_buf(),
                    message: format!("face index {bad} out of range in object {:?}", model.name),
                });
            }
            triangles.push([base + tri[0], base + tri[1], base + tri[2]]);
        }
    }
    if triangles.is_empty() {
        return Err(ObjError::NoTriangles {
            path: path.to_path_buf(),
        });
    }
    let (vertices, triangles) = weld(vertices, triangles);
    Ok(ObjMesh {
        path: path.to_path_buf(),
        vertices,
        triangles,
    })
}

/// Checks `v` and `f` lines, reporting the first bad one with its line number.
fn prescan(path: &Path, text: &str) -> Result<(), ObjError> {
    let malformed = |line: usize, message: String| ObjError::Malformed {
        path: path.to_path_buf(),
        line,
        message,
    };
    let total_vertices = text
        .lines()
        .filter(|l| l.split_whitespace().next() == Some("v"))
        .count();
    let mut seen_vertices = 0usize;
    let mut faces = 0usize;
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let mut words = raw.split_whitespace();
        match words.next() {
            Some("v") => {
                seen_vertices += 1;
                let coords: Vec<&str> = words.collect();
                if coords.len() < 3 {
                    return Err(malformed(line, format!("expected `v x y z`, got {raw:?}")));
                }
                for c in &coords[..3] {
                    let value: f32 = c.parse().map_err(|_| {
                        malformed(
                            line,
                            format!("expected a number for a coordinate, got {c:?}"),
                        )
                    })?;
                    if !value.is_finite() {
                        return Err(ObjError::NonFinite {
                            path: path.to_path_buf(),
                            line,
                            text: raw.trim().to_string(),
                        });
                    }
                }
            }
            Some("f") => {
                faces += 1;
                let corners: Vec<&str> = words.collect();
                if corners.len() < 3 {
                    return Err(malformed(
                        line,
                        format!("a face needs 3 or more vertices, got {raw:?}"),
                    ));
                }
                for corner in corners {
                    let first = corner.split('/').next().unwrap_or("");
                    let index: i64 = first.parse().map_err(|_| {
                        malformed(line, format!("expected a vertex index, got {corner:?}"))
                    })?;
                    // Negative indices count back from the last vertex read so far.
                    let ok = match index {
                        0 => false,
                        i if i > 0 => i as usize <= total_vertices,
                        i => i.unsigned_abs() as usize <= seen_vertices,
                    };
                    if !ok {
                        return Err(ObjError::IndexOutOfRange {
                            path: path.to_path_buf(),
                            line,
                            index,
                            count: if index < 0 {
                                seen_vertices
                            } else {
                                total_vertices
                            },
                        });
                    }
                }
            }
            _ => {}
        }
    }
    if faces == 0 {
        return Err(ObjError::NoTriangles {
            path: path.to_path_buf(),
        });
    }
    Ok(())
}

/// Merges vertices at bit-identical positions (−0 and +0 alike); keeps the
/// first occurrence's order so the result is deterministic.
fn weld(vertices: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let key = |p: Vec3| {
        (
            (p.x + 0.0).to_bits(),
            (p.y + 0.0).to_bits(),
            (p.z + 0.0).to_bits(),
        )
    };
    let mut order: Vec<u32> = (0..vertices.len() as u32).collect();
    order.sort_by_key(|&i| (key(vertices[i as usize]), i));
    let mut canonical = vec![0u32; vertices.len()];
    for group in order.chunk_by(|&a, &b| key(vertices[a as usize]) == key(vertices[b as usize])) {
        for &i in group {
            canonical[i as usize] = group[0];
        }
    }
    let mut remap = vec![u32::MAX; vertices.len()];
    let mut welded = Vec::new();
    for i in 0..vertices.len() {
        let c = canonical[i] as usize;
        if remap[c] == u32::MAX {
            remap[c] = welded.len() as u32;
            welded.push(vertices[c]);
        }
        remap[i] = remap[c];
    }
    let triangles = triangles
        .iter()
        .map(|t| t.map(|i| remap[i as usize]))
        .collect();
    (welded, triangles)
}

/// Writes `contents` to `path` through a temporary file renamed when complete.
pub fn write_atomically(path: &Path, contents: &str) -> Result<(), ObjError> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = PathBuf::from(tmp);
    let result = std::fs::write(&tmp, contents).and_then(|()| std::fs::rename(&tmp, path));
    result.map_err(|source| {
        let _ = std::fs::remove_file(&tmp);
        ObjError::Write {
            path: path.to_path_buf(),
            source,
        }
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
    for name in COLOR_NAMES {
        let path = dir.join(format!("balloon_{name}.mtl"));
        let rgb = color_rgb(name).unwrap_or([1.0; 3]);
        write_atomically(&path, &mtl_text("balloon", rgb))?;
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

#[cfg(test)]
#[path = "obj_tests.rs"]
mod tests;
