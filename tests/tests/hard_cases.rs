//! Hard cases stay numerically stable: no NaN or Inf anywhere, and the
//! expected answer, on every backend. Grazing and tangent rays, light
//! reflected a dozen times inside a glass ball, total internal reflection,
//! prism edges and vertices, thin walls, scenes far from the origin, extreme
//! gather radii, index 1 and diamond, glass in water, degenerate triangles,
//! empty gathers, more than 2^24 photons in one gather, photons on grid cell
//! borders, 1 and 256 bands.

use prismatic_core::geometry::primitive::{Primitive, Ray, prism_faces};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::{Dispersion, Glass};
use prismatic_core::model::photon::{Photon, PhotonMap, WHITE_BAND, oct_pack};
use prismatic_core::model::scene::{Estimator, Light, MaterialKind, Object, RenderSettings, Shape};
use prismatic_core::optics::fresnel::fresnel;
use prismatic_core::optics::scatter::offset_origin;
use prismatic_core::optics::surface::Surface;
use prismatic_core::photons::gather::{GatherQuery, gather};
use prismatic_core::photons::grid::PhotonGrid;
use prismatic_core::{Backend, BackendError, BandTable, Image, NoProgress, PreparedScene, Scene, Vec3};
use prismatic_cpu::CpuGrid;
use prismatic_tests::backends::{every_backend, fixed, frame, trace};
use prismatic_tests::parity::compare_maps;
use prismatic_tests::tolerance::{KNIFE_EDGE_OUTLIER_FRACTION, Tolerance};
use prismatic_tests::{PrismExperiment, builtin, camera, glass, prepare, settings, sphere_in_a_catcher, white};

/// Panics unless every photon of `map` is finite and every pixel of `image` too.
fn assert_finite(case: &str, map: &PhotonMap, image: Option<&Image>) {
    for p in &map.photons {
        let ok = p.position.iter().all(|x| x.is_finite())
            && p.direction().is_finite()
            && p.flux.is_finite()
            && p.flux > 0.0
            && p.wavelength().is_none_or(|l| (360.0..=830.0).contains(&l));
        assert!(ok, "{case}: photon {p:?}");
    }
    let s = map.stats;
    for x in [s.flux_emitted, s.flux_stored, s.flux_escaped, s.flux_direct, s.flux_depth_limited] {
        assert!(x.is_finite(), "{case}: {s:?}");
    }
    if let Some(image) = image {
        // A single channel may dip below 0 where a caustic is more saturated
        // than sRGB can show (spectral colours lie outside its gamut; the PNG
        // clips them), but light itself, the luminance, never does.
        let luminance = |p: &Vec3| p.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        let bad = image.pixels.iter().position(|p| !(p.is_finite() && luminance(p) >= 0.0));
        assert!(bad.is_none(), "{case}: pixel {bad:?} is NaN, Inf or negative: {:?}", bad.map(|i| image.pixels[i]));
    }
}

/// The paper's frame of `scene` on `backend` (pass 0 at the scene's radius):
/// its photon map, its image and its image without caustics.
fn frame_and_base(backend: &mut dyn Backend, scene: &PreparedScene) -> (PhotonMap, Image, Image) {
    let name = backend.name();
    let (map, image) = frame(backend, scene);
    let mut render = backend.prepare(&fixed(scene)).unwrap_or_else(|e| panic!("{name}: prepare: {e}"));
    (map, image, render.base().unwrap_or_else(|e| panic!("{name}: base: {e}")))
}

/// Mean of all channels over each 8×8 block of pixels.
fn blocks_of(image: &Image) -> Vec<f64> {
    let (w, h) = (image.width as usize, image.height as usize);
    let mut blocks = vec![0.0; w.div_ceil(8) * h.div_ceil(8)];
    for (i, p) in image.pixels.iter().enumerate() {
        let (x, y) = (i % w, i / w);
        blocks[(y / 8) * w.div_ceil(8) + x / 8] += f64::from(p.x + p.y + p.z) / 192.0;
    }
    blocks
}

/// Σ over the image of all channels.
fn image_energy(image: &Image) -> f64 {
    image.pixels.iter().map(|p| f64::from(p.x + p.y + p.z)).sum()
}

/// 20,000 photons, 7 bands, depth 64.
fn deep_settings() -> prismatic_core::RenderSettings {
    let mut render = settings(20_000, BandSpec::Paper7);
    render.max_depth = 64;
    render
}

