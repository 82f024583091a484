//! The scalar reference view pass: the specification of every backend's
//! view rays.
//!
//! One primary ray per pixel centre. At a diffuse hit the pixel gets
//! `(ρE_direct + ρE_caustic)/π + albedo · ambient`, where ρE is irradiance
//! reflected by the surface's reflectance spectrum (the albedo's, see
//! [`crate::model::reflectance`]), E_direct is
//! the ray-traced irradiance from each light (with shadow rays; glass casts
//! a full shadow because the light it passes on arrives as caustic photons)
//! and E_caustic is the gathered photon irradiance: the caustic is added to
//! the ray-traced colour, not mixed with it, which is the physically
//! consistent blend (the two estimate disjoint light paths). The view pass
//! leaves the caustic out: each diffuse hit that needs it becomes a visible
//! point whose weight says what a unit of caustic irradiance there adds to
//! the pixel, and every photon pass gathers there (with light tracing,
//! only the hits behind a mirror or glass: see [`gathers_at`]).
//!
//! Mirrors reflect. Metals reflect off one facet of their GGX
//! microsurface ([`scatter_metal`]; the mirror direction when polished),
//! the path weighted by the facet's Fresnel at its wavelength times the
//! unshadowed share G2/G1, its numbers [`PixelSampler::facet`]'s, and a
//! rough metal adds the highlights of the lights no ray meets
//! ([`ViewContext::metal_highlights`]). Dielectrics trace both the
//! Fresnel-weighted reflection and the refraction, to `max_depth` (rough
//! glass: off one facet, each branch weighted by G2/G1, plus the
//! highlights of hidden lights on both sides), dropping branches whose share of the
//! pixel (Fresnel factors times, after a split, the band's largest RGB
//! weight) falls below [`MIN_VIEW_WEIGHT`]. Rough metal and glass rough
//! enough ([`gathers_on_rough`]) leave a visible point too, which gathers
//! the photons met there with the surface's BSDF: the hidden lights'
//! light that mirrors, metals and glass bring, which no view ray finds.
//! Behind a rough surface where that light is counted (so gathered, or
//! light traced where the camera sees it: [`behind_rough`]), paths add no
//! highlights and leave no rough visible points: that light is the
//! photons'. At the first dispersive glass a
//! view ray splits into one ray per band, each weighted by the band's RGB
//! weight C_i. A ray that crossed coloured glass keeps its Beer–Lambert
//! transmittance (per RGB channel for white rays, the band's for a band;
//! see [`glass_transmittance`]).
//!
//! With per-pass view paths ([`crate::model::scene::ViewPaths::per_pass`])
//! each pass traces its own view, with the numbers of [`PixelSampler`]: at
//! the first dispersive glass M = 4 hero paths ([`hero_view_paths`], at
//! most N), path i in band b = ⌊v·N⌋ with v = (i + u)/M (u the pixel's
//! spectrum number for the pass), weighted (N/M)·C_b, at its own
//! wavelength when the scene's photons are (continuous and hero
//! wavelengths). Hero paths start at the pixel's centre and take both
//! Fresnel branches at glass, as centre rays do; sampled paths start at a
//! jittered point of the pixel and take the reflection with probability
//! R, else the refraction (the factor R or 1 − R cancels against its
//! probability). Each pass's view is then an unbiased sample of what the
//! pixel's centre sees (hero) or of the box-filtered pixel (sampled), and
//! the passes' mean converges to it.

use crate::geometry::camera::PinholeCamera;
use crate::geometry::form_factor::{in_front_of, triangle_view};
use crate::geometry::primitive::Ray;
use crate::model::image::Image;
use crate::model::light_range::range_window;
use crate::model::photon::WHITE_BAND;
use crate::model::scene::{Light, WavelengthSampling};
use crate::optics::fresnel::reflect;
use crate::optics::metal::MetalOptics;
use crate::optics::microfacet::Ggx;
use crate::optics::rough_glass::rough_glass_bsdf;
use crate::optics::scatter::{
    Face, offset_origin, scatter_dielectric, scatter_metal, scatter_rough_dielectric, split_dielectric,
    split_rough_dielectric,
};
use crate::optics::surface::{DielectricOptics, Surface};
use crate::photons::light_tracing::traces_behind_rough;
use crate::photons::path::stored_wavelength;
use crate::photons::wavelengths::spectrum_share;
use crate::plan::area::area;
use crate::plan::area_aims::shadow_sample;
use crate::plan::prepared::{Hit, PreparedScene};
use crate::render::visible::{VisiblePoint, VisiblePoints};
use crate::sampling::pixel_sample::PixelSampler;
use crate::sampling::spot_cone::SpotCone;
use crate::util::progress::{Progress, Stage};
use crate::util::tolerance::{CONNECTION_REL, MIN_VIEW_WEIGHT};
use alloc::vec::Vec;
use core::f32::consts::PI;
use glam::Vec3;

