//! The caustic layer from an engine's depth and normal textures (its
//! prepass, drawn by the engine_loop example's raster as Bevy draws one)
//! is the layer of the same frame handed over from the host; the engine's
//! occluder, which prismatic's scene does not hold, hides the caustic.

#[path = "../examples/engine_loop/ball.rs"]
mod ball;
#[path = "../examples/engine_loop/raster.rs"]
mod raster;

use prismatic_core::geometry::camera::PinholeCamera;
use prismatic_core::model::scene::{Camera, RenderSettings, ViewPaths};
use prismatic_core::{Image, LayerFrame, NoProgress, PreparedScene, Render, Vec3};
use prismatic_gpu::{DepthEncoding, FrameTextures, GpuOptions, GpuSession, NormalEncoding, test_context};

const SIZE: (u32, u32) = (160, 120);

/// The ball's scene, light traced through pixel centres; without the
/// ball, the frame an engine's prepass draws.
fn scene(with_ball: bool) -> PreparedScene {
    let render = RenderSettings {
        width: SIZE.0,
        height: SIZE.1,
        photons: 20_000,
        view_paths: ViewPaths::Centre,
        ..RenderSettings::default()
    };
    ball::scene(render, ball::spot(Vec3::new(-2.5, 6.0, -0.5), 40.0), with_ball)
}

/// The engine's frame from the host: the floor, and the occluder over the left half at depth 1.
fn host_frame() -> LayerFrame {
    let mut frame = LayerFrame::seen_by_camera(&scene(false));
    let forward = (ball::camera().look_at - ball::camera().position).normalize();
    for (i, (depth, normal)) in frame.depth.iter_mut().zip(&mut frame.normal).enumerate() {
        if (i as u32 % SIZE.0) < SIZE.0 / 2 {
            (*depth, *normal) = (1.0, -forward);
        }
    }
    frame
}

/// A quad 1 unit in front of `camera` over the left half of its view
/// (an engine's object that prismatic's scene does not hold).
fn occluder_over_the_left_half(camera: &Camera, width: u32, height: u32) -> [[Vec3; 3]; 2] {
    let pinhole = PinholeCamera::new(camera, width, height);
    let at = |u: f32, v: f32| {
        pinhole.origin + pinhole.corner + pinhole.right * (u * width as f32) + pinhole.down * (v * height as f32)
    };
    let (l, m) = (-0.1, 0.5);
    raster::quad(at(l, -0.1), at(l, 1.1), at(m, 1.1), at(m, -0.1))
}

/// Two passes of the layer, its frame set by `set`.
fn layer(session: &mut GpuSession, set: impl FnOnce(&mut GpuSession)) -> Image {
    set(session);
    for k in 0..2 {
        session.run_pass(k, &mut NoProgress).expect("pass");
    }
    session.image().expect("image")
}

/// The engine's triangles: a floor, and the occluder over the left half.
fn engine_triangles() -> Vec<[Vec3; 3]> {
    [raster::floor(), occluder_over_the_left_half(&ball::camera(), SIZE.0, SIZE.1)].concat()
}

/// The prepass's textures as the layer reads them.
fn textures<'a>(depth: &'a wgpu::TextureView, normal: &'a wgpu::TextureView) -> FrameTextures<'a> {
    FrameTextures {
        depth,
        depth_encoding: DepthEncoding::ReverseInfinite { near: raster::NEAR },
        normal,
        normal_encoding: NormalEncoding::Unorm,
    }
}

#[test]
fn a_layer_from_the_engines_textures_is_the_layer_of_its_frame() {
    let Some(ctx) = test_context("the layer from an engine's textures") else { return };
    let (prepass, commands) = raster::prepass(&ctx.device, &ball::camera(), SIZE, &engine_triangles());
    ctx.queue.submit([commands]);
    let (depth, normal) = (raster::view(&prepass.depth), raster::view(&prepass.normal));
    let mut session = GpuSession::new(ctx, &scene(true), GpuOptions::default()).expect("session");
    let from_textures =
        layer(&mut session, |s| s.set_layer_textures(&textures(&depth, &normal)).expect("the textures fit"));
    let from_host = layer(&mut session, |s| s.set_layer(Some(&host_frame())).expect("the frame fits"));
    let left = |i: usize| (i as u32 % SIZE.0) < SIZE.0 / 2;
    let total = |img: &Image, half: bool| -> f64 {
        img.pixels.iter().enumerate().filter(|(i, _)| left(*i) == half).map(|(_, p)| f64::from(p.element_sum())).sum()
    };
    assert_eq!(total(&from_textures, true), 0.0, "the engine's occluder hides the caustic");
    let (want, got) = (total(&from_host, false), total(&from_textures, false));
    assert!(want > 0.0, "the caustic reaches the right half");
    // The prepass stores normals in 10 bits a channel, off by up to 1.7e-3
    // rad: a photon's irradiance (∝ cos θ) by 1.7e-3 · tan θ, 1 % where the
    // camera grazes the far floor.
    assert!((got / want - 1.0).abs() < 3e-3, "the right half's caustic: {got} from textures, {want} from the host");
    let brightest = from_host.pixels.iter().map(|p| p.max_element()).fold(0.0f32, f32::max);
    for (i, (a, b)) in from_host.pixels.iter().zip(&from_textures.pixels).enumerate() {
        let allowed = 1.5e-2 * a.max_element() + 1e-2 * brightest;
        assert!((*a - *b).abs().max_element() <= allowed, "pixel {i}: {a} from the host, {b} from textures");
    }
}

