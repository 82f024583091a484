//! The scene-file schema: which tables and keys a scene has
//! (`[render]`, `[camera]`, `[[light]]`, `[material.NAME]`, `[[object]]`),
//! what each means and its default, read into a core [`Scene`]. Meshes
//! come from OBJ files, textures from image files, dispersion tables from
//! CSV files, placed glTF files through the glTF importer.

use super::names::{
    parse_bands, parse_estimator, parse_photon_sequence, parse_radius_mode, parse_tone_map, parse_view_paths,
    parse_wavelengths, parse_white_point,
};
use super::reader::{LOCAL_FRAME_RADIUS, Reader, Result, Table, join};
use crate::environment_file;
use crate::gltf_scene;
use crate::ior_table;
use crate::obj;
use crate::texture_file;
use glam::DVec3;
use glam::{Vec2, Vec4};
use prismatic_core::model::bands::BandSpec;
use prismatic_core::model::color::ToneMap;
use prismatic_core::model::dispersion::{Dispersion, Glass};
use prismatic_core::model::metalness::{Metalness, SpecularLayer};
use prismatic_core::model::metals::{MetalColor, NamedMetal};
use prismatic_core::model::scene::{
    Attenuation, Camera, Checker, EnvironmentMap, Estimator, FilmMap, Filter, Light, Material, MaterialKind, NormalMap,
    Object, PhotonSequence, RadiusMode, RenderSettings, Sampler, Shape, SpecularMap, Texture, ThinFilm, ViewPaths,
    WavelengthSampling, WhitePoint, Wrap, default_ambient,
};
use prismatic_core::model::spectrum::Spectrum;
use prismatic_core::{Scene, Vec3};
use std::ops::Range;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

