//! Physics against closed forms, on every backend: prism deviation (several
//! apex angles and glasses, at and away from minimum deviation), the rainbow's
//! Descartes angles, recombination through an inverted prism, and energy
//! conservation with a closed catcher.

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::{Dispersion, Glass};
use prismatic_core::model::photon::{PhotonMap, WHITE_BAND};
use prismatic_core::model::scene::{Light, RenderSettings};
use prismatic_core::optics::surface::Surface;
use prismatic_core::{PreparedScene, Scene};
use prismatic_tests::backends::{every_backend, trace};
use prismatic_tests::{PrismExperiment, descartes_deg, prepare, settings, snell_path_2d, sphere_in_a_catcher};

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

/// White photons per prism experiment.
const PHOTONS: u32 = 3000;

/// Mean and standard error of the mean.
fn mean_and_error(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Each band leaves the prism deviated by the closed form D(n, i) and its
/// centroid lands where Snell's law at both faces puts the beam's centre ray:
/// 30°, 45° and 60° prisms of BK7 and SF11 (Sellmeier), with the beam at the
/// middle band's minimum-deviation incidence and 10° steeper.
#[test]
fn prisms_deviate_every_band_as_snell_law_at_both_faces_says() {
    let bands = BandSpec::Physical(7);
    let table = prismatic_core::BandTable::new(bands);
    for mut backend in every_backend() {
        let name = backend.name();
        for glass in [Glass::Bk7, Glass::Sf11] {
            let dispersion = glass.dispersion();
            let n_mid = f64::from(dispersion.ior_for_band(&table, 3));
            for apex_deg in [30.0, 45.0, 60.0] {
                let at_min = (PrismExperiment::min_deviation_deg(apex_deg, n_mid) + apex_deg) / 2.0;
                for incidence_deg in [at_min, at_min + 10.0] {
                    let exp = PrismExperiment { apex_deg, incidence_deg, beam_radius: 0.05, screen_x: 6.0 };
                    let case = format!("{name}: {} {apex_deg}° prism at {incidence_deg:.2}°", glass.name());
                    let scene = prepare(exp.scene(dispersion.clone(), settings(PHOTONS, bands)));
                    let map = trace(backend.as_mut(), &scene);
                    check_prism_bands(&case, &exp, &scene, &map);
                }
            }
        }
    }
}

fn check_prism_bands(case: &str, exp: &PrismExperiment, scene: &PreparedScene, map: &PhotonMap) {
    let Surface::Dielectric(optics) = &scene.surfaces[0] else { unreachable!("object 0 is the prism") };
    let phi = exp.beam_angle();
    for (band, &n) in optics.band_ior.iter().enumerate() {
        let n = f64::from(n);
        let deviation = exp.deviation_deg(n).expect("no total internal reflection in these prisms");
        // Photons of this band that refracted at both faces and nothing else.
        let hits: Vec<_> = map.photons.iter().filter(|p| usize::from(p.band) == band && p.bounces == 2).collect();
        assert!(hits.len() > PHOTONS as usize / 2, "{case}, band {band}: only {} photons arrived", hits.len());
        let mut worst: f64 = 0.0;
        for p in &hits {
            let d = p.direction();
            let got = (phi - f64::from(d.y).atan2(f64::from(d.x))).to_degrees();
            worst = worst.max((got - deviation).abs());
        }
        // f32 refraction at two faces plus the octahedral direction encoding:
        // a few 1e-6 rad, i.e. under 1e-3°.
        assert!(worst < 2e-3, "{case}, band {band}: deviation off {deviation:.4}° by {worst:.5}°");
        // Two flat faces map the parallel beam affinely, so the band's centroid
        // is where the centre ray lands. Tolerance: 4 standard errors of the
        // mean (the spread of landing heights is the beam's radius stretched by
        // the prism's anamorphic magnification, over √N photons), plus 2e-4 for
        // the f32 direction error above carried over the 6 units to the screen.
        let ys: Vec<f64> = hits.iter().map(|p| f64::from(p.position[1])).collect();
        let (mean, error) = mean_and_error(&ys);
        let expected = exp.screen_y(n).unwrap();
        let tolerance = 4.0 * error + 2e-4;
        assert!(
            (mean - expected).abs() < tolerance,
            "{case}, band {band}: centroid y {mean:.5}, Snell puts it at {expected:.5} (tolerance {tolerance:.5})"
        );
    }
}

/// A drop of radius 1 under a parallel beam that covers it exactly.
fn drop_in_a_catcher(dispersion: Dispersion, render: RenderSettings) -> Scene {
    sphere_in_a_catcher(dispersion, render, 0.0, 1.0)
}

/// Photons leaving the drop after one and two internal reflections pile up
/// at the Descartes angles of their band (the bow is a fold caustic: the
/// density diverges at the extreme angle), within 0.2°.
#[test]
fn rainbow_photons_peak_at_each_bands_descartes_angles() {
    const BIN_DEG: f64 = 0.05;
    let mut render = settings(400_000, BandSpec::Physical(8));
    render.max_depth = 6;
    let scene = prepare(drop_in_a_catcher(Glass::Water.dispersion(), render));
    let Surface::Dielectric(water) = &scene.surfaces[0] else { unreachable!("object 0 is the drop") };
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        for (band, &n) in water.band_ior.iter().enumerate() {
            for k in [1u16, 2] {
                let mut histogram = vec![0u32; (90.0 / BIN_DEG) as usize];
                for p in map.photons.iter().filter(|p| usize::from(p.band) == band && p.bounces == k + 2) {
                    // Angle between the returning photon and the beam's reverse (+z).
                    let theta = f64::from(p.direction().z).clamp(-1.0, 1.0).acos().to_degrees();
                    let bin = ((theta / BIN_DEG) as usize).min(histogram.len() - 1);
                    histogram[bin] += 1;
                }
                let (bin, _) = histogram.iter().enumerate().max_by_key(|(_, c)| **c).unwrap();
                let peak = (bin as f64 + 0.5) * BIN_DEG;
                let expected = descartes_deg(f64::from(n), f64::from(k));
                assert!(
                    (peak - expected).abs() < 0.2,
                    "{name}: band {band} (n = {n}), {k} reflection(s): peak at {peak:.2}°, Descartes {expected:.2}°"
                );
            }
        }
    }
}

