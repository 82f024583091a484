//! The GPU session (the engine-facing live render): its frames are the
//! progressive passes of the scalar reference, and a scene update redoes
//! exactly what it invalidates, giving the image a fresh session would.

use prismatic_core::progressive::ProgressiveRender;
use prismatic_core::scene::Light;
use prismatic_core::{Image, NoProgress, PreparedScene, ReferenceBackend, Vec3};
use prismatic_gpu::{AdapterChoice, Change, GpuContext, GpuOptions, GpuSession, SessionFrame};
use prismatic_tests::builtin;
use prismatic_tests::parity::compare_images;

fn small(name: &str, photons: u32) -> PreparedScene {
    builtin(name, |r| {
        (r.width, r.height, r.photons) = (80, 80, photons);
    })
}

/// A session on the best adapter (lavapipe in CI, where a missing adapter fails).
fn session(scene: &PreparedScene, options: GpuOptions) -> Option<GpuSession> {
    match GpuContext::new(AdapterChoice::Any) {
        Ok(ctx) => Some(GpuSession::new(ctx, scene, options).unwrap_or_else(|e| panic!("session: {e}"))),
        Err(e) if std::env::var_os("CI").is_some() => panic!("CI=true and no GPU adapter: {e}"),
        Err(e) => {
            eprintln!("SKIPPING the GPU session on this machine: {e}");
            None
        }
    }
}

fn frames(session: &mut GpuSession, n: u32) -> Vec<SessionFrame> {
    (0..n).map(|_| session.frame().unwrap_or_else(|e| panic!("frame: {e}"))).collect()
}

/// The reference's progressive render of `passes` passes.
fn reference(scene: &PreparedScene, passes: u32) -> Image {
    let mut render = ProgressiveRender::prepare(&mut ReferenceBackend, scene, &mut NoProgress).unwrap();
    for k in 0..passes {
        render.run_pass(&mut ReferenceBackend, k).unwrap();
    }
    render.image()
}

