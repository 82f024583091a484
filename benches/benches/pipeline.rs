//! Criterion benches of the host backends through the render protocol, on
//! the paper's configuration (400×400, 20,000 white photons, 7 bands, a
//! fixed radius) of the `sphere` and `prism` scenes, and on 1,000,000
//! photons:
//!
//! - `trace/<backend>`: a pass's photon map, `Render::photon_map` (a new
//!   map each call; throughput in white photons); `trace/cpu-1t` and
//!   `trace/cpu-2t` pin the thread count;
//! - `grid/<kernel>`: the hash-grid build over a pass's photons (counting sort);
//! - `view/<backend>`: a render prepared and its view rays traced;
//!   `view/cpu-32-{centre,sampled}`: the same with 32 bands, hero
//!   wavelengths and light tracing, view rays through the pixel centres
//!   (split into 32 bands at the glass) or sampled (pass 0's paths, 4
//!   hero wavelengths): the first pass's floor;
//! - `frame/<backend>`: the paper's frame (view rays, one pass, image);
//! - `effects/<scene>/{planned,unplanned}`: what the effect plan saves;
//! - `progressive/<backend>-<threads>t/<photons>/pass-<k>`: pass k of a
//!   progressive render of `sphere` as `prismatic render` runs it (radii
//!   shrink with k), on a render whose view rays, pilot and pass 1 are
//!   traced, and
//!   `progressive/prepare`: the view rays and the pilot pass;
//! - `lights/<light>/{trace,view}`: `sphere` (default settings, 400×400,
//!   100,000 photons) under its spot light and under the studio
//!   environment (32 suns of its median cut, projection maps on): the CPU's
//!   photon pass (throughput in photons) and its view pass (direct light,
//!   one shadow ray per light per point);
//! - `metals/{rough,mapped,coloured,filmed,polished,mirrors}/{trace,view}`:
//!   the built-in `ring` (100,000 photons) with its metals as they are, as
//!   they are read through white roughness maps and through white colour
//!   textures, under a film, all polished and as mirrors: the CPU's photon
//!   pass and its view pass;
//! - `rough_glass/{frosted,polished}/{trace,view}`: the built-in `sphere`
//!   (100,000 photons) with its glass frosted (roughness 0.3) and polished;
//! - `scene/{new,update-camera,update-mesh}/<triangles>`: `sphere` with its
//!   sphere as a closed mesh, prepared from scratch (every hierarchy
//!   built) and updated from the last frame's preparation after the camera
//!   moved (hierarchy shared) or the mesh's vertices moved (refitted).

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use prismatic_benches::{frame, paper_config};
use prismatic_core::photons::grid::PhotonGrid;
use prismatic_core::{Backend, BandSpec, NoProgress, PreparedScene, ReferenceBackend, ViewPaths, WavelengthSampling};
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
                let mut render = ReferenceBackend.prepare(&scene).unwrap();
                g.bench_function(BenchmarkId::new("reference", &id), |b| {
                    b.iter(|| black_box(render.photon_map(0, &mut NoProgress).unwrap()))
                });
            }
            for threads in [1, 2] {
                let mut render = CpuBackend::with_threads(threads).expect("thread pool").prepare(&scene).unwrap();
                g.bench_function(BenchmarkId::new(format!("cpu-{threads}t"), &id), |b| {
                    b.iter(|| black_box(render.photon_map(0, &mut NoProgress).unwrap()))
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
        let map = CpuBackend::new().prepare(&scene).unwrap().photon_map(0, &mut NoProgress).unwrap();
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

fn view_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("view");
    g.sample_size(10);
    let scene = paper_config("sphere", PAPER_PHOTONS);
    let with = |view_paths: ViewPaths| {
        let mut s = scene.scene.clone();
        let r = &mut s.render;
        (r.bands, r.wavelengths, r.light_tracing, r.view_paths) =
            (BandSpec::Physical(32), WavelengthSampling::Hero, true, view_paths);
        PreparedScene::new(s).unwrap()
    };
    let cases: [(&str, Box<dyn Backend>, PreparedScene); 4] = [
        ("cpu-32-centre", Box::new(CpuBackend::new()), with(ViewPaths::Centre)),
        ("cpu-32-sampled", Box::new(CpuBackend::new()), with(ViewPaths::Sampled)),
        ("reference", Box::new(ReferenceBackend), scene.clone()),
        ("cpu", Box::new(CpuBackend::new()), scene),
    ];
    for (name, mut backend, scene) in cases {
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut render = backend.prepare(&scene).unwrap();
                render.ready(&mut NoProgress).unwrap();
                black_box(render)
            })
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
                b.iter(|| black_box(frame(&mut ReferenceBackend, &scene)))
            });
        }
        let mut backend = CpuBackend::new();
        g.bench_function(BenchmarkId::new("cpu", photons), |b| b.iter(|| black_box(frame(&mut backend, &scene))));
    }
    g.finish();
}

