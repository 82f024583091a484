//! glTF 2.0 scenes (`.gltf`, `.glb`): triangle meshes placed by their node
//! transforms, materials from `pbrMetallicRoughness` (diffuse with the
//! base-colour texture on `TEXCOORD_0`, its sampler and its
//! `KHR_texture_transform`, or a metal of the base colour and roughness
//! blended with a diffuse base by its metalness, texel by texel),
//! their normal maps (the mesh's `TANGENT`, else MikkTSpace's tangents)
//! and the transmission (rough or polished), IOR,
//! volume and dispersion extensions, `KHR_lights_punctual` lights, and the
//! first camera (else one that frames the scene).
//!
//! Emissive materials (`emissiveFactor` × `KHR_materials_emissive_strength`)
//! make their meshes area lights.
//!
//! What prismatic cannot represent (other textures,
//! skins, morph targets, lines and points) is reported once per
//! element as a warning and left out; what makes no sense (a missing
//! buffer, an unreadable image, an index out of range, a NaN) is an error
//! naming the element's glTF path.

use crate::scene_file::document::{SceneDocument, SceneFileError};
use crate::tangents::add_mikktspace_tangents;
use crate::texture_file;
use glam::{Affine2, Mat3, Mat4, Vec2, Vec3, Vec4};
use gltf::khr_lights_punctual::Kind;
use gltf::texture::{MagFilter, WrappingMode};
use prismatic_core::geometry::texture::srgb_to_linear;
use prismatic_core::model::mesh::open_edge;
use prismatic_core::model::metalness::{Metalness, SpecularLayer};
use prismatic_core::model::scene::{
    Attenuation, Camera, EnvironmentMap, FilmMap, Filter, Light, MAX_IMAGE_SIDE, Material, MaterialKind, NormalMap,
    Object, RenderSettings, Sampler, Scene, Shape, SpecularMap, Texture, ThinFilm, Wrap, default_ambient,
};
use prismatic_core::model::spectrum::Spectrum;
use prismatic_core::sampling::spot_cone::SpotCone;
use prismatic_core::{Dispersion, MetalColor};
use std::collections::HashMap;
use std::path::Path;

/// A spot whose `innerConeAngle` is at least this fraction of its
/// `outerConeAngle` is read as a hard edge (glTF cannot write an equal
/// pair): the paper's spot, as prismatic's scene files write it.
pub const HARD_EDGE: f32 = 0.99;

/// A glTF file's contents as prismatic scene parts.
#[derive(Debug, Default)]
pub struct GltfScene {
    /// One material per glTF material used (and a default one if a mesh has none).
    pub materials: Vec<Material>,
    /// One mesh object per triangle primitive.
    pub objects: Vec<Object>,
    /// Spot and point lights.
    pub lights: Vec<Light>,
    /// The first camera, if the file has one.
    pub camera: Option<Camera>,
    /// Its width over its height, when the file gives one.
    pub aspect_ratio: Option<f32>,
    /// What was left out, one line per element.
    pub warnings: Vec<String>,
    /// The glTF element behind each scene key (`object[2]` →
    /// `meshes[1].primitives[0]`), for errors the scene's validation finds.
    pub elements: Vec<(String, String)>,
}

/// An error in a glTF file: the element's path (`meshes[0].primitives[1]`) and why.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfError {
    /// Where in the file.
    pub path: String,
    /// What is wrong.
    pub reason: String,
}

impl GltfError {
    fn new(path: impl Into<String>, reason: impl Into<String>) -> Self {
        GltfError { path: path.into(), reason: reason.into() }
    }
}

/// Reads `path` (a `.gltf` with its buffers, or a `.glb`) into scene parts.
pub fn import(path: &Path) -> Result<GltfScene, GltfError> {
    let bytes = std::fs::read(path).map_err(|e| GltfError::new("", format!("cannot read the file: {e}")))?;
    import_slice(&bytes, path.parent())
}

