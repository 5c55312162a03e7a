//! Shapes: spheres, sphere trees (moving bodies) and triangle meshes (static geometry).

pub mod aabb;
pub mod bvh;
pub mod sphere;
pub mod sphere_tree;
pub mod trimesh;
