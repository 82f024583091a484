//! Light tracing: the caustic photons the camera sees directly, connected
//! to the camera (`prismatic_core::photons::light_tracing`), and only the rest gathered;
//! its error falls as 1/√N (unbiased, no radius); and combined with the
//! gather behind mirrors and glass, no path is counted twice.

use prismatic_conformance::compare::{caustic_of, caustic_rel_rmse};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::Dispersion;
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{Camera, Light, Material, MaterialKind, Object, Shape, ViewPaths};
use prismatic_core::photons::light_tracing::splat_photons;
use prismatic_core::{Backend, MetalColor, NoProgress, PreparedScene, ReferenceBackend, Render, Scene, Vec3};
use prismatic_cpu::CpuBackend;
use prismatic_tests::backends::{every_backend, image_after};
use prismatic_tests::{builtin, prepare, settings, white};

/// Built-in scene `name` at `size`² pixels, `photons` a pass, light tracing on or off.
fn scene(name: &str, size: u32, photons: u32, light_tracing: bool) -> PreparedScene {
    builtin(name, |r| (r.width, r.height, r.photons, r.light_tracing) = (size, size, photons, light_tracing))
}

/// A render of `scene` on `backend` with passes `passes`.
fn render(backend: &mut dyn Backend, scene: &PreparedScene, passes: std::ops::Range<u32>) -> Box<dyn Render> {
    let name = backend.name();
    let mut render = backend.prepare(scene).unwrap_or_else(|e| panic!("{name}: prepare: {e}"));
    for k in passes {
        render.run_pass(k, &mut NoProgress).unwrap_or_else(|e| panic!("{name}: pass {k}: {e}"));
    }
    render
}

/// The caustic alone of a render's image.
fn caustic(render: &mut dyn Render) -> Vec<f64> {
    caustic_of(&render.image().unwrap(), &render.base().unwrap())
}

/// relRMSE over the caustic, which the reference must have.
fn rel_rmse(got: &[f64], reference: &[f64]) -> f64 {
    let error = caustic_rel_rmse(got, reference);
    assert!(error.is_finite(), "the reference has a caustic");
    error
}

#[test]
fn only_diffuse_hits_behind_a_mirror_or_glass_gather() {
    // Every backend's light-traced images against the reference are the
    // conformance suite's (`light_traced_images_match_the_reference`);
    // here, the partition on the built-in scenes. `prism`: the spectrum
    // on a wall the camera sees directly, so light tracing alone and no
    // visible point; `caustic`: also seen through the sphere, where the
    // points stay, fewer than the gather alone makes.
    for (name, photons) in [("prism", 4_000), ("caustic", 20_000)] {
        let points = |light_tracing: bool| {
            let mut r = render(&mut ReferenceBackend, &scene(name, 64, photons, light_tracing), 0..1);
            let points = r.stats().unwrap().visible_points;
            assert!(caustic(r.as_mut()).iter().sum::<f64>() > 0.0, "{name}: a caustic");
            points
        };
        let (traced, gathered) = (points(true), points(false));
        assert!(traced < gathered, "{name}: {traced} visible points with light tracing, {gathered} without");
        assert_eq!(traced > 0, name == "caustic", "{name}: {traced} visible points with light tracing");
    }
}

#[test]
fn the_light_traced_error_falls_as_one_over_the_square_root_of_the_passes() {
    // The reference: passes no other render here uses, so its own noise is
    // independent. Each error is the root mean square over disjoint runs
    // of 256 passes in all, so that one lucky run does not set the slope.
    let scene = scene("prism", 96, 2_000, true);
    let caustic_of = |passes| caustic(render(&mut CpuBackend::new(), &scene, passes).as_mut());
    let reference = caustic_of(10_000..11_024);
    let error = |n: u32| {
        let runs = 256 / n;
        let squares: f64 = (0..runs).map(|i| rel_rmse(&caustic_of(i * n..(i + 1) * n), &reference).powi(2)).sum();
        (squares / f64::from(runs)).sqrt()
    };
    let passes = [4u32, 16, 64];
    let errors: Vec<f64> = passes.iter().map(|&n| error(n)).collect();
    let slope = (errors[2] / errors[0]).ln() / (f64::from(passes[2]) / f64::from(passes[0])).ln();
    assert!(slope <= -0.4, "relRMSE after {passes:?} passes: {errors:?}, log-log slope {slope:.3}");
}