/// The photon map of `scene` on `backend`, traced to the scene's depth,
/// and the frame of it seen by view paths of the default depth (12).
/// The GPU compiles a view pipeline for each view-ray stack size, and
/// depth 64's (68 entries) was compiled for these tests alone: 35 s of
/// lavapipe's compile in every CI run (the grazing test took 43 s after
/// the default pipelines were compiled, 6.6 s with this). Its WGSL is
/// validated by the GPU crate's `shaders` test; the photons, where depth
/// matters here, still go to 64.
fn deep_photons_shallow_view(backend: &mut dyn Backend, scene: &PreparedScene) -> (PhotonMap, Image) {
    let map = trace(backend, scene);
    let mut shallow = scene.scene.clone();
    shallow.render.max_depth = RenderSettings::default().max_depth;
    let (_, image) = frame(backend, &prepare(shallow));
    (map, image)
}

/// A paper-glass sphere and a beam whose axis grazes its silhouette
/// (impact parameter 1), inside a closed catcher.
fn tangent_beam(beam_radius: f32) -> Scene {
    sphere_in_a_catcher(Glass::Paper.dispersion(), deep_settings(), 1.0, beam_radius)
}

/// Rays tangent to a sphere and at grazing incidence (cos θ from 0.14 down to
/// below 1e-3): finite, energy closes, and light reflected once off the rim
/// turns by no more than the steepest ray of the beam allows.
#[test]
fn grazing_and_tangent_rays_on_a_sphere() {
    for beam_radius in [1e-2f32, 1e-4, 1e-6] {
        let scene = prepare(tangent_beam(beam_radius));
        // The steepest ray meets the sphere at impact parameter 1 − ρ, with
        // cos θ = √(1 − (1 − ρ)²) ≈ √(2ρ); reflection turns it by 2·asin(cos θ)...
        let cos_max = (1.0 - (1.0 - f64::from(beam_radius)).powi(2)).sqrt();
        // ...plus the conditioning of a near-tangent hit: the ray's f32 origin 5
        // units away puts its impact parameter δb ≈ 5·2^-23 ≈ 6e-7 off, and the
        // hit point moves along the sphere by δb / cos θ, turning the normal
        // (and twice over the reflection) by as much.
        let max_turn = 2.0 * cos_max.asin().to_degrees() + 2.0 * (6e-7 / cos_max).to_degrees();
        for mut backend in every_backend() {
            let case = format!("{} with a beam of radius {beam_radius}", backend.name());
            let (map, image) = deep_photons_shallow_view(backend.as_mut(), &scene);
            assert_finite(&case, &map, Some(&image));
            let s = map.stats;
            assert_eq!(s.flux_escaped, 0.0, "{case}");
            let accounted = s.flux_stored + s.flux_direct + s.flux_depth_limited;
            assert!((accounted - s.flux_emitted).abs() <= 1e-6 * s.flux_emitted, "{case}: {s:?}");
            assert!(s.specular_paths > 0, "{case}: no ray met the sphere");
            for p in map.photons.iter().filter(|p| p.bounces == 1) {
                let turn = p.direction().angle_between(Vec3::NEG_Z).to_degrees();
                assert!(f64::from(turn) <= max_turn, "{case}: reflected off the rim by {turn}°, at most {max_turn}°");
            }
        }
    }
}

/// Light that enters a glass ball near its rim (cos θ ≈ 0.09) reflects
/// inside it again and again, and a sphere meets every chord at the same
/// angle: the angle it refracted to, below the critical one. So no
/// reflection inside is total, and the flux still inside at the depth limit
/// D is the closed form Σ_b (1/N)·(1 − R_b)·R_b^(D−1), R_b the Fresnel
/// reflectance at the entry angle (Stokes: the same inside). The surface
/// offsets move each new chord a little towards the centre, away from the
/// critical angle, so R falls along the path and the flux left is below the
/// closed form (measured: 0.78 of it at D = 12). When a hit point a few ulps
/// off the sphere gave the next reflection a direction off unit length, the
/// error grew about fivefold a bounce, reached a false total internal
/// reflection by the eighth, and trapped 5.7 times the closed form inside.
#[test]
fn light_inside_a_glass_ball_keeps_its_angle_bounce_after_bounce() {
    const DEPTH: u32 = 12;
    let impact = 0.996f32;
    let mut render = settings(100_000, BandSpec::Paper7);
    render.max_depth = DEPTH;
    let scene = prepare(sphere_in_a_catcher(Glass::Paper.dispersion(), render, impact, 1e-4));
    let Surface::Dielectric(optics) = &scene.surfaces[0] else { unreachable!("object 0 is the ball") };
    let cos_i = (1.0 - impact * impact).sqrt();
    let bands = scene.bands.len();
    let inside: f64 = (0..bands as u16)
        .map(|b| f64::from(fresnel(cos_i, 1.0, optics.ior(b))))
        .map(|r| (1.0 - r) * r.powi(DEPTH as i32 - 1) / bands as f64)
        .sum();
    for mut backend in every_backend() {
        let map = trace(backend.as_mut(), &scene);
        let s = map.stats;
        let share = s.flux_depth_limited / s.flux_emitted;
        let case =
            format!("{}: {share:.3e} of the flux inside at depth {DEPTH}, closed form {inside:.3e}", backend.name());
        assert!((0.65 * inside..=1.05 * inside).contains(&share), "{case}");
    }
}

