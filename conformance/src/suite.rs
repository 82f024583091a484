//! The test bodies every backend must pass, each a function of the backend
//! under test. The scalar reference ([`ReferenceBackend`]) is the
//! specification: results are compared with its under the rules of
//! [`crate::compare`], and a backend's own results with each other bit for
//! bit where the protocol promises it (passes merge exactly, run in any
//! order, an update gives a fresh render's sums).

use crate::compare::{compare_images, compare_maps};
use crate::scenes;
use crate::tolerance::Tolerance;
use prismatic_core::model::scene::{Light, PhotonSequence, RadiusMode, ViewPaths};
use prismatic_core::{
    Accumulation, Backend, BackendError, BandSpec, Change, LayerFrame, NoProgress, PhotonMap, PreparedScene,
    ReferenceBackend, Render, Scene,
};

/// A render of `scene` on `backend`, panicking with the backend's name.
fn prepare(backend: &mut dyn Backend, scene: &PreparedScene) -> Box<dyn Render> {
    let name = backend.name();
    backend.prepare(scene).unwrap_or_else(|e| panic!("{name}: prepare: {e}"))
}

/// `render` after running `passes` in order.
fn run(render: &mut dyn Render, passes: impl IntoIterator<Item = u32>) {
    for k in passes {
        render.run_pass(k, &mut NoProgress).unwrap_or_else(|e| panic!("{}: pass {k}: {e}", render.backend()));
    }
}

fn sums(render: &mut dyn Render) -> Accumulation {
    render.sums().unwrap_or_else(|e| panic!("{}: sums: {e}", render.backend()))
}

fn photon_map(render: &mut dyn Render, pass: u32) -> PhotonMap {
    render.photon_map(pass, &mut NoProgress).unwrap_or_else(|e| panic!("{}: photon map: {e}", render.backend()))
}

/// `scene` with `edit` applied to its description.
fn edited(scene: &PreparedScene, edit: impl FnOnce(&mut Scene)) -> PreparedScene {
    let mut s = scene.scene.clone();
    edit(&mut s);
    PreparedScene::new(s).unwrap_or_else(|e| panic!("an edited conformance scene is invalid: {e}"))
}

/// The photon map of a pass is the reference's (same keys in canonical
/// order, positions and flux within the parity tolerances), with the same
/// emissions, for several passes, with Sobol and with random photons.
pub fn photon_maps_match_the_reference(backend: &mut dyn Backend) {
    let tol = Tolerance::of(backend.arithmetic());
    let sequences = [PhotonSequence::Sobol, PhotonSequence::Random];
    for ((name, scene), sequence) in scenes::with_caustics().into_iter().flat_map(|s| sequences.map(|q| (s.clone(), q)))
    {
        let scene = edited(&scene, |s| s.render.photon_sequence = sequence);
        let mut reference = prepare(&mut ReferenceBackend, &scene);
        let mut got = prepare(backend, &scene);
        for pass in [0, 3] {
            let (expected, map) = (photon_map(reference.as_mut(), pass), photon_map(got.as_mut(), pass));
            let case = format!("{}, {name}, {} photons, pass {pass}", backend.name(), sequence.name());
            assert!(map.is_canonical(), "{case}: not in canonical order");
            assert!(!expected.photons.is_empty(), "{case}: the reference stores no photon to compare");
            assert_eq!(map.stats.emitted, expected.stats.emitted, "{case}: emitted");
            compare_maps(&expected, &map, scene.bands.len(), tol).unwrap_or_else(|e| panic!("{case}: {e}"));
        }
    }
}

