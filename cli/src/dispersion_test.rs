//! The built-in `dispersion-test` scene, after the layout of Khronos's
//! `DispersionTest` sample model: a grid of glass prisms on a floor, the
//! index of refraction growing down the rows (1.0, 1.33, 1.5, 1.76, 2.42)
//! and `KHR_materials_dispersion` along the columns (0, 0.5, 1, 2, 5), lit
//! from the side by the sun (a directional light) so that each prism throws
//! its caustic onto the floor, with a backdrop wall behind the grid. Floor
//! and wall are textured (tiles, and a grid the prisms refract). The
//! project writes it as glTF and reads it back through the glTF importer,
//! so the scene is also a test of both.

use crate::gltf_write::{GltfCamera, GltfDocument, GltfLight, GltfMaterial, GltfMesh, prism};
use crate::patterns::{graph_paper, tiles};
use prismatic_core::model::color::ToneMap;
use prismatic_core::model::scene::RenderSettings;
use prismatic_core::{BandSpec, Estimator};

/// Indices of refraction, one per row (front to back).
pub const IORS: [f32; 5] = [1.0, 1.33, 1.5, 1.76, 2.42];
/// `KHR_materials_dispersion` values (20/V_d), one per column (left to right).
pub const DISPERSIONS: [f32; 5] = [0.0, 0.5, 1.0, 2.0, 5.0];
/// Distance between neighbouring prisms.
pub const SPACING: f32 = 1.2;
/// The sun's irradiance on a surface facing it (W/m²; the spot light this
/// scene had, 700 W/sr from 14 units away, gave the same).
const SUN_IRRADIANCE: f32 = 700.0 / (14.0 * 14.0);

/// Where the prism of `row` and `column` stands (its centre on the floor).
pub fn prism_centre(row: usize, column: usize) -> [f32; 2] {
    [(column as f32 - 2.0) * SPACING, (row as f32 - 2.0) * SPACING]
}

/// The scene as a glTF document.
pub fn document() -> GltfDocument {
    let floor = GltfMaterial { base_color_texture: Some(tiles()), ..GltfMaterial::diffuse("floor", [0.9; 3]) };
    let mut materials = vec![floor];
    // One tile texture (two tiles a side) per 4 × 4 units.
    let mut meshes = vec![GltfMesh {
        name: "floor".into(),
        positions: vec![[-7.0, 0.0, -7.0], [7.0, 0.0, -7.0], [7.0, 0.0, 7.0], [-7.0, 0.0, 7.0]],
        indices: vec![0, 2, 1, 0, 3, 2],
        uvs: vec![[0.0, 0.0], [3.5, 0.0], [3.5, 3.5], [0.0, 3.5]],
        normals: Vec::new(),
        material: 0,
        translation: [0.0; 3],
        tangents: Vec::new(),
    }];
    // The backdrop: a wall along the far edge of the floor, facing the grid,
    // its lines a unit apart.
    let backdrop =
        GltfMaterial { base_color_texture: Some(graph_paper()), ..GltfMaterial::diffuse("backdrop", [1.0; 3]) };
    materials.push(backdrop);
    meshes.push(GltfMesh {
        name: "backdrop".into(),
        positions: vec![[-7.0, 0.0, -7.0], [7.0, 0.0, -7.0], [7.0, 5.0, -7.0], [-7.0, 5.0, -7.0]],
        indices: vec![0, 1, 2, 0, 2, 3],
        uvs: vec![[0.0, 1.25], [3.5, 1.25], [3.5, 0.0], [0.0, 0.0]],
        normals: Vec::new(),
        material: 1,
        translation: [0.0; 3],
        tangents: Vec::new(),
    });
    for (row, &ior) in IORS.iter().enumerate() {
        for (column, &dispersion) in DISPERSIONS.iter().enumerate() {
            materials.push(GltfMaterial::glass(&format!("n {ior}, dispersion {dispersion}"), ior, dispersion));
            // A 60° prism lying along z, apex up, held 0.8 above the floor
            // so that its spectrum has room to fan out before it lands.
            let (positions, indices) =
                prism([[-0.3, 0.8, -0.25], [0.3, 0.8, -0.25], [0.0, 1.32, -0.25]], [0.0, 0.0, 0.5]);
            let [x, z] = prism_centre(row, column);
            meshes.push(GltfMesh {
                name: format!("prism row {row} column {column}"),
                positions,
                indices,
                uvs: Vec::new(),
                normals: Vec::new(),
                material: materials.len() - 1,
                translation: [x, 0.0, z],
                tangents: Vec::new(),
            });
        }
    }
    // The sun 60° above the floor, from −x (the backdrop, edge-on to it,
    // is lit by the ambient term only: a dark wall the prisms refract).
    let elevation = 60f32.to_radians();
    let direction = [elevation.cos(), -elevation.sin(), 0.0];
    GltfDocument {
        materials,
        meshes,
        lights: vec![GltfLight::Directional { direction, intensity: SUN_IRRADIANCE }],
        camera: Some(GltfCamera { position: [0.0, 6.0, 9.0], look_at: [0.6, 0.6, -1.0], yfov: 48f32.to_radians() }),
    }
}

/// Its render settings: physically based bands and enough photons for
/// twenty-five caustics.
pub fn settings(render: &mut RenderSettings) {
    render.bands = BandSpec::Physical(16);
    render.estimator = Estimator::Density;
    render.photons = 200_000;
    render.radius = 0.03;
    render.ambient = 0.05;
    // The ambient stands in for bounced light, as when the picture was
    // made: at 16 passes indirect photons speckle the backdrop in shade.
    render.indirect_photons = 0;
    render.tone_map = ToneMap::Reinhard;
    render.auto_exposure = false;
}
