//! Validation of the scene model: [`Scene::validate`] checks every value
//! and reports the first problem with the key it belongs to (for example
//! `object[2].radius`) and the reason, using the scene-file format's key
//! names so that a file loader can pass them straight through.

use crate::model::bands::{BandSpec, MAX_BANDS, VISIBLE_NM};
use crate::model::dispersion::{Dispersion, MAX_SELLMEIER_TERMS};
use crate::model::environment::MAX_ENVIRONMENT_SIDE;
use crate::model::metalness::Metalness;
use crate::model::metals::MetalColor;
use crate::model::scene::{
    Attenuation, FilmMap, Light, MAX_AREA_LIGHTS, MAX_DEPTH, MAX_ENVIRONMENT_LIGHTS, MAX_FILM_NM, MAX_IMAGE_SIDE,
    MAX_MESH_TRIANGLES, MAX_PHOTONS, MAX_TEXTURE_SIDE, Material, MaterialKind, Scene, SceneError, Shape, SpecularMap,
    Texture, ThinFilm,
};
use crate::model::spectrum::Spectrum;
use alloc::format;
use alloc::string::{String, ToString};
use glam::{Vec3, Vec4};

/// Collects checks for one key prefix.
struct Check<'a> {
    prefix: &'a str,
}

impl Check<'_> {
    fn key(&self, field: &str) -> String {
        if self.prefix.is_empty() { field.to_string() } else { format!("{}.{field}", self.prefix) }
    }

    fn err(&self, field: &str, reason: impl Into<String>) -> SceneError {
        SceneError::new(self.key(field), reason)
    }

    fn finite(&self, field: &str, x: f32) -> Result<(), SceneError> {
        if x.is_finite() { Ok(()) } else { Err(self.err(field, format!("must be a finite number, got {x}"))) }
    }

    fn positive(&self, field: &str, x: f32) -> Result<(), SceneError> {
        self.finite(field, x)?;
        if x > 0.0 { Ok(()) } else { Err(self.err(field, format!("must be greater than 0, got {x}"))) }
    }

    fn non_negative(&self, field: &str, x: f32) -> Result<(), SceneError> {
        self.finite(field, x)?;
        if x >= 0.0 { Ok(()) } else { Err(self.err(field, format!("must not be negative, got {x}"))) }
    }

    fn vector(&self, field: &str, v: Vec3) -> Result<(), SceneError> {
        if v.is_finite() {
            Ok(())
        } else {
            Err(self.err(field, format!("must have finite components, got [{}, {}, {}]", v.x, v.y, v.z)))
        }
    }

    fn direction(&self, field: &str, v: Vec3) -> Result<(), SceneError> {
        self.vector(field, v)?;
        if v.length_squared() > 1e-20 { Ok(()) } else { Err(self.err(field, "must not be a zero-length vector")) }
    }

    fn colour(&self, field: &str, v: Vec3) -> Result<(), SceneError> {
        self.vector(field, v)?;
        if v.min_element() >= 0.0 {
            Ok(())
        } else {
            Err(self.err(field, format!("must not be negative, got [{}, {}, {}]", v.x, v.y, v.z)))
        }
    }
}