/// Reads a glTF document from memory; `base` resolves its buffers' file names.
pub fn import_slice(bytes: &[u8], base: Option<&Path>) -> Result<GltfScene, GltfError> {
    let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| GltfError::new("", e.to_string()))?;
    let buffers = gltf::import_buffers(&gltf.document, base, gltf.blob.clone())
        .map_err(|e| GltfError::new("buffers", e.to_string()))?;
    // Images are decoded when a material shows one, each once.
    let mut images = Images {
        json: gltf.document.as_json(),
        document: &gltf.document,
        base,
        buffers: &buffers,
        decoded: HashMap::new(),
    };
    let mut out = GltfScene::default();
    // By glTF material (the default one last): its index in `out.materials`
    // and the transform of its base-colour texture's coordinates.
    let mut material_of: Vec<Option<(usize, Option<Affine2>)>> = vec![None; gltf.document.materials().len() + 1];
    let scene = gltf.document.default_scene().or_else(|| gltf.document.scenes().next());
    let Some(scene) = scene else {
        return Err(GltfError::new("scenes", "the file has no scene"));
    };
    // Depth first, in file order (the stack pops its last entry first).
    let mut stack: Vec<(gltf::Node<'_>, Mat4)> = scene.nodes().map(|n| (n, Mat4::IDENTITY)).collect();
    stack.reverse();
    while let Some((node, parent)) = stack.pop() {
        let node_path = format!("nodes[{}]", node.index());
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if !world.is_finite() {
            return Err(GltfError::new(node_path, "transform is not finite"));
        }
        if node.skin().is_some() {
            out.warnings.push(format!("{node_path}: skin ignored (the mesh is used in its bind pose)"));
        }
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                let prim_path = format!("meshes[{}].primitives[{}]", mesh.index(), primitive.index());
                if primitive.mode() != gltf::mesh::Mode::Triangles {
                    out.warnings
                        .push(format!("{prim_path}: {:?} primitives are left out (triangles only)", primitive.mode()));
                    continue;
                }
                if primitive.morph_targets().next().is_some() {
                    out.warnings.push(format!("{prim_path}: morph targets ignored"));
                }
                let mut shape = mesh_shape(&primitive, &buffers, world, &prim_path)?;
                let slot = primitive.material().index().map_or(material_of.len() - 1, |i| i);
                let (material, uv_transform) = match material_of[slot] {
                    Some(m) => m,
                    None => {
                        let (m, uv_transform) = material(&primitive.material(), &mut images, &mut out.warnings)?;
                        out.elements.push((format!("material.{}", m.name), material_path(&primitive.material())));
                        out.materials.push(m);
                        material_of[slot] = Some((out.materials.len() - 1, uv_transform));
                        (out.materials.len() - 1, uv_transform)
                    }
                };
                let material = match (&out.materials[material].kind, &shape) {
                    // A volume needs a closed surface; glTF does not ask
                    // for one, so an open mesh is drawn as a sheet.
                    (MaterialKind::Dielectric { thin: false, .. }, Shape::Mesh { positions, triangles, .. })
                        if open_edge(positions, triangles).is_some() =>
                    {
                        out.warnings.push(format!(
                            "{prim_path}: an open mesh has no inside: its volume is left out, drawn as thin-walled glass"
                        ));
                        thin_twin(&mut out, material)
                    }
                    _ => material,
                };
                if let (Some(t), Shape::Mesh { uvs, .. }) = (uv_transform, &mut shape) {
                    uvs.iter_mut().for_each(|uv| *uv = t.transform_point2(*uv));
                }
                if out.materials[material].normal_map.is_some() {
                    add_mikktspace_tangents(&mut shape);
                }
                // The scene's checks (closed glass, …) name the primitive.
                let object = format!("object[{}]", out.objects.len());
                out.elements.push((format!("{object}.triangles"), format!("{prim_path}.indices")));
                out.elements.push((object, prim_path));
                out.objects.push(Object { shape, material });
            }
        }
        if let Some(light) = node.light() {
            let position = world.transform_point3(Vec3::ZERO);
            // A glTF light shines down its node's −Z.
            let direction = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
            // Intensity is read as W/sr, a directional light's as W/m²
            // (prismatic is radiometric; no lm → W). Its linear RGB colour
            // becomes a smooth spectrum, and the intensity takes the factor
            // that makes the light emit that colour.
            let (spectrum, factor) = Spectrum::from_rgb(light.color());
            let intensity = light.intensity() * factor;
            let light_path = format!("{node_path}.extensions.KHR_lights_punctual");
            // A distance, which the node's scale leaves alone (as the extension says).
            let range = light.range();
            let emitted = match light.kind() {
                // A black light is valid glTF and emits nothing.
                _ if factor == 0.0 => None,
                Kind::Point => {
                    Some(Light::Point { position, power: 4.0 * std::f32::consts::PI * intensity, spectrum, range })
                }
                Kind::Spot { inner_cone_angle, outer_cone_angle } => {
                    // The intensity is the axis's; the soft edge (innerConeAngle,
                    // 0 by default) holds less power than a uniform cone.
                    let cone_deg = outer_cone_angle.to_degrees();
                    let inner_cone_deg = match inner_cone_angle >= outer_cone_angle * HARD_EDGE {
                        true => cone_deg,
                        false => inner_cone_angle.to_degrees(),
                    };
                    let cone = SpotCone::new(cone_deg, inner_cone_deg);
                    Some(Light::Spot {
                        position,
                        direction,
                        cone_deg,
                        inner_cone_deg,
                        power: 2.0 * std::f32::consts::PI * cone.measure() * intensity,
                        spectrum,
                        range,
                    })
                }
                Kind::Directional => Some(Light::Sun { direction, irradiance: intensity, spectrum, mean_toward: None }),
            };
            match emitted {
                Some(l) => {
                    out.elements.push((format!("light[{}]", out.lights.len()), light_path));
                    out.lights.push(l);
                }
                None => {
                    out.warnings.push(format!("{light_path}: its colour is black: it emits nothing and is left out"))
                }
            }
        }
        if let (Some(camera), None) = (node.camera(), &out.camera) {
            match camera.projection() {
                gltf::camera::Projection::Perspective(p) => {
                    let position = world.transform_point3(Vec3::ZERO);
                    out.camera = Some(Camera {
                        position,
                        // A glTF camera looks down its node's −Z with +Y up.
                        look_at: position + world.transform_vector3(Vec3::NEG_Z).normalize_or_zero(),
                        up: world.transform_vector3(Vec3::Y),
                        fov_deg: p.yfov().to_degrees(),
                    });
                    out.aspect_ratio = p.aspect_ratio().filter(|a| a.is_finite() && *a > 0.0);
                }
                gltf::camera::Projection::Orthographic(_) => {
                    out.warnings.push(format!("cameras[{}]: orthographic cameras are left out", camera.index()))
                }
            }
        }
        let mut children: Vec<_> = node.children().map(|c| (c, world)).collect();
        children.reverse();
        stack.extend(children);
    }
    Ok(out)
}

