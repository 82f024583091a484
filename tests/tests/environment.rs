//! Environment light against its closed forms, on every backend: a constant
//! sky of radiance L gives a floor πL of irradiance (the median cut's suns
//! send it exactly what the sky does, since the first cut is the horizon);
//! rays that leave the scene see the map, through glass too; its suns send
//! caustic photons through the glass, and the backends agree on all of it.

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::environment::EnvironmentMap;
use prismatic_core::model::scene::{Camera, Light, Material, MaterialKind, Object, Shape};
use prismatic_core::{PreparedScene, Scene, Vec3};
use prismatic_tests::backends::{every_backend, frame};
use prismatic_tests::parity::{Output, assert_parity};
use prismatic_tests::{glass, prepare, settings};

/// The floor's albedo.
const ALBEDO: f32 = 0.6;

fn floor() -> (Material, Object) {
    let m = Material {
        name: "floor".into(),
        kind: MaterialKind::Diffuse { albedo: Vec3::splat(ALBEDO), checker: None, texture: None, emission: Vec3::ZERO },
    };
    (m, Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 })
}

fn sky(map: EnvironmentMap, strength: f32) -> Light {
    Light::Environment { map, strength, rotation_deg: 0.0, spectrum: Default::default() }
}

/// A camera looking down at a floor under a constant sky of radiance `l`,
/// the horizon in the top rows.
fn floor_scene(l: f32) -> PreparedScene {
    let (m, o) = floor();
    let mut render = settings(1000, BandSpec::Paper7);
    (render.width, render.height, render.ambient) = (8, 8, 0.0);
    prepare(Scene {
        render,
        camera: Camera {
            position: Vec3::new(0.0, 1.0, 4.0),
            look_at: Vec3::new(0.0, 0.0, -2.0),
            up: Vec3::Y,
            fov_deg: 30.0,
        },
        lights: vec![sky(EnvironmentMap::constant(Vec3::ONE), l)],
        materials: vec![m],
        objects: vec![o],
    })
}

#[test]
fn a_constant_sky_lights_a_floor_with_pi_l_and_is_seen_beyond_it() {
    const L: f32 = 2.5;
    let scene = floor_scene(L);
    assert_eq!(scene.lights.len(), 32, "the default cut");
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, image) = frame(backend.as_mut(), &scene);
        // A diffuse floor under E = πL shows ρE/π = ρL; the sky beyond shows L.
        for (i, p) in image.pixels.iter().enumerate() {
            let floor = (*p - Vec3::splat(ALBEDO * L)).abs().max_element() < 2e-3 * L;
            let sky = (*p - Vec3::splat(L)).abs().max_element() < 1e-4 * L;
            assert!(floor || sky, "{name}: pixel {i} is {p}, neither the floor's {} nor the sky's {L}", ALBEDO * L);
        }
        assert!(image.pixels[63].x < L * 0.99 && image.pixels[0].x > L * 0.99, "{name}: floor below, sky above");
    }
}

/// A map with a sharp edge (white above a dark band) behind a dispersive
/// glass sphere on a floor: what is seen through the glass, the sky's
/// shadows and its caustic.
fn glass_scene() -> PreparedScene {
    let (w, h) = (64u32, 32u32);
    let texels: Vec<Vec3> = (0..w * h)
        .map(|i| match (i % w, i / w) {
            (x, y) if (20..28).contains(&x) && y < 10 => Vec3::splat(40.0),
            (_, y) if y < 14 => Vec3::new(0.6, 0.7, 0.9),
            _ => Vec3::splat(0.1),
        })
        .collect();
    let map = EnvironmentMap { name: "window".into(), width: w, height: h, texels: texels.into() };
    let (m, o) = floor();
    let mut render = settings(6_000, BandSpec::Physical(16));
    (render.width, render.height, render.ambient) = (32, 24, 0.0);
    render.environment_lights = 16;
    prepare(Scene {
        render,
        camera: Camera {
            position: Vec3::new(0.0, 1.2, 3.5),
            look_at: Vec3::new(0.0, 0.6, 0.0),
            up: Vec3::Y,
            fov_deg: 45.0,
        },
        lights: vec![Light::Environment { map, strength: 1.0, rotation_deg: 30.0, spectrum: Default::default() }],
        materials: vec![m, glass("glass", prismatic_core::Glass::Sf11.dispersion())],
        objects: vec![
            o,
            Object { shape: Shape::Sphere { center: Vec3::new(0.0, 0.7, 0.0), radius: 0.6 }, material: 1 },
        ],
    })
}

#[test]
fn the_backends_agree_on_a_glass_under_an_environment() {
    let scene = glass_scene();
    let mut outputs = every_backend().into_iter().map(|mut b| Output::frame(b.as_mut(), &scene));
    let reference = outputs.next().expect("the reference backend");
    assert!(reference.map.stats.flux_stored > 0.0, "the sky's suns leave caustic photons behind the glass");
    assert!(reference.map.photons.iter().any(|p| p.band != prismatic_core::model::photon::WHITE_BAND));
    for got in outputs {
        assert_parity("environment glass", &scene, &reference, &got);
    }
}
