//! `[[furniture]]`: static pieces standing in the room, a table or a chair
//! made to a size, or any closed OBJ mesh. Balloons and ribbons collide with
//! them as with the room (`build::furniture` adds their triangles to the
//! room's mesh). Their ranges are checked here (`check`), with the file,
//! line and key path of a bad value; where a piece stands against the room
//! and the other pieces is checked when it is built, its shape known.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::validate::Checker;
use super::Scene;
use crate::error::SceneError;

/// Most pieces a scene may list: their triangles join the room's, which
/// every balloon near them tests each step.
pub const MAX_FURNITURE: usize = 64;
/// Size range of a made piece along each axis, m.
pub const MIN_FURNITURE_SIZE_M: f32 = 0.1;
pub const MAX_FURNITURE_SIZE_M: f32 = 10.0;
/// A dining table for four: 1.2 m × 0.8 m, its top 0.75 m high.
pub const DEFAULT_TABLE_SIZE_M: [f32; 3] = [1.2, 0.75, 0.8];
/// A dining chair: 0.45 m wide, its back 0.9 m high, 0.5 m deep (its seat
/// at half its height).
pub const DEFAULT_CHAIR_SIZE_M: [f32; 3] = [0.45, 0.9, 0.5];

/// What a made piece is.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FurnitureKind {
    /// A top on four legs.
    Table,
    /// A seat on four legs, with a back along its −z side.
    Chair,
}

impl FurnitureKind {
    /// The name scene files use.
    pub fn name(self) -> &'static str {
        match self {
            FurnitureKind::Table => "table",
            FurnitureKind::Chair => "chair",
        }
    }

    /// Width, height, depth a piece of this kind gets when its `size` is left out, m.
    pub fn default_size(self) -> [f32; 3] {
        match self {
            FurnitureKind::Table => DEFAULT_TABLE_SIZE_M,
            FurnitureKind::Chair => DEFAULT_CHAIR_SIZE_M,
        }
    }
}

/// One piece of furniture (`[[furniture]]`): `kind` or `mesh`, one of the two.
#[cfg_attr(feature = "tsify", derive(tsify_next::Tsify))]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FurnitureSpec {
    /// `"table"` or `"chair"`: made to `size`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<FurnitureKind>,
    /// A closed OBJ mesh instead (metres, Y up, its origin at `position`),
    /// relative to the scene file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<String>,
    /// m, world frame: the middle of a made piece's footprint on the floor
    /// (y = 0), or where a mesh's origin goes. Required; inside the room.
    #[serde(deserialize_with = "super::parse::xyz")]
    pub position: [f32; 3],
    /// Degrees about the vertical (counter-clockwise seen from above); 0.
    /// Range [−360, 360].
    #[serde(default)]
    pub yaw_deg: f32,
    /// m: width (x), height (y), depth (z) of a made piece; a table
    /// [1.2, 0.75, 0.8], a chair [0.45, 0.9, 0.5]. Each in [0.1, 10].
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "super::parse::point"
    )]
    pub size: Option<[f32; 3]>,
}

impl FurnitureSpec {
    /// A made piece of `kind` at `position`, every other key left out.
    pub fn made(kind: FurnitureKind, position: [f32; 3]) -> FurnitureSpec {
        FurnitureSpec {
            kind: Some(kind),
            mesh: None,
            position,
            yaw_deg: 0.0,
            size: None,
        }
    }

    /// A made piece's size: as given, or its kind's default.
    pub fn resolved_size(&self) -> Option<[f32; 3]> {
        let kind = self.kind?;
        Some(self.size.unwrap_or(kind.default_size()))
    }

    /// What the piece is, for messages: `table`, `chair`, or its mesh's name.
    pub fn label(&self) -> String {
        match (&self.kind, &self.mesh) {
            (Some(kind), _) => kind.name().to_string(),
            (None, Some(mesh)) => format!("mesh {mesh}"),
            (None, None) => "piece".to_string(),
        }
    }
}

impl Scene {
    /// The mesh path of piece `i`, resolved against the scene file's directory.
    pub fn furniture_mesh_path(&self, i: usize) -> Option<PathBuf> {
        let mesh = Path::new(self.furniture.get(i)?.mesh.as_ref()?);
        Some(match &self.source.dir {
            Some(dir) if mesh.is_relative() => dir.join(mesh),
            _ => mesh.to_path_buf(),
        })
    }
}

/// Every piece within its ranges: a kind or a mesh, a finite position in
/// the room's box, a yaw, a size for a made piece only.
pub(super) fn check(c: &Checker) -> Result<(), SceneError> {
    let scene = c.scene;
    let pieces = &scene.furniture;
    if pieces.len() > MAX_FURNITURE {
        return Err(c.fail(
            &format!("furniture[{MAX_FURNITURE}]"),
            format!("at most {MAX_FURNITURE} pieces of furniture"),
            pieces.len().to_string(),
        ));
    }
    let room = &scene.room;
    let bounds = room.mesh.is_none().then(|| {
        let (hx, hz) = (room.width / 2.0, room.depth / 2.0);
        ([-hx, 0.0, -hz], [hx, room.top(), hz])
    });
    for (i, piece) in pieces.iter().enumerate() {
        let key = |k: &str| format!("furniture[{i}].{k}");
        match (&piece.kind, &piece.mesh) {
            (Some(_), Some(_)) => {
                return Err(c.fail(&key("mesh"), "either kind or mesh, not both", "both"))
            }
            (None, None) => {
                return Err(c.fail(
                    &format!("furniture[{i}]"),
                    "kind = \"table\" or \"chair\", or mesh = \"file.obj\"",
                    "neither",
                ))
            }
            (None, Some(mesh)) if mesh.trim().is_empty() => {
                return Err(c.fail(&key("mesh"), "a path to an OBJ file", "an empty string"))
            }
            (None, Some(_)) if piece.size.is_some() => {
                return Err(c.fail(
                    &key("size"),
                    "no size for a mesh (it is drawn in metres as it is)",
                    format!("{:?}", piece.size.unwrap_or_default()),
                ))
            }
            _ => {}
        }
        let p = piece.position;
        let inside = match bounds {
            Some((lo, hi)) => (0..3).all(|a| lo[a] <= p[a] && p[a] <= hi[a]),
            None => true,
        };
        if !(p.iter().all(|x| x.is_finite()) && inside) {
            let expected = match bounds {
                Some((lo, hi)) => {
                    format!("a point [x, y, z] inside the room, from {lo:?} to {hi:?} m")
                }
                None => "a finite point [x, y, z], m".to_string(),
            };
            return Err(c.fail(&key("position"), expected, format!("{p:?}")));
        }
        c.range(&key("yaw_deg"), piece.yaw_deg, -360.0, 360.0, false, "°")?;
        if let Some(size) = piece.size {
            for (axis, &s) in size.iter().enumerate() {
                c.range(
                    &format!("{}[{axis}]", key("size")),
                    s,
                    MIN_FURNITURE_SIZE_M,
                    MAX_FURNITURE_SIZE_M,
                    false,
                    "m",
                )?;
            }
        }
    }
    Ok(())
}
