//! The room: a closed triangle mesh whose normals point into the room.
//!
//! The original's room (report Figure 1): origin at the centre of the floor,
//! +Y up, metres; a floor of two triangles, four walls of two triangles each,
//! and a pyramidal ceiling of four triangles meeting at an apex above the
//! centre (or a flat ceiling of two). Any closed OBJ mesh can be a room too;
//! its winding is detected and flipped if its normals point outwards.

use std::path::Path;

use glam::{DVec2, Vec3};
use thiserror::Error;
use up_geom::fit::mesh_integrals::solid_integrals;
use up_geom::{Aabb, TriMesh, TriMeshError};

use crate::obj::{read_obj_mesh, ObjError};

/// The shape of the ceiling of a box room.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ceiling {
    /// Four triangles meeting `apex_height` metres above the tops of the walls
    /// (1.5 in the original).
    Pyramid { apex_height: f32 },
    /// Two triangles at the height of the walls.
    Flat,
}

#[derive(Debug, Error)]
pub enum RoomError {
    #[error("room {key}: expected {expected}, got {value}")]
    BadDimension {
        key: &'static str,
        value: f32,
        expected: &'static str,
    },
    #[error("{0}")]
    Obj(#[from] ObjError),
    #[error("{path}: the room encloses no volume ({volume} m³)")]
    NoVolume { path: String, volume: f32 },
    #[error("room mesh: {0}")]
    Mesh(#[from] TriMeshError),
}

/// A closed room, normals pointing in. Built only through `box_room`,
/// `room_from_obj` or `RoomMesh::from_inward_mesh`, so it is always valid.
#[derive(Clone, Debug)]
pub struct RoomMesh {
    mesh: TriMesh,
    /// m³ enclosed.
    volume: f32,
}

/// Largest room side accepted, m.
const MAX_SIDE: f32 = 10_000.0;

fn dimension(key: &'static str, value: f32) -> Result<f32, RoomError> {
    if value.is_finite() && value > 0.0 && value <= MAX_SIDE {
        Ok(value)
    } else {
        Err(RoomError::BadDimension {
            key,
            value,
            expected: "metres in (0, 10000]",
        })
    }
}

/// The original's room: `width` along x, `depth` along z, walls `wall_height`
/// high (m; 6, 6, 3 in the original), with the given ceiling.
pub fn box_room(
    width: f32,
    depth: f32,
    wall_height: f32,
    ceiling: Ceiling,
) -> Result<RoomMesh, RoomError> {
    let (x, z) = (
        0.5 * dimension("width", width)?,
        0.5 * dimension("depth", depth)?,
    );
    let h = dimension("wall_height", wall_height)?;
    let apex = match ceiling {
        Ceiling::Pyramid { apex_height } => Some(h + dimension("apex_height", apex_height)?),
        Ceiling::Flat => None,
    };
    // Floor corners 0..4 and wall tops 4..8, counter-clockwise seen from above.
    let corners = [(-x, -z), (x, -z), (x, z), (-x, z)];
    let mut vertices: Vec<Vec3> = corners
        .iter()
        .map(|&(cx, cz)| Vec3::new(cx, 0.0, cz))
        .collect();
    vertices.extend(corners.iter().map(|&(cx, cz)| Vec3::new(cx, h, cz)));
    let mut triangles = vec![[0, 2, 1], [0, 3, 2]];
    for i in 0..4u32 {
        let j = (i + 1) % 4;
        triangles.push([i, j, j + 4]);
        triangles.push([i, j + 4, i + 4]);
    }
    match apex {
        Some(y) => {
            vertices.push(Vec3::new(0.0, y, 0.0));
            for i in 0..4u32 {
                triangles.push([i + 4, (i + 1) % 4 + 4, 8]);
            }
        }
        None => triangles.extend([[4, 5, 6], [4, 6, 7]]),
    }
    // The room is convex: make every face look at a point inside it.
    let inside = Vec3::new(0.0, 0.5 * h, 0.0);
    for t in &mut triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        if (b - a).cross(c - a).dot(inside - a) < 0.0 {
            t.swap(1, 2);
        }
    }
    RoomMesh::from_inward_mesh(vertices, triangles, "box room")
}

/// A room from a closed OBJ mesh (metres, Y up). Its winding is detected: a
/// mesh whose normals point outwards is flipped so they point in.
pub fn room_from_obj(path: &Path) -> Result<RoomMesh, RoomError> {
    let mesh = read_obj_mesh(path)?;
    mesh.check_closed()?;
    let (vertices, mut triangles) = mesh.into_parts();
    // Outward normals give a positive signed volume: flip to point inwards.
    if solid_integrals(&vertices, &triangles).volume > 0.0 {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    RoomMesh::from_inward_mesh(vertices, triangles, &path.display().to_string())
}

impl RoomMesh {
    /// A closed mesh whose normals already point into the room; `name` labels errors.
    pub fn from_inward_mesh(
        vertices: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
        name: &str,
    ) -> Result<Self, RoomError> {
        up_geom::fit::check_closed(&vertices, &triangles).map_err(|source| ObjError::Mesh {
            path: name.into(),
            source,
        })?;
        let signed = solid_integrals(&vertices, &triangles).volume;
        let extent = Aabb::from_points(&vertices).extents().max_element();
        // Inward normals: a negative signed volume of real size.
        if signed.is_nan() || -signed <= 1e-9 * extent * extent * extent {
            return Err(RoomError::NoVolume {
                path: name.into(),
                volume: -signed,
            });
        }
        let mesh = TriMesh::new(vertices, triangles)?;
        Ok(Self {
            mesh,
            volume: -signed,
        })
    }

    pub fn vertices(&self) -> &[Vec3] {
        self.mesh.vertices()
    }

    pub fn triangles(&self) -> &[[u32; 3]] {
        self.mesh.triangles()
    }

    /// The mesh the physics world collides with.
    pub fn trimesh(&self) -> &TriMesh {
        &self.mesh
    }

    pub fn to_trimesh(&self) -> TriMesh {
        self.mesh.clone()
    }

    /// m³ of air in the room; 126 for the original (108 + 18 under the pyramid).
    pub fn volume(&self) -> f32 {
        self.volume
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(self.mesh.vertices())
    }

    /// True when `p` is inside the closed room (used to count escaped
    /// balloons). Winding number: the solid angles of the triangles seen from
    /// `p` add up to −4π inside (normals point in) and 0 outside.
    pub fn contains_point(&self, p: Vec3) -> bool {
        if !p.is_finite() || !self.bounds().contains_point(p) {
            return false;
        }
        let p = p.as_dvec3();
        let mut total = 0.0f64;
        for t in self.mesh.triangles() {
            let [a, b, c] = t.map(|i| self.mesh.vertices()[i as usize].as_dvec3() - p);
            let (la, lb, lc) = (a.length(), b.length(), c.length());
            let numerator = a.dot(b.cross(c));
            let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
            // Van Oosterom & Strackee: tan(Ω/2) = numerator / denominator.
            total += 2.0 * DVec2::new(denominator, numerator).to_angle();
        }
        total < -2.0 * std::f64::consts::PI
    }
}