#[test]
fn descartes_angles_match_the_published_figures() {
    // PHYSICS.md's figures for red (C line, 656.3 nm) and violet (h line, 404.7 nm).
    let water = Glass::Water.dispersion();
    let n = |nm: f32| f64::from(water.ior_at(nm).unwrap());
    for (nm, k, expected) in [(656.3, 1.0, 42.3), (404.7, 1.0, 40.6), (656.3, 2.0, 50.5), (404.7, 2.0, 53.5)] {
        let got = descartes_deg(n(nm), k);
        assert!((got - expected).abs() < 0.05, "{nm} nm, {k} reflection(s): {got:.2}°, expected ≈ {expected}°");
    }
}

/// A second prism, the first one's point reflection, bends every band back
/// parallel to the beam, and the bands' spots downstream coincide.
#[test]
fn an_inverted_prism_recombines_the_bands() {
    const GAP: f64 = 0.1;
    let paper = Glass::Paper.dispersion();
    let bands = BandSpec::Physical(16);
    let table = prismatic_core::BandTable::new(bands);
    let n_mid = f64::from(paper.ior_for_band(&table, 8));
    let incidence_deg = (PrismExperiment::min_deviation_deg(60.0, n_mid) + 60.0) / 2.0;
    let exp = PrismExperiment { apex_deg: 60.0, incidence_deg, beam_radius: 0.05, screen_x: 8.0 };
    let mut scene = exp.scene(paper, settings(PHOTONS, bands));
    let second = exp.add_inverted_prism(&mut scene, n_mid, GAP);
    let scene = prepare(scene);
    let Surface::Dielectric(optics) = &scene.surfaces[0] else { unreachable!("object 0 is the prism") };
    let Light::Beam { direction, .. } = scene.scene.lights[0] else { unreachable!("a beam scene") };
    // Closed form: each band's centre ray, refracted at all four faces.
    let first = exp.corners().map(|p| (f64::from(p.0 as f32), f64::from(p.1 as f32)));
    let entry = exp.entry_point();
    let start = (entry.0 - exp.beam_angle().cos(), entry.1 - exp.beam_angle().sin());
    let expected: Vec<f64> = optics
        .band_ior
        .iter()
        .map(|&n| snell_path_2d(&[first, second], start, exp.beam_angle(), f64::from(n), 8.0).unwrap())
        .collect();
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        for (band, &expected_y) in expected.iter().enumerate() {
            // Four refractions, then the screen.
            let on_screen: Vec<_> =
                map.photons.iter().filter(|p| usize::from(p.band) == band && p.bounces == 4).collect();
            assert!(
                on_screen.len() > PHOTONS as usize / 2,
                "{name}: band {band}: {} photons on the screen",
                on_screen.len()
            );
            for p in &on_screen {
                // Four f32 refractions: under 4e-3° (see the prism test).
                let angle = p.direction().angle_between(direction).to_degrees();
                assert!(angle < 4e-3, "{name}: band {band} leaves {angle}° off the beam");
            }
            // The same tolerance as the prism test: 4 standard errors of the
            // centroid, plus the f32 direction error carried to the screen.
            let ys: Vec<f64> = on_screen.iter().map(|p| f64::from(p.position[1])).collect();
            let (mean, error) = mean_and_error(&ys);
            let tolerance = 4.0 * error + 2e-4;
            assert!(
                (mean - expected_y).abs() < tolerance,
                "{name}: band {band}: centroid y {mean:.5}, Snell puts it at {expected_y:.5} (tolerance {tolerance:.5})"
            );
        }
    }
    // What remains after recombination is a lateral shift that grows with n
    // (the pair acts like a thick tilted plate, paths inside the glass differ
    // by band). The closed form gives 0.060 here; the band spots coincide
    // within 0.075, less than the beam's diameter (0.1), so they overlap.
    let spread = expected.iter().copied().fold(f64::MIN, f64::max) - expected.iter().copied().fold(f64::MAX, f64::min);
    assert!(spread < 0.075, "closed-form band centres {spread:.4} apart: {expected:?}");
}

