//! The plugin in a headless Bevy app (no window; lavapipe in CI, where a
//! missing adapter fails). The whole image: after some frames the caustic
//! image, read back from Bevy's own texture, holds the sphere's caustic,
//! and moving the light entity moves it. The caustic layer: a Bevy camera's
//! frame with a `Glass` icosphere `Mesh3d` over a `CausticMaterial` floor
//! holds the caustic irradiance the reference draws in the same frame,
//! and Bevy's final frame shows it on the floor.

use bevy::app::SubApps;
use bevy::camera::RenderTarget;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::ecs::system::ScheduleSystem;
use bevy::light::GlobalAmbientLight;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::gpu_readback::{Readback, ReadbackComplete};
use bevy::render::render_resource::{TextureFormat, TextureUsages};
use bevy::render::renderer::RenderDevice;
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use prismatic_bevy::prismatic_core::Vec3 as CoreVec3;
use prismatic_bevy::prismatic_core::model::dispersion::Dispersion;
use prismatic_bevy::prismatic_core::model::scene::MaterialKind;
use prismatic_bevy::prismatic_core::model::scene::{RenderSettings, Shape};
use prismatic_bevy::prismatic_core::{Backend as _, LayerFrame, NoProgress, PreparedScene, ReferenceBackend};
use prismatic_bevy::{
    CausticCamera, CausticImage, CausticLayer, CausticLight, CausticMaterial, CausticReceiver, CausticScene,
    CausticSettings, CausticShape, CausticStats, Glass, PrismaticPlugin, Receiver,
};
use prismatic_core::model::metalness::Metalness;
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
        Glass { dispersion: Dispersion::Paper, film: None, roughness: 0.0 },
        Transform::from_xyz(0.0, 1.0, 0.0),
    ));
}

/// A headless app with the plugin, `settings` and `spawn`'s entities.
fn headless_app<M>(settings: RenderSettings, spawn: impl IntoScheduleConfigs<ScheduleSystem, M>) -> Option<SubApps> {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(WindowPlugin { primary_window: None, exit_condition: ExitCondition::DontExit, ..default() })
            .set(RenderPlugin { synchronous_pipeline_compilation: true, ..default() })
            .disable::<WinitPlugin>(),
    )
    .add_plugins(PrismaticPlugin)
    .insert_resource(CausticSettings(settings))
    .add_systems(Startup, spawn);
    app.finish();
    app.cleanup();
    if app.world().get_resource::<RenderDevice>().is_none() {
        assert!(std::env::var_os("CI").is_none(), "CI=true and Bevy found no GPU adapter");
        eprintln!("SKIPPING: Bevy found no GPU adapter on this machine");
        return None;
    }
    Some(std::mem::take(app.sub_apps_mut()))
}

fn app() -> Option<SubApps> {
    let settings = RenderSettings { width: WIDTH, height: HEIGHT, photons: 20_000, ..CausticSettings::default().0 };
    headless_app(settings, spawn_scene)
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
    let texels: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&read_texture(apps, handle));
    assert_eq!(texels.len(), (WIDTH * HEIGHT) as usize, "rows are not padded at this width");
    texels.iter().map(|t| 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]).collect()
}

/// An image's texels read back through Bevy's readback.
fn read_texture(apps: &mut SubApps, handle: Handle<Image>) -> Vec<u8> {
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
            return bytes;
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

/// The layer's scene in Bevy's terms: a `CausticLayer` camera drawing into
/// an image, a `CausticMaterial` floor, a `Glass` icosphere (hidden from
/// Bevy's own passes: the glass is transparent to its prepass) and the spot
/// light; no Bevy light but a dim ambient one, so the caustic stands out.
fn spawn_layer_scene(
    mut commands: Commands,
    mut images: ResMut<Assets<Image>>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<CausticMaterial>>,
) {
    let mut target = Image::new_target_texture(WIDTH, HEIGHT, TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let target = images.add(target);
    commands.insert_resource(FinalFrame(target.clone()));
    commands.insert_resource(GlobalAmbientLight { brightness: 20.0, ..GlobalAmbientLight::NONE });
    commands.spawn((
        Camera3d::default(),
        RenderTarget::Image(target.into()),
        Projection::Perspective(PerspectiveProjection { fov: 42f32.to_radians(), ..default() }),
        Tonemapping::Reinhard,
        Transform::from_xyz(4.2, 2.6, 3.4).looking_at(Vec3::new(0.4, 0.3, 0.0), Vec3::Y),
        CausticLayer::default(),
    ));
    commands.spawn((
        CausticLight::Spot { cone_deg: 40.0, power: 38.0 },
        Transform::from_xyz(-2.5, 6.0, -0.5).looking_to(Vec3::new(2.5, -5.0, 0.5), Vec3::Y),
    ));
    let floor = CausticMaterial {
        base: StandardMaterial {
            base_color: Color::linear_rgb(0.85, 0.85, 0.85),
            perceptual_roughness: 1.0,
            ..default()
        },
        extension: CausticReceiver::default(),
    };
    commands
        .spawn((Mesh3d(meshes.add(Plane3d::default().mesh().size(20.0, 20.0))), MeshMaterial3d(materials.add(floor))));
    commands.spawn((
        Mesh3d(meshes.add(Sphere::new(1.0).mesh().ico(3).expect("an icosphere"))),
        Glass { dispersion: Dispersion::Paper, film: None, roughness: 0.0 },
        Visibility::Hidden,
        Transform::from_xyz(0.0, 1.0, 0.0),
    ));
    // A metallic `CausticMaterial` (behind the camera, outside the spot):
    // mirrored as a metal of its colour and roughness.
    let brass = CausticMaterial {
        base: StandardMaterial {
            base_color: Color::linear_rgb(0.9, 0.7, 0.3),
            metallic: 1.0,
            perceptual_roughness: 0.3,
            ..default()
        },
        extension: CausticReceiver::default(),
    };
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(0.5, 0.5, 0.5).mesh())),
        MeshMaterial3d(materials.add(brass)),
        Transform::from_xyz(8.0, 0.5, 8.0),
    ));
}

