//! The prism experiment against its closed form: a 60° BK7 prism at minimum
//! deviation sends each band where D_min(λ) = 2·asin(n(λ)·sin(A/2)) − A says.

use prismatic_core::bands::BandSpec;
use prismatic_core::dispersion::Glass;
use prismatic_core::photon::WHITE_BAND;
use prismatic_core::trace::trace_photons;
use prismatic_tests::{PrismExperiment, prepare, settings};

/// PHYSICS.md's figures for a 60° BK7 prism, from the closed form and the Sellmeier fit.
#[test]
fn bk7_minimum_deviation_closed_form_matches_published_figures() {
    let bk7 = Glass::Bk7.dispersion();
    for (lambda, d_min) in [(486.13, 39.14), (587.56, 38.65), (656.27, 38.43)] {
        let n = f64::from(bk7.ior_at(lambda).unwrap());
        let got = PrismExperiment::min_deviation_deg(60.0, n);
        assert!((got - d_min).abs() < 0.01, "{lambda} nm: {got:.3}°, expected {d_min}°");
    }
}

/// Each band, with the beam set to that band's minimum-deviation incidence,
/// leaves the prism deviated by D_min(λ) and lands where the closed form
/// puts it on the screen.
#[test]
fn bk7_prism_sends_each_band_to_its_minimum_deviation() {
    const PHOTONS: u32 = 4000;
    let bands = BandSpec::Physical(7);
    let bk7 = Glass::Bk7.dispersion();
    let table = prismatic_core::BandTable::new(bands);
    for band in 0..table.len() {
        let n = f64::from(bk7.ior_for_band(&table, band));
        let d_min = PrismExperiment::min_deviation_deg(60.0, n);
        let exp =
            PrismExperiment { apex_deg: 60.0, incidence_deg: (d_min + 60.0) / 2.0, beam_radius: 0.05, screen_x: 6.0 };
        let scene = prepare(exp.scene(bk7.clone(), settings(PHOTONS, bands)));
        let map = trace_photons(&scene);
        // Photons of this band that refracted twice and nothing else.
        let hits: Vec<_> = map.photons.iter().filter(|p| p.band == band as u16 && p.bounces == 2).collect();
        assert!(hits.len() as f64 > 0.85 * f64::from(PHOTONS), "band {band}: only {} photons arrived", hits.len());
        let phi = exp.beam_angle();
        let mut worst_dev: f64 = 0.0;
        let mut mean_y = 0.0;
        for p in &hits {
            let d = p.direction();
            let deviation = (phi - f64::from(d.y).atan2(f64::from(d.x))).to_degrees();
            worst_dev = worst_dev.max((deviation - d_min).abs());
            mean_y += f64::from(p.position[1]) / hits.len() as f64;
        }
        // f32 refraction through two faces: a few 1e-6 rad of direction error.
        assert!(worst_dev < 2e-3, "band {band}: deviation off D_min = {d_min:.4}° by {worst_dev:.5}°");
        // The beam's centroid is mapped affinely by two flat faces, so the band's
        // centroid is the centre ray's landing point. Sampling noise: beam radius
        // 0.05 ⇒ σ(y) ≈ 0.05/2 · stretch / √N ≈ 6e-4 for N ≈ 3900; allow 4σ.
        let expected = exp.screen_y(n).unwrap();
        assert!((mean_y - expected).abs() < 2.5e-3, "band {band}: centroid y {mean_y:.5}, closed form {expected:.5}");
    }
}

/// With one beam, the bands fan out in order: longer wavelengths deviate less.
#[test]
fn bands_fan_out_in_wavelength_order() {
    let exp = PrismExperiment { apex_deg: 60.0, incidence_deg: 60.0, beam_radius: 0.02, screen_x: 6.0 };
    let scene = prepare(exp.scene(Glass::Sf11.dispersion(), settings(3000, BandSpec::Physical(8))));
    let map = trace_photons(&scene);
    assert!(map.photons.iter().all(|p| p.band != WHITE_BAND), "white light must split in SF11");
    let centroid = |b: u16| {
        let ys: Vec<f32> =
            map.photons.iter().filter(|p| p.band == b && p.bounces == 2).map(|p| p.position[1]).collect();
        ys.iter().sum::<f32>() / ys.len() as f32
    };
    // Physical bands run from short (violet) to long (red) wavelength; red lands highest.
    let ys: Vec<f32> = (0..8).map(centroid).collect();
    assert!(ys.windows(2).all(|w| w[0] < w[1]), "band centroids (short to long λ): {ys:?}");
}