/// Where a view ray is on its way from the camera: its band (or white) and
/// wavelength (`None`: the band's own index), specular depth, share of the
/// pixel (for pruning), RGB factor, and a sampled path's numbers and hero
/// path (0 before the split), the numbers its rough metals' facets
/// take (the pass's own, or pass 0's for centre rays, which are traced
/// once), and whether it left a rough surface where the hidden lights'
/// light is counted, light traced or gathered ([`behind_rough`]).
#[derive(Clone, Copy, Debug)]
struct ViewPath {
    band: u16,
    hero: u32,
    lambda_nm: Option<f32>,
    depth: u32,
    weight: f32,
    tint: Vec3,
    sampler: Option<PixelSampler>,
    facets: PixelSampler,
    behind_rough: bool,
}

/// Everything a pixel's view rays need: the scene and the camera.
pub struct ViewContext<'a> {
    /// The scene.
    pub scene: &'a PreparedScene,
    /// The camera.
    pub camera: PinholeCamera,
}

impl<'a> ViewContext<'a> {
    /// Sets up the view rays of `scene`.
    pub fn new(scene: &'a PreparedScene) -> Self {
        let r = &scene.scene.render;
        ViewContext { scene, camera: PinholeCamera::new(&scene.scene.camera, r.width, r.height) }
    }

    /// Pixel (x, y) without its caustic, exposure applied; the diffuse hits
    /// whose caustic it needs are appended to `points` (their weight includes
    /// the exposure and their pixel is the row-major index of (x, y)).
    pub fn pixel(&self, x: u32, y: u32, points: &mut Vec<VisiblePoint>) -> Vec3 {
        self.trace_pixel(x, y, None, points)
    }

    /// [`ViewContext::pixel`] on pass `pass`'s own path ([`crate::model::scene::ViewPaths::per_pass`]).
    pub fn sampled_pixel(&self, x: u32, y: u32, pass: u32, points: &mut Vec<VisiblePoint>) -> Vec3 {
        let r = &self.scene.scene.render;
        self.trace_pixel(x, y, Some(PixelSampler::new(r.seed, y * r.width + x, pass)), points)
    }

    fn trace_pixel(&self, x: u32, y: u32, sampler: Option<PixelSampler>, points: &mut Vec<VisiblePoint>) -> Vec3 {
        let response = self.scene.camera_response();
        let r = &self.scene.scene.render;
        let facets = sampler.unwrap_or_else(|| PixelSampler::new(r.seed, y * r.width + x, 0));
        let path = ViewPath {
            band: WHITE_BAND,
            hero: 0,
            lambda_nm: None,
            depth: 0,
            weight: 1.0,
            tint: response,
            sampler,
            facets,
            behind_rough: false,
        };
        let first = points.len();
        let ray = match sampler {
            Some(s) if self.scene.scene.render.view_paths.jittered() => self.camera.ray_through(x, y, s.jitter()),
            _ => self.camera.ray(x, y),
        };
        let radiance = self.radiance(&ray, path, points) * response;
        let pixel = y * self.scene.scene.render.width + x;
        for p in &mut points[first..] {
            p.pixel = pixel;
        }
        radiance
    }

