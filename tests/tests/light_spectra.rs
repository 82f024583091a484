//! Lights with spectra: photons' wavelengths drawn from what the light
//! emits (a lamp's photons on its lines, none between), their colours from
//! their wavelengths, and the light's colour in its direct light.

use prismatic_core::model::scene::WhitePoint;
use prismatic_core::model::spectrum::{Lamp, Spectrum};
use prismatic_core::{BandSpec, Glass, Light, PreparedScene, RenderSettings, WavelengthSampling};
use prismatic_tests::backends::{every_backend, trace};
use prismatic_tests::{PrismExperiment, prepare, settings};

/// `exp`'s prism scene lit by `spectrum`, with `sampling`.
fn prism_lit_by(exp: &PrismExperiment, spectrum: Spectrum, sampling: WavelengthSampling) -> PreparedScene {
    let render = RenderSettings { wavelengths: sampling, ..settings(20_000, BandSpec::Physical(16)) };
    let mut scene = exp.scene(Glass::Bk7.dispersion(), render);
    *scene.lights[0].spectrum_mut() = spectrum;
    prepare(scene)
}

/// A mercury lamp through a 60° BK7 prism: every photon on one of the
/// lamp's lines (none between), its 435.8 nm and 546.1 nm lines at
/// Snell's deviation within 0.05°, in proportion to the lines' powers.
#[test]
fn a_mercury_lamp_through_a_prism_puts_its_lines_at_snells_deviation() {
    let exp = PrismExperiment { apex_deg: 60.0, incidence_deg: 55.0, beam_radius: 0.02, screen_x: 6.0 };
    let lines: Vec<f32> = Lamp::Mercury.lines().iter().map(|l| l.0).collect();
    let glass = Glass::Bk7.dispersion();
    for sampling in [WavelengthSampling::Continuous, WavelengthSampling::Hero] {
        let scene = prism_lit_by(&exp, Spectrum::Lamp(Lamp::Mercury), sampling);
        for mut backend in every_backend() {
            let name = backend.name();
            let map = trace(backend.as_mut(), &scene);
            let mut per_line = vec![0u32; lines.len()];
            for p in map.photons.iter().filter(|p| p.bounces == 2) {
                let lambda = p.wavelength().expect("a lamp's photons have wavelengths");
                let k = lines.iter().position(|&l| l == lambda);
                let k = k.unwrap_or_else(|| panic!("{name} {sampling:?}: a photon at {lambda} nm, between lines"));
                per_line[k] += 1;
                let d = p.direction();
                let got = (exp.beam_angle() - f64::from(d.y).atan2(f64::from(d.x))).to_degrees();
                let expected = exp.deviation_deg(f64::from(glass.ior_at(lambda).unwrap())).unwrap();
                assert!(
                    (got - expected).abs() < 0.05,
                    "{name} {sampling:?}: {lambda} nm at {got:.4}°, Snell {expected:.4}°"
                );
            }
            // 435.8 nm (power 4000 of 7570) and 546.1 nm (1100) are there.
            let total: u32 = per_line.iter().sum();
            assert!(total > 10_000, "{name} {sampling:?}: {total} photons through");
            let share = |k: usize| f64::from(per_line[k]) / f64::from(total);
            assert!((share(2) - 4000.0 / 7570.0).abs() < 0.02, "{name} {sampling:?}: {per_line:?}");
            assert!((share(3) - 1100.0 / 7570.0).abs() < 0.02, "{name} {sampling:?}: {per_line:?}");
        }
    }
}

/// A white wall under a spot light with spectrum `spectrum`, with white
/// point `white_point`: the wall's colour in the image's centre, on `backend`.
fn wall_colour(
    backend: &mut dyn prismatic_core::Backend,
    spectrum: Spectrum,
    white_point: WhitePoint,
) -> prismatic_core::Vec3 {
    use prismatic_core::{NoProgress, Object, Scene, Shape, Vec3};
    let render = RenderSettings { width: 16, height: 16, ambient: 0.0, white_point, ..RenderSettings::default() };
    let mut camera = prismatic_tests::camera();
    (camera.position, camera.look_at) = (Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO);
    let scene = Scene {
        render,
        camera,
        lights: vec![Light::Spot {
            position: Vec3::new(0.0, 0.0, 3.0),
            direction: Vec3::NEG_Z,
            cone_deg: 30.0,
            inner_cone_deg: 30.0,
            power: 50.0,
            spectrum,
            range: None,
        }],
        materials: vec![prismatic_tests::white("wall")],
        objects: vec![Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Z }, material: 0 }],
    };
    let mut render = backend.prepare(&prepare(scene)).expect("prepare");
    render.run_pass(0, &mut NoProgress).expect("pass");
    let image = render.image().expect("image");
    image.pixels[8 * 16 + 8]
}