impl Scene {
    /// Checks every value of the scene; the first problem is returned with its key.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.validate_since(None)
    }

    /// [`Scene::validate`] of a changed version of `previous`, a valid
    /// scene: a glass mesh that `previous` held as glass at the same index,
    /// unchanged, is not checked for closedness again (the costly check,
    /// tens of milliseconds at 10⁵ triangles).
    pub fn validate_since(&self, previous: Option<&Scene>) -> Result<(), SceneError> {
        self.validate_render()?;
        self.validate_camera()?;
        if self.lights.is_empty() && !self.objects.iter().any(|o| self.emits(o)) {
            return Err(SceneError::new("light", "the scene has no light (no [[light]] and no emissive mesh)"));
        }
        for (i, light) in self.lights.iter().enumerate() {
            let c = Check { prefix: &format!("light[{i}]") };
            validate_light(&c, light)?;
            validate_spectrum(&c, light.spectrum(), &self.render)?;
        }
        let mut environments = self.lights.iter().enumerate().filter(|(_, l)| matches!(l, Light::Environment { .. }));
        if let Some((i, _)) = environments.nth(1) {
            return Err(SceneError::new(
                format!("light[{i}]"),
                "a second environment: the scene has one sky (merge the maps into one)",
            ));
        }
        for m in &self.materials {
            validate_material(&Check { prefix: &format!("material.{}", m.name) }, m, self.render.bands)?;
        }
        for (i, object) in self.objects.iter().enumerate() {
            let c = Check { prefix: &format!("object[{i}]") };
            let Some(material) = self.materials.get(object.material) else {
                return Err(c.err("material", format!("refers to material #{} which does not exist", object.material)));
            };
            validate_shape(&c, &object.shape)?;
            if matches!(material.kind, MaterialKind::Dielectric { thin: false, .. }) && !object.shape.is_closed() {
                return Err(c.err(
                    "material",
                    format!(
                        "dielectric '{}' needs a closed shape (sphere, prism or mesh), not a {}",
                        material.name,
                        object.shape.name()
                    ),
                ));
            }
            if material.kind.emission() != Vec3::ZERO && !matches!(object.shape, Shape::Mesh { .. }) {
                return Err(c.err(
                    "material",
                    format!(
                        "'{}' emits light, which only a mesh can (its triangles are the area light); this is a {}",
                        material.name,
                        object.shape.name()
                    ),
                ));
            }
            let image = match &material.kind {
                MaterialKind::Diffuse { texture: Some(texture), .. }
                | MaterialKind::Metal { texture: Some(texture), .. } => Some(("texture", texture)),
                _ => material.normal_map.as_ref().map(|map| ("normal map", &map.texture)),
            }
            .or(material.roughness_map.as_ref().map(|t| ("roughness map", t)))
            .or(material
                .film_map
                .iter()
                .flat_map(|m| m.thickness.iter().chain(&m.factor))
                .next()
                .map(|t| ("film map", t)))
            .or(material
                .specular_map
                .iter()
                .flat_map(|m| m.weight.iter().chain(&m.color))
                .next()
                .map(|t| ("specular map", t)));
            let has_uvs = matches!(&object.shape, Shape::Mesh { uvs, .. } if !uvs.is_empty());
            if let (Some((what, texture)), false) = (image, has_uvs) {
                return Err(c.err(
                    "material",
                    format!(
                        "'{}' has the {what} {}, which needs a mesh with texture coordinates (uvs); this {} has none",
                        material.name,
                        texture.name,
                        object.shape.name()
                    ),
                ));
            }
            let checked_before = previous.is_some_and(|p| {
                p.objects.get(i).is_some_and(|o| {
                    o.shape == object.shape
                        && matches!(
                            p.materials.get(o.material).map(|m| &m.kind),
                            Some(MaterialKind::Dielectric { thin: false, .. })
                        )
                })
            });
            if let (MaterialKind::Dielectric { thin: false, .. }, Shape::Mesh { positions, triangles, .. }) =
                (&material.kind, &object.shape)
                && !checked_before
                && let Some((a, b)) = crate::model::mesh::open_edge(positions, triangles)
            {
                return Err(c.err(
                    "triangles",
                    format!(
                        "dielectric '{}' needs a closed mesh (every edge shared by two triangles of opposite \
                         winding); the edge from {a} to {b} is not",
                        material.name
                    ),
                ));
            }
        }
        Ok(())
    }

    fn validate_render(&self) -> Result<(), SceneError> {
        let r = &self.render;
        let c = Check { prefix: "render" };
        for (field, side) in [("width", r.width), ("height", r.height)] {
            if side == 0 || side > MAX_IMAGE_SIDE {
                return Err(c.err(field, format!("must be between 1 and {MAX_IMAGE_SIDE}, got {side}")));
            }
        }
        if r.photons > MAX_PHOTONS {
            return Err(c.err(
                "photons",
                format!("{} white photons would not fit in memory; at most {MAX_PHOTONS}", r.photons),
            ));
        }
        if r.photons.saturating_add(r.indirect_photons) > MAX_PHOTONS {
            return Err(c.err(
                "indirect_photons",
                format!(
                    "{} caustic and {} indirect photons would not fit in memory; at most {MAX_PHOTONS} together",
                    r.photons, r.indirect_photons
                ),
            ));
        }
        c.positive("radius", r.radius)?;
        if let BandSpec::Physical(n) = r.bands
            && (n == 0 || usize::from(n) > MAX_BANDS)
        {
            return Err(c.err("bands", format!("must be \"paper3\", \"paper7\" or 1 to {MAX_BANDS}, got {n}")));
        }
        if r.max_depth == 0 || r.max_depth > MAX_DEPTH {
            return Err(c.err("max_depth", format!("must be between 1 and {MAX_DEPTH}, got {}", r.max_depth)));
        }
        if r.passes == 0 {
            return Err(c.err("passes", "must be at least 1, got 0"));
        }
        if !(r.alpha > 0.0 && r.alpha <= 1.0) {
            return Err(c.err("alpha", format!("must be in (0, 1], got {}", r.alpha)));
        }
        if r.neighbours == 0 {
            return Err(c.err("neighbours", "must be at least 1, got 0"));
        }
        if r.area_lights == 0 || r.area_lights > MAX_AREA_LIGHTS {
            return Err(c.err("area_lights", format!("must be 1 to {MAX_AREA_LIGHTS}, got {}", r.area_lights)));
        }
        if r.environment_lights == 0 || r.environment_lights > MAX_ENVIRONMENT_LIGHTS {
            return Err(c.err(
                "environment_lights",
                format!("must be 1 to {MAX_ENVIRONMENT_LIGHTS}, got {}", r.environment_lights),
            ));
        }
        c.non_negative("ambient", r.ambient)?;
        c.positive("exposure", r.exposure)?;
        c.colour("background", r.background)
    }

    fn validate_camera(&self) -> Result<(), SceneError> {
        let cam = &self.camera;
        let c = Check { prefix: "camera" };
        c.vector("position", cam.position)?;
        c.vector("look_at", cam.look_at)?;
        c.direction("up", cam.up)?;
        let view = cam.look_at - cam.position;
        if view.length_squared() <= 1e-20 {
            return Err(c.err("look_at", "must differ from camera.position"));
        }
        if view.normalize().cross(cam.up.normalize()).length() < 1e-4 {
            return Err(c.err("up", "must not be parallel to the viewing direction"));
        }
        c.finite("fov_deg", cam.fov_deg)?;
        if !(cam.fov_deg > 0.0 && cam.fov_deg < 180.0) {
            return Err(c.err("fov_deg", format!("must be between 0 and 180 degrees (exclusive), got {}", cam.fov_deg)));
        }
        Ok(())
    }
}

