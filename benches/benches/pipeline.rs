//! Criterion benches, one group per pipeline stage and backend, on the
//! paper's configuration (400×400, 20,000 white photons, 7 bands) of the
//! `sphere` and `prism` scenes, and on 1,000,000 photons:
//!
//! - `trace/<backend>`: photon tracing (throughput in white photons);
//!   `trace/cpu-1t` and `trace/cpu-2t` pin the thread count;
//! - `grid/cpu`: hash-grid build (counting sort);
//! - `gather/cpu`: ray tracing + gather of a frame with a built grid;
//! - `frame/<backend>`: the whole frame (trace, grid, render);
//! - `effects/<scene>/{planned,unplanned}`: what the effect plan saves;
//! - `progressive/<backend>-<threads>t/<photons>/pass-<k>`: one progressive
//!   pass (trace + grids + gather at the visible points) of `sphere` as
//!   `prismatic render` runs it, at pass k (radii shrink with k), and
//!   `progressive/prepare`: the view rays and the pilot pass.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use prismatic_benches::paper_config;
use prismatic_core::PhotonMap;
use prismatic_core::grid::PhotonGrid;
use prismatic_core::{render, trace};
use prismatic_cpu::{CpuBackend, CpuGrid};
use std::hint::black_box;

const PAPER_PHOTONS: u32 = 20_000;
const MANY_PHOTONS: u32 = 1_000_000;

fn trace_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("trace");
    for name in ["sphere", "prism"] {
        for photons in [PAPER_PHOTONS, MANY_PHOTONS] {
            let scene = paper_config(name, photons);
            let id = format!("{name}/{photons}");
            g.throughput(Throughput::Elements(u64::from(photons)));
            if photons == PAPER_PHOTONS {
                g.bench_function(BenchmarkId::new("reference", &id), |b| {
                    b.iter(|| black_box(trace::trace_photons(&scene)))
                });
            }
            for threads in [1, 2] {
                // An engine traces every frame into the same map: no allocation after the first.
                let mut backend = CpuBackend::with_threads(threads).expect("thread pool");
                let mut map = PhotonMap::default();
                g.bench_function(BenchmarkId::new(format!("cpu-{threads}t"), &id), |b| {
                    b.iter(|| backend.trace_into(&scene, black_box(&mut map)))
                });
            }
        }
    }
    g.finish();
}

fn grid_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("grid");
    for photons in [PAPER_PHOTONS, MANY_PHOTONS] {
        let scene = paper_config("sphere", photons);
        let map = prismatic_cpu::trace_photons(&scene);
        let r = scene.scene.render.radius;
        g.throughput(Throughput::Elements(map.photons.len() as u64));
        if photons == PAPER_PHOTONS {
            g.bench_function(BenchmarkId::new("reference", photons), |b| {
                b.iter(|| black_box(PhotonGrid::build(&map.photons, r)))
            });
        }
        g.bench_function(BenchmarkId::new("cpu", photons), |b| b.iter(|| black_box(CpuGrid::build(&map.photons, r))));
    }
    g.finish();
}

fn gather_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("gather");
    g.sample_size(10);
    for photons in [PAPER_PHOTONS, MANY_PHOTONS] {
        let scene = paper_config("sphere", photons);
        let map = prismatic_cpu::trace_photons(&scene);
        let grid = CpuGrid::build(&map.photons, scene.scene.render.radius);
        g.bench_function(BenchmarkId::new("cpu", photons), |b| {
            b.iter(|| black_box(prismatic_cpu::render_with_grid(&scene, &grid)))
        });
    }
    g.finish();
}