    /// Radiance arriving along `ray` on `path`, less the caustic: each
    /// diffuse hit that needs it is recorded in `points` instead (weighted
    /// by the path's tint).
    fn radiance(&self, ray: &Ray, path: ViewPath, points: &mut Vec<VisiblePoint>) -> Vec3 {
        let Some(hit) = self.scene.intersect(ray, f32::INFINITY) else {
            return self.scene.background(ray.direction);
        };
        let surface = &self.scene.surfaces[hit.object];
        // What coloured glass left of the ray, when it crossed glass to get here.
        let kept = match surface {
            Surface::Dielectric(glass) => glass_transmittance(glass, ray.direction, hit.normal, hit.t, path.band),
            _ => Vec3::ONE,
        };
        let path = ViewPath { weight: path.weight * kept.max_element(), tint: path.tint * kept, ..path };
        let ViewPath { band, depth, weight, tint, .. } = path;
        if let Surface::Diffuse { .. } = surface {
            return kept * self.shade_diffuse(ray, &hit, (path.tint, path.depth), points);
        }
        if let Surface::Metal(metal) = surface
            && metal.is_blended()
        {
            return self.blended_metal(ray, &hit, metal, path, points);
        }
        // Mirrors, metals and glass scatter about the shading normal.
        let hit = Hit { normal: self.scene.scattering_normal(&hit, ray.direction), ..hit };
        // Rough glass's visible point, before a split into bands: one for the path.
        if let Surface::Dielectric(_) = surface
            && depth < self.scene.plan.max_depth
            && !path.behind_rough
            && gathers_on_rough(self.scene, depth, self.scene.facets(&hit))
        {
            points.push(VisiblePoint::on_rough(&hit, ray.direction, tint));
        }
        kept * match surface {
            _ if depth >= self.scene.plan.max_depth => Vec3::ZERO,
            Surface::Mirror => {
                let d = reflect(ray.direction, hit.normal);
                let next = ViewPath { depth: depth + 1, ..path };
                self.radiance(&Ray { origin: offset_origin(hit.point, hit.normal, d), direction: d }, next, points)
            }
            Surface::Metal(metal) => self.off_metal(ray, &hit, metal, path, points),
            Surface::Dielectric(glass) if band == WHITE_BAND && glass.splits_view_rays => match path.sampler {
                Some(sampler) => hero_view_paths(self.scene, sampler.spectrum())
                    .map(|HeroViewPath { hero, band, lambda_nm, weight: w }| {
                        let share = weight * w.abs().max_element();
                        let p = ViewPath { band, hero, lambda_nm, weight: share, tint: tint * w, ..path };
                        w * self.through_dielectric(ray, &hit, (self.face(glass, &hit, &p), glass), p, points)
                    })
                    .sum(),
                None => self
                    .scene
                    .bands
                    .bands()
                    .iter()
                    .enumerate()
                    .map(|(b, info)| {
                        // The band's share of the pixel bounds what its branches can add.
                        let share = weight * info.weight.abs().max_element();
                        let band_path = ViewPath { band: b as u16, weight: share, tint: tint * info.weight, ..path };
                        let face = self.scene.face(glass, &hit, b as u16, None);
                        info.weight * self.through_dielectric(ray, &hit, (face, glass), band_path, points)
                    })
                    .sum(),
            },
            Surface::Dielectric(glass) => {
                self.through_dielectric(ray, &hit, (self.face(glass, &hit, &path), glass), path, points)
            }
            Surface::Diffuse { .. } => unreachable!("shaded above"),
        }
    }

    /// What a path arriving along `ray` sees of the metal `metal` at `hit`
    /// (its normal the scattering normal), or of a blended metal's
    /// specular part: its highlights, and the light reflected off one
    /// facet, weighted by its Fresnel at the path's wavelength
    /// ([`MetalOptics::specular_tint`]) times G2/G1.
    fn off_metal(
        &self,
        ray: &Ray,
        hit: &Hit,
        metal: &MetalOptics,
        path: ViewPath,
        points: &mut Vec<VisiblePoint>,
    ) -> Vec3 {
        let ViewPath { band, depth, weight, tint, .. } = path;
        let metal = &self.scene.metal_at(metal, hit);
        let lambda_nm = stored_wavelength(&self.scene.bands, band, path.lambda_nm);
        let lit = match path.behind_rough {
            true => Vec3::ZERO,
            false => self.metal_highlights(ray.direction, (hit.point, hit.normal), metal, band, lambda_nm),
        };
        if !path.behind_rough && gathers_on_rough(self.scene, depth, metal.ggx) {
            points.push(VisiblePoint::on_rough(hit, ray.direction, tint));
        }
        let (u1, u2) = if metal.ggx.is_some() { path.facets.facet(path.hero, depth) } else { (0.0, 0.0) };
        let Some(b) = scatter_metal(ray.direction, hit.point, hit.normal, metal.ggx, u1, u2) else {
            return lit;
        };
        let f = metal.specular_tint(b.cos_facet, band, lambda_nm, &self.scene.bands) * b.unshadowed;
        let behind_rough = behind_rough(self.scene, path.behind_rough, depth, metal.ggx);
        let next =
            ViewPath { depth: depth + 1, weight: weight * f.max_element(), tint: tint * f, behind_rough, ..path };
        lit + if next.weight > MIN_VIEW_WEIGHT { f * self.radiance(&b.ray, next, points) } else { Vec3::ZERO }
    }

