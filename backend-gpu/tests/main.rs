//! The GPU backend's tests, one binary: the conformance suite, the shaders' validation and the WGSL twins.

mod conformance;
mod shaders;
mod twins;