/// `effects/<scene>/{planned,unplanned}`: a whole CPU frame of each built-in
/// scene as it is (with a fixed radius), against the same scene with every
/// effect forced on and no projection maps, emitting as many more photons
/// as it takes to store the same caustic (the time the effect plan saves at
/// equal quality).
fn effects_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("effects");
    g.sample_size(10);
    for name in ["sphere", "prism", "recombine", "rainbow"] {
        let planned = builtin(name, None, prismatic_core::model::scene::RadiusMode::Fixed);
        let scale = planned.plan.projections.iter().flatten().map(|p| p.scale).fold(1.0f32, f32::min);
        let more = (planned.scene.render.photons as f32 / scale) as u32;
        let mut unplanned = builtin(name, Some(more), prismatic_core::model::scene::RadiusMode::Fixed);
        unplanned.simulate_everything();
        for (id, scene) in [("planned", &planned), ("unplanned", &unplanned)] {
            let mut backend = CpuBackend::new();
            g.bench_function(BenchmarkId::new(name, id), |b| b.iter(|| black_box(frame(&mut backend, scene))));
        }
    }
    g.finish();
}

/// `progressive/...`: a pass of the built-in `sphere` (400×400, its own
/// radius and 7 paper bands) at 65k (the scene's) and 1M photons a pass;
/// pass 2 against pass 64 shows whether a pass's cost stays flat, 1 against
/// 2 threads how the gather scales. Each measurement runs its pass on a
/// render made outside the timing (view rays, pilot and pass 1 traced, so
/// that the kernels' buffers have grown to a pass's size, as they have for
/// every pass of a render after its first).
fn progressive_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("progressive");
    g.sample_size(10);
    let progressive = prismatic_core::model::scene::RadiusMode::Progressive;
    let scene = builtin("sphere", None, progressive);
    let mut backend = CpuBackend::new();
    g.bench_function("prepare", |b| {
        b.iter(|| {
            let mut render = backend.prepare(&scene).unwrap();
            render.ready(&mut NoProgress).unwrap();
            black_box(render)
        })
    });
    for photons in [scene.scene.render.photons, MANY_PHOTONS] {
        let scene = builtin("sphere", Some(photons), progressive);
        for threads in [1, 2] {
            let backend = CpuBackend::with_threads(threads).expect("pool");
            for k in [2u32, 64] {
                let id = BenchmarkId::new(format!("cpu-{threads}t/{photons}"), format!("pass-{k}"));
                let ready = || {
                    let mut render = backend.clone().prepare(&scene).unwrap();
                    render.run_pass(0, &mut NoProgress).unwrap();
                    render
                };
                g.bench_function(id, |b| {
                    b.iter_batched(
                        ready,
                        |mut r| {
                            r.run_pass(k - 1, &mut NoProgress).unwrap();
                            black_box(r)
                        },
                        BatchSize::PerIteration,
                    )
                });
            }
        }
    }
    // The default settings (light tracing, 32 bands with hero wavelengths,
    // each path coloured by its wavelength) on the sphere: a later pass.
    let mut doc = prismatic_cli::load_scene("sphere").expect("built-in sphere");
    let r = &doc.scene.render;
    doc.scene.render = prismatic_core::RenderSettings {
        width: r.width,
        height: r.height,
        photons: 200_000,
        radius: r.radius,
        exposure: r.exposure,
        ambient: r.ambient,
        ..Default::default()
    };
    let scene = PreparedScene::new(doc.scene).expect("valid");
    let backend = CpuBackend::with_threads(2).expect("pool");
    g.bench_function(BenchmarkId::new("cpu-2t/defaults-200000", "pass-2"), |b| {
        b.iter_batched(
            || {
                let mut render = backend.clone().prepare(&scene).unwrap();
                render.run_pass(0, &mut NoProgress).unwrap();
                render
            },
            |mut r| {
                r.run_pass(1, &mut NoProgress).unwrap();
                black_box(r)
            },
            BatchSize::PerIteration,
        )
    });
    g.finish();
}

/// A pass's photons and the view pass under the spot, the studio environment and a light panel.
fn lights_group(c: &mut Criterion) {
    trace_and_view_group(c, "lights", prismatic_benches::lit_by_each_light(100_000));
}

/// A pass of the `ring` scene's photons (100,000) and its view pass on the
/// CPU, with its metals as built, mapped, textured, filmed, polished and as mirrors.
fn metals_group(c: &mut Criterion) {
    trace_and_view_group(c, "metals", prismatic_benches::ring_metals(100_000));
}

