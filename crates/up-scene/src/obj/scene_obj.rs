//! A whole scene as one Wavefront OBJ with its MTL, for Blender and other
//! tools (`up export-obj`): every balloon where the world has it, and every
//! ribbon as a thin flat strip along its points, each an OBJ object of its
//! own with a material of its colour, and every piece of furniture, flat
//! shaded in one wood material. The room is `obj_export::export_room_obj`.
//!
//! Balloons are the group's model mesh placed at the body's pose and size (smooth
//! normals); a ribbon is a strip `RIBBON_WIDTH` wide whose flat side is
//! carried along the ribbon without twisting (parallel transport of the
//! first point's side), so a hanging ribbon reads as a ribbon from the side
//! and as a line end on.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::Vec3;
use up_physics::ribbon::RIBBON_WIDTH;

use crate::build::{color_index, group_index, BuiltScene};
use crate::obj::ObjError;

/// The strip along `points`, `width` wide: two vertices a point, two
/// triangles a segment; with a normal a vertex (the strip's face).
pub struct Strip {
    pub vertices: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}

/// A direction at right angles to `t` (unit).
fn perpendicular(t: Vec3) -> Vec3 {
    let helper = if t.x.abs() < 0.9 { Vec3::X } else { Vec3::Z };
    t.cross(helper).normalize_or_zero()
}

/// A flat strip `width` wide centred on the polyline `points` (at least two
/// distinct points make a strip; fewer give an empty one).
pub fn ribbon_strip(points: &[Vec3], width: f32) -> Strip {
    let mut strip = Strip {
        vertices: Vec::with_capacity(2 * points.len()),
        normals: Vec::with_capacity(2 * points.len()),
        triangles: Vec::with_capacity(2 * points.len()),
    };
    if points.len() < 2 {
        return strip;
    }
    let half = 0.5 * width;
    let mut side = Vec3::ZERO;
    let mut last_tangent = Vec3::ZERO;
    for (i, &p) in points.iter().enumerate() {
        // Tangent: the mean of the segments on either side (a point on top
        // of its neighbour keeps the last tangent).
        let before = points[i.saturating_sub(1)];
        let after = points[(i + 1).min(points.len() - 1)];
        let tangent = (after - before).try_normalize().unwrap_or(last_tangent);
        // Carry the side over: what of it is across the new tangent.
        let carried = (side - side.dot(tangent) * tangent).normalize_or_zero();
        side = if carried == Vec3::ZERO {
            perpendicular(tangent)
        } else {
            carried
        };
        last_tangent = tangent;
        let normal = tangent.cross(side).normalize_or_zero();
        strip.vertices.push(p - half * side);
        strip.vertices.push(p + half * side);
        strip.normals.extend([normal, normal]);
    }
    for k in 0..points.len() as u32 - 1 {
        let (a, b, c, d) = (2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3);
        strip.triangles.push([a, b, d]);
        strip.triangles.push([a, d, c]);
    }
    strip
}

/// A material name from a colour's name: `red`, or `#d4af37` as `d4af37`.
fn material_name(prefix: &str, color: &str) -> String {
    let clean: String = color
        .chars()
        .filter(|c| c.is_ascii_alphanumeric())
        .map(|c| c.to_ascii_lowercase())
        .collect();
    format!("{prefix}_{clean}")
}

/// Six decimals: micrometres; adding zero turns −0 into +0.
fn push_vec3(out: &mut String, tag: &str, v: Vec3) {
    let v = v + Vec3::ZERO;
    let _ = writeln!(out, "{tag} {:.6} {:.6} {:.6}", v.x, v.y, v.z);
}

/// One object of the file: its vertices and normals (world frame) and its
/// triangles, indexing both.
struct ObjObject<'a> {
    name: String,
    material: &'a str,
    /// Smooth shading (`s 1`) or flat (`s off`).
    smooth: bool,
    vertices: Vec<Vec3>,
    normals: Vec<Vec3>,
    triangles: &'a [[u32; 3]],
}