/// The primitive's triangles in world space.
fn mesh_shape(
    primitive: &gltf::Primitive<'_>,
    buffers: &[gltf::buffer::Data],
    world: Mat4,
    path: &str,
) -> Result<Shape, GltfError> {
    let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
    let positions: Vec<Vec3> = reader
        .read_positions()
        .ok_or_else(|| GltfError::new(format!("{path}.attributes.POSITION"), "missing or unreadable"))?
        .map(|p| world.transform_point3(Vec3::from(p)))
        .collect();
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(GltfError::new(format!("{path}.attributes.POSITION"), format!("vertex {i} is not finite")));
    }
    let indices: Vec<u32> = match reader.read_indices() {
        Some(ix) => ix.into_u32().collect(),
        None => (0..positions.len() as u32).collect(),
    };
    if let Some(&i) = indices.iter().find(|&&i| i as usize >= positions.len()) {
        return Err(GltfError::new(
            format!("{path}.indices"),
            format!("index {i} is out of range ({} vertices)", positions.len()),
        ));
    }
    if !indices.len().is_multiple_of(3) {
        return Err(GltfError::new(
            format!("{path}.indices"),
            format!("{} indices is not a whole number of triangles", indices.len()),
        ));
    }
    // A mirroring transform turns the winding inside out.
    let flip = world.determinant() < 0.0;
    let triangles =
        indices.chunks_exact(3).map(|t| if flip { [t[0], t[2], t[1]] } else { [t[0], t[1], t[2]] }).collect();
    let uvs: Vec<Vec2> = match reader.read_tex_coords(0) {
        Some(uv) => uv.into_f32().map(Vec2::from).collect(),
        None => Vec::new(),
    };
    if !uvs.is_empty() && uvs.len() != positions.len() {
        return Err(GltfError::new(
            format!("{path}.attributes.TEXCOORD_0"),
            format!("{} coordinates for {} vertices", uvs.len(), positions.len()),
        ));
    }
    let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
    let normals: Vec<Vec3> = match reader.read_normals() {
        Some(n) => n.map(|n| (normal_matrix * Vec3::from(n)).normalize_or_zero()).collect(),
        None => Vec::new(),
    };
    if !normals.is_empty() && normals.len() != positions.len() {
        return Err(GltfError::new(
            format!("{path}.attributes.NORMAL"),
            format!("{} normals for {} vertices", normals.len(), positions.len()),
        ));
    }
    if let Some(i) = normals.iter().position(|n| *n == Vec3::ZERO) {
        return Err(GltfError::new(format!("{path}.attributes.NORMAL"), format!("normal {i} is not a unit vector")));
    }
    // Tangents turn as directions; a mirroring transform turns their handedness.
    let linear = Mat3::from_mat4(world);
    let handedness = if flip { -1.0 } else { 1.0 };
    let tangents: Vec<Vec4> = match reader.read_tangents() {
        Some(t) => t.map(|[x, y, z, w]| (linear * Vec3::new(x, y, z)).extend(w * handedness)).collect(),
        None => Vec::new(),
    };
    if !tangents.is_empty() && tangents.len() != positions.len() {
        return Err(GltfError::new(
            format!("{path}.attributes.TANGENT"),
            format!("{} tangents for {} vertices", tangents.len(), positions.len()),
        ));
    }
    if let Some(i) = tangents.iter().position(|t| !t.is_finite() || t.truncate() == Vec3::ZERO || t.w == 0.0) {
        let reason = format!("tangent {i} is not a unit vector with a handedness w of ±1");
        return Err(GltfError::new(format!("{path}.attributes.TANGENT"), reason));
    }
    Ok(Shape::Mesh { positions, triangles, uvs, normals, tangents })
}

/// The file's images, decoded once each, and where to find them.
struct Images<'a> {
    /// The document as written (the gltf crate panics on an image without a source).
    json: &'a gltf::json::Root,
    /// The document, for textures an extension names by index.
    document: &'a gltf::Document,
    base: Option<&'a Path>,
    buffers: &'a [gltf::buffer::Data],
    /// By image index and the channels read, with the default sampler.
    decoded: HashMap<(usize, Channels), Texture>,
}

/// Which of an image's channels a texture's texels hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Channels {
    /// Its red, green and blue (a grey image's grey in each).
    Rgb,
    /// Its alpha in each (255 where it has none): `specularTexture`'s.
    Alpha,
}