fn validate_light(c: &Check<'_>, light: &Light) -> Result<(), SceneError> {
    if let Some(range) = light.range() {
        c.positive("range", range)?;
    }
    match light {
        Light::Spot { position, direction, cone_deg, inner_cone_deg, power, .. } => {
            c.vector("position", *position)?;
            c.direction("direction", *direction)?;
            c.finite("cone_deg", *cone_deg)?;
            if !(*cone_deg > 0.0 && *cone_deg <= 90.0) {
                return Err(c.err("cone_deg", format!("must be a half-angle in (0, 90] degrees, got {cone_deg}")));
            }
            c.finite("inner_cone_deg", *inner_cone_deg)?;
            if !(*inner_cone_deg >= 0.0 && inner_cone_deg <= cone_deg) {
                return Err(c.err(
                    "inner_cone_deg",
                    format!("must be a half-angle from 0 to cone_deg ({cone_deg}), got {inner_cone_deg}"),
                ));
            }
            c.positive("power", *power)
        }
        Light::Point { position, power, .. } => {
            c.vector("position", *position)?;
            c.positive("power", *power)
        }
        Light::Beam { position, direction, radius, power, .. } => {
            c.vector("position", *position)?;
            c.direction("direction", *direction)?;
            c.positive("radius", *radius)?;
            c.positive("power", *power)
        }
        Light::Area { vertices, power, .. } => {
            for (k, v) in vertices.iter().enumerate() {
                c.vector(&format!("vertices[{k}]"), *v)?;
            }
            let [a, b, cc] = *vertices;
            if (b - a).cross(cc - a).length_squared() <= 0.0 {
                return Err(c.err("vertices", "must span a triangle of non-zero area"));
            }
            c.positive("power", *power)
        }
        Light::Sun { direction, irradiance, .. } => {
            c.direction("direction", *direction)?;
            c.positive("irradiance", *irradiance)
        }
        Light::Environment { map, strength, rotation_deg, .. } => {
            c.positive("strength", *strength)?;
            c.finite("rotation_deg", *rotation_deg)?;
            let (w, h) = (map.width, map.height);
            if w == 0 || h == 0 || w > MAX_ENVIRONMENT_SIDE || h > MAX_ENVIRONMENT_SIDE {
                return Err(c.err(
                    "map",
                    format!("{}: {w}×{h} texels; each side must be 1 to {MAX_ENVIRONMENT_SIDE}", map.name),
                ));
            }
            if map.texels.len() != w as usize * h as usize {
                return Err(c.err("map", format!("{}: {} texels for a {w}×{h} map", map.name, map.texels.len())));
            }
            match map.texels.iter().position(|t| !t.is_finite() || t.min_element() < 0.0) {
                Some(i) => Err(c.err("map", format!("{}: texel {i} is not a finite radiance ≥ 0", map.name))),
                None if map.texels.iter().all(|t| t.max_element() == 0.0) => {
                    Err(c.err("map", format!("{}: black everywhere, it emits nothing", map.name)))
                }
                None => Ok(()),
            }
        }
    }
}

