//! Criterion benches, one group per pipeline stage and backend:
//! `trace/reference` (photons per second) and `frame/reference` (trace +
//! grid + render) on the paper's configuration of the `sphere` scene.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use prismatic_benches::paper_config;
use prismatic_core::grid::PhotonGrid;
use prismatic_core::{render, trace};
use std::hint::black_box;

const PAPER_PHOTONS: u32 = 20_000;

fn trace_reference(c: &mut Criterion) {
    let mut g = c.benchmark_group("trace/reference");
    for name in ["sphere", "prism"] {
        let scene = paper_config(name, PAPER_PHOTONS);
        g.throughput(Throughput::Elements(u64::from(PAPER_PHOTONS)));
        g.bench_function(name, |b| b.iter(|| black_box(trace::trace_photons(&scene))));
    }
    g.finish();
}

fn grid_reference(c: &mut Criterion) {
    let scene = paper_config("sphere", PAPER_PHOTONS);
    let map = trace::trace_photons(&scene);
    let mut g = c.benchmark_group("grid/reference");
    g.throughput(Throughput::Elements(map.photons.len() as u64));
    g.bench_function("sphere", |b| b.iter(|| black_box(PhotonGrid::build(&map.photons, scene.scene.render.radius))));
    g.finish();
}

fn frame_reference(c: &mut Criterion) {
    let scene = paper_config("sphere", PAPER_PHOTONS);
    let mut g = c.benchmark_group("frame/reference");
    g.sample_size(10);
    g.bench_function("sphere", |b| {
        b.iter(|| {
            let map = trace::trace_photons(&scene);
            black_box(render::render(&scene, &map))
        })
    });
    g.finish();
}

criterion_group!(benches, trace_reference, grid_reference, frame_reference);
criterion_main!(benches);
