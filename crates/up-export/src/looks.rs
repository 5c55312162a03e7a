//! What a recorded world looks like, taken once from the built scene: each
//! balloon model's mesh and finish, each balloon's id and colour, each
//! ribbon's balloon, length in points, colour and weight, and the room's
//! triangles; and where the camera and the page's lights stand in it.

use glam::{Mat3, Quat, Vec3};
use up_physics::ribbon::RIBBON_WIDTH;
use up_scene::build::{color_index, group_index, BuiltScene};
use up_scene::ribbons::ribbon_rgb;
use up_scene::scene::{Finish, RibbonSpec, Scene};

/// A balloon model: its surface in its body frame (the mesh `up export-obj`
/// and the page draw) and how it is drawn.
#[derive(Clone, Debug)]
pub struct ModelLook {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
    pub finish: Finish,
}

/// One balloon: its id (as `up run --out` writes it), model and colour.
#[derive(Clone, Debug)]
pub struct BalloonLook {
    pub id: u32,
    pub model: usize,
    /// Display sRGB, 0–1, and the name the scene gave it.
    pub rgb: [f32; 3],
    pub color_name: String,
}

/// One ribbon: the balloon it hangs from (its id), its points, its look.
#[derive(Clone, Debug)]
pub struct RibbonLook {
    pub balloon: u32,
    pub points: usize,
    /// Display sRGB, 0–1.
    pub rgb: [f32; 3],
    /// Whether a weight hangs at the free end.
    pub weighted: bool,
}

/// Everything about a recorded world that does not move.
#[derive(Clone, Debug)]
pub struct SceneLooks {
    pub models: Vec<ModelLook>,
    pub balloons: Vec<BalloonLook>,
    pub ribbons: Vec<RibbonLook>,
    pub room_vertices: Vec<Vec3>,
    /// Wound so that their normals point into the room.
    pub room_triangles: Vec<[u32; 3]>,
    /// Every piece of furniture's surface, world frame, normals outward.
    pub furniture_vertices: Vec<Vec3>,
    pub furniture_triangles: Vec<[u32; 3]>,
    /// m: the flat strip a ribbon is drawn as.
    pub ribbon_width: f32,
}

impl SceneLooks {
    /// The looks of `built`, the world of `scene`, as it is now.
    pub fn of(scene: &Scene, built: &BuiltScene) -> SceneLooks {
        let world = &built.world;
        let models = built
            .balloon_models
            .iter()
            .enumerate()
            .map(|(g, model)| ModelLook {
                positions: model.mesh.positions.clone(),
                normals: model.mesh.normals.clone(),
                triangles: model.mesh.indices.clone(),
                finish: scene.balloons.get(g).map_or(Finish::Latex, |b| b.finish()),
            })
            .collect();
        let balloons = world
            .body_ids()
            .iter()
            .map(|&id| {
                let user_data = world.user_data(id).unwrap_or(0);
                let color = color_index(user_data);
                BalloonLook {
                    id: id.index,
                    model: group_index(user_data),
                    rgb: built.colors.get(color).copied().unwrap_or([1.0; 3]),
                    color_name: built.color_names.get(color).cloned().unwrap_or_default(),
                }
            })
            .collect();
        let ribbons = world
            .ribbon_ids()
            .into_iter()
            .filter_map(|r| {
                let body = world.ribbon_body(r)?;
                let group = world.user_data(body).map_or(0, group_index);
                let ribbon = built.group_ribbons.get(group).and_then(Option::as_ref);
                Some(RibbonLook {
                    balloon: body.index,
                    points: world.ribbon_points(r)?.len(),
                    rgb: ribbon.map_or_else(|| ribbon_rgb(&RibbonSpec::default()), |r| r.rgb),
                    weighted: ribbon.is_some_and(|r| r.spec.weight_g > 0.0),
                })
            })
            .collect();
        SceneLooks {
            models,
            balloons,
            ribbons,
            room_vertices: built.room.vertices().to_vec(),
            room_triangles: built.room.triangles().to_vec(),
            furniture_vertices: built
                .furniture
                .iter()
                .flat_map(|p| p.vertices.iter().copied())
                .collect(),
            furniture_triangles: furniture_triangles(built),
            ribbon_width: RIBBON_WIDTH,
        }
    }