/// A light's spectrum: a blackbody's temperature, a table's wavelengths
/// and powers, some power in the visible range; with wavelengths of their
/// own (continuous, hero), a coloured spectrum needs physically based
/// bands (the paper's presets colour by their bands, made for its white).
fn validate_spectrum(
    c: &Check<'_>,
    spectrum: &Spectrum,
    render: &crate::model::scene::RenderSettings,
) -> Result<(), SceneError> {
    match spectrum {
        Spectrum::Blackbody { kelvin } => {
            if !(*kelvin >= 500.0 && *kelvin <= 100_000.0) {
                return Err(c.err("spectrum.blackbody", format!("must be between 500 and 100000 K, got {kelvin}")));
            }
        }
        Spectrum::Tabulated { nm, power } => {
            if nm.len() != power.len() || nm.len() < 2 {
                let reason =
                    format!("needs as many powers as wavelengths, two or more (got {} and {})", nm.len(), power.len());
                return Err(c.err("spectrum", reason));
            }
            if !nm.iter().all(|x| x.is_finite()) || !nm.windows(2).all(|w| w[0] < w[1]) {
                return Err(c.err("spectrum.nm", "must be finite and strictly increasing"));
            }
            if !power.iter().all(|p| p.is_finite() && *p >= 0.0) {
                return Err(c.err("spectrum.power", "must be finite and not negative"));
            }
            let (lo, hi) = VISIBLE_NM;
            let visible =
                (0..=400).any(|k| spectrum.power_at(f64::from(lo) + f64::from(hi - lo) * f64::from(k) / 400.0) > 0.0);
            if !visible {
                return Err(c.err("spectrum", format!("has no power between {lo} and {hi} nm")));
            }
        }
        _ => {}
    }
    let paper = matches!(render.bands, BandSpec::Paper3 | BandSpec::Paper7);
    if !spectrum.is_equal_energy() && paper && render.wavelengths.continuous() {
        let reason = format!(
            "with {} wavelengths a light of spectrum {spectrum} needs physically based bands (`bands = N`): \
             the paper's {} bands colour by their own weights, made for white light",
            render.wavelengths.name(),
            render.bands
        );
        return Err(c.err("spectrum", reason));
    }
    Ok(())
}