#[test]
fn light_tracing_and_the_gather_together_count_every_caustic_path_once() {
    // `caustic`: the floor's caustic seen directly (light traced) and
    // through the sphere (gathered). The gather alone is the long
    // reference: the same light must give the same total, where counting
    // the directly seen paths twice would add their energy again.
    let (passes, size) = (24, 96);
    let total = |light_tracing: bool| -> f64 {
        let scene = scene("caustic", size, 65_000, light_tracing);
        caustic(render(&mut CpuBackend::new(), &scene, 0..passes).as_mut()).iter().sum()
    };
    let (combined, gathered) = (total(true), total(false));
    // What light tracing brings of it: the splats of the same passes' photons.
    let lit = scene("caustic", size, 65_000, true);
    let mut r = CpuBackend::new().prepare(&lit).unwrap();
    let direct: f64 = (0..passes)
        .map(|k| {
            let map = r.photon_map(k, &mut NoProgress).unwrap();
            splat_photons(&lit, &map.photons).iter().map(|s| f64::from(s.radiance.element_sum())).sum::<f64>()
        })
        .sum::<f64>()
        / f64::from(passes);
    assert!(direct > 0.1 * combined, "light tracing brings {direct:.1} of {combined:.1}: a double count would show");
    assert!(
        (combined / gathered - 1.0).abs() < 0.01,
        "caustic energy: combined {combined:.2}, gather alone {gathered:.2}"
    );
}

#[test]
fn light_traced_pixels_do_not_depend_on_the_thread_count() {
    let scene = scene("caustic", 48, 10_000, true);
    let sums = |threads| render(&mut CpuBackend::with_threads(threads).expect("pool"), &scene, 0..3).sums().unwrap();
    assert_eq!(sums(1), sums(2));
}

/// The sum of every pixel of `scene`'s image after `passes` passes on `backend`.
fn image_sum(backend: &mut dyn Backend, scene: &PreparedScene, passes: u32) -> f64 {
    image_after(backend, scene, passes).pixels.iter().map(|p| f64::from(p.element_sum())).sum()
}

/// A whole metal of RGB reflectance `color` (Schlick's F0) and `roughness`.
fn rough_metal(color: Vec3, roughness: f32) -> Material {
    let metalness = Metalness::WHOLE;
    let kind = MaterialKind::Metal { color: MetalColor::Rgb(color), roughness, texture: None, film: None, metalness };
    Material { kind, ..white("rough metal") }
}

/// What a rough `floor` (a disc of radius 0.9 about (1, 0, 0) in the plane y = 0) seen from above shows of a beam
/// of power 1000 (radius 0.6, white) that comes down on it obliquely (along
/// (1, −2, 0)/√5, its axis meeting the floor at (1, 0, 0); with `below`,
/// mirrored in the floor: from under it). `mirrored`: the beam travels
/// along +x at height 2 and a mirror (a disc at (0, ±2, 0)) folds it onto
/// the floor, so the floor's light is the caustic of one specular bounce,
/// which only light tracing brings (photons met on the floor); else the
/// beam itself comes from where the mirror sends it, and the view's
/// highlights bring it. What the floor reflects leaves away from the
/// mirror. A black sky, no ambient light: the floor's light is the beam's alone.
fn beam_on_a_rough_floor(floor: Material, below: bool, mirrored: bool, photons: u32) -> PreparedScene {
    let side = if below { -1.0 } else { 1.0 };
    let mut render = settings(photons, BandSpec::Paper3);
    (render.width, render.height, render.light_tracing) = (32, 32, true);
    // Jittered view paths: the passes' mean is each pixel's mean, as a splat's is.
    render.view_paths = ViewPaths::Sampled;
    (render.background, render.ambient) = (Vec3::ZERO, 0.0);
    let mirror_at = Vec3::new(0.0, 6.0 * side, 0.0);
    let onto = Vec3::new(1.0, -2.0 * side, 0.0).normalize();
    let spot = Vec3::new(3.0, 0.0, 0.0);
    let (position, direction) = match mirrored {
        true => (Vec3::new(-3.0, 6.0 * side, 0.0), Vec3::X),
        false => (spot - 3.0 * onto, onto),
    };
    let beam = Light::Beam { position, direction, radius: 0.6, power: 1000.0, spectrum: Default::default() };
    let mirror = Material { kind: MaterialKind::Mirror, ..white("mirror") };
    // A floor just wide enough for the beam: what the mirror sends back misses it.
    let disc = Shape::Disk { center: spot, normal: Vec3::Y, radius: 0.9, inner_radius: 0.0 };
    let mut objects = vec![Object { shape: disc, material: 0 }];
    if mirrored {
        let normal = (onto - Vec3::X).normalize();
        let shape = Shape::Disk { center: mirror_at, normal, radius: 1.6, inner_radius: 0.0 };
        objects.push(Object { shape, material: 1 });
    }
    prepare(Scene {
        render,
        camera: Camera { position: spot + Vec3::new(0.0, 3.0, 5.0), look_at: spot, up: Vec3::Y, fov_deg: 36.0 },
        lights: vec![beam],
        materials: vec![floor, mirror],
        objects,
    })
}

