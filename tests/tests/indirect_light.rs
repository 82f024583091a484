//! Indirect light against its closed form, on every backend: inside a
//! closed box whose walls glow with radiance L_e and reflect a fraction a,
//! every wall shows L_e Σ aᵏ (the furnace test), summed up to the bounce
//! the depth limit allows; light tracing and the gather both reach it.
//! Off, as before; on, coloured walls bleed their colour.

use prismatic_core::model::scene::{Camera, Material, MaterialKind, Object, RenderSettings, Shape};
use prismatic_core::{Image, PreparedScene, Scene, Vec3};
use prismatic_tests::backends::{every_backend, frame};
use prismatic_tests::prepare;

/// The walls' radiance.
const GLOW: f32 = 1.0;
/// The image's side.
const SIDE: u32 = 24;

fn diffuse(name: &str, albedo: Vec3, emission: Vec3) -> Material {
    Material {
        name: name.into(),
        kind: MaterialKind::Diffuse { albedo, checker: None, texture: None, emission },
        normal_map: None,
        roughness_map: None,
        film_map: None,
        specular_map: None,
    }
}

/// The twelve triangles of the cube [−1, 1]³, wound to face inward.
fn inward_cube() -> Shape {
    let positions: Vec<Vec3> =
        (0..8).map(|i| Vec3::new([-1.0, 1.0][i & 1], [-1.0, 1.0][(i >> 1) & 1], [-1.0, 1.0][(i >> 2) & 1])).collect();
    // Each face's corners in order round it, then turned to face the centre.
    let faces = [[0, 2, 6, 4], [1, 5, 7, 3], [0, 4, 5, 1], [2, 3, 7, 6], [0, 1, 3, 2], [4, 6, 7, 5]];
    let mut triangles = Vec::new();
    for [a, b, c, d] in faces {
        for t in [[a, b, c], [a, c, d]] {
            let [p, q, r] = t.map(|i| positions[i as usize]);
            let inward = (q - p).cross(r - p).dot(-(p + q + r)) > 0.0;
            triangles.push(if inward { t } else { [t[0], t[2], t[1]] });
        }
    }
    Shape::Mesh { positions, triangles, uvs: Vec::new(), normals: Vec::new(), tangents: Vec::new() }
}

/// The camera at the box's centre, looking at a wall.
fn inside() -> Camera {
    Camera { position: Vec3::ZERO, look_at: Vec3::Z, up: Vec3::Y, fov_deg: 60.0 }
}

/// The glowing box of albedo `albedo`, with `indirect` photons a pass.
fn furnace(albedo: f32, indirect: u32, edit: impl FnOnce(&mut RenderSettings)) -> PreparedScene {
    let mut render = RenderSettings {
        width: SIDE,
        height: SIDE,
        photons: 0,
        indirect_photons: indirect,
        max_depth: 6,
        ambient: 0.0,
        ..RenderSettings::default()
    };
    edit(&mut render);
    prepare(Scene {
        render,
        camera: inside(),
        lights: Vec::new(),
        materials: vec![diffuse("wall", Vec3::splat(albedo), Vec3::splat(GLOW))],
        objects: vec![Object { shape: inward_cube(), material: 0 }],
    })
}

/// L_e Σₖ aᵏ for k = 0 (the glow) to D + 1: light reflected once (direct
/// light) and then D more times, the depth limit's last.
fn closed_form(albedo: f32, max_depth: u32) -> f32 {
    GLOW * (1.0 - albedo.powi(max_depth as i32 + 2)) / (1.0 - albedo)
}

/// The mean over the image, and over each of its 4 × 4 blocks (the wall's
/// edges and corners included).
fn means(image: &Image) -> (f32, Vec<f32>) {
    let grey = |p: &Vec3| p.element_sum() / 3.0;
    let all = image.pixels.iter().map(grey).sum::<f32>() / image.pixels.len() as f32;
    let b = SIDE as usize / 4;
    let blocks = (0..16)
        .map(|k| {
            let (bx, by) = (k % 4 * b, k / 4 * b);
            let sum: f32 = (0..b * b).map(|i| grey(&image.pixels[(by + i / b) * SIDE as usize + bx + i % b])).sum();
            sum / (b * b) as f32
        })
        .collect();
    (all, blocks)
}

