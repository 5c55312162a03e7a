//! Furniture (`[[furniture]]`) made into closed triangle meshes in the world
//! frame, normals outward: a table (a top on four legs) or a chair (a seat
//! on four legs and a back) as boxes to its size, or a closed OBJ mesh.
//!
//! The pieces collide as the room does: their triangles are added to the
//! room's static mesh (`room_with_furniture`), whose normals point into the
//! room's air; a piece's outward normals point into that air too, so the
//! room's contacts, the fast bodies' sweep and the ribbons' pushes see a
//! piece as they see a wall. A made piece's boxes touch (legs under a top)
//! and keep their faces where they touch: a one-sided face pushes only what
//! is within a radius behind it and over it, which is inside the box beside
//! it, where nothing reaches. A scene without furniture keeps the room's
//! mesh as it was, so it steps bit for bit as before.
//!
//! Each piece must stand inside the room and clear of the others (checked
//! on its boxes: a mesh's is its bounding box); the spawn layout keeps
//! balloons out of those boxes (`reserve`).

use glam::{Quat, Vec2, Vec3};
use up_geom::fit::mesh_integrals::solid_integrals;
use up_geom::TriMesh;

use super::room::RoomMesh;
use super::spawn::Occupancy;
use crate::error::SceneError;
use crate::obj::read_obj_mesh;
use crate::scene::{FurnitureKind, Scene};

/// A piece of furniture as built: its closed surface in the world frame
/// (normals outward) and the boxes it is checked and reserved by.
#[derive(Clone, Debug)]
pub struct FurniturePiece {
    /// `table`, `chair` or `mesh <file>`, for messages.
    pub label: String,
    pub kind: Option<FurnitureKind>,
    pub vertices: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
    /// World-frame boxes holding the piece (a made piece's parts; a mesh's bounds).
    pub boxes: Vec<YawBox>,
}

/// A box turned about the vertical, world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct YawBox {
    pub center: Vec3,
    /// Half extents along the box's own axes, m.
    pub half: Vec3,
    /// Radians about +Y.
    pub yaw: f32,
}

/// Thickness of a table's top, m (a solid wood top; thinner for a small table).
const TABLE_TOP_M: f32 = 0.04;
/// Side of a table's square legs, m.
const TABLE_LEG_M: f32 = 0.06;
/// A table's legs stand this far in from the top's edges, m.
const TABLE_LEG_INSET_M: f32 = 0.04;
/// Thickness of a chair's seat, m.
const CHAIR_SEAT_M: f32 = 0.04;
/// Side of a chair's square legs, m.
const CHAIR_LEG_M: f32 = 0.04;
/// Thickness of a chair's back, m.
const CHAIR_BACK_M: f32 = 0.04;
/// Pieces may touch (a chair against a table's leg) but not overlap by more
/// than this, m.
const TOUCH_M: f32 = 1e-3;
/// Spacing of the spheres that reserve a piece's boxes in the spawn layout, m.
const RESERVE_SPACING_M: f32 = 0.05;
/// The most spheres one box reserves; past it the spacing grows.
const MAX_RESERVE_SPHERES: f32 = 4096.0;

impl YawBox {
    fn rotation(&self) -> Quat {
        Quat::from_rotation_y(self.yaw)
    }

    /// The eight corners, world frame.
    pub fn corners(&self) -> [Vec3; 8] {
        let q = self.rotation();
        std::array::from_fn(|k| {
            let sign = Vec3::new(
                if k & 1 == 0 { -1.0 } else { 1.0 },
                if k & 2 == 0 { -1.0 } else { 1.0 },
                if k & 4 == 0 { -1.0 } else { 1.0 },
            );
            self.center + q * (sign * self.half)
        })
    }

