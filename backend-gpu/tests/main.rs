//! The GPU backend's tests, one binary: the conformance suite, the caustic layer from an engine's textures, the shaders' validation and the WGSL twins.

mod conformance;
mod layer;
mod shaders;
mod twins;