impl Images<'_> {
    /// The texture `info` names (a base colour's, a metallic-roughness
    /// one's, a specular layer's), its `channels`, with its sampler and the
    /// `KHR_texture_transform` of its coordinates; `None` (and `other_set`
    /// in `unused`) when it reads a texture coordinate set other than 0.
    fn texture_info(
        &mut self,
        info: &gltf::texture::Info<'_>,
        channels: Channels,
        other_set: &'static str,
        unused: &mut Vec<&'static str>,
    ) -> Result<Option<(Texture, Option<Affine2>)>, GltfError> {
        let transform = info.texture_transform();
        if transform.as_ref().and_then(|t| t.tex_coord()).unwrap_or(info.tex_coord()) != 0 {
            unused.push(other_set);
            return Ok(None);
        }
        let transform = transform.map(|t| uv_transform(t.offset(), t.rotation(), t.scale()));
        Ok(Some((self.texture(&info.texture(), channels)?, transform)))
    }

    /// The normal map `info` names, with the `KHR_texture_transform` of its
    /// coordinates; `None` (and a line in `unused`) when it reads a texture
    /// coordinate set other than 0. Its texels are its image's bytes (a
    /// normal map is linear, so they are not decoded from sRGB).
    fn normal_map(
        &mut self,
        info: &gltf::material::NormalTexture<'_>,
        unused: &mut Vec<&'static str>,
    ) -> Result<Option<(NormalMap, Option<Affine2>)>, GltfError> {
        let transform = info.extension_value("KHR_texture_transform");
        if json_tex_coord(transform, info.tex_coord()) != 0 {
            unused.push("normalTexture on a texture coordinate set other than 0");
            return Ok(None);
        }
        let map = NormalMap { texture: self.texture(&info.texture(), Channels::Rgb)?, scale: info.scale() };
        Ok(Some((map, transform.map(json_uv_transform))))
    }

    /// The texture an extension's texture info `info` names (JSON: its
    /// `index`, `texCoord` and `KHR_texture_transform`; `path` in errors),
    /// with the transform of its coordinates; `None` (and `other_set` in
    /// `unused`) when it reads a texture coordinate set other than 0.
    fn extension_texture(
        &mut self,
        info: &serde_json::Value,
        path: &str,
        other_set: &'static str,
        unused: &mut Vec<&'static str>,
    ) -> Result<Option<(Texture, Option<Affine2>)>, GltfError> {
        let index = info.get("index").and_then(serde_json::Value::as_u64);
        let Some(texture) = index.and_then(|i| self.document.textures().nth(i as usize)) else {
            return Err(GltfError::new(format!("{path}.index"), "must name one of the file's textures"));
        };
        let transform = info.get("extensions").and_then(|e| e.get("KHR_texture_transform"));
        let tex_coord = info.get("texCoord").and_then(serde_json::Value::as_u64).unwrap_or(0) as u32;
        if json_tex_coord(transform, tex_coord) != 0 {
            unused.push(other_set);
            return Ok(None);
        }
        Ok(Some((self.texture(&texture, Channels::Rgb)?, transform.map(json_uv_transform))))
    }

    /// The `channels` of the image `texture` shows (decoded once) with its sampler.
    fn texture(&mut self, texture: &gltf::Texture<'_>, channels: Channels) -> Result<Texture, GltfError> {
        let decoded = self.decoded(&texture.source(), channels)?;
        let sampler = texture.sampler();
        let wrap = |w: WrappingMode| match w {
            WrappingMode::Repeat => Wrap::Repeat,
            WrappingMode::ClampToEdge => Wrap::ClampToEdge,
            WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
        };
        let filter = match sampler.mag_filter() {
            Some(MagFilter::Nearest) => Filter::Nearest,
            _ => Filter::Linear,
        };
        Ok(Texture {
            sampler: Sampler { filter, wrap_u: wrap(sampler.wrap_s()), wrap_v: wrap(sampler.wrap_t()) },
            ..decoded
        })
    }

    /// The mean linear colour of a texture's image (what an emissive
    /// texture emits on average).
    fn mean_colour(&mut self, info: &gltf::texture::Info<'_>) -> Result<Vec3, GltfError> {
        let decoded = self.decoded(&info.texture().source(), Channels::Rgb)?;
        let channel = |x: u32, shift: u32| srgb_to_linear((x >> shift) & 0xff);
        let sum: Vec3 = decoded.texels.iter().map(|&x| Vec3::new(channel(x, 0), channel(x, 8), channel(x, 16))).sum();
        Ok(sum / decoded.texels.len().max(1) as f32)
    }

    /// The `channels` of `image` decoded, once however many textures show it.
    fn decoded(&mut self, image: &gltf::Image<'_>, channels: Channels) -> Result<Texture, GltfError> {
        if let Some(t) = self.decoded.get(&(image.index(), channels)) {
            return Ok(t.clone());
        }
        let t = self.decode(image, channels)?;
        self.decoded.insert((image.index(), channels), t.clone());
        Ok(t)
    }

    /// An image's pixels as 8-bit texels: their colour (grey images as
    /// grey, alpha left out) or their alpha, 16-bit channels to their high byte.
    fn decode(&self, image: &gltf::Image<'_>, read: Channels) -> Result<Texture, GltfError> {
        use gltf::image::Format;
        let path = format!("images[{}]", image.index());
        let json = &self.json.images[image.index()];
        match (&json.buffer_view, &json.mime_type, &json.uri) {
            (Some(_), None, _) => return Err(GltfError::new(&path, "an image in a buffer view needs a mimeType")),
            (None, _, None) => return Err(GltfError::new(&path, "the image has neither a uri nor a bufferView")),
            _ => {}
        }
        let name = match image.source() {
            gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => format!("{path} ({uri})"),
            _ => image.name().map_or_else(|| path.clone(), |n| format!("{path} ({n})")),
        };
        let data = gltf::image::Data::from_source(image.source(), self.base, self.buffers)
            .map_err(|e| GltfError::new(&path, format!("cannot read the image: {e}")))?;
        let (channels, bytes) = match data.format {
            Format::R8 => (1, 1),
            Format::R8G8 => (2, 1),
            Format::R8G8B8 => (3, 1),
            Format::R8G8B8A8 => (4, 1),
            Format::R16 => (1, 2),
            Format::R16G16 => (2, 2),
            Format::R16G16B16 => (3, 2),
            Format::R16G16B16A16 => (4, 2),
            other => {
                return Err(GltfError::new(&path, format!("{other:?} images are not supported as textures")));
            }
        };
        // The most significant byte of each channel (16-bit channels are native-endian).
        let high = |px: &[u8], c: usize| {
            if bytes == 1 { px[c] } else { u16::from_ne_bytes([px[2 * c], px[2 * c + 1]]).to_be_bytes()[0] }
        };
        let pixels = data.pixels.chunks_exact(channels * bytes).map(|px| match (read, channels) {
            (Channels::Alpha, 2 | 4) => [high(px, channels - 1); 3],
            (Channels::Alpha, _) => [255; 3],
            (Channels::Rgb, 1 | 2) => [high(px, 0); 3],
            (Channels::Rgb, _) => [high(px, 0), high(px, 1), high(px, 2)],
        });
        Ok(texture_file::from_rgb8(name, data.width, data.height, pixels, Sampler::default()))
    }
}

