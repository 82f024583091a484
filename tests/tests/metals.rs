//! Metals (glTF's metallic materials) against closed forms on every
//! backend: Schlick's Fresnel of the base colour, per wavelength by its
//! reflectance spectrum, and the spread of a rough metal's GGX facets.
//!
//! At normal incidence the visible facet normals are distributed as
//! D(m) cos θm, under which tan²θm has the distribution x/(α² + x): half of
//! the facets lie within tan θm < α, and their reflections within 2·atan α
//! of the normal. Near the normal the masking a reflection survives
//! (G2/G1 = 1/(1 + Λ(ωi))) differs from 1 by at most α⁴, so half the light
//! lands within that cone.

use crate::roughness_maps::{assert_the_same_images, beam_at_a_square, lit_beside_the_camera};
use prismatic_core::geometry::texture::srgb_to_linear;
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::photon::{Photon, WHITE_BAND};
use prismatic_core::model::scene::{
    Camera, Filter, Light, Material, MaterialKind, Object, Sampler, Shape, Texture, ThinFilm, WavelengthSampling,
};
use prismatic_core::optics::metal::MetalOptics;
use prismatic_core::optics::surface::Surface;
use prismatic_core::{Backend, MetalColor, NamedMetal, PreparedScene, Scene, Vec3};
use prismatic_tests::backends::{every_backend, frame, trace};
use prismatic_tests::{
    TRIANGLE_WITH_UVS, UNIT_SPHERE, beam_onto_a_wall, one_material_scene_file, prepare, settings, view_through_a_sheet,
    white,
};

/// glTF's usual gold, in linear RGB.
pub(crate) const GOLD: Vec3 = Vec3::new(1.0, 0.766, 0.336);

fn metal(color: Vec3, roughness: f32) -> Material {
    Material {
        name: "metal".into(),
        kind: MaterialKind::Metal {
            color: MetalColor::Rgb(color),
            roughness,
            texture: None,
            film: None,
            metalness: Metalness::WHOLE,
        },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    }
}

/// Schlick's Fresnel of `f0` at incidence cosine `cos`, in f64.
pub(crate) fn schlick(f0: f64, cos: f64) -> f64 {
    f0 + (1.0 - f0) * (1.0 - cos).powi(5)
}

/// A beam of radius 0.2 along +x folded by `metal` (a disc at the origin
/// tilted 45°) onto a white wall at y = 3.
pub(crate) fn folded_beam(metal: Material, photons: u32, bands: BandSpec) -> Scene {
    let normal = Vec3::new(-1.0, 1.0, 0.0).normalize();
    let disc = Shape::Disk { center: Vec3::ZERO, normal, radius: 1.0, inner_radius: 0.0 };
    let mut scene = beam_onto_a_wall(photons, metal, disc).scene;
    scene.render.bands = bands;
    scene.objects[1].shape = Shape::Plane { point: Vec3::new(0.0, 3.0, 0.0), normal: Vec3::NEG_Y };
    scene
}

/// On every backend, the photons of [`folded_beam`] `scene` (of `photons`
/// emitted) that its disc sent on are all stored on the wall and are the
/// share `want` of them, within 5σ; `what` names the case.
pub(crate) fn assert_beam_goes_on(scene: &PreparedScene, photons: u32, want: f64, what: &str) {
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), scene);
        // The beam meets the disc first: direct light there, stored only on the wall.
        assert!(map.photons.iter().all(|p| p.pos().y > 2.9), "{name}, {what}: a photon stored off the wall");
        let got = map.photons.len() as f64 / f64::from(photons);
        let sd = (want * (1.0 - want) / f64::from(photons)).sqrt();
        assert!((got - want).abs() < 5.0 * sd, "{name}, {what}: {got:.4} went on, want {want:.4}");
    }
}