#[test]
fn a_glowing_box_shows_the_furnace_closed_form_on_every_backend() {
    for albedo in [0.5, 0.75] {
        let scene = furnace(albedo, 100_000, |_| {});
        assert!(scene.plan.indirect.on, "{}", scene.plan.explain());
        let want = closed_form(albedo, 6);
        for mut backend in every_backend() {
            let name = backend.name();
            let (map, image) = frame(backend.as_mut(), &scene);
            assert!(map.stats.stored > 0, "{name}: no indirect photon stored");
            let (mean, blocks) = means(&image);
            assert!((mean - want).abs() < 0.01 * want, "{name}, a = {albedo}: mean {mean}, closed form {want}");
            for (k, block) in blocks.iter().enumerate() {
                assert!((block - want).abs() < 0.1 * want, "{name}, a = {albedo}: block {k} shows {block} of {want}");
            }
        }
    }
}

#[test]
fn the_gather_reaches_the_same_closed_form_as_light_tracing() {
    // Gathered at the visible points within a radius (the walls' middles:
    // a disc that crosses an edge of the box finds fewer photons).
    let scene = furnace(0.5, 60_000, |r| (r.light_tracing, r.radius) = (false, 0.15));
    let want = closed_form(0.5, 6);
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, image) = frame(backend.as_mut(), &scene);
        let (_, blocks) = means(&image);
        for k in [5, 6, 9, 10] {
            assert!((blocks[k] - want).abs() < 0.05 * want, "{name}: centre block {k} shows {} of {want}", blocks[k]);
        }
    }
}

#[test]
fn without_indirect_photons_the_box_shows_its_glow_and_direct_light_only() {
    let scene = furnace(0.5, 0, |_| {});
    assert!(!scene.plan.indirect.on && !scene.plan.photon_pass(), "{}", scene.plan.explain());
    let want = GLOW * 1.5;
    for mut backend in every_backend() {
        let name = backend.name();
        let (map, image) = frame(backend.as_mut(), &scene);
        assert_eq!(map.stats.emitted, 0, "{name}");
        let (mean, _) = means(&image);
        assert!((mean - want).abs() < 1e-3 * want, "{name}: {mean} vs L_e (1 + a) = {want}");
    }
}

#[test]
fn a_red_wall_bleeds_red_onto_a_white_floor() {
    // A white floor and a red wall meeting at a right angle, lit from
    // above by a white panel: seen from straight above, the floor next to
    // the wall is redder than the floor far from it, and only with
    // indirect light.
    let red = diffuse("red", Vec3::new(0.8, 0.1, 0.1), Vec3::ZERO);
    let white = diffuse("white", Vec3::splat(0.8), Vec3::ZERO);
    let panel = diffuse("panel", Vec3::splat(0.5), Vec3::splat(8.0));
    let corners = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)].map(|(x, z)| Vec3::new(x, 2.0, z));
    // Wound to face down.
    let panel_shape = Shape::Mesh {
        positions: corners.to_vec(),
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        uvs: Vec::new(),
        normals: Vec::new(),
        tangents: Vec::new(),
    };
    let scene = |indirect: u32, x: f32| {
        let render = RenderSettings {
            width: SIDE,
            height: SIDE,
            photons: 0,
            indirect_photons: indirect,
            ambient: 0.0,
            ..RenderSettings::default()
        };
        let above =
            Camera { position: Vec3::new(x, 1.0, 0.0), look_at: Vec3::new(x, 0.0, 0.0), up: Vec3::Z, fov_deg: 10.0 };
        prepare(Scene {
            render,
            camera: above,
            lights: Vec::new(),
            materials: vec![white.clone(), red.clone(), panel.clone()],
            objects: vec![
                Object { shape: Shape::Plane { point: Vec3::ZERO, normal: Vec3::Y }, material: 0 },
                // The wall at x = −1, facing +x.
                Object { shape: Shape::Plane { point: Vec3::new(-1.0, 0.0, 0.0), normal: Vec3::X }, material: 1 },
                Object { shape: panel_shape.clone(), material: 2 },
            ],
        })
    };
    let redness = |backend: &mut dyn prismatic_core::Backend, indirect: u32, x: f32| {
        let (_, image) = frame(backend, &scene(indirect, x));
        let sum: Vec3 = image.pixels.iter().sum();
        sum.x / sum.y
    };
    for mut backend in every_backend() {
        let name = backend.name();
        let (near, far) = (redness(backend.as_mut(), 200_000, -0.8), redness(backend.as_mut(), 200_000, 0.8));
        assert!(near > 1.1 * far && far > 0.99, "{name}: red by the wall {near}, far from it {far}");
        let (near, far) = (redness(backend.as_mut(), 0, -0.8), redness(backend.as_mut(), 0, 0.8));
        assert!(
            (near - 1.0).abs() < 1e-4 && (far - 1.0).abs() < 1e-4,
            "{name}: without indirect light both are white ({near}, {far})"
        );
    }
}