#[test]
fn light_tracing_shows_a_mirrored_beam_on_a_rough_floor_as_the_beam_itself() {
    // Photons met on a rough metal or glass are connected to the camera
    // through its BSDF; the beam's image, lit straight, is the view's
    // highlight (its closed form is tested with the metals and rough
    // glass; the CPU's, 16 passes of jittered pixels). The two must
    // agree: summed over the image, within 2 % (measured 0.3 %).
    let metal = rough_metal(Vec3::new(0.9, 0.6, 0.3), 0.5);
    let sheet = Material {
        kind: MaterialKind::Dielectric {
            dispersion: Dispersion::Constant(1.5),
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin: true,
            film: None,
            roughness: 0.5,
        },
        ..white("frosted sheet")
    };
    let cases = [("a rough metal", metal, false), ("a frosted sheet", sheet.clone(), false)];
    let through = [("light through a frosted sheet", sheet, true)];
    for (what, floor, below) in cases.into_iter().chain(through) {
        let scene = |mirrored: bool| beam_on_a_rough_floor(floor.clone(), below, mirrored, 40_000);
        let highlight = image_sum(&mut CpuBackend::new(), &scene(false), 16);
        assert!(highlight > 1.0, "{what}: the beam's highlight {highlight:.3}");
        for mut backend in every_backend() {
            let traced = image_sum(backend.as_mut(), &scene(true), 4);
            let name = backend.name();
            let ratio = traced / highlight;
            assert!((ratio - 1.0).abs() < 0.02, "{name}, {what}: light traced {traced:.3}, highlight {highlight:.3}");
        }
    }
}

/// A rough metal floor (a disc of radius 2 about the origin) under a rough
/// metal ceiling (a disc of radius 1, 1.5 above it) that a spot light
/// between them lights from below, seen from the side; the floor's only
/// light is what the ceiling reflects (the spot shines up). Light traced
/// or not, per-pass jittered view paths.
fn lit_between_rough_metals(light_tracing: bool) -> PreparedScene {
    let metal = |roughness| rough_metal(Vec3::splat(0.9), roughness);
    let mut render = settings(20_000, BandSpec::Paper3);
    (render.width, render.height, render.light_tracing) = (32, 32, light_tracing);
    (render.view_paths, render.background, render.ambient) = (ViewPaths::Sampled, Vec3::ZERO, 0.0);
    let spot = Light::Spot {
        position: Vec3::new(0.0, 0.5, 0.0),
        direction: Vec3::Y,
        cone_deg: 70.0,
        inner_cone_deg: 70.0,
        power: 1000.0,
        spectrum: Default::default(),
        range: None,
    };
    let disc =
        |y: f32, normal: Vec3, radius: f32| Shape::Disk { center: Vec3::Y * y, normal, radius, inner_radius: 0.0 };
    prepare(Scene {
        render,
        camera: Camera { position: Vec3::new(0.0, 1.0, 5.0), look_at: Vec3::ZERO, up: Vec3::Y, fov_deg: 50.0 },
        lights: vec![spot],
        materials: vec![metal(0.6), metal(0.4)],
        objects: vec![
            Object { shape: disc(0.0, Vec3::Y, 2.0), material: 0 },
            Object { shape: disc(1.5, Vec3::NEG_Y, 1.0), material: 1 },
        ],
    })
}

