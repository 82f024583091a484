//! Frame times of the GPU's render (the session an engine embeds) on
//! whatever adapter wgpu picks, at sizes criterion cannot sample in
//! reasonable time (1080p, 10M photons): per configuration a live render,
//! one pass per frame. Per frame, waited for alone (latency) and back to
//! back with one wait at the end (throughput, what an engine's frame loop
//! sees), the host's time to submit a frame, and the same render with a
//! 1×1 image (photons and grid only) to say which half bounds the frame,
//! the GPU time of its stages (photons, grid, gather; median over the
//! waited frames, where the adapter has timestamp queries), the grid levels
//! the render built (bit l: cells of the pass radius / 4^l) and the bytes a
//! frame moves each way. The paper's configuration gathers within a fixed
//! radius (its frame is one pass); the others are progressive. The last
//! seven are the default render's light transport (light tracing, hero
//! wavelengths and view paths), as prismatic's image, as a caustic layer
//! in the frame the camera sees, and as an engine's frames (its prepass
//! read each frame, one pass, the layer's history): what an engine pays.
//! Then `room` as authored (caustic and indirect photons), with four
//! wavelengths a path and one, each also without light tracing: the
//! "gather" stage holds the photons' splat to the camera, so the
//! difference is what the splat costs.
//!
//! Then the photon map of one pass read back (what `prismatic photons` pays).
//!
//! `cargo run --release -p prismatic-benches --example gpu_frame_times -- [FRAMES] [--session-only] [--only TEXT]`
//! (`--only`: the configurations whose label contains TEXT)

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::scene::{RadiusMode, RenderSettings, WavelengthSampling};
use prismatic_core::{LayerFrame, NoProgress, PreparedScene, Render, StageTimes};
use prismatic_gpu::{AdapterChoice, DepthEncoding, FrameTextures, GpuBackend, GpuContext, GpuOptions, NormalEncoding};

#[path = "../../backend-gpu/examples/engine_loop/raster.rs"]
mod raster;
use std::time::{Duration, Instant};

/// One configuration to time.
struct Config {
    label: &'static str,
    /// The built-in scene.
    scene: &'static str,
    width: u32,
    height: u32,
    photons: u32,
    bands: BandSpec,
    wavelengths: WavelengthSampling,
    projection_maps: bool,
    radius_mode: RadiusMode,
    /// The paper's light transport, or the default render's.
    transport: Transport,
}

/// How a configuration's photons reach the image.
#[derive(Clone, Copy, PartialEq)]
enum Transport {
    /// As the configuration's settings say (the paper's gather).
    Gathered,
    /// The default render's: light tracing, hero wavelengths and view
    /// paths, the density gather behind glass.
    LightTraced,
    /// As light traced, drawn as a caustic layer in the frame the camera
    /// sees (an engine's depth and normals): no view rays, no gather.
    Layer,
    /// A caustic layer as an engine draws it every frame
    /// (`GpuSession::layer_frame`): its frame read from its prepass's
    /// textures (engine_loop's raster of the floor), one pass, the history.
    EngineFrames,
    /// The scene's own settings but the size and wavelengths, with light
    /// tracing as given.
    AsAuthored { light_tracing: bool },
}

