//! Frame times of the GPU backend on whatever adapter wgpu picks, at sizes
//! criterion cannot sample in reasonable time (1080p, 10M photons): each
//! configuration's whole frame (`GpuBackend::frame`, which waits for the
//! device), and two reduced frames that bound its stages: the same photons
//! into a 1×1 image (upload, trace, compaction, grid) and the same image
//! with one photon (view rays and visible points, an empty gather).
//!
//! Then one progressive pass (`Backend::gather_pass`: trace, grid levels,
//! gather at the visible points, sums read back) at 1080p, the visible
//! points and first radii prepared by the CPU backend.
//!
//! Then the engine path: a live `GpuSession` per configuration, one
//! progressive pass per frame. Per frame, waited for alone (latency) and
//! back to back with one wait at the end (throughput, what an engine's
//! frame loop sees), the host's time to submit a frame, and the same
//! session with a 1×1 image (photons and grid only) to say which half
//! bounds the frame, the GPU time of its stages (photons, grid, gather;
//! median over the waited frames, where the adapter has timestamp
//! queries) and the grid levels the session built (bit l: cells of the
//! pass radius / 4^l).
//!
//! `cargo run --release -p prismatic-benches --example gpu_frame_times -- [FRAMES] [--skip-frames] [--session-only]`

use prismatic_core::bands::BandSpec;
use prismatic_core::scene::WavelengthSampling;
use prismatic_core::{Backend, NoProgress, PreparedScene};
use prismatic_gpu::{AdapterChoice, GpuBackend};
use std::time::{Duration, Instant};

/// One configuration to time.
struct Config {
    label: &'static str,
    width: u32,
    height: u32,
    photons: u32,
    bands: BandSpec,
    wavelengths: WavelengthSampling,
    projection_maps: bool,
}

fn scene(c: &Config, width: u32, height: u32, photons: u32) -> PreparedScene {
    let mut doc = prismatic_cli::load_scene("sphere").expect("built-in sphere");
    let r = &mut doc.scene.render;
    (r.width, r.height, r.photons) = (width, height, photons);
    r.bands = c.bands;
    r.wavelengths = c.wavelengths;
    r.projection_maps = c.projection_maps;
    PreparedScene::new(doc.scene).expect("valid")
}

