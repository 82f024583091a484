//! The photon pass: splitting only at dispersive interfaces, bit-for-bit
//! determinism, canonical order, and flux bookkeeping.

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::{Dispersion, Glass};
use prismatic_core::model::photon::WHITE_BAND;
use prismatic_core::model::scene::{Light, Material, MaterialKind, Object, Shape};
use prismatic_core::photons::trace::trace_photons;
use prismatic_core::{PhotonMap, Scene, Vec3};
use prismatic_tests::{camera, glass, prepare, settings, white};

/// A glass sphere above a floor under a spot light, like the paper's scene.
fn sphere_scene(dispersion: Dispersion, bands: BandSpec, photons: u32, seed: u32) -> Scene {
    let mut render = settings(photons, bands);
    render.seed = seed;
    Scene {
        render,
        camera: camera(),
        lights: vec![Light::Spot {
            position: Vec3::new(0.0, 5.0, 0.0),
            direction: -Vec3::Y,
            cone_deg: 12.0,
            inner_cone_deg: 12.0,
            power: 10.0,
            spectrum: Default::default(),
            range: None,
        }],
        materials: vec![glass("glass", dispersion), white("floor")],
        objects: vec![
            Object { shape: Shape::Sphere { center: Vec3::new(0.0, 1.5, 0.0), radius: 1.0 }, material: 0 },
            Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 1 },
        ],
    }
}

fn trace(scene: Scene) -> PhotonMap {
    trace_photons(&prepare(scene), &mut prismatic_core::NoProgress)
}

#[test]
fn dispersive_glass_splits_white_photons_into_every_band() {
    let map = trace(sphere_scene(Glass::Bk7.dispersion(), BandSpec::Paper7, 2000, 1));
    assert!(!map.photons.is_empty());
    assert!(map.photons.iter().all(|p| p.band != WHITE_BAND && p.band < 7));
    // Each split photon's bands share its flux: 1/7 of the white photon's.
    let white_flux = 10.0 / 2000.0;
    assert!(map.photons.iter().all(|p| (p.flux - white_flux / 7.0).abs() < 1e-9));
    // Every band is present, and no (emission, band) pair twice.
    for b in 0..7 {
        assert!(map.photons.iter().any(|p| p.band == b), "band {b} missing");
    }
    assert!(map.is_canonical());
    assert!(map.stats.paths > map.stats.emitted, "splits add paths");
}

#[test]
fn constant_index_glass_never_splits_whatever_the_band_count() {
    for bands in [BandSpec::Paper7, BandSpec::Physical(64)] {
        let map = trace(sphere_scene(Dispersion::Constant(1.5), bands, 2000, 1));
        assert!(!map.photons.is_empty());
        assert!(map.photons.iter().all(|p| p.band == WHITE_BAND), "{bands}: a constant glass split a photon");
        assert_eq!(map.stats.paths, map.stats.emitted, "{bands}: no extra paths without dispersion");
    }
}

#[test]
fn a_per_band_table_with_one_index_does_not_split_either() {
    let map = trace(sphere_scene(Dispersion::PerBand(vec![1.5; 3]), BandSpec::Paper3, 500, 1));
    assert!(map.photons.iter().all(|p| p.band == WHITE_BAND));
}

#[test]
fn mirrors_reflect_white_light_without_splitting() {
    let mut scene = sphere_scene(Glass::Bk7.dispersion(), BandSpec::Paper7, 1000, 1);
    scene.materials[0] = Material::new("mirror", MaterialKind::Mirror);
    // Tilt the light so reflections reach the floor.
    scene.lights[0] = Light::Spot {
        position: Vec3::new(-3.0, 3.0, 0.0),
        direction: Vec3::new(3.0, -1.5, 0.0),
        cone_deg: 15.0,
        inner_cone_deg: 15.0,
        power: 1.0,
        spectrum: Default::default(),
        range: None,
    };
    let map = trace(scene);
    assert!(!map.photons.is_empty(), "the mirror sphere should cast a caustic");
    assert!(map.photons.iter().all(|p| p.band == WHITE_BAND && p.bounces >= 1));
}

#[test]
fn photons_that_reach_a_diffuse_surface_directly_are_not_stored() {
    let mut scene = sphere_scene(Glass::Bk7.dispersion(), BandSpec::Paper7, 1000, 1);
    scene.objects.remove(0); // no glass: only direct light
    let mut scene = prepare(scene);
    scene.plan.caustics.on = true; // the effect plan would skip the pass; run it anyway
    let map = trace_photons(&scene, &mut prismatic_core::NoProgress);
    assert!(map.photons.is_empty());
    assert_eq!(map.stats.stored, 0);
    assert!(map.stats.flux_direct > 0.0);
}

#[test]
fn same_seed_gives_the_same_photon_map_bit_for_bit() {
    let a = trace(sphere_scene(Glass::Water.dispersion(), BandSpec::Physical(16), 3000, 42));
    let b = trace(sphere_scene(Glass::Water.dispersion(), BandSpec::Physical(16), 3000, 42));
    assert!(!a.photons.is_empty());
    assert_eq!(bytemuck_bytes(&a), bytemuck_bytes(&b));
    assert_eq!(a.stats, b.stats);
    let c = trace(sphere_scene(Glass::Water.dispersion(), BandSpec::Physical(16), 3000, 43));
    assert_ne!(bytemuck_bytes(&a), bytemuck_bytes(&c), "a different seed must trace different photons");
}

#[test]
fn tracing_in_chunks_gives_the_same_map_as_in_one_go() {
    let scene = prepare(sphere_scene(Glass::Bk7.dispersion(), BandSpec::Paper7, 3000, 7));
    let whole = trace_photons(&scene, &mut prismatic_core::NoProgress);
    let mut chunked = PhotonMap::default();
    for start in (0..3000).step_by(700) {
        let end = (start + 700).min(3000);
        prismatic_core::photons::trace::trace_range(&scene, start..end, &mut chunked.photons, &mut chunked.stats);
    }
    assert_eq!(bytemuck_bytes(&whole), bytemuck_bytes(&chunked));
}

#[test]
fn flux_is_conserved_by_the_photon_pass() {
    let map = trace(sphere_scene(Glass::Bk7.dispersion(), BandSpec::Paper7, 5000, 3));
    let s = &map.stats;
    let accounted = s.flux_stored + s.flux_escaped + s.flux_direct + s.flux_depth_limited;
    assert!((s.flux_emitted - 10.0).abs() < 1e-4, "emitted {}", s.flux_emitted);
    assert!((accounted - s.flux_emitted).abs() < 1e-6 * s.flux_emitted, "{accounted} vs {}", s.flux_emitted);
    let stored: f64 = map.photons.iter().map(|p| f64::from(p.flux)).sum();
    assert!((stored - s.flux_stored).abs() < 1e-9);
}

fn bytemuck_bytes(map: &PhotonMap) -> Vec<u8> {
    bytemuck::cast_slice(&map.photons).to_vec()
}