#[test]
fn a_grey_metal_reflects_schlicks_share_of_the_light() {
    const PHOTONS: u32 = 20_000;
    let scene = prepare(folded_beam(metal(Vec3::splat(0.6), 0.0), PHOTONS, BandSpec::Paper7));
    let want = schlick(0.6, std::f64::consts::FRAC_1_SQRT_2);
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        let got = map.photons.len() as f64 / f64::from(PHOTONS);
        let sd = (want * (1.0 - want) / f64::from(PHOTONS)).sqrt();
        assert!((got - want).abs() < 5.0 * sd, "{name}: {got:.4} reflected, Schlick's {want:.4}");
        // A grey metal keeps white light white.
        assert!(map.photons.iter().all(|p| p.band == prismatic_core::model::photon::WHITE_BAND), "{name}");
        let s = &map.stats;
        let balance = s.flux_stored + s.flux_absorbed + s.flux_escaped - s.flux_emitted;
        assert!(balance.abs() < 1e-4 * s.flux_emitted, "{name}: {s:?}");
    }
}

#[test]
fn gold_reflects_the_colour_of_its_fresnel_wavelength_by_wavelength() {
    const PHOTONS: u32 = 40_000;
    let mut scene = folded_beam(metal(GOLD, 0.0), PHOTONS, BandSpec::Physical(16));
    scene.render.wavelengths = WavelengthSampling::Continuous;
    let scene = prepare(scene);
    let cos = std::f64::consts::FRAC_1_SQRT_2;
    let want = [GOLD.x, GOLD.y, GOLD.z].map(|f0| schlick(f64::from(f0), cos));
    for mut backend in every_backend() {
        let mean = assert_reflected_colour(backend.as_mut(), &scene, PHOTONS, want);
        // Gold's blue is its weakest: far below its red.
        assert!(mean[2] < 0.5 * mean[0], "{}: {mean:?}", backend.name());
    }
}

/// On `backend`, the photons a chromatic metal in `scene` reflected of
/// `photons` white ones (each split into wavelengths there), each by its
/// own wavelength's colour: their mean per photon emitted is the light's
/// colour after the metal (white light's being (1, 1, 1)), `want` within
/// 5σ. Returns the mean.
fn assert_reflected_colour(backend: &mut dyn Backend, scene: &PreparedScene, photons: u32, want: [f64; 3]) -> [f64; 3] {
    let name = backend.name();
    let map = trace(backend, scene);
    assert!(map.photons.iter().all(|p| p.band != prismatic_core::model::photon::WHITE_BAND), "{name}");
    let n = f64::from(photons);
    let per_photon = map.stats.flux_emitted / n;
    let (mut sum, mut sum2) = ([0.0f64; 3], [0.0f64; 3]);
    for p in &map.photons {
        let rgb = scene.bands.rgb_of_flux(p.band, p.lambda_nm, p.flux).to_array();
        for c in 0..3 {
            let x = f64::from(rgb[c]) / per_photon;
            (sum[c], sum2[c]) = (sum[c] + x, sum2[c] + x * x);
        }
    }
    let mean = sum.map(|s| s / n);
    for c in 0..3 {
        let sd = ((sum2[c] / n - mean[c] * mean[c]) / n).sqrt();
        assert!((mean[c] - want[c]).abs() < 5.0 * sd + 1e-3, "{name}, channel {c}: {:.4} ± {sd:.4}, {want:?}", mean[c]);
    }
    mean
}

/// The exact Fresnel reflectance of a conductor of complex index n + ik
/// at incidence cosine `cos`, from the complex amplitudes r_s and r_p
/// (f64; the core's closed form is written differently).
fn conductor_fresnel(cos: f64, n: f64, k: f64) -> f64 {
    let sin2 = 1.0 - cos * cos;
    // η̃² = (n + ik)² and √(η̃² − sin²θ), as (re, im) pairs.
    let eta2 = (n * n - k * k, 2.0 * n * k);
    let (a, b) = (eta2.0 - sin2, eta2.1);
    let m = a.hypot(b);
    let root = (((m + a) / 2.0).sqrt(), b.signum() * ((m - a) / 2.0).sqrt());
    let norm2 = |(re, im): (f64, f64)| re * re + im * im;
    let div = |(a, b): (f64, f64), (c, d): (f64, f64)| (a * c + b * d, b * c - a * d);
    let rs = norm2(div((cos - root.0, -root.1), (cos + root.0, root.1))) / norm2((cos + root.0, root.1)).powi(2);
    let e = (eta2.0 * cos, eta2.1 * cos);
    let rp = norm2(div((e.0 - root.0, e.1 - root.1), (e.0 + root.0, e.1 + root.1)))
        / norm2((e.0 + root.0, e.1 + root.1)).powi(2);
    0.5 * (rs + rp)
}