/// The CIE 1931 chromaticity the renderer's linear RGB stands for: the
/// colour of the equal-energy spectrum is (1, 1, 1), so each channel is
/// first scaled back by the equal-energy light's sRGB.
fn chromaticity_of(rgb: prismatic_core::Vec3) -> (f64, f64) {
    use prismatic_core::model::{cie, color};
    let (lo, hi) = prismatic_core::model::bands::VISIBLE_NM;
    let white = color::xyz_to_linear_srgb(cie::integrate(f64::from(lo), f64::from(hi)));
    let xyz = color::XYZ_TO_LINEAR_SRGB.inverse() * (rgb.as_dvec3() * white);
    (xyz.x / xyz.element_sum(), xyz.y / xyz.element_sum())
}

/// The spectrum's own chromaticity over the visible range it emits in.
fn chromaticity_of_spectrum(spectrum: &Spectrum) -> (f64, f64) {
    let mut xyz = glam::DVec3::ZERO;
    for k in 0..4000 {
        let nm = 380.0 + (f64::from(k) + 0.5) * 0.1;
        xyz += prismatic_core::model::cie::cmf(nm) * spectrum.power_at(nm);
    }
    (xyz.x / xyz.element_sum(), xyz.y / xyz.element_sum())
}

/// The renderer's linear RGB of light with CIE 1931 chromaticity (x, y)
/// and the channel sum `sum`: the inverse of [`chromaticity_of`].
fn rgb_of_chromaticity((x, y): (f64, f64), sum: f32) -> prismatic_core::Vec3 {
    use prismatic_core::model::{cie, color};
    let (lo, hi) = prismatic_core::model::bands::VISIBLE_NM;
    let white = color::xyz_to_linear_srgb(cie::integrate(f64::from(lo), f64::from(hi)));
    let rgb = (color::XYZ_TO_LINEAR_SRGB * glam::DVec3::new(x, y, 1.0 - x - y)) / white;
    (rgb * (f64::from(sum) / rgb.element_sum())).as_vec3()
}

/// A blackbody's direct light on a white wall has the blackbody's CIE
/// chromaticity (within 0.002 in x and y, and ΔE00 < 1 against the colour
/// of that chromaticity at the wall's brightness, both shown at a
/// brightest channel of 0.8), an equal-energy light's is neutral, on
/// every backend.
#[test]
fn a_lights_colour_on_a_white_wall_is_its_spectrums() {
    use prismatic_cli::study::metrics::{ciede2000, lab};
    for mut backend in every_backend() {
        let name = backend.name();
        for spectrum in [
            Spectrum::Blackbody { kelvin: 2700.0 },
            Spectrum::Blackbody { kelvin: 6500.0 },
            Spectrum::Illuminant(prismatic_core::model::spectrum::Illuminant::F11),
        ] {
            let wall = wall_colour(backend.as_mut(), spectrum.clone(), WhitePoint::E);
            let (x, y) = chromaticity_of(wall);
            let (ex, ey) = chromaticity_of_spectrum(&spectrum);
            assert!(
                (x - ex).abs() < 2e-3 && (y - ey).abs() < 2e-3,
                "{name} {spectrum}: ({x:.4}, {y:.4}) vs ({ex:.4}, {ey:.4})"
            );
            let expected = rgb_of_chromaticity((ex, ey), wall.element_sum());
            let shown = 0.8 / wall.max_element().max(expected.max_element());
            let tone_map = prismatic_core::model::color::ToneMap::Clamp;
            let delta_e = ciede2000(lab(wall * shown, tone_map), lab(expected * shown, tone_map));
            assert!(delta_e < 1.0, "{name} {spectrum}: ΔE00 {delta_e:.3} ({wall} vs {expected})");
        }
        let white = wall_colour(backend.as_mut(), Spectrum::EqualEnergy, WhitePoint::E);
        assert!(white.x > 0.0 && white.x == white.y && white.y == white.z, "{name}: {white}");
    }
}

