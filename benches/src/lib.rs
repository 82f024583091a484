//! Shared set-up for the criterion benches: the paper's configuration of a
//! built-in scene, and its frame through the render protocol.

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::scene::RadiusMode;
use prismatic_core::{Backend, Image, NoProgress, PreparedScene};

/// The paper's configuration (Table 5): 400×400, 20,000 white photons, 7 bands,
/// a fixed gather radius, applied to built-in scene `name`, with `photons`
/// overriding the count. Projection maps are off: the paper emits over the
/// whole spot cone (the `effects` bench group measures what aiming saves).
pub fn paper_config(name: &str, photons: u32) -> PreparedScene {
    let mut doc = prismatic_cli::load_scene(name).expect("built-in scene parses");
    let r = &mut doc.scene.render;
    r.width = 400;
    r.height = 400;
    r.photons = photons;
    r.bands = BandSpec::Paper7;
    r.projection_maps = false;
    r.radius_mode = RadiusMode::Fixed;
    PreparedScene::new(doc.scene).expect("built-in scene is valid")
}

/// The paper's frame of `scene` (with fixed radii) on `backend`: a render
/// prepared, its view rays, pass 0, the image read out.
pub fn frame(backend: &mut dyn Backend, scene: &PreparedScene) -> Image {
    let mut render = backend.prepare(scene).expect("prepare");
    render.run_pass(0, &mut NoProgress).expect("pass");
    render.image().expect("image")
}
