//! Layer 3, geometry: rays, triangles, the primitives and their intersections,
//! bounding volume hierarchies, the camera, texture lookup, smooth shading normals and what a point
//! sees of a triangle (form factors).

pub mod bvh;
pub mod bvh_build;
pub mod camera;
pub mod form_factor;
pub mod normal_map;
pub mod primitive;
pub mod ray;
pub mod shading;
pub mod texture;
pub mod triangle;
