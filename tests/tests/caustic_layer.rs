//! The caustic layer (`prismatic_core::render::layer`): the irradiance an
//! engine's surfaces receive, in the engine's frame. On a diffuse floor the
//! camera sees directly it is the light-traced image's caustic over the
//! floor's ρ/π; an engine's occluder in its depth buffer hides it. (Every
//! backend against the reference: the conformance suite's
//! `caustic_layers_match_the_reference`.)

use prismatic_core::geometry::camera::PinholeCamera;
use prismatic_core::model::scene::{MaterialKind, ViewPaths};
use prismatic_core::optics::surface::Surface;
use prismatic_core::{Backend, Image, LayerFrame, NoProgress, PreparedScene, ReferenceBackend, Vec3};

/// The floor's grey albedo.
const ALBEDO: f32 = 0.8;

/// The built-in sphere, light traced through pixel centres, on a plain grey floor.
fn scene() -> PreparedScene {
    let mut doc = prismatic_cli::load_scene("sphere").expect("built-in sphere");
    let r = &mut doc.scene.render;
    (r.width, r.height, r.photons, r.light_tracing, r.view_paths) = (96, 72, 20_000, true, ViewPaths::Centre);
    doc.scene.materials[0].kind =
        MaterialKind::Diffuse { albedo: Vec3::splat(ALBEDO), checker: None, texture: None, emission: Vec3::ZERO };
    PreparedScene::new(doc.scene).expect("valid")
}

/// Passes 0..2 of `scene` on the reference, drawn as a layer in `frame` when given.
fn image(scene: &PreparedScene, frame: Option<&LayerFrame>) -> (Image, Image) {
    let mut render = ReferenceBackend.prepare(scene).expect("prepare");
    render.set_layer(frame).expect("the frame fits");
    for k in 0..2 {
        render.run_pass(k, &mut NoProgress).expect("pass");
    }
    (render.image().expect("image"), render.base().expect("base"))
}

/// Per pixel, whether the camera sees the diffuse floor at the pixel's centre.
fn sees_the_floor(scene: &PreparedScene) -> Vec<bool> {
    let r = &scene.scene.render;
    let camera = PinholeCamera::new(&scene.scene.camera, r.width, r.height);
    (0..r.height)
        .flat_map(|y| (0..r.width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let hit = scene.intersect(&camera.ray(x, y), f32::INFINITY);
            hit.is_some_and(|h| matches!(scene.surfaces[h.object], Surface::Diffuse { .. }))
        })
        .collect()
}

#[test]
fn the_layer_is_the_light_traced_caustic_over_the_albedo() {
    let scene = scene();
    let (traced, base) = image(&scene, None);
    let (layer, layer_base) = image(&scene, Some(&LayerFrame::seen_by_camera(&scene)));
    assert!(layer_base.pixels.iter().all(|p| *p == Vec3::ZERO), "a layer's base is black");
    let floor = sees_the_floor(&scene);
    let brdf = ALBEDO / std::f32::consts::PI;
    let (mut want, mut got, mut lit, mut off) = (0.0f64, 0.0f64, 0, 0);
    for (i, on_floor) in floor.iter().enumerate() {
        let caustic = traced.pixels[i] - base.pixels[i];
        let expected = layer.pixels[i] * brdf;
        if !on_floor {
            assert_eq!(layer.pixels[i], Vec3::ZERO, "pixel {i}: a layer on glass");
            continue;
        }
        want += f64::from(caustic.element_sum());
        got += f64::from(expected.element_sum());
        if caustic.max_element() > 0.0 {
            lit += 1;
            if (caustic - expected).abs().max_element() > 1e-4 * caustic.max_element() + 1e-6 {
                off += 1;
            }
        }
    }
    assert!(lit > 100, "{lit} lit floor pixels");
    // A photon at the sphere's silhouette may be hidden from the camera
    // (light tracing) in a pixel whose centre sees the floor (the layer).
    assert!(off * 100 <= lit, "{off} of {lit} lit floor pixels differ");
    assert!((got / want - 1.0).abs() < 1e-3, "the floor's caustic: layer × ρ/π {got}, light traced {want}");
}

#[test]
fn an_engines_occluder_hides_the_caustic_behind_it() {
    // An engine's object that prismatic's scene does not hold: nearer
    // depths over the left half of the frame, at 1 unit from the camera.
    let scene = scene();
    let frame = LayerFrame::seen_by_camera(&scene);
    let mut occluded = frame.clone();
    let w = frame.width as usize;
    for (i, depth) in occluded.depth.iter_mut().enumerate() {
        if i % w < w / 2 {
            *depth = 1.0;
        }
    }
    let (open, _) = image(&scene, Some(&frame));
    let (hidden, _) = image(&scene, Some(&occluded));
    let left = |img: &Image| -> f32 {
        img.pixels.iter().enumerate().filter(|(i, _)| i % w < w / 2).map(|(_, p)| p.element_sum()).sum()
    };
    assert!(left(&open) > 0.0, "the caustic reaches the left half");
    assert_eq!(left(&hidden), 0.0, "the occluder hides it");
    for (i, (a, b)) in open.pixels.iter().zip(&hidden.pixels).enumerate() {
        if i % w >= w / 2 {
            assert_eq!(a, b, "pixel {i}: the right half is untouched");
        }
    }
}