/// `KHR_texture_transform`'s T · R · S on texture coordinates: scale, then
/// rotate, then offset. Its rotation turns u toward −v (rows (cos, sin) and
/// (−sin, cos)), as the Khronos sample viewer, three.js and Bevy read it:
/// glam's angle is its negative.
fn uv_transform(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> Affine2 {
    Affine2::from_scale_angle_translation(scale.into(), -rotation, offset.into())
}

/// The prismatic material of a glTF material, with the transform of its
/// textures' coordinates (its base colour's, else its normal map's); what
/// it leaves out goes to `warnings`.
fn material(
    m: &gltf::Material<'_>,
    images: &mut Images<'_>,
    warnings: &mut Vec<String>,
) -> Result<(Material, Option<Affine2>), GltfError> {
    let path = material_path(m);
    let name = m.name().map_or_else(|| path.clone(), str::to_string);
    let pbr = m.pbr_metallic_roughness();
    let mut unused = Vec::new();
    // occlusionTexture is not left out but not needed: it bakes for
    // rasterisers the shadowing that traced rays find themselves.
    let metal_roughness = match pbr.metallic_roughness_texture() {
        Some(info) => images.texture_info(
            &info,
            Channels::Rgb,
            "metallicRoughnessTexture on a texture coordinate set other than 0",
            &mut unused,
        )?,
        None => None,
    };
    let transmission = m.transmission().map_or(0.0, |t| t.transmission_factor());
    // Any metal in it: a metal blended with a diffuse base by its metalness.
    let metal = match transmission > 0.0 {
        true => None,
        false => Metalness::of(pbr.metallic_factor(), metal_roughness.as_ref().map(|(t, _)| &*t.texels)),
    };
    let glass_or_metal = transmission > 0.0 || metal.is_some();
    let mut emission = emission(m);
    if glass_or_metal && emission != Vec3::ZERO {
        unused.push("emission of glass or a metal (only diffuse surfaces emit)");
    } else if let Some(info) = m.emissive_texture().filter(|_| emission != Vec3::ZERO) {
        // Emission is per mesh: the texture's mean keeps its flux, not its pattern.
        emission *= images.mean_colour(&info)?;
        unused.push("emissiveTexture's pattern (the mesh emits the texture's mean colour evenly)");
    }
    // The diffuse base's specular layer (an emitter stays diffuse: only
    // diffuse surfaces emit, and its glow outshines its reflections).
    let layer = match transmission > 0.0 || (metal.is_none() && emission != Vec3::ZERO) {
        true => None,
        false => specular_layer(m),
    };
    let bare = !glass_or_metal && layer.is_none();
    if bare && m.extensions().is_some_and(|e| e.contains_key("KHR_materials_iridescence")) {
        unused
            .push("KHR_materials_iridescence of a bare diffuse material (films are drawn on glass, metals and layers)");
    }
    let metalness = metal.map(|metal| metal.with_layer(layer)).or_else(|| layer.map(Metalness::layered));
    let mut uv_transform = None;
    let mut kind = if transmission > 0.0 {
        if pbr.base_color_texture().is_some() {
            unused.push("baseColorTexture of glass (its colour is the volume's attenuation)");
        }
        // Without a volume (or with thicknessFactor 0) glTF's transmission
        // is thin-walled: a sheet, which may be any shape, tinted by its
        // base colour (a thin-walled volume's attenuation is named as left out).
        let thin = m.volume().is_none_or(|v| v.thickness_factor() == 0.0);
        let [r, g, b, _] = pbr.base_color_factor();
        let tint = Vec3::new(r, g, b).clamp(Vec3::splat(1e-4), Vec3::ONE);
        let volume = attenuation(m, &mut unused);
        let attenuation = match thin {
            true => (tint != Vec3::ONE).then_some(Attenuation { color: tint, distance: 1.0 }),
            false => volume,
        };
        let film = film(m)?;
        MaterialKind::Dielectric {
            dispersion: dispersion(m),
            outside: Dispersion::Constant(1.0),
            attenuation,
            thin,
            film,
            // Frosted glass: its transmission and reflection spread by GGX.
            roughness: pbr.roughness_factor(),
        }
    } else {
        let [r, g, b, _] = pbr.base_color_factor();
        let texture = match pbr.base_color_texture() {
            Some(info) => {
                let other_set = "baseColorTexture on a texture coordinate set other than 0";
                images.texture_info(&info, Channels::Rgb, other_set, &mut unused)?
            }
            None => None,
        };
        let (texture, transform) = texture.unzip();
        uv_transform = transform.flatten();
        match metalness {
            // A metal's base colour (times its texture) is its reflectance
            // at normal incidence, and its diffuse part's albedo (glTF's
            // non-metals too: a diffuse base under a specular layer).
            Some(metalness) => MaterialKind::Metal {
                color: MetalColor::Rgb(Vec3::new(r, g, b).clamp(Vec3::ZERO, Vec3::ONE)),
                roughness: pbr.roughness_factor(),
                texture,
                film: film(m)?,
                metalness,
            },
            None => MaterialKind::Diffuse { albedo: Vec3::new(r, g, b), checker: None, texture, emission },
        }
    };
    // The mesh has one set of coordinates: its textures must agree on their
    // transform (the first texture's, the base colour's where it has one).
    let mut transform = has_base_colour_texture(&kind).then_some(uv_transform);
    let mut agrees = |t: Option<Affine2>| *transform.get_or_insert(t) == t;
    // The green channel scales the roughness of a metal, glass or a
    // specular layer (a bare diffuse surface has none to scale), the blue
    // a metal's metalness.
    let has_facets = glass_or_metal || layer.is_some();
    let roughness_map = match metal_roughness {
        Some((texture, t)) if has_facets && agrees(t) => Some(texture),
        Some(_) if has_facets => {
            unused.push("metallicRoughnessTexture with another KHR_texture_transform than baseColorTexture");
            None
        }
        _ => None,
    };
    if let MaterialKind::Metal { metalness, .. } = &mut kind {
        // Without its map, the metalness is its factor's (a whole metal has no base to layer).
        metalness.mapped &= roughness_map.is_some();
        *metalness = metalness.with_layer(metalness.layer);
    }
    let normal_map = match m.normal_texture() {
        Some(info) => match images.normal_map(&info, &mut unused)? {
            Some((map, t)) if agrees(t) => Some(map),
            Some(_) => {
                unused.push("normalTexture with another KHR_texture_transform than the material's other textures");
                None
            }
            None => None,
        },
        None => None,
    };
    // A film's textures vary it (on glass or a metal that has one).
    let filmed =
        matches!(kind, MaterialKind::Metal { film: Some(_), .. } | MaterialKind::Dielectric { film: Some(_), .. });
    let moved = "iridescence textures with another KHR_texture_transform than the material's other textures";
    let film_map = film_map(m, images, &mut unused)?;
    let film_map = kept(film_map, filmed, &mut agrees, moved, &mut unused);
    // The layer's textures vary it (where it has one: not on a whole metal).
    let layered = matches!(kind, MaterialKind::Metal { metalness: Metalness { layer: Some(_), .. }, .. });
    let moved = "specular textures with another KHR_texture_transform than the material's other textures";
    let specular_map = specular_map(m, images, &mut unused)?;
    let specular_map = kept(specular_map, layered, &mut agrees, moved, &mut unused);
    if !unused.is_empty() {
        warnings.push(format!("{path} ({name}): left out: {}", unused.join(", ")));
    }
    let material = Material { normal_map, roughness_map, film_map, specular_map, ..Material::new(name, kind) };
    Ok((material, transform.flatten()))
}

/// An extension's maps `read` (with their textures' transforms), kept
/// where they `apply` and their transforms agree with the material's other
/// textures' (the mesh has one set of coordinates); `moved` goes to
/// `unused` where they apply but do not agree.
fn kept<T>(
    read: Option<(T, UvTransforms)>,
    apply: bool,
    agrees: &mut impl FnMut(Option<Affine2>) -> bool,
    moved: &'static str,
    unused: &mut Vec<&'static str>,
) -> Option<T> {
    let (maps, transforms) = read.filter(|_| apply)?;
    if transforms.iter().all(|&t| agrees(t)) {
        return Some(maps);
    }
    unused.push(moved);
    None
}

/// Does a material of `kind` read its base colour from a texture?
fn has_base_colour_texture(kind: &MaterialKind) -> bool {
    matches!(kind, MaterialKind::Diffuse { texture: Some(_), .. } | MaterialKind::Metal { texture: Some(_), .. })
}

/// The thin-walled twin of solid glass `material` (made once, named after
/// it, without its volume's attenuation).
fn thin_twin(out: &mut GltfScene, material: usize) -> usize {
    let name = format!("{} (thin-walled)", out.materials[material].name);
    if let Some(i) = out.materials.iter().position(|m| m.name == name) {
        return i;
    }
    let mut twin = Material { name, ..out.materials[material].clone() };
    if let MaterialKind::Dielectric { thin, attenuation, .. } = &mut twin.kind {
        (*thin, *attenuation) = (true, None);
    }
    let element = out.elements.iter().find(|(key, _)| *key == format!("material.{}", out.materials[material].name));
    let element = element.map_or_else(String::new, |(_, path)| path.clone());
    out.elements.push((format!("material.{}", twin.name), element));
    out.materials.push(twin);
    out.materials.len() - 1
}

/// Where a material is in the file (`materials[3]`).
fn material_path(m: &gltf::Material<'_>) -> String {
    m.index().map_or("the default material".to_string(), |i| format!("materials[{i}]"))
}

/// Beer–Lambert absorption from `KHR_materials_volume`: `attenuationColor`
/// after `attenuationDistance` (channels of 0 kept at 1e-4, so the
/// coefficient stays finite). A thin-walled material (`thicknessFactor` 0)
/// has no volume by the extension's rule; the thickness itself is a hint
/// for rasterisers (this renderer traces the real geometry).
fn attenuation(m: &gltf::Material<'_>, unused: &mut Vec<&'static str>) -> Option<Attenuation> {
    let volume = m.volume()?;
    let distance = volume.attenuation_distance();
    if !distance.is_finite() || distance <= 0.0 {
        return None;
    }
    if volume.thickness_factor() == 0.0 {
        unused.push("volume attenuation of a thin-walled material (thicknessFactor 0)");
        return None;
    }
    let color = Vec3::from(volume.attenuation_color()).clamp(Vec3::splat(1e-4), Vec3::ONE);
    Some(Attenuation { color, distance })
}

/// The specular layer of a material's dielectric base: `KHR_materials_ior`
/// (default 1.5) and `KHR_materials_specular`'s factor and colour
/// (defaults 1 and white), glTF's F0 of 0.04 and F90 of 1 without either
/// (its textures are [`specular_map`]'s).
fn specular_layer(m: &gltf::Material<'_>) -> Option<SpecularLayer> {
    let (weight, color) =
        m.specular().map_or((1.0, Vec3::ONE), |s| (s.specular_factor(), s.specular_color_factor().into()));
    SpecularLayer::gltf(m.ior().unwrap_or(1.5), weight, color)
}

/// The textures of `KHR_materials_specular`, each with the transform of
/// its coordinates: `specularTexture`, whose alpha scales
/// `specularFactor`, and `specularColorTexture` (sRGB), which scales
/// `specularColorFactor`; `None` without either. One on another
/// coordinate set is named in `unused`.
fn specular_map(
    m: &gltf::Material<'_>,
    images: &mut Images<'_>,
    unused: &mut Vec<&'static str>,
) -> Result<Option<(SpecularMap, UvTransforms)>, GltfError> {
    let Some(specular) = m.specular() else { return Ok(None) };
    let mut transforms = Vec::new();
    let mut read = |info: Option<gltf::texture::Info<'_>>, channels: Channels, other_set: &'static str| {
        let Some(info) = info else { return Ok(None) };
        let read = images.texture_info(&info, channels, other_set, unused)?;
        Ok::<_, GltfError>(read.map(|(texture, t)| {
            transforms.push(t);
            texture
        }))
    };
    let weight =
        read(specular.specular_texture(), Channels::Alpha, "specularTexture on a texture coordinate set other than 0")?;
    let color = read(
        specular.specular_color_texture(),
        Channels::Rgb,
        "specularColorTexture on a texture coordinate set other than 0",
    )?;
    if weight.is_none() && color.is_none() {
        return Ok(None);
    }
    let color_f0 = SpecularLayer::unclipped_f0(m.ior().unwrap_or(1.5), specular.specular_color_factor().into());
    Ok(Some((SpecularMap { weight, color, color_f0 }, transforms)))
}

/// The radiance a material emits: `emissiveFactor` × `KHR_materials_emissive_strength`
/// (the texture is named as left out above).
fn emission(m: &gltf::Material<'_>) -> Vec3 {
    Vec3::from(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0)
}

/// n(λ) of a transmissive material: `KHR_materials_ior` (default 1.5) and
/// `KHR_materials_dispersion`, whose `dispersion` is 20/V_d (0: none).
fn dispersion(m: &gltf::Material<'_>) -> Dispersion {
    let ior = m.ior().unwrap_or(1.5);
    let spread = m
        .extensions()
        .and_then(|e| e.get("KHR_materials_dispersion"))
        .and_then(|d| d.get("dispersion"))
        .and_then(serde_json::Value::as_f64)
        .unwrap_or(0.0) as f32;
    if spread > 0.0 { Dispersion::Abbe { nd: ior, vd: 20.0 / spread } } else { Dispersion::Constant(ior) }
}

/// The `KHR_texture_transform`s of a material's textures, in turn.
type UvTransforms = Vec<Option<Affine2>>;

/// The textures of `KHR_materials_iridescence`, each with the transform of
/// its coordinates: `iridescenceThicknessTexture`, whose green channel g
/// makes the film `iridescenceThicknessMinimum` (default 100 nm) plus g
/// times the rest of `iridescenceThicknessMaximum`, and
/// `iridescenceTexture`, whose red channel scales `iridescenceFactor`;
/// `None` without either. One on another coordinate set is named in `unused`.
fn film_map(
    m: &gltf::Material<'_>,
    images: &mut Images<'_>,
    unused: &mut Vec<&'static str>,
) -> Result<Option<(FilmMap, UvTransforms)>, GltfError> {
    let Some(ext) = m.extensions().and_then(|e| e.get("KHR_materials_iridescence")) else { return Ok(None) };
    let path = format!("{}.extensions.KHR_materials_iridescence", material_path(m));
    let mut transforms = Vec::new();
    let mut read = |key: &str, other_set: &'static str| -> Result<Option<Texture>, GltfError> {
        let Some(info) = ext.get(key) else { return Ok(None) };
        let read = images.extension_texture(info, &format!("{path}.{key}"), other_set, unused)?;
        Ok(read.map(|(texture, t)| {
            transforms.push(t);
            texture
        }))
    };
    let thickness =
        read("iridescenceThicknessTexture", "iridescenceThicknessTexture on a texture coordinate set other than 0")?;
    let factor = read("iridescenceTexture", "iridescenceTexture on a texture coordinate set other than 0")?;
    if thickness.is_none() && factor.is_none() {
        return Ok(None);
    }
    let min_nm = ext.get("iridescenceThicknessMinimum").and_then(serde_json::Value::as_f64).unwrap_or(100.0) as f32;
    Ok(Some((FilmMap { thickness, min_nm, factor }, transforms)))
}

