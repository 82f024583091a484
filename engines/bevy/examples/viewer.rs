//! An interactive caustic viewer: a glass sphere and a prism on a checkered
//! floor under a spot light, rendered live by prismatic on Bevy's device.
//!
//! Mouse drag: orbit the camera. Wheel: zoom. Arrow keys / PageUp /
//! PageDown: move the light. 3 / 7 / N: the paper's 3 or 7 bands, or 16
//! physically based bands. E: switch the estimator (paper / density).
//! The window title shows the frame time, photons per second, the GPU time
//! of the photon pass, grid and gather (where the adapter has timestamps)
//! and passes.
//!
//! `cargo run --release -p prismatic-bevy --example viewer [-- --size 960x540] [--photons 100000] [--screenshot FILE.png [FRAMES]]`
//! (with `--screenshot`, the window is saved after FRAMES frames, 60 by
//! default, and the viewer exits: the README's picture is taken so, under Xvfb).

use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::prelude::*;
use bevy::render::view::window::screenshot::{Screenshot, save_to_disk};
use bevy::window::PrimaryWindow;
use prismatic_bevy::prismatic_core::Vec3 as CoreVec3;
use prismatic_bevy::prismatic_core::model::bands::BandSpec;
use prismatic_bevy::prismatic_core::model::dispersion::Dispersion;
use prismatic_bevy::prismatic_core::model::scene::{Checker, Estimator, Shape};
use prismatic_bevy::{
    CausticCamera, CausticImage, CausticLight, CausticSettings, CausticShape, CausticStats, Glass, PrismaticPlugin,
    Receiver,
};

/// The orbiting camera's state: angles around the target and distance.
#[derive(Resource)]
struct Orbit {
    yaw: f32,
    pitch: f32,
    distance: f32,
}

const TARGET: Vec3 = Vec3::new(0.3, 0.5, 0.0);

/// The value after `flag` on the command line.
fn arg(flag: &str) -> Option<String> {
    let args: Vec<String> = std::env::args().collect();
    args.iter().position(|a| a == flag).and_then(|at| args.get(at + 1).cloned())
}

fn main() {
    let mut settings = CausticSettings::default();
    if let Some((w, h)) = arg("--size").and_then(|s| s.split_once('x').map(|(w, h)| (w.parse(), h.parse()))) {
        (settings.0.width, settings.0.height) = (w.expect("--size WxH"), h.expect("--size WxH"));
    }
    if let Some(n) = arg("--photons") {
        settings.0.photons = n.parse().expect("--photons N");
    }
    let resolution = (settings.0.width, settings.0.height);
    App::new()
        .add_plugins(DefaultPlugins.set(WindowPlugin {
            primary_window: Some(Window { title: "prismatic".into(), resolution: resolution.into(), ..default() }),
            ..default()
        }))
        .add_plugins(PrismaticPlugin)
        .insert_resource(settings)
        .insert_resource(Orbit { yaw: 0.9, pitch: 0.45, distance: 5.9 })
        .add_systems(Startup, setup)
        .add_systems(Update, (orbit_camera, move_light, switch_settings, show_image, show_stats, screenshot))
        .run();
}

/// With `--screenshot FILE [FRAMES]`: saves the window after FRAMES frames, then exits.
fn screenshot(mut commands: Commands, mut frame: Local<u32>, mut exit: MessageWriter<AppExit>) {
    let args: Vec<String> = std::env::args().collect();
    let Some(at) = args.iter().position(|a| a == "--screenshot") else { return };
    let Some(path) = args.get(at + 1) else { return };
    let frames: u32 = args.get(at + 2).and_then(|f| f.parse().ok()).unwrap_or(60);
    *frame += 1;
    if *frame == frames {
        commands.spawn(Screenshot::primary_window()).observe(save_to_disk(path.clone()));
    }
    if *frame == frames + 10 {
        exit.write(AppExit::Success);
    }
}

fn setup(mut commands: Commands) {
    commands.spawn(Camera2d);
    commands.spawn((CausticCamera { fov_deg: 42.0 }, Transform::default()));
    commands.spawn((
        CausticLight::Spot { cone_deg: 40.0, power: 38.0 },
        Transform::from_xyz(-2.5, 6.0, -0.5).looking_to(Vec3::new(2.5, -5.0, 0.5), Vec3::Y),
    ));
    commands.spawn((
        CausticShape(Shape::Plane { point: CoreVec3::ZERO, normal: CoreVec3::Y }),
        Receiver {
            albedo: CoreVec3::new(0.85, 0.85, 0.82),
            checker: Some(Checker { size: 0.5, albedo: CoreVec3::new(0.45, 0.47, 0.55), offset: CoreVec3::ZERO }),
        },
        Transform::IDENTITY,
    ));
    commands.spawn((
        CausticShape(Shape::Sphere { center: CoreVec3::ZERO, radius: 1.0 }),
        Glass { dispersion: Dispersion::Paper, film: None, roughness: 0.0 },
        Transform::from_xyz(0.0, 1.0, 0.0),
    ));
    // A 60° prism standing on the floor beside the sphere.
    let s = 0.6;
    commands.spawn((
        CausticShape(Shape::Prism {
            vertices: [CoreVec3::new(-s, 0.0, 0.0), CoreVec3::new(s, 0.0, 0.0), CoreVec3::new(0.0, 0.0, -s * 1.732)],
            extrude: CoreVec3::new(0.0, 1.2, 0.0),
        }),
        Glass { dispersion: Dispersion::Paper, film: None, roughness: 0.0 },
        Transform::from_xyz(1.6, 0.0, -1.4),
    ));
}