    /// How deep two boxes overlap, m (the least over the separating axes:
    /// the vertical and the four horizontal sides); ≤ 0 when apart.
    pub fn overlap(&self, other: &YawBox) -> f32 {
        let vertical = (self.half.y + other.half.y) - (self.center.y - other.center.y).abs();
        let d = Vec2::new(
            other.center.x - self.center.x,
            other.center.z - self.center.z,
        );
        let axes = |b: &YawBox| {
            let (s, c) = (b.yaw.sin(), b.yaw.cos());
            // Rotation about +Y takes x to (cos, −sin) and z to (sin, cos) in x–z.
            [Vec2::new(c, -s), Vec2::new(s, c)]
        };
        let (a, b) = (axes(self), axes(other));
        let reach = |axes: &[Vec2; 2], half: Vec3, n: Vec2| {
            half.x * axes[0].dot(n).abs() + half.z * axes[1].dot(n).abs()
        };
        a.iter()
            .chain(b.iter())
            .map(|&n| reach(&a, self.half, n) + reach(&b, other.half, n) - d.dot(n).abs())
            .fold(vertical, f32::min)
    }
}

/// A box's closed surface, normals outward: 8 corners and 12 triangles
/// appended to `vertices` and `triangles`.
fn push_box(b: &YawBox, vertices: &mut Vec<Vec3>, triangles: &mut Vec<[u32; 3]>) {
    let base = vertices.len() as u32;
    vertices.extend(b.corners());
    // Corner k has x from bit 0, y from bit 1, z from bit 2; each face
    // counter-clockwise seen from outside.
    const FACES: [[u32; 4]; 6] = [
        [0, 4, 6, 2], // −x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // −y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // −z
        [4, 5, 7, 6], // +z
    ];
    for [a, b, c, d] in FACES {
        triangles.push([base + a, base + b, base + c]);
        triangles.push([base + a, base + c, base + d]);
    }
}

/// The boxes of a made piece in its own frame (origin at the middle of its
/// footprint on the floor, +y up; a chair's back along −z), m.
fn made_parts(kind: FurnitureKind, [w, h, d]: [f32; 3]) -> Vec<(Vec3, Vec3)> {
    let part = |lo: Vec3, hi: Vec3| ((lo + hi) * 0.5, (hi - lo) * 0.5);
    let legs = |side: f32, inset: f32, top: f32| {
        let (x, z) = (0.5 * w - inset - 0.5 * side, 0.5 * d - inset - 0.5 * side);
        [(-x, -z), (x, -z), (-x, z), (x, z)].map(|(cx, cz)| {
            part(
                Vec3::new(cx - 0.5 * side, 0.0, cz - 0.5 * side),
                Vec3::new(cx + 0.5 * side, top, cz + 0.5 * side),
            )
        })
    };
    let smallest = w.min(d);
    match kind {
        FurnitureKind::Table => {
            let top = TABLE_TOP_M.min(0.25 * h);
            let side = TABLE_LEG_M.min(0.2 * smallest);
            let inset = TABLE_LEG_INSET_M.min(0.1 * smallest);
            let mut parts = vec![part(
                Vec3::new(-0.5 * w, h - top, -0.5 * d),
                Vec3::new(0.5 * w, h, 0.5 * d),
            )];
            parts.extend(legs(side, inset, h - top));
            parts
        }
        FurnitureKind::Chair => {
            let seat_top = 0.5 * h;
            let seat = CHAIR_SEAT_M.min(0.25 * seat_top);
            let side = CHAIR_LEG_M.min(0.2 * smallest);
            let back = CHAIR_BACK_M.min(0.2 * d);
            let mut parts = vec![
                part(
                    Vec3::new(-0.5 * w, seat_top - seat, -0.5 * d),
                    Vec3::new(0.5 * w, seat_top, 0.5 * d),
                ),
                part(
                    Vec3::new(-0.5 * w, seat_top, -0.5 * d),
                    Vec3::new(0.5 * w, h, -0.5 * d + back),
                ),
            ];
            parts.extend(legs(side, 0.0, seat_top - seat));
            parts
        }
    }
}

