//! Sampled view paths (`view_paths = "sampled"`): each pass traces one
//! jittered, spectrally sampled path per pixel, and the passes' mean
//! converges to the box-filtered image. An edge at a known angle against
//! its exact pixel coverage on every backend, and a scene with glass against
//! its supersampled image.

use prismatic_core::geometry::camera::PinholeCamera;
use prismatic_core::model::scene::{Light, Object, Shape, ViewPaths};
use prismatic_core::{Backend, Image, NoProgress, Scene, Vec3};
use prismatic_tests::backends::every_backend;
use prismatic_tests::{builtin, camera, prepare, settings, white};

/// The edge's angle to the image's rows, in degrees.
const EDGE_DEG: f32 = 23.0;

/// A floor triangle whose one edge crosses the view at [`EDGE_DEG`] (the
/// other two far outside it), under a sun straight above, seen from above
/// on black: white on one side of the edge, black on the other.
fn edge_scene(view_paths: ViewPaths) -> Scene {
    let mut render = settings(0, prismatic_core::BandSpec::Paper3);
    (render.ambient, render.view_paths) = (0.0, view_paths);
    let (c, d) = (Vec3::new(0.3, -0.2, 0.0), Vec3::new(EDGE_DEG.to_radians().cos(), EDGE_DEG.to_radians().sin(), 0.0));
    let side = Vec3::Z.cross(d);
    let positions = vec![c - d * 100.0, c + d * 100.0, c + side * 100.0];
    Scene {
        render,
        camera: camera(),
        lights: vec![Light::Sun {
            direction: -Vec3::Z,
            irradiance: std::f32::consts::PI,
            spectrum: Default::default(),
            mean_toward: None,
        }],
        materials: vec![white("floor")],
        objects: vec![Object {
            shape: Shape::Mesh {
                positions,
                triangles: vec![[0, 1, 2]],
                uvs: vec![],
                normals: vec![],
                tangents: Vec::new(),
            },
            material: 0,
        }],
    }
}

/// Where `p` falls on the image plane, in pixels from the top-left corner.
fn image_point(camera: &PinholeCamera, p: Vec3) -> (f64, f64) {
    let v = p - camera.origin;
    let q = v / v.dot(camera.forward) - camera.corner;
    (
        f64::from(q.dot(camera.right) / camera.right.length_squared()),
        f64::from(q.dot(camera.down) / camera.down.length_squared()),
    )
}