fn validate_material(c: &Check<'_>, m: &Material, bands: BandSpec) -> Result<(), SceneError> {
    if let Some(map) = &m.normal_map {
        validate_texture(c, "normal_map", &map.texture)?;
        c.finite("normal_scale", map.scale)?;
    }
    if let Some(map) = &m.roughness_map {
        validate_texture(c, "roughness_map", map)?;
        if !matches!(m.kind, MaterialKind::Metal { .. } | MaterialKind::Dielectric { .. }) {
            let reason = "scales a metal's or a dielectric's roughness; this material has none";
            return Err(c.err("roughness_map", reason));
        }
    }
    if let Some(map) = &m.film_map {
        validate_film_map(c, map, &m.kind)?;
    }
    if let Some(map) = &m.specular_map {
        validate_specular_map(c, map, &m.kind)?;
    }
    if let MaterialKind::Metal { film, metalness, .. } = &m.kind {
        if let Some(f) = film {
            validate_film(c, f, bands)?;
        }
        validate_metalness(c, metalness, m.roughness_map.is_some())?;
    }
    match &m.kind {
        MaterialKind::Diffuse { albedo, checker, texture, emission } => {
            c.colour("albedo", *albedo)?;
            c.colour("emission", *emission)?;
            if let Some(ch) = checker {
                c.positive("checker.size", ch.size)?;
                c.colour("checker.albedo", ch.albedo)?;
            }
            match texture {
                Some(t) => validate_texture(c, "texture", t),
                None => Ok(()),
            }
        }
        MaterialKind::Mirror => Ok(()),
        MaterialKind::Metal { color: MetalColor::Measured(metal), roughness, texture, .. } => {
            if texture.is_some() {
                let reason = format!(
                    "colours an RGB metal; {} reflects by its measured optical constants (give color as [r, g, b])",
                    metal.name()
                );
                return Err(c.err("texture", reason));
            }
            validate_roughness(c, *roughness)
        }
        MaterialKind::Metal { color: MetalColor::Rgb(color), roughness, texture, metalness, .. } => {
            // No metal anywhere: the colour is a diffuse base's albedo (a scene file's `albedo`).
            let plastic = metalness.factor == 0.0 && !metalness.mapped;
            c.colour(if plastic { "albedo" } else { "color" }, *color)?;
            if !plastic && color.max_element() > 1.0 {
                let reason = format!("a metal reflects at most all light, got [{}, {}, {}]", color.x, color.y, color.z);
                return Err(c.err("color", reason));
            }
            if let Some(t) = texture {
                validate_texture(c, "texture", t)?;
            }
            validate_roughness(c, *roughness)
        }
        MaterialKind::Dielectric { dispersion, outside, attenuation, film, roughness, .. } => {
            validate_roughness(c, *roughness)?;
            validate_dispersion(c, "ior", dispersion, bands)?;
            validate_dispersion(c, "outside_ior", outside, bands)?;
            if let Some(f) = film {
                validate_film(c, f, bands)?;
            }
            match attenuation {
                Some(a) => validate_attenuation(c, a),
                None => Ok(()),
            }
        }
    }
}

fn validate_film_map(c: &Check<'_>, map: &FilmMap, kind: &MaterialKind) -> Result<(), SceneError> {
    for (key, texture) in [("film_thickness_map", &map.thickness), ("film_factor_map", &map.factor)] {
        if let Some(t) = texture {
            validate_texture(c, key, t)?;
        }
    }
    let has_film =
        matches!(kind, MaterialKind::Metal { film: Some(_), .. } | MaterialKind::Dielectric { film: Some(_), .. });
    if !has_film {
        let key = if map.thickness.is_some() { "film_thickness_map" } else { "film_factor_map" };
        return Err(c.err(key, "varies a film; this material has none (give film_thickness_nm)"));
    }
    c.non_negative("film_min_nm", map.min_nm)?;
    if map.min_nm > MAX_FILM_NM {
        return Err(c.err("film_min_nm", format!("must be at most {MAX_FILM_NM} nm, got {}", map.min_nm)));
    }
    Ok(())
}

