//! Shared set-up for the criterion benches: the paper's configuration of a
//! built-in scene, the same scene under each kind of light, and a frame
//! through the render protocol.

use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::environment::EnvironmentMap;
use prismatic_core::model::scene::{MaterialKind, Object, RadiusMode, Shape, Texture, ThinFilm};
use prismatic_core::{Backend, Image, Light, NoProgress, PreparedScene, RenderSettings, Vec3};
use std::f32::consts::TAU;

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

/// The built-in `sphere` with today's default settings and `photons` a pass,
/// lit by its spot (`"spot"`), by the built-in studio environment instead
/// (`"environment"`) and by a light panel of the spot's power above the
/// ball (`"area"`): what each light costs in a pass.
pub fn lit_by_each_light(photons: u32) -> [(&'static str, PreparedScene); 3] {
    let doc = prismatic_cli::load_scene("sphere").expect("built-in sphere");
    let mut spot = doc.scene;
    spot.render = RenderSettings { photons, ..RenderSettings::default() };
    let mut studio = spot.clone();
    studio.lights = vec![Light::Environment {
        map: EnvironmentMap::studio(),
        strength: 1.0,
        rotation_deg: 0.0,
        spectrum: Default::default(),
    }];
    let mut area = spot.clone();
    area.lights.clear();
    // Half a metre a side at 38 W: radiance 38 / (π · 0.25).
    let emission = Vec3::splat(38.0 / (core::f32::consts::PI * 0.25));
    let (panel, shape) = prismatic_conformance::scenes::light_panel(Vec3::new(-1.0, 4.0, -0.2), emission);
    area.objects.push(Object { shape, material: area.materials.len() });
    area.materials.push(panel);
    let [spot, studio, area] = [spot, studio, area].map(|s| PreparedScene::new(s).expect("valid"));
    [("spot", spot), ("environment", studio), ("area", area)]
}

/// The `sphere` under its spot with `photons` indirect photons and no
/// caustic ones, and the same scene with as many caustic photons and no
/// indirect ones: the `indirect` groups' pair.
pub fn indirect_and_caustic(photons: u32) -> [(&'static str, PreparedScene); 2] {
    let [(_, spot), ..] = lit_by_each_light(photons);
    let mut indirect = spot.scene.clone();
    (indirect.render.photons, indirect.render.indirect_photons) = (0, photons);
    [("indirect", PreparedScene::new(indirect).expect("valid")), ("caustic", spot)]
}

/// The paper's frame of `scene` (with fixed radii) on `backend`: a render
/// prepared, its view rays, pass 0, the image read out.
pub fn frame(backend: &mut dyn Backend, scene: &PreparedScene) -> Image {
    let mut render = backend.prepare(scene).expect("prepare");
    render.run_pass(0, &mut NoProgress).expect("pass");
    render.image().expect("image")
}

/// The built-in `sphere` with `photons` a pass: its dispersive glass
/// frosted (roughness 0.3, `"frosted"`) and polished as built
/// (`"polished"`, which the CPU traces in packets): what rough glass costs.
pub fn sphere_frosted(photons: u32) -> [(&'static str, PreparedScene); 2] {
    let mut polished = prismatic_cli::load_scene("sphere").expect("built-in sphere").scene;
    polished.render.photons = photons;
    let mut frosted = polished.clone();
    for m in &mut frosted.materials {
        if let MaterialKind::Dielectric { roughness, .. } = &mut m.kind {
            *roughness = 0.3;
        }
    }
    let [frosted, polished] = [frosted, polished].map(|s| PreparedScene::new(s).expect("valid"));
    [("frosted", frosted), ("polished", polished)]
}

/// The built-in `ring` with `photons` a pass: its metals as they are (a
/// gold ring of roughness 0.03, a copper ball of 0.3, a polished silver
/// ball; `"rough"`), as they are under roughness maps of white texels
/// (`"mapped"`: the same facets, each read through its map), under colour
/// textures of white texels (`"coloured"`: the same F0, each read through
/// its texture), under a 300 nm film of index 1.8 (`"filmed"`), all
/// polished (`"polished"`) and as mirrors (`"mirrors"`, which the CPU
/// traces in packets): what metals, their maps and their films cost.
pub fn ring_metals(photons: u32) -> [(&'static str, PreparedScene); 6] {
    let mut rough = prismatic_cli::load_scene("ring").expect("built-in ring").scene;
    rough.render.photons = photons;
    let mut mapped = rough.clone();
    let white = Texture {
        name: "white".into(),
        width: 16,
        height: 16,
        texels: vec![0xffffff; 256].into(),
        sampler: Default::default(),
    };
    let mut coloured = rough.clone();
    for (scene, colour) in [(&mut mapped, false), (&mut coloured, true)] {
        for o in &mut scene.objects {
            let material = &mut scene.materials[o.material];
            if let (MaterialKind::Metal { texture, .. }, Shape::Mesh { positions, uvs, .. }) =
                (&mut material.kind, &mut o.shape)
            {
                // Around the y axis and up it.
                *uvs = positions.iter().map(|p| [p.z.atan2(p.x) / TAU, p.y].into()).collect();
                // The ring's metals are glTF's, RGB: each takes a colour texture.
                match colour {
                    true => *texture = Some(white.clone()),
                    false => material.roughness_map = Some(white.clone()),
                }
            }
        }
    }
    let mut filmed = rough.clone();
    for m in &mut filmed.materials {
        if let MaterialKind::Metal { film, .. } = &mut m.kind {
            *film = Some(ThinFilm::new(1.8, 300.0));
        }
    }
    let mut polished = rough.clone();
    let mut mirrors = rough.clone();
    for m in &mut polished.materials {
        if let MaterialKind::Metal { roughness, .. } = &mut m.kind {
            *roughness = 0.0;
        }
    }
    for m in &mut mirrors.materials {
        if let MaterialKind::Metal { .. } = m.kind {
            m.kind = MaterialKind::Mirror;
        }
    }
    let [rough, mapped, coloured, filmed, polished, mirrors] =
        [rough, mapped, coloured, filmed, polished, mirrors].map(|s| PreparedScene::new(s).expect("valid"));
    [
        ("rough", rough),
        ("mapped", mapped),
        ("coloured", coloured),
        ("filmed", filmed),
        ("polished", polished),
        ("mirrors", mirrors),
    ]
}