#[test]
fn measured_gold_reflects_each_wavelength_by_its_complex_index() {
    const PHOTONS: u32 = 40_000;
    let gold = Material {
        name: "gold".into(),
        kind: MaterialKind::Metal {
            color: MetalColor::Measured(NamedMetal::Gold),
            roughness: 0.0,
            texture: None,
            film: None,
            metalness: Metalness::WHOLE,
        },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    };
    let mut scene = folded_beam(gold, PHOTONS, BandSpec::Physical(16));
    scene.render.wavelengths = WavelengthSampling::Continuous;
    let scene = prepare(scene);
    let colours = prismatic_core::model::wavelength_rgb::WavelengthRgb::new();
    let cos = std::f64::consts::FRAC_1_SQRT_2;
    // The light's colour after the metal: the mean over 380–780 nm of each
    // wavelength's colour times its reflectance (midpoints of 1/4 nm).
    let mut want = [0.0f64; 3];
    for i in 0..1600 {
        let lambda = 380.0 + (i as f32 + 0.5) / 4.0;
        let (n, k) = NamedMetal::Gold.optical_constants(lambda);
        let f = conductor_fresnel(cos, f64::from(n), f64::from(k)) / 1600.0;
        let rgb = colours.at(lambda).as_dvec3().to_array();
        (0..3).for_each(|c| want[c] += rgb[c] * f);
    }
    for mut backend in every_backend() {
        assert_reflected_colour(backend.as_mut(), &scene, PHOTONS, want);
    }
    // The closed form itself: head on, ((n − 1)² + k²)/((n + 1)² + k²) at ten wavelengths.
    for lambda in (0..10).map(|i| 400.0 + 35.0 * i as f32) {
        let (n, k) = NamedMetal::Gold.optical_constants(lambda);
        let head_on = f64::from(NamedMetal::Gold.normal_reflectance(lambda));
        assert!((conductor_fresnel(1.0, f64::from(n), f64::from(k)) - head_on).abs() < 1e-6, "{lambda}");
    }
}

/// A thin beam along +x from x = −1 meets a metal head on at x = 0 that
/// reflects every facet's light (F0 = 1); what it reflects lands on a
/// white wall at x = −3.
fn beam_at_a_rough_metal(roughness: f32, photons: u32) -> PreparedScene {
    let mut scene = folded_beam(metal(Vec3::ONE, roughness), photons, BandSpec::Paper7);
    scene.lights = vec![Light::Beam {
        position: Vec3::new(-1.0, 0.0, 0.0),
        direction: Vec3::X,
        radius: 1e-3,
        power: 1.0,
        spectrum: Default::default(),
    }];
    scene.objects = vec![
        Object {
            shape: Shape::Disk { center: Vec3::ZERO, normal: Vec3::NEG_X, radius: 1.0, inner_radius: 0.0 },
            material: 0,
        },
        Object { shape: Shape::Plane { point: Vec3::new(-3.0, 0.0, 0.0), normal: Vec3::X }, material: 1 },
    ];
    prepare(scene)
}

#[test]
fn half_of_a_rough_metals_light_lands_within_twice_the_arctangent_of_alpha() {
    const PHOTONS: u32 = 20_000;
    for roughness in [0.2f32, 0.4] {
        let alpha = f64::from(roughness * roughness);
        let radius = 3.0 * (2.0 * alpha.atan()).tan();
        let scene = beam_at_a_rough_metal(roughness, PHOTONS);
        for mut backend in every_backend() {
            let name = backend.name();
            let map = trace(backend.as_mut(), &scene);
            let inside = map
                .photons
                .iter()
                .filter(|p| f64::from(p.position[1]).hypot(f64::from(p.position[2])) < radius)
                .count() as f64
                / f64::from(PHOTONS);
            let sd = (0.25 / f64::from(PHOTONS)).sqrt();
            assert!((inside - 0.5).abs() < 5.0 * sd, "{name}, roughness {roughness}: {inside:.4} within {radius:.4}");
        }
    }
}