    /// The room's half width (x), half depth (z) and highest point (y), m.
    pub fn room_box(&self) -> (f32, f32, f32) {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for &v in &self.room_vertices {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if lo.x > hi.x {
            return (3.0, 3.0, 4.5);
        }
        (0.5 * (hi.x - lo.x), 0.5 * (hi.z - lo.z), hi.y)
    }
}

/// sRGB (as the palette is written) to the linear values glTF's factors take.
pub fn linear_from_srgb(rgb: [f32; 3]) -> [f32; 3] {
    rgb.map(|c| {
        let c = c.clamp(0.0, 1.0);
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    })
}

/// 0xRRGGBB (sRGB) to linear 0–1.
pub fn linear_from_hex(hex: u32) -> [f32; 3] {
    linear_from_srgb([16, 8, 0].map(|shift| ((hex >> shift) & 0xff) as f32 / 255.0))
}

/// The rotation that turns a glTF camera or light (looking down its −Z,
/// +Y up) at `eye` toward `target`.
pub fn look_rotation(eye: Vec3, target: Vec3) -> Quat {
    let back = (eye - target).normalize_or_zero();
    let back = if back == Vec3::ZERO { Vec3::Z } else { back };
    let up = if back.y.abs() > 0.999 {
        Vec3::Z
    } else {
        Vec3::Y
    };
    let right = up.cross(back).normalize();
    let up = back.cross(right);
    Quat::from_mat3(&Mat3::from_cols(right, up, back)).normalize()
}

/// The pieces' triangles, indexing their vertices laid one piece after another.
fn furniture_triangles(built: &BuiltScene) -> Vec<[u32; 3]> {
    let mut base = 0u32;
    let mut out = Vec::new();
    for piece in &built.furniture {
        out.extend(piece.triangles.iter().map(|t| t.map(|k| k + base)));
        base += piece.vertices.len() as u32;
    }
    out
}

/// A camera standing in the room, 10 cm in from the walls in the direction
/// the page's first view comes from (azimuth 0.6 rad), at under half the
/// room's top (below where a pyramid's slopes meet the walls), looking up at
/// the room's centre: inside, so that a renderer that draws both sides of
/// the walls and ceiling still sees the balloons.
pub fn camera_pose(half_width: f32, half_depth: f32, top: f32) -> (Vec3, Quat) {
    let center = Vec3::new(0.0, top * 0.55, 0.0);
    let (sin, cos) = 0.6f32.sin_cos();
    let reach = ((half_width - 0.1) / sin)
        .min((half_depth - 0.1) / cos)
        .max(0.1);
    let eye = center + Vec3::new(sin * reach, -0.1 * top, cos * reach);
    (eye, look_rotation(eye, center))
}

/// The page's lights (web/src/render/roomLights.ts): the key light standing
/// for the ceiling lamps (directional, toward the floor's centre) and the
/// warm fill lamp low in the far corner (a point light).
pub struct PageLight {
    pub name: &'static str,
    pub directional: bool,
    /// Linear RGB.
    pub color: [f32; 3],
    pub intensity: f32,
    pub position: Vec3,
    pub rotation: Quat,
}

/// The page's key and fill lights for a room of these half sizes and top, m.
pub fn page_lights(half_width: f32, half_depth: f32, top: f32) -> [PageLight; 2] {
    let key = Vec3::new(half_width * 0.6, top * 2.2, half_depth * 0.9);
    [
        PageLight {
            name: "key-light",
            directional: true,
            color: linear_from_hex(0xfff1dc),
            intensity: 2.2,
            position: key,
            rotation: look_rotation(key, Vec3::ZERO),
        },
        PageLight {
            name: "fill-lamp",
            directional: false,
            color: linear_from_hex(0xffe2c0),
            intensity: 2.0 * (half_width * half_depth / 9.0).max(1.0),
            position: Vec3::new(-half_width * 0.4, top * 0.8, -half_depth * 0.3),
            rotation: Quat::IDENTITY,
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_looking_rotation_turns_minus_z_toward_the_target() {
        let eye = Vec3::new(2.0, 1.0, 3.0);
        let target = Vec3::new(0.0, 2.0, -1.0);
        let q = look_rotation(eye, target);
        let forward = q * Vec3::NEG_Z;
        assert!(
            forward.distance((target - eye).normalize()) < 1e-5,
            "{forward}"
        );
        assert!((q * Vec3::Y).y > 0.0, "upright");
    }

    #[test]
    fn the_camera_stands_inside_the_room() {
        let (eye, _) = camera_pose(3.0, 3.0, 4.5);
        assert!(eye.x.abs() < 3.0 && eye.z.abs() < 3.0 && eye.y > 0.0);
        assert!(eye.y < 0.5 * 4.5, "below a pyramid's eaves: {eye}");
    }

    #[test]
    fn srgb_becomes_linear() {
        assert_eq!(linear_from_srgb([0.0, 1.0, 0.0]), [0.0, 1.0, 0.0]);
        assert!((linear_from_srgb([0.5; 3])[0] - 0.214).abs() < 1e-3);
        assert!((linear_from_hex(0x808080)[1] - 0.2158).abs() < 1e-3);
    }
}