/// Piece `i` of `scene`, built in the world frame.
fn build_piece(scene: &Scene, i: usize) -> Result<FurniturePiece, SceneError> {
    let spec = &scene.furniture[i];
    let yaw = spec.yaw_deg.to_radians();
    let (q, position) = (Quat::from_rotation_y(yaw), Vec3::from_array(spec.position));
    let mut piece = FurniturePiece {
        label: spec.label(),
        kind: spec.kind,
        vertices: Vec::new(),
        triangles: Vec::new(),
        boxes: Vec::new(),
    };
    if let (Some(kind), Some(size)) = (spec.kind, spec.resolved_size()) {
        for (center, half) in made_parts(kind, size) {
            let b = YawBox {
                center: position + q * center,
                half,
                yaw,
            };
            push_box(&b, &mut piece.vertices, &mut piece.triangles);
            piece.boxes.push(b);
        }
        return Ok(piece);
    }
    let path = scene
        .furniture_mesh_path(i)
        .ok_or_else(|| SceneError::Invalid {
            at: scene.locate(&format!("furniture[{i}]")),
            expected: "kind = \"table\" | \"chair\", or mesh = \"file.obj\"".into(),
            found: "neither".into(),
        })?;
    let bad = |problem: String| SceneError::Invalid {
        at: scene.locate(&format!("furniture[{i}].mesh")),
        expected: "a closed OBJ mesh, in metres, Y up, its normals pointing out".into(),
        found: problem,
    };
    let mesh = read_obj_mesh(&path).map_err(|e| bad(e.to_string()))?;
    mesh.check_closed().map_err(|e| bad(e.to_string()))?;
    let (local, triangles) = mesh.into_parts();
    let volume = solid_integrals(&local, &triangles).volume;
    let (lo, hi) = local
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    let extent = (hi - lo).max_element();
    if volume.is_nan() || volume.abs() <= 1e-9 * extent * extent * extent {
        return Err(bad(format!(
            "{}: the mesh encloses no volume ({volume} m³)",
            path.display()
        )));
    }
    if volume < 0.0 {
        return Err(bad(format!(
            "{}: the mesh is inside out: its normals point in (signed volume {volume} m³)",
            path.display()
        )));
    }
    piece.vertices = local.iter().map(|&p| position + q * p).collect();
    piece.triangles = triangles;
    piece.boxes.push(YawBox {
        center: position + q * ((lo + hi) * 0.5),
        half: (hi - lo) * 0.5,
        yaw,
    });
    Ok(piece)
}

/// Where a point lies outside a box room's walls, floor or ceiling, if it does.
fn outside_box(p: Vec3, lo: Vec3, hi: Vec3) -> Option<String> {
    let tolerance = 1e-4;
    for (axis, name) in [(0, "x"), (2, "z")] {
        if p[axis] < lo[axis] - tolerance {
            return Some(format!("the wall at {name} = {} m", lo[axis]));
        }
        if p[axis] > hi[axis] + tolerance {
            return Some(format!("the wall at {name} = {} m", hi[axis]));
        }
    }
    if p.y < lo.y - tolerance {
        return Some(format!("the floor (y = {} m)", lo.y));
    }
    if p.y > hi.y + tolerance {
        return Some(format!("the ceiling (y = {} m)", hi.y));
    }
    None
}