/// A camera on the x axis looking head on at `metal` (a disc at the origin
/// tilted 45°, normal (−1, 0, 1)/√2), which shows the background of
/// radiance 1 above it (3×3 pixels: the middle one sees the disc's centre).
pub(crate) fn metal_in_view(metal: Material) -> Scene {
    let mut render = settings(1000, BandSpec::Paper7);
    (render.width, render.height, render.background, render.ambient) = (3, 3, Vec3::ONE, 0.0);
    Scene {
        render,
        camera: Camera { position: Vec3::new(-5.0, 0.0, 0.0), look_at: Vec3::ZERO, up: Vec3::Z, fov_deg: 10.0 },
        lights: vec![Light::Point {
            position: Vec3::new(-5.0, 0.0, 5.0),
            power: 1.0,
            spectrum: Default::default(),
            range: None,
        }],
        materials: vec![metal, white("floor")],
        objects: vec![
            Object {
                shape: Shape::Disk {
                    center: Vec3::ZERO,
                    normal: Vec3::new(-1.0, 0.0, 1.0).normalize(),
                    radius: 2.0,
                    inner_radius: 0.0,
                },
                material: 0,
            },
            Object { shape: Shape::Plane { point: Vec3::new(0.0, 0.0, -3.0), normal: Vec3::Z }, material: 1 },
        ],
    }
}

#[test]
fn a_metal_in_view_shows_its_fresnel_colour_and_a_slightly_rough_one_nearly_so() {
    let cos = std::f64::consts::FRAC_1_SQRT_2;
    let want = Vec3::from_array([GOLD.x, GOLD.y, GOLD.z].map(|f0| schlick(f64::from(f0), cos) as f32));
    for (roughness, tolerance) in [(0.0f32, 1e-4f32), (0.05, 1e-2)] {
        let scene = prepare(metal_in_view(metal(GOLD, roughness)));
        for mut backend in every_backend() {
            let name = backend.name();
            let (_, image) = frame(backend.as_mut(), &scene);
            let got = image.pixels[4];
            assert!((got - want).abs().max_element() < tolerance, "{name}, roughness {roughness}: {got}, {want}");
        }
    }
}

/// GGX's D and Smith's height-correlated G2 for width `alpha`, in f64 from
/// their textbook forms (Walter et al. 2007; Heitz 2014), at the cosines
/// of the half vector, the view and the light to the normal.
fn ggx_d_g2(alpha: f64, cos_h: f64, cos_o: f64, cos_i: f64) -> (f64, f64) {
    let a2 = alpha * alpha;
    let d = a2 / (std::f64::consts::PI * (cos_h * cos_h * (a2 - 1.0) + 1.0).powi(2));
    let lambda = |c: f64| (-1.0 + (1.0 + a2 * (1.0 - c * c) / (c * c)).sqrt()) / 2.0;
    (d, 1.0 / (1.0 + lambda(cos_o) + lambda(cos_i)))
}

/// The disc of [`metal_in_view`] alone under a black sky, its normal
/// pointing at the point light: the pixel is the light's highlight, the
/// BRDF D G2 F / (4 cos θo cos θi) times the irradiance P/(4π d²).
#[test]
fn a_rough_metal_shows_a_point_lights_highlight_by_the_ggx_closed_form() {
    let roughness = 0.5f64;
    let mut scene = metal_in_view(metal(GOLD, roughness as f32));
    scene.render.background = Vec3::ZERO;
    scene.objects.truncate(1);
    let Light::Point { power, .. } = &mut scene.lights[0] else { unreachable!() };
    *power = 1000.0;
    let scene = prepare(scene);
    let (n, wo) = (glam::DVec3::new(-1.0, 0.0, 1.0).normalize(), glam::DVec3::NEG_X);
    let h = (wo + n).normalize();
    let (d, g2) = ggx_d_g2(roughness * roughness, h.dot(n), wo.dot(n), 1.0);
    let irradiance = 1000.0 / (4.0 * std::f64::consts::PI * 50.0);
    let brdf = d * g2 / (4.0 * wo.dot(n));
    let want = Vec3::from_array(
        [GOLD.x, GOLD.y, GOLD.z].map(|f0| (schlick(f64::from(f0), wo.dot(h)) * brdf * irradiance) as f32),
    );
    assert!(want.x > 0.1, "a visible highlight: {want}");
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, image) = frame(backend.as_mut(), &scene);
        let got = image.pixels[4];
        assert!(((got - want) / want).abs().max_element() < 1e-3, "{name}: {got}, the closed form {want}");
    }
}

