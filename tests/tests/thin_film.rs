//! Thin-film coatings (glTF's `KHR_materials_iridescence`) against the
//! closed form on every backend. At normal incidence the film's Fresnel
//! amplitudes are real, r₀₁ = (n₀ − n₁)/(n₀ + n₁) and r₁₂ = (n₁ − n₂)/(n₁ + n₂),
//! and the Airy sum reads
//! R = (r₀₁² + r₁₂² + 2 r₀₁ r₁₂ cos δ) / (1 + r₀₁² r₁₂² + 2 r₀₁ r₁₂ cos δ),
//! δ = 4π n₁ d / λ, an independent formula from the core's complex one. A
//! coated sheet reflects 2R/(1 + R) of each wavelength and passes the rest:
//! photons of each band pass by their own share, and a view through the
//! sheet takes the colour of what passes.

use prismatic_core::model::bands::{BandSpec, BandTable};
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::photon::PhotonMap;
use prismatic_core::model::scene::{Material, MaterialKind, Shape, ThinFilm};
use prismatic_core::{PreparedScene, Vec3};
use prismatic_tests::backends::{every_backend, frame, trace};
use prismatic_tests::{beam_onto_a_wall, view_through_a_sheet};

/// The sheet's index, its film's index and thickness: a high-index coating
/// whose reflectance swings from 8 % to 51 % across the visible bands.
const GLASS: f64 = 1.5;
const FILM: ThinFilm = ThinFilm::new(2.4, 300.0);

fn coated_sheet() -> Material {
    Material {
        name: "coated sheet".into(),
        kind: MaterialKind::Dielectric {
            dispersion: Dispersion::Constant(GLASS as f32),
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin: true,
            film: Some(FILM),
            roughness: 0.0,
        },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    }
}

/// The film's reflectance at normal incidence over a base of index `n2`
/// at `lambda_nm`, by the real-amplitude Airy sum (in f64).
fn airy_at_normal_incidence(n2: f64, lambda_nm: f64) -> f64 {
    let (n0, n1, d) = (1.0, f64::from(FILM.ior), f64::from(FILM.thickness_nm));
    let (r01, r12) = ((n0 - n1) / (n0 + n1), (n1 - n2) / (n1 + n2));
    let cos = (4.0 * std::f64::consts::PI * n1 * d / lambda_nm).cos();
    (r01 * r01 + r12 * r12 + 2.0 * r01 * r12 * cos) / (1.0 + r01 * r01 * r12 * r12 + 2.0 * r01 * r12 * cos)
}

/// What the coated sheet passes of light of `lambda_nm` met head on.
fn sheet_transmittance(lambda_nm: f64) -> f64 {
    let r = airy_at_normal_incidence(GLASS, lambda_nm);
    1.0 - 2.0 * r / (1.0 + r)
}

/// Each band's photons in `map` are the share `want[band]` of `photons`
/// emitted, within 5σ; `what` names the case (the backend, what the
/// photons did).
pub(crate) fn assert_band_shares(map: &PhotonMap, photons: u32, want: &[f64], what: &str) {
    for (band, &want) in want.iter().enumerate() {
        let got = map.photons.iter().filter(|p| usize::from(p.band) == band).count() as f64 / f64::from(photons);
        let sd = (want * (1.0 - want) / f64::from(photons)).sqrt();
        assert!((got - want).abs() < 5.0 * sd, "{what}, band {band}: {got:.4}, Airy's {want:.4}");
    }
}

/// A beam along +x met head on by a coated sheet (a disc) at x = 0.
fn photon_scene(photons: u32) -> PreparedScene {
    let disc = Shape::Disk { center: Vec3::ZERO, normal: Vec3::NEG_X, radius: 1.0, inner_radius: 0.0 };
    beam_onto_a_wall(photons, coated_sheet(), disc)
}

#[test]
fn each_band_passes_a_coated_sheet_by_the_airy_closed_form() {
    const PHOTONS: u32 = 20_000;
    let scene = photon_scene(PHOTONS);
    let bands = BandTable::new(BandSpec::Paper7);
    let expected: Vec<f64> = bands.bands().iter().map(|b| sheet_transmittance(f64::from(b.lambda_nm))).collect();
    // The film colours the light: the bands' shares are far apart.
    let (lo, hi) = expected.iter().fold((1.0f64, 0.0f64), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    assert!(hi - lo > 0.3, "the bands pass {expected:?}");
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        assert_band_shares(&map, PHOTONS, &expected, &format!("{name}, passed"));
        let s = &map.stats;
        assert!((s.flux_stored + s.flux_escaped - s.flux_emitted).abs() < 1e-4 * s.flux_emitted, "{name}: {s:?}");
    }
}

#[test]
fn a_view_through_a_coated_sheet_takes_the_colour_of_what_it_passes() {
    let scene = view_through_a_sheet(coated_sheet());
    // The white view ray splits into the bands, each passing its share.
    let expected: Vec3 =
        scene.bands.bands().iter().map(|b| b.weight * sheet_transmittance(f64::from(b.lambda_nm)) as f32).sum();
    let white: Vec3 = scene.bands.bands().iter().map(|b| b.weight).sum();
    assert!((white - Vec3::ONE).abs().max_element() < 1e-3, "the bands sum to white: {white}");
    assert!(expected.max_element() - expected.min_element() > 0.05, "the film tints the view: {expected}");
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, image) = frame(backend.as_mut(), &scene);
        let got = image.pixels[4];
        assert!((got - expected).abs().max_element() < 1e-4, "{name}: {got}, the closed form {expected}");
    }
}
