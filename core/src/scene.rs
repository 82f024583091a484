//! The scene model (what a scene file or an engine describes) and its validation.
//!
//! A [`Scene`] is plain data. [`Scene::validate`] checks every value and
//! reports the first problem with the key it belongs to (for example
//! `object[2].radius`) and the reason, using the same key names as the
//! scene-file format so that a file loader can pass them straight through.

use crate::bands::{BandSpec, MAX_BANDS};
use crate::color::ToneMap;
use crate::dispersion::{Dispersion, MAX_SELLMEIER_TERMS};
use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt;
use glam::Vec3;

/// The most white photons one render may emit (each may store up to N band
/// photons of 32 bytes: beyond this the map would not fit in memory).
pub const MAX_PHOTONS: u32 = 100_000_000;

/// The largest allowed trace depth (specular bounces per path).
pub const MAX_DEPTH: u32 = 64;

/// The largest image side.
pub const MAX_IMAGE_SIDE: u32 = 16_384;

/// A problem found in a scene: the key it belongs to and why it is wrong.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{key}: {reason}")]
pub struct SceneError {
    /// Dotted key of the offending value, as in the scene file (`light[0].cone_deg`).
    pub key: String,
    /// What is wrong with it.
    pub reason: String,
}

impl SceneError {
    /// A new error for `key`.
    pub fn new(key: impl Into<String>, reason: impl Into<String>) -> Self {
        SceneError { key: key.into(), reason: reason.into() }
    }
}

/// Which gather estimator turns caustic photons into colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Estimator {
    /// The paper's: hue from band counts (W/Total), strength from photon density.
    Paper,
    /// Per-band flux density Σ Φ / (π r²) through the band weights.
    Density,
}

impl Estimator {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            Estimator::Paper => "paper",
            Estimator::Density => "density",
        }
    }
}

/// How a white photon's spectrum is sampled at the first dispersive glass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WavelengthSampling {
    /// Split into all N bands, each with 1/N of the flux (the paper's method).
    #[default]
    Split,
    /// Continue as one band chosen uniformly at random, carrying the whole
    /// flux (1/N × N): N times fewer paths, more colour noise.
    RandomBand,
    /// One random band as in `RandomBand`, traced at a wavelength drawn
    /// uniformly from the band's interval: stripes become continuous while
    /// colours keep the band's weight.
    Continuous,
}

impl WavelengthSampling {
    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            WavelengthSampling::Split => "split",
            WavelengthSampling::RandomBand => "random_band",
            WavelengthSampling::Continuous => "continuous",
        }
    }

    /// Parses a scene-file name.
    pub fn from_name(name: &str) -> Option<Self> {
        [WavelengthSampling::Split, WavelengthSampling::RandomBand, WavelengthSampling::Continuous]
            .into_iter()
            .find(|w| w.name() == name)
    }
}

/// Image and photon-pass settings (`[render]`).
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// White photons emitted (over all lights).
    pub photons: u32,
    /// Gather radius in world units.
    pub radius: f32,
    /// The band table.
    pub bands: BandSpec,
    /// The gather estimator.
    pub estimator: Estimator,
    /// How white photons sample the spectrum at dispersive glass.
    pub wavelengths: WavelengthSampling,
    /// Seed of the counter-based RNG.
    pub seed: u32,
    /// Most specular interactions on a photon path or view ray.
    pub max_depth: u32,
    /// Uniform ambient irradiance factor (fraction of albedo added everywhere).
    pub ambient: f32,
    /// Multiplier applied to radiance before the sRGB encoding.
    pub exposure: f32,
    /// Radiance of rays that leave the scene.
    pub background: Vec3,
    /// How radiance becomes displayable.
    pub tone_map: ToneMap,
    /// Aim caustic photons only at mirrors and glass (projection maps).
    pub projection_maps: bool,
    /// Photon passes of a progressive render (`radius` is then the largest
    /// first radius; see `progressive`).
    pub passes: u32,
    /// How fast progressive radii shrink: r_k² ∝ Π (j + α)/(j + 1), 0 < α ≤ 1
    /// (1 keeps them; smaller shrinks faster, less blur, more noise).
    pub alpha: f32,
    /// Independent photon paths a progressive render's first radius should
    /// hold (more: smoother early passes, more blur until the radii shrink).
    pub neighbours: u32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            width: 400,
            height: 400,
            photons: 100_000,
            radius: 0.05,
            bands: BandSpec::Paper7,
            estimator: Estimator::Paper,
            wavelengths: WavelengthSampling::Split,
            seed: 1,
            max_depth: 12,
            ambient: 0.03,
            exposure: 1.0,
            background: Vec3::ZERO,
            tone_map: ToneMap::Clamp,
            projection_maps: true,
            passes: 16,
            alpha: crate::progressive::DEFAULT_ALPHA,
            neighbours: crate::progressive::DEFAULT_NEIGHBOURS,
        }
    }
}

