//! Cross-crate tests of prismatic, one binary: physics, determinism, parity, scene files.

mod builtin_scenes;
mod caustic_layer;
mod coloured_glass;
mod docs_links;
mod effects;
mod fuzz_scene_file;
mod gather;
mod gpu_session;
mod hard_cases;
mod light_spectra;
mod light_tracing;
mod meshes;
mod optics;
mod parity_cpu;
mod parity_gpu;
mod photon_map;
mod physics;
mod progressive;
mod scene_files;
mod spectral_truth;
mod spectrum;
mod sun;
mod textures;
mod thin_glass;
mod view_paths;
mod wavelengths;