/// Median wall time of `frames` frames after one warm-up frame, and what the first stored.
fn time_frames(gpu: &mut GpuBackend, s: &PreparedScene, frames: usize) -> Result<(Duration, u32), String> {
    let info = gpu.frame(s).map_err(|e| e.to_string())?;
    let mut times = Vec::with_capacity(frames);
    for _ in 0..frames {
        let t = Instant::now();
        gpu.frame(s).map_err(|e| e.to_string())?;
        times.push(t.elapsed());
    }
    times.sort();
    Ok((times[times.len() / 2], info.stored))
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() {
    let frames: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(5);
    let skip_frames = std::env::args().any(|a| a == "--skip-frames");
    let session_only = std::env::args().any(|a| a == "--session-only");
    let mut gpu = GpuBackend::new(AdapterChoice::Any).unwrap_or_else(|e| panic!("no adapter: {e}"));
    let info = gpu.adapter().map(prismatic_gpu::describe).unwrap_or_default();
    println!("adapter: {info}; median of {frames} frames after one warm-up");
    let split = WavelengthSampling::Split;
    let configs = [
        Config {
            label: "paper: 400x400, 20k, paper7, no projection maps",
            width: 400,
            height: 400,
            photons: 20_000,
            bands: BandSpec::Paper7,
            wavelengths: split,
            projection_maps: false,
        },
        Config {
            label: "sphere 1080p, 1M x paper7 split",
            width: 1920,
            height: 1080,
            photons: 1_000_000,
            bands: BandSpec::Paper7,
            wavelengths: split,
            projection_maps: true,
        },
        Config {
            label: "sphere 1080p, 1M x 7 physical bands split",
            width: 1920,
            height: 1080,
            photons: 1_000_000,
            bands: BandSpec::Physical(7),
            wavelengths: split,
            projection_maps: true,
        },
        Config {
            label: "sphere 1080p, 10M x paper7 split",
            width: 1920,
            height: 1080,
            photons: 10_000_000,
            bands: BandSpec::Paper7,
            wavelengths: split,
            projection_maps: true,
        },
        Config {
            label: "sphere 1080p, 10M x paper7 random_band",
            width: 1920,
            height: 1080,
            photons: 10_000_000,
            bands: BandSpec::Paper7,
            wavelengths: WavelengthSampling::RandomBand,
            projection_maps: true,
        },
    ];
    session_frames(&configs, frames.max(8));
    if session_only {
        return;
    }
    println!();
    println!("| configuration | frame | fps | trace+grid (1x1 image) | view rays (1 photon) | stored photons |");
    println!("|---|---:|---:|---:|---:|---:|");
    for c in configs.iter().filter(|_| !skip_frames) {
        let full = time_frames(&mut gpu, &scene(c, c.width, c.height, c.photons), frames);
        let trace = time_frames(&mut gpu, &scene(c, 1, 1, c.photons), frames);
        let rays = time_frames(&mut gpu, &scene(c, c.width, c.height, 1), frames);
        match (full, trace, rays) {
            (Ok((f, stored)), Ok((t, _)), Ok((r, _))) => println!(
                "| {} | {:.2} ms | {:.1} | {:.2} ms | {:.2} ms | {stored} |",
                c.label,
                ms(f),
                1.0 / f.as_secs_f64(),
                ms(t),
                ms(r)
            ),
            (f, t, r) => println!("| {} | {f:?} | | {t:?} | {r:?} | |", c.label),
        }
    }
    progressive_passes(&mut gpu, &configs[1..], frames);
    if skip_frames {
        return;
    }
    // The photon map read back (what `prismatic photons` pays on top of the trace).
    let c = &configs[1];
    let s = scene(c, c.width, c.height, c.photons);
    let t = Instant::now();
    match gpu.trace_photons(&s, &mut NoProgress) {
        Ok(map) => println!(
            "trace_photons with readback, {}: {:.2} ms, {} photons",
            c.label,
            ms(t.elapsed()),
            map.photons.len()
        ),
        Err(e) => println!("trace_photons failed: {e}"),
    }
}

/// Median time of a progressive pass (pass 2 and pass 64) per configuration.
fn progressive_passes(gpu: &mut GpuBackend, configs: &[Config], frames: usize) {
    use prismatic_core::progressive::{ProgressiveRender, pass_radius, photon_pass_scene};
    println!();
    println!("| progressive pass | visible points | pass 2 | pass 64 | passes/s |");
    println!("|---|---:|---:|---:|---:|");
    for c in configs {
        let s = scene(c, c.width, c.height, c.photons);
        let t = Instant::now();
        let render = ProgressiveRender::prepare(&mut prismatic_cpu::CpuBackend::new(), &s, &mut NoProgress)
            .expect("cpu prepares");
        let prepare = t.elapsed();
        let points = &render.points().points;
        let mut medians = Vec::new();
        for k in [2u32, 64] {
            let pass = photon_pass_scene(&s, s.scene.render.alpha, k - 1);
            let shrink = pass_radius(1.0, s.scene.render.alpha, k);
            let radii: Vec<f32> =
                render.initial_radii().iter().map(|r| (r * shrink).min(pass.scene.render.radius)).collect();
            let mut times = Vec::new();
            for _ in 0..=frames {
                let t = Instant::now();
                if let Err(e) = gpu.gather_pass(&pass, points, &radii) {
                    println!("| {} | pass {k} failed: {e} |", c.label);
                    return;
                }
                times.push(t.elapsed());
            }
            times.remove(0);
            times.sort();
            medians.push(times[times.len() / 2]);
        }
        println!(
            "| {} (cpu prepare {:.2} s) | {} | {:.2} ms | {:.2} ms | {:.1} |",
            c.label,
            prepare.as_secs_f64(),
            points.len(),
            ms(medians[0]),
            ms(medians[1]),
            1.0 / medians[1].as_secs_f64()
        );
    }
}

/// A live session's frames per configuration (see the module's comment).
fn session_frames(configs: &[Config], frames: usize) {
    use prismatic_gpu::{GpuContext, GpuOptions, GpuSession};
    println!();
    println!(
        "| session | first frame | frame (waited) | frames back to back | fps | host submit | photons+grid only (1x1) | GPU stages (median) | grid levels |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for c in configs {
        let run = |width: u32, height: u32| -> Result<([Duration; 4], String, u32), String> {
            let ctx = GpuContext::new(AdapterChoice::Any).map_err(|e| e.to_string())?;
            let s = scene(c, width, height, c.photons);
            let mut session = GpuSession::new(ctx, &s, GpuOptions::default()).map_err(|e| e.to_string())?;
            let t = Instant::now();
            session.frame().map_err(|e| e.to_string())?;
            session.context().wait().map_err(|e| e.to_string())?;
            let first = t.elapsed();
            let (mut waited, mut stages) = (Vec::with_capacity(frames), Vec::with_capacity(frames));
            for _ in 0..frames {
                let t = Instant::now();
                session.frame().map_err(|e| e.to_string())?;
                session.context().wait().map_err(|e| e.to_string())?;
                waited.push(t.elapsed());
                // The frame before this one's, come back while this one was waited for.
                stages.extend(session.stage_times().filter(|t| t.view.is_zero()));
            }
            waited.sort();
            let median = |stage: fn(&prismatic_gpu::StageTimes) -> Duration| {
                let mut times: Vec<Duration> = stages.iter().map(stage).collect();
                times.sort();
                times[times.len() / 2]
            };
            let gpu = if stages.is_empty() {
                "no timestamps".to_string()
            } else {
                let t = prismatic_gpu::StageTimes {
                    view: Duration::ZERO,
                    photons: median(|t| t.photons),
                    grid: median(|t| t.grid),
                    gather: median(|t| t.gather),
                };
                t.to_string()
            };
            let (t, mut submit) = (Instant::now(), Duration::ZERO);
            for _ in 0..frames {
                let s = Instant::now();
                session.frame().map_err(|e| e.to_string())?;
                submit += s.elapsed();
            }
            session.context().wait().map_err(|e| e.to_string())?;
            let n = frames as u32;
            Ok(([first, waited[frames / 2], t.elapsed() / n, submit / n], gpu, session.grid_levels()))
        };
        match (run(c.width, c.height), run(1, 1)) {
            (Ok(([first, waited, piped, submit], gpu, levels)), Ok(([_, alone, ..], ..))) => println!(
                "| {} | {:.1} ms | {:.2} ms | {:.2} ms | {:.1} | {:.2} ms | {:.2} ms | {gpu} | {levels:#05b} |",
                c.label,
                ms(first),
                ms(waited),
                ms(piped),
                1.0 / piped.as_secs_f64(),
                ms(submit),
                ms(alone)
            ),
            (full, alone) => println!("| {} | {full:?} | {alone:?} |", c.label),
        }
    }
}
