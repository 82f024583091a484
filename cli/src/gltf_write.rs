//! Writes small glTF 2.0 documents: triangle meshes (with texture
//! coordinates, normals, tangents), materials with a base-colour texture
//! or a normal map or the transmission,
//! IOR, dispersion and volume extensions, punctual lights and a camera,
//! with the binary data and PNG images in the file (a base64 data URI).
//! The project writes its own glTF scenes and test files with it.

use crate::gltf_scene::HARD_EDGE;
use glam::{Mat3, Quat, Vec3};
use serde_json::{Value, json};
use std::f32::consts::{PI, TAU};

/// A material: base colour, metal/roughness, and for glass the
/// transmission, index and `KHR_materials_dispersion` value (20/V_d).
#[derive(Clone, Debug, PartialEq)]
pub struct GltfMaterial {
    /// Name.
    pub name: String,
    /// Base colour (linear RGB).
    pub base_color: [f32; 3],
    /// Metalness, 0–1.
    pub metallic: f32,
    /// Roughness, 0–1.
    pub roughness: f32,
    /// `KHR_materials_transmission` factor (0: opaque).
    pub transmission: f32,
    /// `KHR_materials_ior`.
    pub ior: f32,
    /// `KHR_materials_dispersion` (0: none).
    pub dispersion: f32,
    /// `KHR_materials_specular`'s `specularFactor` of an opaque non-metal:
    /// 1 is glTF's default specular layer over its diffuse base, 0 none
    /// (a Lambertian surface, prismatic's diffuse).
    pub specular: f32,
    /// `KHR_materials_volume`'s `attenuationColor` and `attenuationDistance`
    /// (`None`: clear glass).
    pub attenuation: Option<([f32; 3], f32)>,
    /// `baseColorTexture` on `TEXCOORD_0`.
    pub base_color_texture: Option<GltfTexture>,
    /// `metallicRoughnessTexture` on `TEXCOORD_0` (its pixels linear:
    /// roughness in green, metalness in blue).
    pub metallic_roughness_texture: Option<GltfTexture>,
    /// `normalTexture` on `TEXCOORD_0` (its pixels linear) and its `scale`.
    pub normal_texture: Option<(GltfTexture, f32)>,
}

/// An image (stored as PNG) with its sampler.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfTexture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// 8-bit sRGB pixels, row by row from the top.
    pub pixels: Vec<[u8; 3]>,
    /// `magFilter` nearest (else linear).
    pub nearest: bool,
    /// `wrapS` and `wrapT` as glTF numbers them (10497 repeat, 33071
    /// clamp to edge, 33648 mirrored repeat).
    pub wrap: [u32; 2],
}

impl GltfMesh {
    /// A mesh without texture coordinates or normals: `name`, its
    /// positions and indices, its material and its node's translation.
    pub fn new(
        name: &str,
        (positions, indices): (Vec<[f32; 3]>, Vec<u32>),
        material: usize,
        translation: [f32; 3],
    ) -> Self {
        let (uvs, normals, tangents) = (Vec::new(), Vec::new(), Vec::new());
        GltfMesh { name: name.into(), positions, indices, uvs, normals, tangents, material, translation }
    }

    /// A ball of `radius` centred on its node (`rings` × 2·`rings` quads,
    /// [`sphere`]) with the sphere's normals at its vertices: smooth.
    pub fn ball(name: &str, (radius, rings): (f32, u32), material: usize, translation: [f32; 3]) -> Self {
        let (positions, indices) = sphere(radius, rings);
        let normals = positions.iter().map(|p| p.map(|x| x / radius)).collect();
        GltfMesh { normals, ..GltfMesh::new(name, (positions, indices), material, translation) }
    }
}

impl GltfMaterial {
    /// An opaque diffuse material: Lambertian, without glTF's specular layer.
    pub fn diffuse(name: &str, base_color: [f32; 3]) -> Self {
        GltfMaterial {
            name: name.into(),
            base_color,
            metallic: 0.0,
            roughness: 1.0,
            transmission: 0.0,
            ior: 1.5,
            dispersion: 0.0,
            specular: 0.0,
            attenuation: None,
            base_color_texture: None,
            metallic_roughness_texture: None,
            normal_texture: None,
        }
    }

    /// Clear smooth solid glass (a volume) of index `ior` and dispersion `dispersion`.
    pub fn glass(name: &str, ior: f32, dispersion: f32) -> Self {
        GltfMaterial {
            name: name.into(),
            base_color: [1.0; 3],
            metallic: 0.0,
            roughness: 0.0,
            transmission: 1.0,
            ior,
            dispersion,
            specular: 1.0,
            attenuation: None,
            base_color_texture: None,
            metallic_roughness_texture: None,
            normal_texture: None,
        }
    }
}

