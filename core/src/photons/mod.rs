//! Layer 6, photons: the light's side. Emission, the photon trace (caustic and indirect), the spatial
//! hash grid, the gather estimators, and light tracing to the camera.

pub mod emit;
pub mod gather;
pub mod grid;
pub mod indirect;
pub mod light_tracing;
pub mod path;
pub mod reflects;
pub mod trace;
pub mod wavelengths;
