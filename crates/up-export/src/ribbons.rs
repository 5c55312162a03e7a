//! Ribbons as skinned strips: each ribbon point is a joint, a node
//! `ribbon-<id>-<k>` (k from 0 at the knot) under the ribbon's node
//! `ribbon-<id>`, whose translation channel is that point's path in world
//! coordinates; the strip (`ribbon-<id>-strip`, the flat 5 mm strip `up
//! export-obj` writes, at the first frame) binds each of its two vertices
//! at a point wholly to that point's joint. A weight at the free end is a
//! small metal ball, a node `weight-<id>` under the last joint; a free end
//! without one curls, as the page draws it: a helix of the page's radius,
//! turns and length (web/src/render/ribbons.ts) hanging from the last joint,
//! a node `ribbon-<id>-curl`.

use glam::{Quat, Vec3};
use gltf_json as json;
use json::accessor::Type;
use json::animation::Property;
use json::mesh::Semantic;
use json::{Index, Material, Mesh, Node, Skin};
use up_physics::ribbon::WEIGHT_RADIUS;
use up_scene::scene_obj::ribbon_strip;

use crate::builder::Builder;
use crate::glb::Elements;
use crate::looks::{linear_from_srgb, RibbonLook};
use crate::materials::plain;
use crate::recording::Recording;

/// The page's curl at a free end: length, m, helix radius, m, and turns.
const CURL_LENGTH: f32 = 0.18;
const CURL_RADIUS: f32 = 0.011;
const CURL_TURNS: f32 = 6.0;
/// Samples along the curl.
const CURL_SAMPLES: u32 = 96;