/// With glass that absorbs nothing inside a closed catcher, no flux escapes
/// and every band receives exactly 1/N of the flux that reached the glass.
#[test]
fn flux_is_conserved_per_band_in_a_closed_catcher() {
    for (glass_name, dispersion, bands) in [
        ("water", Glass::Water.dispersion(), BandSpec::Physical(8)),
        ("diamond", Glass::Diamond.dispersion(), BandSpec::Paper7),
        ("sf11", Glass::Sf11.dispersion(), BandSpec::Physical(1)),
    ] {
        let mut render = settings(20_000, bands);
        render.max_depth = 64;
        let scene = prepare(drop_in_a_catcher(dispersion, render));
        let n = scene.bands.len();
        for mut backend in every_backend() {
            let case = format!("{}: {glass_name}, {n} band(s)", backend.name());
            let map = trace(backend.as_mut(), &scene);
            let s = map.stats;
            assert_eq!(s.flux_escaped, 0.0, "{case}: flux escaped a closed catcher");
            let accounted = s.flux_stored + s.flux_direct + s.flux_depth_limited;
            assert!((accounted - s.flux_emitted).abs() <= 1e-6 * s.flux_emitted, "{case}: {s:?}");
            // Photons that met the glass: split evenly into the bands, each of
            // which ends stored (or, rarely, at the depth limit).
            let per_band = (s.flux_emitted - s.flux_direct) / n as f64;
            for band in 0..n as u16 {
                let stored: f64 = map
                    .photons
                    .iter()
                    .filter(|p| p.band == band || (n == 1 && p.band == WHITE_BAND))
                    .map(|p| f64::from(p.flux))
                    .sum();
                let missing = per_band - stored;
                assert!(
                    missing >= -1e-6 * per_band && missing <= s.flux_depth_limited + 1e-6 * per_band,
                    "{case}: band {band} stored {stored}, expected {per_band} (depth-limited {})",
                    s.flux_depth_limited
                );
            }
        }
    }
}
