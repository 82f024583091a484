//! Layer 5, plan: what a render of this scene will do. Which lights reach which
//! objects, where photons are aimed, which effects the scene calls for, the
//! prepared scene, and the pass schedule.

pub mod effects;
pub mod prepared;
pub mod projection;
pub mod reach;
pub mod schedule;