fn validate_specular_map(c: &Check<'_>, map: &SpecularMap, kind: &MaterialKind) -> Result<(), SceneError> {
    for (key, texture) in [("specular_map", &map.weight), ("specular_color_map", &map.color)] {
        if let Some(t) = texture {
            validate_texture(c, key, t)?;
        }
    }
    if !matches!(kind, MaterialKind::Metal { metalness: Metalness { layer: Some(_), .. }, .. }) {
        let key = if map.weight.is_some() { "specular_map" } else { "specular_color_map" };
        return Err(c.err(key, "varies a specular layer; this material has none (give specular)"));
    }
    let sane = map.color_f0.is_finite() && map.color_f0.min_element() >= 0.0;
    if map.color.is_some() && !sane {
        let reason = format!("with specular_ior, must give a reflectance of at least 0, got {}", map.color_f0);
        return Err(c.err("specular_color", reason));
    }
    Ok(())
}

fn validate_metalness(c: &Check<'_>, metalness: &Metalness, has_map: bool) -> Result<(), SceneError> {
    c.finite("metalness", metalness.factor)?;
    if !(0.0..=1.0).contains(&metalness.factor) {
        return Err(c.err("metalness", format!("must be between 0 and 1, got {}", metalness.factor)));
    }
    if metalness.mapped && !has_map {
        return Err(c.err("metalness", "is read from the roughness map's blue channel, but there is no roughness_map"));
    }
    if let Some(layer) = metalness.layer {
        c.finite("specular", layer.f90)?;
        if !(0.0..=1.0).contains(&layer.f90) {
            return Err(c.err("specular", format!("must be between 0 and 1, got {}", layer.f90)));
        }
        // F0 comes of specular_ior and specular_color, at most F90 when both are sane.
        let sane = layer.f0.is_finite() && layer.f0.min_element() >= 0.0 && layer.f0.max_element() <= layer.f90;
        if !sane {
            return Err(c.err(
                "specular_color",
                format!("with specular_ior, must give a reflectance between 0 and specular, got {}", layer.f0),
            ));
        }
    }
    Ok(())
}

fn validate_roughness(c: &Check<'_>, roughness: f32) -> Result<(), SceneError> {
    c.finite("roughness", roughness)?;
    if (0.0..=1.0).contains(&roughness) {
        Ok(())
    } else {
        Err(c.err("roughness", format!("must be between 0 and 1, got {roughness}")))
    }
}

/// An image (`key`: the material's key that names it) has the texels its size says.
fn validate_texture(c: &Check<'_>, key: &str, t: &Texture) -> Result<(), SceneError> {
    let (w, h) = (t.width, t.height);
    if w == 0 || h == 0 || w > MAX_TEXTURE_SIDE || h > MAX_TEXTURE_SIDE {
        return Err(c.err(key, format!("{}: {w}×{h} texels; each side must be 1 to {MAX_TEXTURE_SIDE}", t.name)));
    }
    if t.texels.len() != w as usize * h as usize {
        return Err(c.err(key, format!("{}: {} texels for a {w}×{h} image", t.name, t.texels.len())));
    }
    match t.texels.iter().position(|&x| x >= 1 << 24) {
        Some(i) => Err(c.err(key, format!("{}: texel {i} is not three 8-bit channels", t.name))),
        None => Ok(()),
    }
}

fn validate_film(c: &Check<'_>, f: &ThinFilm, bands: BandSpec) -> Result<(), SceneError> {
    validate_dispersion(c, "film_ior", &Dispersion::Constant(f.ior), bands)?;
    if !(f.thickness_nm.is_finite() && (0.0..=MAX_FILM_NM).contains(&f.thickness_nm)) {
        return Err(c.err(
            "film_thickness_nm",
            format!("a film's thickness must be 0 to {MAX_FILM_NM} nm, got {}", f.thickness_nm),
        ));
    }
    if !(0.0..=1.0).contains(&f.factor) {
        return Err(c.err("film_factor", format!("a film's factor must be 0 to 1, got {}", f.factor)));
    }
    Ok(())
}

fn validate_attenuation(c: &Check<'_>, a: &Attenuation) -> Result<(), SceneError> {
    c.vector("attenuation_color", a.color)?;
    if !(a.color.min_element() > 0.0 && a.color.max_element() <= 1.0) {
        let [r, g, b] = a.color.to_array();
        return Err(c.err(
            "attenuation_color",
            format!(
                "each channel must be in (0, 1] (the fraction left after attenuation_distance), got [{r}, {g}, {b}]"
            ),
        ));
    }
    c.positive("attenuation_distance", a.distance)
}