/// The curl as a strip `width` wide wound on a helix about the vertical
/// through its top, hanging down from the origin: positions, normals
/// (outward from the axis), triangles.
fn curl(width: f32) -> (Vec<Vec3>, Vec<Vec3>, Vec<[u32; 3]>) {
    let (mut positions, mut normals, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    let half = Vec3::new(0.0, 0.5 * width, 0.0);
    for i in 0..=CURL_SAMPLES {
        let along = i as f32 / CURL_SAMPLES as f32;
        let angle = std::f32::consts::TAU * CURL_TURNS * along;
        let out = Vec3::new(angle.cos(), 0.0, angle.sin());
        // Starts at the origin: the axis is one radius from the free end.
        let p = CURL_RADIUS * (out - Vec3::X) - Vec3::Y * (CURL_LENGTH * along);
        positions.extend([p - half, p + half]);
        normals.extend([out, out]);
        if i > 0 {
            let a = 2 * (i - 1);
            triangles.extend([[a, a + 2, a + 1], [a + 1, a + 2, a + 3]]);
        }
    }
    (positions, normals, triangles)
}

/// A UV sphere of `radius`: positions, normals, triangles.
fn sphere(radius: f32) -> (Vec<Vec3>, Vec<Vec3>, Vec<[u32; 3]>) {
    const RINGS: u32 = 8;
    const SEGMENTS: u32 = 12;
    let mut normals = Vec::new();
    for r in 0..=RINGS {
        let polar = std::f32::consts::PI * r as f32 / RINGS as f32;
        for s in 0..=SEGMENTS {
            let azimuth = std::f32::consts::TAU * s as f32 / SEGMENTS as f32;
            normals.push(Vec3::new(
                polar.sin() * azimuth.cos(),
                polar.cos(),
                polar.sin() * azimuth.sin(),
            ));
        }
    }
    let mut triangles = Vec::new();
    let row = SEGMENTS + 1;
    for r in 0..RINGS {
        for s in 0..SEGMENTS {
            let (a, b) = (r * row + s, (r + 1) * row + s);
            if r > 0 {
                triangles.push([a, a + 1, b]);
            }
            if r + 1 < RINGS {
                triangles.push([a + 1, b + 1, b]);
            }
        }
    }
    let positions = normals.iter().map(|&n| n * radius).collect();
    (positions, normals, triangles)
}

/// Adds every ribbon of `recording` to the document; returns the nodes to
/// put at the scene's root.
pub fn add_ribbons(b: &mut Builder, recording: &Recording) -> Vec<Index<Node>> {
    let frames: Vec<_> = recording.frames().collect();
    let Some(first) = frames.first() else {
        return Vec::new();
    };
    let mut roots = Vec::new();
    // Made on first use, one per colour: a material no node draws is a validator's notice.
    let mut strips: Vec<([f32; 3], Index<Material>)> = Vec::new();
    let mut weights: Vec<([f32; 3], Index<Material>)> = Vec::new();
    let mut curls: Vec<([f32; 3], Index<Mesh>)> = Vec::new();
    let mut curl_surface = None;
    let mut offset = 0;
    for look in &recording.looks.ribbons {
        let n = look.points;
        let range = offset..offset + n;
        offset += n;
        if n < 2 {
            continue;
        }
        let (rgb, hex) = (
            linear_from_srgb(look.rgb),
            crate::document::hex_name(look.rgb),
        );
        let strip_material = material_for(&mut strips, look.rgb, || {
            b.root.push(Material {
                double_sided: true,
                ..plain(format!("ribbon-{hex}"), rgb, 0.6, 0.0)
            })
        });
        let bind = &first.ribbon_points[range.clone()];
        let id = look.balloon;
        let joints: Vec<Index<Node>> = (0..n)
            .map(|k| {
                let joint = b.node(format!("ribbon-{id}-{k}"), bind[k], Quat::IDENTITY);
                let path: Vec<f32> = frames
                    .iter()
                    .flat_map(|f| f.ribbon_points[range.start + k].to_array())
                    .collect();
                b.channel(joint, Property::Translation, &path);
                joint
            })
            .collect();
        if look.weighted {
            let material = material_for(&mut weights, look.rgb, || {
                b.root.push(plain(format!("weight-{hex}"), rgb, 0.25, 1.0))
            });
            add_weight(b, joints[n - 1], id, material);
        } else {
            let surface = *curl_surface.get_or_insert_with(|| {
                let (positions, normals, triangles) = curl(recording.looks.ribbon_width);
                b.surface(&positions, &normals, &triangles)
            });
            let mesh = match curls.iter().find(|(c, _)| *c == look.rgb) {
                Some(&(_, mesh)) => mesh,
                None => {
                    let mesh = b.mesh(format!("ribbon-curl-{hex}"), surface, strip_material, &[]);
                    curls.push((look.rgb, mesh));
                    mesh
                }
            };
            let node = b.root.push(Node {
                name: Some(format!("ribbon-{id}-curl")),
                mesh: Some(mesh),
                ..Default::default()
            });
            let end = &mut b.root.nodes[joints[n - 1].value()];
            end.children.get_or_insert_with(Vec::new).push(node);
        }
        let parent = b.root.push(Node {
            name: Some(format!("ribbon-{id}")),
            children: Some(joints.clone()),
            ..Default::default()
        });
        roots.push(parent);
        roots.push(add_strip(
            b,
            look,
            bind,
            &joints,
            parent,
            strip_material,
            recording.looks.ribbon_width,
        ));
    }
    roots
}

/// The material of colour `rgb` in `made`, made by `make` the first time.
fn material_for(
    made: &mut Vec<([f32; 3], Index<Material>)>,
    rgb: [f32; 3],
    make: impl FnOnce() -> Index<Material>,
) -> Index<Material> {
    if let Some(&(_, m)) = made.iter().find(|(c, _)| *c == rgb) {
        return m;
    }
    let m = make();
    made.push((rgb, m));
    m
}

/// The weight: a ball under the free end's joint, which carries it.
fn add_weight(b: &mut Builder, end: Index<Node>, id: u32, material: Index<Material>) {
    let (positions, normals, triangles) = sphere(WEIGHT_RADIUS);
    let surface = b.surface(&positions, &normals, &triangles);
    let mesh = b.mesh(format!("weight-{id}"), surface, material, &[]);
    let weight = b.root.push(Node {
        name: Some(format!("weight-{id}")),
        mesh: Some(mesh),
        ..Default::default()
    });
    let joint = &mut b.root.nodes[end.value()];
    joint.children.get_or_insert_with(Vec::new).push(weight);
}

/// The strip bound to the joints: a node at the scene's root with no
/// transform of its own (its vertices follow the joints alone).
fn add_strip(
    b: &mut Builder,
    look: &RibbonLook,
    bind: &[Vec3],
    joints: &[Index<Node>],
    skeleton: Index<Node>,
    material: Index<Material>,
    width: f32,
) -> Index<Node> {
    let id = look.balloon;
    let strip = ribbon_strip(bind, width);
    let surface = b.surface(&strip.vertices, &strip.normals, &strip.triangles);
    // Two vertices a point, both on that point's joint.
    let joint_of: Vec<u16> = (0..strip.vertices.len())
        .flat_map(|v| [(v / 2) as u16, 0, 0, 0])
        .collect();
    let weights: Vec<f32> = (0..strip.vertices.len())
        .flat_map(|_| [1.0, 0.0, 0.0, 0.0])
        .collect();
    let joint_accessor = b.bin.accessor(
        &mut b.root,
        Elements::U16(&joint_of),
        Type::Vec4,
        Some(json::buffer::Target::ArrayBuffer),
        false,
    );
    let weight_accessor = b.vertices(&weights, Type::Vec4, false);
    // Each joint's inverse bind matrix undoes its point at the first frame
    // (column-major: the translation is the last column).
    let inverse_binds: Vec<f32> = bind
        .iter()
        .flat_map(|p| {
            let mut m = glam::Mat4::from_translation(-*p).to_cols_array();
            m[15] = 1.0;
            m
        })
        .collect();
    let ibm = b.bin.accessor(
        &mut b.root,
        Elements::F32(&inverse_binds),
        Type::Mat4,
        None,
        false,
    );
    let skin = b.root.push(Skin {
        extensions: None,
        extras: Default::default(),
        inverse_bind_matrices: Some(ibm),
        joints: joints.to_vec(),
        name: Some(format!("ribbon-{id}")),
        skeleton: Some(skeleton),
    });
    let mesh = b.mesh(
        format!("ribbon-{id}"),
        surface,
        material,
        &[
            (Semantic::Joints(0), joint_accessor),
            (Semantic::Weights(0), weight_accessor),
        ],
    );
    b.root.push(Node {
        name: Some(format!("ribbon-{id}-strip")),
        mesh: Some(mesh),
        skin: Some(skin),
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_curl_hangs_from_the_free_end_as_long_and_wide_as_the_page_draws_it() {
        let (positions, normals, triangles) = curl(0.005);
        let top = (positions[0] + positions[1]) * 0.5;
        assert!(top.length() < 1e-6, "starts at the free end: {top}");
        let last = positions.len() - 1;
        let bottom = (positions[last] + positions[last - 1]) * 0.5;
        assert!((bottom.y + CURL_LENGTH).abs() < 1e-6);
        assert!((positions[1].y - positions[0].y - 0.005).abs() < 1e-6);
        assert!(normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
        assert_eq!(triangles.len(), 2 * CURL_SAMPLES as usize);
    }

    #[test]
    fn the_weight_ball_is_closed_and_round() {
        let (positions, normals, triangles) = sphere(0.025);
        for (p, n) in positions.iter().zip(&normals) {
            assert!((p.length() - 0.025).abs() < 1e-6);
            assert!((n.length() - 1.0).abs() < 1e-5);
        }
        // Every triangle faces out (wound counter-clockwise seen from outside).
        for t in &triangles {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            let normal = (b - a).cross(c - a);
            assert!(normal.dot(a + b + c) > 0.0, "{t:?}");
        }
    }
}
