//! prismatic-gpu: the wgpu compute backend (WGSL ports of the core's tracer,
//! grid build and gather, buffers resident on the device).
//!
//! Not built yet: `prismatic --backend gpu` says so and points to
//! `--backend reference`.