    /// What a path arriving along `ray` sees of a blended metal (`metal`
    /// at `hit`): its diffuse part, shaded as a diffuse surface of albedo
    /// F0 and weighted by its share toward the viewer (its visible point
    /// too), and its specular part ([`ViewContext::off_metal`]), whose
    /// Fresnel holds its metalness ([`crate::optics::metal`]).
    fn blended_metal(
        &self,
        ray: &Ray,
        hit: &Hit,
        metal: &MetalOptics,
        path: ViewPath,
        points: &mut Vec<VisiblePoint>,
    ) -> Vec3 {
        let bent = Hit { normal: self.scene.scattering_normal(hit, ray.direction), ..*hit };
        let at = self.scene.metalness_at(metal, hit);
        let lambda_nm = stored_wavelength(&self.scene.bands, path.band, path.lambda_nm);
        let cos = ray.direction.dot(bent.normal).abs();
        let share = self.scene.diffuse_share_at(metal, hit, at, cos, path.band, lambda_nm);
        let mut sum = Vec3::ZERO;
        if share > 0.0 {
            sum += share * self.shade_diffuse(ray, hit, (path.tint * share, path.depth), points);
        }
        // Where a point is whole metal it is followed as a whole metal is.
        let most = at.specular_share();
        let followed = most >= 1.0 || path.weight * most > MIN_VIEW_WEIGHT;
        if most > 0.0 && path.depth < self.scene.plan.max_depth && followed {
            sum += self.off_metal(ray, &bent, metal, path, points);
        }
        sum
    }

    /// What `path` meets at `glass` where `hit` is: its band's index, or at
    /// its own wavelength, and the film there at that wavelength.
    fn face(&self, glass: &DielectricOptics, hit: &Hit, path: &ViewPath) -> Face {
        self.scene.face(glass, hit, path.band, path.lambda_nm)
    }

    /// Fresnel-weighted reflection plus refraction at a dielectric hit
    /// (the path's index there, and the glass: a tinted thin sheet keeps
    /// its crossing's colour of what passes it).
    fn through_dielectric(
        &self,
        ray: &Ray,
        hit: &Hit,
        (face, glass): (Face, &DielectricOptics),
        path: ViewPath,
        points: &mut Vec<VisiblePoint>,
    ) -> Vec3 {
        if let Some(ggx) = self.scene.facets(hit) {
            return self.through_rough_dielectric(ray, hit, (face, glass, ggx), path, points);
        }
        let thin = glass.thin;
        let crossing = glass.sheet_crossing_rgb(path.band);
        let crossed =
            |p: ViewPath| ViewPath { weight: p.weight * crossing.max_element(), tint: p.tint * crossing, ..p };
        if let Some(sampler) = path.sampler.filter(|_| self.scene.scene.render.view_paths.jittered()) {
            // One branch, chosen with its Fresnel probability, as photons choose theirs.
            let next = ViewPath { depth: path.depth + 1, ..path };
            let u = sampler.branch(path.hero, path.depth);
            let out = scatter_dielectric(ray.direction, hit.point, hit.normal, face, u);
            if thin && out.direction == ray.direction {
                return crossing * self.radiance(&out, crossed(next), points);
            }
            return self.radiance(&out, next, points);
        }
        let split = split_dielectric(ray.direction, hit.point, hit.normal, face);
        let r = split.reflectance;
        let mut sum = Vec3::ZERO;
        let branch = |f: f32| ViewPath { depth: path.depth + 1, weight: path.weight * f, tint: path.tint * f, ..path };
        if r * path.weight > MIN_VIEW_WEIGHT {
            sum += self.radiance(&split.reflected, branch(r), points) * r;
        }
        let t = 1.0 - r;
        if t * path.weight > MIN_VIEW_WEIGHT
            && let Some(refracted) = split.refracted
        {
            sum += crossing * self.radiance(&refracted, crossed(branch(t)), points) * t;
        }
        sum
    }

