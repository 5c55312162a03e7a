//! A recording as one glTF 2.0 document and its `.glb`: the balloons
//! (nodes `balloon-<id>`, their model's mesh in a material of their finish
//! and colour, translation and rotation channels, and a scale channel where
//! the gas shrinks them), the ribbons (`ribbons.rs`), the room (floor, walls
//! and ceiling as the page tells them apart, static), one camera and the
//! page's key and fill lights (`KHR_lights_punctual`). One animation,
//! `run`, whose keys are the recorded frames; the scene's `extras.up` says
//! where in the run it starts and how fast it plays.

use glam::{Quat, Vec3};
use gltf_json as json;
use json::animation::Property;
use json::extensions::scene::khr_lights_punctual as lights;
use json::validation::Checked;
use json::{Animation, Camera, Index, Mesh, Node, Root};
use serde_json::value::RawValue;
use up_scene::scene::Finish;

use crate::builder::{rotation_keys, Builder};
use crate::glb::{glb_bytes, Elements};
use crate::looks::{camera_pose, linear_from_hex, linear_from_srgb, page_lights};
use crate::materials::{balloon, extensions_of, plain};
use crate::recording::Recording;
use crate::ribbons::add_ribbons;
use crate::ExportError;

/// Share of a latex balloon's volume lost when it has come down: full age
/// (web/src/render/balloons.ts).
const VOLUME_LOST_WHEN_LANDED: f32 = 0.55;
/// Scales closer than this to each other are one size (no scale channel).
const SCALE_STILL: f32 = 1e-6;

/// `#rrggbb` of an sRGB colour, without the `#`: a name part.
pub fn hex_name(rgb: [f32; 3]) -> String {
    rgb.iter()
        .map(|c| format!("{:02x}", (c.clamp(0.0, 1.0) * 255.0).round() as u8))
        .collect()
}

/// How aged the latex looks at the last frame, 0–1, as the page reckons it.
fn latex_age(recording: &Recording) -> f32 {
    let Some(last) = recording.frames().last() else {
        return 0.0;
    };
    let looks = &recording.looks;
    let (mut lost, mut latex) = (0.0, 0);
    for (b, &s) in looks.balloons.iter().zip(&last.scales) {
        if looks
            .models
            .get(b.model)
            .is_some_and(|m| m.finish != Finish::Foil)
        {
            lost += 1.0 - s * s * s;
            latex += 1;
        }
    }
    if latex == 0 {
        0.0
    } else {
        (lost / latex as f32 / VOLUME_LOST_WHEN_LANDED).clamp(0.0, 1.0)
    }
}

/// The balloons' nodes and their channels.
fn add_balloons(b: &mut Builder, recording: &Recording) -> Vec<Index<Node>> {
    let looks = &recording.looks;
    let frames: Vec<_> = recording.frames().collect();
    let age = latex_age(recording);
    let surfaces: Vec<_> = looks
        .models
        .iter()
        .map(|m| b.surface(&m.positions, &m.normals, &m.triangles))
        .collect();
    // One mesh per model and colour, sharing the model's accessors.
    let mut meshes: Vec<((usize, String), Index<Mesh>)> = Vec::new();
    let mut nodes = Vec::new();
    for (i, look) in looks.balloons.iter().enumerate() {
        let Some(model) = looks.models.get(look.model) else {
            continue;
        };
        let key = (look.model, hex_name(look.rgb));
        let mesh = match meshes.iter().find(|(k, _)| *k == key) {
            Some(&(_, mesh)) => mesh,
            None => {
                let name = format!("balloon-{}-{}", model.finish.name(), key.1);
                let material = b.root.push(balloon(
                    name.clone(),
                    model.finish,
                    linear_from_srgb(look.rgb),
                    age,
                ));
                let mesh = b.mesh(name, surfaces[look.model], material, &[]);
                meshes.push((key, mesh));
                mesh
            }
        };
        let first = frames[0];
        let node = b.node(
            format!("balloon-{}", look.id),
            first.positions[i],
            first.rotations[i],
        );
        b.root.nodes[node.value()].mesh = Some(mesh);
        let path: Vec<f32> = frames
            .iter()
            .flat_map(|f| f.positions[i].to_array())
            .collect();
        b.channel(node, Property::Translation, &path);
        let turns = rotation_keys(frames.iter().map(|f| f.rotations[i]));
        b.channel(node, Property::Rotation, &turns);
        let scales: Vec<f32> = frames.iter().map(|f| f.scales[i]).collect();
        let (lo, hi) = scales
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &s| {
                (lo.min(s), hi.max(s))
            });
        if hi - lo > SCALE_STILL {
            let keys: Vec<f32> = scales.iter().flat_map(|&s| [s, s, s]).collect();
            b.channel(node, Property::Scale, &keys);
        } else if (first.scales[i] - 1.0).abs() > SCALE_STILL {
            b.root.nodes[node.value()].scale = Some([first.scales[i]; 3]);
        }
        nodes.push(node);
    }
    nodes
}

