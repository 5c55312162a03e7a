//! Pure geometry for UP: shapes and queries on them, with no world and no state.
//!
//! Conventions, stated once: SI units (metres), right-handed, Y up. A query
//! takes shapes and poses and returns a value; nothing here allocates except
//! where a caller-owned `Vec` is passed in to be appended to.

pub mod contact;
pub mod fit;
pub mod norm;
pub mod pose;
pub mod query;
pub mod shape;
pub mod split_mix;
#[cfg(test)]
mod test_meshes;

pub use contact::Contact;
pub use glam::{Mat3, Quat, Vec3};
pub use pose::Pose;
pub use query::closest_point_triangle::{
    closest_point_segment, closest_point_triangle, TriangleRegion,
};
pub use query::contact_sphere_sphere::contact_sphere_sphere;
pub use query::contact_sphere_triangle::contact_sphere_triangle;
pub use query::contact_sphere_trimesh::contact_sphere_trimesh;
pub use query::contact_tree_tree::contact_tree_tree;
pub use query::contact_tree_trimesh::contact_tree_trimesh;
pub use query::prune_shadowed::{prune_shadowed, RelativeMotion};
pub use query::toi_bisect::{
    toi_bisect, toi_bisect_conservative, toi_sphere_sphere_bisect, toi_sphere_triangle_bisect,
};
pub use query::toi_sphere_sphere::toi_sphere_sphere;
pub use query::toi_sphere_triangle::toi_sphere_triangle;
pub use query::toi_sphere_trimesh::{toi_sphere_trimesh, toi_sphere_trimesh_new_contact};
pub use query::triangle_reach::TriangleReach;
pub use shape::aabb::Aabb;
pub use shape::bvh::{Bvh, BvhNode};
pub use shape::sphere::Sphere;
pub use shape::sphere_tree::{PlacedTree, SphereNode, SphereTree, SphereTreeError};
pub use shape::trimesh::{EdgeAdjacency, EdgeKind, TriMesh, TriMeshData, TriMeshError};
pub use split_mix::SplitMix64;