/// A metal's colour texture (glTF's `baseColorTexture` of a metal): one
/// row of sRGB texels, read nearest.
fn colours(texels: &[[u8; 3]]) -> Texture {
    Texture {
        name: "base colour".into(),
        width: texels.len() as u32,
        height: 1,
        texels: texels
            .iter()
            .map(|&[r, g, b]| u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16)
            .collect::<Vec<_>>()
            .into(),
        sampler: Sampler { filter: Filter::Nearest, ..Sampler::default() },
    }
}

/// The linear colour of an sRGB texel.
fn linear(texel: [u8; 3]) -> Vec3 {
    Vec3::from_array(texel.map(|c| srgb_to_linear(u32::from(c))))
}

/// A metal of colour `color` and roughness 0.3, its colour scaled by `texture`.
fn textured(color: Vec3, texture: Option<Texture>) -> Material {
    let kind = MaterialKind::Metal {
        color: MetalColor::Rgb(color),
        roughness: 0.3,
        texture,
        film: None,
        metalness: Metalness::WHOLE,
    };
    Material::new("metal", kind)
}

/// A beam meets a metal of colour (1, 0.9, 0.8) under a texture of two
/// texels, orange (u < ½) and blue (u > ½): on each it reflects as the
/// untextured metal of the colour times that texel does (the same
/// photons, flux and bands: white light splits there, as at any coloured
/// metal), on every backend.
#[test]
fn a_metals_colour_texture_is_its_reflectance_texel_by_texel() {
    const PHOTONS: u32 = 4_000;
    let (factor, texels) = (Vec3::new(1.0, 0.9, 0.8), [[230, 90, 20], [40, 120, 220]]);
    for mut backend in every_backend() {
        let name = backend.name();
        let mut maps = Vec::new();
        for (z, texel) in [(-0.5, texels[0]), (0.5, texels[1])] {
            let mut photons = |metal: Material| {
                let mut map = trace(backend.as_mut(), &beam_at_a_square(metal, z, PHOTONS));
                map.photons.sort_by_key(|p| p.key());
                map.photons
            };
            let got = photons(textured(factor, Some(colours(&texels))));
            let want = photons(textured(factor * linear(texel), None));
            assert!(got.len() > PHOTONS as usize / 2, "{name}, texel {texel:?}: {} photons reflected", got.len());
            assert_eq!(got.len(), want.len(), "{name}, texel {texel:?}: photons reflected");
            for (g, w) in got.iter().zip(&want) {
                assert_eq!(g.key(), w.key(), "{name}, texel {texel:?}");
                assert!(
                    (g.pos() - w.pos()).length() < 1e-5 && g.flux == w.flux,
                    "{name}, texel {texel:?}: {g:?} vs {w:?}"
                );
            }
            maps.push(got);
        }
        // The two texels reflect differently (the test sees the texture).
        let count = |map: &[Photon], nm: std::ops::Range<f32>| map.iter().filter(|p| nm.contains(&p.lambda_nm)).count();
        let (red, blue) = (600.0..780.0, 380.0..480.0);
        assert!(count(&maps[0], red.clone()) > 2 * count(&maps[1], red), "{name}: the orange texel reflects red");
        assert!(count(&maps[1], blue.clone()) > 2 * count(&maps[0], blue), "{name}: the blue texel reflects blue");
    }
}