#[test]
fn behind_a_light_traced_rough_surface_the_view_leaves_the_hidden_lights_highlights_to_the_photons() {
    // The floor shows the ceiling's highlight (and the ceiling the floor's
    // reflection of it): with light tracing, photons met on the floor (on
    // the ceiling) after the ceiling (the floor) bring it, and the view's
    // paths behind them show no highlights, or the light would count
    // twice (1.59 times the total, measured); without, the view's paths
    // find it at the other surface. Summed over the image, the two agree:
    // the view's estimate (4096 passes on the CPU, about 0.5 % noise)
    // against each backend's light traced one (16 passes).
    let viewed = image_sum(&mut CpuBackend::new(), &lit_between_rough_metals(false), 4096);
    assert!(viewed > 1000.0, "the floor shows the ceiling's highlight: {viewed:.3}");
    for mut backend in every_backend() {
        let traced = image_sum(backend.as_mut(), &lit_between_rough_metals(true), 16);
        let name = backend.name();
        assert!((traced / viewed - 1.0).abs() < 0.025, "{name}: light traced {traced:.3}, viewed {viewed:.3}");
    }
}

#[test]
fn light_leaving_rough_glass_toward_the_camera_has_walters_radiance() {
    // A beam of power 1 (radius 0.3) inside a ball of frosted glass (index
    // 1.5, roughness 0.5: α 0.25, radius 10) folded by a mirror straight
    // up onto the ball's top, which the camera sees from far above, head
    // on (every pixel within the beam's spot). The light traced radiance
    // is Walter et al.'s BTDF times the irradiance inside, E = P/(πr²):
    // head on, the facet is the normal, so f = η_o² (1 − F) D(n) G2 /
    // (η_i cos i − η_o cos o)² with D(n) = 1/(πα²), G2 = 1, F = 0.04,
    // η_i = 1.5 inside and η_o = 1. Radiance over n² is what a ray keeps:
    // the glass's own BTDF (the renderer's, which carries radiance across
    // unscaled) would give 2.25 times it.
    let (alpha, n_glass, radius) = (0.25f64, 1.5f64, 0.3f64);
    let fresnel = ((n_glass - 1.0) / (n_glass + 1.0)).powi(2);
    let d = 1.0 / (std::f64::consts::PI * alpha * alpha);
    let btdf = (1.0 - fresnel) * d / (n_glass - 1.0).powi(2);
    let want = btdf / (std::f64::consts::PI * radius * radius);
    let frosted = Material {
        kind: MaterialKind::Dielectric {
            dispersion: Dispersion::Constant(n_glass as f32),
            outside: Dispersion::Constant(1.0),
            attenuation: None,
            thin: false,
            film: None,
            roughness: 0.5,
        },
        ..white("frosted ball")
    };
    let mut render = settings(40_000, BandSpec::Paper3);
    (render.width, render.height, render.light_tracing) = (8, 8, true);
    (render.background, render.ambient) = (Vec3::ZERO, 0.0);
    let mirror = Shape::Disk {
        center: Vec3::new(0.0, 5.0, 0.0),
        normal: Vec3::new(-1.0, 1.0, 0.0).normalize(),
        radius: 0.6,
        inner_radius: 0.0,
    };
    let beam = Light::Beam {
        position: Vec3::new(-5.0, 5.0, 0.0),
        direction: Vec3::X,
        radius: radius as f32,
        power: 1.0,
        spectrum: Default::default(),
    };
    let scene = prepare(Scene {
        render,
        camera: Camera { position: Vec3::new(0.0, 40.0, 0.0), look_at: Vec3::Y * 10.0, up: Vec3::Z, fov_deg: 0.6 },
        lights: vec![beam],
        materials: vec![frosted, Material { kind: MaterialKind::Mirror, ..white("mirror") }],
        objects: vec![
            Object { shape: Shape::Sphere { center: Vec3::ZERO, radius: 10.0 }, material: 0 },
            Object { shape: mirror, material: 1 },
        ],
    });
    for mut backend in every_backend() {
        let name = backend.name();
        let image = image_after(backend.as_mut(), &scene, 4);
        let got = image.pixels.iter().map(|p| f64::from(p.element_sum()) / 3.0).sum::<f64>() / 64.0;
        assert!((got / want - 1.0).abs() < 0.02, "{name}: light traced {got:.3}, Walter's {want:.3}");
    }
}