impl ObjObject<'_> {
    /// Appends the object to `obj`; `next` holds the file's next vertex and
    /// normal indices (OBJ counts from 1 over the whole file) and moves on.
    fn write(&self, obj: &mut String, next: &mut (u32, u32)) {
        let _ = writeln!(obj, "o {}", self.name);
        for &p in &self.vertices {
            push_vec3(obj, "v", p);
        }
        for &n in &self.normals {
            push_vec3(obj, "vn", n);
        }
        let shading = if self.smooth { "1" } else { "off" };
        let _ = writeln!(obj, "usemtl {}\ns {shading}", self.material);
        for t in self.triangles {
            let [a, b, c] = t.map(|i| i + next.0);
            let [na, nb, nc] = t.map(|i| i + next.1);
            let _ = writeln!(obj, "f {a}//{na} {b}//{nb} {c}//{nc}");
        }
        next.0 += self.vertices.len() as u32;
        next.1 += self.normals.len() as u32;
    }
}

fn push_material(mtl: &mut String, name: &str, rgb: [f32; 3], shine: bool) {
    let [r, g, b] = rgb;
    let (ks, ns) = if shine { (0.35, 120.0) } else { (0.1, 20.0) };
    let _ = writeln!(
        mtl,
        "newmtl {name}\nKa 0.000 0.000 0.000\nKd {r:.3} {g:.3} {b:.3}\n\
         Ks {ks:.3} {ks:.3} {ks:.3}\nNs {ns:.1}\nd 1.0\nillum 2\n"
    );
}

/// The furniture's material: a mid oak, sRGB.
const WOOD_RGB: [f32; 3] = [0.55, 0.36, 0.2];

/// A piece's triangles flat shaded: three vertices and a face normal each.
fn flat_object<'a>(
    name: String,
    material: &'a str,
    vertices: &[Vec3],
    triangles: &[[u32; 3]],
    corners: &'a mut Vec<[u32; 3]>,
) -> ObjObject<'a> {
    let mut object_vertices = Vec::with_capacity(3 * triangles.len());
    let mut normals = Vec::with_capacity(3 * triangles.len());
    corners.clear();
    for t in triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        let base = object_vertices.len() as u32;
        object_vertices.extend([a, b, c]);
        normals.extend([n; 3]);
        corners.push([base, base + 1, base + 2]);
    }
    ObjObject {
        name,
        material,
        smooth: false,
        vertices: object_vertices,
        normals,
        triangles: corners,
    }
}

