//! The built-in `pool` scene: the sun through rippled water onto a tiled
//! floor, the net of bright lines that lies on the bottom of every
//! swimming pool. The water is a still slab whose top wears a normal map
//! of ripples (glTF's `normalTexture`), so the surface stays flat to the
//! rays that cross it while it bends them as the waves would; water's
//! weak dispersion fringes the brightest lines. Written as glTF and read
//! back through the importer, like `ring`.

use crate::gltf_write::{GltfCamera, GltfDocument, GltfLight, GltfMaterial, GltfMesh, GltfTexture};
use crate::patterns::tiles;
use glam::Vec3;
use prismatic_core::model::scene::{RenderSettings, WavelengthSampling};
use std::f32::consts::TAU;

/// The sun's irradiance on a surface facing it (W/m²).
const SUN_IRRADIANCE: f32 = 3.0;

/// Half the water's width.
const HALF_WIDTH: f32 = 2.0;

/// The water's depth.
const DEPTH: f32 = 0.8;

/// How many times the ripples repeat across the water.
const RIPPLE_REPEATS: f32 = 3.0;

/// The ripples' texels per side.
const RIPPLE_TEXELS: u32 = 128;

/// The waves of the water's surface: (cycles across the image along u
/// and along v, height in world units, phase). Whole cycles, so the
/// image repeats without a seam.
const WAVES: [(f32, f32, f32, f32); 6] = [
    (2.0, 1.0, 0.010, 0.0),
    (-1.0, 3.0, 0.008, 1.3),
    (3.0, -2.0, 0.006, 2.1),
    (1.0, 4.0, 0.004, 4.0),
    (-4.0, -1.0, 0.005, 5.2),
    (5.0, 2.0, 0.002, 0.7),
];

/// The ripples as a tangent-space normal map: the normals of the height
/// field Σ h sin(2π(a u + b v) + φ) over one repeat (`RIPPLE_REPEATS` to
/// the water's width), +X along u and +Y up the image (where v falls).
pub fn ripples() -> GltfTexture {
    let length = 2.0 * HALF_WIDTH / RIPPLE_REPEATS;
    let byte = |x: f32| ((x + 1.0) * 0.5 * 255.0).round() as u8;
    let pixels = (0..RIPPLE_TEXELS * RIPPLE_TEXELS)
        .map(|k| {
            let (u, v) = ((k % RIPPLE_TEXELS) as f32 + 0.5, (k / RIPPLE_TEXELS) as f32 + 0.5);
            let (u, v) = (u / RIPPLE_TEXELS as f32, v / RIPPLE_TEXELS as f32);
            // Slopes along the world axes under u and v.
            let (du, dv) = WAVES.iter().fold((0.0, 0.0), |(du, dv), &(a, b, h, phase)| {
                let c = h * TAU / length * (TAU * (a * u + b * v) + phase).cos();
                (du + a * c, dv + b * c)
            });
            let n = Vec3::new(-du, dv, 1.0).normalize();
            [byte(n.x), byte(n.y), byte(n.z)]
        })
        .collect();
    GltfTexture { width: RIPPLE_TEXELS, height: RIPPLE_TEXELS, pixels, nearest: false, wrap: [10497; 2] }
}

/// The water: a closed box of six faces with vertices of their own, wound
/// outward, standing a hair above the floor. Only its top has texture
/// coordinates (u along x, v along z); the other faces' all sit at one
/// point of the image, where a normal map has no frame and leaves them flat.
fn water(material: usize) -> GltfMesh {
    let (h, d) = (HALF_WIDTH, DEPTH / 2.0);
    let centre = Vec3::new(0.0, 0.002 + d, 0.0);
    let (x, y, z) = (Vec3::X * h, Vec3::Y * d, Vec3::Z * h);
    // Each face: its centre's offset and two half-edges s, t with s × t outward.
    let faces = [(y, z, x), (-y, x, z), (x, y, z), (-x, z, y), (z, x, y), (-z, y, x)];
    let (mut positions, mut uvs, mut indices) = (Vec::new(), Vec::new(), Vec::new());
    for (face, (offset, s, t)) in faces.into_iter().enumerate() {
        let first = positions.len() as u32;
        for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let p = centre + offset + s * a + t * b;
            positions.push(p.to_array());
            let repeats = RIPPLE_REPEATS / (2.0 * HALF_WIDTH);
            uvs.push(if face == 0 { [(p.x + h) * repeats, (p.z + h) * repeats] } else { [0.0, 0.0] });
        }
        indices.extend([first, first + 1, first + 2, first, first + 2, first + 3]);
    }
    GltfMesh { uvs, ..GltfMesh::new("water", (positions, indices), material, [0.0; 3]) }
}

/// The scene as a glTF document.
pub fn document() -> GltfDocument {
    let water_material = GltfMaterial {
        attenuation: Some(([0.8, 0.95, 0.97], 1.0)),
        normal_texture: Some((ripples(), 1.0)),
        // Water: n_d 1.333, V_d 55.8 (KHR_materials_dispersion is 20/V_d).
        ..GltfMaterial::glass("water", 1.333, 20.0 / 55.8)
    };
    let materials = vec![
        GltfMaterial { base_color_texture: Some(tiles()), ..GltfMaterial::diffuse("floor", [0.9; 3]) },
        water_material,
    ];
    let floor = (vec![[-6.0, 0.0, -6.0], [6.0, 0.0, -6.0], [6.0, 0.0, 6.0], [-6.0, 0.0, 6.0]], vec![0, 2, 1, 0, 3, 2]);
    let meshes = vec![
        GltfMesh {
            uvs: vec![[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]],
            ..GltfMesh::new("floor", floor, 0, [0.0; 3])
        },
        water(1),
    ];
    // The sun high (62° up), from behind on the left.
    let elevation = 62f32.to_radians();
    let direction = [elevation.cos() * 0.5, -elevation.sin(), elevation.cos() * 0.87];
    GltfDocument {
        materials,
        meshes,
        lights: vec![GltfLight::Directional { direction, intensity: SUN_IRRADIANCE }],
        camera: Some(GltfCamera { position: [0.0, 3.6, 4.4], look_at: [0.0, 0.2, 0.0], yfov: 42f32.to_radians() }),
    }
}

/// Its render settings: `sunlit-glass`'s (16 bands, 150,000 photons a
/// pass, no indirect light), with 4 hero wavelengths a path, a small
/// radius for thin lines, and a pale sky for the water to mirror (glTF
/// has no environment).
pub fn settings(render: &mut RenderSettings) {
    crate::sunlit_glass::settings(render);
    (render.width, render.height) = (480, 360);
    render.wavelengths = WavelengthSampling::Hero;
    render.radius = 0.012;
    render.background = prismatic_core::Vec3::new(0.45, 0.5, 0.58);
}
