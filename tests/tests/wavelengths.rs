//! Wavelength sampling at dispersive glass: splitting into every band (the
//! paper), one random band per photon, continuous wavelengths and hero
//! wavelengths. The physics of each against closed forms, their
//! expectations against each other, and every backend against the reference.

use prismatic_core::model::photon::WHITE_BAND;
use prismatic_core::model::scene::HERO_WAVELENGTHS;
use prismatic_core::optics::surface::Surface;
use prismatic_core::photons::wavelengths::{sample_band, split_bands};
use prismatic_core::{Backend, BandSpec, Glass, NoProgress, PreparedScene, ReferenceBackend, WavelengthSampling};
use prismatic_tests::backends::{every_backend, fixed, trace};
use prismatic_tests::parity::{Output, assert_parity};
use prismatic_tests::{PrismExperiment, builtin, prepare, settings};

const SAMPLINGS: [WavelengthSampling; 4] = WavelengthSampling::ALL;

/// The wavelength photon `p` of pass 0 was traced at: its own, or its hero
/// path's (the one whose band it carries).
fn traced_wavelength(pass: &PreparedScene, p: &prismatic_core::Photon) -> f32 {
    split_bands(pass, p.emission)
        .find(|&(band, _)| band == p.band)
        .and_then(|(_, lambda)| lambda)
        .expect("a continuous photon carries one of its white photon's wavelengths")
}

#[test]
fn single_band_photons_carry_the_whole_flux_and_keep_one_band() {
    let bands = BandSpec::Physical(16);
    let exp = PrismExperiment { apex_deg: 60.0, incidence_deg: 50.0, beam_radius: 0.05, screen_x: 6.0 };
    for sampling in [WavelengthSampling::RandomBand, WavelengthSampling::Continuous] {
        let mut render = settings(20_000, bands);
        render.wavelengths = sampling;
        let scene = prepare(exp.scene(Glass::Bk7.dispersion(), render));
        let map = prismatic_core::photons::trace::trace_photons(&scene, &mut NoProgress);
        let flux = prismatic_core::photons::trace::photon_flux(&scene);
        // One path per emitted photon: nothing splits.
        assert_eq!(map.stats.paths, map.stats.emitted, "{sampling:?}");
        let mut per_band = [0u32; 16];
        for p in &map.photons {
            assert_ne!(p.band, WHITE_BAND, "{sampling:?}: white photon stored behind dispersive glass");
            assert_eq!(p.flux, flux, "{sampling:?}: a band photon carries N × 1/N of the white flux");
            assert_eq!(p.band, sample_band(&scene, p.emission).0);
            per_band[usize::from(p.band)] += 1;
        }
        // Bands are uniform: each count within 5 binomial standard deviations of n/16.
        let n = map.photons.len() as f64;
        let (mean, sd) = (n / 16.0, (n * (1.0 / 16.0) * (15.0 / 16.0)).sqrt());
        for (b, &c) in per_band.iter().enumerate() {
            assert!(
                (f64::from(c) - mean).abs() < 5.0 * sd,
                "{sampling:?}: band {b} has {c} photons, expected {mean:.0}"
            );
        }
    }
}

