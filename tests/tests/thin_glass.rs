//! Thin-walled glass (glTF's transmission without a volume) against its
//! closed form, on every backend: a sheet reflects R_s = 2R/(1+R) (both
//! faces and every bounce between them) and passes T_s = (1−R)/(1+R)
//! straight on, with no offset, whatever its shape; a tinted sheet keeps
//! its colour of what crosses it.

use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::scene::{Attenuation, Material, MaterialKind, Shape};
use prismatic_core::optics::surface::Surface;
use prismatic_core::{PreparedScene, Scene, Vec3};
use prismatic_tests::backends::{every_backend, frame, trace};
use prismatic_tests::{beam_onto_a_wall, prepare, view_through_a_sheet};

/// The sheet's index.
const IOR: f64 = 1.5;

fn sheet(ior: f32) -> Material {
    Material {
        name: "sheet".into(),
        kind: MaterialKind::Dielectric {
            dispersion: Dispersion::Constant(ior),
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin: true,
            film: None,
            roughness: 0.0,
        },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    }
}

/// Unpolarised Fresnel reflectance of one face at incidence cosine `c`.
fn face_reflectance(c: f64, n: f64) -> f64 {
    let t = (1.0 - (1.0 - c * c) / (n * n)).sqrt();
    let rs = (c - n * t) / (c + n * t);
    let rp = (t - n * c) / (t + n * c);
    0.5 * (rs * rs + rp * rp)
}

/// What a sheet passes at incidence cosine `c`: (1 − R)/(1 + R).
fn sheet_transmittance(c: f64, n: f64) -> f64 {
    let r = face_reflectance(c, n);
    (1.0 - r) / (1.0 + r)
}

/// The beam's radius.
const BEAM: f32 = 0.2;

/// A beam along +x through a sheet (a disc, an open shape) tilted 30° at
/// x = 0 onto a white wall at x = 3.
fn photon_scene(photons: u32) -> PreparedScene {
    let tilt = 30f32.to_radians();
    let normal = Vec3::new(tilt.cos(), tilt.sin(), 0.0);
    beam_onto_a_wall(
        photons,
        sheet(IOR as f32),
        Shape::Disk { center: Vec3::ZERO, normal, radius: 1.0, inner_radius: 0.0 },
    )
}

#[test]
fn a_sheet_passes_its_closed_form_fraction_of_photons_straight_on() {
    const PHOTONS: u32 = 20_000;
    let scene = photon_scene(PHOTONS);
    let expected = sheet_transmittance(30f64.to_radians().cos(), IOR);
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        let got = map.photons.len() as f64 / f64::from(PHOTONS);
        let sd = (expected * (1.0 - expected) / f64::from(PHOTONS)).sqrt();
        assert!((got - expected).abs() < 5.0 * sd, "{name}: {got:.4} passed, the sheet's closed form {expected:.4}");
        // Straight on: every photon lands inside the beam's own footprint.
        for p in &map.photons {
            let [x, y, z] = p.position;
            assert!(
                (x - 3.0).abs() < 1e-4 && y.hypot(z) <= BEAM * (1.0 + 1e-4),
                "{name}: a photon at {:?}",
                p.position
            );
        }
        let s = &map.stats;
        assert!((s.flux_stored + s.flux_escaped - s.flux_emitted).abs() < 1e-4 * s.flux_emitted, "{name}: {s:?}");
    }
}

/// [`view_through_a_sheet`] of the clear sheet.
fn view_scene() -> PreparedScene {
    view_through_a_sheet(sheet(IOR as f32))
}

#[test]
fn a_view_through_a_sheet_keeps_its_closed_form_fraction() {
    let scene = view_scene();
    let expected = sheet_transmittance(1.0, IOR) as f32;
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, image) = frame(backend.as_mut(), &scene);
        let got = image.pixels[4];
        assert!((got - Vec3::splat(expected)).abs().max_element() < 1e-4, "{name}: {got}, the closed form {expected}");
    }
}

/// What a tinted sheet keeps of white light in one crossing (glTF's base
/// colour of thin-walled glass).
const TINT: Vec3 = Vec3::new(0.8, 0.45, 0.15);

fn tinted(mut scene: Scene) -> PreparedScene {
    let MaterialKind::Dielectric { attenuation, .. } = &mut scene.materials[0].kind else { unreachable!() };
    *attenuation = Some(Attenuation { color: TINT, distance: 1.0 });
    prepare(scene)
}

#[test]
fn a_tinted_sheet_keeps_its_colour_of_what_crosses_it() {
    // Seen straight through: T_s times the tint, per channel.
    let scene = tinted(view_scene().scene);
    let expected = TINT * sheet_transmittance(1.0, IOR) as f32;
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, image) = frame(backend.as_mut(), &scene);
        let got = image.pixels[4];
        assert!((got - expected).abs().max_element() < 1e-4, "{name}: {got}, the closed form {expected}");
    }
    // Photons: each band passes T_s times its crossing's share (the
    // absorption of the band's colour), and no white photon crosses.
    const PHOTONS: u32 = 20_000;
    let scene = tinted(photon_scene(PHOTONS).scene);
    let Surface::Dielectric(glass) = &scene.surfaces[0] else { unreachable!() };
    let t_s = sheet_transmittance(30f64.to_radians().cos(), IOR);
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        for band in 0..scene.bands.len() as u16 {
            let expected = t_s * f64::from(glass.sheet_crossing(band));
            let got = map.photons.iter().filter(|p| p.band == band).count() as f64 / f64::from(PHOTONS);
            let sd = (expected * (1.0 - expected) / f64::from(PHOTONS)).sqrt();
            assert!((got - expected).abs() < 5.0 * sd, "{name}, band {band}: {got:.4}, expected {expected:.4}");
        }
        let s = &map.stats;
        let accounted = s.flux_stored + s.flux_escaped + s.flux_absorbed;
        assert!((accounted - s.flux_emitted).abs() < 1e-4 * s.flux_emitted, "{name}: {s:?}");
    }
}
