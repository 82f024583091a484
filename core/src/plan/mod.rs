//! Layer 5, plan: what a render of this scene will do. Which lights (emissive
//! meshes' triangles among them) reach which
//! objects, where photons are aimed, which effects the scene calls for, the
//! prepared scene, and the pass schedule.

pub mod area;
pub mod area_aims;
pub mod drawn_suns;
pub mod drawn_triangles;
pub mod effects;
pub mod prepared;
pub mod projection;
pub mod reach;
pub mod schedule;
