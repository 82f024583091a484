//! A light's range (glTF's `KHR_lights_punctual` `range`) against its
//! closed forms, on every backend: a point light's direct light on a floor
//! is the inverse square law times the window w(d) = 1 − (d/R)⁴ out to R
//! and nothing beyond; its photons reach the floor with the window's share
//! of its flux; and the backends agree on a glass ball's caustic under a
//! spot whose range ends just past the ball.

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::scene::{Camera, Light, Material, MaterialKind, Object, Shape};
use prismatic_core::{Glass, PreparedScene, Scene, Vec3};
use prismatic_tests::backends::{assert_floor_from_above, every_backend, pixel_cosines, trace};
use prismatic_tests::parity::{Output, assert_parity};
use prismatic_tests::{glass, prepare, settings, white};
use std::f32::consts::PI;

/// The floor's albedo (`white`'s).
const ALBEDO: f32 = 0.8;
/// The light's height over the floor.
const HEIGHT: f32 = 1.0;
/// Its range: twice its height.
const RANGE: f32 = 2.0;
/// Its power.
const POWER: f32 = 30.0;
/// The image's side.
const SIDE: u32 = 41;

fn floor() -> Object {
    Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 }
}

fn point_light() -> Light {
    Light::Point {
        position: Vec3::new(0.0, HEIGHT, 0.0),
        power: POWER,
        spectrum: Default::default(),
        range: Some(RANGE),
    }
}

#[test]
fn a_ranged_point_light_lights_the_floor_as_its_window_says() {
    // Seen from the light itself, looking down: each pixel's ray meets the
    // floor at cos θ = c, distance h/c.
    let camera = Camera { position: Vec3::new(0.0, HEIGHT, 0.0), look_at: Vec3::ZERO, up: Vec3::Z, fov_deg: 130.0 };
    let mut render = settings(1000, BandSpec::Paper7);
    (render.width, render.height, render.ambient) = (SIDE, SIDE, 0.0);
    let scene = prepare(Scene {
        render,
        camera: camera.clone(),
        lights: vec![point_light()],
        materials: vec![white("floor")],
        objects: vec![floor()],
    });
    let intensity = POWER / (4.0 * PI);
    let window = |c: f32| (1.0 - (HEIGHT / c / RANGE).powi(4)).max(0.0);
    let want = |c: f32| ALBEDO / PI * intensity * c * c * c / (HEIGHT * HEIGHT) * window(c);
    assert_floor_from_above(&scene, &camera, SIDE, want, 1e-4 * intensity / (HEIGHT * HEIGHT));
    let cosines = pixel_cosines(&camera, SIDE);
    let windowed = cosines.iter().filter(|&&c| window(c) > 0.0 && window(c) < 0.9).count();
    let beyond = cosines.iter().filter(|&&c| HEIGHT / c > RANGE).count();
    assert!(windowed > 30 && beyond > 30, "the image holds the window ({windowed}) and beyond it ({beyond})");
}