    /// Reflection and refraction off one facet of rough glass (drawn with
    /// the path's [`PixelSampler::facet`] numbers): Fresnel's choice for a
    /// sampled path, both branches for a centre or hero path, each weighted
    /// by G2/G1 ([`scatter_rough_dielectric`], [`split_rough_dielectric`]),
    /// plus the highlights of the lights no ray meets, on either side
    /// ([`rough_glass_bsdf`]). A tinted sheet keeps its crossing's colour
    /// of what passes it.
    fn through_rough_dielectric(
        &self,
        ray: &Ray,
        hit: &Hit,
        (face, glass, ggx): (Face, &DielectricOptics, Ggx),
        path: ViewPath,
        points: &mut Vec<VisiblePoint>,
    ) -> Vec3 {
        let crossing = glass.sheet_crossing_rgb(path.band);
        let at = (hit.point, hit.normal);
        let lit = match path.behind_rough {
            true => Vec3::ZERO,
            false => self.rough_glass_highlights(ray.direction, at, (face, ggx), crossing),
        };
        let behind_rough = behind_rough(self.scene, path.behind_rough, path.depth, Some(ggx));
        let mut follow = |out: &Ray, weight: f32, crossed: bool| {
            let f = if crossed { crossing * weight } else { Vec3::splat(weight) };
            let (depth, weight, tint) = (path.depth + 1, path.weight * f.max_element(), path.tint * f);
            let next = ViewPath { depth, weight, tint, behind_rough, ..path };
            if next.weight > MIN_VIEW_WEIGHT { f * self.radiance(out, next, points) } else { Vec3::ZERO }
        };
        let facet = path.facets.facet(path.hero, path.depth);
        if let Some(sampler) = path.sampler.filter(|_| self.scene.scene.render.view_paths.jittered()) {
            let u = sampler.branch(path.hero, path.depth);
            return lit
                + scatter_rough_dielectric(ray.direction, at, face, ggx, facet, u)
                    .map_or(Vec3::ZERO, |b| follow(&b.ray, b.unshadowed, b.crossed));
        }
        let split = split_rough_dielectric(ray.direction, at, face, ggx, facet);
        let reflected = split.reflected.map_or(Vec3::ZERO, |(r, w)| follow(&r, w, false));
        lit + reflected + split.crossed.map_or(Vec3::ZERO, |(r, w)| follow(&r, w, true))
    }

    /// Radiance leaving a diffuse hit (or a blended metal's diffuse part)
    /// toward the viewer (an emissive surface's own glow included), less
    /// its caustic, which is left to a visible point of weight `tint`/π for
    /// a path of that tint at `depth` (when the plan traces caustics and
    /// light tracing does not bring it: see [`gathers_at`]). Backends that
    /// take a blended metal ray by ray call it.
    pub fn shade_diffuse(
        &self,
        ray: &Ray,
        hit: &Hit,
        (tint, depth): (Vec3, u32),
        points: &mut Vec<VisiblePoint>,
    ) -> Vec3 {
        let side = if ray.direction.dot(hit.normal) < 0.0 { 1.0 } else { -1.0 };
        let n = hit.normal * side;
        let albedo = self.scene.albedo_at(hit.object, hit.triangle, hit.point, n);
        let settings = &self.scene.scene.render;
        // Each light's irradiance, in the colour the surface reflects of its
        // spectrum, with the cosine of the smooth normal.
        let shading = self.scene.scattering_normal(hit, ray.direction) * side;
        let reflected: Vec3 = (0..self.scene.lights.len())
            .map(|i| self.scene.light_spectra[i].reflected * albedo * self.direct_irradiance(i, hit.point, shading))
            .sum();
        if gathers_at(self.scene, depth) {
            points.push(VisiblePoint { point: hit.point, normal: n, weight: tint / PI, albedo, pixel: 0, rough: None });
        }
        let emitted = self.scene.surfaces[hit.object].emitted(ray.direction, hit.normal);
        reflected * (1.0 / PI) + albedo * settings.ambient + emitted
    }