/// The area of the unit square at (x, y) on the side of the line through
/// `a` and `b` where `inside` lies (the square clipped by the half-plane).
fn coverage(x: f64, y: f64, a: (f64, f64), b: (f64, f64), inside: (f64, f64)) -> f64 {
    let side = |p: (f64, f64)| (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
    let sign = side(inside).signum();
    let square = [(x, y), (x + 1.0, y), (x + 1.0, y + 1.0), (x, y + 1.0)];
    let mut clipped = Vec::new();
    for i in 0..4 {
        let (p, q) = (square[i], square[(i + 1) % 4]);
        let (sp, sq) = (side(p) * sign, side(q) * sign);
        if sp >= 0.0 {
            clipped.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            let t = sp / (sp - sq);
            clipped.push((p.0 + (q.0 - p.0) * t, p.1 + (q.1 - p.1) * t));
        }
    }
    let n = clipped.len();
    (0..n).map(|i| clipped[i].0 * clipped[(i + 1) % n].1 - clipped[(i + 1) % n].0 * clipped[i].1).sum::<f64>().abs()
        / 2.0
}

/// The image of `passes` passes of `scene` on `backend`.
fn rendered(backend: &mut dyn Backend, scene: &Scene, passes: u32) -> Image {
    let mut render = backend.prepare(&prepare(scene.clone())).unwrap_or_else(|e| panic!("{}: {e}", backend.name()));
    for k in 0..passes {
        render.run_pass(k, &mut NoProgress).unwrap_or_else(|e| panic!("{}: pass {k}: {e}", backend.name()));
    }
    render.image().unwrap_or_else(|e| panic!("{}: {e}", backend.name()))
}

/// Largest and mean error against the exact coverage (in units of the
/// white side's radiance) over the pixels the edge crosses.
fn edge_errors(image: &Image, scene: &Scene) -> (f64, f64) {
    let r = &scene.render;
    let camera = PinholeCamera::new(&scene.camera, r.width, r.height);
    let Shape::Mesh { positions, .. } = &scene.objects[0].shape else { unreachable!() };
    let (a, b, inside) =
        (image_point(&camera, positions[0]), image_point(&camera, positions[1]), image_point(&camera, positions[2]));
    // albedo/π · E with E = π: the white side's radiance is the albedo.
    let white = 0.8;
    let mut errors = Vec::new();
    for y in 0..r.height {
        for x in 0..r.width {
            let expected = coverage(f64::from(x), f64::from(y), a, b, inside);
            if expected > 0.0 && expected < 1.0 {
                let got = f64::from(image.pixels[(y * r.width + x) as usize].x) / white;
                errors.push((got - expected).abs());
            }
        }
    }
    assert!(errors.len() > 30, "the edge crosses {} pixels", errors.len());
    (errors.iter().copied().fold(0.0, f64::max), errors.iter().sum::<f64>() / errors.len() as f64)
}

#[test]
fn an_edges_pixels_converge_to_their_coverage_on_every_backend() {
    let sampled = edge_scene(ViewPaths::Sampled);
    for mut backend in every_backend() {
        let name = backend.name();
        let (max4, mean4) = edge_errors(&rendered(backend.as_mut(), &sampled, 4), &sampled);
        let (max64, mean64) = edge_errors(&rendered(backend.as_mut(), &sampled, 64), &sampled);
        eprintln!(
            "{name}: edge error after 4 passes max {max4:.4} mean {mean4:.4}, after 64 max {max64:.4} mean {mean64:.4}"
        );
        // Stratified jitter: 64 passes leave 0.036 and 0.012 here (the same bits on every backend).
        assert!(max64 < 0.045 && mean64 < 0.015, "{name}: after 64 passes max {max64}, mean {mean64}");
        assert!(mean64 < mean4 / 4.0, "{name}: the error falls with passes: {mean4} then {mean64}");
    }
    // Rays through the pixel centres leave a staircase: all or nothing.
    let centre = edge_scene(ViewPaths::Centre);
    let (max, mean) = edge_errors(&rendered(&mut prismatic_core::ReferenceBackend, &centre, 4), &centre);
    assert!(max > 0.4 && mean > 0.15, "pixel centres: max {max}, mean {mean}");
}

#[test]
fn sampled_view_paths_converge_to_the_supersampled_image() {
    // The sphere's floor, shadow, caustic and its dispersed view through
    // the glass: sampled paths at 96² converge to the box-filtered image,
    // here centre rays at 384² averaged over 4 × 4 blocks (wavelength and
    // Fresnel choices weighted by their probabilities, nothing lost).
    let image = |size: u32, view_paths: ViewPaths, passes: u32| -> Image {
        let scene =
            builtin("sphere", |r| (r.width, r.height, r.photons, r.view_paths) = (size, size, 20_000, view_paths));
        let mut render = prismatic_cpu::CpuBackend::new().prepare(&scene).expect("prepare");
        for k in 0..passes {
            render.run_pass(k, &mut NoProgress).expect("pass");
        }
        render.image().expect("image")
    };
    let (sampled, fine) = (image(96, ViewPaths::Sampled, 64), image(384, ViewPaths::Centre, 16));
    let centre = image(96, ViewPaths::Centre, 64);
    let block = |x: u32, y: u32| -> Vec3 {
        (0..16).map(|i| fine.pixels[((4 * y + i / 4) * 384 + 4 * x + i % 4) as usize]).sum::<Vec3>() / 16.0
    };
    let (mut sum_sampled, mut sum_fine, mut squared, mut squared_centre) = (Vec3::ZERO, Vec3::ZERO, 0.0f64, 0.0f64);
    for y in 0..96 {
        for x in 0..96 {
            let (i, f) = ((y * 96 + x) as usize, block(x, y));
            (sum_sampled, sum_fine) = (sum_sampled + sampled.pixels[i], sum_fine + f);
            squared += f64::from((sampled.pixels[i] - f).length_squared());
            squared_centre += f64::from((centre.pixels[i] - f).length_squared());
        }
    }
    let (rmse, rmse_centre) = ((squared / (96.0 * 96.0)).sqrt(), (squared_centre / (96.0 * 96.0)).sqrt());
    eprintln!("mean: sampled {sum_sampled}, supersampled {sum_fine}; RMSE sampled {rmse:.4}, centre {rmse_centre:.4}");
    // Edges and the checker's moiré: centre rays stay off the filtered image.
    assert!(rmse < rmse_centre / 2.0, "RMSE to the supersampled image: sampled {rmse}, centre rays {rmse_centre}");
    for c in 0..3 {
        let rel = (sum_sampled[c] - sum_fine[c]).abs() / sum_fine[c];
        assert!(rel < 0.01, "channel {c}: sampled {sum_sampled}, supersampled {sum_fine}: {rel:.4}");
    }
}