#[test]
fn session_frames_are_the_references_progressive_passes() {
    for (name, photons) in [("sphere", 20_000), ("prism", 4_000)] {
        let scene = small(name, photons);
        let Some(mut s) = session(&scene, GpuOptions::default()) else { return };
        let done = frames(&mut s, 3);
        assert_eq!(done.iter().map(|f| f.passes).collect::<Vec<_>>(), [1, 2, 3], "{name}");
        assert_eq!(done[0].redone, Change::Size, "{name}: the first frame sets everything up");
        assert_eq!(done[1].redone, Change::None, "{name}: later frames only add a pass");
        // The first frame traces the pilot's photons (an eighth) and its pass's.
        assert_eq!(done[0].photons, u64::from(photons + photons / 8), "{name}");
        assert_eq!(done[1].photons, u64::from(photons), "{name}");
        let got = s.image().unwrap();
        compare_images(&reference(&scene, 3), &got).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn sessions_in_bucket_segments_and_several_bindings_match_the_reference() {
    let options = GpuOptions { window_photons: Some(50_000), gather_span: Some(16) };
    let scene = small("sphere", 20_000);
    let Some(mut s) = session(&scene, options) else { return };
    frames(&mut s, 2);
    // The segments' widest-bucket reads wait, so the second pass has the finer levels.
    assert!(s.grid_levels() > 0b1, "no finer level built (levels {:#b})", s.grid_levels());
    compare_images(&reference(&scene, 2), &s.image().unwrap()).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn small_first_radii_are_gathered_in_finer_grid_levels() {
    // Within 4× the sphere scene's radius its caustic is dense: the pilot
    // gives many points first radii of a quarter of that or less, gathered
    // in finer grids.
    let scene = builtin("sphere", |r| {
        (r.width, r.height, r.photons) = (80, 80, 20_000);
        r.radius *= 4.0;
    });
    let Some(mut s) = session(&scene, GpuOptions::default()) else { return };
    assert_eq!(s.grid_levels(), 0b1, "before the pilot, the pass radius's grid alone");
    frames(&mut s, 1);
    s.context().wait().unwrap(); // the pilot's mark of the levels comes back
    frames(&mut s, 2);
    assert!(s.grid_levels() > 0b1, "no finer level built (levels {:#b})", s.grid_levels());
    assert_eq!(s.grid_levels() & 1, 1, "level 0 serves the points of levels not built");
    compare_images(&reference(&scene, 3), &s.image().unwrap()).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn changes_are_classified_by_what_they_invalidate() {
    let scene = small("sphere", 1_000).scene;
    let edited = |edit: &dyn Fn(&mut prismatic_core::Scene)| {
        let mut s = scene.clone();
        edit(&mut s);
        Change::between(&scene, &s)
    };
    assert_eq!(edited(&|_| {}), Change::None);
    assert_eq!(edited(&|s| s.render.tone_map = prismatic_core::color::ToneMap::Reinhard), Change::None);
    assert_eq!(edited(&|s| s.render.photons += 1), Change::Photons);
    assert_eq!(edited(&|s| s.render.seed += 1), Change::Photons);
    assert_eq!(edited(&|s| s.lights[0] = moved(&s.lights[0], 0.1)), Change::View);
    assert_eq!(edited(&|s| s.render.alpha = 0.5), Change::Photons);
    assert_eq!(edited(&|s| s.camera.position.x += 0.1), Change::View);
    assert_eq!(edited(&|s| s.render.bands = prismatic_core::bands::BandSpec::Paper3), Change::View);
    assert_eq!(edited(&|s| s.render.width += 1), Change::Size);
}

/// `light` moved by `dx` along x.
fn moved(light: &Light, dx: f32) -> Light {
    let mut l = light.clone();
    match &mut l {
        Light::Spot { position, .. } | Light::Point { position, .. } | Light::Beam { position, .. } => {
            *position += Vec3::new(dx, 0.0, 0.0);
        }
    }
    l
}

#[test]
fn an_update_gives_the_image_of_a_fresh_session() {
    let scene = small("sphere", 20_000);
    let Some(mut s) = session(&scene, GpuOptions::default()) else { return };
    frames(&mut s, 2);
    let mut edits: Vec<(Change, prismatic_core::Scene)> = Vec::new();
    let mut photons = scene.scene.clone();
    photons.render.seed += 1;
    edits.push((Change::Photons, photons.clone()));
    // More photons a pass: a new photon map and grid, the visible points kept.
    photons.render.photons = 30_000;
    edits.push((Change::Photons, photons.clone()));
    let mut light = photons;
    light.lights[0] = moved(&light.lights[0], 0.3);
    edits.push((Change::View, light.clone()));
    let mut camera = light.clone();
    camera.camera.position.x += 0.5;
    edits.push((Change::View, camera.clone()));
    let mut bands = camera.clone();
    bands.render.bands = prismatic_core::bands::BandSpec::Paper3;
    edits.push((Change::View, bands.clone()));
    let mut size = bands;
    (size.render.width, size.render.height) = (96, 64);
    edits.push((Change::Size, size));
    for (change, edited) in edits {
        let edited = PreparedScene::new(edited).unwrap();
        assert_eq!(s.update(&edited).unwrap(), change);
        let after = frames(&mut s, 2);
        assert_eq!(after[0].redone, change, "the frame after the update redoes what it invalidated");
        assert_eq!(after.iter().map(|f| f.passes).collect::<Vec<_>>(), [1, 2], "{change:?}: the passes restart");
        let mut fresh = session(&edited, GpuOptions::default()).unwrap();
        frames(&mut fresh, 2);
        compare_images(&fresh.image().unwrap(), &s.image().unwrap()).unwrap_or_else(|e| panic!("{change:?}: {e}"));
    }
}

#[test]
fn the_caustic_follows_the_light() {
    // Moving the spot light moves the sphere's caustic: the updated
    // session's image differs from the old one where the caustic was.
    let scene = small("sphere", 20_000);
    let Some(mut s) = session(&scene, GpuOptions::default()) else { return };
    frames(&mut s, 2);
    let before = s.image().unwrap();
    let mut edited = scene.scene.clone();
    edited.lights[0] = moved(&edited.lights[0], 0.6);
    s.update(&PreparedScene::new(edited).unwrap()).unwrap();
    frames(&mut s, 2);
    let after = s.image().unwrap();
    assert!(compare_images(&before, &after).is_err(), "moving the light changed nothing");
}

#[test]
fn stage_times_come_back_a_frame_later_and_fit_in_the_frames_wall_time() {
    let scene = small("sphere", 20_000);
    let Some(mut s) = session(&scene, GpuOptions::default()) else { return };
    let timestamps = s.context().device.features().contains(prismatic_gpu::timestamp_features());
    // Lavapipe has timestamp queries: CI times its sessions' stages.
    assert!(timestamps || std::env::var_os("CI").is_none(), "CI=true and the adapter has no timestamp queries");
    let start = std::time::Instant::now();
    frames(&mut s, 1);
    assert_eq!(s.stage_times(), None, "times before the frame's stamps came back");
    s.image().unwrap(); // waits for the device, so the stamps are mapped
    let wall = start.elapsed();
    frames(&mut s, 1);
    if !timestamps {
        assert_eq!(s.stage_times(), None);
        return;
    }
    // The first frame's: view rays, then the pilot's and the pass's photons, grid and gather.
    let t = s.stage_times().expect("the first frame's stage times");
    for (stage, time) in [("view", t.view), ("photons", t.photons), ("grid", t.grid), ("gather", t.gather)] {
        assert!(time > std::time::Duration::ZERO, "{stage} took no time: {t:?}");
    }
    // Ticks scaled by the queue's timestamp period: the GPU's frame fits in the host's.
    assert!(t.frame() <= wall, "GPU frame {:?} longer than the host's {wall:?}: {t:?}", t.frame());
    s.image().unwrap();
    frames(&mut s, 1);
    let later = s.stage_times().expect("the second frame's stage times");
    assert_eq!(later.view, std::time::Duration::ZERO, "a frame after the first traces no view rays: {later:?}");
    assert!(later.photons > std::time::Duration::ZERO && later.gather > std::time::Duration::ZERO, "{later:?}");
}