/// The layer camera's target: Bevy's final frame.
#[derive(Resource)]
struct FinalFrame(Handle<Image>);

#[test]
fn the_layer_in_bevys_frame_is_the_references_and_lights_the_floor() {
    let settings = RenderSettings { photons: 50_000, ..CausticSettings::default().0 };
    let Some(mut apps) = headless_app(settings, spawn_layer_scene) else { return };
    for _ in 0..12 {
        update(&mut apps);
    }
    let stats = apps.main.world().resource::<CausticStats>().get();
    assert_eq!(stats.error, None);
    assert_eq!(stats.passes, 1, "a layer's frame is one pass, its history the mean: {stats:?}");
    // The layer, read back from Bevy's texture: irradiance per pixel.
    let handle = apps.main.world().resource::<CausticImage>().0.clone();
    let texels: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&read_texture(&mut apps, handle));
    let layer: Vec<f32> = texels.iter().map(|t| t[0] + t[1] + t[2]).collect();
    assert!(layer.iter().all(|e| e.is_finite() && *e >= 0.0), "a layer pixel is negative or not finite");
    // The reference's layer of the mirrored scene in the frame its camera
    // sees without the glass (what Bevy's prepass holds), four passes.
    let scene = apps.main.world().resource::<CausticScene>().scene.clone();
    let brass = MaterialKind::Metal {
        color: prismatic_core::MetalColor::Rgb(prismatic_core::Vec3::new(0.9, 0.7, 0.3)),
        roughness: 0.3,
        texture: None,
        film: None,
        metalness: Metalness::WHOLE,
    };
    assert!(scene.scene.materials.iter().any(|m| m.kind == brass), "the metallic receiver mirrored as a metal");
    let reference = {
        let mut frame_scene = scene.scene.clone();
        frame_scene
            .objects
            .retain(|o| !matches!(frame_scene.materials[o.material].kind, MaterialKind::Dielectric { .. }));
        let frame = LayerFrame::seen_by_camera(&PreparedScene::new(frame_scene).expect("valid"));
        let mut render = ReferenceBackend.prepare(&scene).expect("prepare");
        render.set_layer(Some(&frame)).expect("the frame fits");
        for k in 0..4 {
            render.run_pass(k, &mut NoProgress).expect("pass");
        }
        render.image().expect("image").pixels.iter().map(|p| p.element_sum()).collect::<Vec<f32>>()
    };
    let total = |v: &[f32]| v.iter().map(|&x| f64::from(x)).sum::<f64>();
    let (want, got) = (total(&reference), total(&layer));
    assert!(want > 0.0, "the reference's layer has the caustic");
    // Passes 0..4 against Bevy's 3 or more: the caustic's flux agrees
    // within its noise; Bevy's prepass normals carry 10 bits.
    assert!((got / want - 1.0).abs() < 0.03, "the layer's total irradiance: {got} in Bevy, {want} in the reference");
    let centroid = |v: &[f32]| {
        let cut = v.iter().copied().fold(0.0f32, f32::max) * 0.2;
        let bright: Vec<usize> = (0..v.len()).filter(|&i| v[i] >= cut).collect();
        let n = bright.len() as f32;
        let x = bright.iter().map(|&i| (i as u32 % WIDTH) as f32).sum::<f32>() / n;
        let y = bright.iter().map(|&i| (i as u32 / WIDTH) as f32).sum::<f32>() / n;
        (x, y)
    };
    let (a, b) = (centroid(&reference), centroid(&layer));
    assert!((a.0 - b.0).hypot(a.1 - b.1) < 1.5, "the caustic's centre: {b:?} in Bevy, {a:?} in the reference");
    // Bevy's final frame is brighter where the layer is bright (the floor's
    // own light is a dim ambient one).
    let frame = apps.main.world().resource::<FinalFrame>().0.clone();
    // Its rows come back padded to 256 bytes.
    let rgba = read_texture(&mut apps, frame);
    let row = rgba.len() / HEIGHT as usize;
    let luma: Vec<f32> = (0..(WIDTH * HEIGHT) as usize)
        .map(|i| &rgba[(i / WIDTH as usize) * row + (i % WIDTH as usize) * 4..][..3])
        .map(|p| f32::from(p[0]) + f32::from(p[1]) + f32::from(p[2]))
        .collect();
    let max = layer.iter().copied().fold(0.0f32, f32::max);
    let mean = |pick: &dyn Fn(f32) -> bool| {
        let v: Vec<f32> = layer.iter().zip(&luma).filter(|(e, _)| pick(**e)).map(|(_, l)| *l).collect();
        v.iter().sum::<f32>() / v.len().max(1) as f32
    };
    let (lit, dark) = (mean(&|e| e > 0.3 * max), mean(&|e| e > 0.0 && e < 0.01 * max));
    assert!(
        lit > 2.0 * dark + 10.0,
        "the final frame's caustic: {lit:.1} where the layer is bright, {dark:.1} beside it"
    );
}