/// The OBJ and MTL text of the scene as the world has it now; the OBJ
/// names `mtllib`.
pub fn scene_obj_text(built: &BuiltScene, mtllib: &str) -> (String, String) {
    let world = &built.world;
    let mut obj = String::new();
    let mut mtl = String::from("# UP scene materials\n");
    let mut materials: Vec<String> = Vec::new();
    let mut use_material = |mtl: &mut String, name: String, rgb: [f32; 3], shine: bool| {
        if !materials.contains(&name) {
            push_material(mtl, &name, rgb, shine);
            materials.push(name.clone());
        }
        name
    };
    let _ = writeln!(
        obj,
        "# UP scene: metres, +Y up, origin at the centre of the floor\n\
         # {} balloons, {} ribbons, {} pieces of furniture\nmtllib {mtllib}",
        world.body_count(),
        world.ribbon_count(),
        built.furniture.len()
    );
    // OBJ indices count from 1 over the whole file.
    let mut next = (1u32, 1u32);
    for &id in world.body_ids() {
        let (Some(pose), Some(user_data)) = (world.pose(id), world.user_data(id)) else {
            continue;
        };
        let Some(model) = built.balloon_models.get(group_index(user_data)) else {
            continue;
        };
        let color = color_index(user_data);
        let (Some(&rgb), Some(name)) = (built.colors.get(color), built.color_names.get(color))
        else {
            continue;
        };
        let material = use_material(&mut mtl, material_name("balloon", name), rgb, true);
        let mesh = &model.mesh;
        // The size its gas has left it (1 without gas).
        let scale = world.body_scale(id).unwrap_or(1.0);
        let object = ObjObject {
            name: format!("balloon_{}", id.index),
            material: &material,
            smooth: true,
            vertices: mesh
                .positions
                .iter()
                .map(|&p| pose.position + pose.rotation * (p * scale))
                .collect(),
            normals: mesh.normals.iter().map(|&n| pose.rotation * n).collect(),
            triangles: &mesh.indices,
        };
        object.write(&mut obj, &mut next);
    }
    for id in world.ribbon_ids() {
        let (Some(body), Some(points)) = (world.ribbon_body(id), world.ribbon_points(id)) else {
            continue;
        };
        let group = world.user_data(body).map(group_index);
        let ribbon = group.and_then(|g| built.group_ribbons.get(g)?.as_ref());
        let (color, rgb) = match ribbon {
            Some(r) => (r.spec.color.as_str(), r.rgb),
            None => ("white", [1.0; 3]),
        };
        let material = use_material(&mut mtl, material_name("ribbon", color), rgb, false);
        let strip = ribbon_strip(points, RIBBON_WIDTH);
        let object = ObjObject {
            name: format!("ribbon_{}", body.index),
            material: &material,
            smooth: false,
            vertices: strip.vertices,
            normals: strip.normals,
            triangles: &strip.triangles,
        };
        object.write(&mut obj, &mut next);
    }
    let mut corners = Vec::new();
    for (i, piece) in built.furniture.iter().enumerate() {
        let material = use_material(&mut mtl, "furniture_wood".into(), WOOD_RGB, false);
        let label: String = piece
            .label
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        let name = format!("furniture_{i}_{label}");
        flat_object(
            name,
            &material,
            &piece.vertices,
            &piece.triangles,
            &mut corners,
        )
        .write(&mut obj, &mut next);
    }
    (obj, mtl)
}