/// The paper's frame (one pass, fixed radius) and a progressive render's
/// first passes give the reference's image, and the same visible points.
pub fn images_match_the_reference(backend: &mut dyn Backend) {
    let tol = Tolerance::of(backend.arithmetic());
    for (name, scene) in scenes::with_caustics() {
        for mode in [RadiusMode::Fixed, RadiusMode::Progressive] {
            let scene = edited(&scene, |s| s.render.radius_mode = mode);
            let passes = if mode == RadiusMode::Fixed { 1 } else { 3 };
            let case = format!("{}, {name}, {} radii, {passes} passes", backend.name(), mode.name());
            let mut reference = prepare(&mut ReferenceBackend, &scene);
            let mut got = prepare(backend, &scene);
            run(reference.as_mut(), 0..passes);
            run(got.as_mut(), 0..passes);
            let (expected, image) = (reference.image().unwrap(), got.image().unwrap());
            compare_images(&reference.base().unwrap(), &got.base().unwrap(), tol)
                .unwrap_or_else(|e| panic!("{case}: image without caustics: {e}"));
            compare_images(&expected, &image, tol).unwrap_or_else(|e| panic!("{case}: {e}"));
            let (want, have) = (reference.stats().unwrap(), got.stats().unwrap());
            assert_eq!(have.visible_points, want.visible_points, "{case}: visible points");
            assert_eq!(have.passes, passes, "{case}: passes");
        }
    }
}

/// With light tracing, the images of every scene with caustics are the
/// reference's (the same visible points: only those behind a specular
/// bounce), and partial renders merge into one run's sums bit for bit.
pub fn light_traced_images_match_the_reference(backend: &mut dyn Backend) {
    let tol = Tolerance::of(backend.arithmetic());
    for (name, scene) in scenes::with_caustics() {
        let scene = edited(&scene, |s| s.render.light_tracing = true);
        let case = format!("{}, {name}, light tracing, 2 passes", backend.name());
        let mut reference = prepare(&mut ReferenceBackend, &scene);
        let mut got = prepare(backend, &scene);
        run(reference.as_mut(), 0..2);
        run(got.as_mut(), 0..2);
        compare_images(&reference.base().unwrap(), &got.base().unwrap(), tol)
            .unwrap_or_else(|e| panic!("{case}: image without caustics: {e}"));
        let (expected, image) = (reference.image().unwrap(), got.image().unwrap());
        compare_images(&expected, &image, tol).unwrap_or_else(|e| panic!("{case}: {e}"));
        let (want, have) = (reference.stats().unwrap(), got.stats().unwrap());
        assert_eq!(have.visible_points, want.visible_points, "{case}: visible points");
        let (mut first, mut second) = (prepare(backend, &scene), prepare(backend, &scene));
        run(first.as_mut(), [1]);
        run(second.as_mut(), [0]);
        let mut merged = sums(first.as_mut());
        merged.merge(&sums(second.as_mut())).expect("disjoint passes");
        assert_eq!(merged, sums(got.as_mut()), "{case}: merged partials differ from one run");
    }
}

