//! Queries: `<op>_<shape1>_<shape2>`. Each takes shapes and poses and returns a value.

pub mod closest_point_triangle;
pub mod contact_sphere_sphere;
pub mod contact_sphere_triangle;
pub mod contact_sphere_trimesh;
pub mod contact_tree_tree;
pub mod contact_tree_trimesh;
pub mod mesh_feature;
pub mod prune_shadowed;
pub mod toi_bisect;
pub mod toi_sphere_sphere;
pub mod toi_sphere_triangle;
pub mod toi_sphere_trimesh;
pub mod triangle_reach;