#[test]
fn hero_photons_split_into_one_wavelength_in_each_share_of_the_spectrum() {
    let bands = BandSpec::Physical(16);
    let exp = PrismExperiment { apex_deg: 60.0, incidence_deg: 50.0, beam_radius: 0.05, screen_x: 6.0 };
    let mut render = settings(20_000, bands);
    render.wavelengths = WavelengthSampling::Hero;
    let scene = prepare(exp.scene(Glass::Bk7.dispersion(), render));
    let map = prismatic_core::photons::trace::trace_photons(&scene, &mut NoProgress);
    let (m, n) = (HERO_WAVELENGTHS as usize, scene.bands.len());
    let flux = prismatic_core::photons::trace::photon_flux(&scene) / m as f32;
    // Every emitted photon meets the prism: M paths each.
    assert_eq!(map.stats.paths, map.stats.emitted * m as u64);
    let mut per_share = vec![0u32; m];
    for p in &map.photons {
        assert_eq!(p.flux, flux, "a hero photon carries 1/M of the white flux");
        let share = split_bands(&scene, p.emission).position(|(band, _)| band == p.band).expect("its band");
        // Share i covers bands ⌊i·N/M⌋..⌊(i+1)·N/M⌋, and its wavelength lies in its band.
        assert!(
            (share * n / m..(share + 1) * n / m).contains(&usize::from(p.band)),
            "band {} in share {share}",
            p.band
        );
        let lambda = split_bands(&scene, p.emission).nth(share).unwrap().1.expect("hero wavelengths are continuous");
        let (lo, hi) = scene.bands.band(usize::from(p.band)).interval_nm;
        assert!((lo..=hi).contains(&lambda));
        per_share[share] += 1;
    }
    // Every share lights the screen: BK7 passes most of each share's photons.
    assert!(per_share.iter().all(|&c| c > 15_000), "photons per share {per_share:?}");
    // One white photon's bands are a rotation: N/M bands apart (± 1 for rounding).
    for (emission, band) in map.photons.iter().map(|p| (p.emission, p.band)).take(200) {
        let bands: Vec<u16> = split_bands(&scene, emission).map(|(band, _)| band).collect();
        assert_eq!(bands.len(), m);
        assert!(bands.windows(2).all(|w| (n / m - 1..=n / m + 1).contains(&usize::from(w[1] - w[0]))), "{bands:?}");
        assert!(bands.contains(&band));
    }
}

#[test]
fn continuous_photons_deviate_as_snell_law_says_at_their_own_wavelength() {
    let bands = BandSpec::Physical(7);
    let glass = Glass::Sf11.dispersion();
    let exp = PrismExperiment { apex_deg: 60.0, incidence_deg: 60.0, beam_radius: 0.05, screen_x: 6.0 };
    for sampling in [WavelengthSampling::Continuous, WavelengthSampling::Hero] {
        let mut render = settings(20_000, bands);
        render.wavelengths = sampling;
        for mut backend in every_backend() {
            let scene = prepare(exp.scene(glass.clone(), render.clone()));
            let map = trace(backend.as_mut(), &scene);
            // The map is pass 0's: its wavelengths are drawn with pass 0's seed.
            let pass = prismatic_core::plan::schedule::pass_scene(&scene, 0);
            let phi = exp.beam_angle();
            let mut spread = (f64::INFINITY, f64::NEG_INFINITY);
            let mut checked = 0;
            for p in map.photons.iter().filter(|p| p.bounces == 2) {
                let lambda = traced_wavelength(&pass, p);
                // The map states it (a GPU's f32 may round it differently).
                let stated = p.wavelength().expect("a band photon");
                assert!((stated - lambda).abs() < 1e-4, "{}: states {stated} nm, traced at {lambda}", backend.name());
                let (lo, hi) = scene.bands.band(usize::from(p.band)).interval_nm;
                assert!((lo..=hi).contains(&lambda), "λ {lambda} outside band {} ({lo}–{hi})", p.band);
                let n = f64::from(glass.ior_at(lambda).unwrap());
                let d = p.direction();
                let got = (phi - f64::from(d.y).atan2(f64::from(d.x))).to_degrees();
                let expected = exp.deviation_deg(n).unwrap();
                // As for band photons (physics.rs), plus the 1 nm curve's
                // interpolation error (< 1e-7 in n, ~1e-5°) and the stored
                // direction's 16-bit encoding (< 0.004°).
                assert!((got - expected).abs() < 6e-3, "λ {lambda}: deviation {got:.5}° vs {expected:.5}°");
                spread = (spread.0.min(got), spread.1.max(got));
                checked += 1;
            }
            // SF11 (n ≈ 1.78) reflects ~16 % at each face: about 70 % pass both.
            assert!(checked > 12_000, "{} {sampling:?}: only {checked} photons passed both faces", backend.name());
            // The stripe is continuous: deviations cover the whole visible range's
            // span (SF11, 380–780 nm), not 7 lines.
            let span = exp.deviation_deg(f64::from(glass.ior_at(390.0).unwrap())).unwrap()
                - exp.deviation_deg(f64::from(glass.ior_at(770.0).unwrap())).unwrap();
            assert!(spread.1 - spread.0 > span, "{} {sampling:?}: deviations span {spread:?}", backend.name());
        }
    }
}