/// A pinhole camera (`[camera]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub position: Vec3,
    /// Point the camera looks at.
    pub look_at: Vec3,
    /// Up direction (need not be orthogonal to the view direction).
    pub up: Vec3,
    /// Vertical field of view in degrees.
    pub fov_deg: f32,
}

/// A light source (`[[light]]`). Power is radiant flux in watts.
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    /// The paper's spot light: uniform intensity inside a cone.
    Spot {
        /// Apex of the cone.
        position: Vec3,
        /// Axis of the cone.
        direction: Vec3,
        /// Half-angle of the cone in degrees.
        cone_deg: f32,
        /// Flux in W.
        power: f32,
    },
    /// Isotropic point light.
    Point {
        /// Position.
        position: Vec3,
        /// Flux in W.
        power: f32,
    },
    /// Collimated beam leaving a disc (prism experiments, rainbows).
    Beam {
        /// Centre of the emitting disc.
        position: Vec3,
        /// Direction of travel (the disc's normal).
        direction: Vec3,
        /// Radius of the disc.
        radius: f32,
        /// Flux in W.
        power: f32,
    },
}

impl Light {
    /// The light's flux.
    pub fn power(&self) -> f32 {
        match self {
            Light::Spot { power, .. } | Light::Point { power, .. } | Light::Beam { power, .. } => *power,
        }
    }
}

/// A checker texture on a diffuse material.
#[derive(Clone, Debug, PartialEq)]
pub struct Checker {
    /// Edge length of one square.
    pub size: f32,
    /// Albedo of the alternate squares.
    pub albedo: Vec3,
    /// Added to a point before the pattern is evaluated: a scene recentred
    /// on a new origin sets it to that origin modulo two squares, so the
    /// squares stay where they are in the world.
    pub offset: Vec3,
}

/// How a surface scatters light.
#[derive(Clone, Debug, PartialEq)]
pub enum MaterialKind {
    /// Lambertian, optionally with a checker texture. Caustic photons are stored here.
    Diffuse {
        /// Albedo (reflectance) per RGB channel.
        albedo: Vec3,
        /// Optional checker texture.
        checker: Option<Checker>,
    },
    /// Smooth non-absorbing dielectric with a dispersion model.
    Dielectric {
        /// n(λ).
        dispersion: Dispersion,
        /// n(λ) of the medium the object sits in (`Constant(1.0)`: air). Only
        /// the ratio of the two indices matters at an interface, so glass in
        /// water is glass with the relative index n_glass/n_water.
        outside: Dispersion,
    },
    /// Perfect mirror.
    Mirror,
}

/// A named material (`[material.NAME]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The name objects refer to.
    pub name: String,
    /// The scattering model.
    pub kind: MaterialKind,
}

/// The geometry of an object.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere {
        /// Centre.
        center: Vec3,
        /// Radius.
        radius: f32,
    },
    /// An infinite plane (two-sided).
    Plane {
        /// A point on the plane.
        point: Vec3,
        /// Its normal.
        normal: Vec3,
    },
    /// A disc, optionally with a concentric hole (a screen with a hole).
    Disk {
        /// Centre.
        center: Vec3,
        /// Normal.
        normal: Vec3,
        /// Outer radius.
        radius: f32,
        /// Radius of the hole (0 for none).
        inner_radius: f32,
    },
    /// A triangular prism: one end's triangle extruded along a vector.
    Prism {
        /// The three corners of one end.
        vertices: [Vec3; 3],
        /// The vector from that end to the other.
        extrude: Vec3,
    },
    /// A triangle mesh; closed meshes used as dielectrics must wind
    /// counter-clockwise seen from outside.
    Mesh {
        /// Vertex positions.
        positions: Vec<Vec3>,
        /// Triangles as indices into `positions`.
        triangles: Vec<[u32; 3]>,
    },
}