/// With per-pass view paths (each pass its own spectrally sampled view:
/// sampled paths gathered and light traced, hero paths light traced), the
/// images of every scene with caustics after three progressive passes are
/// the reference's; the base is black (every pass's view is in its sums);
/// partial renders merge into one run's sums bit for bit (each scene checks
/// one kind of view path, the kinds in turn: every kind is checked on a
/// third of the scenes, and the light-traced suite checks every scene's
/// merge; a lavapipe pass costs 0.03 to 0.7 s); and a change of
/// the photons alone gives a fresh render's sums (the pilot gathers at pass
/// 0's view again), as does a new seed (a change of the view: the view
/// paths take their numbers from it).
pub fn sampled_view_paths_match_the_reference(backend: &mut dyn Backend) {
    let tol = Tolerance::of(backend.arithmetic());
    let kinds = [(ViewPaths::Sampled, false), (ViewPaths::Sampled, true), (ViewPaths::Hero, true)];
    for (i, (name, scene)) in scenes::with_caustics().into_iter().enumerate() {
        for (k, (view_paths, light_tracing)) in kinds.into_iter().enumerate() {
            let scene = edited(&scene, |s| {
                s.render.view_paths = view_paths;
                s.render.light_tracing = light_tracing;
            });
            let view = view_paths.name();
            let case = format!("{}, {name}, {view} view paths, light tracing {light_tracing}", backend.name());
            let mut reference = prepare(&mut ReferenceBackend, &scene);
            let mut got = prepare(backend, &scene);
            run(reference.as_mut(), 0..3);
            run(got.as_mut(), 0..3);
            let (expected, image) = (reference.image().unwrap(), got.image().unwrap());
            compare_images(&expected, &image, tol).unwrap_or_else(|e| panic!("{case}: {e}"));
            let base = got.base().unwrap();
            assert!(base.pixels.iter().all(|p| *p == glam::Vec3::ZERO), "{case}: a base with per-pass view paths");
            let (want, have) = (reference.stats().unwrap(), got.stats().unwrap());
            assert_eq!(have.visible_points, want.visible_points, "{case}: visible points");
            if k != i % kinds.len() {
                continue;
            }
            let (mut first, mut second) = (prepare(backend, &scene), prepare(backend, &scene));
            run(first.as_mut(), [2]);
            run(second.as_mut(), [1, 0]);
            let mut merged = sums(first.as_mut());
            merged.merge(&sums(second.as_mut())).expect("disjoint passes");
            assert_eq!(merged, sums(got.as_mut()), "{case}: merged partials differ from one run");
        }
    }
    let scene = edited(&scenes::glass_sphere(), |s| s.render.view_paths = ViewPaths::Sampled);
    let name = backend.name();
    let edits = [
        (Change::Photons, edited(&scene, |s| s.render.photons += 3_000)),
        (Change::View, edited(&scene, |s| s.render.seed += 1)),
    ];
    for (change, new) in edits {
        let mut render = prepare(backend, &scene);
        run(render.as_mut(), 0..2);
        assert_eq!(render.update(&new).unwrap(), change, "{name}");
        run(render.as_mut(), 0..2);
        let mut fresh = prepare(backend, &new);
        run(fresh.as_mut(), 0..2);
        let (got, want) = (sums(render.as_mut()), sums(fresh.as_mut()));
        assert!(got == want, "{name}: sampled view paths, {change:?}: not a fresh render's sums");
    }
}

/// A caustic layer in an engine's frame (the frame the scene's camera sees,
/// and for the first scene once more with an engine's occluder in front of
/// the left half): the reference's image after two passes, a black base
/// and no visible points; partial renders merge into one run's sums bit for
/// bit; leaving the layer gives a fresh render's sums; a frame of another
/// size is refused.
pub fn caustic_layers_match_the_reference(backend: &mut dyn Backend) {
    let tol = Tolerance::of(backend.arithmetic());
    let name = backend.name();
    for (i, (scene_name, scene)) in scenes::with_caustics().into_iter().enumerate() {
        let seen = LayerFrame::seen_by_camera(&scene);
        let mut frames = vec![("its camera's frame", seen.clone())];
        if i == 0 {
            let mut occluded = seen.clone();
            for (k, depth) in occluded.depth.iter_mut().enumerate() {
                if k as u32 % seen.width < seen.width / 2 {
                    *depth = depth.min(1.0);
                }
            }
            frames.push(("an occluded frame", occluded));
        }
        for (frame_name, frame) in &frames {
            let case = format!("{name}, {scene_name}, {frame_name}");
            let layer = |backend: &mut dyn Backend, passes: std::ops::Range<u32>| {
                let mut render = prepare(backend, &scene);
                render.set_layer(Some(frame)).unwrap_or_else(|e| panic!("{case}: set_layer: {e}"));
                run(render.as_mut(), passes);
                render
            };
            let (mut reference, mut got) = (layer(&mut ReferenceBackend, 0..2), layer(backend, 0..2));
            let expected = reference.image().unwrap();
            assert!(expected.pixels.iter().any(|p| p.max_element() > 0.0), "{case}: the reference's layer is black");
            compare_images(&expected, &got.image().unwrap(), tol).unwrap_or_else(|e| panic!("{case}: {e}"));
            assert!(got.base().unwrap().pixels.iter().all(|p| *p == glam::Vec3::ZERO), "{case}: base");
            assert_eq!(got.stats().unwrap().visible_points, 0, "{case}: visible points");
            let (mut first, mut second) = (layer(backend, 0..1), layer(backend, 1..2));
            let mut merged = sums(first.as_mut());
            merged.merge(&sums(second.as_mut())).expect("disjoint passes");
            assert_eq!(merged, sums(got.as_mut()), "{case}: merged partials differ from one run");
        }
    }
    let scene = scenes::glass_sphere();
    let seen = LayerFrame::seen_by_camera(&scene);
    let mut left = prepare(backend, &scene);
    left.set_layer(Some(&seen)).unwrap();
    run(left.as_mut(), 0..1);
    left.set_layer(None).unwrap();
    run(left.as_mut(), 0..2);
    let mut fresh = prepare(backend, &scene);
    run(fresh.as_mut(), 0..2);
    assert_eq!(sums(left.as_mut()), sums(fresh.as_mut()), "{name}: the image after a layer");
    assert_eq!(left.base().unwrap(), fresh.base().unwrap(), "{name}: the base after a layer");
    let mut small = seen;
    (small.width, small.depth, small.normal) = (small.width - 1, vec![1.0; 1], vec![glam::Vec3::Y; 1]);
    let refused = prepare(backend, &scene).set_layer(Some(&small));
    assert!(matches!(refused, Err(BackendError::FrameSize { .. })), "{name}: {refused:?}");
}