/// Seen by the camera, a metal under a texture of one texel is the metal
/// of its colour times that texel: its reflection of a lit grey wall and,
/// rough, its highlight of a point light, on every backend.
#[test]
fn in_view_a_metals_colour_texture_is_the_colour_it_scales_to() {
    let (factor, texel) = (Vec3::new(0.9, 1.0, 0.7), [200, 150, 60]);
    for roughness in [0.0f32, 0.5] {
        let lit = |texture: Option<Texture>, color: Vec3| {
            let kind = MaterialKind::Metal {
                color: MetalColor::Rgb(color),
                roughness,
                texture,
                film: None,
                metalness: Metalness::WHOLE,
            };
            let mut scene = view_through_a_sheet(Material::new("metal", kind)).scene;
            scene.materials[1] = white("grey wall");
            prepare(lit_beside_the_camera(scene))
        };
        let (textured, plain) = (lit(Some(colours(&[texel])), factor), lit(None, factor * linear(texel)));
        assert_the_same_images(&format!("roughness {roughness}"), &textured, &plain, 0.05);
    }
}

/// A scene file colours a metal with a `texture` (sRGB, beside it; its
/// `color`, white unless given, scales it) and coats it with a film
/// (`film_thickness_nm`, `film_ior`); a measured metal, whose colour is
/// its optical constants, and a shape without texture coordinates refuse
/// a texture with its key.
#[test]
fn scene_files_give_metals_textures_and_films() {
    let dir = tempfile::tempdir().unwrap();
    image::RgbImage::from_raw(1, 1, vec![200, 150, 60]).unwrap().save(dir.path().join("brass.png")).unwrap();
    let check = |material: &str, shape: &str| one_material_scene_file(dir.path(), material, shape);
    let (quad, sphere) = (TRIANGLE_WITH_UVS, UNIT_SPHERE);
    let brass = "kind = \"metal\"\nroughness = 0.4\ntexture = \"brass.png\"\ntexture_filter = \"nearest\"";
    for (material, color) in
        [(brass.to_string(), Vec3::ONE), (format!("{brass}\ncolor = [1, 0.5, 0.5]"), Vec3::new(1.0, 0.5, 0.5))]
    {
        let doc = check(&material, quad).unwrap_or_else(|e| panic!("{e}"));
        let MaterialKind::Metal { color: MetalColor::Rgb(c), texture: Some(t), .. } = &doc.scene.materials[0].kind
        else {
            panic!("{material}: a textured metal: {:?}", doc.scene.materials[0].kind)
        };
        assert_eq!((*c, t.texels[0], t.sampler.filter), (color, 200 | 150 << 8 | 60 << 16, Filter::Nearest));
    }
    let doc = check("kind = \"metal\"\ncolor = \"aluminium\"\nfilm_thickness_nm = 250\nfilm_ior = 1.65", sphere)
        .unwrap_or_else(|e| panic!("{e}"));
    let MaterialKind::Metal { film, .. } = &doc.scene.materials[0].kind else { panic!("a metal") };
    assert_eq!(*film, Some(OXIDE));
    for (material, shape, key, reason) in [
        (format!("{brass}\ncolor = \"gold\""), quad, "material.m.texture", "measured optical constants"),
        (brass.replace("brass.png", "missing.png"), quad, "material.m.texture", "cannot read texture"),
        (brass.to_string(), sphere, "object[0].material", "texture"),
        ("kind = \"metal\"\ntexture_wrap = \"repeat\"".to_string(), quad, "material.m.texture_wrap", "names none"),
        ("kind = \"metal\"\nroughness = 0.4".to_string(), quad, "material.m.color", ""),
        ("kind = \"metal\"\ncolor = \"gold\"\nfilm_ior = 1.5".to_string(), quad, "material.m.film_ior", "thickness"),
        (
            "kind = \"metal\"\ncolor = \"gold\"\nfilm_thickness_nm = -3".to_string(),
            quad,
            "material.m.film_thickness_nm",
            "0 to",
        ),
    ] {
        let e = check(&material, shape).map(|_| ()).unwrap_err();
        assert!(e.key == key && e.reason.contains(reason), "{material} / {shape}: {e}");
    }
}

