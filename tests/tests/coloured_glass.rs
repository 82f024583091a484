//! Coloured glass against Beer–Lambert's closed form, on every backend: a
//! slab of known thickness passes e^(−σd) of each band's photons (with the
//! Fresnel losses and inner reflections of both faces), and a view ray
//! through it keeps that fraction of each RGB channel.

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::photon::WHITE_BAND;
use prismatic_core::model::scene::{Attenuation, Light, Material, MaterialKind, Object, Shape};
use prismatic_core::optics::surface::Surface;
use prismatic_core::{PreparedScene, Scene, Vec3};
use prismatic_tests::backends::{every_backend, frame, trace};
use prismatic_tests::{beam_onto_a_wall, prepare, settings};

/// Slab thickness (along x, from x = 0).
const THICKNESS: f32 = 1.0;
/// What white light keeps of each channel after `DISTANCE` inside.
const COLOR: Vec3 = Vec3::new(0.8, 0.45, 0.15);
const DISTANCE: f32 = 0.7;

/// A slab of glass of index `ior` and colour [`COLOR`] between x = 0 and
/// x = [`THICKNESS`]: a prism whose end triangle stands in the plane x = 0.
fn slab(ior: Dispersion) -> (Material, Object) {
    let material = Material {
        name: "amber".into(),
        kind: MaterialKind::Dielectric {
            dispersion: ior,
            outside: Dispersion::Constant(1.0),
            attenuation: Some(Attenuation { color: COLOR, distance: DISTANCE }),
            thin: false,
            film: None,
            roughness: 0.0,
        },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    };
    let vertices = [Vec3::new(0.0, -3.0, -2.0), Vec3::new(0.0, 3.0, -2.0), Vec3::new(0.0, 0.0, 3.0)];
    (material, Object { shape: Shape::Prism { vertices, extrude: Vec3::X * THICKNESS }, material: 0 })
}

/// Fraction of light at normal incidence that a slab of relative index `n`
/// passes when one crossing keeps `tau`: (1−R)² τ / (1 − R²τ²), every inner
/// reflection summed.
fn slab_transmittance(n: f64, tau: f64) -> f64 {
    let r = ((n - 1.0) / (n + 1.0)).powi(2);
    (1.0 - r).powi(2) * tau / (1.0 - r * r * tau * tau)
}

/// What a view ray at normal incidence brings back from a uniform
/// background of radiance 1 through the slab: the reflection of the front
/// face plus everything that leaves either face, R + (1−R)² τ / (1 − Rτ).
fn slab_view(n: f64, tau: f64) -> f64 {
    let r = ((n - 1.0) / (n + 1.0)).powi(2);
    r + (1.0 - r).powi(2) * tau / (1.0 - r * tau)
}

/// A beam along +x through the slab onto a white wall at x = 3.
fn photon_scene(photons: u32) -> PreparedScene {
    let (amber, object) = slab(Dispersion::Constant(1.5));
    beam_onto_a_wall(photons, amber, object.shape)
}

#[test]
fn a_coloured_slab_passes_each_bands_beer_lambert_fraction_of_photons() {
    const PHOTONS: u32 = 20_000;
    let scene = photon_scene(PHOTONS);
    let Surface::Dielectric(glass) = &scene.surfaces[0] else { unreachable!("object 0 is the slab") };
    assert!(glass.splits_photons, "white photons split at coloured glass even when it does not disperse");
    let absorption = glass.absorption.as_ref().expect("the slab absorbs");
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        let s = &map.stats;
        assert_eq!(s.emitted, u64::from(PHOTONS), "{name}");
        for (band, &sigma) in absorption.band.iter().enumerate() {
            let stored = map.photons.iter().filter(|p| usize::from(p.band) == band).count();
            let got = stored as f64 / f64::from(PHOTONS);
            let expected = slab_transmittance(1.5, (-f64::from(sigma) * f64::from(THICKNESS)).exp());
            let sd = (expected * (1.0 - expected) / f64::from(PHOTONS)).sqrt();
            assert!(
                (got - expected).abs() < 5.0 * sd,
                "{name}, band {band}: {got:.4} of the photons passed, Beer–Lambert says {expected:.4} (±{sd:.4})"
            );
        }
        assert!(map.photons.iter().all(|p| p.band != WHITE_BAND), "{name}: a white photon crossed coloured glass");
        // Every watt is stored, escaped (reflected back), absorbed or depth-limited.
        let accounted = s.flux_stored + s.flux_escaped + s.flux_absorbed + s.flux_depth_limited + s.flux_direct;
        assert!((accounted - s.flux_emitted).abs() < 1e-4 * s.flux_emitted, "{name}: {s:?}");
        assert!(s.flux_absorbed > 0.2 * s.flux_emitted, "{name}: the slab absorbed only {}", s.flux_absorbed);
    }
}

