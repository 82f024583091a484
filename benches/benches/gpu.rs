//! Criterion benches of the GPU backend, one group per stage: `trace/gpu`
//! (photon pass and readback of the map), `grid/gpu` (upload and grid
//! build), `gather/gpu` (grid, ray tracing and gather from a given map, image
//! read back), `frame/gpu` (the whole frame on the device) and
//! `frame/gpu-session` (one progressive pass of a live `GpuSession`, the
//! engine-facing path: photons, grid levels, gather at resident visible
//! points, sums; also `frame/gpu-session-caustic`, a dense caustic filling
//! the view, where the finer grid levels carry most points). Every
//! measurement ends with a device sync. On lavapipe they only show that
//! the stages run; real figures need a GPU.

use criterion::{Criterion, criterion_group, criterion_main};
use prismatic_core::{Backend, NoProgress};
use prismatic_gpu::{AdapterChoice, GpuBackend, GpuContext, GpuOptions, GpuSession};

fn scene(photons: u32) -> prismatic_core::PreparedScene {
    let mut doc = prismatic_cli::load_scene("sphere").expect("built-in sphere");
    doc.scene.render.photons = photons;
    prismatic_core::PreparedScene::new(doc.scene).expect("valid")
}

fn gpu_groups(c: &mut Criterion) {
    let mut gpu = match GpuBackend::new(AdapterChoice::Any) {
        Ok(gpu) => gpu,
        Err(e) => panic!("the gpu benches need an adapter (lavapipe will do): {e}"),
    };
    let paper = scene(20_000);
    let map = gpu.trace_photons(&paper, &mut NoProgress).expect("trace");
    c.benchmark_group("trace")
        .bench_function("gpu", |b| b.iter(|| gpu.trace_photons(&paper, &mut NoProgress).unwrap()));
    c.benchmark_group("grid").bench_function("gpu", |b| b.iter(|| gpu.build_grid(&paper, &map).unwrap()));
    c.benchmark_group("gather")
        .bench_function("gpu", |b| b.iter(|| gpu.render(&paper, &map, &mut NoProgress).unwrap()));
    let mut frame = c.benchmark_group("frame");
    frame.bench_function("gpu", |b| b.iter(|| gpu.frame(&paper).unwrap()));
    // The paper's configuration as a live session: after the first frame
    // (view rays, pilot), each frame is one pass.
    let ctx = GpuContext::new(AdapterChoice::Any).expect("adapter");
    let mut session = GpuSession::new(ctx, &paper, GpuOptions::default()).expect("session");
    session.frame().expect("first frame");
    frame.bench_function("gpu-session", |b| {
        b.iter(|| {
            session.frame().unwrap();
            session.context().wait().unwrap();
        })
    });
    // A dense caustic filling the view (the built-in `caustic` close-up):
    // most first radii are small, gathered in the finer grid levels.
    let mut doc = prismatic_cli::load_scene("caustic").expect("built-in caustic");
    let r = &mut doc.scene.render;
    (r.width, r.height, r.photons) = (200, 200, 100_000);
    let caustic = prismatic_core::PreparedScene::new(doc.scene).expect("valid");
    let ctx = GpuContext::new(AdapterChoice::Any).expect("adapter");
    let mut session = GpuSession::new(ctx, &caustic, GpuOptions::default()).expect("session");
    session.frame().expect("first frame");
    session.context().wait().expect("the grid levels come back");
    frame.bench_function("gpu-session-caustic", |b| {
        b.iter(|| {
            session.frame().unwrap();
            session.context().wait().unwrap();
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = gpu_groups
}
criterion_main!(benches);
