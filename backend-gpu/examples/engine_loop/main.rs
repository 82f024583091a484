//! prismatic in any wgpu 30 engine, without Bevy: the engine owns the
//! device, the queue, its depth and normal prepass (`raster`: a floor and a
//! crate that prismatic's scene does not hold) and a storage texture; a
//! `GpuSession` draws a glass sphere's caustic into that texture as a
//! caustic layer in the engine's frame, one progressive pass per frame,
//! for the engine's lighting to add (irradiance × albedo / π) to its own
//! surfaces; the light moves halfway through (the session redoes only what
//! that invalidates).
//!
//! `cargo run --release -p prismatic-gpu --example engine_loop`

mod ball;
mod raster;

use prismatic_core::model::scene::RenderSettings;
use prismatic_core::{NoProgress, PreparedScene, Render, Vec3};
use prismatic_gpu::{DepthEncoding, FrameTextures, GpuContext, GpuOptions, GpuSession, NormalEncoding};
use std::time::Instant;

/// The engine's view.
const SIZE: (u32, u32) = (640, 360);

/// The engine's scene in prismatic's terms, the light at `light_x`.
fn scene(light_x: f32) -> PreparedScene {
    let render = RenderSettings { width: SIZE.0, height: SIZE.1, photons: 100_000, ..RenderSettings::default() };
    ball::scene(render, ball::spot(Vec3::new(light_x, 6.0, -0.5), 40.0), true)
}

/// The engine's opaque triangles: the floor, and a crate beside the sphere.
fn engine_triangles() -> Vec<[Vec3; 3]> {
    let v = Vec3::new;
    let mut triangles = raster::floor().to_vec();
    let (lo, hi) = (v(1.4, 0.0, 0.6), v(2.0, 0.6, 1.2));
    let corner = |i: u32| {
        v(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    };
    for [a, b, c, d] in [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]] {
        triangles.extend(raster::quad(corner(a), corner(b), corner(c), corner(d)));
    }
    triangles
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The engine's device: any adapter, with the limits prismatic needs
    // (and timestamp queries where the adapter has them, for stage times).
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions::default()))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_limits: prismatic_gpu::required_limits(&adapter.limits()),
        required_features: adapter.features() & prismatic_gpu::timestamp_features(),
        ..Default::default()
    }))?;
    // The engine's prepass of its frame, and the texture its lighting samples.
    let (prepass, prepass_commands) = raster::prepass(&device, &ball::camera(), SIZE, &engine_triangles());
    queue.submit([prepass_commands]);
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("caustic irradiance"),
        size: wgpu::Extent3d { width: SIZE.0, height: SIZE.1, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba16Float,
        usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });

    // prismatic on the engine's device: one session (the GPU's render) for the scene's life,
    // timing its stages with GPU timestamps.
    let options = GpuOptions { stage_times: true, ..GpuOptions::default() };
    let mut session = GpuSession::new(GpuContext::from_device(device.clone(), queue)?, &scene(-2.5), options)?;
    // The caustic as a layer in the engine's frame (again whenever the camera or the frame's depth changes).
    let (depth, normal) = (raster::view(&prepass.depth), raster::view(&prepass.normal));
    session.set_layer_textures(&FrameTextures {
        depth: &depth,
        depth_encoding: DepthEncoding::ReverseInfinite { near: raster::NEAR },
        normal: &normal,
        normal_encoding: NormalEncoding::Unorm,
    })?;
    for frame in 0..40 {
        if frame == 20 {
            // The light moved: the render diffs the scene and restarts the passes.
            let change = session.update(&scene(-1.0))?;
            println!("frame {frame}: the light moved ({change:?})");
        }
        let t = Instant::now();
        let pass = session.next_pass(&mut NoProgress)?; // one pass, submitted, not waited for
        session.copy_to_texture(&texture)?; // the irradiance, into the engine's texture, on the device
        let submit = t.elapsed();
        // ... the engine records and submits its own frame here: its lighting
        // adds `texture` × albedo / π to its surfaces, before its tone mapping ...
        device.poll(wgpu::PollType::wait_indefinitely())?; // (only to time the GPU in this example)
        // A recent frame's GPU time per stage (read back without waiting).
        let gpu = session.stage_times().map_or(String::new(), |t| format!("; GPU: {t}"));
        println!(
            "frame {frame}: pass {pass} ({} photons), submitted in {:.2} ms, done in {:.2} ms{gpu}",
            session.scene().scene.render.photons,
            submit.as_secs_f64() * 1e3,
            t.elapsed().as_secs_f64() * 1e3
        );
    }
    let layer = session.image()?;
    let brightest = layer.pixels.iter().map(|p| p.max_element()).fold(0.0f32, f32::max);
    println!("the layer after {} passes: caustic irradiance up to {brightest:.3}", session.passes()[0].1);
    Ok(())
}