/// Partial renders of passes `0..2` and `2..4` merge into the sums of one
/// render of `0..4`, bit for bit, and so into its image.
pub fn partial_renders_merge_into_one_run(backend: &mut dyn Backend) {
    let scene = scenes::glass_sphere();
    let mut whole = prepare(backend, &scene);
    run(whole.as_mut(), 0..4);
    let (mut first, mut second) = (prepare(backend, &scene), prepare(backend, &scene));
    run(first.as_mut(), 0..2);
    run(second.as_mut(), 2..4);
    let mut merged = sums(first.as_mut());
    merged.merge(&sums(second.as_mut())).expect("disjoint passes");
    let name = backend.name();
    assert_eq!(merged.passes, [(0, 4)], "{name}");
    assert_eq!(merged, sums(whole.as_mut()), "{name}: merged partials differ from one run");
    assert_eq!(first.base().unwrap(), whole.base().unwrap(), "{name}: the base differs between renders");
    assert_eq!(merged.image(&first.base().unwrap()), whole.image().unwrap(), "{name}: images differ");
}

/// Passes run in any order sum to the same bits; a pass is summed once;
/// the next pass is the lowest one not summed.
pub fn passes_run_in_any_order_and_once(backend: &mut dyn Backend) {
    let scene = scenes::prism();
    let mut in_order = prepare(backend, &scene);
    run(in_order.as_mut(), 0..4);
    let mut shuffled = prepare(backend, &scene);
    run(shuffled.as_mut(), [2, 0, 3]);
    let name = backend.name();
    assert_eq!(shuffled.passes(), [(0, 1), (2, 4)], "{name}");
    assert_eq!(shuffled.next_pass(&mut NoProgress).unwrap(), 1, "{name}: the next pass fills the gap");
    assert_eq!(sums(shuffled.as_mut()), sums(in_order.as_mut()), "{name}: order changed the sums");
    assert_eq!(shuffled.run_pass(2, &mut NoProgress), Err(BackendError::PassRepeated(2)), "{name}");
    assert_eq!(sums(shuffled.as_mut()).pass_count(), 4, "{name}: a refused pass changed the sums");
}