/// The built-in `sphere` (100,000 photons) with its glass frosted and
/// polished, on the CPU.
fn rough_glass_group(c: &mut Criterion) {
    trace_and_view_group(c, "rough_glass", prismatic_benches::sphere_frosted(100_000));
}

/// Group `group`: each named scene's photon pass (throughput in photons)
/// and its view pass (in pixels) on the CPU.
fn trace_and_view_group<const N: usize>(c: &mut Criterion, group: &str, scenes: [(&str, PreparedScene); N]) {
    let mut g = c.benchmark_group(group);
    g.sample_size(10);
    for (name, scene) in scenes {
        let mut render = CpuBackend::new().prepare(&scene).unwrap();
        g.throughput(Throughput::Elements(u64::from(scene.scene.render.photons)));
        g.bench_function(BenchmarkId::new(name, "trace"), |b| {
            b.iter(|| black_box(render.photon_map(0, &mut NoProgress).unwrap()))
        });
        g.throughput(Throughput::Elements(u64::from(scene.scene.render.width * scene.scene.render.height)));
        g.bench_function(BenchmarkId::new(name, "view"), |b| {
            b.iter(|| {
                let mut render = CpuBackend::new().prepare(&scene).unwrap();
                render.ready(&mut NoProgress).unwrap();
                black_box(render)
            })
        });
    }
    g.finish();
}

/// A pass of 100,000 indirect photons (no caustic ones) in the built-in
/// sphere scene: the scalar reference against the CPU's packets, and the
/// spot's caustic pass of as many photons beside it.
fn indirect_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("indirect");
    g.sample_size(10);
    let [(_, indirect), (_, caustic)] = prismatic_benches::indirect_and_caustic(100_000);
    g.throughput(Throughput::Elements(100_000));
    for (name, scene) in [("indirect", &indirect), ("caustic", &caustic)] {
        let mut cpu = CpuBackend::new().prepare(scene).unwrap();
        g.bench_function(BenchmarkId::new(name, "cpu"), |b| {
            b.iter(|| black_box(cpu.photon_map(0, &mut NoProgress).unwrap()))
        });
    }
    let mut reference = ReferenceBackend.prepare(&indirect).unwrap();
    g.bench_function(BenchmarkId::new("indirect", "reference"), |b| {
        b.iter(|| black_box(reference.photon_map(0, &mut NoProgress).unwrap()))
    });
    g.finish();
}

/// What preparing a changed scene costs, against preparing it anew.
fn scene_group(c: &mut Criterion) {
    let mut g = c.benchmark_group("scene");
    g.sample_size(10);
    for rings in [50u32, 158] {
        let mut doc = prismatic_cli::load_scene("sphere").expect("built-in sphere");
        let prismatic_core::Shape::Sphere { center, radius } = doc.scene.objects[1].shape else {
            panic!("object 1 is the sphere")
        };
        doc.scene.objects[1].shape = prismatic_conformance::scenes::sphere_mesh(center, radius, rings);
        let triangles = 4 * rings * rings;
        let before = prismatic_core::PreparedScene::new(doc.scene.clone()).expect("valid");
        let mut camera_moved = doc.scene.clone();
        camera_moved.camera.position.x += 0.1;
        let mut mesh_moved = doc.scene.clone();
        if let prismatic_core::Shape::Mesh { positions, .. } = &mut mesh_moved.objects[1].shape {
            positions.iter_mut().for_each(|p| p.y += 0.01 * p.x);
        }
        g.bench_function(BenchmarkId::new("new", triangles), |b| {
            b.iter(|| black_box(prismatic_core::PreparedScene::new(mesh_moved.clone()).unwrap()))
        });
        g.bench_function(BenchmarkId::new("update-camera", triangles), |b| {
            b.iter(|| black_box(before.update(camera_moved.clone()).unwrap()))
        });
        g.bench_function(BenchmarkId::new("update-mesh", triangles), |b| {
            b.iter(|| black_box(before.update(mesh_moved.clone()).unwrap()))
        });
    }
    g.finish();
}

/// A built-in scene as it is, or with `photons` instead of its own count, with `radius_mode`.
fn builtin(
    name: &str,
    photons: Option<u32>,
    radius_mode: prismatic_core::model::scene::RadiusMode,
) -> prismatic_core::PreparedScene {
    let mut doc = prismatic_cli::load_scene(name).expect("built-in scene parses");
    doc.scene.render.photons = photons.unwrap_or(doc.scene.render.photons);
    doc.scene.render.radius_mode = radius_mode;
    prismatic_core::PreparedScene::new(doc.scene).expect("built-in scene is valid")
}

criterion_group!(
    benches,
    trace_group,
    grid_group,
    view_group,
    frame_group,
    effects_group,
    progressive_group,
    lights_group,
    metals_group,
    rough_glass_group,
    indirect_group,
    scene_group
);
criterion_main!(benches);