#[test]
fn continuous_index_follows_the_glass_curve_across_each_band() {
    // At any wavelength inside a band, the index a continuous photon sees is
    // n(λ) of the glass (band index moved along the 1 nm curve), and at the
    // band's centre exactly the band's own index.
    for glass in [Glass::Bk7, Glass::Water, Glass::Sf11] {
        let mut doc = builtin("prism", |r| r.bands = BandSpec::Physical(16)).scene;
        for m in &mut doc.materials {
            if let prismatic_core::model::scene::MaterialKind::Dielectric { dispersion, .. } = &mut m.kind {
                *dispersion = glass.dispersion();
            }
        }
        let scene = PreparedScene::new(doc).unwrap();
        let Some(optics) = scene.surfaces.iter().find_map(|s| match s {
            Surface::Dielectric(g) => Some(g),
            _ => None,
        }) else {
            panic!("the prism scene has glass")
        };
        for (b, band) in scene.bands.bands().iter().enumerate() {
            let b16 = b as u16;
            assert_eq!(optics.ior_at_wavelength(b16, band.lambda_nm, &scene.bands), optics.ior(b16));
            let (lo, hi) = band.interval_nm;
            for f in [0.0, 0.137, 0.5, 0.9, 1.0] {
                let lambda = lo + (hi - lo) * f;
                let expected = glass.dispersion().ior_at(lambda).unwrap();
                let got = optics.ior_at_wavelength(b16, lambda, &scene.bands);
                // Linear interpolation over 1 nm (< 1e-7) plus f32 rounding.
                assert!((got - expected).abs() < 2e-6, "{glass:?} at {lambda} nm: {got} vs {expected}");
            }
        }
    }
}

#[test]
fn every_sampling_lights_the_caustic_with_the_same_expected_energy() {
    // Expectations agree; only the noise differs. The sphere's caustic energy
    // (image sum minus the image without photons), 200k photons.
    let energy = |sampling: WavelengthSampling| {
        let scene = builtin("sphere", |r| {
            r.wavelengths = sampling;
            r.photons = 200_000;
            r.width = 64;
            r.height = 64;
            r.estimator = prismatic_core::Estimator::Density;
        });
        let mut render = ReferenceBackend.prepare(&fixed(&scene)).unwrap();
        render.run_pass(0, &mut NoProgress).unwrap();
        let (with, without) = (render.image().unwrap().pixels, render.base().unwrap().pixels);
        with.iter().zip(&without).map(|(a, b)| (*a - *b).as_dvec3()).sum::<glam::DVec3>()
    };
    let split = energy(WavelengthSampling::Split);
    for sampling in [WavelengthSampling::RandomBand, WavelengthSampling::Continuous, WavelengthSampling::Hero] {
        let got = energy(sampling);
        // Per channel within 3 %: the split image's caustic covers ~300
        // pixels with ~100 photons each; random bands add colour noise that
        // averages out over the caustic.
        let rel = ((got - split) / split).abs().max_element();
        assert!(rel < 0.03, "{sampling:?}: caustic energy {got} vs split {split} ({rel:.4})");
    }
}

#[test]
fn every_backend_matches_the_reference_for_every_sampling() {
    for sampling in SAMPLINGS {
        for (name, photons) in [("sphere", 20_000), ("prism", 4_000), ("rainbow", 40_000)] {
            let scene = builtin(name, |r| {
                r.wavelengths = sampling;
                r.photons = photons;
                r.width = 64;
                r.height = 64;
            });
            let mut backends = every_backend();
            let expected = Output::frame(backends[0].as_mut(), &scene);
            for backend in &mut backends[1..] {
                let got = Output::frame(backend.as_mut(), &scene);
                assert_parity(&format!("{}-{name}-{}", backend.name(), sampling.name()), &scene, &expected, &got);
            }
        }
    }
}