/// A 90° prism used as a reflector: the beam enters a leg at normal
/// incidence, is totally reflected at the hypotenuse (45° > the critical
/// angle) and leaves through the other leg at normal incidence, turned by
/// exactly 90°, all bands together. Nothing refracts out of the hypotenuse,
/// and the flux that comes out is the two normal-incidence transmittances.
#[test]
fn total_internal_reflection_inside_a_prism() {
    const PHOTONS: u32 = 20_000;
    let exp = PrismExperiment { apex_deg: 90.0, incidence_deg: 0.0, beam_radius: 0.05, screen_x: 6.0 };
    let mut scene = exp.scene(Glass::Paper.dispersion(), settings(PHOTONS, BandSpec::Paper7));
    scene.objects[1].shape = Shape::Sphere { center: Vec3::ZERO, radius: 50.0 };
    let scene = prepare(scene);
    let Surface::Dielectric(optics) = &scene.surfaces[0] else { unreachable!("object 0 is the prism") };
    let out = Vec3::new(1.0, 1.0, 0.0).normalize();
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        assert_finite(name, &map, None);
        // In, out of the hypotenuse: would be two refractions.
        assert!(map.photons.iter().all(|p| p.bounces != 2), "{name}: light refracted out of the hypotenuse");
        for (band, &n) in optics.band_ior.iter().enumerate() {
            let through: Vec<_> =
                map.photons.iter().filter(|p| usize::from(p.band) == band && p.bounces == 3).collect();
            for p in &through {
                let angle = p.direction().angle_between(out).to_degrees();
                assert!(angle < 1e-3, "{name}: band {band} leaves {angle}° off 90°");
            }
            // Binomial count: expected T² of the photons, 5 standard deviations.
            let t = 1.0 - ((f64::from(n) - 1.0) / (f64::from(n) + 1.0)).powi(2);
            let expected = f64::from(PHOTONS) * t * t;
            let sigma = (expected * (1.0 - t * t)).sqrt();
            let got = through.len() as f64;
            assert!(
                (got - expected).abs() < 5.0 * sigma,
                "{name}: band {band}: {got} photons out, T² predicts {expected:.0}"
            );
        }
    }
}

/// The analytic prism and the same prism as a triangle mesh.
fn prism_primitives() -> Vec<(&'static str, Primitive, Vec<Vec3>)> {
    let v = [Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, -1.0), Vec3::new(0.0, 1.732_050_8, -1.0)];
    let e = Vec3::new(0.0, 0.0, 2.0);
    let corners: Vec<Vec3> = v.iter().copied().chain(v.iter().map(|&p| p + e)).collect();
    // Two end caps and three side quads split along a diagonal.
    let triangles: [[u32; 3]; 8] =
        [[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]];
    let mesh = Primitive::mesh(&corners, &triangles);
    // Points on every edge (including the quads' diagonals) and every vertex.
    let mut targets = corners.clone();
    let mut edges: Vec<[usize; 2]> = Vec::new();
    for t in &triangles {
        for k in 0..3 {
            edges.push([t[k] as usize, t[(k + 1) % 3] as usize]);
        }
    }
    for [a, b] in edges {
        for s in [0.5f32, 0.25, 1.0 / 3.0, 0.9] {
            targets.push(corners[a].lerp(corners[b], s));
        }
    }
    vec![
        ("analytic prism", Primitive::Convex { faces: prism_faces(v, e) }, targets.clone()),
        ("mesh prism", mesh, targets),
    ]
}

/// Rays aimed through a prism's edges and vertices toward its inside must
/// enter and leave again: no ray slips between two faces or two triangles.
#[test]
fn rays_through_prism_edges_and_vertices_do_not_leak() {
    let centre = Vec3::new(0.0, 0.577, 0.0);
    for (name, prim, targets) in prism_primitives() {
        for (i, &target) in targets.iter().enumerate() {
            for k in 0..24 {
                // Toward points spread around the inside, so the ray crosses the edge into the solid.
                let phi = k as f32 * 0.2618;
                let inner = centre + Vec3::new(0.3 * phi.cos(), 0.3 * phi.sin(), 0.5 * (phi * 0.7).sin());
                let d = (inner - target).normalize();
                let ray = Ray { origin: target - d * 5.0, direction: d };
                let Some(enter) = prim.intersect(&ray, 0.0, f32::INFINITY) else {
                    panic!("{name}: ray {k} through edge/vertex point {i} ({target}) slipped in without a hit");
                };
                assert!(enter.normal.dot(d) < 0.0, "{name}: point {i}, ray {k}: first hit is not an entry");
                let p = ray.at(enter.t);
                let inside = Ray { origin: offset_origin(p, enter.normal, d), direction: d };
                let exit = prim.intersect(&inside, 0.0, f32::INFINITY);
                assert!(
                    exit.is_some_and(|h| h.normal.dot(d) > 0.0),
                    "{name}: ray {k} through point {i} ({target}) entered and never left"
                );
            }
        }
    }
}