    /// What a rough surface at `point` (normal `normal`, either side) sends
    /// toward the viewer of the lights no ray can meet
    /// ([`Light::hidden_direction`]: spot, point and beam lights, suns of
    /// their own): its BSDF `bsdf` toward each (the light's direction in,
    /// per RGB channel out), in the colour of the light's spectrum, times
    /// the light's irradiance on the side it shines on (with its shadow).
    /// The light of what rays can meet (environments, area lights,
    /// everything lit) comes by the scattered path, so nothing is counted
    /// twice. Polished surfaces have none: their highlights are points.
    fn highlights(&self, (point, normal): (Vec3, Vec3), bsdf: impl Fn(Vec3) -> Vec3) -> Vec3 {
        (0..self.scene.lights.len())
            .filter_map(|i| {
                let wi = self.scene.lights[i].hidden_direction(point)?;
                let f = bsdf(wi);
                let n = if wi.dot(normal) > 0.0 { normal } else { -normal };
                (f != Vec3::ZERO)
                    .then(|| self.scene.light_spectra[i].reflected * f * self.direct_irradiance(i, point, n))
            })
            .sum()
    }

    /// What a rough metal seen along `direction` by a path of band `band`
    /// at `lambda_nm` reflects of the lights no ray can meet
    /// ([`Light::hidden_direction`]): its BRDF toward each times the
    /// light's irradiance, in the colour of its spectrum, with its shadow
    /// (zero when polished, whose highlights are points). What rays can
    /// meet comes by the reflected path, so nothing is counted twice.
    pub fn metal_highlights(
        &self,
        direction: Vec3,
        (point, normal): (Vec3, Vec3),
        metal: &MetalOptics,
        band: u16,
        lambda_nm: f32,
    ) -> Vec3 {
        if metal.ggx.is_none() {
            return Vec3::ZERO;
        }
        let n = if direction.dot(normal) < 0.0 { normal } else { -normal };
        self.highlights((point, normal), |wi| metal.reflection(-direction, wi, n, band, lambda_nm, &self.scene.bands))
    }

    /// What rough glass (`face`, facets `ggx`) seen along `direction`
    /// sends toward the viewer of the lights no ray can meet, on both
    /// sides: its BSDF ([`rough_glass_bsdf`]) toward each times the light's
    /// irradiance on the side it shines on, with its shadow; what passes a
    /// tinted sheet keeps its crossing's colour `crossing`.
    pub fn rough_glass_highlights(
        &self,
        direction: Vec3,
        (point, normal): (Vec3, Vec3),
        (face, ggx): (Face, Ggx),
        crossing: Vec3,
    ) -> Vec3 {
        self.highlights((point, normal), |wi| {
            let f = rough_glass_bsdf(-direction, wi, normal, face, ggx);
            let behind = wi.dot(normal) * direction.dot(normal) > 0.0;
            if behind { crossing * f } else { Vec3::splat(f) }
        })
    }