#[test]
fn each_bands_bounced_flux_matches_its_closed_form_with_one_wavelength_a_path_or_several() {
    // The glowing box with coloured walls: band b of the power Φ_b the
    // walls emit is stored Φ_b Σ_{k=1}^{D} ρ_bᵏ (second diffuse hit to the
    // depth limit's). A path carrying several wavelengths goes on with
    // survival Σ fⱼ ρⱼ and fractions fⱼ ρⱼ / Σ fⱼ ρⱼ, which must keep
    // every band's expectation, as one wavelength a path does.
    use prismatic_core::model::bands::BandSpec;
    use prismatic_core::model::scene::WavelengthSampling::{RandomBand, Split};
    use prismatic_tests::backends::trace;
    let albedo = Vec3::new(0.8, 0.5, 0.2);
    let depth = 6;
    let cases = [
        (Split, BandSpec::Paper7, 4, 40_000),
        (Split, BandSpec::Paper3, 3, 40_000),
        (Split, BandSpec::Physical(12), 4, 40_000),
        (RandomBand, BandSpec::Paper7, 1, 150_000),
    ];
    for (sampling, bands, carried, photons) in cases {
        let mut scene = furnace(0.5, photons, |r| (r.wavelengths, r.bands, r.max_depth) = (sampling, bands, depth));
        scene.scene.materials[0] = diffuse("wall", albedo, Vec3::splat(GLOW));
        let scene = prepare(scene.scene);
        let n = scene.bands.len();
        let spectrum = &scene.light_spectra[0];
        let emitted =
            |b: usize| scene.total_power * if spectrum.is_uniform() { 1.0 / n as f32 } else { spectrum.band_shares[b] };
        let want: Vec<f64> = (0..n)
            .map(|b| {
                let rho = scene.bands.bounce_reflectance(albedo, b as u16, scene.bands.band(b).lambda_nm);
                f64::from(emitted(b)) * (1..=depth as i32).map(|k| f64::from(rho).powi(k)).sum::<f64>()
            })
            .collect();
        for mut backend in every_backend() {
            let name = backend.name();
            let map = trace(backend.as_mut(), &scene);
            let mut got = vec![0.0f64; n];
            for p in &map.photons {
                got[usize::from(p.band)] += f64::from(p.flux);
            }
            let case = format!("{name}, {sampling:?} over {bands}");
            for b in 0..n {
                let err = (got[b] - want[b]).abs() / want[b];
                assert!(err < 0.04, "{case}: band {b} stored {:.4} W, closed form {:.4} W", got[b], want[b]);
            }
            // Photons stored at one hit: one per wavelength the path carries.
            let hits = map.photons.iter().map(|p| (p.emission, p.bounces)).collect::<std::collections::HashSet<_>>();
            let per_hit = map.photons.len() as f64 / hits.len() as f64;
            let most = f64::from(carried);
            assert!(
                per_hit <= most && per_hit > most - 0.25,
                "{case}: {per_hit} photons a hit, {carried} wavelengths a path"
            );
        }
    }
}