fn validate_dispersion(c: &Check<'_>, key: &str, d: &Dispersion, bands: BandSpec) -> Result<(), SceneError> {
    let index_ok = |n: f32| n.is_finite() && (1.0..=5.0).contains(&n);
    match d {
        Dispersion::Constant(n) if !index_ok(*n) => {
            Err(c.err(key, format!("an index of refraction must be between 1 and 5, got {n}")))
        }
        Dispersion::Cauchy { a, b } if !(a.is_finite() && b.is_finite()) => {
            Err(c.err(&format!("{key}.cauchy"), "A and B must be finite numbers"))
        }
        Dispersion::Abbe { nd, vd } if !(index_ok(*nd) && vd.is_finite() && *vd > 0.0) => Err(
            c.err(&format!("{key}.abbe"), format!("needs n_d in [1, 5] and a positive Abbe number, got [{nd}, {vd}]"))
        ),
        Dispersion::Sellmeier { b, c: cs } => {
            if b.is_empty() || b.len() != cs.len() || b.len() > MAX_SELLMEIER_TERMS {
                return Err(c.err(
                    &format!("{key}.sellmeier"),
                    format!("b and c need the same number of terms, 1 to {MAX_SELLMEIER_TERMS}"),
                ));
            }
            if !b.iter().chain(cs).all(|x| x.is_finite()) {
                return Err(c.err(&format!("{key}.sellmeier"), "coefficients must be finite numbers"));
            }
            check_visible_range(c, key, d)
        }
        Dispersion::Table { lambda_nm, n } => {
            let key = format!("{key}.table");
            if lambda_nm.len() != n.len() || lambda_nm.len() < 2 {
                return Err(c.err(&key, format!("needs at least 2 rows, got {}", lambda_nm.len().min(n.len()))));
            }
            if let Some(i) = lambda_nm.iter().position(|x| !x.is_finite()) {
                return Err(
                    c.err(&key, format!("row {}: wavelength must be a finite number, got {}", i + 1, lambda_nm[i]))
                );
            }
            if let Some(i) = lambda_nm.windows(2).position(|w| w[0] >= w[1]) {
                return Err(c.err(
                    &key,
                    format!(
                        "wavelengths must increase: row {} ({} nm) after {} nm",
                        i + 2,
                        lambda_nm[i + 1],
                        lambda_nm[i]
                    ),
                ));
            }
            let (lo, hi) = crate::model::bands::VISIBLE_NM;
            let (first, last) = (lambda_nm[0], lambda_nm[lambda_nm.len() - 1]);
            if !(first <= lo && last >= hi) {
                return Err(
                    c.err(&key, format!("covers {first}–{last} nm; it must cover the visible range {lo}–{hi} nm"))
                );
            }
            match n.iter().position(|&x| !index_ok(x)) {
                Some(i) => Err(
                    c.err(&key, format!("row {}: an index of refraction must be between 1 and 5, got {}", i + 1, n[i]))
                ),
                None => Ok(()),
            }
        }
        Dispersion::PerBand(n) => {
            let expected = crate::model::bands::BandTable::new(bands).len();
            if n.len() != expected {
                return Err(c.err(
                    &format!("{key}.bands"),
                    format!("has {} entries but the render uses {expected} bands ({bands})", n.len()),
                ));
            }
            match n.iter().position(|&x| !index_ok(x)) {
                Some(i) => Err(c.err(
                    &format!("{key}.bands[{i}]"),
                    format!("an index of refraction must be between 1 and 5, got {}", n[i]),
                )),
                None => Ok(()),
            }
        }
        _ => check_visible_range(c, key, d),
    }
}

/// A continuous model must give a physical index over the whole visible range.
fn check_visible_range(c: &Check<'_>, key: &str, d: &Dispersion) -> Result<(), SceneError> {
    let (lo, hi) = crate::model::bands::VISIBLE_NM;
    for k in 0..=40 {
        let lambda = lo + (hi - lo) * k as f32 / 40.0;
        let n = d.ior_at(lambda).unwrap_or(1.0);
        if !(n.is_finite() && (1.0..=5.0).contains(&n)) {
            return Err(c.err(key, format!("gives n = {n} at {lambda} nm; an index must be between 1 and 5")));
        }
    }
    Ok(())
}

