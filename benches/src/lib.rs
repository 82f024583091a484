//! Shared set-up for the criterion benches: the paper's configuration of a built-in scene.

use prismatic_core::PreparedScene;
use prismatic_core::bands::BandSpec;

/// The paper's configuration (Table 5): 400×400, 20,000 white photons, 7 bands,
/// applied to built-in scene `name`, with `photons` overriding the count.
/// Projection maps are off: the paper emits over the whole spot cone (the
/// `effects` bench group measures what aiming saves).
pub fn paper_config(name: &str, photons: u32) -> PreparedScene {
    let mut doc = prismatic_cli::load_scene(name).expect("built-in scene parses");
    let r = &mut doc.scene.render;
    r.width = 400;
    r.height = 400;
    r.photons = photons;
    r.bands = BandSpec::Paper7;
    r.projection_maps = false;
    PreparedScene::new(doc.scene).expect("built-in scene is valid")
}