    /// Irradiance from light `index` at `p` (unit normal `n`), zero when in
    /// shadow (shadow rays only where the effect plan asks for them). An
    /// area light's drawn shadow point takes its share only, which can leave
    /// a pass's irradiance negative in a penumbra ([`crate::plan::area_aims`]);
    /// so can a drawn sun's shadow ([`crate::plan::drawn_suns`]).
    pub fn direct_irradiance(&self, index: usize, p: Vec3, n: Vec3) -> f32 {
        let shadows = self.scene.plan.shadows[index].on;
        match &self.scene.lights[index] {
            Light::Spot { position, direction, cone_deg, inner_cone_deg, power, range, .. } => {
                let cone = SpotCone::new(*cone_deg, *inner_cone_deg);
                let Some((l, dist, cos_s)) = self.toward_light(*position, p, n, shadows) else {
                    return 0.0;
                };
                let falloff = cone.falloff((-l).dot(direction.normalize())) * range_window(dist, *range);
                if falloff == 0.0 {
                    return 0.0;
                }
                let intensity = power / (2.0 * PI * cone.measure());
                falloff * (intensity * cos_s / (dist * dist))
            }
            Light::Point { position, power, range, .. } => {
                let Some((_, dist, cos_s)) = self.toward_light(*position, p, n, shadows) else {
                    return 0.0;
                };
                range_window(dist, *range) * (power / (4.0 * PI) * cos_s / (dist * dist))
            }
            Light::Beam { position, direction, radius, power, .. } => {
                let axis = direction.normalize();
                let along = (p - *position).dot(axis);
                let cos_s = -axis.dot(n);
                if along <= 0.0 || cos_s <= 0.0 || (p - *position - axis * along).length() > *radius {
                    return 0.0;
                }
                if shadows && self.scene.occluded(offset_origin(p, n, -axis), -axis, along) {
                    return 0.0;
                }
                power / (PI * radius * radius) * cos_s
            }
            Light::Sun { direction, irradiance, mean_toward, .. } => {
                let to_sun = -direction.normalize();
                let cos_s = to_sun.dot(n);
                let lit = || {
                    cos_s > 0.0 && !(shadows && self.scene.occluded(offset_origin(p, n, to_sun), to_sun, f32::INFINITY))
                };
                match mean_toward.map(|m| m.dot(n)) {
                    // A drawn sun's control variate (plan::drawn_suns): the
                    // mean unshadowed light, less the draw's where it is not lit.
                    Some(mean_cos) if mean_cos > 0.0 => match lit() {
                        true => irradiance * mean_cos,
                        false => irradiance * (mean_cos - cos_s),
                    },
                    _ if lit() => irradiance * cos_s,
                    _ => 0.0,
                }
            }
            Light::Area { vertices, power, aim, .. } => {
                if !in_front_of(p, *vertices) {
                    return 0.0;
                }
                let seen = triangle_view(p, n, *vertices);
                if seen.projected_solid_angle <= 0.0 {
                    return 0.0;
                }
                let unblocked = power / (PI * area(vertices)) * seen.projected_solid_angle;
                let blocked = |target: Vec3| {
                    let l = (target - p).normalize();
                    let origin = offset_origin(p, n, l);
                    self.scene.occluded(origin, l, (target - origin).length() * (1.0 - CONNECTION_REL))
                };
                match aim {
                    _ if !shadows => unblocked,
                    // The pass's point: what it stands for goes where it is hidden.
                    Some(st) => match shadow_sample(*vertices, *power, *st, p, n) {
                        Some((y, share)) if blocked(y) => unblocked - share,
                        _ => unblocked,
                    },
                    None if blocked(seen.centre) => 0.0,
                    None => unblocked,
                }
            }
            Light::Environment { .. } => unreachable!("an environment shines as its suns (PreparedScene::lights)"),
        }
    }

    /// Direction to a point light, its distance and the surface cosine, or
    /// `None` when the light is behind the surface or blocked.
    fn toward_light(&self, light: Vec3, p: Vec3, n: Vec3, shadows: bool) -> Option<(Vec3, f32, f32)> {
        let to = light - p;
        let dist = to.length();
        let l = to / dist;
        let cos_s = l.dot(n);
        if cos_s <= 0.0 {
            return None;
        }
        if !shadows {
            return Some((l, dist, cos_s));
        }
        let origin = offset_origin(p, n, l);
        (!self.scene.occluded(origin, l, (light - origin).length())).then_some((l, dist, cos_s))
    }
}

/// One of the hero paths a sampled view path splits into at the first
/// dispersive glass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeroViewPath {
    /// Which of the M paths (it numbers the path's Fresnel choices).
    pub hero: u32,
    /// Its band.
    pub band: u16,
    /// Its wavelength (`None`: the band's own index).
    pub lambda_nm: Option<f32>,
    /// Its RGB weight: (N/M)·C_b, or the colour of its wavelength over M
    /// when paths take their colour from it.
    pub weight: Vec3,
}