/// A triangle mesh in its node's frame, placed by a translation.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfMesh {
    /// Name.
    pub name: String,
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Three indices a triangle, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
    /// Texture coordinates per vertex (`TEXCOORD_0`), or empty.
    pub uvs: Vec<[f32; 2]>,
    /// Unit normals per vertex (`NORMAL`), or empty: flat triangles.
    pub normals: Vec<[f32; 3]>,
    /// Tangents with their handedness per vertex (`TANGENT`), or empty.
    pub tangents: Vec<[f32; 4]>,
    /// Index into the document's materials.
    pub material: usize,
    /// The node's translation.
    pub translation: [f32; 3],
}

/// A closed sphere of `rings` × 2·`rings` quads, wound outward (the poles'
/// triangles have no area and are dropped when the scene is prepared).
pub fn sphere(radius: f32, rings: u32) -> (Vec<[f32; 3]>, Vec<u32>) {
    let segments = 2 * rings;
    let mut positions = Vec::new();
    for r in 0..=rings {
        let theta = PI * r as f32 / rings as f32;
        // The poles exactly (sin π in f32 is not 0).
        let (sin, cos) = match r {
            0 => (0.0, 1.0),
            _ if r == rings => (0.0, -1.0),
            _ => theta.sin_cos(),
        };
        for s in 0..segments {
            let phi = TAU * s as f32 / segments as f32;
            positions.push([radius * sin * phi.cos(), radius * cos, radius * sin * phi.sin()]);
        }
    }
    let mut indices = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            let (a, b) = (r * segments + s, r * segments + (s + 1) % segments);
            let (c, d) = (a + segments, b + segments);
            indices.extend([a, b, c, b, d, c]);
        }
    }
    (positions, indices)
}

/// A `KHR_lights_punctual` light.
#[derive(Clone, Debug, PartialEq)]
pub enum GltfLight {
    /// A spot light: intensity in W/sr (prismatic reads candela as W/sr),
    /// outer cone half-angle in radians.
    Spot {
        /// Position.
        position: [f32; 3],
        /// Direction it shines.
        direction: [f32; 3],
        /// Intensity.
        intensity: f32,
        /// Outer cone half-angle, radians.
        outer_cone: f32,
    },
    /// A point light: intensity in W/sr.
    Point {
        /// Position.
        position: [f32; 3],
        /// Intensity.
        intensity: f32,
    },
    /// A directional light (the sun): intensity read as W/m² (prismatic
    /// reads lux as W/m²).
    Directional {
        /// Direction it shines.
        direction: [f32; 3],
        /// Intensity.
        intensity: f32,
    },
}

/// A perspective camera.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfCamera {
    /// Eye.
    pub position: [f32; 3],
    /// Point looked at.
    pub look_at: [f32; 3],
    /// Vertical field of view, radians.
    pub yfov: f32,
}

/// A whole document.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GltfDocument {
    /// Materials.
    pub materials: Vec<GltfMaterial>,
    /// Meshes, one node each.
    pub meshes: Vec<GltfMesh>,
    /// Lights, one node each.
    pub lights: Vec<GltfLight>,
    /// The camera, if any.
    pub camera: Option<GltfCamera>,
}