/// The room: floor, walls and ceiling (faces told apart by their inward
/// normals, as the page does), and the furniture standing in it, in oak
/// (render/furniture.ts), flat-shaded, under one node `room`.
fn add_room(b: &mut Builder, recording: &Recording) -> Index<Node> {
    let looks = &recording.looks;
    // sRGB: the floor's oak planks on average, the walls', the ceiling's (room.ts).
    let parts: [(&str, u32, f32); 3] = [
        ("floor", 0xd2b282, 0.55),
        ("walls", 0xe9e2d6, 0.9),
        ("ceiling", 0xf4efe6, 0.85),
    ];
    let mut children = Vec::new();
    for (part, (name, hex, roughness)) in parts.into_iter().enumerate() {
        let (mut positions, mut normals, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
        for t in &looks.room_triangles {
            let [a, c, d] = t.map(|i| looks.room_vertices[i as usize]);
            let normal = (c - a).cross(d - a).normalize_or_zero();
            let kind = if normal.y > 0.7 {
                0
            } else if normal.y < -0.2 {
                2
            } else {
                1
            };
            if kind != part {
                continue;
            }
            let base = positions.len() as u32;
            positions.extend([a, c, d]);
            normals.extend([normal; 3]);
            triangles.push([base, base + 1, base + 2]);
        }
        if triangles.is_empty() {
            continue;
        }
        let material = b.root.push(plain(
            format!("room-{name}"),
            linear_from_hex(hex),
            roughness,
            0.0,
        ));
        let surface = b.surface(&positions, &normals, &triangles);
        let mesh = b.mesh(format!("room-{name}"), surface, material, &[]);
        let node = b.node(format!("room-{name}"), Vec3::ZERO, Quat::IDENTITY);
        b.root.nodes[node.value()].mesh = Some(mesh);
        children.push(node);
    }
    if !looks.furniture_triangles.is_empty() {
        let (mut positions, mut normals, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
        for t in &looks.furniture_triangles {
            let [a, c, d] = t.map(|i| looks.furniture_vertices[i as usize]);
            let base = positions.len() as u32;
            positions.extend([a, c, d]);
            normals.extend([(c - a).cross(d - a).normalize_or_zero(); 3]);
            triangles.push([base, base + 1, base + 2]);
        }
        let material = b.root.push(plain(
            "furniture".into(),
            linear_from_hex(0x96623a),
            0.5,
            0.0,
        ));
        let surface = b.surface(&positions, &normals, &triangles);
        let mesh = b.mesh("furniture".into(), surface, material, &[]);
        let node = b.node("furniture".into(), Vec3::ZERO, Quat::IDENTITY);
        b.root.nodes[node.value()].mesh = Some(mesh);
        children.push(node);
    }
    b.root.push(Node {
        name: Some("room".into()),
        children: Some(children),
        ..Default::default()
    })
}

/// The camera and the page's lights.
fn add_camera_and_lights(b: &mut Builder, recording: &Recording) -> Vec<Index<Node>> {
    let (half_width, half_depth, top) = recording.looks.room_box();
    let camera = b.root.push(Camera {
        name: Some("camera".into()),
        orthographic: None,
        perspective: Some(json::camera::Perspective {
            aspect_ratio: None,
            yfov: 60f32.to_radians(),
            zfar: Some(500.0),
            znear: 0.05,
            extensions: None,
            extras: Default::default(),
        }),
        type_: Checked::Valid(json::camera::Type::Perspective),
        extensions: None,
        extras: Default::default(),
    });
    let (eye, rotation) = camera_pose(half_width, half_depth, top);
    let camera_node = b.node("camera".into(), eye, rotation);
    b.root.nodes[camera_node.value()].camera = Some(camera);
    let mut nodes = vec![camera_node];
    let mut defined = Vec::new();
    for light in page_lights(half_width, half_depth, top) {
        let index = Index::new(defined.len() as u32);
        defined.push(lights::Light {
            color: light.color,
            extensions: None,
            extras: Default::default(),
            intensity: light.intensity,
            name: Some(light.name.into()),
            range: None,
            spot: None,
            type_: Checked::Valid(if light.directional {
                lights::Type::Directional
            } else {
                lights::Type::Point
            }),
        });
        let node = b.node(light.name.into(), light.position, light.rotation);
        b.root.nodes[node.value()].extensions = Some(json::extensions::scene::Node {
            khr_lights_punctual: Some(lights::KhrLightsPunctual { light: index }),
            ..Default::default()
        });
        nodes.push(node);
    }
    b.root.extensions = Some(json::extensions::root::Root {
        khr_lights_punctual: Some(json::extensions::root::KhrLightsPunctual { lights: defined }),
        ..Default::default()
    });
    nodes
}

/// The recording as a glTF document and its binary buffer.
pub fn document(recording: &Recording) -> Result<(Root, Vec<u8>), ExportError> {
    let frames: Vec<_> = recording.frames().collect();
    let (Some(first), Some(last)) = (frames.first(), frames.last()) else {
        return Err(ExportError::NoFrames);
    };
    let mut b = Builder::default();
    b.root.asset = json::Asset {
        generator: Some(format!("UP {} (up-export)", env!("CARGO_PKG_VERSION"))),
        version: "2.0".into(),
        copyright: None,
        extensions: None,
        extras: Default::default(),
        min_version: None,
    };
    let times: Vec<f32> = frames.iter().map(|f| recording.animation_time(f)).collect();
    b.times = Some(b.bin.accessor(
        &mut b.root,
        Elements::F32(&times),
        json::accessor::Type::Scalar,
        None,
        true,
    ));
    let mut roots = add_balloons(&mut b, recording);
    roots.extend(add_ribbons(&mut b, recording));
    roots.push(add_room(&mut b, recording));
    roots.extend(add_camera_and_lights(&mut b, recording));

    let Builder {
        mut root,
        bin,
        channels,
        samplers,
        ..
    } = b;
    root.push(Animation {
        extensions: None,
        extras: Default::default(),
        channels,
        name: Some("run".into()),
        samplers,
    });
    let extras = serde_json::json!({ "up": {
        "start_s": first.time,
        "end_s": last.time,
        "frames": frames.len(),
        "sim_seconds_per_second": recording.time_scale,
    }});
    let scene = root.push(json::Scene {
        extensions: None,
        extras: RawValue::from_string(extras.to_string()).ok(),
        name: Some("up".into()),
        nodes: roots,
    });
    root.scene = Some(scene);
    let mut used = vec!["KHR_lights_punctual".to_string()];
    for m in &root.materials {
        for name in extensions_of(m) {
            if !used.contains(&name) {
                used.push(name);
            }
        }
    }
    root.extensions_used = used;
    bin.declare(&mut root);
    Ok((root, bin.bytes))
}

/// The recording as a `.glb`, whole, in memory.
pub fn glb(recording: &Recording) -> Result<Vec<u8>, ExportError> {
    let (root, bin) = document(recording)?;
    let text = root
        .to_vec()
        .map_err(|e| ExportError::Json(e.to_string()))?;
    Ok(glb_bytes(&text, &bin))
}