fn scene(c: &Config, width: u32, height: u32) -> PreparedScene {
    let mut doc = prismatic_cli::load_scene(c.scene).expect("a built-in scene");
    let r = &mut doc.scene.render;
    if let Transport::AsAuthored { light_tracing } = c.transport {
        (r.width, r.height, r.wavelengths, r.light_tracing) = (width, height, c.wavelengths, light_tracing);
        return PreparedScene::new(doc.scene).expect("valid");
    }
    (r.width, r.height, r.photons) = (width, height, c.photons);
    r.bands = c.bands;
    r.wavelengths = c.wavelengths;
    r.projection_maps = c.projection_maps;
    r.radius_mode = c.radius_mode;
    if c.transport != Transport::Gathered {
        let d = RenderSettings::default();
        (r.estimator, r.light_tracing, r.view_paths) = (d.estimator, d.light_tracing, d.view_paths);
    }
    PreparedScene::new(doc.scene).expect("valid")
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() {
    let frames: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(8).max(2);
    let session_only = std::env::args().any(|a| a == "--session-only");
    let ctx = GpuContext::new(AdapterChoice::Any).unwrap_or_else(|e| panic!("no adapter: {e}"));
    let gpu = GpuBackend::with_context(ctx, GpuOptions { stage_times: true, ..GpuOptions::default() });
    let info = gpu.adapter().map(prismatic_gpu::describe).unwrap_or_default();
    println!("adapter: {info}; median of {frames} frames after the first");
    let (split, progressive) = (WavelengthSampling::Split, RadiusMode::Progressive);
    let config = |label, (width, height), photons, bands, wavelengths, projection_maps, radius_mode| Config {
        label,
        scene: "sphere",
        width,
        height,
        photons,
        bands,
        wavelengths,
        projection_maps,
        radius_mode,
        transport: Transport::Gathered,
    };
    let hero = |label, photons, transport| Config {
        transport,
        ..config(label, (1920, 1080), photons, BandSpec::Physical(32), WavelengthSampling::Hero, true, progressive)
    };
    let light_traced = |label, photons| hero(label, photons, Transport::LightTraced);
    let layer = |label, photons| hero(label, photons, Transport::Layer);
    let engine_frames = |label, photons| hero(label, photons, Transport::EngineFrames);
    let hd = (1920, 1080);
    let room = |label, wavelengths, light_tracing| Config {
        scene: "room",
        transport: Transport::AsAuthored { light_tracing },
        ..config(label, (400, 400), 0, BandSpec::Physical(32), wavelengths, true, progressive)
    };
    let configs = [
        config(
            "paper: 400x400, 20k, paper7, fixed radius",
            (400, 400),
            20_000,
            BandSpec::Paper7,
            split,
            false,
            RadiusMode::Fixed,
        ),
        config("sphere 1080p, 1M x paper7 split", hd, 1_000_000, BandSpec::Paper7, split, true, progressive),
        config(
            "sphere 1080p, 1M x 7 physical bands split",
            hd,
            1_000_000,
            BandSpec::Physical(7),
            split,
            true,
            progressive,
        ),
        config("sphere 1080p, 10M x paper7 split", hd, 10_000_000, BandSpec::Paper7, split, true, progressive),
        config(
            "sphere 1080p, 10M x paper7 random_band",
            hd,
            10_000_000,
            BandSpec::Paper7,
            WavelengthSampling::RandomBand,
            true,
            progressive,
        ),
        light_traced("sphere 1080p, 100k x hero, light traced", 100_000),
        light_traced("sphere 1080p, 1M x hero, light traced", 1_000_000),
        light_traced("sphere 1080p, 4M x hero, light traced", 4_000_000),
        layer("sphere 1080p, 100k x hero, caustic layer", 100_000),
        layer("sphere 1080p, 1M x hero, caustic layer", 1_000_000),
        layer("sphere 1080p, 4M x hero, caustic layer", 4_000_000),
        engine_frames("sphere 1080p, 1M x hero, caustic layer in engine frames", 1_000_000),
        room("room 400x400, hero", WavelengthSampling::Hero, true),
        room("room 400x400, random_band", WavelengthSampling::RandomBand, true),
        room("room 400x400, hero, no light tracing", WavelengthSampling::Hero, false),
        room("room 400x400, random_band, no light tracing", WavelengthSampling::RandomBand, false),
    ];
    let args: Vec<String> = std::env::args().collect();
    let only = args.iter().position(|a| a == "--only").and_then(|i| args.get(i + 1));
    let chosen: Vec<Config> =
        configs.into_iter().filter(|c| only.is_none_or(|o| c.label.contains(o.as_str()))).collect();
    let configs = chosen;
    session_frames(&gpu, &configs, frames);
    if configs.is_empty() {
        return;
    }
    if session_only {
        return;
    }
    // The photon map of a pass read back.
    let c = &configs[1];
    let mut render = gpu.session(&scene(c, c.width, c.height)).expect("a session");
    let t = Instant::now();
    match render.photon_map(0, &mut NoProgress) {
        Ok(map) => {
            println!(
                "photon map of a pass read back, {}: {:.2} ms, {} photons",
                c.label,
                ms(t.elapsed()),
                map.photons.len()
            )
        }
        Err(e) => println!("the photon map failed: {e}"),
    }
}

/// What one configuration's render measured.
struct Timed {
    first: Duration,
    waited: Duration,
    piped: Duration,
    submit: Duration,
    gpu: String,
    levels: u32,
    /// Bytes a frame uploads and reads back.
    traffic: (u64, u64),
}

/// A live render's frames per configuration (see the module's comment).
fn session_frames(gpu: &GpuBackend, configs: &[Config], frames: usize) {
    println!();
    println!(
        "| render | first frame | frame (waited) | frames back to back | fps | host submit | photons+grid only (1x1) | GPU stages (median) | grid levels | bytes up / back a frame |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for c in configs {
        let run = |width: u32, height: u32| -> Result<Timed, String> {
            let scene = scene(c, width, height);
            let mut session = gpu.session(&scene).map_err(|e| e.to_string())?;
            if c.transport == Transport::Layer {
                session.set_layer(Some(&LayerFrame::seen_by_camera(&scene))).map_err(|e| e.to_string())?;
            }
            let ctx = session.context().clone();
            let prepass = (c.transport == Transport::EngineFrames).then(|| {
                let floor = raster::floor();
                let (prepass, commands) = raster::prepass(&ctx.device, &scene.scene.camera, (width, height), &floor);
                ctx.queue.submit([commands]);
                (raster::view(&prepass.depth), raster::view(&prepass.normal))
            });
            let mut frame = 0;
            let mut step = |session: &mut prismatic_gpu::GpuSession| -> Result<(), String> {
                frame += 1;
                match &prepass {
                    Some((depth, normal)) => {
                        let textures = FrameTextures {
                            depth,
                            depth_encoding: DepthEncoding::ReverseInfinite { near: raster::NEAR },
                            normal,
                            normal_encoding: NormalEncoding::Unorm,
                        };
                        session.layer_frame(&textures, frame, 256).map_err(|e| e.to_string())
                    }
                    None => session.next_pass(&mut NoProgress).map(|_| ()).map_err(|e| e.to_string()),
                }
            };
            let wait = |s: &prismatic_gpu::GpuSession| s.context().wait().map_err(|e| e.to_string());
            let t = Instant::now();
            step(&mut session)?;
            wait(&session)?;
            let first = t.elapsed();
            let (mut waited, mut stages) = (Vec::with_capacity(frames), Vec::with_capacity(frames));
            for frame in 0..frames {
                let t = Instant::now();
                step(&mut session)?;
                wait(&session)?;
                waited.push(t.elapsed());
                // The frame before this one's, come back while this one was
                // waited for; the first frame's (view rays and pilot) is left out.
                stages.extend(session.stage_times().filter(|_| frame > 0));
            }
            waited.sort();
            let median = |stage: fn(&StageTimes) -> Duration| {
                let mut times: Vec<Duration> = stages.iter().map(stage).collect();
                times.sort();
                times[times.len() / 2]
            };
            let gpu = if stages.is_empty() {
                "no timestamps".to_string()
            } else {
                let t = StageTimes {
                    view: median(|t| t.view),
                    photons: median(|t| t.photons),
                    grid: median(|t| t.grid),
                    gather: median(|t| t.gather),
                };
                t.to_string()
            };
            let before = session.context().traffic();
            let (t, mut submit) = (Instant::now(), Duration::ZERO);
            for _ in 0..frames {
                let s = Instant::now();
                step(&mut session)?;
                submit += s.elapsed();
            }
            wait(&session)?;
            let after = session.context().traffic();
            let n = frames as u32;
            let per_frame = ((after.0 - before.0) / n as u64, (after.1 - before.1) / n as u64);
            Ok(Timed {
                first,
                waited: waited[frames / 2],
                piped: t.elapsed() / n,
                submit: submit / n,
                gpu,
                levels: session.grid_levels(),
                traffic: per_frame,
            })
        };
        match (run(c.width, c.height), run(1, 1)) {
            (Ok(t), Ok(alone)) => println!(
                "| {} | {:.1} ms | {:.2} ms | {:.2} ms | {:.1} | {:.2} ms | {:.2} ms | {} | {:#05b} | {} / {} |",
                c.label,
                ms(t.first),
                ms(t.waited),
                ms(t.piped),
                1.0 / t.piped.as_secs_f64(),
                ms(t.submit),
                ms(alone.waited),
                t.gpu,
                t.levels,
                t.traffic.0,
                t.traffic.1
            ),
            (full, alone) => println!("| {} | {:?} | {:?} |", c.label, full.err(), alone.err()),
        }
    }
}
