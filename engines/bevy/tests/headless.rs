//! The plugin in a headless Bevy app (no window; lavapipe in CI, where a
//! missing adapter fails): after some frames the caustic image, read back
//! from Bevy's own texture, holds the sphere's caustic, and moving the
//! light entity moves it.

use bevy::app::SubApps;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::gpu_readback::{Readback, ReadbackComplete};
use bevy::render::renderer::RenderDevice;
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use prismatic_bevy::prismatic_core::Vec3 as CoreVec3;
use prismatic_bevy::prismatic_core::model::dispersion::Dispersion;
use prismatic_bevy::prismatic_core::model::scene::Shape;
use prismatic_bevy::{
    CausticCamera, CausticImage, CausticLight, CausticSettings, CausticShape, CausticStats, Glass, PrismaticPlugin,
    Receiver,
};
use std::sync::{Arc, Mutex};

const WIDTH: u32 = 160;
const HEIGHT: u32 = 120;

/// The built-in sphere scene as entities: glass ball on a floor, spot light.
fn spawn_scene(mut commands: Commands) {
    commands.spawn((
        CausticCamera { fov_deg: 42.0 },
        Transform::from_xyz(4.2, 2.6, 3.4).looking_at(Vec3::new(0.4, 0.3, 0.0), Vec3::Y),
    ));
    commands.spawn((
        CausticLight::Spot { cone_deg: 40.0, power: 38.0 },
        Transform::from_xyz(-2.5, 6.0, -0.5).looking_to(Vec3::new(2.5, -5.0, 0.5), Vec3::Y),
    ));
    commands.spawn((
        CausticShape(Shape::Plane { point: CoreVec3::ZERO, normal: CoreVec3::Y }),
        Receiver { albedo: CoreVec3::splat(0.85), checker: None },
        Transform::IDENTITY,
    ));
    commands.spawn((
        CausticShape(Shape::Sphere { center: CoreVec3::ZERO, radius: 1.0 }),
        Glass { dispersion: Dispersion::Paper },
        Transform::from_xyz(0.0, 1.0, 0.0),
    ));
}

fn app() -> Option<SubApps> {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin { primary_window: None, exit_condition: ExitCondition::DontExit, ..default() })
            .set(RenderPlugin { synchronous_pipeline_compilation: true, ..default() })
            .disable::<WinitPlugin>(),
    )
    .add_plugins(PrismaticPlugin)
    .insert_resource(CausticSettings(prismatic_bevy::prismatic_core::model::scene::RenderSettings {
        width: WIDTH,
        height: HEIGHT,
        photons: 20_000,
        ..CausticSettings::default().0
    }))
    .add_systems(Startup, spawn_scene);
    app.finish();
    app.cleanup();
    if app.world().get_resource::<RenderDevice>().is_none() {
        assert!(std::env::var_os("CI").is_none(), "CI=true and Bevy found no GPU adapter");
        eprintln!("SKIPPING: Bevy found no GPU adapter on this machine");
        return None;
    }
    Some(std::mem::take(app.sub_apps_mut()))
}

/// Runs one frame and waits for the device.
fn update(apps: &mut SubApps) {
    apps.update();
    let device = apps.main.world().resource::<RenderDevice>().wgpu_device().clone();
    device.poll(wgpu::PollType::wait_indefinitely()).expect("device");
}

/// Reads the caustic image back through Bevy's readback: linear RGB luminance per pixel.
fn read_image(apps: &mut SubApps) -> Vec<f32> {
    let handle = apps.main.world().resource::<CausticImage>().0.clone();
    let data = Arc::new(Mutex::new(None));
    let sink = Arc::clone(&data);
    // `ReadbackOnce` is for systems (it is dropped at the start of the next
    // update); from outside, a `Readback` despawned once it has answered.
    let reader = apps
        .main
        .world_mut()
        .spawn(Readback::texture(handle))
        .observe(move |event: On<ReadbackComplete>| {
            *sink.lock().unwrap() = Some(event.data.clone());
        })
        .id();
    for _ in 0..20 {
        update(apps);
        if let Some(bytes) = data.lock().unwrap().take() {
            apps.main.world_mut().despawn(reader);
            let texels: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
            assert_eq!(texels.len(), (WIDTH * HEIGHT) as usize, "rows are not padded at this width");
            return texels.iter().map(|t| 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]).collect();
        }
    }
    panic!("the readback never completed");
}

/// The centroid (x, y) of the brightest 0.5 % of pixels, and how much
/// brighter the brightest 0.1 % are than the median.
fn caustic(lum: &[f32]) -> ((f32, f32), f32) {
    let mut sorted = lum.to_vec();
    sorted.sort_by(f32::total_cmp);
    let at = |q: f64| sorted[((sorted.len() - 1) as f64 * q) as usize];
    let (cut, peak, median) = (at(0.995), at(0.999), at(0.5));
    let bright: Vec<usize> = (0..lum.len()).filter(|&i| lum[i] >= cut).collect();
    let n = bright.len() as f32;
    let x = bright.iter().map(|&i| (i as u32 % WIDTH) as f32).sum::<f32>() / n;
    let y = bright.iter().map(|&i| (i as u32 / WIDTH) as f32).sum::<f32>() / n;
    ((x, y), peak / median.max(1e-6))
}

#[test]
fn the_caustic_is_there_and_follows_the_light_entity() {
    let Some(mut apps) = app() else { return };
    for _ in 0..6 {
        update(&mut apps);
    }
    let stats = apps.main.world().resource::<CausticStats>().get();
    assert_eq!(stats.error, None);
    assert!(stats.passes >= 3, "passes accumulate while nothing changes: {stats:?}");
    // Bevy asks for every feature the adapter has; lavapipe has timestamps.
    let device = apps.main.world().resource::<RenderDevice>().wgpu_device().clone();
    if device.features().contains(prismatic_gpu::timestamp_features()) {
        let gpu = stats.gpu.unwrap_or_else(|| panic!("no GPU stage times after 6 waited frames: {stats:?}"));
        assert!(gpu.gather > std::time::Duration::ZERO, "{gpu:?}");
    } else {
        assert!(std::env::var_os("CI").is_none(), "CI=true and Bevy's device has no timestamp queries");
    }
    let before = read_image(&mut apps);
    assert!(before.iter().all(|l| l.is_finite()), "non-finite pixels");
    let (centre_before, contrast) = caustic(&before);
    assert!(contrast > 3.0, "no bright caustic: the brightest pixels are {contrast:.2}× the median");

    // Move the light 1.5 units along +z: the caustic on the floor moves away from it.
    let mut lights = apps.main.world_mut().query_filtered::<&mut Transform, With<CausticLight>>();
    for mut t in lights.iter_mut(apps.main.world_mut()) {
        t.translation.z += 1.5;
    }
    for _ in 0..4 {
        update(&mut apps);
    }
    let moved = apps.main.world().resource::<CausticStats>().get();
    assert!(moved.generation > stats.generation, "the light move reached the session: {moved:?}");
    let after = read_image(&mut apps);
    let (centre_after, contrast_after) = caustic(&after);
    assert!(contrast_after > 3.0, "no bright caustic after the move: {contrast_after:.2}×");
    let shift = ((centre_after.0 - centre_before.0).powi(2) + (centre_after.1 - centre_before.1).powi(2)).sqrt();
    eprintln!("caustic {centre_before:?} ({contrast:.1}x) -> {centre_after:?} ({contrast_after:.1}x), {shift:.1} px");
    assert!(shift > 4.0, "the caustic stayed at {centre_before:?} → {centre_after:?} ({shift:.1} px)");
}