/// The white point is a setting: a D65 light renders neutral with
/// `white_point = "D65"` (within 1e-3 of its mean per channel) and blue
/// with the default E; an E light warm with D65 and neutral with E.
#[test]
fn a_light_whose_spectrum_is_the_white_point_renders_neutral() {
    let d65 = Spectrum::Illuminant(prismatic_core::model::spectrum::Illuminant::D65);
    let spread = |c: prismatic_core::Vec3| {
        (c - prismatic_core::Vec3::splat(c.element_sum() / 3.0)).abs().max_element() / c.element_sum() * 3.0
    };
    for mut backend in every_backend() {
        let name = backend.name();
        let neutral = wall_colour(backend.as_mut(), d65.clone(), WhitePoint::D65);
        assert!(spread(neutral) < 1e-3, "{name}: D65 under a D65 white point is {neutral}");
        let blue = wall_colour(backend.as_mut(), d65.clone(), WhitePoint::E);
        assert!(blue.z > 1.05 * blue.x, "{name}: D65 under an E white point is {blue}");
        let warm = wall_colour(backend.as_mut(), Spectrum::EqualEnergy, WhitePoint::D65);
        assert!(warm.x > 1.05 * warm.z, "{name}: E under a D65 white point is {warm}");
    }
}

/// A sodium lamp's light through a glass sphere onto a green floor, seen
/// from below the sphere (the floor only), as `render` renders it: the
/// image after two passes on `backend`.
fn sodium_on_green(backend: &mut dyn prismatic_core::Backend, render: RenderSettings) -> prismatic_core::Image {
    use prismatic_core::model::scene::MaterialKind;
    use prismatic_core::{Material, NoProgress, Object, Scene, Shape, Vec3};
    let camera =
        prismatic_core::Camera { position: Vec3::new(0.0, 0.6, 0.0), look_at: Vec3::ZERO, up: Vec3::Z, fov_deg: 90.0 };
    let green = Material {
        name: "green".into(),
        kind: MaterialKind::Diffuse {
            albedo: Vec3::new(0.1, 0.7, 0.2),
            checker: None,
            texture: None,
            emission: Vec3::ZERO,
        },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    };
    let scene = Scene {
        render,
        camera,
        lights: vec![Light::Spot {
            position: Vec3::new(0.0, 4.0, 0.0),
            direction: Vec3::NEG_Y,
            cone_deg: 20.0,
            inner_cone_deg: 20.0,
            power: 40.0,
            spectrum: Spectrum::Lamp(Lamp::Sodium),
            range: None,
        }],
        materials: vec![green, prismatic_tests::glass("glass", Glass::Bk7.dispersion())],
        objects: vec![
            Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 },
            Object { shape: Shape::Sphere { center: Vec3::new(0.0, 1.6, 0.0), radius: 0.5 }, material: 1 },
        ],
    };
    let mut render = backend.prepare(&prepare(scene)).expect("prepare");
    for pass in 0..2 {
        render.run_pass(pass, &mut NoProgress).expect("pass");
    }
    render.image().expect("image")
}

/// Under a line lamp every surface takes the lamp's hue, whatever its
/// albedo: a sodium lamp's direct light and its caustic under a glass
/// sphere, light traced and gathered, on a green floor have the lamp's CIE
/// chromaticity (within 0.002 in x and y) on every backend, where the RGB
/// product of the lamp's colour and the albedo would be green. The
/// albedo's reflectance spectrum meets the lamp's lines.
#[test]
fn a_line_lamp_gives_a_coloured_surface_its_own_hue() {
    let mut xyz = glam::DVec3::ZERO;
    for &(nm, power) in Lamp::Sodium.lines() {
        xyz += prismatic_core::model::cie::cmf(f64::from(nm)) * f64::from(power);
    }
    let (ex, ey) = (xyz.x / xyz.element_sum(), xyz.y / xyz.element_sum());
    for mut backend in every_backend() {
        let name = backend.name();
        for light_tracing in [true, false] {
            let render = RenderSettings {
                width: 24,
                height: 24,
                photons: 20_000,
                radius: 0.05,
                ambient: 0.0,
                light_tracing,
                ..RenderSettings::default()
            };
            let image = sodium_on_green(backend.as_mut(), render);
            let brightest = image.pixels.iter().map(|p| p.element_sum()).fold(0.0, f32::max);
            let lit: Vec<_> = image.pixels.iter().filter(|p| p.element_sum() > 0.05 * brightest).collect();
            assert!(lit.len() > 100, "{name}: {} lit pixels", lit.len());
            for p in lit {
                let (x, y) = chromaticity_of(*p);
                assert!(
                    (x - ex).abs() < 2e-3 && (y - ey).abs() < 2e-3,
                    "{name}, light tracing {light_tracing}: {p} is ({x:.4}, {y:.4}), sodium ({ex:.4}, {ey:.4})"
                );
            }
        }
    }
}