fn validate_shape(c: &Check<'_>, shape: &Shape) -> Result<(), SceneError> {
    match shape {
        Shape::Sphere { center, radius } => {
            c.vector("center", *center)?;
            c.positive("radius", *radius)
        }
        Shape::Plane { point, normal } => {
            c.vector("point", *point)?;
            c.direction("normal", *normal)
        }
        Shape::Disk { center, normal, radius, inner_radius } => {
            c.vector("center", *center)?;
            c.direction("normal", *normal)?;
            c.positive("radius", *radius)?;
            c.non_negative("inner_radius", *inner_radius)?;
            if inner_radius >= radius {
                return Err(
                    c.err("inner_radius", format!("must be smaller than radius ({radius}), got {inner_radius}"))
                );
            }
            Ok(())
        }
        Shape::Prism { vertices, extrude } => {
            for (i, v) in vertices.iter().enumerate() {
                c.vector(&format!("vertices[{i}]"), *v)?;
            }
            c.direction("extrude", *extrude)?;
            let normal = (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]);
            let scale = (vertices[1] - vertices[0]).length_squared().max((vertices[2] - vertices[0]).length_squared());
            if normal.length() <= 1e-6 * scale {
                return Err(c.err("vertices", "the three corners are collinear: the prism has no cross-section"));
            }
            if normal.normalize().dot(extrude.normalize()).abs() < 1e-3 {
                return Err(c.err("extrude", "lies in the plane of the vertices: the prism has no volume"));
            }
            Ok(())
        }
        Shape::Mesh { positions, triangles, uvs, normals, tangents } => {
            if triangles.is_empty() {
                return Err(c.err("triangles", "the mesh has no triangles"));
            }
            if triangles.len() > MAX_MESH_TRIANGLES {
                return Err(c.err(
                    "triangles",
                    format!("{} triangles: one mesh holds at most {MAX_MESH_TRIANGLES}", triangles.len()),
                ));
            }
            for (i, p) in positions.iter().enumerate() {
                c.vector(&format!("positions[{i}]"), *p)?;
            }
            for (i, t) in triangles.iter().enumerate() {
                if let Some(&bad) = t.iter().find(|&&k| k as usize >= positions.len()) {
                    return Err(c.err(
                        &format!("triangles[{i}]"),
                        format!("vertex index {bad} is out of range ({} positions)", positions.len()),
                    ));
                }
            }
            if !uvs.is_empty() && uvs.len() != positions.len() {
                return Err(c.err(
                    "uvs",
                    format!(
                        "{} texture coordinates for {} positions: give one per position",
                        uvs.len(),
                        positions.len()
                    ),
                ));
            }
            if let Some(i) = uvs.iter().position(|uv| !uv.is_finite()) {
                return Err(c.err(&format!("uvs[{i}]"), format!("must be finite, got {}", uvs[i])));
            }
            if !normals.is_empty() && normals.len() != positions.len() {
                return Err(c.err(
                    "normals",
                    format!("{} normals for {} positions: give one per position", normals.len(), positions.len()),
                ));
            }
            if let Some(i) = normals.iter().position(|n| !n.is_finite() || n.length_squared() == 0.0) {
                return Err(c.err(&format!("normals[{i}]"), format!("must be finite and not zero, got {}", normals[i])));
            }
            if !tangents.is_empty() && tangents.len() != positions.len() {
                return Err(c.err(
                    "tangents",
                    format!("{} tangents for {} positions: give one per position", tangents.len(), positions.len()),
                ));
            }
            let bad = |t: &Vec4| !t.is_finite() || t.truncate().length_squared() == 0.0 || t.w == 0.0;
            match tangents.iter().position(bad) {
                Some(i) => Err(c.err(
                    &format!("tangents[{i}]"),
                    format!("must be finite with a non-zero direction and a handedness w of ±1, got {}", tangents[i]),
                )),
                None => Ok(()),
            }
        }
    }
}