#[test]
fn a_recorded_frame_submitted_with_the_engines_is_the_submitted_frame() {
    // The engine's frame as Bevy submits one: its prepass, the layer's
    // frame and passes, then the rest, in one submission at the end.
    let Some(ctx) = test_context("a recorded layer") else { return };
    let (prepass, prepass_commands) = raster::prepass(&ctx.device, &ball::camera(), SIZE, &engine_triangles());
    let (depth, normal) = (raster::view(&prepass.depth), raster::view(&prepass.normal));
    let queue = ctx.queue.clone();
    let mut recorded = GpuSession::new(ctx.clone(), &scene(true), GpuOptions::default()).expect("session");
    let (done, layer_commands) = recorded.record(|s| {
        s.set_layer_textures(&textures(&depth, &normal))?;
        (0..2).try_for_each(|k| s.run_pass(k, &mut NoProgress))
    });
    done.expect("recorded");
    assert!(!layer_commands.is_empty(), "the layer recorded its work");
    queue.submit(std::iter::once(prepass_commands).chain(layer_commands));
    let mut submitted = GpuSession::new(ctx, &scene(true), GpuOptions::default()).expect("session");
    let direct = layer(&mut submitted, |s| s.set_layer_textures(&textures(&depth, &normal)).expect("fits"));
    let image = recorded.image().expect("image");
    assert!(image.pixels.iter().any(|p| p.max_element() > 0.0), "the recorded layer has the caustic");
    assert_eq!(image, direct, "the recorded frame differs from the submitted one");
}

#[test]
fn the_history_is_the_mean_of_its_frames_and_starts_again_where_the_surface_changed() {
    // Four frames behind the occluder, then one without it: where the
    // occluder stood the history starts again (this frame's pass alone);
    // elsewhere it is the mean of the five passes, as the protocol's
    // progressive image of those passes is.
    let Some(ctx) = test_context("a layer's history") else { return };
    let (occluded, first) = raster::prepass(&ctx.device, &ball::camera(), SIZE, &engine_triangles());
    let (open, second) = raster::prepass(&ctx.device, &ball::camera(), SIZE, &raster::floor());
    ctx.queue.submit([first, second]);
    let views = |p: &raster::Prepass| (raster::view(&p.depth), raster::view(&p.normal));
    let ((od, on), (fd, fnormal)) = (views(&occluded), views(&open));
    let mut session = GpuSession::new(ctx.clone(), &scene(true), GpuOptions::default()).expect("session");
    for frame in 0..4 {
        session.layer_frame(&textures(&od, &on), frame, 256).expect("frame");
    }
    session.layer_frame(&textures(&fd, &fnormal), 4, 256).expect("frame");
    let shown = shown_image(&session);
    let image_of = |passes: std::ops::Range<u32>| {
        let mut s = GpuSession::new(ctx.clone(), &scene(true), GpuOptions::default()).expect("session");
        s.set_layer_textures(&textures(&fd, &fnormal)).expect("fits");
        for k in passes {
            s.run_pass(k, &mut NoProgress).expect("pass");
        }
        s.image().expect("image")
    };
    let (alone, mean) = (image_of(4..5), image_of(0..5));
    let left = |i: usize| (i as u32 % SIZE.0) < SIZE.0 / 2;
    let brightest = mean.pixels.iter().map(|p| p.max_element()).fold(0.0f32, f32::max);
    let (mut restarted, mut kept) = (0, 0);
    for (i, got) in shown.iter().enumerate() {
        let want = if left(i) { alone.pixels[i] } else { mean.pixels[i] };
        let off = (*got - want).abs().max_element();
        assert!(off <= 1e-4 * brightest + 1e-3 * want.max_element(), "pixel {i}: {got} shown, {want} expected");
        if want.max_element() > 0.0 {
            *(if left(i) { &mut restarted } else { &mut kept }) += 1;
        }
    }
    assert!(restarted > 0 && kept > 0, "{restarted} lit pixels started again, {kept} kept their history");
}

/// What the session shows (its device image, which `copy_to_texture` copies).
fn shown_image(session: &GpuSession) -> Vec<Vec3> {
    let ctx = session.context();
    let bytes = ctx.read(session.pixels(), 0, session.pixels().size()).expect("read");
    bytemuck::pod_collect_to_vec::<u8, [f32; 4]>(&bytes).iter().map(|p| Vec3::new(p[0], p[1], p[2])).collect()
}
