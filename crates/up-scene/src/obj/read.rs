//! Reading Wavefront OBJ triangle meshes (through tobj): rooms and the
//! shapes `up fit-spheres` fits. Writing them is `export`.
//!
//! Reading checks each line first, so a bad file is reported with its name,
//! its line and what was expected; tobj then triangulates polygons. Vertices
//! at exactly the same position are welded (exporters often split them per
//! group or per normal), so closedness can be checked on positions alone.

use std::io::{Cursor, Read};
use std::path::{Path, PathBuf};

use glam::Vec3;
use thiserror::Error;
use up_geom::fit::{check_closed, MeshCheck, MeshCheckError};

/// Largest OBJ file read, bytes (64 MiB, about a million triangles): a bigger
/// file is refused before it is read whole, and devices that never end
/// (`/dev/zero`) stop there too.
pub const MAX_OBJ_BYTES: u64 = 64 << 20;

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
pub(super) fn read_capped(path: &Path, max: u64) -> Result<String, ObjError> {
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
