//! Smooth shading on every backend: a tessellated glass ball with its
//! vertex normals bends each photon as the round ball does, and a diffuse
//! one is lit as the round ball is; without them each flat facet bends
//! its photons as a little prism would, and takes one cosine of the light.

use prismatic_conformance::scenes::{smooth_sphere_mesh, sphere_mesh};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::dispersion::Glass;
use prismatic_core::model::scene::{Camera, Light, Object, Shape};
use prismatic_core::render::aov::features;
use prismatic_core::{Image, PhotonMap, Vec3};
use prismatic_tests::backends::{every_backend, frame, trace};
use prismatic_tests::{prepare, settings, sphere_in_a_catcher, white};
use std::collections::HashMap;

const PHOTONS: u32 = 4000;

/// The paper's scene: a beam of radius 0.9 through a BK7 ball of radius 1
/// (`ball`) onto the catcher of radius 50 around it.
fn ball_in_a_catcher(ball: Shape) -> prismatic_core::Scene {
    let mut scene = sphere_in_a_catcher(Glass::Bk7.dispersion(), settings(PHOTONS, BandSpec::Paper3), 0.0, 0.9);
    scene.objects[0].shape = ball;
    // Every photon leaves as it does toward the round ball (not aimed at the mesh's bounds).
    scene.render.projection_maps = false;
    scene
}

/// The median angle (degrees, seen from the ball's centre) between where
/// `map` and `round` store the photons they both store, and the share of
/// `round`'s photons that `map` stores too.
fn median_angle_and_shared(map: &PhotonMap, round: &PhotonMap) -> (f32, f32) {
    let at: HashMap<_, Vec3> = round.photons.iter().map(|p| (p.key(), p.pos())).collect();
    let mut angles: Vec<f32> = map
        .photons
        .iter()
        .filter_map(|p| at.get(&p.key()).map(|q| p.pos().normalize().angle_between(q.normalize()).to_degrees()))
        .collect();
    angles.sort_by(f32::total_cmp);
    (angles[angles.len() / 2], angles.len() as f32 / round.photons.len() as f32)
}

#[test]
fn a_smooth_mesh_ball_bends_photons_as_the_round_ball_does_on_every_backend() {
    let round = prepare(ball_in_a_catcher(Shape::Sphere { center: Vec3::ZERO, radius: 1.0 }));
    let smooth = prepare(ball_in_a_catcher(smooth_sphere_mesh(Vec3::ZERO, 1.0, 24)));
    let flat = prepare(ball_in_a_catcher(sphere_mesh(Vec3::ZERO, 1.0, 24)));
    for mut backend in every_backend() {
        let name = backend.name();
        let round = trace(backend.as_mut(), &round);
        assert!(round.photons.len() > 2 * PHOTONS as usize, "{name}: most photons cross the ball");
        let (angle, shared) = median_angle_and_shared(&trace(backend.as_mut(), &smooth), &round);
        assert!(angle < 0.25 && shared > 0.95, "{name}: smooth facets: median {angle:.3}°, {shared:.3} shared");
        let (angle, shared) = median_angle_and_shared(&trace(backend.as_mut(), &flat), &round);
        assert!(angle > 1.0, "{name}: flat facets: median {angle:.3}°, {shared:.3} shared");
    }
}