fn frame_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("frame");
    g.sample_size(10);
    for photons in [PAPER_PHOTONS, MANY_PHOTONS] {
        let scene = paper_config("sphere", photons);
        if photons == PAPER_PHOTONS {
            g.bench_function(BenchmarkId::new("reference", photons), |b| {
                b.iter(|| {
                    let map = trace::trace_photons(&scene);
                    black_box(render::render(&scene, &map))
                })
            });
        }
        let mut backend = CpuBackend::new();
        let mut map = PhotonMap::default();
        g.bench_function(BenchmarkId::new("cpu", photons), |b| {
            b.iter(|| {
                backend.trace_into(&scene, &mut map);
                black_box(prismatic_cpu::render(&scene, &map))
            })
        });
    }
    g.finish();
}

/// `effects/<scene>/{planned,unplanned}`: a whole CPU frame of each built-in
/// scene as it is, against the same scene with every effect forced on and
/// no projection maps, emitting as many more photons as it takes to store
/// the same caustic (the time the effect plan saves at equal quality).
fn effects_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("effects");
    g.sample_size(10);
    for name in ["sphere", "prism", "recombine", "rainbow"] {
        let planned = builtin(name, None);
        let scale = planned.plan.projections.iter().flatten().map(|p| p.scale).fold(1.0f32, f32::min);
        let more = (planned.scene.render.photons as f32 / scale) as u32;
        let mut unplanned = builtin(name, Some(more));
        unplanned.simulate_everything();
        for (id, scene) in [("planned", &planned), ("unplanned", &unplanned)] {
            let mut backend = CpuBackend::new();
            let mut map = PhotonMap::default();
            g.bench_function(BenchmarkId::new(name, id), |b| {
                b.iter(|| {
                    backend.trace_into(scene, &mut map);
                    black_box(prismatic_cpu::render(scene, &map))
                })
            });
        }
    }
    g.finish();
}

/// `progressive/...`: a pass of the built-in `sphere` (400×400, its own
/// radius and 7 paper bands) at 65k (the scene's) and 1M photons a pass;
/// pass 2 against pass 64 shows whether a pass's cost stays flat, 1 against
/// 2 threads how the gather scales.
fn progressive_group(c: &mut Criterion) {
    use prismatic_core::progressive::{ProgressiveRender, pass_radius, photon_pass_scene};
    use prismatic_core::{Backend, NoProgress};
    let mut g = c.benchmark_group("progressive");
    g.sample_size(10);
    let scene = builtin("sphere", None);
    let mut backend = CpuBackend::new();
    g.bench_function("prepare", |b| {
        b.iter(|| black_box(ProgressiveRender::prepare(&mut backend, &scene, &mut NoProgress).unwrap()))
    });
    for photons in [scene.scene.render.photons, MANY_PHOTONS] {
        let scene = builtin("sphere", Some(photons));
        for threads in [1, 2] {
            let mut backend = CpuBackend::with_threads(threads).expect("pool");
            let render = ProgressiveRender::prepare(&mut backend, &scene, &mut NoProgress).unwrap();
            let points = &render.points().points;
            for k in [2, 64] {
                let pass = photon_pass_scene(&scene, scene.scene.render.alpha, k - 1);
                let shrink = pass_radius(1.0, scene.scene.render.alpha, k);
                let radii: Vec<f32> = render.initial_radii().iter().map(|r| r * shrink).collect();
                let id = BenchmarkId::new(format!("cpu-{threads}t/{photons}"), format!("pass-{k}"));
                g.bench_function(id, |b| b.iter(|| black_box(backend.gather_pass(&pass, points, &radii).unwrap())));
            }
        }
    }
    g.finish();
}

/// A built-in scene as it is, or with `photons` instead of its own count.
fn builtin(name: &str, photons: Option<u32>) -> prismatic_core::PreparedScene {
    let mut doc = prismatic_cli::load_scene(name).expect("built-in scene parses");
    doc.scene.render.photons = photons.unwrap_or(doc.scene.render.photons);
    prismatic_core::PreparedScene::new(doc.scene).expect("built-in scene is valid")
}

criterion_group!(benches, trace_group, grid_group, gather_group, frame_group, effects_group, progressive_group);
criterion_main!(benches);
