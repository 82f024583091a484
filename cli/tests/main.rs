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

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `prismatic render SCENE --backend cpu -o DIR/out.exr EXTRA…` (an
/// earlier `out.exr` removed first): the run, and where its image goes.
fn render_to_exr(scene: &Path, dir: &Path, extra: &[&str]) -> (Output, PathBuf) {
    let out = dir.join("out.exr");
    let _ = std::fs::remove_file(&out);
    let run = Command::new(env!("CARGO_BIN_EXE_prismatic"))
        .args(["render", scene.to_str().unwrap(), "--backend", "cpu", "-o", out.to_str().unwrap()])
        .args(extra)
        .output()
        .unwrap();
    (run, out)
}