impl GltfDocument {
    /// The document as glTF JSON text (`.gltf`), its buffer embedded.
    pub fn to_json(&self) -> String {
        let mut bin: Vec<u8> = Vec::new();
        let (mut views, mut accessors, mut meshes, mut nodes) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (i, m) in self.meshes.iter().enumerate() {
            let (lo, hi) = m.positions.iter().fold(([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]), |(lo, hi), p| {
                (std::array::from_fn(|k| lo[k].min(p[k])), std::array::from_fn(|k| hi[k].max(p[k])))
            });
            let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
            let position_view = push_view(&mut bin, &mut views, floats(m.positions.as_flattened()), Some(34962));
            let index_view =
                push_view(&mut bin, &mut views, m.indices.iter().flat_map(|x| x.to_le_bytes()), Some(34963));
            accessors.push(json!({
                "bufferView": position_view, "componentType": 5126, "count": m.positions.len(),
                "type": "VEC3", "min": lo, "max": hi
            }));
            let mut attributes = json!({ "POSITION": accessors.len() - 1 });
            accessors.push(
                json!({ "bufferView": index_view, "componentType": 5125, "count": m.indices.len(), "type": "SCALAR" }),
            );
            let indices = accessors.len() - 1;
            if !m.uvs.is_empty() {
                let uv_view = push_view(&mut bin, &mut views, floats(m.uvs.as_flattened()), Some(34962));
                accessors.push(
                    json!({ "bufferView": uv_view, "componentType": 5126, "count": m.uvs.len(), "type": "VEC2" }),
                );
                attributes["TEXCOORD_0"] = json!(accessors.len() - 1);
            }
            if !m.normals.is_empty() {
                let normal_view = push_view(&mut bin, &mut views, floats(m.normals.as_flattened()), Some(34962));
                accessors.push(
                    json!({ "bufferView": normal_view, "componentType": 5126, "count": m.normals.len(), "type": "VEC3" }),
                );
                attributes["NORMAL"] = json!(accessors.len() - 1);
            }
            if !m.tangents.is_empty() {
                let tangent_view = push_view(&mut bin, &mut views, floats(m.tangents.as_flattened()), Some(34962));
                accessors.push(
                    json!({ "bufferView": tangent_view, "componentType": 5126, "count": m.tangents.len(), "type": "VEC4" }),
                );
                attributes["TANGENT"] = json!(accessors.len() - 1);
            }
            meshes.push(json!({
                "name": m.name,
                "primitives": [{ "attributes": attributes, "indices": indices, "material": m.material }]
            }));
            nodes.push(json!({ "name": m.name, "mesh": i, "translation": m.translation }));
        }
        let mut lights = Vec::new();
        for (i, l) in self.lights.iter().enumerate() {
            let (light, position, direction) = match *l {
                // A hard edge: glTF asks innerConeAngle < outerConeAngle.
                GltfLight::Spot { position, direction, intensity, outer_cone } => (
                    json!({ "type": "spot", "intensity": intensity,
                            "spot": { "innerConeAngle": outer_cone * HARD_EDGE, "outerConeAngle": outer_cone } }),
                    position,
                    direction,
                ),
                GltfLight::Point { position, intensity } => {
                    (json!({ "type": "point", "intensity": intensity }), position, [0.0, 0.0, -1.0])
                }
                GltfLight::Directional { direction, intensity } => {
                    (json!({ "type": "directional", "intensity": intensity }), [0.0; 3], direction)
                }
            };
            lights.push(light);
            // A light shines down its node's −Z.
            let rotation = Quat::from_rotation_arc(Vec3::NEG_Z, Vec3::from(direction).normalize());
            nodes.push(json!({
                "name": format!("light {i}"), "translation": position, "rotation": rotation.to_array(),
                "extensions": { "KHR_lights_punctual": { "light": i } }
            }));
        }
        let mut cameras = Vec::new();
        if let Some(c) = &self.camera {
            let (eye, target) = (Vec3::from(c.position), Vec3::from(c.look_at));
            let back = (eye - target).normalize();
            let right = Vec3::Y.cross(back).normalize();
            let rotation = Quat::from_mat3(&Mat3::from_cols(right, back.cross(right), back));
            cameras.push(json!({ "type": "perspective", "perspective": { "yfov": c.yfov, "znear": 0.01 } }));
            nodes.push(
                json!({ "name": "camera", "camera": 0, "translation": c.position, "rotation": rotation.to_array() }),
            );
        }
        // Each material's textures: a PNG in the buffer, a sampler, an image and a texture of their own.
        let (mut images, mut samplers, mut textures) = (Vec::new(), Vec::new(), Vec::new());
        let mut texture = |t: &GltfTexture| {
            let view = push_view(&mut bin, &mut views, encode_png(t), None);
            images.push(json!({ "bufferView": view, "mimeType": "image/png" }));
            let mag = if t.nearest { 9728 } else { 9729 };
            samplers.push(json!({ "magFilter": mag, "wrapS": t.wrap[0], "wrapT": t.wrap[1] }));
            textures.push(json!({ "source": images.len() - 1, "sampler": samplers.len() - 1 }));
            textures.len() - 1
        };
        let mut materials: Vec<Value> = Vec::new();
        for m in &self.materials {
            let mut json = material_json(m);
            if let Some(t) = &m.base_color_texture {
                json["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": texture(t) });
            }
            if let Some(t) = &m.metallic_roughness_texture {
                json["pbrMetallicRoughness"]["metallicRoughnessTexture"] = json!({ "index": texture(t) });
            }
            if let Some((t, scale)) = &m.normal_texture {
                json["normalTexture"] = json!({ "index": texture(t), "scale": scale });
            }
            materials.push(json);
        }
        let uri = format!("data:application/octet-stream;base64,{}", base64::encode(&bin));
        let mut doc = json!({
            "asset": { "version": "2.0", "generator": "prismatic" },
            "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_dispersion", "KHR_materials_volume", "KHR_materials_specular"],
            "scene": 0,
            "scenes": [{ "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
            "nodes": nodes,
            "meshes": meshes,
            "materials": materials,
            "accessors": accessors,
            "bufferViews": views,
            "buffers": [{ "byteLength": bin.len(), "uri": uri }],
            "extensions": { "KHR_lights_punctual": { "lights": lights } },
        });
        if !cameras.is_empty() {
            doc["cameras"] = Value::Array(cameras);
        }
        if !textures.is_empty() {
            doc["images"] = Value::Array(images);
            doc["samplers"] = Value::Array(samplers);
            doc["textures"] = Value::Array(textures);
        }
        serde_json::to_string_pretty(&doc).expect("JSON values serialize")
    }
}

