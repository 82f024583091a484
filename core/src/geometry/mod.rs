//! Layer 3, geometry: rays, triangles, the primitives and their intersections,
//! bounding volume hierarchies, the camera and texture lookup.

pub mod bvh;
pub mod bvh_build;
pub mod camera;
pub mod primitive;
pub mod ray;
pub mod texture;
pub mod triangle;