/// Writes `scene.obj` and `scene.mtl` into `dir`, each whole or not at all;
/// returns their paths.
pub fn export_scene_obj(dir: &Path, built: &BuiltScene) -> Result<Vec<PathBuf>, ObjError> {
    let (obj_text, mtl_text) = scene_obj_text(built, "scene.mtl");
    let mut written = Vec::new();
    for (name, text) in [("scene.obj", obj_text), ("scene.mtl", mtl_text)] {
        let path = dir.join(name);
        crate::atomic_file::write_atomically(&path, text.as_bytes()).map_err(|e| {
            ObjError::Write {
                path: path.clone(),
                source: e.into_io_error(),
            }
        })?;
        written.push(path);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::build_world;
    use crate::scene::Scene;

    #[test]
    fn a_strip_follows_its_points_at_its_width_without_twisting() {
        // A ribbon hanging, then lying along the floor.
        let points = [
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.5, 0.0),
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.5, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
        ];
        let strip = ribbon_strip(&points, 0.005);
        assert_eq!(strip.vertices.len(), 10);
        assert_eq!(strip.triangles.len(), 8);
        for (k, p) in points.iter().enumerate() {
            let (a, b) = (strip.vertices[2 * k], strip.vertices[2 * k + 1]);
            assert!(((a + b) * 0.5).distance(*p) < 1e-6, "centred on the point");
            assert!((a.distance(b) - 0.005).abs() < 1e-6, "its width");
        }
        // The side never flips from one point to the next.
        for k in 0..points.len() - 1 {
            let side = strip.vertices[2 * k + 1] - strip.vertices[2 * k];
            let next = strip.vertices[2 * k + 3] - strip.vertices[2 * k + 2];
            assert!(side.dot(next) > 0.0, "twisted at {k}");
        }
        assert!(strip
            .normals
            .iter()
            .all(|n| (n.length() - 1.0).abs() < 1e-5));
        assert!(ribbon_strip(&points[..1], 0.005).triangles.is_empty());
    }

    #[test]
    fn the_scene_obj_has_an_object_a_balloon_and_a_ribbon_with_their_colours() {
        let text = "[[balloons]]\ncount = 2\ncolors = [\"red\", \"#102030\"]\n\
                    [balloons.ribbon]\ncolor = \"#d4af37\"\nsegments = 4\n\
                    [[balloons]]\ncount = 1\ncolors = [\"blue\"]\n";
        let built = build_world(&Scene::from_toml_str(text, "t.toml").unwrap()).unwrap();
        let dir = std::env::temp_dir().join(format!("up-scene-scene-obj-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let written = export_scene_obj(&dir, &built).unwrap();
        assert_eq!(written.len(), 2);
        let (models, materials) =
            tobj::load_obj(&written[0], &tobj::LoadOptions::default()).unwrap();
        let materials = materials.unwrap();
        let names: Vec<&str> = models.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(
            names.iter().filter(|n| n.starts_with("balloon_")).count(),
            3
        );
        assert_eq!(names.iter().filter(|n| n.starts_with("ribbon_")).count(), 2);
        let material_of = |model: &tobj::Model| &materials[model.mesh.material_id.unwrap()];
        for model in &models {
            let m = material_of(model);
            if model.name.starts_with("ribbon_") {
                assert_eq!(m.name, "ribbon_d4af37");
                let d = m.diffuse.unwrap();
                assert!((d[0] - 0xd4 as f32 / 255.0).abs() < 2e-3, "{d:?}");
                // 5 points, two vertices each, where the world has them.
                assert_eq!(model.mesh.positions.len(), 5 * 2 * 3);
            }
        }
        let balloon_materials: Vec<&str> = models
            .iter()
            .filter(|m| m.name.starts_with("balloon_"))
            .map(|m| material_of(m).name.as_str())
            .collect();
        assert_eq!(
            balloon_materials,
            ["balloon_red", "balloon_102030", "balloon_blue"]
        );
        // Each balloon is the model mesh at its pose: its bottom pole, a
        // vertex, is the knot where the ribbon is tied.
        let world = &built.world;
        let body = world.body_ids()[0];
        let pose = world.pose(body).unwrap();
        let knot = pose.position
            + pose.rotation * crate::build::ribbons::knot_point(&built.balloon_models[0]);
        let ribbon = world.ribbon_of(body).unwrap();
        assert!(knot.distance(world.ribbon_points(ribbon).unwrap()[0]) < 1e-5);
        let nearest = models[0]
            .mesh
            .positions
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]).distance(knot))
            .fold(f32::INFINITY, f32::min);
        assert!(nearest < 1e-5, "{nearest} m");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_scene_obj_has_each_piece_of_furniture_where_it_stands_in_wood() {
        let text = "[[furniture]]\nkind = \"table\"\nposition = [1, 0, 0]\n\
                    [[furniture]]\nkind = \"chair\"\nposition = [-1, 0, 0]\n";
        let built = build_world(&Scene::from_toml_str(text, "t.toml").unwrap()).unwrap();
        let (obj, mtl) = scene_obj_text(&built, "scene.mtl");
        assert!(mtl.contains("newmtl furniture_wood"), "{mtl}");
        assert!(obj.contains("o furniture_0_table") && obj.contains("o furniture_1_chair"));
        let (models, _) = tobj::load_obj_buf(
            &mut std::io::Cursor::new(obj),
            &tobj::LoadOptions::default(),
            |_| Ok((Vec::new(), Default::default())),
        )
        .unwrap();
        let table = models
            .iter()
            .find(|m| m.name == "furniture_0_table")
            .unwrap();
        let piece = &built.furniture[0];
        assert_eq!(table.mesh.indices.len(), 3 * piece.triangles.len());
        let xs = table.mesh.positions.chunks_exact(3).map(|p| p[0]);
        let (lo, hi) = xs.fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
        assert!(
            (lo - 0.4).abs() < 1e-5 && (hi - 1.6).abs() < 1e-5,
            "{lo} to {hi}"
        );
    }
}