/// A polished metal under a film of oxide (`KHR_materials_iridescence` on
/// a metal): measured aluminium under 250 nm of index 1.65, and an RGB
/// steel (F0 0.56) under 120 nm of index 2.2, each the metal of the
/// disc that folds the beam at 45°.
fn filmed(color: MetalColor, film: ThinFilm) -> Material {
    Material::new(
        "filmed",
        MaterialKind::Metal { color, roughness: 0.0, texture: None, film: Some(film), metalness: Metalness::WHOLE },
    )
}

const OXIDE: ThinFilm = ThinFilm::new(1.65, 250.0);
const TEMPER: ThinFilm = ThinFilm::new(2.2, 120.0);

/// A film on a metal colours its reflection wavelength by wavelength by
/// the Airy sum of the film over the metal's complex index (the core's
/// `ThinFilm::reflectance_on`, held to Born & Wolf's characteristic
/// matrix): the photons a polished filmed metal reflects at 45° carry
/// the light's colour times it, on every backend; the film changes it
/// (the bare metal's colour is far from it).
#[test]
fn a_film_on_a_metal_colours_its_reflection_by_the_airy_sum() {
    const PHOTONS: u32 = 40_000;
    let colours = prismatic_core::model::wavelength_rgb::WavelengthRgb::new();
    let cos = std::f32::consts::FRAC_1_SQRT_2;
    let mut want = [0.0f64; 3];
    let mut bare = [0.0f64; 3];
    for i in 0..1600 {
        let lambda = 380.0 + (i as f32 + 0.5) / 4.0;
        let base = NamedMetal::Aluminium.optical_constants(lambda);
        let f = f64::from(OXIDE.reflectance_on(cos, 1.0, base, lambda)) / 1600.0;
        let b = conductor_fresnel(f64::from(cos), f64::from(base.0), f64::from(base.1)) / 1600.0;
        let rgb = colours.at(lambda).as_dvec3().to_array();
        (0..3).for_each(|c| (want[c], bare[c]) = (want[c] + rgb[c] * f, bare[c] + rgb[c] * b));
    }
    let distance = (0..3).map(|c| (want[c] - bare[c]).abs()).fold(0.0, f64::max);
    assert!(distance > 0.05, "the film barely changes aluminium's colour: {want:?} vs {bare:?}");
    let mut scene =
        folded_beam(filmed(MetalColor::Measured(NamedMetal::Aluminium), OXIDE), PHOTONS, BandSpec::Physical(16));
    scene.render.wavelengths = WavelengthSampling::Continuous;
    let scene = prepare(scene);
    for mut backend in every_backend() {
        assert_reflected_colour(backend.as_mut(), &scene, PHOTONS, want);
    }
}

/// Seen by the camera, a polished filmed metal shows the background of
/// radiance 1 in the colour Σ C_b R(λ_b) of its film's reflectance at
/// each band's wavelength (the core's `MetalOptics::tint` of white
/// light), on every backend: measured aluminium under an oxide, and an
/// RGB steel under a temper film.
#[test]
fn a_filmed_metal_in_view_shows_its_films_colour() {
    for color in [MetalColor::Measured(NamedMetal::Aluminium), MetalColor::Rgb(Vec3::splat(0.56))] {
        let film = if matches!(color, MetalColor::Rgb(_)) { TEMPER } else { OXIDE };
        let scene = prepare(metal_in_view(filmed(color, film)));
        let Surface::Metal(optics) = &scene.surfaces[0] else { panic!("a metal") };
        let cos = std::f32::consts::FRAC_1_SQRT_2;
        let want = optics.tint(cos, WHITE_BAND, 0.0, &scene.bands);
        let bare = MetalOptics { film: None, ..*optics }.tint(cos, WHITE_BAND, 0.0, &scene.bands);
        assert!((want - bare).abs().max_element() > 0.03, "{color:?}: the film changes nothing: {want} vs {bare}");
        for mut backend in every_backend() {
            let name = backend.name();
            let (_, image) = frame(backend.as_mut(), &scene);
            let got = image.pixels[4];
            assert!((got - want).abs().max_element() < 1e-4, "{color:?}, {name}: {got}, {want}");
        }
    }
}