/// The texture coordinate set a texture reads: its `KHR_texture_transform`'s
/// `texCoord` (JSON `transform`) where it has one, else `own`.
fn json_tex_coord(transform: Option<&serde_json::Value>, own: u32) -> u32 {
    transform.and_then(|t| t.get("texCoord")).and_then(serde_json::Value::as_u64).map_or(own, |c| c as u32)
}

/// A `KHR_texture_transform` (JSON) as the affine map of coordinates.
fn json_uv_transform(transform: &serde_json::Value) -> Affine2 {
    let number = |key: &str| transform.get(key).and_then(serde_json::Value::as_f64);
    let pair = |key: &str, default: [f32; 2]| {
        let values = transform.get(key).and_then(serde_json::Value::as_array);
        let at = |i: usize| values.and_then(|v| v.get(i)).and_then(serde_json::Value::as_f64);
        [at(0).map_or(default[0], |x| x as f32), at(1).map_or(default[1], |x| x as f32)]
    };
    uv_transform(pair("offset", [0.0, 0.0]), number("rotation").unwrap_or(0.0) as f32, pair("scale", [1.0, 1.0]))
}

/// The film of `KHR_materials_iridescence` on glass or a metal: `iridescenceIor`
/// (default 1.3), `iridescenceFactor` (the extension's mix of the film's
/// and the bare surface's Fresnel; 0, the default, is no film) and,
/// without a thickness texture, the film is `iridescenceThicknessMaximum`
/// thick (default 400 nm), as the extension reads a missing texture (its
/// textures are [`film_map`]'s). A factor above 1 is refused.
fn film(m: &gltf::Material<'_>) -> Result<Option<ThinFilm>, GltfError> {
    let Some(ext) = m.extensions().and_then(|e| e.get("KHR_materials_iridescence")) else { return Ok(None) };
    let number = |key: &str, default: f64| ext.get(key).and_then(serde_json::Value::as_f64).unwrap_or(default) as f32;
    let factor = number("iridescenceFactor", 0.0);
    if factor <= 0.0 {
        return Ok(None);
    }
    if factor > 1.0 {
        let path = format!("{}.extensions.KHR_materials_iridescence.iridescenceFactor", material_path(m));
        return Err(GltfError::new(path, format!("must be 0 to 1, got {factor}")));
    }
    Ok(Some(ThinFilm {
        ior: number("iridescenceIor", 1.3),
        thickness_nm: number("iridescenceThicknessMaximum", 400.0),
        factor,
    }))
}

