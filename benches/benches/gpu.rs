//! Criterion benches of the GPU backend through the render protocol:
//! `trace/gpu` (a pass's photon map traced and read back), `frame/gpu` (the
//! paper's frame: a render prepared, its view rays, one fixed-radius pass,
//! the image read out), `frame/gpu-session` (one pass of a live render of
//! the paper's configuration with progressive radii, the engine-facing
//! path: photons, grid levels, gather at resident visible points, sums;
//! also `frame/gpu-session-caustic`, a dense caustic filling the view,
//! where the finer grid levels carry most points), `lights/{spot,environment}`
//! (a pass's photons under the `sphere`'s spot and under the studio
//! environment, and each one's view pass), `indirect/{indirect,caustic}/gpu`
//! (a pass of 100,000 indirect photons in the `sphere`, beside its spot's
//! caustic pass of as many, as the CPU's `indirect` group),
//! `metals/{rough,mapped,coloured,filmed,polished,mirrors}` and `rough_glass/{frosted,polished}`
//! (the CPU's groups of the same names at 1,000,000 photons: a pass's
//! photons, and a whole pass of a live render, photons to sums, at the
//! scene's size). Every measurement ends with a device sync. On lavapipe they only show that the stages run;
//! real figures need a GPU.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use prismatic_benches::{frame, lit_by_each_light, paper_config};
use prismatic_core::model::scene::RadiusMode;
use prismatic_core::{Backend, NoProgress, PreparedScene, Render};
use prismatic_gpu::{AdapterChoice, GpuBackend};

fn gpu_groups(c: &mut Criterion) {
    let mut gpu = match GpuBackend::new(AdapterChoice::Any) {
        Ok(gpu) => gpu,
        Err(e) => panic!("the gpu benches need an adapter (lavapipe will do): {e}"),
    };
    let paper = paper_config("sphere", 20_000);
    let mut render = gpu.prepare(&paper).expect("prepare");
    c.benchmark_group("trace").bench_function("gpu", |b| b.iter(|| render.photon_map(0, &mut NoProgress).unwrap()));
    let mut group = c.benchmark_group("frame");
    group.bench_function("gpu", |b| b.iter(|| frame(&mut gpu, &paper)));
    // The paper's configuration as a live render: after the first pass
    // (view rays, pilot), each frame is one pass.
    let mut live = paper.clone();
    live.scene.render.radius_mode = RadiusMode::Progressive;
    let mut session = gpu.session(&live).expect("session");
    session.next_pass(&mut NoProgress).expect("first pass");
    group.bench_function("gpu-session", |b| {
        b.iter(|| {
            session.next_pass(&mut NoProgress).unwrap();
            session.context().wait().unwrap();
        })
    });
    // A dense caustic filling the view (the built-in `caustic` close-up):
    // most first radii are small, gathered in the finer grid levels.
    let mut doc = prismatic_cli::load_scene("caustic").expect("built-in caustic");
    let r = &mut doc.scene.render;
    (r.width, r.height, r.photons) = (200, 200, 100_000);
    let caustic = prismatic_core::PreparedScene::new(doc.scene).expect("valid");
    let mut session = gpu.session(&caustic).expect("session");
    session.next_pass(&mut NoProgress).expect("first pass");
    session.context().wait().expect("the grid levels come back");
    group.bench_function("gpu-session-caustic", |b| {
        b.iter(|| {
            session.next_pass(&mut NoProgress).unwrap();
            session.context().wait().unwrap();
        })
    });
    group.finish();
    let mut group = c.benchmark_group("lights");
    for (name, scene) in lit_by_each_light(1_000_000) {
        let mut render = gpu.prepare(&scene).expect("prepare");
        group.throughput(Throughput::Elements(u64::from(scene.scene.render.photons)));
        group.bench_function(BenchmarkId::new(name, "trace"), |b| {
            b.iter(|| render.photon_map(0, &mut NoProgress).unwrap())
        });
        group.throughput(Throughput::Elements(u64::from(scene.scene.render.width * scene.scene.render.height)));
        group.bench_function(BenchmarkId::new(name, "view"), |b| {
            b.iter(|| {
                let mut session = gpu.session(&scene).unwrap();
                session.ready(&mut NoProgress).unwrap();
                session.context().wait().unwrap();
            })
        });
    }
    group.finish();
    let mut group = c.benchmark_group("indirect");
    for (name, scene) in prismatic_benches::indirect_and_caustic(100_000) {
        let mut render = gpu.prepare(&scene).expect("prepare");
        group.throughput(Throughput::Elements(100_000));
        group.bench_function(BenchmarkId::new(name, "gpu"), |b| {
            b.iter(|| render.photon_map(0, &mut NoProgress).unwrap())
        });
    }
    group.finish();
    trace_and_pass_group(c, &mut gpu, "metals", prismatic_benches::ring_metals(1_000_000));
    trace_and_pass_group(c, &mut gpu, "rough_glass", prismatic_benches::sphere_frosted(1_000_000));
}

/// Group `group`: each named scene's photons (throughput in photons) and
/// one pass of its live render after the first (in pixels) on the GPU.
fn trace_and_pass_group<const N: usize>(
    c: &mut Criterion,
    gpu: &mut GpuBackend,
    group: &str,
    scenes: [(&str, PreparedScene); N],
) {
    let mut g = c.benchmark_group(group);
    for (name, scene) in scenes {
        let mut render = gpu.prepare(&scene).expect("prepare");
        g.throughput(Throughput::Elements(u64::from(scene.scene.render.photons)));
        g.bench_function(BenchmarkId::new(name, "trace"), |b| {
            b.iter(|| render.photon_map(0, &mut NoProgress).unwrap())
        });
        let mut session = gpu.session(&scene).expect("session");
        session.next_pass(&mut NoProgress).expect("first pass");
        g.throughput(Throughput::Elements(u64::from(scene.scene.render.width * scene.scene.render.height)));
        g.bench_function(BenchmarkId::new(name, "pass"), |b| {
            b.iter(|| {
                session.next_pass(&mut NoProgress).unwrap();
                session.context().wait().unwrap();
            })
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = gpu_groups
}
criterion_main!(benches);