/// Every piece of `scene`, built, each inside `room` and clear of the others.
pub fn build_furniture(scene: &Scene, room: &RoomMesh) -> Result<Vec<FurniturePiece>, SceneError> {
    let bounds = room.bounds();
    let mut pieces: Vec<FurniturePiece> = Vec::with_capacity(scene.furniture.len());
    for i in 0..scene.furniture.len() {
        let piece = build_piece(scene, i)?;
        let at = || scene.locate(&format!("furniture[{i}].position"));
        let spec = &scene.furniture[i];
        // Boxes are convex: their corners inside the room put them inside
        // (a mesh's bounding box stands in for it). Each corner is moved a
        // millimetre into its box first, off the floor it may stand on.
        let beyond = if scene.room.mesh.is_some() {
            "the room's mesh"
        } else {
            "the ceiling"
        };
        let through = piece.boxes.iter().find_map(|b| {
            b.corners().into_iter().find_map(|p| {
                outside_box(p, bounds.min, bounds.max).or_else(|| {
                    let nudged = p + (b.center - p).normalize_or_zero() * 1e-3;
                    (!room.contains_point(nudged)).then(|| beyond.to_string())
                })
            })
        });
        if let Some(wall) = through {
            return Err(SceneError::Invalid {
                at: at(),
                expected: format!("a {} standing inside the room", piece.label),
                found: format!("{:?}: it reaches through {wall}", spec.position),
            });
        }
        for (j, other) in pieces.iter().enumerate() {
            let depth = piece
                .boxes
                .iter()
                .flat_map(|a| other.boxes.iter().map(|b| a.overlap(b)))
                .fold(f32::NEG_INFINITY, f32::max);
            if depth > TOUCH_M {
                return Err(SceneError::Invalid {
                    at: at(),
                    expected: format!(
                        "a {} clear of furniture[{j}] (a {} at {:?})",
                        piece.label, other.label, scene.furniture[j].position
                    ),
                    found: format!("{:?}: the two overlap by {depth:.3} m", spec.position),
                });
            }
        }
        pieces.push(piece);
    }
    Ok(pieces)
}

/// The mesh the world collides with: the room's triangles, then each
/// piece's; the room's own mesh, unchanged, without furniture.
pub fn room_with_furniture(
    scene: &Scene,
    room: &RoomMesh,
    pieces: &[FurniturePiece],
) -> Result<TriMesh, SceneError> {
    if pieces.is_empty() {
        return Ok(room.to_trimesh());
    }
    let mut vertices = room.vertices().to_vec();
    let mut triangles = room.triangles().to_vec();
    for piece in pieces {
        let base = vertices.len() as u32;
        vertices.extend(&piece.vertices);
        triangles.extend(piece.triangles.iter().map(|t| t.map(|k| k + base)));
    }
    TriMesh::new(vertices, triangles).map_err(|e| SceneError::Room {
        at: scene.locate("furniture"),
        message: e.to_string(),
    })
}

/// Keeps balloons (and the ribbons the layout hangs) from starting inside
/// the pieces: spheres covering each box go into the layout's occupancy.
pub fn reserve(pieces: &[FurniturePiece], occupied: &mut Occupancy) {
    for b in pieces.iter().flat_map(|p| &p.boxes) {
        let q = b.rotation();
        // Coarser over a large box (a mesh piece's whole bounds), so a room-sized
        // piece reserves thousands of spheres, not millions.
        let mut spacing = RESERVE_SPACING_M;
        let mut cells = (2.0 * b.half / spacing).ceil().max(Vec3::ONE);
        while cells.x * cells.y * cells.z > MAX_RESERVE_SPHERES {
            spacing *= 1.25;
            cells = (2.0 * b.half / spacing).ceil().max(Vec3::ONE);
        }
        let step = 2.0 * b.half / cells;
        // A sphere through a cell's corners covers the cell.
        let radius = 0.5 * step.length();
        let n = cells.as_uvec3();
        for (x, y, z) in
            (0..n.x).flat_map(|x| (0..n.y).flat_map(move |y| (0..n.z).map(move |z| (x, y, z))))
        {
            let local = -b.half + step * (Vec3::new(x as f32, y as f32, z as f32) + 0.5);
            occupied.insert(b.center + q * local, radius);
        }
    }
}

#[cfg(test)]
#[path = "furniture_tests.rs"]
mod tests;