impl Shape {
    /// The scene-file name of the shape.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Sphere { .. } => "sphere",
            Shape::Plane { .. } => "plane",
            Shape::Disk { .. } => "disk",
            Shape::Prism { .. } => "prism",
            Shape::Mesh { .. } => "mesh",
        }
    }

    /// True for shapes that enclose a volume (may be dielectrics).
    pub fn is_closed(&self) -> bool {
        matches!(self, Shape::Sphere { .. } | Shape::Prism { .. } | Shape::Mesh { .. })
    }
}

/// An object: a shape made of a material (`[[object]]`).
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Geometry.
    pub shape: Shape,
    /// Index into [`Scene::materials`].
    pub material: usize,
}

/// A whole scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// `[render]`.
    pub render: RenderSettings,
    /// `[camera]`.
    pub camera: Camera,
    /// `[[light]]`.
    pub lights: Vec<Light>,
    /// `[material.NAME]`.
    pub materials: Vec<Material>,
    /// `[[object]]`.
    pub objects: Vec<Object>,
}

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
        self.validate_render()?;
        self.validate_camera()?;
        if self.lights.is_empty() {
            return Err(SceneError::new("light", "the scene has no light"));
        }
        for (i, light) in self.lights.iter().enumerate() {
            validate_light(&Check { prefix: &format!("light[{i}]") }, light)?;
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
            if matches!(material.kind, MaterialKind::Dielectric { .. }) && !object.shape.is_closed() {
                return Err(c.err(
                    "material",
                    format!(
                        "dielectric '{}' needs a closed shape (sphere, prism or mesh), not a {}",
                        material.name,
                        object.shape.name()
                    ),
                ));
            }
            if let (MaterialKind::Dielectric { .. }, Shape::Mesh { positions, triangles }) =
                (&material.kind, &object.shape)
                && let Some((a, b)) = crate::mesh::open_edge(positions, triangles)
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
    match light {
        Light::Spot { position, direction, cone_deg, power } => {
            c.vector("position", *position)?;
            c.direction("direction", *direction)?;
            c.finite("cone_deg", *cone_deg)?;
            if !(*cone_deg > 0.0 && *cone_deg <= 90.0) {
                return Err(c.err("cone_deg", format!("must be a half-angle in (0, 90] degrees, got {cone_deg}")));
            }
            c.positive("power", *power)
        }
        Light::Point { position, power } => {
            c.vector("position", *position)?;
            c.positive("power", *power)
        }
        Light::Beam { position, direction, radius, power } => {
            c.vector("position", *position)?;
            c.direction("direction", *direction)?;
            c.positive("radius", *radius)?;
            c.positive("power", *power)
        }
    }
}

fn validate_material(c: &Check<'_>, m: &Material, bands: BandSpec) -> Result<(), SceneError> {
    match &m.kind {
        MaterialKind::Diffuse { albedo, checker } => {
            c.colour("albedo", *albedo)?;
            if let Some(ch) = checker {
                c.positive("checker.size", ch.size)?;
                c.colour("checker.albedo", ch.albedo)?;
            }
            Ok(())
        }
        MaterialKind::Mirror => Ok(()),
        MaterialKind::Dielectric { dispersion, outside } => {
            validate_dispersion(c, "ior", dispersion, bands)?;
            validate_dispersion(c, "outside_ior", outside, bands)
        }
    }
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
            let (lo, hi) = crate::bands::VISIBLE_NM;
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
            let expected = crate::bands::BandTable::new(bands).len();
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
    let (lo, hi) = crate::bands::VISIBLE_NM;
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
        Shape::Mesh { positions, triangles } => {
            if triangles.is_empty() {
                return Err(c.err("triangles", "the mesh has no triangles"));
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
            Ok(())
        }
    }
}

impl fmt::Display for Estimator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
