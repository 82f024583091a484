//! Light tracing against the gather, random photons against Sobol ones,
//! per built-in scene on the CPU: the caustic's relRMSE (the RMSE over the
//! pixels whose reference is above 5 % of its maximum, over the
//! reference's mean there) after 2, 8, 32 and 128 passes, and the time to
//! get there, with `light_tracing` off (every diffuse hit gathers) and on,
//! each with `photon_sequence` random and sobol. The reference is a long light-traced
//! render of other passes (REFERENCE passes, 256 unless given): light
//! tracing converges to the pixel's box-filtered image, the gather at the
//! pixel centres to the point-sampled one, so an error that stops falling
//! against it is that difference, not noise.
//!
//! `cargo run --release -p prismatic-benches --example light_tracing -- [SCENE] [SIZE] [REFERENCE]`

use prismatic_conformance::compare::{caustic_of, caustic_rel_rmse};
use prismatic_core::model::scene::PhotonSequence;
use prismatic_core::{Backend, NoProgress, PreparedScene, Render};
use prismatic_cpu::CpuBackend;
use std::time::Instant;

/// The caustic alone of a render's image.
fn caustic(render: &mut dyn Render) -> Vec<f64> {
    caustic_of(&render.image().expect("image"), &render.base().expect("base"))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map_or("caustic", String::as_str);
    let size: u32 = args.get(1).map_or(200, |s| s.parse().expect("SIZE: pixels a side"));
    let long: u32 = args.get(2).map_or(256, |s| s.parse().expect("REFERENCE: passes"));
    let scene = |light_tracing: bool, sequence: PhotonSequence| -> PreparedScene {
        let mut doc = prismatic_cli::load_scene(name).expect("a built-in scene");
        let r = &mut doc.scene.render;
        (r.width, r.height, r.light_tracing, r.photon_sequence) = (size, size, light_tracing, sequence);
        PreparedScene::new(doc.scene).expect("valid")
    };
    let t = Instant::now();
    let mut reference = CpuBackend::new().prepare(&scene(true, PhotonSequence::Sobol)).expect("prepare");
    for k in 10_000..10_000 + long {
        reference.run_pass(k, &mut NoProgress).expect("pass");
    }
    let reference = caustic(reference.as_mut());
    println!("{name}, {size}×{size}: reference of {long} light-traced passes in {:.1} s", t.elapsed().as_secs_f64());
    println!("| light tracing | photons | passes | relRMSE | time |\n|---|---|---:|---:|---:|");
    let configs =
        [false, true].into_iter().flat_map(|l| [PhotonSequence::Random, PhotonSequence::Sobol].map(|s| (l, s)));
    for (light_tracing, sequence) in configs {
        let t = Instant::now();
        let mut render = CpuBackend::new().prepare(&scene(light_tracing, sequence)).expect("prepare");
        let mut done = 0;
        for n in [2u32, 8, 32, 128].into_iter().filter(|&n| n <= long / 2) {
            for k in done..n {
                render.run_pass(k, &mut NoProgress).expect("pass");
            }
            done = n;
            let error = caustic_rel_rmse(&caustic(render.as_mut()), &reference);
            let time = t.elapsed().as_secs_f64();
            println!("| {light_tracing} | {} | {n} | {error:.4} | {time:.2} s |", sequence.name());
        }
    }
}