impl Reader<'_> {
    pub fn scene(&mut self, root: &DeTable<'_>, span: Range<usize>) -> Result<Scene> {
        let root = Table { key: String::new(), span, entries: root };
        self.check_keys(&root, &["render", "camera", "light", "material", "object"])?;
        let render = match self.get(&root, "render") {
            Some(v) => {
                let t = self.table("render", v)?;
                self.render(&t)?
            }
            None => RenderSettings::default(),
        };
        let camera = {
            let v = self.required(&root, "camera")?;
            let t = self.table("camera", v)?;
            if let Some(position) = self.get(&t, "position") {
                let at = self.dvec3("camera.position", position)?;
                if at.abs().max_element() > LOCAL_FRAME_RADIUS {
                    self.origin = at;
                }
            }
            self.camera(&t)?
        };
        let lights = match self.get(&root, "light") {
            Some(v) => self
                .array("light", v)?
                .iter()
                .enumerate()
                .map(|(i, l)| {
                    let t = self.table(&format!("light[{i}]"), l)?;
                    self.light(&t)
                })
                .collect::<Result<Vec<_>>>()?,
            None => Vec::new(),
        };
        let mut materials = Vec::new();
        if let Some(v) = self.get(&root, "material") {
            let t = self.table("material", v)?;
            for (name, m) in t.entries.iter() {
                let key = format!("material.{}", name.get_ref());
                let mt = self.table(&key, m)?;
                materials.push(Material {
                    name: name.get_ref().to_string(),
                    kind: self.material(&mt)?,
                    normal_map: self.normal_map(&mt)?,
                    roughness_map: self.roughness_map(&mt)?,
                    film_map: self.film_map(&mt)?,
                    specular_map: self.specular_map(&mt)?,
                });
            }
        }
        let mut objects = Vec::new();
        if let Some(v) = self.get(&root, "object") {
            for (i, o) in self.array("object", v)?.iter().enumerate() {
                let t = self.table(&format!("object[{i}]"), o)?;
                if self.get(&t, "shape").is_some_and(|s| s.get_ref().as_str() == Some("gltf")) {
                    self.gltf_objects(&t, &mut materials, &mut objects)?;
                } else {
                    objects.push(self.object(&t, &materials)?);
                }
            }
        }
        Ok(Scene { render, camera, lights, materials, objects })
    }

    fn render(&mut self, t: &Table<'_, '_>) -> Result<RenderSettings> {
        self.check_keys(
            t,
            &[
                "width",
                "height",
                "photons",
                "indirect_photons",
                "radius",
                "radius_mode",
                "bands",
                "estimator",
                "light_tracing",
                "wavelengths",
                "photon_sequence",
                "view_paths",
                "seed",
                "max_depth",
                "ambient",
                "exposure",
                "white_point",
                "background",
                "tone_map",
                "auto_exposure",
                "projection_maps",
                "passes",
                "alpha",
                "neighbours",
                "environment_lights",
                "area_lights",
            ],
        )?;
        let d = RenderSettings::default();
        let u32_max = u64::from(u32::MAX);
        let indirect_photons =
            self.opt(t, "indirect_photons", |p, k, v| p.uint(k, v, u32_max))?.map_or(d.indirect_photons, |x| x as u32);
        Ok(RenderSettings {
            width: self.opt(t, "width", |p, k, v| p.uint(k, v, u32_max))?.map_or(d.width, |x| x as u32),
            height: self.opt(t, "height", |p, k, v| p.uint(k, v, u32_max))?.map_or(d.height, |x| x as u32),
            photons: self.opt(t, "photons", |p, k, v| p.uint(k, v, u32_max))?.map_or(d.photons, |x| x as u32),
            indirect_photons,
            radius: self.opt(t, "radius", Self::float)?.unwrap_or(d.radius),
            radius_mode: self.opt(t, "radius_mode", Self::radius_mode)?.unwrap_or(d.radius_mode),
            bands: self.opt(t, "bands", Self::bands)?.unwrap_or(d.bands),
            estimator: self.opt(t, "estimator", Self::estimator)?.unwrap_or(d.estimator),
            light_tracing: self.opt(t, "light_tracing", Self::boolean)?.unwrap_or(d.light_tracing),
            wavelengths: self.opt(t, "wavelengths", Self::wavelengths)?.unwrap_or(d.wavelengths),
            photon_sequence: self.opt(t, "photon_sequence", Self::photon_sequence)?.unwrap_or(d.photon_sequence),
            view_paths: self.opt(t, "view_paths", Self::view_paths)?.unwrap_or(d.view_paths),
            seed: self.opt(t, "seed", |p, k, v| p.uint(k, v, u32_max))?.map_or(d.seed, |x| x as u32),
            max_depth: self.opt(t, "max_depth", |p, k, v| p.uint(k, v, u32_max))?.map_or(d.max_depth, |x| x as u32),
            ambient: self.opt(t, "ambient", Self::float)?.unwrap_or(default_ambient(indirect_photons)),
            exposure: self.opt(t, "exposure", Self::float)?.unwrap_or(d.exposure),
            white_point: self.opt(t, "white_point", Self::white_point)?.unwrap_or(d.white_point),
            background: self.opt(t, "background", Self::vec3)?.unwrap_or(d.background),
            tone_map: self.opt(t, "tone_map", Self::tone_map)?.unwrap_or(d.tone_map),
            auto_exposure: self.opt(t, "auto_exposure", Self::boolean)?.unwrap_or(d.auto_exposure),
            projection_maps: self.opt(t, "projection_maps", Self::boolean)?.unwrap_or(d.projection_maps),
            passes: self.opt(t, "passes", |p, k, v| p.uint(k, v, u32_max))?.map_or(d.passes, |x| x as u32),
            alpha: self.opt(t, "alpha", Self::float)?.unwrap_or(d.alpha),
            neighbours: self.opt(t, "neighbours", |p, k, v| p.uint(k, v, u32_max))?.map_or(d.neighbours, |x| x as u32),
            environment_lights: self
                .opt(t, "environment_lights", |p, k, v| p.uint(k, v, u32_max))?
                .map_or(d.environment_lights, |x| x as u32),
            area_lights: self
                .opt(t, "area_lights", |p, k, v| p.uint(k, v, u32_max))?
                .map_or(d.area_lights, |x| x as u32),
        })
    }

    fn bands(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<BandSpec> {
        match v.get_ref() {
            DeValue::String(s) => parse_bands(s).map_err(|reason| self.err(key, &v.span(), reason)),
            DeValue::Integer(_) => {
                let n = self.uint(key, v, u64::from(u16::MAX))?;
                Ok(BandSpec::Physical(n as u16))
            }
            other => Err(self.err(
                key,
                &v.span(),
                format!("must be \"paper3\", \"paper7\" or a number of bands, got {}", other.type_str()),
            )),
        }
    }

    fn tone_map(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<ToneMap> {
        parse_tone_map(self.string(key, v)?).map_err(|reason| self.err(key, &v.span(), reason))
    }

    fn estimator(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<Estimator> {
        parse_estimator(self.string(key, v)?).map_err(|reason| self.err(key, &v.span(), reason))
    }

    fn wavelengths(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<WavelengthSampling> {
        parse_wavelengths(self.string(key, v)?).map_err(|reason| self.err(key, &v.span(), reason))
    }

    fn photon_sequence(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<PhotonSequence> {
        parse_photon_sequence(self.string(key, v)?).map_err(|reason| self.err(key, &v.span(), reason))
    }

    fn view_paths(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<ViewPaths> {
        parse_view_paths(self.string(key, v)?).map_err(|reason| self.err(key, &v.span(), reason))
    }

    fn white_point(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<WhitePoint> {
        parse_white_point(self.string(key, v)?).map_err(|reason| self.err(key, &v.span(), reason))
    }

    fn radius_mode(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<RadiusMode> {
        parse_radius_mode(self.string(key, v)?).map_err(|reason| self.err(key, &v.span(), reason))
    }

    fn camera(&mut self, t: &Table<'_, '_>) -> Result<Camera> {
        self.check_keys(t, &["position", "look_at", "up", "fov_deg"])?;
        Ok(Camera {
            position: self.req(t, "position", Self::point)?,
            look_at: self.req(t, "look_at", Self::point)?,
            up: self.opt(t, "up", Self::vec3)?.unwrap_or(Vec3::Y),
            fov_deg: self.opt(t, "fov_deg", Self::float)?.unwrap_or(45.0),
        })
    }

    fn light(&mut self, t: &Table<'_, '_>) -> Result<Light> {
        let kind = self.req(t, "kind", |p, k, v| p.string(k, v).map(str::to_string))?;
        Ok(match kind.as_str() {
            "spot" => {
                self.check_keys(
                    t,
                    &["kind", "position", "direction", "cone_deg", "inner_cone_deg", "power", "spectrum", "range"],
                )?;
                let cone_deg = self.req(t, "cone_deg", Self::float)?;
                Light::Spot {
                    position: self.req(t, "position", Self::point)?,
                    direction: self.req(t, "direction", Self::vec3)?,
                    cone_deg,
                    inner_cone_deg: self.opt(t, "inner_cone_deg", Self::float)?.unwrap_or(cone_deg),
                    power: self.req(t, "power", Self::float)?,
                    spectrum: self.opt(t, "spectrum", Self::spectrum)?.unwrap_or_default(),
                    range: self.opt(t, "range", Self::float)?,
                }
            }
            "point" => {
                self.check_keys(t, &["kind", "position", "power", "spectrum", "range"])?;
                Light::Point {
                    position: self.req(t, "position", Self::point)?,
                    power: self.req(t, "power", Self::float)?,
                    spectrum: self.opt(t, "spectrum", Self::spectrum)?.unwrap_or_default(),
                    range: self.opt(t, "range", Self::float)?,
                }
            }
            "beam" => {
                self.check_keys(t, &["kind", "position", "direction", "radius", "power", "spectrum"])?;
                Light::Beam {
                    position: self.req(t, "position", Self::point)?,
                    direction: self.req(t, "direction", Self::vec3)?,
                    radius: self.req(t, "radius", Self::float)?,
                    power: self.req(t, "power", Self::float)?,
                    spectrum: self.opt(t, "spectrum", Self::spectrum)?.unwrap_or_default(),
                }
            }
            "environment" => {
                self.check_keys(t, &["kind", "map", "color", "strength", "rotation_deg", "spectrum"])?;
                let map = match (self.get(t, "map"), self.get(t, "color")) {
                    (Some(_), Some(v)) => {
                        return Err(self.err(&join(&t.key, "color"), &v.span(), "give a map or a colour, not both"));
                    }
                    (Some(v), None) => {
                        let key = join(&t.key, "map");
                        let name = self.string(&key, v)?;
                        match environment_file::built_in(name) {
                            Some(map) => map,
                            None => {
                                environment_file::load(&self.beside(name)).map_err(|e| self.err(&key, &v.span(), e))?
                            }
                        }
                    }
                    (None, Some(_)) => EnvironmentMap::constant(self.req(t, "color", Self::vec3)?),
                    (None, None) => EnvironmentMap::studio(),
                };
                Light::Environment {
                    map,
                    strength: self.opt(t, "strength", Self::float)?.unwrap_or(1.0),
                    rotation_deg: self.opt(t, "rotation_deg", Self::float)?.unwrap_or(0.0),
                    spectrum: self.opt(t, "spectrum", Self::spectrum)?.unwrap_or_default(),
                }
            }
            "sun" => {
                self.check_keys(t, &["kind", "direction", "irradiance", "spectrum"])?;
                Light::Sun {
                    direction: self.req(t, "direction", Self::vec3)?,
                    irradiance: self.req(t, "irradiance", Self::float)?,
                    spectrum: self.opt(t, "spectrum", Self::spectrum)?.unwrap_or_default(),
                    mean_toward: None,
                }
            }
            other => {
                let v = self.required(t, "kind")?;
                return Err(self.err(
                    &join(&t.key, "kind"),
                    &v.span(),
                    format!("unknown light kind \"{other}\"; expected spot, point, beam, sun or environment"),
                ));
            }
        })
    }

    fn material(&mut self, t: &Table<'_, '_>) -> Result<MaterialKind> {
        let kind = self.req(t, "kind", |p, k, v| p.string(k, v).map(str::to_string))?;
        Ok(match kind.as_str() {
            "diffuse" => {
                self.check_keys(
                    t,
                    &[
                        "kind",
                        "albedo",
                        "checker",
                        "texture",
                        "texture_filter",
                        "texture_wrap",
                        "emission",
                        "specular",
                        "specular_ior",
                        "specular_color",
                        "specular_map",
                        "specular_color_map",
                        "roughness",
                        "film_thickness_nm",
                        "film_ior",
                        "film_factor",
                        "normal_map",
                        "normal_scale",
                    ],
                )?;
                let layer = self.specular_layer(t)?;
                for key in ["roughness", "film_thickness_nm", "film_ior", "film_factor"] {
                    if let Some(v) = self.get(t, key).filter(|_| layer.is_none()) {
                        let reason = "needs a specular layer on the diffuse surface (give specular)";
                        return Err(self.err(&join(&t.key, key), &v.span(), reason));
                    }
                }
                let checker = match self.get(t, "checker") {
                    Some(v) => {
                        let ct = self.table(&join(&t.key, "checker"), v)?;
                        self.check_keys(&ct, &["size", "albedo"])?;
                        let size = self.req(&ct, "size", Self::float)?;
                        // The pattern stays where it is in the world: shift it by
                        // the local frame's origin modulo two squares (one period).
                        let period = 2.0 * f64::from(size);
                        let offset =
                            if period > 0.0 { self.origin.rem_euclid(DVec3::splat(period)) } else { DVec3::ZERO };
                        Some(Checker { size, albedo: self.req(&ct, "albedo", Self::vec3)?, offset: offset.as_vec3() })
                    }
                    None => None,
                };
                let texture = self.texture(t)?;
                // An image shows as it is unless an albedo scales it.
                let default_albedo = if texture.is_some() { Vec3::ONE } else { Vec3::splat(0.8) };
                let albedo = self.opt(t, "albedo", Self::vec3)?.unwrap_or(default_albedo);
                match layer {
                    // Under a specular layer: glTF's non-metal, a metal of no metalness.
                    Some(layer) => {
                        for key in ["checker", "emission"] {
                            if let Some(v) = self.get(t, key) {
                                let reason =
                                    "cannot be combined with a specular layer (a diffuse surface without specular can)";
                                return Err(self.err(&join(&t.key, key), &v.span(), reason));
                            }
                        }
                        MaterialKind::Metal {
                            color: MetalColor::Rgb(albedo),
                            roughness: self.opt(t, "roughness", Self::float)?.unwrap_or(0.0),
                            texture,
                            film: self.film(t)?,
                            metalness: Metalness::layered(layer),
                        }
                    }
                    None => MaterialKind::Diffuse {
                        albedo,
                        checker,
                        texture,
                        emission: self.opt(t, "emission", Self::vec3)?.unwrap_or(Vec3::ZERO),
                    },
                }
            }
            "dielectric" => {
                self.check_keys(
                    t,
                    &[
                        "kind",
                        "ior",
                        "outside_ior",
                        "attenuation_color",
                        "attenuation_distance",
                        "thin",
                        "film_thickness_nm",
                        "film_ior",
                        "film_factor",
                        "film_thickness_map",
                        "film_min_nm",
                        "film_factor_map",
                        "roughness",
                        "roughness_map",
                        "normal_map",
                        "normal_scale",
                    ],
                )?;
                let dispersion = self.req(t, "ior", |p, k, v| p.ior(k, v))?;
                let outside = self.opt(t, "outside_ior", |p, k, v| p.ior(k, v))?.unwrap_or(Dispersion::Constant(1.0));
                // Coloured glass names both halves of Beer–Lambert's law, as glTF does.
                let coloured = ["attenuation_color", "attenuation_distance"].iter().any(|k| self.get(t, k).is_some());
                let attenuation = if coloured {
                    Some(Attenuation {
                        color: self.req(t, "attenuation_color", Self::vec3)?,
                        distance: self.req(t, "attenuation_distance", Self::float)?,
                    })
                } else {
                    None
                };
                let thin = self.opt(t, "thin", Self::boolean)?.unwrap_or(false);
                let film = self.film(t)?;
                let roughness = self.opt(t, "roughness", Self::float)?.unwrap_or(0.0);
                MaterialKind::Dielectric { dispersion, outside, attenuation, thin, film, roughness }
            }
            "mirror" => {
                self.check_keys(t, &["kind", "normal_map", "normal_scale"])?;
                MaterialKind::Mirror
            }
            "metal" => {
                self.check_keys(
                    t,
                    &[
                        "kind",
                        "color",
                        "roughness",
                        "roughness_map",
                        "texture",
                        "texture_filter",
                        "texture_wrap",
                        "film_thickness_nm",
                        "film_ior",
                        "film_factor",
                        "film_thickness_map",
                        "film_min_nm",
                        "film_factor_map",
                        "metalness",
                        "metalness_from_map",
                        "specular",
                        "specular_ior",
                        "specular_color",
                        "specular_map",
                        "specular_color_map",
                        "normal_map",
                        "normal_scale",
                    ],
                )?;
                // A texture is the colour unless a colour scales it, as on a diffuse surface.
                let texture = self.texture(t)?;
                let color = match texture {
                    Some(_) => {
                        self.opt(t, "color", |p, k, v| p.metal_color(k, v))?.unwrap_or(MetalColor::Rgb(Vec3::ONE))
                    }
                    None => self.req(t, "color", |p, k, v| p.metal_color(k, v))?,
                };
                let roughness = self.opt(t, "roughness", Self::float)?.unwrap_or(0.0);
                let metalness = Metalness {
                    factor: self.opt(t, "metalness", Self::float)?.unwrap_or(1.0),
                    mapped: self.opt(t, "metalness_from_map", Self::boolean)?.unwrap_or(false),
                    layer: None,
                };
                let metalness = metalness.with_layer(self.specular_layer(t)?);
                MaterialKind::Metal { color, roughness, texture, film: self.film(t)?, metalness }
            }
            other => {
                let v = self.required(t, "kind")?;
                return Err(self.err(
                    &join(&t.key, "kind"),
                    &v.span(),
                    format!("unknown material kind \"{other}\"; expected diffuse, dielectric, mirror or metal"),
                ));
            }
        })
    }

    /// A metal's `color`: its reflectance at normal incidence as `[r, g,
    /// b]`, or the name of a measured metal ([`NamedMetal`]).
    fn metal_color(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<MetalColor> {
        let DeValue::String(name) = v.get_ref() else { return Self::vec3(self, key, v).map(MetalColor::Rgb) };
        NamedMetal::from_name(name).map(MetalColor::Measured).ok_or_else(|| {
            let names: Vec<&str> = NamedMetal::ALL.iter().map(|m| m.name()).collect();
            self.err(key, &v.span(), format!("unknown metal \"{name}\"; named metals are {}", names.join(", ")))
        })
    }

    /// The specular layer of a diffuse surface or a blended metal's base,
    /// as glTF's `KHR_materials_specular` and `KHR_materials_ior` give it:
    /// `specular` (its factor, 1 by default), `specular_ior` (1.5) and
    /// `specular_color` (white); `None` without any of them.
    fn specular_layer(&self, t: &Table<'_, '_>) -> Result<Option<SpecularLayer>> {
        if !["specular", "specular_ior", "specular_color"].iter().any(|k| self.get(t, k).is_some()) {
            return Ok(None);
        }
        let weight = self.opt(t, "specular", Self::float)?.unwrap_or(1.0);
        if let Some(v) = self.get(t, "specular").filter(|_| !(0.0..=1.0).contains(&weight)) {
            return Err(self.err(
                &join(&t.key, "specular"),
                &v.span(),
                format!("must be between 0 and 1, got {weight}"),
            ));
        }
        let ior = self.opt(t, "specular_ior", Self::float)?.unwrap_or(1.5);
        if let Some(v) = self.get(t, "specular_ior").filter(|_| !(ior.is_finite() && ior >= 1.0)) {
            return Err(self.err(&join(&t.key, "specular_ior"), &v.span(), format!("must be at least 1, got {ior}")));
        }
        Ok(SpecularLayer::gltf(ior, weight, self.opt(t, "specular_color", Self::vec3)?.unwrap_or(Vec3::ONE)))
    }

    /// A specular layer's maps (glTF's `KHR_materials_specular` textures):
    /// `specular_map`, whose red channel, read as linear values, scales
    /// `specular` (a grey image: its grey), and `specular_color_map`, whose
    /// colour (sRGB) scales `specular_color`; both images beside the scene.
    /// A map needs a layer, which the scene's check asks for.
    fn specular_map(&self, t: &Table<'_, '_>) -> Result<Option<SpecularMap>> {
        let (weight, color) = (self.image(t, "specular_map")?, self.image(t, "specular_color_map")?);
        if weight.is_none() && color.is_none() {
            return Ok(None);
        }
        let ior = self.opt(t, "specular_ior", Self::float)?.unwrap_or(1.5);
        let tint = self.opt(t, "specular_color", Self::vec3)?.unwrap_or(Vec3::ONE);
        Ok(Some(SpecularMap { weight, color, color_f0: SpecularLayer::unclipped_f0(ior, tint) }))
    }

    /// A dielectric's or metal's film: its `film_thickness_nm`, its
    /// `film_ior` (glTF's iridescenceIor by default) and its `film_factor`
    /// (glTF's iridescenceFactor, 1 by default).
    fn film(&self, t: &Table<'_, '_>) -> Result<Option<ThinFilm>> {
        match self.opt(t, "film_thickness_nm", Self::float)? {
            Some(thickness_nm) => Ok(Some(ThinFilm {
                ior: self.opt(t, "film_ior", Self::float)?.unwrap_or(1.3),
                thickness_nm,
                factor: self.opt(t, "film_factor", Self::float)?.unwrap_or(1.0),
            })),
            None => match ["film_ior", "film_factor"].into_iter().find_map(|k| Some((k, self.get(t, k)?))) {
                Some((key, v)) => {
                    let reason = "a film needs film_thickness_nm (its thickness in nanometres)";
                    Err(self.err(&join(&t.key, key), &v.span(), reason))
                }
                None => Ok(None),
            },
        }
    }

    /// A diffuse material's or metal's `texture` (an image file beside the scene) with
    /// its `texture_filter` and `texture_wrap`.
    fn texture(&self, t: &Table<'_, '_>) -> Result<Option<Texture>> {
        let filter = self.opt(t, "texture_filter", |p, k, v| match p.string(k, v)? {
            "linear" => Ok(Filter::Linear),
            "nearest" => Ok(Filter::Nearest),
            other => Err(p.err(k, &v.span(), format!("unknown filter \"{other}\"; expected linear or nearest"))),
        })?;
        let wrap = self.opt(t, "texture_wrap", |p, k, v| match p.string(k, v)? {
            "repeat" => Ok(Wrap::Repeat),
            "clamp_to_edge" => Ok(Wrap::ClampToEdge),
            "mirrored_repeat" => Ok(Wrap::MirroredRepeat),
            other => Err(p.err(
                k,
                &v.span(),
                format!("unknown wrap \"{other}\"; expected repeat, clamp_to_edge or mirrored_repeat"),
            )),
        })?;
        let Some(v) = self.get(t, "texture") else {
            if let Some(k) = ["texture_filter", "texture_wrap"].into_iter().find(|k| self.get(t, k).is_some()) {
                let v = self.required(t, k)?;
                return Err(self.err(&join(&t.key, k), &v.span(), "applies to a texture; the material names none"));
            }
            return Ok(None);
        };
        let key = join(&t.key, "texture");
        let path = self.beside(self.string(&key, v)?);
        let wrap = wrap.unwrap_or_default();
        let sampler = Sampler { filter: filter.unwrap_or_default(), wrap_u: wrap, wrap_v: wrap };
        texture_file::load(&path, sampler).map(Some).map_err(|e| self.err(&key, &v.span(), e))
    }

    /// A material's `normal_map` (an image file beside the scene, its
    /// channels linear, read bilinearly and repeated) with its
    /// `normal_scale` (default 1).
    fn normal_map(&self, t: &Table<'_, '_>) -> Result<Option<NormalMap>> {
        let scale = self.opt(t, "normal_scale", Self::float)?;
        let Some(v) = self.get(t, "normal_map") else {
            if let Some(v) = self.get(t, "normal_scale") {
                let reason = "applies to a normal map; the material names none";
                return Err(self.err(&join(&t.key, "normal_scale"), &v.span(), reason));
            }
            return Ok(None);
        };
        let key = join(&t.key, "normal_map");
        let path = self.beside(self.string(&key, v)?);
        let texture = texture_file::load(&path, Sampler::default()).map_err(|e| self.err(&key, &v.span(), e))?;
        Ok(Some(NormalMap { texture, scale: scale.unwrap_or(1.0) }))
    }

    /// A metal's or dielectric's `roughness_map`: an image file beside the
    /// scene whose green channel, read as linear values, scales its
    /// `roughness` texel by texel (a grey image: its grey).
    fn roughness_map(&self, t: &Table<'_, '_>) -> Result<Option<Texture>> {
        self.image(t, "roughness_map")
    }

    /// An image file beside the scene at `key` of `t`, its texels as they
    /// are stored (a map reads them as linear values, a colour map as sRGB).
    fn image(&self, t: &Table<'_, '_>, key: &str) -> Result<Option<Texture>> {
        let Some(v) = self.get(t, key) else { return Ok(None) };
        let key = join(&t.key, key);
        let path = self.beside(self.string(&key, v)?);
        texture_file::load(&path, Sampler::default()).map(Some).map_err(|e| self.err(&key, &v.span(), e))
    }

    /// A film's maps (glTF's iridescence textures): `film_thickness_map`,
    /// whose green channel g makes the film `film_min_nm` (default 0) plus
    /// g times the rest of `film_thickness_nm` thick, and
    /// `film_factor_map`, whose red channel scales `film_factor`; both
    /// images beside the scene, read as linear values.
    fn film_map(&self, t: &Table<'_, '_>) -> Result<Option<FilmMap>> {
        let (thickness, factor) = (self.image(t, "film_thickness_map")?, self.image(t, "film_factor_map")?);
        let min_nm = self.opt(t, "film_min_nm", Self::float)?;
        if let (None, Some(v)) = (&thickness, self.get(t, "film_min_nm")) {
            let reason = "the thinnest a film_thickness_map makes the film; there is no film_thickness_map";
            return Err(self.err(&join(&t.key, "film_min_nm"), &v.span(), reason));
        }
        if thickness.is_none() && factor.is_none() {
            return Ok(None);
        }
        Ok(Some(FilmMap { thickness, min_nm: min_nm.unwrap_or(0.0), factor }))
    }

    /// A light's `spectrum`: a name (`"D65"`, `"mercury"`, …), `{ blackbody = K }`,
    /// `{ rgb = [r, g, b] }` (a colour's smooth spectrum) or `{ nm = [..], power = [..] }`.
    fn spectrum(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<Spectrum> {
        let forms = format!(
            "a name ({}), {{ blackbody = KELVIN }}, {{ rgb = [R, G, B] }} or {{ nm = [..], power = [..] }}",
            Spectrum::names()
        );
        match v.get_ref() {
            DeValue::String(name) => Spectrum::from_name(name)
                .ok_or_else(|| self.err(key, &v.span(), format!("unknown spectrum \"{name}\"; expected {forms}"))),
            DeValue::Table(_) => {
                let t = self.table(key, v)?;
                let has = |name: &str| t.entries.iter().any(|(k, _)| k.get_ref() == name);
                let (blackbody, rgb) = (has("blackbody"), has("rgb"));
                let allowed: &[&str] = match (blackbody, rgb) {
                    (true, _) => &["blackbody"],
                    (_, true) => &["rgb"],
                    _ => &["nm", "power"],
                };
                if let Some((k, _)) = t.entries.iter().find(|(k, _)| !allowed.contains(&k.get_ref().as_ref())) {
                    let reason = format!("unknown key; expected {}", allowed.join(" and "));
                    return Err(self.err(&join(key, k.get_ref()), &k.span(), reason));
                }
                if blackbody {
                    return Ok(Spectrum::Blackbody { kelvin: self.req(&t, "blackbody", Self::float)? });
                }
                if rgb {
                    let colour = self.req(&t, "rgb", Self::vec3)?;
                    if !(colour.min_element() >= 0.0 && colour.max_element() > 0.0) {
                        let v = self.required(&t, "rgb")?;
                        let reason = "must be a colour with no negative channel and one above 0";
                        return Err(self.err(&join(key, "rgb"), &v.span(), reason));
                    }
                    return Ok(Spectrum::from_rgb(colour.to_array()).0);
                }
                let floats = |p: &Self, k: &str, v: &Spanned<DeValue<'_>>| -> Result<Vec<f32>> {
                    Ok(p.floats(k, v)?.into_iter().map(|x| x as f32).collect())
                };
                Ok(Spectrum::Tabulated { nm: self.req(&t, "nm", floats)?, power: self.req(&t, "power", floats)? })
            }
            other => Err(self.err(key, &v.span(), format!("must be {forms}, got {}", other.type_str()))),
        }
    }

    fn ior(&self, key: &str, v: &Spanned<DeValue<'_>>) -> Result<Dispersion> {
        match v.get_ref() {
            DeValue::Float(_) | DeValue::Integer(_) => Ok(Dispersion::Constant(self.float(key, v)?)),
            DeValue::String(name) => Glass::from_name(name).map(Glass::dispersion).ok_or_else(|| {
                let names: Vec<&str> = Glass::ALL.iter().map(|g| g.name()).collect();
                self.err(key, &v.span(), format!("unknown glass \"{name}\"; named glasses are {}", names.join(", ")))
            }),
            DeValue::Table(t) => {
                let models = "cauchy = [A, B], sellmeier = { b = [..], c = [..] }, abbe = [nd, vd], table = \"file.csv\" \
                              or bands = [n1, ..]";
                let mut entries = t.iter();
                let (Some((model, value)), None) = (entries.next(), entries.next()) else {
                    return Err(self.err(key, &v.span(), format!("needs exactly one model: {models}")));
                };
                let mkey = join(key, model.get_ref());
                let pair = |p: &Self| -> Result<(f32, f32)> {
                    let x = p.floats(&mkey, value)?;
                    match x[..] {
                        [a, b] => Ok((a as f32, b as f32)),
                        _ => Err(p.err(
                            &mkey,
                            &value.span(),
                            format!("must be an array of two numbers, got {}", x.len()),
                        )),
                    }
                };
                match model.get_ref().as_ref() {
                    "cauchy" => pair(self).map(|(a, b)| Dispersion::Cauchy { a, b }),
                    "abbe" => pair(self).map(|(nd, vd)| Dispersion::Abbe { nd, vd }),
                    "table" => {
                        let rel = self.string(&mkey, value)?;
                        let path = self.beside(rel);
                        let (lambda_nm, n) = ior_table::load(&path).map_err(|e| self.err(&mkey, &value.span(), e))?;
                        Ok(Dispersion::Table { lambda_nm, n })
                    }
                    "bands" => {
                        Ok(Dispersion::PerBand(self.floats(&mkey, value)?.into_iter().map(|x| x as f32).collect()))
                    }
                    "sellmeier" => {
                        let st = self.table(&mkey, value)?;
                        for (k, _) in st.entries.iter() {
                            if !["b", "c"].contains(&k.get_ref().as_ref()) {
                                return Err(self.err(
                                    &join(&mkey, k.get_ref()),
                                    &k.span(),
                                    "unknown key; expected b or c",
                                ));
                            }
                        }
                        Ok(Dispersion::Sellmeier {
                            b: self.req(&st, "b", Self::floats)?,
                            c: self.req(&st, "c", Self::floats)?,
                        })
                    }
                    other => Err(self.err(
                        &mkey,
                        &model.span(),
                        format!("unknown dispersion model \"{other}\"; expected {models}"),
                    )),
                }
            }
            other => Err(self.err(
                key,
                &v.span(),
                format!("must be a number, a glass name or a model table, got {}", other.type_str()),
            )),
        }
    }

    fn object(&mut self, t: &Table<'_, '_>, materials: &[Material]) -> Result<Object> {
        let shape_name = self.req(t, "shape", |p, k, v| p.string(k, v).map(str::to_string))?;
        let shape = match shape_name.as_str() {
            "sphere" => {
                self.check_keys(t, &["shape", "material", "center", "radius"])?;
                Shape::Sphere {
                    center: self.req(t, "center", Self::point)?,
                    radius: self.req(t, "radius", Self::float)?,
                }
            }
            "plane" => {
                self.check_keys(t, &["shape", "material", "point", "normal"])?;
                Shape::Plane { point: self.req(t, "point", Self::point)?, normal: self.req(t, "normal", Self::vec3)? }
            }
            "disk" => {
                self.check_keys(t, &["shape", "material", "center", "normal", "radius", "inner_radius"])?;
                Shape::Disk {
                    center: self.req(t, "center", Self::point)?,
                    normal: self.req(t, "normal", Self::vec3)?,
                    radius: self.req(t, "radius", Self::float)?,
                    inner_radius: self.opt(t, "inner_radius", Self::float)?.unwrap_or(0.0),
                }
            }
            "prism" => {
                self.check_keys(t, &["shape", "material", "vertices", "extrude"])?;
                let key = join(&t.key, "vertices");
                let v = self.required(t, "vertices")?;
                let corners = self.array(&key, v)?;
                if corners.len() != 3 {
                    return Err(self.err(&key, &v.span(), format!("must list three corners, got {}", corners.len())));
                }
                let mut vertices = [Vec3::ZERO; 3];
                for (i, c) in corners.iter().enumerate() {
                    vertices[i] = self.point(&format!("{key}[{i}]"), c)?;
                }
                Shape::Prism { vertices, extrude: self.req(t, "extrude", Self::vec3)? }
            }
            "mesh" => {
                let keys = ["shape", "material", "positions", "triangles", "uvs", "normals", "tangents", "path"];
                self.check_keys(t, &keys)?;
                self.mesh(t)?
            }
            other => {
                let v = self.required(t, "shape")?;
                return Err(self.err(
                    &join(&t.key, "shape"),
                    &v.span(),
                    format!("unknown shape \"{other}\"; expected sphere, plane, disk, prism, mesh or gltf"),
                ));
            }
        };
        let key = join(&t.key, "material");
        let v = self.required(t, "material")?;
        let name = self.string(&key, v)?;
        let material = materials.iter().position(|m| m.name == name).ok_or_else(|| {
            let known: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
            self.err(
                &key,
                &v.span(),
                format!(
                    "unknown material \"{name}\"; defined: {}",
                    if known.is_empty() { "none".into() } else { known.join(", ") }
                ),
            )
        })?;
        Ok(Object { shape, material })
    }

    /// `shape = "gltf"`: the meshes of a glTF file (with their materials,
    /// named `FILE/MATERIAL`), scaled by `scale` and moved by `translate`.
    /// The file's lights and camera are left out: the scene has its own.
    fn gltf_objects(
        &mut self,
        t: &Table<'_, '_>,
        materials: &mut Vec<Material>,
        objects: &mut Vec<Object>,
    ) -> Result<()> {
        self.check_keys(t, &["shape", "path", "translate", "scale"])?;
        let key = join(&t.key, "path");
        let v = self.required(t, "path")?;
        let rel = self.string(&key, v)?;
        let path = self.beside(rel);
        let model = gltf_scene::import(&path)
            .map_err(|e| self.err(&key, &v.span(), format!("{}: {}: {}", path.display(), e.path, e.reason)))?;
        let translate = self.opt(t, "translate", Self::dvec3)?.unwrap_or(DVec3::ZERO);
        let scale = self.opt(t, "scale", Self::float)?.map_or(1.0, f64::from);
        if !(scale.is_finite() && scale > 0.0) {
            let v = self.required(t, "scale")?;
            return Err(self.err(&join(&t.key, "scale"), &v.span(), format!("must be greater than 0, got {scale}")));
        }
        let stem = path.file_stem().map_or_else(|| rel.to_string(), |s| s.to_string_lossy().into_owned());
        let first = materials.len();
        materials.extend(model.materials.into_iter().map(|m| Material { name: format!("{stem}/{}", m.name), ..m }));
        for object in model.objects {
            let Shape::Mesh { positions, triangles, uvs, normals, tangents } = object.shape else { continue };
            let positions = positions
                .into_iter()
                .map(|p| {
                    let world = p.as_dvec3() * scale + translate;
                    self.local(world)
                        .ok_or_else(|| self.err(&key, &v.span(), format!("vertex {world} is out of range")))
                })
                .collect::<Result<Vec<_>>>()?;
            objects.push(Object {
                shape: Shape::Mesh { positions, triangles, uvs, normals, tangents },
                material: first + object.material,
            });
        }
        let left_out = model.warnings.into_iter().chain(
            (!model.lights.is_empty() || model.camera.is_some())
                .then(|| "its lights and camera are left out (the scene file has its own)".to_string()),
        );
        self.warnings.extend(left_out.map(|w| format!("{}: {w}", t.key)));
        Ok(())
    }

    fn mesh(&self, t: &Table<'_, '_>) -> Result<Shape> {
        if let Some(v) = self.get(t, "path") {
            let key = join(&t.key, "path");
            if ["positions", "triangles", "uvs", "normals", "tangents"].iter().any(|k| self.get(t, k).is_some()) {
                return Err(self.err(
                    &key,
                    &v.span(),
                    "give either path or positions + triangles (+ uvs, normals, tangents), not both",
                ));
            }
            let rel = self.string(&key, v)?;
            let path = self.beside(rel);
            let mesh = obj::load(&path).map_err(|e| self.err(&key, &v.span(), e))?;
            let positions = mesh
                .positions
                .into_iter()
                .map(|p| self.local(p).ok_or_else(|| self.err(&key, &v.span(), format!("vertex {p} is out of range"))))
                .collect::<Result<Vec<_>>>()?;
            return Ok(Shape::Mesh {
                positions,
                triangles: mesh.triangles,
                uvs: mesh.uvs,
                normals: mesh.normals,
                tangents: Vec::new(),
            });
        }
        let positions = {
            let key = join(&t.key, "positions");
            let v = self.required(t, "positions")?;
            self.array(&key, v)?
                .iter()
                .enumerate()
                .map(|(i, p)| self.point(&format!("{key}[{i}]"), p))
                .collect::<Result<Vec<_>>>()?
        };
        let key = join(&t.key, "triangles");
        let v = self.required(t, "triangles")?;
        let triangles = self
            .array(&key, v)?
            .iter()
            .enumerate()
            .map(|(i, tri)| {
                let k = format!("{key}[{i}]");
                let idx = self.array(&k, tri)?;
                if idx.len() != 3 {
                    return Err(self.err(&k, &tri.span(), format!("must be three vertex indices, got {}", idx.len())));
                }
                let mut out = [0u32; 3];
                for (j, x) in idx.iter().enumerate() {
                    out[j] = self.uint(&format!("{k}[{j}]"), x, u64::from(u32::MAX))? as u32;
                }
                Ok(out)
            })
            .collect::<Result<Vec<_>>>()?;
        let uvs = match self.get(t, "uvs") {
            Some(v) => {
                let key = join(&t.key, "uvs");
                self.array(&key, v)?
                    .iter()
                    .enumerate()
                    .map(|(i, uv)| {
                        let k = format!("{key}[{i}]");
                        match self.floats(&k, uv)?[..] {
                            [u, v] => Ok(Vec2::new(u as f32, v as f32)),
                            ref x => Err(self.err(&k, &uv.span(), format!("must be [u, v], got {} numbers", x.len()))),
                        }
                    })
                    .collect::<Result<Vec<_>>>()?
            }
            None => Vec::new(),
        };
        let normals = match self.get(t, "normals") {
            Some(v) => {
                let key = join(&t.key, "normals");
                let normals = self.array(&key, v)?.iter().enumerate();
                normals
                    .map(|(i, n)| Ok(self.dvec3(&format!("{key}[{i}]"), n)?.as_vec3()))
                    .collect::<Result<Vec<_>>>()?
            }
            None => Vec::new(),
        };
        let tangents = match self.get(t, "tangents") {
            Some(v) => {
                let key = join(&t.key, "tangents");
                self.array(&key, v)?
                    .iter()
                    .enumerate()
                    .map(|(i, tangent)| {
                        let k = format!("{key}[{i}]");
                        match self.floats(&k, tangent)?[..] {
                            [x, y, z, w] => Ok(Vec4::new(x as f32, y as f32, z as f32, w as f32)),
                            ref x => {
                                let reason =
                                    format!("must be [x, y, z, w] (w: ±1, the handedness), got {} numbers", x.len());
                                Err(self.err(&k, &tangent.span(), reason))
                            }
                        }
                    })
                    .collect::<Result<Vec<_>>>()?
            }
            None => Vec::new(),
        };
        Ok(Shape::Mesh { positions, triangles, uvs, normals, tangents })
    }
}