/// A scene file's mesh takes `normals`, one per position; a count that
/// differs or a zero normal is refused with its key.
#[test]
fn scene_files_give_meshes_normals_and_bad_ones_are_refused() {
    let scene = |normals: &str| {
        format!(
            "[camera]\nposition = [0, 1, 5]\nlook_at = [0, 0, 0]\n\n\
             [[light]]\nkind = \"point\"\nposition = [0, 4, 0]\npower = 10\n\n\
             [material.silver]\nkind = \"metal\"\ncolor = \"silver\"\n\n\
             [[object]]\nshape = \"mesh\"\nmaterial = \"silver\"\n\
             positions = [[0, 0, 0], [1, 0, 0], [0, 0, -1]]\ntriangles = [[0, 1, 2]]\n{normals}\n"
        )
    };
    let check = |normals: &str| {
        let doc =
            prismatic_cli::scene_file::parse(&scene(normals), "test.toml", None).unwrap_or_else(|e| panic!("{e}"));
        doc.validate().map(|_| doc)
    };
    let doc = check("normals = [[0, 1, 0], [0.6, 0.8, 0], [0, 2, 0]]").unwrap_or_else(|e| panic!("{e}"));
    let Shape::Mesh { normals, .. } = &doc.scene.objects[0].shape else { panic!("a mesh") };
    assert_eq!(normals, &[Vec3::Y, Vec3::new(0.6, 0.8, 0.0), Vec3::new(0.0, 2.0, 0.0)]);
    let e = check("normals = [[0, 1, 0], [0, 1, 0]]").unwrap_err();
    assert_eq!(e.key, "object[0].normals", "{e}");
    assert!(e.reason.contains("2 normals for 3 positions"), "{e}");
    let e = check("normals = [[0, 1, 0], [0, 0, 0], [0, 1, 0]]").unwrap_err();
    assert_eq!(e.key, "object[0].normals[1]", "{e}");
}

/// A white ball (`ball`) lit by a sun from the upper left, filling a
/// 48×48 image head on (camera at z = 4, 40°).
fn sunlit_ball(ball: Shape) -> prismatic_core::PreparedScene {
    let mut render = settings(1000, BandSpec::Paper3);
    (render.width, render.height) = (48, 48);
    prepare(prismatic_core::Scene {
        render,
        camera: Camera { position: Vec3::new(0.0, 0.0, 4.0), look_at: Vec3::ZERO, up: Vec3::Y, fov_deg: 40.0 },
        lights: vec![Light::Sun {
            direction: Vec3::new(1.0, -1.0, -1.0).normalize(),
            irradiance: 2.0,
            spectrum: Default::default(),
            mean_toward: None,
        }],
        materials: vec![white("ball")],
        objects: vec![Object { shape: ball, material: 0 }],
    })
}

/// Mean absolute difference of two images' pixels (every channel).
fn mean_difference(a: &Image, b: &Image) -> f32 {
    let sum: f32 = a.pixels.iter().zip(&b.pixels).map(|(p, q)| (*p - *q).abs().element_sum()).sum();
    sum / (3 * a.pixels.len()) as f32
}

/// A diffuse ball mesh with its normals takes the sun's cosine as the
/// round ball does (on every backend), and gives a denoiser the round
/// ball's normals: far closer than the same mesh flat, whose facets each
/// take one cosine. (The silhouette's polygon differs alike in both.)
#[test]
fn a_smooth_diffuse_ball_is_shaded_as_the_round_ball_on_every_backend() {
    let round = sunlit_ball(Shape::Sphere { center: Vec3::ZERO, radius: 1.0 });
    let smooth = sunlit_ball(smooth_sphere_mesh(Vec3::ZERO, 1.0, 16));
    let flat = sunlit_ball(sphere_mesh(Vec3::ZERO, 1.0, 16));
    for mut backend in every_backend() {
        let name = backend.name();
        let (_, want) = frame(backend.as_mut(), &round);
        let (from_smooth, from_flat) = (
            mean_difference(&frame(backend.as_mut(), &smooth).1, &want),
            mean_difference(&frame(backend.as_mut(), &flat).1, &want),
        );
        assert!(from_smooth < 0.3 * from_flat, "{name}: smooth {from_smooth:.5}, flat {from_flat:.5} off");
    }
    let normals = |scene: &prismatic_core::PreparedScene| features(scene).normal;
    let want = normals(&round);
    let (from_smooth, from_flat) = (mean_difference(&normals(&smooth), &want), mean_difference(&normals(&flat), &want));
    assert!(from_smooth < 0.3 * from_flat, "normals: smooth {from_smooth:.5}, flat {from_flat:.5} off");
}
