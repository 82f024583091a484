//! How steady a caustic layer is from frame to frame
//! (`GpuSession::layer_frame`), by the length of its history: a glass
//! sphere's caustic on an engine's floor (its prepass drawn by
//! engine_loop's raster), one pass of photons a frame.
//!
//! - **Flicker** of a still caustic: the frame-to-frame standard deviation
//!   of each caustic pixel over frames 48–63, over its mean (the median over
//!   the pixels above 20 % of the brightest), for history caps of 1 (no
//!   history: each frame its own pass), 16 and 256 frames.
//! - **Lag** under a light moving at a known speed along x: the caustic's
//!   centroid (pixels above 30 % of the frame's brightest) against its
//!   closed-form position (where the line from the light through the
//!   sphere's centre meets the floor, projected), along the motion, in
//!   frames; and the centroid's frame-to-frame jitter across the motion,
//!   for caps of 1, 2, 4 and 8 frames (the cap an engine uses while things move).
//!
//! `cargo run --release -p prismatic-gpu --example layer_stability -- [PHOTONS]`

#[path = "engine_loop/ball.rs"]
mod ball;
#[path = "engine_loop/raster.rs"]
mod raster;

use prismatic_core::geometry::camera::PinholeCamera;
use prismatic_core::model::scene::RenderSettings;
use prismatic_core::{PreparedScene, Render, Vec3};
use prismatic_gpu::{AdapterChoice, DepthEncoding, FrameTextures, GpuContext, GpuOptions, GpuSession, NormalEncoding};

const SIZE: (u32, u32) = (320, 180);
/// How far the light moves along x a frame.
const SPEED: f32 = 0.02;

/// The light's position at `x`.
fn light_at(x: f32) -> Vec3 {
    Vec3::new(x, 6.0, -0.5)
}

/// The ball's scene with the light at `light`, `photons` a pass.
fn scene(light: Vec3, photons: u32) -> PreparedScene {
    let render = RenderSettings { width: SIZE.0, height: SIZE.1, photons, ..RenderSettings::default() };
    ball::scene(render, ball::spot(light, 20.0), true)
}

/// The image the session shows (its history), as luminance per pixel.
fn shown(session: &GpuSession) -> Vec<f32> {
    let ctx = session.context();
    let bytes = ctx.read(session.pixels(), 0, session.pixels().size()).expect("read");
    bytemuck::pod_collect_to_vec::<u8, [f32; 4]>(&bytes).iter().map(|p| p[0] + p[1] + p[2]).collect()
}

/// The centroid of the pixels above `fraction` of the brightest.
fn centroid(lum: &[f32], fraction: f32) -> (f32, f32) {
    let cut = lum.iter().copied().fold(0.0f32, f32::max) * fraction;
    let (mut x, mut y, mut n) = (0.0, 0.0, 0.0);
    for (i, &l) in lum.iter().enumerate() {
        if l >= cut && l > 0.0 {
            (x, y, n) = (x + (i as u32 % SIZE.0) as f32 + 0.5, y + (i as u32 / SIZE.0) as f32 + 0.5, n + 1.0);
        }
    }
    (x / n, y / n)
}

/// The caustic's closed-form centre for a light at `light`: the floor point
/// on the line from the light through the sphere's centre, in pixels.
fn closed_form(light: Vec3) -> (f32, f32) {
    let t = light.y / (light.y - ball::CENTRE.y);
    let p = light + (ball::CENTRE - light) * t;
    // PinholeCamera::project, without rounding to a pixel.
    let c = PinholeCamera::new(&ball::camera(), SIZE.0, SIZE.1);
    let v = p - c.origin;
    let q = v / v.dot(c.forward) - c.corner;
    (q.dot(c.right) / c.right.length_squared(), q.dot(c.down) / c.down.length_squared())
}

fn main() {
    let photons = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(50_000);
    let ctx = GpuContext::new(AdapterChoice::Any).expect("an adapter");
    let info = ctx.adapter.as_ref().map(prismatic_gpu::describe).unwrap_or_default();
    println!("adapter: {info}; {}x{}, {photons} photons a frame", SIZE.0, SIZE.1);
    let (prepass, commands) = raster::prepass(&ctx.device, &ball::camera(), SIZE, &raster::floor());
    ctx.queue.submit([commands]);
    let (depth, normal) = (raster::view(&prepass.depth), raster::view(&prepass.normal));
    let textures = FrameTextures {
        depth: &depth,
        depth_encoding: DepthEncoding::ReverseInfinite { near: raster::NEAR },
        normal: &normal,
        normal_encoding: NormalEncoding::Unorm,
    };
    let new_session =
        |light| GpuSession::new(ctx.clone(), &scene(light, photons), GpuOptions::default()).expect("session");

    println!("\n| history (frames) | flicker of a still caustic (median frame-to-frame std / mean) |");
    println!("|---:|---:|");
    for cap in [1, 16, 256] {
        let mut session = new_session(light_at(-2.5));
        let frames: Vec<Vec<f32>> = (0..64)
            .map(|frame| {
                session.layer_frame(&textures, frame, cap).expect("frame");
                shown(&session)
            })
            .collect();
        let window = &frames[48..];
        let last = &frames[63];
        let brightest = last.iter().copied().fold(0.0f32, f32::max);
        let mut ratios: Vec<f32> = (0..last.len())
            .filter(|&i| last[i] > 0.2 * brightest)
            .map(|i| {
                let n = window.len() as f32;
                let mean = window.iter().map(|f| f[i]).sum::<f32>() / n;
                let var = window.iter().map(|f| (f[i] - mean).powi(2)).sum::<f32>() / (n - 1.0);
                var.sqrt() / mean
            })
            .collect();
        ratios.sort_by(f32::total_cmp);
        println!("| {cap} | {:.4} |", ratios[ratios.len() / 2]);
    }

    println!(
        "\n| history while moving (frames) | centroid − closed form along the motion (px) | lag (frames) | jitter across the motion (px, frame to frame) |"
    );
    println!("|---:|---:|---:|---:|");
    let (x0, frames) = (-2.5, 48u32);
    let motion = {
        let (a, b) = (closed_form(light_at(x0)), closed_form(light_at(x0 + SPEED)));
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let speed = (dx * dx + dy * dy).sqrt();
        (dx / speed, dy / speed, speed)
    };
    let mut bias = None;
    for cap in [1, 2, 4, 8] {
        let mut session = new_session(light_at(x0));
        let (mut along, mut across) = (Vec::new(), Vec::new());
        for frame in 0..frames {
            let light = light_at(x0 + SPEED * frame as f32);
            session.update(&scene(light, photons)).expect("update");
            session.layer_frame(&textures, frame, cap).expect("frame");
            if frame >= 16 {
                let (c, p) = (centroid(&shown(&session), 0.3), closed_form(light));
                let (dx, dy) = (c.0 - p.0, c.1 - p.1);
                along.push(dx * motion.0 + dy * motion.1);
                across.push(-dx * motion.1 + dy * motion.0);
            }
        }
        let mean_along = along.iter().sum::<f32>() / along.len() as f32;
        let base = *bias.get_or_insert(mean_along);
        let jitter = (across.windows(2).map(|w| (w[1] - w[0]).powi(2)).sum::<f32>() / (across.len() - 1) as f32).sqrt();
        println!("| {cap} | {mean_along:.2} | {:.2} | {jitter:.3} |", (base - mean_along) / motion.2);
    }
    println!("\n(the light moves {SPEED} units a frame: its caustic {:.2} px a frame)", motion.2);
}
