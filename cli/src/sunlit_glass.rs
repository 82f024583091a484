//! The built-in `sunlit-glass` scene: what a glTF file as people make them
//! brings, in one picture. An amber glass ball, a green dispersive prism and
//! a clear flint prism on a tiled floor before a graph-paper wall, lit by
//! the sun (a `KHR_lights_punctual` directional light): coloured glass
//! (`KHR_materials_volume`) casts coloured caustics and shadows, dispersion
//! (`KHR_materials_dispersion`) fans a spectrum, base-colour textures show
//! through and around the glass. Written as glTF and read back through the
//! importer, like `dispersion-test`.

use crate::gltf_write::{GltfCamera, GltfDocument, GltfLight, GltfMaterial, GltfMesh, prism};
use crate::patterns::{graph_paper, tiles};
use prismatic_core::model::color::ToneMap;
use prismatic_core::model::scene::{RenderSettings, WavelengthSampling};
use prismatic_core::{BandSpec, Estimator};

/// The sun's irradiance on a surface facing it (W/m²).
const SUN_IRRADIANCE: f32 = 3.0;

/// Coloured glass: `attenuation` is the colour left after `distance`.
fn coloured(name: &str, ior: f32, dispersion: f32, attenuation: [f32; 3], distance: f32) -> GltfMaterial {
    GltfMaterial { attenuation: Some((attenuation, distance)), ..GltfMaterial::glass(name, ior, dispersion) }
}

/// The scene as a glTF document.
pub fn document() -> GltfDocument {
    let materials = vec![
        GltfMaterial { base_color_texture: Some(tiles()), ..GltfMaterial::diffuse("floor", [0.9; 3]) },
        GltfMaterial { base_color_texture: Some(graph_paper()), ..GltfMaterial::diffuse("wall", [1.0; 3]) },
        coloured("amber glass", 1.5, 0.0, [0.95, 0.55, 0.15], 1.0),
        coloured("green flint", 1.62, 1.0, [0.35, 0.85, 0.4], 0.5),
        GltfMaterial::glass("dense flint", 1.78, 1.2),
    ];
    let mesh = GltfMesh::new;
    // Both prisms lie along z, apex up, held above the floor so that what
    // they refract has room to fan out.
    let prism_shape = || prism([[-0.35, 0.0, -0.45], [0.35, 0.0, -0.45], [0.0, 0.6, -0.45]], [0.0, 0.0, 0.9]);
    let meshes = vec![
        GltfMesh {
            uvs: vec![[0.0, 0.0], [3.0, 0.0], [3.0, 3.0], [0.0, 3.0]],
            ..mesh(
                "floor",
                (vec![[-6.0, 0.0, -6.0], [6.0, 0.0, -6.0], [6.0, 0.0, 6.0], [-6.0, 0.0, 6.0]], vec![0, 2, 1, 0, 3, 2]),
                0,
                [0.0; 3],
            )
        },
        GltfMesh {
            uvs: vec![[0.0, 1.0], [3.0, 1.0], [3.0, 0.0], [0.0, 0.0]],
            ..mesh(
                "wall",
                (
                    vec![[-6.0, 0.0, -3.0], [6.0, 0.0, -3.0], [6.0, 4.0, -3.0], [-6.0, 4.0, -3.0]],
                    vec![0, 1, 2, 0, 2, 3],
                ),
                1,
                [0.0; 3],
            )
        },
        GltfMesh::ball("amber ball", (0.75, 24), 2, [-1.7, 0.75, 0.2]),
        mesh("green prism", prism_shape(), 3, [0.1, 0.7, 0.6]),
        mesh("clear prism", prism_shape(), 4, [1.6, 0.9, -0.8]),
    ];
    // The sun from the left, a little in front, 55° up: the prisms'
    // spectra fan out to their right.
    let elevation = 55f32.to_radians();
    let direction = [elevation.cos() * 0.94, -elevation.sin(), -elevation.cos() * 0.34];
    GltfDocument {
        materials,
        meshes,
        lights: vec![GltfLight::Directional { direction, intensity: SUN_IRRADIANCE }],
        camera: Some(GltfCamera { position: [0.3, 3.2, 6.2], look_at: [0.6, 0.5, -0.6], yfov: 40f32.to_radians() }),
    }
}

/// Its render settings: the continuous spectrum in 16 bands, enough
/// photons for three caustics in a few seconds.
pub fn settings(render: &mut RenderSettings) {
    (render.width, render.height) = (480, 320);
    render.bands = BandSpec::Physical(16);
    render.wavelengths = WavelengthSampling::Continuous;
    render.estimator = Estimator::Density;
    render.photons = 150_000;
    render.radius = 0.02;
    render.ambient = 0.12;
    // The ambient stands in for bounced light, as when the picture was
    // made: at 16 passes indirect photons speckle the wall in shade.
    render.indirect_photons = 0;
    render.tone_map = ToneMap::Reinhard;
    render.auto_exposure = false;
}
