//! The built-in `ring` scene: metals as a glTF file brings them
//! (`pbrMetallicRoughness` with `metallicFactor` 1). A gold ring stands on
//! a pale floor in low sunlight, and the light its inner wall reflects
//! gathers on the floor inside it into the cusped curve of a coffee cup's
//! caustic; beside it a rough copper ball shows the sun as a soft
//! highlight and a polished silver ball mirrors the scene. Written as glTF
//! and read back through the importer, like `sunlit-glass`.

use crate::gltf_write::{GltfCamera, GltfDocument, GltfLight, GltfMaterial, GltfMesh};
use prismatic_core::model::scene::{RenderSettings, WavelengthSampling};
use std::f32::consts::TAU;

/// The sun's irradiance on a surface facing it (W/m²).
const SUN_IRRADIANCE: f32 = 3.0;

/// An open cylinder about the y axis of `radius` and `height`, standing on
/// y = 0, of `segments` quads: one sheet, which a metal reflects on both
/// sides, smooth (its normals point out from the axis, as its quads wind).
fn ring(name: &str, (radius, height, segments): (f32, f32, u32), material: usize) -> GltfMesh {
    let (mut positions, mut normals) = (Vec::new(), Vec::new());
    for s in 0..segments {
        let (sin, cos) = (TAU * s as f32 / segments as f32).sin_cos();
        positions.extend([[radius * cos, 0.0, radius * sin], [radius * cos, height, radius * sin]]);
        normals.extend([[cos, 0.0, sin]; 2]);
    }
    let mut indices = Vec::new();
    for s in 0..segments {
        let (a, b) = (2 * s, 2 * ((s + 1) % segments));
        indices.extend([a, a + 1, b, b, a + 1, b + 1]);
    }
    GltfMesh { normals, ..GltfMesh::new(name, (positions, indices), material, [0.0; 3]) }
}

/// A metal of linear colour `color` and `roughness`, as glTF writes one.
fn metal(name: &str, color: [f32; 3], roughness: f32) -> GltfMaterial {
    GltfMaterial { metallic: 1.0, roughness, ..GltfMaterial::diffuse(name, color) }
}

/// The scene as a glTF document.
pub fn document() -> GltfDocument {
    let materials = vec![
        GltfMaterial::diffuse("floor", [0.6, 0.59, 0.57]),
        metal("gold", [1.0, 0.766, 0.336], 0.03),
        metal("copper", [0.955, 0.637, 0.538], 0.3),
        metal("silver", [0.972, 0.960, 0.915], 0.0),
    ];
    let mesh = GltfMesh::new;
    let floor = (vec![[-8.0, 0.0, -8.0], [8.0, 0.0, -8.0], [8.0, 0.0, 8.0], [-8.0, 0.0, 8.0]], vec![0, 2, 1, 0, 3, 2]);
    let meshes = vec![
        mesh("floor", floor, 0, [0.0; 3]),
        ring("gold ring", (1.0, 0.6, 720), 1),
        GltfMesh::ball("copper ball", (0.45, 48), 2, [1.9, 0.45, -0.9]),
        GltfMesh::ball("silver ball", (0.35, 48), 3, [-1.8, 0.35, -1.1]),
    ];
    // The sun low (14° up) from behind the ring, a little to the right:
    // the far half of the inner wall is lit and focuses toward the camera.
    let elevation = 14f32.to_radians();
    let direction = [-elevation.cos() * 0.3, -elevation.sin(), elevation.cos() * 0.95];
    GltfDocument {
        materials,
        meshes,
        lights: vec![GltfLight::Directional { direction, intensity: SUN_IRRADIANCE }],
        camera: Some(GltfCamera { position: [0.0, 4.6, 3.4], look_at: [0.0, 0.0, -0.3], yfov: 42f32.to_radians() }),
    }
}

/// Its render settings: `sunlit-glass`'s (16 bands, 150,000 photons a
/// pass, no indirect light), with 4 hero wavelengths a path (a coloured
/// metal splits white photons as dispersive glass does), a smaller radius
/// for a sharp cusp, and a pale sky for the metals to mirror (glTF has no
/// environment).
pub fn settings(render: &mut RenderSettings) {
    crate::sunlit_glass::settings(render);
    (render.width, render.height) = (480, 360);
    render.wavelengths = WavelengthSampling::Hero;
    render.radius = 0.012;
    render.ambient = 0.1;
    render.background = prismatic_core::Vec3::new(0.45, 0.5, 0.58);
}
