//! The command line's tests, one binary: the `prismatic` binary run as a user runs it.

mod area_lights;
mod bad_scenes;
mod cli;
mod environment;
mod exr_layers;
mod gltf;
mod indirect_light;
mod slurm;
mod study;