/// An update says what it invalidates, starts the passes again where it
/// invalidates the photons, and the render then gives the sums of a fresh
/// render of the new scene.
pub fn updates_give_a_fresh_renders_sums(backend: &mut dyn Backend) {
    let scene = scenes::glass_sphere();
    let moved = |s: &mut Scene| {
        if let Light::Spot { position, .. } = &mut s.lights[0] {
            position.x += 0.4;
        }
    };
    let edits: Vec<(Change, PreparedScene)> = vec![
        (Change::None, edited(&scene, |s| s.render.passes = 3)),
        (Change::Photons, edited(&scene, |s| s.render.seed += 1)),
        (Change::Photons, edited(&scene, |s| s.render.photon_sequence = PhotonSequence::Random)),
        (Change::Photons, edited(&scene, |s| s.render.photons += 3_000)),
        (Change::Photons, edited(&scene, |s| s.render.radius_mode = RadiusMode::Fixed)),
        (Change::View, edited(&scene, moved)),
        (Change::View, edited(&scene, |s| s.camera.position.x += 0.3)),
        (Change::View, edited(&scene, |s| s.render.bands = BandSpec::Paper3)),
        (Change::View, edited(&scene, |s| s.render.light_tracing = true)),
        (Change::View, edited(&scene, |s| s.render.view_paths = ViewPaths::Sampled)),
        (Change::Size, edited(&scene, |s| (s.render.width, s.render.height) = (40, 28))),
    ];
    let name = backend.name();
    for (change, new) in edits {
        let mut render = prepare(backend, &scene);
        run(render.as_mut(), 0..2);
        assert_eq!(render.update(&new).unwrap(), change, "{name}: {change:?}");
        let kept = if change >= Change::Photons { 0 } else { 2 };
        assert_eq!(sums(render.as_mut()).pass_count(), kept, "{name}: {change:?}: passes after the update");
        if change >= Change::Photons {
            run(render.as_mut(), 0..2);
        }
        let mut fresh = prepare(backend, &new);
        run(fresh.as_mut(), 0..2);
        assert_eq!(sums(render.as_mut()), sums(fresh.as_mut()), "{name}: {change:?}: not a fresh render's sums");
        assert_eq!(render.base().unwrap(), fresh.base().unwrap(), "{name}: {change:?}: not a fresh render's base");
    }
}

/// Before any pass a render reads out its base and empty sums, and its
/// statistics count the passes, the photons and the visible points.
pub fn read_outs_and_statistics(backend: &mut dyn Backend) {
    let tol = Tolerance::of(backend.arithmetic());
    let scene = scenes::glass_sphere();
    let name = backend.name();
    let mut reference = prepare(&mut ReferenceBackend, &scene);
    let mut render = prepare(backend, &scene);
    let empty = sums(render.as_mut());
    let r = &scene.scene.render;
    assert_eq!((empty.pass_count(), empty.width, empty.height), (0, r.width, r.height), "{name}");
    assert!(empty.sums.iter().all(|s| *s == [0; 3]), "{name}: sums before any pass");
    compare_images(&reference.base().unwrap(), &render.base().unwrap(), tol).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(render.stats().unwrap().passes, 0, "{name}");
    run(render.as_mut(), 0..2);
    let stats = render.stats().unwrap();
    let stored: u64 = (0..2).map(|k| photon_map(render.as_mut(), k).stats.stored).sum();
    assert_eq!(stats.passes, 2, "{name}");
    assert_eq!(stats.trace.emitted, 2 * u64::from(r.photons), "{name}: photons emitted");
    assert_eq!(stats.trace.stored, stored, "{name}: photons stored, against the passes' maps");
    assert_eq!(stats.visible_points, reference.stats().unwrap().visible_points, "{name}: visible points");
    assert_eq!(stats.view_paths_cut, 0, "{name}: view paths cut short");
    let (lo, hi) = stats.first_radii.unwrap_or_else(|| panic!("{name}: no first radii"));
    assert!(0.0 < lo && lo <= hi && hi <= r.radius, "{name}: first radii {lo}..{hi} of {}", r.radius);
}

/// A scene without mirrors or glass traces no caustic photon and its image
/// is its base, bit for bit.
pub fn a_scene_without_caustics_is_its_base(backend: &mut dyn Backend) {
    let scene = scenes::no_caustics();
    let mut render = prepare(backend, &scene);
    run(render.as_mut(), 0..2);
    let name = backend.name();
    assert_eq!(render.image().unwrap(), render.base().unwrap(), "{name}");
    let stats = render.stats().unwrap();
    assert_eq!((stats.trace.stored, stats.visible_points), (0, 0), "{name}: {stats:?}");
    assert!(photon_map(render.as_mut(), 0).photons.is_empty(), "{name}");
}
