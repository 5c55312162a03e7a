//! The parts every section of the document is made of: the document and
//! its binary buffer together, meshes, nodes and animation channels.

use glam::{Quat, Vec3};
use gltf_json as json;
use json::accessor::Type;
use json::animation::{Channel, Interpolation, Property, Sampler, Target as AnimTarget};
use json::buffer::Target;
use json::mesh::{Mode, Primitive, Semantic};
use json::scene::UnitQuaternion;
use json::validation::Checked;
use json::{Accessor, Index, Material, Mesh, Node, Root};

use crate::glb::{BinBuffer, Elements};

/// A document being written, its buffer, and its one animation's parts.
#[derive(Default)]
pub struct Builder {
    pub root: Root,
    pub bin: BinBuffer,
    pub channels: Vec<Channel>,
    pub samplers: Vec<Sampler>,
    /// The keyframe times every sampler shares.
    pub times: Option<Index<Accessor>>,
}

/// Unit normals: a zero or non-finite one (a degenerate face) points up.
pub fn unit_normals(normals: &[Vec3]) -> Vec<f32> {
    normals
        .iter()
        .flat_map(|n| n.try_normalize().unwrap_or(Vec3::Y).to_array())
        .collect()
}

/// The floats of `vectors`, xyz after xyz.
pub fn flat(vectors: &[Vec3]) -> Vec<f32> {
    vectors.iter().flat_map(|v| v.to_array()).collect()
}

impl Builder {
    /// An accessor over vertex data (or, with `bounds`, positions).
    pub fn vertices(&mut self, data: &[f32], type_: Type, bounds: bool) -> Index<Accessor> {
        self.bin.accessor(
            &mut self.root,
            Elements::F32(data),
            type_,
            Some(Target::ArrayBuffer),
            bounds,
        )
    }

    /// An accessor over triangle indices.
    pub fn indices(&mut self, triangles: &[[u32; 3]]) -> Index<Accessor> {
        let flat: Vec<u32> = triangles.iter().flatten().copied().collect();
        self.bin.accessor(
            &mut self.root,
            Elements::U32(&flat),
            Type::Scalar,
            Some(Target::ElementArrayBuffer),
            false,
        )
    }

    /// The accessors of a surface: positions, unit normals, triangles.
    pub fn surface(
        &mut self,
        positions: &[Vec3],
        normals: &[Vec3],
        triangles: &[[u32; 3]],
    ) -> [Index<Accessor>; 3] {
        [
            self.vertices(&flat(positions), Type::Vec3, true),
            self.vertices(&unit_normals(normals), Type::Vec3, false),
            self.indices(triangles),
        ]
    }

    /// A mesh of one triangle list over `surface` drawn with `material`,
    /// plus the extra vertex `attributes` (a skin's joints and weights).
    pub fn mesh(
        &mut self,
        name: String,
        surface: [Index<Accessor>; 3],
        material: Index<Material>,
        attributes: &[(Semantic, Index<Accessor>)],
    ) -> Index<Mesh> {
        let [positions, normals, indices] = surface;
        let mut map = std::collections::BTreeMap::new();
        map.insert(Checked::Valid(Semantic::Positions), positions);
        map.insert(Checked::Valid(Semantic::Normals), normals);
        for (semantic, accessor) in attributes {
            map.insert(Checked::Valid(semantic.clone()), *accessor);
        }
        self.root.push(Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name),
            primitives: vec![Primitive {
                attributes: map,
                extensions: None,
                extras: Default::default(),
                indices: Some(indices),
                material: Some(material),
                mode: Checked::Valid(Mode::Triangles),
                targets: None,
            }],
            weights: None,
        })
    }

    /// A node named `name` at `translation`, turned by `rotation`.
    pub fn node(&mut self, name: String, translation: Vec3, rotation: Quat) -> Index<Node> {
        let q = rotation.normalize();
        self.root.push(Node {
            name: Some(name),
            translation: (translation != Vec3::ZERO).then(|| translation.to_array()),
            rotation: (q != Quat::IDENTITY).then(|| UnitQuaternion(q.to_array())),
            ..Default::default()
        })
    }

    /// Animates `node`'s `property` through `values` (3 or 4 floats a key,
    /// one key per shared time), linearly.
    pub fn channel(&mut self, node: Index<Node>, property: Property, values: &[f32]) {
        let Some(times) = self.times else {
            return;
        };
        let type_ = if property == Property::Rotation {
            Type::Vec4
        } else {
            Type::Vec3
        };
        let output = self
            .bin
            .accessor(&mut self.root, Elements::F32(values), type_, None, false);
        let sampler = Index::new(self.samplers.len() as u32);
        self.samplers.push(Sampler {
            extensions: None,
            extras: Default::default(),
            input: times,
            interpolation: Checked::Valid(Interpolation::Linear),
            output,
        });
        self.channels.push(Channel {
            sampler,
            target: AnimTarget {
                extensions: None,
                extras: Default::default(),
                node,
                path: Checked::Valid(property),
            },
            extensions: None,
            extras: Default::default(),
        });
    }
}

/// Rotations as keys for linear interpolation: unit, each on the same side
/// of the sphere as the one before (q and −q are one rotation; a sign flip
/// between keys would spin the long way round in tools that interpolate
/// the components).
pub fn rotation_keys(rotations: impl Iterator<Item = Quat>) -> Vec<f32> {
    let mut out = Vec::new();
    let mut last = Quat::IDENTITY;
    for (k, q) in rotations.enumerate() {
        let mut q = q.normalize();
        if k > 0 && q.dot(last) < 0.0 {
            q = -q;
        }
        last = q;
        out.extend(q.to_array());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_keys_stay_on_one_side() {
        let a = Quat::from_rotation_y(0.1);
        let keys = rotation_keys([a, -a, Quat::from_rotation_y(0.2)].into_iter());
        assert_eq!(keys.len(), 12);
        assert!(keys[4..8]
            .iter()
            .zip(&keys[0..4])
            .all(|(x, y)| (x - y).abs() < 1e-6));
        assert!(keys[11] > 0.0);
    }

    #[test]
    fn degenerate_normals_point_up() {
        let n = unit_normals(&[Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0)]);
        assert_eq!(n, [0.0, 1.0, 0.0, 0.0, 0.0, 1.0]);
    }
}