/// The M hero paths (as many as a hero photon's, [`WavelengthSampling::paths`])
/// a sampled view path with spectrum number `u` splits into: path i in band
/// ⌊v·N⌋ at v = (i + u)/M ([`spectrum_share`]), weighted (N/M)·C_b, since
/// each band falls to path i with probability M/N (or, coloured by its
/// wavelength, by that colour over M: v is uniform over the spectrum).
pub fn hero_view_paths(scene: &PreparedScene, u: f32) -> impl Iterator<Item = HeroViewPath> + '_ {
    let n = scene.bands.len();
    let m = WavelengthSampling::Hero.paths(n);
    (0..m).map(move |hero| {
        let (band, lambda_nm) = spectrum_share(scene, u, hero, m);
        let weight = match (lambda_nm, scene.bands.wavelength_colours()) {
            (Some(lambda), Some(colours)) => colours.at(lambda) / m as f32,
            _ => scene.bands.band(usize::from(band)).weight * (n as f32 / m as f32),
        };
        HeroViewPath { hero, band, lambda_nm, weight }
    })
}

/// Whether a diffuse hit that a view path reaches after `depth` specular
/// bounces gathers photons: when the plan traces caustics or indirect
/// light, unless light tracing brings them there (it does for every diffuse surface the camera
/// sees directly, depth 0: see [`crate::photons::light_tracing`]).
pub fn gathers_at(scene: &PreparedScene, depth: u32) -> bool {
    scene.plan.photon_pass() && (depth > 0 || !scene.scene.render.light_tracing)
}

/// Whether a view path that meets rough metal or glass of facets `ggx`
/// (`None`: polished there) after `depth` bounces leaves a visible point
/// there that gathers the photons met on it
/// ([`crate::photons::gather::gather_rough`]), unless it is behind one
/// already ([`behind_rough`]): the plan gathers on rough surfaces, these
/// facets are rough enough ([`Ggx::gathers`]; below that light tracing
/// alone brings that light, where the camera sees the surface), and light
/// tracing does not bring it (it does where the camera sees the surface
/// directly, depth 0).
pub fn gathers_on_rough(scene: &PreparedScene, depth: u32, ggx: Option<Ggx>) -> bool {
    scene.plan.rough_gathers && ggx.is_some_and(|g| g.gathers()) && (depth > 0 || !scene.scene.render.light_tracing)
}

/// Whether the paths a view path sends on from rough metal or glass of
/// facets `ggx` that it meets after `depth` bounces (`behind`: it is
/// behind such a surface already) add no highlights of the rough surfaces
/// they meet and leave no visible points on them: the hidden lights' light
/// that reaches this surface after mirrors, metals, glass or rough
/// surfaces is counted here, by light tracing ([`traces_behind_rough`],
/// where the camera sees it directly) or by its visible point
/// ([`gathers_on_rough`]), so it is not counted again behind it.
pub fn behind_rough(scene: &PreparedScene, behind: bool, depth: u32, ggx: Option<Ggx>) -> bool {
    behind || (ggx.is_some() && ((depth == 0 && traces_behind_rough(scene)) || gathers_on_rough(scene, depth, ggx)))
}

/// What a view ray of `band` keeps of each RGB channel on a segment of
/// length `t` along `dir` that ends on `glass` (outward `normal` there):
/// the Beer–Lambert transmittance when the segment ran inside coloured
/// glass, else all of it.
pub fn glass_transmittance(glass: &DielectricOptics, dir: Vec3, normal: Vec3, t: f32, band: u16) -> Vec3 {
    match &glass.absorption {
        Some(absorption) if dir.dot(normal) > 0.0 && !glass.thin => absorption.view_transmittance(band, t),
        _ => Vec3::ONE,
    }
}

/// Traces every pixel's view rays with the scalar reference (pass `pass`'s
/// own paths when [`crate::model::scene::ViewPaths::per_pass`]; the same for every pass
/// otherwise): the image without caustics and the visible points that need
/// them, reporting progress after every row.
pub fn visible_points(scene: &PreparedScene, pass: u32, progress: &mut dyn Progress) -> VisiblePoints {
    let ctx = ViewContext::new(scene);
    let (w, h) = (scene.scene.render.width, scene.scene.render.height);
    let sampled = scene.scene.render.view_paths.per_pass();
    let mut out = VisiblePoints { base: Image::new(w, h), points: Vec::new() };
    for y in 0..h {
        for x in 0..w {
            out.base.pixels[(y * w + x) as usize] = match sampled {
                true => ctx.sampled_pixel(x, y, pass, &mut out.points),
                false => ctx.pixel(x, y, &mut out.points),
            };
        }
        progress.advance(Stage::View, u64::from(y) + 1, u64::from(h));
    }
    out
}
