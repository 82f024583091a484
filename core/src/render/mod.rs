//! Layer 7, render: the camera's side and the protocol. View rays and their
//! visible points, the exact sums, the auxiliary images (features), the render protocol, its host driver and the
//! scalar reference backend.

pub mod accumulation;
pub mod aov;
pub mod host;
pub mod layer;
pub mod protocol;
pub mod reference;
pub mod view;
pub mod visible;
