//! Light tracing: the caustic photons the camera sees directly, connected
//! to the camera (`prismatic_core::photons::light_tracing`), and only the rest gathered;
//! its error falls as 1/√N (unbiased, no radius); and combined with the
//! gather behind mirrors and glass, no path is counted twice.

use prismatic_conformance::compare::{caustic_of, caustic_rel_rmse};
use prismatic_core::photons::light_tracing::splat_photons;
use prismatic_core::{Backend, NoProgress, PreparedScene, ReferenceBackend, Render, Vec3};
use prismatic_cpu::CpuBackend;
use prismatic_tests::backends::{every_backend, image_after};
use prismatic_tests::builtin;
use prismatic_tests::rough::{
    ball_top_radiance, beam_in_a_frosted_ball, beam_on_a_rough_floor, frosted, image_sum, lit_between_rough_metals,
    rough_metal,
};

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

#[test]
fn light_tracing_shows_a_mirrored_beam_on_a_rough_floor_as_the_beam_itself() {
    // Photons met on a rough metal or glass are connected to the camera
    // through its BSDF; the beam's image, lit straight, is the view's
    // highlight (its closed form is tested with the metals and rough
    // glass; the CPU's, 16 passes of jittered pixels). The two must
    // agree: summed over the image, within 2 % (measured 0.3 %).
    let metal = rough_metal(Vec3::new(0.9, 0.6, 0.3), 0.5);
    let sheet = frosted(1.5, 0.5, true);
    let cases = [("a rough metal", metal, false), ("a frosted sheet", sheet.clone(), false)];
    let through = [("light through a frosted sheet", sheet, true)];
    for (what, floor, below) in cases.into_iter().chain(through) {
        let scene = |mirrored: bool| beam_on_a_rough_floor(floor.clone(), below, mirrored, true);
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

#[test]
fn behind_a_rough_surface_where_photons_count_the_view_leaves_the_hidden_lights_highlights_to_them() {
    // The floor shows the ceiling's highlight (and the ceiling the floor's
    // reflection of it). With photons, those met on the floor (on the
    // ceiling) after the ceiling (the floor) bring it, light traced, or
    // without light tracing gathered at visible points on both (α 0.36
    // and 0.16, rough enough); the view's paths behind them show no
    // highlights, or the light would count twice (1.59 times the total,
    // measured, light traced). With no photons, the view's paths find it
    // at the other surface. Summed over the image, the three agree: the
    // view's estimate (4096 passes on the CPU, about 0.5 % noise) against
    // each backend's light traced and gathered ones (16 passes).
    let viewed = image_sum(&mut CpuBackend::new(), &lit_between_rough_metals(0, false), 4096);
    assert!(viewed > 1000.0, "the floor shows the ceiling's highlight: {viewed:.3}");
    for mut backend in every_backend() {
        let name = backend.name();
        for (how, light_tracing) in [("light traced", true), ("gathered", false)] {
            let got = image_sum(backend.as_mut(), &lit_between_rough_metals(20_000, light_tracing), 16);
            assert!((got / viewed - 1.0).abs() < 0.025, "{name}: {how} {got:.3}, viewed {viewed:.3}");
        }
    }
}

#[test]
fn light_leaving_rough_glass_toward_the_camera_has_walters_radiance() {
    // The top of a frosted ball lit from inside by a beam, seen head on
    // from far above (beam_in_a_frosted_ball), shows Walter et al.'s
    // radiance (ball_top_radiance); the glass's own BTDF (the renderer's,
    // which carries radiance across unscaled) would give 2.25 times it.
    let want = ball_top_radiance();
    let scene = beam_in_a_frosted_ball(true, false);
    for mut backend in every_backend() {
        let name = backend.name();
        let image = image_after(backend.as_mut(), &scene, 4);
        let got = image.pixels.iter().map(|p| f64::from(p.element_sum()) / 3.0).sum::<f64>() / 64.0;
        assert!((got / want - 1.0).abs() < 0.02, "{name}: light traced {got:.3}, Walter's {want:.3}");
    }
}