#[test]
fn a_ranged_lights_photons_reach_the_floor_with_the_windows_share() {
    // The photons that go down meet the floor first: Φ/(4π) ∫ w(h/μ) 2π dμ
    // over the lower hemisphere, Φ/2 · (1 − 4a/3 + a⁴/3) with a = h/R. A
    // small mirror above the light, within its range, makes the plan trace
    // photons (no projection maps, so they leave in every direction); what
    // it reflects lands on the floor as a caustic, not first.
    let mut render = settings(40_000, BandSpec::Paper7);
    (render.width, render.height, render.projection_maps) = (8, 8, false);
    let mirror = Material::new("mirror", MaterialKind::Mirror);
    let scene = prepare(Scene {
        render,
        camera: prismatic_tests::camera(),
        lights: vec![point_light()],
        materials: vec![white("floor"), mirror],
        objects: vec![
            floor(),
            Object {
                shape: Shape::Disk {
                    center: Vec3::new(0.0, 2.5, 0.0),
                    normal: Vec3::NEG_Y,
                    radius: 0.5,
                    inner_radius: 0.0,
                },
                material: 1,
            },
        ],
    });
    let a = HEIGHT / RANGE;
    let want = 0.5 * (1.0 - 4.0 * a / 3.0 + a.powi(4) / 3.0);
    for mut backend in every_backend() {
        let name = backend.name();
        let stats = trace(backend.as_mut(), &scene).stats;
        let share = stats.flux_direct / stats.flux_emitted;
        assert!((share - f64::from(want)).abs() < 2e-3, "{name}: {share} of the flux lit the floor first, not {want}");
        assert!(stats.stored > 0, "{name}: the mirror within range casts a caustic");
        // What the window takes leaves as if it escaped.
        let ledger =
            stats.flux_direct + stats.flux_escaped + stats.flux_stored + stats.flux_absorbed + stats.flux_depth_limited;
        assert!((ledger / stats.flux_emitted - 1.0).abs() < 1e-4, "{name}: {ledger} of {}", stats.flux_emitted);
    }
}

#[test]
fn a_glass_beyond_the_range_is_left_out_of_the_plan() {
    // Nothing of it is nearer than the range: no caustic is traced, and the
    // plan says why.
    let glass_at = |z: f32| {
        let mut render = settings(1000, BandSpec::Paper7);
        (render.width, render.height) = (8, 8);
        prepare(Scene {
            render,
            camera: prismatic_tests::camera(),
            lights: vec![point_light()],
            materials: vec![white("floor"), glass("glass", Glass::Sf11.dispersion())],
            objects: vec![
                floor(),
                Object { shape: Shape::Sphere { center: Vec3::new(0.0, HEIGHT, z), radius: 0.5 }, material: 1 },
            ],
        })
    };
    let beyond = glass_at(RANGE + 0.6);
    assert!(!beyond.plan.caustics.on && beyond.plan.caustics.reason.contains("range"), "{:?}", beyond.plan.caustics);
    let within = glass_at(RANGE + 0.4);
    assert!(within.plan.caustics.on, "{:?}", within.plan.caustics);
}

#[test]
fn the_backends_agree_on_a_glass_ball_under_a_spot_whose_range_ends_past_it() {
    // The spot is 4.2 from the ball's centre and reaches 5: the window
    // thins the light the ball gets and what it refracts.
    let mut render = settings(6_000, BandSpec::Physical(16));
    (render.width, render.height, render.ambient) = (32, 24, 0.0);
    let scene: PreparedScene = prepare(Scene {
        render,
        camera: Camera {
            position: Vec3::new(0.0, 1.5, 4.0),
            look_at: Vec3::new(0.0, 0.5, 0.0),
            up: Vec3::Y,
            fov_deg: 45.0,
        },
        lights: vec![Light::Spot {
            position: Vec3::new(1.0, 4.8, 0.5),
            direction: Vec3::new(-1.0, -4.0, -0.5),
            cone_deg: 25.0,
            inner_cone_deg: 20.0,
            power: 40.0,
            spectrum: Default::default(),
            range: Some(5.0),
        }],
        materials: vec![white("floor"), glass("glass", Glass::Sf11.dispersion())],
        objects: vec![
            floor(),
            Object { shape: Shape::Sphere { center: Vec3::new(0.0, 0.7, 0.0), radius: 0.6 }, material: 1 },
        ],
    });
    let mut outputs = every_backend().into_iter().map(|mut b| Output::frame(b.as_mut(), &scene));
    let reference = outputs.next().expect("the reference backend");
    let stats = &reference.map.stats;
    assert!(stats.flux_stored > 0.0 && stats.flux_escaped > 0.05 * stats.flux_emitted, "{stats:?}");
    for got in outputs {
        assert_parity("ranged spot over glass", &scene, &reference, &got);
    }
}