/// A ray leaving a surface does not hit it again at once, and a wall
/// 1e-3 thick (the thinnest the tolerances promise) is never skipped,
/// anywhere within 10 units of the origin.
#[test]
fn rays_leave_their_surface_and_do_not_skip_thin_walls() {
    for offset in [Vec3::ZERO, Vec3::new(9.0, -7.0, 3.0)] {
        // A slab 1e-3 thick as a prism with a wide triangle cross-section.
        let v = [Vec3::new(-2.0, 0.0, -2.0), Vec3::new(2.0, 0.0, -2.0), Vec3::new(0.0, 0.0, 2.0)].map(|p| p + offset);
        let slab = Primitive::Convex { faces: prism_faces(v, Vec3::new(0.0, 1e-3, 0.0)) };
        for k in 0..200 {
            let a = k as f32 * 0.031;
            // From above at angles down to 3° from grazing.
            let d = Vec3::new(0.7 * a.cos(), -(0.05 + (k as f32 / 200.0)), 0.7 * a.sin()).normalize();
            let target = offset + Vec3::new(0.1 * a.sin(), 0.0005, 0.1 * a.cos());
            let ray = Ray { origin: target - d * 3.0, direction: d };
            let top = slab.intersect(&ray, 0.0, f32::INFINITY).expect("the slab's top");
            let p = ray.at(top.t);
            // Leaving outward (reflection): nothing more to hit.
            let up = d - top.normal * 2.0 * d.dot(top.normal);
            assert!(
                slab.intersect(&Ray { origin: offset_origin(p, top.normal, up), direction: up }, 0.0, f32::INFINITY)
                    .is_none(),
                "self-hit at {p}"
            );
            // Going on inside: the bottom face 1e-3 below.
            let inside = Ray { origin: offset_origin(p, top.normal, d), direction: d };
            let bottom = slab
                .intersect(&inside, 0.0, f32::INFINITY)
                .unwrap_or_else(|| panic!("skipped the wall's far side at {p}"));
            assert!(bottom.normal.y < -0.99, "left through {:?}, not the bottom", bottom.normal);
        }
    }
}