/// Shows the caustic image full-window (once it exists).
fn show_image(
    mut commands: Commands,
    image: Option<Res<CausticImage>>,
    window: Single<&Window, With<PrimaryWindow>>,
    mut sprites: Query<&mut Sprite>,
) {
    let Some(image) = image else { return };
    let size = Some(window.size());
    match sprites.single_mut() {
        Ok(mut sprite) => {
            if sprite.image != image.0 || sprite.custom_size != size {
                (sprite.image, sprite.custom_size) = (image.0.clone(), size);
            }
        }
        Err(_) => {
            commands.spawn(Sprite { image: image.0.clone(), custom_size: size, ..default() });
        }
    }
}

fn orbit_camera(
    mut orbit: ResMut<Orbit>,
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    mut camera: Single<&mut Transform, With<CausticCamera>>,
) {
    if buttons.pressed(MouseButton::Left) {
        orbit.yaw -= motion.delta.x * 0.005;
        orbit.pitch = (orbit.pitch + motion.delta.y * 0.005).clamp(0.05, 1.4);
    }
    orbit.distance = (orbit.distance * (1.0 - scroll.delta.y * 0.1)).clamp(2.5, 20.0);
    let (yaw, pitch) = (orbit.yaw, orbit.pitch);
    let eye = TARGET + orbit.distance * Vec3::new(pitch.cos() * yaw.cos(), pitch.sin(), pitch.cos() * yaw.sin());
    let wanted = Transform::from_translation(eye).looking_at(TARGET, Vec3::Y);
    if **camera != wanted {
        **camera = wanted;
    }
}

fn move_light(keys: Res<ButtonInput<KeyCode>>, time: Res<Time>, mut light: Single<&mut Transform, With<CausticLight>>) {
    let step = 2.0 * time.delta_secs();
    let mut d = Vec3::ZERO;
    for (key, dir) in [
        (KeyCode::ArrowLeft, Vec3::NEG_X),
        (KeyCode::ArrowRight, Vec3::X),
        (KeyCode::ArrowUp, Vec3::NEG_Z),
        (KeyCode::ArrowDown, Vec3::Z),
        (KeyCode::PageUp, Vec3::Y),
        (KeyCode::PageDown, Vec3::NEG_Y),
    ] {
        if keys.pressed(key) {
            d += dir * step;
        }
    }
    if d != Vec3::ZERO {
        light.translation += d;
        // Keep aiming at the sphere's centre.
        light.look_at(Vec3::new(0.0, 1.0, 0.0), Vec3::Y);
    }
}

fn switch_settings(keys: Res<ButtonInput<KeyCode>>, mut settings: ResMut<CausticSettings>) {
    let r = &mut settings.0;
    if keys.just_pressed(KeyCode::Digit3) {
        r.bands = BandSpec::Paper3;
    }
    if keys.just_pressed(KeyCode::Digit7) {
        r.bands = BandSpec::Paper7;
    }
    if keys.just_pressed(KeyCode::KeyN) {
        r.bands = BandSpec::Physical(16);
    }
    if keys.just_pressed(KeyCode::KeyE) {
        r.estimator = match r.estimator {
            Estimator::Paper => Estimator::Density,
            Estimator::Density => Estimator::Paper,
        };
    }
}

fn show_stats(stats: Res<CausticStats>, settings: Res<CausticSettings>, mut window: Single<&mut Window>) {
    let s = stats.get();
    let r = &settings.0;
    let gpu = s.gpu.map_or(String::new(), |t| format!(" | GPU {t}"));
    let title = match &s.error {
        Some(e) => format!("prismatic: {e}"),
        None => format!(
            "prismatic | {:.1} ms/frame | {:.1} M photons/s{gpu} | pass {} | {} bands, {:?} | {}x{}",
            s.frame_seconds * 1e3,
            s.photons as f64 / s.frame_seconds.max(1e-9) / 1e6,
            s.passes,
            r.bands,
            r.estimator,
            r.width,
            r.height
        ),
    };
    if window.title != title {
        window.title = title;
    }
}