/// Appends `bytes` to `bin` (4-byte aligned) as a new buffer view; its index.
/// `target` is the buffer binding (`None` for images).
fn push_view(
    bin: &mut Vec<u8>,
    views: &mut Vec<Value>,
    bytes: impl IntoIterator<Item = u8>,
    target: Option<u32>,
) -> usize {
    let offset = bin.len();
    bin.extend(bytes);
    let length = bin.len() - offset;
    bin.resize(bin.len().next_multiple_of(4), 0);
    let mut view = json!({ "buffer": 0, "byteOffset": offset, "byteLength": length });
    if let Some(target) = target {
        view["target"] = json!(target);
    }
    views.push(view);
    views.len() - 1
}

/// The texture's pixels as PNG bytes.
fn encode_png(t: &GltfTexture) -> Vec<u8> {
    let raw: Vec<u8> = t.pixels.iter().flatten().copied().collect();
    let image = image::RgbImage::from_raw(t.width, t.height, raw).expect("width × height pixels");
    let mut png = std::io::Cursor::new(Vec::new());
    image.write_to(&mut png, image::ImageFormat::Png).expect("PNG encoding into memory does not fail");
    png.into_inner()
}

fn material_json(m: &GltfMaterial) -> Value {
    let [r, g, b] = m.base_color;
    let mut extensions = serde_json::Map::new();
    if m.transmission > 0.0 {
        extensions.insert("KHR_materials_transmission".into(), json!({ "transmissionFactor": m.transmission }));
        extensions.insert("KHR_materials_ior".into(), json!({ "ior": m.ior }));
        if m.dispersion > 0.0 {
            extensions.insert("KHR_materials_dispersion".into(), json!({ "dispersion": m.dispersion }));
        }
        // Solid glass: a volume (without one, glTF's glass is a thin sheet).
        let volume = match m.attenuation {
            Some((color, distance)) => {
                json!({ "thicknessFactor": 1.0, "attenuationColor": color, "attenuationDistance": distance })
            }
            None => json!({ "thicknessFactor": 1.0 }),
        };
        extensions.insert("KHR_materials_volume".into(), volume);
    } else if m.specular != 1.0 {
        extensions.insert("KHR_materials_specular".into(), json!({ "specularFactor": m.specular }));
    }
    json!({
        "name": m.name,
        "pbrMetallicRoughness": { "baseColorFactor": [r, g, b, 1.0], "metallicFactor": m.metallic, "roughnessFactor": m.roughness },
        "extensions": extensions,
    })
}

/// A triangular prism: one end's three corners extruded by `extrude`,
/// eight triangles wound counter-clockwise seen from outside.
pub fn prism(mut corners: [[f32; 3]; 3], extrude: [f32; 3]) -> (Vec<[f32; 3]>, Vec<u32>) {
    let e = Vec3::from(extrude);
    let [a, b, c] = corners.map(Vec3::from);
    if (b - a).cross(c - a).dot(e) > 0.0 {
        corners.swap(1, 2);
    }
    let far: Vec<[f32; 3]> = corners.iter().map(|&c| (Vec3::from(c) + e).to_array()).collect();
    let positions = [corners.to_vec(), far].concat();
    // Ends: 0,1,2 seen from outside the near end; the far end reversed.
    let mut indices = vec![0, 1, 2, 3, 5, 4];
    for k in 0..3u32 {
        let (a, b) = (k, (k + 1) % 3);
        indices.extend([a, a + 3, b, b, a + 3, b + 3]);
    }
    (positions, indices)
}