/// A whole scene from a glTF file: its parts, its camera or one framing
/// it, default render settings scaled to its size; what was left out is in
/// the document's warnings.
pub fn load(path: &Path) -> Result<SceneDocument, SceneFileError> {
    let file = path.display().to_string();
    scene(import(path), &file)
}

/// [`load`] of a document in memory, named `file` in errors.
pub fn load_slice(bytes: &[u8], file: &str) -> Result<SceneDocument, SceneFileError> {
    scene(import_slice(bytes, None), file)
}

fn scene(parts: Result<GltfScene, GltfError>, file: &str) -> Result<SceneDocument, SceneFileError> {
    let file = file.to_string();
    let parts = parts.map_err(|e| SceneFileError { file: file.clone(), line: None, key: e.path, reason: e.reason })?;
    let (lo, hi) = bounds(&parts.objects);
    let (centre, size) = ((lo + hi) / 2.0, (hi - lo).length().max(1e-3));
    let mut warnings = parts.warnings;
    let camera = parts.camera.unwrap_or_else(|| framing_camera(centre, size));
    let mut lights = parts.lights;
    let emissive = parts.objects.iter().any(|o| parts.materials[o.material].kind.emission() != Vec3::ZERO);
    if lights.is_empty() && !emissive {
        // As viewers open a file without lights: in a neutral environment.
        warnings.push("no light: lit by the built-in studio environment".into());
        lights.push(Light::Environment {
            map: EnvironmentMap::studio(),
            strength: 1.0,
            rotation_deg: 0.0,
            spectrum: Default::default(),
        });
    }
    // Shown as viewers show a file, which brings no exposure: the
    // log-average at middle grey, through the default tone map; lit with
    // its indirect light (as many photons as caustic ones), not an ambient.
    let d = RenderSettings::default();
    let mut render = RenderSettings {
        radius: size / 100.0,
        auto_exposure: true,
        indirect_photons: d.photons,
        ambient: default_ambient(d.photons),
        ..d
    };
    if let Some(aspect) = parts.aspect_ratio {
        // The camera's frame, as many pixels as the default square.
        let side = f64::from(render.width * render.height);
        render.width = ((side * f64::from(aspect)).sqrt().round() as u32).clamp(1, MAX_IMAGE_SIDE);
        render.height = ((side / f64::from(aspect)).sqrt().round() as u32).clamp(1, MAX_IMAGE_SIDE);
    }
    let scene = Scene { render, camera, lights, materials: parts.materials, objects: parts.objects };
    Ok(SceneDocument::from_scene(scene, &file, warnings, parts.elements))
}

/// The axis-aligned box around the objects' vertices.
fn bounds(objects: &[Object]) -> (Vec3, Vec3) {
    let points = objects.iter().flat_map(|o| match &o.shape {
        Shape::Mesh { positions, .. } => positions.as_slice(),
        _ => &[],
    });
    let (lo, hi) = points.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    if lo.is_finite() { (lo, hi) } else { (Vec3::ZERO, Vec3::ZERO) }
}

/// A camera looking at `centre` from the front and above, far enough to see
/// a scene of diagonal `size`.
fn framing_camera(centre: Vec3, size: f32) -> Camera {
    Camera { position: centre + Vec3::new(0.0, 0.5, 1.2) * size, look_at: centre, up: Vec3::Y, fov_deg: 45.0 }
}