/// A camera on the x axis looking through the slab at a background of
/// radiance 1 (3×3 pixels: the middle one looks straight through).
fn view_scene(ior: Dispersion, bands: BandSpec) -> PreparedScene {
    let (amber, object) = slab(ior);
    let mut render = settings(1000, bands);
    (render.width, render.height, render.background) = (3, 3, Vec3::ONE);
    prepare(Scene {
        render,
        camera: prismatic_core::model::scene::Camera {
            position: Vec3::new(-5.0, 0.0, 0.0),
            look_at: Vec3::ZERO,
            up: Vec3::Z,
            fov_deg: 10.0,
        },
        lights: vec![Light::Point {
            position: Vec3::new(-5.0, 0.0, 5.0),
            power: 1.0,
            spectrum: Default::default(),
            range: None,
        }],
        materials: vec![amber],
        objects: vec![object],
    })
}

/// Rays the view pass prunes (share below 1/1000) and f32: well under this.
const VIEW_TOLERANCE: f32 = 3e-3;

/// Asserts that every backend's middle pixel of `scene` (looking straight
/// through the slab) is `expected`.
fn assert_seen_through_the_slab(scene: &PreparedScene, expected: Vec3) {
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, image) = frame(backend.as_mut(), scene);
        let got = image.pixels[4];
        assert!(
            (got - expected).abs().max_element() < VIEW_TOLERANCE,
            "{name}: through the slab {got}, Beer–Lambert says {expected}"
        );
    }
}

#[test]
fn a_view_ray_through_a_coloured_slab_keeps_beer_lambert_per_channel() {
    // Clear-index glass: the white ray keeps each channel's own fraction.
    let scene = view_scene(Dispersion::Constant(1.5), BandSpec::Paper7);
    let tau = |c: f32| f64::from(c).powf(f64::from(THICKNESS / DISTANCE));
    let expected = Vec3::new(
        slab_view(1.5, tau(COLOR.x)) as f32,
        slab_view(1.5, tau(COLOR.y)) as f32,
        slab_view(1.5, tau(COLOR.z)) as f32,
    );
    assert_seen_through_the_slab(&scene, expected);
}

#[test]
fn band_view_rays_through_coloured_dispersive_glass_keep_their_bands_fraction() {
    // Dispersive glass: the ray splits into bands, each with its own index and σ.
    let scene = view_scene(Dispersion::Cauchy { a: 1.5, b: 0.02 }, BandSpec::Paper7);
    let Surface::Dielectric(glass) = &scene.surfaces[0] else { unreachable!("object 0 is the slab") };
    let absorption = glass.absorption.as_ref().expect("the slab absorbs");
    let expected: Vec3 = scene
        .bands
        .bands()
        .iter()
        .enumerate()
        .map(|(b, info)| {
            let tau = (-f64::from(absorption.band[b]) * f64::from(THICKNESS)).exp();
            info.weight * slab_view(f64::from(glass.band_ior[b]), tau) as f32
        })
        .sum();
    assert_seen_through_the_slab(&scene, expected);
}
