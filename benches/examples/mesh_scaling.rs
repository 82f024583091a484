//! Render time against triangle count: the built-in `sphere` scene with its
//! sphere as a closed glass mesh of about 1k, 10k, 100k and 1M triangles,
//! beside the analytic sphere, on the cpu and gpu backends. Per row: the
//! hierarchy's build time and memory per triangle, a render's time at the
//! scene's own settings (prepared, then PASSES passes, 16 unless given, at
//! 400×400; the CPU's best of three runs, lavapipe's one), photon paths per
//! second (one pass's photon map) and the image's correlation with the
//! analytic sphere's. Each mesh is rendered flat and smooth (with the
//! sphere's normals at its vertices).
//!
//! `cargo run --release -p prismatic-benches --example mesh_scaling -- [PASSES] [--cpu-only]`

use prismatic_conformance::compare::image_correlation;
use prismatic_conformance::scenes::{smooth_sphere_mesh, sphere_mesh};
use prismatic_core::geometry::primitive::Primitive;
use prismatic_core::model::scene::Shape;
use prismatic_core::{Backend, Image, NoProgress, PreparedScene};
use prismatic_cpu::CpuBackend;
use prismatic_gpu::{AdapterChoice, GpuBackend};
use std::time::Instant;

/// Rings of the sphere meshes: 4 · rings² triangles (less the poles').
const RINGS: [u32; 4] = [16, 50, 158, 500];

/// The built-in sphere, or with its sphere a mesh of `rings` rings (smooth or flat).
fn scene(mesh: Option<(u32, bool)>) -> PreparedScene {
    let mut doc = prismatic_cli::load_scene("sphere").expect("built-in sphere");
    if let Some((rings, smooth)) = mesh {
        let Shape::Sphere { center, radius } = doc.scene.objects[1].shape else { panic!("object 1 is the sphere") };
        let shape = if smooth { smooth_sphere_mesh } else { sphere_mesh };
        doc.scene.objects[1].shape = shape(center, radius, rings);
    }
    PreparedScene::new(doc.scene).expect("valid")
}

/// (render seconds, photon paths per second, image): the best of `runs`
/// renders, so that a moment's load on the machine does not make a ratio.
fn render(backend: &mut dyn Backend, scene: &PreparedScene, passes: u32, runs: usize) -> (f64, f64, Image) {
    let mut best: Option<(f64, f64, Image)> = None;
    for _ in 0..runs {
        let start = Instant::now();
        let mut render = backend.prepare(scene).expect("prepare");
        for pass in 0..passes {
            render.run_pass(pass, &mut NoProgress).expect("pass");
        }
        let image = render.image().expect("image");
        let seconds = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let map = render.photon_map(passes, &mut NoProgress).expect("photon map");
        let rate = map.stats.emitted as f64 / start.elapsed().as_secs_f64();
        best = Some(match best {
            Some((s, r, i)) => (s.min(seconds), r.max(rate), i),
            None => (seconds, rate, image),
        });
    }
    best.expect("at least one run")
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let passes = args.iter().find_map(|a| a.parse().ok()).unwrap_or(16);
    let mut backends: Vec<Box<dyn Backend>> = vec![Box::new(CpuBackend::new())];
    if !args.iter().any(|a| a == "--cpu-only") {
        backends.push(Box::new(GpuBackend::new(AdapterChoice::Any).expect("a GPU adapter (lavapipe will do)")));
    }
    println!(
        "| backend | sphere | triangles | build ms | bytes/triangle | render s ({passes} passes) | × analytic | photon paths/s | correlation |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for backend in &mut backends {
        let runs = if backend.name() == "cpu" { 3 } else { 1 };
        let analytic = scene(None);
        let (base_s, base_rate, base_image) = render(backend.as_mut(), &analytic, passes, runs);
        let name = backend.name();
        println!("| {name} | analytic | – | – | – | {base_s:.2} | 1.0 | {base_rate:.3e} | 1 |");
        for (rings, smooth) in RINGS.into_iter().flat_map(|r| [(r, false), (r, true)]) {
            let start = Instant::now();
            let mesh = scene(Some((rings, smooth)));
            let kind = if smooth { "smooth mesh" } else { "flat mesh" };
            let build_ms = start.elapsed().as_secs_f64() * 1e3;
            let Primitive::Mesh(bvh) = &mesh.primitives[1] else { unreachable!() };
            let triangles = bvh.triangles.len();
            let per_triangle = bvh.bytes() as f64 / triangles as f64;
            let (s, rate, image) = render(backend.as_mut(), &mesh, passes, runs);
            let r = image_correlation(&base_image, &image);
            println!(
                "| {name} | {kind} | {triangles} | {build_ms:.0} | {per_triangle:.0} | {s:.2} | {:.2} | {rate:.3e} | {r:.4} |",
                s / base_s
            );
        }
    }
}