/// Shifts every position (keys `position`, `look_at`, `point`, `center`) of
/// a scene file by `by` in x, y and z, written out with full precision.
fn translate_scene_text(source: &str, by: f64) -> String {
    source
        .lines()
        .map(|line| {
            let key = line.split('=').next().unwrap_or("").trim();
            if !["position", "look_at", "point", "center"].contains(&key) {
                return line.to_string();
            }
            let inside = line.split('[').nth(1).and_then(|s| s.split(']').next()).expect("a vector");
            let moved: Vec<String> =
                inside.split(',').map(|x| format!("{:?}", x.trim().parse::<f64>().unwrap() + by)).collect();
            format!("{key} = [{}]", moved.join(", "))
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The `sphere` scene moved 1e4 and 1e6 units away from the origin renders
/// the same caustic as at the origin (f32 has an ulp of 0.06 at 1e6).
#[test]
fn a_scene_far_from_the_origin_renders_as_at_the_origin() {
    let source = prismatic_cli::builtin::find("sphere").unwrap().source;
    let load = |by: f64| {
        let text = translate_scene_text(source, by);
        let mut doc = prismatic_cli::scene_file::parse(&text, "moved.toml", None).unwrap_or_else(|e| panic!("{e}"));
        doc.scene.render.photons = 20_000;
        doc.scene.render.width = 64;
        doc.scene.render.height = 64;
        prepare(doc.scene)
    };
    let home = load(0.0);
    for mut backend in every_backend() {
        let name = backend.name();
        let (home_map, home_image) = frame(backend.as_mut(), &home);
        for by in [1e4, 1e6] {
            let case = format!("{name}, moved by {by}");
            let (map, image) = frame(backend.as_mut(), &load(by));
            assert_finite(&case, &map, Some(&image));
            let stored = |m: &PhotonMap| m.photons.len() as f64;
            assert!(
                (stored(&map) / stored(&home_map) - 1.0).abs() < 0.01,
                "{case}: {} photons stored, {} at the origin",
                stored(&map),
                stored(&home_map)
            );
            // Same light, same caustic: photons land within f32 rounding of the
            // same spots, but a photon that crosses a gather radius or a pixel on
            // a checker border flips, so compare 8×8 blocks (and the whole).
            let (home_blocks, blocks) = (blocks_of(&home_image), blocks_of(&image));
            for (i, (a, b)) in blocks.iter().zip(&home_blocks).enumerate() {
                assert!((a - b).abs() <= 0.03 * b.max(0.05), "{case}: block {i}: {a} vs {b} at the origin");
            }
            let (e, home_e) = (image_energy(&image), image_energy(&home_image));
            assert!((e / home_e - 1.0).abs() < 0.005, "{case}: image energy {e} vs {home_e}");
        }
    }
}

/// The `sphere` scene, small.
fn small_sphere(edit: impl FnOnce(&mut prismatic_core::RenderSettings)) -> PreparedScene {
    builtin("sphere", |r| {
        r.photons = 4000;
        r.width = 48;
        r.height = 48;
        edit(r);
    })
}

/// Gather radii of 1e-6 (cells of 2e-6 over a scene of size 10) and 100
/// (the whole scene in one cell): finite images; the huge radius spreads the
/// stored flux evenly, the tiny one catches next to nothing.
#[test]
fn tiny_and_huge_gather_radii() {
    // The photons do not depend on the radius: the same map gathered in each.
    for mut backend in every_backend() {
        let name = backend.name();
        for radius in [1e-6f32, 100.0] {
            let scene = small_sphere(|r| r.radius = radius);
            let (map, image, no_caustic) = frame_and_base(backend.as_mut(), &scene);
            let case = format!("{name}, radius {radius}");
            assert_finite(&case, &map, Some(&image));
            let added = image_energy(&image) - image_energy(&no_caustic);
            assert!(added >= 0.0, "{case}: the caustic took light away ({added})");
            if radius > 1.0 {
                // Irradiance Σ Φ / (π r²) with r = 100: ≈ 1e-4 of the flux per unit area.
                assert!(added > 0.0, "{case}: no caustic at all");
            }
        }
    }
}

/// Index exactly 1 is no interface: photons cross the sphere unbent and
/// unreflected and land where they would without it. Diamond (2.42, total
/// internal reflection past 24.4°) renders finite with its energy closed.
#[test]
fn index_one_and_diamond() {
    for mut backend in every_backend() {
        let name = backend.name();
        let scene = prepare(sphere_in_a_catcher(Dispersion::Constant(1.0), deep_settings(), 0.0, 0.5));
        let map = trace(backend.as_mut(), &scene);
        assert_finite(name, &map, None);
        assert_eq!(map.photons.len(), 20_000, "{name}: every photon crosses the sphere once");
        for p in &map.photons {
            assert_eq!(p.bounces, 2, "{name}: in and out, nothing else");
            assert!(p.direction().angle_between(Vec3::NEG_Z) < 1e-6, "{name}: bent by an index of 1");
            let (x, y) = (p.position[0], p.position[1]);
            assert!(x * x + y * y <= 0.25 * (1.0 + 1e-5), "{name}: landed outside the beam's shadow");
        }

        let mut diamond = small_sphere(|r| r.max_depth = 64);
        let MaterialKind::Dielectric { dispersion, .. } =
            &mut diamond.scene.materials.iter_mut().find(|m| m.name == "glass").unwrap().kind
        else {
            unreachable!("the sphere is glass")
        };
        *dispersion = Glass::Diamond.dispersion();
        let diamond = prepare(diamond.scene);
        let (map, image) = deep_photons_shallow_view(backend.as_mut(), &diamond);
        assert_finite(&format!("{name}, diamond"), &map, Some(&image));
        let s = map.stats;
        let accounted = s.flux_stored + s.flux_direct + s.flux_depth_limited + s.flux_escaped;
        assert!((accounted - s.flux_emitted).abs() <= 1e-6 * s.flux_emitted, "{name}, diamond: {s:?}");
    }
}

/// Glass inside water: a BK7 prism immersed in a water sphere, beam and
/// screen in the water too. Each band deviates as Snell's law says for the
/// relative index n_glass(λ)/n_water(λ).
#[test]
fn glass_inside_water_refracts_with_the_relative_index() {
    let bands = BandSpec::Physical(5);
    let table = BandTable::new(bands);
    let (bk7, water) = (Glass::Bk7.dispersion(), Glass::Water.dispersion());
    let relative = |b: usize| f64::from(bk7.ior_for_band(&table, b)) / f64::from(water.ior_for_band(&table, b));
    let incidence_deg = (PrismExperiment::min_deviation_deg(60.0, relative(2)) + 60.0) / 2.0;
    let exp = PrismExperiment { apex_deg: 60.0, incidence_deg, beam_radius: 0.05, screen_x: 4.0 };
    let mut scene = exp.scene(bk7.clone(), settings(3000, bands));
    scene.materials[0].kind = MaterialKind::Dielectric {
        dispersion: bk7.clone(),
        outside: water.clone(),
        attenuation: None,
        thin: false,
        film: None,
        roughness: 0.0,
    };
    scene.materials.push(glass("water", water.clone()));
    scene.objects.push(Object { shape: Shape::Sphere { center: Vec3::ZERO, radius: 20.0 }, material: 2 });
    let scene = prepare(scene);
    let phi = exp.beam_angle();
    for mut backend in every_backend() {
        let name = backend.name();
        let map = trace(backend.as_mut(), &scene);
        assert_finite(name, &map, None);
        for band in 0..table.len() {
            let n = relative(band);
            let expected = exp.deviation_deg(n).unwrap();
            let hits: Vec<_> = map.photons.iter().filter(|p| usize::from(p.band) == band && p.bounces == 2).collect();
            assert!(hits.len() > 2000, "{name}: band {band}: {} photons on the screen", hits.len());
            for p in &hits {
                let d = p.direction();
                let got = (phi - f64::from(d.y).atan2(f64::from(d.x))).to_degrees();
                assert!(
                    (got - expected).abs() < 2e-3,
                    "{name}: band {band} deviated {got:.4}°, relative index says {expected:.4}°"
                );
            }
        }
    }
}

/// Zero-area triangles (repeated corners, collinear corners) in a mesh are
/// dropped: the photon map is the one of the mesh without them.
#[test]
fn degenerate_triangles_change_nothing() {
    let exp = PrismExperiment { apex_deg: 60.0, incidence_deg: 50.0, beam_radius: 0.05, screen_x: 6.0 };
    let with_mesh = |degenerate: bool| {
        let mut scene = exp.scene(Glass::Sf11.dispersion(), settings(2000, BandSpec::Paper7));
        let Shape::Prism { vertices, extrude } = scene.objects[0].shape else { unreachable!("a prism") };
        let mut positions: Vec<Vec3> = vertices.iter().copied().chain(vertices.iter().map(|&p| p + extrude)).collect();
        // Outward winding, as in the mesh tests.
        let mut triangles =
            vec![[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]];
        if degenerate {
            positions.push((positions[0] + positions[2]) * 0.5); // on the edge 0–2
            triangles.extend([[0, 0, 1], [0, 6, 2], [4, 4, 4], [2, 6, 0]]);
        }
        scene.objects[0].shape =
            Shape::Mesh { positions, triangles, uvs: Vec::new(), normals: Vec::new(), tangents: Vec::new() };
        prepare(scene)
    };
    let (clean, dirty) = (with_mesh(false), with_mesh(true));
    for mut backend in every_backend() {
        let name = backend.name();
        let (a, b) = (trace(backend.as_mut(), &clean), trace(backend.as_mut(), &dirty));
        assert_finite(name, &b, None);
        assert!(!a.photons.is_empty());
        assert_eq!(a.photons, b.photons, "{name}: degenerate triangles changed the photon map");
    }
}

/// A camera that sees only floor far from every caustic photon: every
/// gather finds zero photons (the paper's W/Total with Total = 0) and the
/// image is the one without a caustic, bit for bit.
#[test]
fn an_empty_gather_adds_nothing() {
    for estimator in [Estimator::Paper, Estimator::Density] {
        let mut scene = small_sphere(|r| r.estimator = estimator).scene;
        (scene.camera.position, scene.camera.look_at) = (Vec3::new(30.0, 2.0, 30.0), Vec3::new(30.0, 0.0, 25.0));
        let scene = prepare(scene);
        for mut backend in every_backend() {
            let name = backend.name();
            let (map, image, none) = frame_and_base(backend.as_mut(), &scene);
            assert!(!map.photons.is_empty(), "{name}: the caustic photons exist, away from the camera");
            assert_finite(name, &map, Some(&image));
            assert_eq!(image.pixels, none.pixels, "{name}, {estimator:?}: an empty gather changed the image");
        }
    }
}

/// A floor seen from the side by a one-pixel camera, and a beam of `power`
/// folded by a mirror onto the floor right where the pixel looks: every
/// caustic photon lands within the gather `radius` of the pixel's point.
fn beam_into_one_pixel(estimator: Estimator, photons: u32, power: f32, radius: f32) -> PreparedScene {
    let mut render = settings(photons, BandSpec::Paper3);
    (render.width, render.height, render.estimator, render.radius, render.ambient) = (1, 1, estimator, radius, 0.0);
    let mut cam = camera();
    (cam.position, cam.look_at, cam.up, cam.fov_deg) = (Vec3::new(3.0, 3.0, 0.0), Vec3::ZERO, Vec3::Z, 1e-3);
    let mirror = prismatic_core::Material::new("mirror", MaterialKind::Mirror);
    prepare(Scene {
        render,
        camera: cam,
        lights: vec![Light::Beam {
            position: Vec3::new(-3.0, 2.0, 0.0),
            direction: Vec3::X,
            radius: 0.1,
            power,
            spectrum: Default::default(),
        }],
        materials: vec![white("floor"), mirror],
        objects: vec![
            Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 },
            Object {
                shape: Shape::Disk {
                    center: Vec3::new(0.0, 2.0, 0.0),
                    normal: Vec3::new(-1.0, -1.0, 0.0),
                    radius: 0.3,
                    inner_radius: 0.0,
                },
                material: 1,
            },
        ],
    })
}

/// More than 2^24 photons in one gather: the counts and sums stay exact
/// (an f32 counter stops at 2^24; an f32 sum of 2^24 photons drifts by
/// percent). The pixel that gathers 2^24 + 3 white photons of one beam has
/// the closed form's radiance, albedo/π · P/(πr²), with either estimator. A
/// GPU whose storage bindings cannot hold that many photons (lavapipe: 4 ×
/// 2^22) must say so and name the CPU backend; it is then held to the
/// closed form at 2^22 + 3 photons, where a plain f32 sum already drifts by
/// 1 to 4 %. The scalar reference is left out: its gather adds up in the
/// core's `GatherSums` (f64 sums, integer counts), as the CPU's does, and
/// tracing 2^24 photons one at a time was the slowest part of the test.
#[test]
fn more_than_two_to_the_24_photons_in_one_gather() {
    for estimator in [Estimator::Paper, Estimator::Density] {
        for mut backend in every_backend().into_iter().filter(|b| b.name() != "reference") {
            let name = backend.name();
            match one_dense_gather(backend.as_mut(), estimator, (1 << 24) + 3) {
                Ok(()) => {}
                Err(BackendError::OutOfMemory(why)) if name == "gpu" => {
                    assert!(why.contains("--backend cpu"), "{name}: {why}");
                    one_dense_gather(backend.as_mut(), estimator, (1 << 22) + 3).unwrap();
                }
                Err(e) => panic!("{name}: render: {e}"),
            }
        }
    }
}

/// [`beam_into_one_pixel`] with `photons` photons, against the closed form.
fn one_dense_gather(backend: &mut dyn Backend, estimator: Estimator, photons: u32) -> Result<(), BackendError> {
    let (power, radius) = (3.0f32, 0.5f32);
    let scene = fixed(&beam_into_one_pixel(estimator, photons, power, radius));
    let mut render = backend.prepare(&scene)?;
    render.run_pass(0, &mut NoProgress)?;
    let stats = render.stats()?;
    assert_eq!(stats.trace.stored, u64::from(photons), "{}: every photon reaches the floor", backend.name());
    let area = std::f64::consts::PI * f64::from(radius) * f64::from(radius);
    // Radiance leaving the white floor: albedo/π times the irradiance P/(πr²), white.
    let expected = 0.8 / std::f64::consts::PI * f64::from(power) / area;
    let got = render.image()?.pixels[0].as_dvec3() / f64::from(scene.scene.render.exposure);
    assert!(
        (got - glam::DVec3::splat(expected)).abs().max_element() <= 1e-5 * expected,
        "{}, {estimator:?}, {photons} photons: {got} vs {expected}",
        backend.name()
    );
    Ok(())
}

/// Photons exactly on grid cell borders (and exactly at the gather radius)
/// are found by both grids exactly as a brute-force search finds them.
#[test]
fn photons_on_cell_borders_are_found() {
    let bands = BandTable::new(BandSpec::Paper7);
    for radius in [0.25f32, 0.1, 0.3] {
        let cell = 2.0 * radius;
        let mut photons = Vec::new();
        for i in -4i32..=4 {
            for k in -4i32..=4 {
                for (dx, dz) in [(0.0, 0.0), (radius, 0.0), (0.0, radius), (radius * 0.5, cell)] {
                    let position = [i as f32 * cell + dx, 0.0, k as f32 * cell + dz];
                    let band = (i + k).rem_euclid(7) as u16;
                    photons.push(Photon {
                        position,
                        flux: 1.0,
                        direction_oct: oct_pack(Vec3::NEG_Y),
                        lambda_nm: bands.band(usize::from(band)).lambda_nm,
                        emission: 0,
                        band,
                        bounces: 1,
                    });
                }
            }
        }
        let core_grid = PhotonGrid::build(&photons, radius);
        let cpu_grid = CpuGrid::build(&photons, radius);
        for i in -8..=8 {
            for k in -8..=8 {
                for (dx, dz) in [(0.0, 0.0), (radius, 0.0), (radius, radius)] {
                    let point = Vec3::new(i as f32 * radius + dx, 0.0, k as f32 * radius + dz);
                    let q = GatherQuery { point, normal: Vec3::Y, radius, albedo: Vec3::ONE };
                    let brute: Vec3 = photons
                        .iter()
                        .filter(|p| (p.pos() - point).length_squared() <= radius * radius)
                        .map(|p| bands.rgb_of_flux(p.band, p.lambda_nm, p.flux))
                        .sum::<Vec3>()
                        / (std::f32::consts::PI * radius * radius);
                    let from_core = gather(&core_grid, &photons, &bands, Estimator::Density, &q);
                    let from_cpu = cpu_grid.gather_counted(&bands, Estimator::Density, &q).0;
                    for (what, got) in [("core", from_core), ("cpu", from_cpu)] {
                        assert!(
                            (got - brute).abs().max_element() <= 1e-5 * brute.max_element().max(1.0),
                            "{what} grid, r = {radius}, at {point}: {got} vs brute force {brute}"
                        );
                    }
                }
            }
        }
    }
}

/// One band (no dispersion possible: white photons only) and 256 bands
/// (the most): both render finite, white light stays white overall, and the
/// two agree on the image's energy.
#[test]
fn one_band_and_256_bands() {
    let one = small_sphere(|r| r.bands = BandSpec::Physical(1));
    let many = small_sphere(|r| {
        r.bands = BandSpec::Physical(256);
        r.photons = 500;
    });
    for mut backend in every_backend() {
        let name = backend.name();
        let (map1, image1) = frame(backend.as_mut(), &one);
        let (map256, image256) = frame(backend.as_mut(), &many);
        assert_finite(&format!("{name}, 1 band"), &map1, Some(&image1));
        assert_finite(&format!("{name}, 256 bands"), &map256, Some(&image256));
        assert!(map1.photons.iter().all(|p| p.band == WHITE_BAND), "{name}: one band cannot split");
        assert!(map256.photons.iter().any(|p| p.band == 255), "{name}: 256 bands split");
        let (e1, e256) = (image_energy(&image1), image_energy(&image256));
        assert!((e256 / e1 - 1.0).abs() < 0.05, "{name}: image energy with 1 band {e1}, with 256 {e256}");
    }
}

/// Thin beams aimed exactly at a mesh prism's vertex and along its edges, in a
/// closed catcher: on every backend the energy closes and the photon map
/// matches the reference's within the parity tolerances (the GPU's outlier
/// bound is `KNIFE_EDGE_OUTLIER_FRACTION`).
#[test]
fn beams_through_mesh_vertices_and_edges_match_the_reference() {
    let exp = PrismExperiment { apex_deg: 60.0, incidence_deg: 50.0, beam_radius: 1e-4, screen_x: 6.0 };
    let mut scene = exp.scene(Glass::Sf11.dispersion(), settings(3000, BandSpec::Paper7));
    scene.objects[1].shape = Shape::Sphere { center: Vec3::ZERO, radius: 50.0 };
    let Shape::Prism { vertices, extrude } = scene.objects[0].shape else { unreachable!("a prism") };
    let positions: Vec<Vec3> = vertices.iter().copied().chain(vertices.iter().map(|&p| p + extrude)).collect();
    let triangles = vec![[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]];
    scene.objects[0].shape = Shape::Mesh {
        positions: positions.clone(),
        triangles,
        uvs: Vec::new(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    // The apex's front vertex, the middle of the apex edge, the middle of the left face's diagonal.
    for target in [positions[2], (positions[2] + positions[5]) * 0.5, (positions[0] + positions[5]) * 0.5] {
        let mut scene = scene.clone();
        let Light::Beam { direction, .. } = scene.lights[0] else { unreachable!("a beam") };
        scene.lights[0] = Light::Beam {
            position: target - direction * 4.0,
            direction,
            radius: 1e-4,
            power: 1.0,
            spectrum: Default::default(),
        };
        let scene = prepare(scene);
        let reference = trace(&mut prismatic_core::ReferenceBackend, &scene);
        for mut backend in every_backend() {
            let case = format!("{}, beam at {target}", backend.name());
            let map = trace(backend.as_mut(), &scene);
            assert_finite(&case, &map, None);
            let s = map.stats;
            assert_eq!(s.flux_escaped, 0.0, "{case}");
            let accounted = s.flux_stored + s.flux_direct + s.flux_depth_limited;
            assert!((accounted - s.flux_emitted).abs() <= 1e-6 * s.flux_emitted, "{case}: {s:?}");
            let mut tol = Tolerance::of(backend.arithmetic());
            if backend.name() == "gpu" {
                tol = tol.allowing_outliers(KNIFE_EDGE_OUTLIER_FRACTION);
            }
            let report = compare_maps(&reference, &map, scene.bands.len(), tol);
            assert!(report.is_ok(), "{case}: {}", report.unwrap_err());
        }
    }
}
