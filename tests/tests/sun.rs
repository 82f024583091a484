//! Sun light against closed forms, on every backend: a floor facing the
//! sun at an angle is lit with E cos θ and shadowed behind an object, and
//! the sun's photons all leave toward the mirrors and glass, carrying the
//! flux E × their cross-sections (none wasted on empty sky).

use core::f32::consts::PI;
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::scene::{Camera, Light, Material, MaterialKind, Object, Shape};
use prismatic_core::{PreparedScene, Scene, Vec3};
use prismatic_tests::backends::{every_backend, trace};
use prismatic_tests::{glass, prepare, settings};

const IRRADIANCE: f32 = 3.0;
const ALBEDO: f32 = 0.6;

/// The sun 35° above the horizon, from −x.
fn sun_direction() -> Vec3 {
    let elevation = 35f32.to_radians();
    Vec3::new(elevation.cos(), -elevation.sin(), 0.0)
}

/// A grey floor (y = 0) under the sun with a glass sphere of radius 1 on
/// it at the origin, seen from straight above.
fn scene(photons: u32) -> PreparedScene {
    let mut render = settings(photons, BandSpec::Paper3);
    (render.width, render.height, render.ambient) = (48, 48, 0.0);
    let floor = Material {
        name: "floor".into(),
        kind: MaterialKind::Diffuse { albedo: Vec3::splat(ALBEDO), checker: None, texture: None, emission: Vec3::ZERO },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    };
    prepare(Scene {
        render,
        camera: Camera { position: Vec3::new(0.0, 20.0, 0.0), look_at: Vec3::ZERO, up: Vec3::Z, fov_deg: 30.0 },
        lights: vec![Light::Sun {
            direction: sun_direction(),
            irradiance: IRRADIANCE,
            spectrum: Default::default(),
            mean_toward: None,
        }],
        materials: vec![floor, glass("glass", Dispersion::Paper)],
        objects: vec![
            Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 },
            Object { shape: Shape::Sphere { center: Vec3::Y, radius: 1.0 }, material: 1 },
        ],
    })
}

/// The pixel of `scene`'s 48×48 image that sees floor point (x, 0, z)
/// (the camera looks down −y with +z up in the image).
fn pixel_at(x: f32, z: f32) -> usize {
    let half = (15f32.to_radians()).tan() * 20.0;
    let col = ((-x / half + 1.0) * 24.0) as usize;
    let row = ((-z / half + 1.0) * 24.0) as usize;
    row * 48 + col
}

#[test]
fn the_sun_lights_the_floor_with_e_cos_theta_and_objects_shadow_it() {
    let scene = scene(2000);
    let cos_theta = -sun_direction().y;
    let lit = ALBEDO / PI * IRRADIANCE * cos_theta;
    // Behind the sphere, away from the sun: the sphere's shadow (the glass
    // casts a full shadow; the light it passes arrives as caustic photons).
    let (sunny, shadowed) = (pixel_at(-3.0, 3.0), pixel_at(1.9, 0.0));
    for mut backend in every_backend() {
        let name = backend.name();
        // The view pass alone: direct light and shadows, no caustic.
        let base = backend.prepare(&scene).unwrap().base().unwrap();
        let got = base.pixels[sunny];
        assert!(
            (got - Vec3::splat(lit)).abs().max_element() < 1e-4 * lit,
            "{name}: sunlit floor {got}, expected {lit}"
        );
        assert!(base.pixels[shadowed].max_element() < 1e-6, "{name}: in the shadow {}", base.pixels[shadowed]);
    }
}

#[test]
fn every_sun_photon_meets_the_glass_with_the_flux_of_its_cross_section() {
    const PHOTONS: u32 = 4000;
    let scene = scene(PHOTONS);
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        let s = &map.stats;
        let expected = f64::from(IRRADIANCE * PI); // E × π r², r = 1
        assert!(
            (s.flux_emitted - expected).abs() < 1e-4 * expected,
            "{name}: emitted {}, E·πr² = {expected}",
            s.flux_emitted
        );
        assert_eq!(s.specular_paths, u64::from(PHOTONS), "{name}: every photon meets the glass");
        assert_eq!(s.flux_direct, 0.0, "{name}: no photon lands on the floor directly");
        assert!(map.photons.len() as u32 > PHOTONS / 2, "{name}: {} caustic photons", map.photons.len());
    }
}

#[test]
fn two_targets_share_the_suns_photons_by_their_cross_sections() {
    let mut s = scene(4000).scene;
    s.objects.push(Object { shape: Shape::Sphere { center: Vec3::new(0.0, 0.5, 4.0), radius: 0.5 }, material: 1 });
    let scene = prepare(s);
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        let expected = f64::from(IRRADIANCE * PI * (1.0 + 0.25));
        let got = map.stats.flux_emitted;
        assert!((got - expected).abs() < 1e-3 * expected, "{name}: emitted {got}, E·Σπr² = {expected}");
        assert_eq!(map.stats.flux_direct, 0.0, "{name}: projection maps aim every photon at a sphere");
    }
}
