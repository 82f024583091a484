//! The effect plan: the renderer simulates only what the scene calls for,
//! skips nothing that would show, and says why. Every test runs on every
//! backend.

use prismatic_core::MetalColor;
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::{Dispersion, Glass};
use prismatic_core::model::metalness::Metalness;
use prismatic_core::model::scene::{Light, MaterialKind, Object, Shape, ThinFilm};
use prismatic_core::optics::microfacet::GATHER_ALPHA;
use prismatic_core::optics::surface::Surface;
use prismatic_core::{Image, NoProgress, PreparedScene, ReferenceBackend, Scene, Vec3};
use prismatic_tests::backends::{assert_same_caustic, every_backend, frame, trace};
use prismatic_tests::random_scene::random_scene;
use prismatic_tests::{camera, glass, prepare, settings, white};

/// A glass sphere above a floor under a spot light aimed at it.
fn sphere_scene(dispersion: Dispersion, cone_deg: f32, aim: Vec3) -> Scene {
    let mut render = settings(4000, BandSpec::Paper7);
    render.width = 48;
    render.height = 48;
    let mut cam = camera();
    cam.position = Vec3::new(0.0, 3.0, 6.0);
    cam.look_at = Vec3::new(0.0, 0.5, 0.0);
    Scene {
        render,
        camera: cam,
        lights: vec![Light::Spot {
            position: Vec3::new(0.0, 6.0, 0.0),
            direction: aim,
            cone_deg,
            inner_cone_deg: cone_deg,
            power: 20.0,
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

#[test]
fn a_scene_without_mirrors_or_glass_traces_no_photons_and_renders_the_same() {
    let mut scene = sphere_scene(Dispersion::Constant(1.5), 20.0, -Vec3::Y);
    scene.materials[0] = white("chalk");
    let scene = prepare(scene);
    assert!(!scene.plan.caustics.on);
    assert_eq!(scene.plan.caustics.reason, "no mirror or glass in the scene");
    assert_eq!(scene.plan.max_depth, 0);
    let mut forced = scene.clone();
    forced.plan.caustics.on = true;
    for mut backend in every_backend() {
        let (map, image) = frame(backend.as_mut(), &scene);
        assert_eq!(map.stats.emitted, 0, "{}: the photon pass ran", backend.name());
        assert!(map.photons.is_empty());
        let (forced_map, forced_image) = frame(backend.as_mut(), &forced);
        assert_eq!(forced_map.stats.emitted, 4000);
        assert!(forced_map.photons.is_empty(), "{}: chalk made caustics", backend.name());
        assert_eq!(image.pixels, forced_image.pixels, "{}", backend.name());
    }
}

#[test]
fn constant_index_glass_traces_white_photons_only_with_a_seventh_of_the_segments() {
    let scene = prepare(sphere_scene(Dispersion::Constant(1.5), 9.0, -Vec3::Y));
    assert!(scene.plan.caustics.on && !scene.plan.band_splitting.on, "{}", scene.plan.summary());
    assert!(scene.plan.band_splitting.reason.contains("constant index"), "{}", scene.plan.band_splitting.reason);
    // The same glass as 7 bands that share one index, forced to split.
    let mut split = prepare(sphere_scene(Dispersion::PerBand(vec![1.5; 7]), 9.0, -Vec3::Y));
    for s in &mut split.surfaces {
        if let Surface::Dielectric(g) = s {
            (g.splits_photons, g.splits_view_rays) = (true, true);
        }
    }
    for mut backend in every_backend() {
        let (white_map, white_image) = frame(backend.as_mut(), &scene);
        let (split_map, split_image) = frame(backend.as_mut(), &split);
        let name = backend.name();
        assert!(white_map.photons.iter().all(|p| p.band == prismatic_core::model::photon::WHITE_BAND), "{name}");
        assert!(split_map.photons.iter().all(|p| p.band < 7), "{name}");
        // One white path against seven band paths behind the first hit: 3 segments against 1 + 7 × 2.
        let ratio = white_map.stats.segments as f64 / split_map.stats.segments as f64;
        assert!(
            (0.14..0.25).contains(&ratio),
            "{name}: segments {} vs {}",
            white_map.stats.segments,
            split_map.stats.segments
        );
        // Same light, different random draws: equal within photon noise.
        let sum = |i: &Image| i.pixels.iter().map(|p| f64::from(p.element_sum())).sum::<f64>();
        let (a, b) = (sum(&white_image), sum(&split_image));
        assert!((a - b).abs() < 0.02 * a, "{name}: image energy {a} vs {b}");
    }
}

#[test]
fn a_film_on_glass_of_one_index_splits_photons_and_view_rays() {
    let mut scene = sphere_scene(Dispersion::Constant(1.5), 9.0, -Vec3::Y);
    let MaterialKind::Dielectric { film, .. } = &mut scene.materials[0].kind else { unreachable!() };
    *film = Some(ThinFilm::new(1.38, 250.0));
    let scene = prepare(scene);
    let plan = &scene.plan;
    assert!(plan.band_splitting.on && plan.band_splitting.reason.contains("coated glass"), "{}", plan.summary());
    assert_eq!(plan.view_dispersion.reason, "coated glass in view", "{}", plan.summary());
    let Surface::Dielectric(g) = &scene.surfaces[0] else { unreachable!() };
    assert!(g.splits_photons && g.splits_view_rays && !g.is_dispersive(), "{g:?}");
}

#[test]
fn a_coloured_metal_gives_photons_bands_and_a_grey_one_keeps_them_white() {
    let metal = |color: Vec3| {
        let mut scene = sphere_scene(Dispersion::Constant(1.5), 9.0, -Vec3::Y);
        scene.materials[0].kind = MaterialKind::Metal {
            color: MetalColor::Rgb(color),
            roughness: 0.2,
            texture: None,
            film: None,
            metalness: Metalness::WHOLE,
        };
        prepare(scene).plan
    };
    let gold = metal(Vec3::new(1.0, 0.766, 0.336));
    assert!(gold.caustics.on, "{}", gold.summary());
    assert!(gold.band_splitting.on && gold.band_splitting.reason.contains("at coloured metal"), "{}", gold.summary());
    let grey = metal(Vec3::splat(0.9));
    assert!(grey.caustics.on && !grey.band_splitting.on, "{}", grey.summary());
}

#[test]
fn glass_outside_every_light_cone_skips_the_photon_pass_and_says_why() {
    // The spot points away from the sphere.
    let scene = prepare(sphere_scene(Glass::Bk7.dispersion(), 10.0, Vec3::new(1.0, -0.2, 0.0)));
    assert!(!scene.plan.caustics.on);
    assert!(
        scene.plan.caustics.reason.contains("object[0] outside every light's cone, beam or range"),
        "{}",
        scene.plan.caustics.reason
    );
    assert!(scene.plan.summary().contains("skipped: caustics"), "{}", scene.plan.summary());
    for mut backend in every_backend() {
        let (map, _) = frame(backend.as_mut(), &scene);
        assert_eq!(map.stats.emitted, 0, "{}", backend.name());
    }
    // Aimed at the sphere, the pass runs.
    assert!(prepare(sphere_scene(Glass::Bk7.dispersion(), 10.0, -Vec3::Y)).plan.caustics.on);
}

#[test]
fn a_rough_floor_receives_a_caustic_only_where_light_tracing_or_its_gather_brings_it() {
    // The sphere over a rough metal floor: light tracing connects a hidden
    // light's caustic on it to the camera, and visible points on a floor
    // rough enough to gather (Ggx::gathers) gather it, so the photon pass
    // runs; on a floor just too smooth to gather without light tracing, or
    // lit by an area light only (whose light behind a rough surface the
    // view's rays meet themselves), nothing would take it, and forcing the
    // pass on changes no pixel.
    let edge = GATHER_ALPHA.sqrt();
    let rough_floor = |roughness: f32, light_tracing: bool| {
        let mut scene = sphere_scene(Dispersion::Constant(1.5), 20.0, -Vec3::Y);
        let metalness = Metalness::WHOLE;
        let color = MetalColor::Rgb(Vec3::splat(0.9));
        scene.materials[1].kind = MaterialKind::Metal { color, roughness, texture: None, film: None, metalness };
        scene.render.light_tracing = light_tracing;
        scene
    };
    assert!(prepare(rough_floor(edge * 0.99, true)).plan.caustics.on);
    assert!(prepare(rough_floor(edge * 1.01, false)).plan.caustics.on);
    let mut lamp = rough_floor(edge * 1.01, true);
    let (a, b, c) = (Vec3::new(-0.3, 5.0, -0.3), Vec3::new(0.3, 5.0, -0.3), Vec3::new(0.0, 5.0, 0.3));
    lamp.lights = vec![Light::Area { vertices: [a, b, c], power: 20.0, spectrum: Default::default(), aim: None }];
    for scene in [rough_floor(edge * 0.99, false), lamp] {
        let scene = prepare(scene);
        let reason = &scene.plan.caustics.reason;
        assert!(!scene.plan.caustics.on && reason.contains("to receive caustics"), "{reason}");
        let mut forced = scene.clone();
        forced.plan.caustics.on = true;
        for mut backend in every_backend() {
            let name = backend.name();
            let ((_, image), (map, forced_image)) = (frame(backend.as_mut(), &scene), frame(backend.as_mut(), &forced));
            assert!(map.photons.iter().all(|p| !p.on_rough_surface()), "{name}: {reason}");
            assert_eq!(image.pixels, forced_image.pixels, "{name}: {reason}");
        }
    }
}

#[test]
fn the_plan_never_skips_light_that_would_show() {
    // Whatever the plan skips, forcing it back on changes nothing. Half the
    // scenes aim their light somewhere random, so that it often misses the glass.
    let mut skipped_caustics = 0;
    for seed in 1..=60 {
        let mut s = random_scene(seed, 1500, 24);
        if seed % 2 == 0 {
            let u = |d: u32| prismatic_core::util::rng::random_f32(seed, 77, d) * 2.0 - 1.0;
            let aim = Vec3::new(u(0) * 6.0, u(1) * 2.0 - 1.0, u(2) * 6.0);
            match &mut s.lights[0] {
                Light::Spot { position, direction, .. } | Light::Beam { position, direction, .. } => {
                    *direction = aim - *position;
                }
                Light::Sun { direction, .. } => *direction = aim,
                Light::Point { .. } | Light::Environment { .. } | Light::Area { .. } => {}
            }
        }
        // Projection maps change where photons start (their unbiasedness is tested separately).
        s.render.projection_maps = false;
        let scene = PreparedScene::new(s).unwrap();
        skipped_caustics += usize::from(!scene.plan.caustics.on);
        let mut forced = scene.clone();
        forced.simulate_everything();
        let (planned, a) = frame(&mut ReferenceBackend, &scene);
        let (full, b) = frame(&mut ReferenceBackend, &forced);
        assert_eq!(planned.photons, full.photons, "seed {seed}: {}", scene.plan.summary());
        assert_eq!(a.pixels, b.pixels, "seed {seed}: {}", scene.plan.summary());
    }
    assert!(skipped_caustics >= 5, "only {skipped_caustics} scenes exercised a skipped photon pass");
}

fn builtin(name: &str, photons: u32, projection_maps: bool) -> PreparedScene {
    prismatic_tests::builtin(name, |r| {
        (r.photons, r.width, r.height, r.projection_maps) = (photons, 64, 64, projection_maps)
    })
}

#[test]
fn projection_maps_store_the_same_caustic_from_ten_times_fewer_photons() {
    const AIMED: u32 = 20_000;
    let aimed = builtin("sphere", AIMED, true);
    let scale = aimed.plan.projections[0].as_ref().expect("the sphere's spot light gets a projection map").scale;
    assert!(scale < 0.1, "the sphere fills {:.1} % of the spot's cone", scale * 100.0);
    assert!(aimed.plan.summary().contains("projection maps (1 of 1 light aimed"), "{}", aimed.plan.summary());
    // Without projection maps, the same stored photons need 1/scale times the emission.
    let whole = builtin("sphere", (AIMED as f32 / scale) as u32, false);
    let ten_times = builtin("sphere", AIMED * 10, false);
    for mut backend in every_backend() {
        let name = backend.name();
        let (map_aimed, image_aimed) = frame(backend.as_mut(), &aimed);
        let (map_whole, image_whole) = frame(backend.as_mut(), &whole);
        let map_ten = trace(backend.as_mut(), &ten_times);
        assert_eq!(map_aimed.stats.specular_paths, u64::from(AIMED), "{name}: every aimed photon meets the glass");
        assert!(
            map_aimed.stats.stored > map_ten.stats.stored,
            "{name}: {} emitted store {}, while 10× as many without projection maps store only {}",
            AIMED,
            map_aimed.stats.stored,
            map_ten.stats.stored
        );
        assert_same_caustic(name, (&map_aimed, &image_aimed), (&map_whole, &image_whole));
    }
}

#[test]
fn a_beam_that_lies_wholly_on_its_prism_has_nothing_to_aim() {
    let scene = builtin("prism", 2_000, true);
    assert!(scene.plan.projections.iter().all(Option::is_none));
    assert!(
        !scene.plan.projection.on && scene.plan.projection.reason.starts_with("no gain"),
        "{}",
        scene.plan.projection.reason
    );
    let map = prismatic_core::photons::trace::trace_photons(&scene, &mut NoProgress);
    assert_eq!(map.stats.specular_paths, 2_000, "every photon of the beam already meets the prism");
}
