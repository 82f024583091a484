//! Packet view rays: the core's view pass (`prismatic_core::render::view`), eight
//! rays per packet, threads over tiles.
//!
//! A tile's primary rays go eight pixels to a packet. Where the reference
//! recurses (mirrors, metals, the two Fresnel branches at glass, rough or not, one ray per band at
//! the first dispersive glass) this tracer queues the next rays with the
//! weight and RGB tint they carry and the pixel they belong to, and traces
//! the queue in packets of eight too, until it is empty: the same sum over
//! paths as the reference, in a different order. Shading (direct light with
//! shadow-ray packets, checker albedo) is lane-parallel; each diffuse hit
//! that needs the caustic becomes a visible point. A ray that crossed
//! coloured glass keeps the reference's transmittance in its tint.
//!
//! Per-pass view paths (`ViewPaths::Hero` and `ViewPaths::Sampled`) queue
//! one ray per pixel and at most one follow-up per ray (M at the split into
//! hero paths): the reference's start (the centre, or jittered), Fresnel
//! choices and hero bands, from the same [`PixelSampler`] numbers.

use crate::form_factor::triangle_view;
use crate::intersect::{HitX8, intersect_scene, occluded, scattering_normals};
use crate::optics::{offset_origin, split_dielectric};
use crate::ray::{RayX8, limit_where};
use crate::simd::{Vec3x8, ge, gt, lt};
use glam::Vec3;
use prismatic_core::Image;
use prismatic_core::geometry::camera::PinholeCamera;
use prismatic_core::geometry::primitive::Ray;
use prismatic_core::model::light_range::range_window;
use prismatic_core::model::photon::WHITE_BAND;
use prismatic_core::model::scene::Light;
use prismatic_core::optics::fresnel::reflect;
use prismatic_core::optics::microfacet::Ggx;
use prismatic_core::optics::scatter::{
    self, Face, scatter_dielectric, scatter_metal, scatter_rough_dielectric, split_rough_dielectric,
};
use prismatic_core::optics::surface::{DielectricOptics, Surface};
use prismatic_core::photons::path::stored_wavelength;
use prismatic_core::plan::area::area;
use prismatic_core::plan::area_aims::on_triangle;
use prismatic_core::plan::prepared::Hit;
use prismatic_core::plan::prepared::PreparedScene;
use prismatic_core::render::view::{
    HeroViewPath, ViewContext, behind_rough, gathers_at, gathers_on_rough, glass_transmittance, hero_view_paths,
};
use prismatic_core::render::visible::{VisiblePoint, VisiblePoints};
use prismatic_core::sampling::pixel_sample::PixelSampler;
use prismatic_core::sampling::spot_cone::SpotCone;
use prismatic_core::util::tolerance::{CONNECTION_REL, MIN_VIEW_WEIGHT};
use rayon::prelude::*;
use std::f32::consts::PI;
use wide::f32x8;

/// Rows per tile (a unit of work for one thread).
pub const TILE_ROWS: u32 = 4;

/// A ray waiting to be traced, with what it carries back to its pixel.
#[derive(Clone, Copy, Debug)]
struct ViewRay {
    origin: Vec3,
    dir: Vec3,
    /// The path's share of the pixel (Fresnel factors, times the band's
    /// largest weight after a split), for pruning as the reference does.
    weight: f32,
    /// RGB factor of the path (Fresnel factors times band weights).
    tint: Vec3,
    band: u16,
    /// The path's wavelength (`None`: its band's own index).
    lambda_nm: Option<f32>,
    depth: u32,
    pixel: u32,
    /// A sampled path's numbers, and its hero path (0 before the split).
    sampler: Option<PixelSampler>,
    hero: u32,
    /// The numbers of its rough metals' facets (pass 0's for centre rays).
    facets: PixelSampler,
    /// It left a rough surface where the hidden lights' light is counted,
    /// light traced or gathered: it shows no highlights and leaves no rough
    /// visible points (the reference's `ViewPath`, [`behind_rough`]).
    behind_rough: bool,
}

/// Traces the view rays (pass `pass`'s own paths when
/// [`prismatic_core::model::scene::ViewPaths::per_pass`]): the image
/// without caustics and the visible points (tile by tile, so their order
/// does not depend on the thread count).
pub fn visible_points(scene: &PreparedScene, pass: u32) -> VisiblePoints {
    let r = &scene.scene.render;
    let camera = PinholeCamera::new(&scene.scene.camera, r.width, r.height);
    let mut image = Image::new(r.width, r.height);
    let row = r.width as usize;
    let tile_pixels = row * TILE_ROWS as usize;
    let (sampled, jittered) = (r.view_paths.per_pass(), r.view_paths.jittered());
    let tiles: Vec<Vec<VisiblePoint>> = image
        .pixels
        .par_chunks_mut(tile_pixels)
        .enumerate()
        .map(|(tile, pixels)| {
            let y0 = tile as u32 * TILE_ROWS;
            let mut queue: Vec<ViewRay> = Vec::with_capacity(pixels.len());
            for (k, _) in pixels.iter().enumerate().rev() {
                let (x, y) = ((k % row) as u32, y0 + (k / row) as u32);
                let sampler = sampled.then(|| PixelSampler::new(r.seed, y * r.width + x, pass));
                let facets = sampler.unwrap_or_else(|| PixelSampler::new(r.seed, y * r.width + x, 0));
                let ray = match sampler {
                    Some(s) if jittered => camera.ray_through(x, y, s.jitter()),
                    _ => camera.ray(x, y),
                };
                queue.push(ViewRay {
                    origin: ray.origin,
                    dir: ray.direction,
                    weight: 1.0,
                    tint: Vec3::ONE,
                    band: WHITE_BAND,
                    lambda_nm: None,
                    depth: 0,
                    pixel: k as u32,
                    sampler,
                    hero: 0,
                    facets,
                    behind_rough: false,
                });
            }
            let view = ViewContext::new(scene);
            let first_pixel = (tile * tile_pixels) as u32;
            let mut shader = Shader { scene, view, points: Vec::new(), first_pixel };
            let mut sum = vec![Vec3::ZERO; pixels.len()];
            while !queue.is_empty() {
                let take = queue.len().min(8);
                let mut batch = [queue[queue.len() - 1]; 8];
                batch[..take].copy_from_slice(&queue[queue.len() - take..]);
                queue.truncate(queue.len() - take);
                shader.trace_packet(&batch[..take], &mut queue, &mut sum);
            }
            for (p, s) in pixels.iter_mut().zip(sum) {
                *p = s * scene.camera_response();
            }
            shader.points
        })
        .collect();
    VisiblePoints { base: image, points: tiles.concat() }
}

struct Shader<'a> {
    scene: &'a PreparedScene,
    /// The core's view pass, for what this tracer takes ray by ray from it.
    view: ViewContext<'a>,
    /// The tile's visible points.
    points: Vec<VisiblePoint>,
    /// The tile's first pixel (ray pixels are relative to it).
    first_pixel: u32,
}

impl Shader<'_> {
    /// Traces up to eight queued rays: adds what they see to their pixels
    /// and queues the rays they spawn.
    fn trace_packet(&mut self, rays: &[ViewRay], queue: &mut Vec<ViewRay>, sum: &mut [Vec3]) {
        let settings = &self.scene.scene.render;
        let lane = |i: usize| &rays[i.min(rays.len() - 1)];
        let ray = RayX8 {
            origin: Vec3x8::from_lanes(&core::array::from_fn(|i| lane(i).origin)),
            dir: Vec3x8::from_lanes(&core::array::from_fn(|i| lane(i).dir)),
        };
        let hit = intersect_scene(self.scene, &ray, f32x8::splat(f32::INFINITY));
        let point = ray.at(hit.t);
        // Sampled paths take one Fresnel branch at glass, the others both.
        let one_branch = settings.view_paths.jittered();
        let object = hit.object.to_array();
        // Diffuse lanes are shaded together; the rest one by one (misses, mirrors, glass).
        let mut diffuse = [0.0f32; 8];
        // The most a blended metal's specular part reflects (1: a whole
        // metal's); its diffuse part is shaded here.
        let mut specular_share = [1.0f32; 8];
        for (i, r) in rays.iter().enumerate() {
            if object[i] < 0.0 {
                sum[r.pixel as usize] += r.tint * self.scene.background(r.dir);
                continue;
            }
            match &self.scene.surfaces[object[i] as usize] {
                Surface::Diffuse { .. } => diffuse[i] = f32::from_bits(u32::MAX),
                Surface::Metal(metal) if metal.is_blended() => {
                    let at = Hit {
                        t: hit.t.to_array()[i],
                        point: point.lane(i),
                        normal: hit.normal.lane(i),
                        object: object[i] as usize,
                        triangle: hit.triangle.to_array()[i] as u32,
                    };
                    let metalness = self.scene.metalness_at(metal, &at);
                    let toward_eye = r.dir.dot(self.scene.scattering_normal(&at, r.dir)).abs();
                    specular_share[i] = metalness.specular_share();
                    let lambda_nm = stored_wavelength(&self.scene.bands, r.band, r.lambda_nm);
                    let share = self.scene.diffuse_share_at(metal, &at, metalness, toward_eye, r.band, lambda_nm);
                    sum[r.pixel as usize] += self.blended_diffuse_part(r, &at, share);
                }
                _ => {}
            }
        }
        let diffuse = f32x8::new(diffuse);
        if diffuse.any() {
            let radiance = self.shade_diffuse(rays, &ray, &hit, point, diffuse);
            for i in lanes(diffuse) {
                sum[rays[i].pixel as usize] += rays[i].tint * radiance[i];
            }
        }
        // Mirrors, metals and glass scatter about the shading normal.
        let normal = scattering_normals(self.scene, &hit, point, ray.dir, !diffuse);
        let mut at_glass = 0u32;
        let mut glass_ior = [1.0f32; 8];
        let mut glass_thin = [0.0f32; 8];
        let mut crossing = [Vec3::ONE; 8];
        // The rays as they arrive: what coloured glass left of those that crossed it.
        let mut arrived = [rays[0]; 8];
        arrived[..rays.len()].copy_from_slice(rays);
        let (t, triangle) = (hit.t.to_array(), hit.triangle.to_array());
        for (i, r) in arrived[..rays.len()].iter_mut().enumerate() {
            if object[i] < 0.0 || diffuse.to_bitmask() & (1 << i) != 0 || r.depth >= self.scene.plan.max_depth {
                continue;
            }
            let (p, n) = (point.lane(i), normal.lane(i));
            let surface = &self.scene.surfaces[object[i] as usize];
            // Rough glass's facets here (a metal's come with its colour, `metal_at`).
            let facets = match surface {
                Surface::Dielectric(_) => self.scene.facets_at(object[i] as usize, triangle[i] as u32, p),
                _ => None,
            };
            if let Surface::Dielectric(glass) = surface {
                let kept = glass_transmittance(glass, r.dir, hit.normal.lane(i), t[i], r.band);
                r.tint *= kept;
                r.weight *= kept.max_element();
            }
            let r = &*r;
            // A blended metal's specular part, followed where it can add
            // something (its Fresnel holds the metalness).
            let most = specular_share[i];
            if most == 0.0 || (most < 1.0 && r.weight * most <= MIN_VIEW_WEIGHT) {
                continue;
            }
            let at = Hit { t: t[i], point: p, normal: n, object: object[i] as usize, triangle: triangle[i] as u32 };
            // Rough glass's visible point, before a split into bands: one for the ray.
            if let Surface::Dielectric(_) = surface
                && !r.behind_rough
                && gathers_on_rough(self.scene, r.depth, facets)
            {
                self.add_rough_point(r, &at);
            }
            match surface {
                // Band rays at glass: Fresnel and refraction for the whole packet at once, below.
                Surface::Mirror => {
                    let d = reflect(r.dir, n);
                    let origin = scatter::offset_origin(p, n, d);
                    queue.push(ViewRay { origin, dir: d, depth: r.depth + 1, ..*r });
                }
                // A metal's highlights, facet and Fresnel: the core's scalar rules, ray by ray.
                Surface::Metal(metal) => {
                    let metal = &self.scene.metal_at(metal, &at);
                    let lambda_nm = stored_wavelength(&self.scene.bands, r.band, r.lambda_nm);
                    if !r.behind_rough {
                        sum[r.pixel as usize] +=
                            r.tint * self.view.metal_highlights(r.dir, (p, n), metal, r.band, lambda_nm);
                        if gathers_on_rough(self.scene, r.depth, metal.ggx) {
                            self.add_rough_point(r, &at);
                        }
                    }
                    let (u1, u2) = if metal.ggx.is_some() { r.facets.facet(r.hero, r.depth) } else { (0.0, 0.0) };
                    let Some(b) = scatter_metal(r.dir, p, n, metal.ggx, u1, u2) else { continue };
                    let f = metal.specular_tint(b.cos_facet, r.band, lambda_nm, &self.scene.bands) * b.unshadowed;
                    let next = ViewRay {
                        origin: b.ray.origin,
                        dir: b.ray.direction,
                        weight: r.weight * f.max_element(),
                        tint: r.tint * f,
                        depth: r.depth + 1,
                        behind_rough: behind_rough(self.scene, r.behind_rough, r.depth, metal.ggx),
                        ..*r
                    };
                    if next.weight > MIN_VIEW_WEIGHT {
                        queue.push(next);
                    }
                }
                Surface::Dielectric(glass) if r.band == WHITE_BAND && glass.splits_view_rays => match r.sampler {
                    Some(sampler) => {
                        for HeroViewPath { hero, band, lambda_nm, weight: w } in
                            hero_view_paths(self.scene, sampler.spectrum())
                        {
                            let share = r.weight * w.abs().max_element();
                            let tinted = ViewRay { tint: r.tint * w, weight: share, band, lambda_nm, hero, ..*r };
                            let face = self.scene.face(glass, &at, band, lambda_nm);
                            self.at_glass(&tinted, (p, n), (face, glass, facets), one_branch, (queue, sum));
                        }
                    }
                    None => {
                        for (b, info) in self.scene.bands.bands().iter().enumerate() {
                            let share = r.weight * info.weight.abs().max_element();
                            let tinted = ViewRay { tint: r.tint * info.weight, weight: share, band: b as u16, ..*r };
                            let face = self.scene.face(glass, &at, b as u16, None);
                            self.at_glass(&tinted, (p, n), (face, glass, facets), one_branch, (queue, sum));
                        }
                    }
                },
                // A film's reflectance is a complex sum per ray, and rough
                // glass's facets and highlights are per ray: the scalar rules.
                Surface::Dielectric(glass) if glass.film.is_some() || glass.ggx.is_some() => {
                    let face = self.scene.face(glass, &at, r.band, r.lambda_nm);
                    self.at_glass(r, (p, n), (face, glass, facets), one_branch, (queue, sum));
                }
                Surface::Dielectric(glass) => {
                    glass_ior[i] = glass.path_ior(r.band, r.lambda_nm, &self.scene.bands);
                    glass_thin[i] = if glass.thin { f32::from_bits(u32::MAX) } else { 0.0 };
                    crossing[i] = glass.sheet_crossing_rgb(r.band);
                    at_glass |= 1 << i;
                }
                Surface::Diffuse { .. } => unreachable!("shaded above"),
            }
        }
        if at_glass != 0 {
            let glass = (f32x8::new(glass_ior), f32x8::new(glass_thin), crossing);
            spawn_packet_at_glass(&arrived[..rays.len()], at_glass, point, normal, glass, one_branch, queue);
        }
    }

    /// [`spawn_at_glass`] for one ray at `p` (outward normal `n`; the
    /// glass's facets there, `None` where polished), with rough glass's
    /// highlights added to its pixel's `sum`.
    fn at_glass(
        &self,
        r: &ViewRay,
        (p, n): (Vec3, Vec3),
        (face, glass, facets): (Face, &DielectricOptics, Option<Ggx>),
        one_branch: bool,
        (queue, sum): (&mut Vec<ViewRay>, &mut [Vec3]),
    ) {
        let Some(ggx) = facets else {
            spawn_at_glass(r, p, n, (face, glass, facets), one_branch, queue);
            return;
        };
        if !r.behind_rough {
            let crossing = glass.sheet_crossing_rgb(r.band);
            sum[r.pixel as usize] += r.tint * self.view.rough_glass_highlights(r.dir, (p, n), (face, ggx), crossing);
        }
        let behind_rough = behind_rough(self.scene, r.behind_rough, r.depth, facets);
        spawn_at_glass(&ViewRay { behind_rough, ..*r }, p, n, (face, glass, facets), one_branch, queue);
    }

    /// Ray `r`'s visible point on the rough metal or glass at `bent` (its
    /// normal the shading normal), in this tile's list.
    fn add_rough_point(&mut self, r: &ViewRay, bent: &Hit) {
        let point = VisiblePoint::on_rough(bent, r.dir, r.tint * self.scene.camera_response());
        self.points.push(VisiblePoint { pixel: self.first_pixel + r.pixel, ..point });
    }

    /// What ray `r` sees of the diffuse part (its `share`, 1 − m) of the
    /// blended metal at `at`: the core's shading, ray by ray, its visible
    /// point in this tile's list with the pixel's weight.
    fn blended_diffuse_part(&mut self, r: &ViewRay, at: &Hit, share: f32) -> Vec3 {
        if share == 0.0 {
            return Vec3::ZERO;
        }
        let first = self.points.len();
        let ray = Ray { origin: r.origin, direction: r.dir };
        let lit = self.view.shade_diffuse(&ray, at, (r.tint * share, r.depth), &mut self.points);
        for p in &mut self.points[first..] {
            p.weight *= self.scene.camera_response();
            p.pixel = self.first_pixel + r.pixel;
        }
        r.tint * share * lit
    }

    /// Radiance toward the viewer at diffuse hits (lanes in `mask`), less
    /// the caustic, which is left to a visible point per lane (where
    /// light tracing does not bring it).
    fn shade_diffuse(&mut self, rays: &[ViewRay], ray: &RayX8, hit: &HitX8, p: Vec3x8, mask: f32x8) -> [Vec3; 8] {
        let settings = &self.scene.scene.render;
        let facing = lt(ray.dir.dot(hit.normal), f32x8::ZERO);
        let n = Vec3x8::select(facing, hit.normal, -hit.normal);
        let (objects, triangles) = (hit.object.to_array(), hit.triangle.to_array());
        let mut albedo = [Vec3::ZERO; 8];
        for i in lanes(mask) {
            let (pi, ni) = (p.lane(i), n.lane(i));
            albedo[i] = self.scene.albedo_at(objects[i] as usize, triangles[i] as u32, pi, ni);
            if gathers_at(self.scene, rays[i].depth) {
                let weight = rays[i].tint / PI * self.scene.camera_response();
                let pixel = self.first_pixel + rays[i].pixel;
                self.points.push(VisiblePoint { point: pi, normal: ni, weight, albedo: albedo[i], pixel, rough: None });
            }
        }
        // Each light's irradiance, in the colour the surface reflects of its
        // spectrum, with the cosine of the smooth normal.
        let smooth = scattering_normals(self.scene, hit, p, ray.dir, mask);
        let shading = Vec3x8::select(facing, smooth, -smooth);
        let mut reflected = [Vec3::ZERO; 8];
        let lights = self.scene.lights.iter().zip(&self.scene.plan.shadows).zip(&self.scene.light_spectra);
        for ((light, plan), spectrum) in lights {
            let e = self.direct_irradiance(light, plan.on, p, shading, mask).to_array();
            for i in lanes(mask) {
                reflected[i] += spectrum.reflected * albedo[i] * e[i];
            }
        }
        // An emissive surface's own glow, seen from its front.
        let mut glow = [Vec3::ZERO; 8];
        for i in lanes(mask) {
            glow[i] = self.scene.surfaces[objects[i] as usize].emitted(rays[i].dir, hit.normal.lane(i));
        }
        core::array::from_fn(|i| reflected[i] * (1.0 / PI) + albedo[i] * settings.ambient + glow[i])
    }

    /// `ViewContext::direct_irradiance` for eight points (shadow rays if `shadows`).
    fn direct_irradiance(&self, light: &Light, shadows: bool, p: Vec3x8, n: Vec3x8, mask: f32x8) -> f32x8 {
        match light {
            Light::Spot { position, direction, cone_deg, inner_cone_deg, power, range, .. } => {
                let cone = SpotCone::new(*cone_deg, *inner_cone_deg);
                let axis = Vec3x8::splat(direction.normalize());
                let (l, dist, cos_s, visible) = self.toward_light(*position, p, n, mask, shadows);
                let c = (-l).dot(axis);
                let inside = ge(c, f32x8::splat(cone.cos_outer));
                let intensity = f32x8::splat(power / (2.0 * PI * cone.measure()));
                let lit = (visible & inside).select(intensity * cos_s / (dist * dist), f32x8::ZERO);
                if cone.cos_inner == cone.cos_outer && range.is_none() {
                    return lit;
                }
                // The soft edge and the range's window, lane by lane.
                let (c, lit, dist) = (c.to_array(), lit.to_array(), dist.to_array());
                f32x8::new(core::array::from_fn(|i| cone.falloff(c[i]) * range_window(dist[i], *range) * lit[i]))
            }
            Light::Point { position, power, range, .. } => {
                let (_, dist, cos_s, visible) = self.toward_light(*position, p, n, mask, shadows);
                let lit = visible.select(f32x8::splat(power / (4.0 * PI)) * cos_s / (dist * dist), f32x8::ZERO);
                if range.is_none() {
                    return lit;
                }
                let (lit, dist) = (lit.to_array(), dist.to_array());
                f32x8::new(core::array::from_fn(|i| range_window(dist[i], *range) * lit[i]))
            }
            Light::Beam { position, direction, radius, power, .. } => {
                let axis = direction.normalize();
                let (a, c) = (Vec3x8::splat(axis), Vec3x8::splat(*position));
                let along = (p - c).dot(a);
                let cos_s = -a.dot(n);
                let off_axis = (p - c - a * along).length_squared().sqrt();
                let lit = mask & gt(along, f32x8::ZERO) & gt(cos_s, f32x8::ZERO) & !gt(off_axis, f32x8::splat(*radius));
                if !lit.any() || !shadows {
                    return lit.select(f32x8::splat(power / (PI * radius * radius)) * cos_s, f32x8::ZERO);
                }
                let shadow = RayX8 { origin: offset_origin(p, n, -a), dir: -a };
                let blocked = occluded(self.scene, &shadow, limit_where(lit, along));
                (lit & !blocked).select(f32x8::splat(power / (PI * radius * radius)) * cos_s, f32x8::ZERO)
            }
            Light::Sun { direction, irradiance, mean_toward, .. } => {
                let to_sun = Vec3x8::splat(-direction.normalize());
                let cos_s = to_sun.dot(n);
                let mut lit = mask & gt(cos_s, f32x8::ZERO);
                if lit.any() && shadows {
                    let shadow = RayX8 { origin: offset_origin(p, n, to_sun), dir: to_sun };
                    lit = lit & !occluded(self.scene, &shadow, limit_where(lit, f32x8::splat(f32::INFINITY)));
                }
                let e = f32x8::splat(*irradiance);
                let plain = lit.select(e * cos_s, f32x8::ZERO);
                let Some(mean) = mean_toward else { return plain };
                // A drawn sun's control variate (plan::drawn_suns), lane by lane.
                let mean_cos = Vec3x8::splat(*mean).dot(n);
                let varied = lit.select(e * mean_cos, e * (mean_cos - cos_s));
                (mask & gt(mean_cos, f32x8::ZERO)).select(varied, plain)
            }
            Light::Area { vertices, power, aim, .. } => {
                let (angle, centre) = triangle_view(p, n, *vertices);
                let lit = mask & gt(angle, f32x8::ZERO);
                let irradiance = f32x8::splat(power / (PI * area(vertices))) * angle;
                if !lit.any() || !shadows {
                    return lit.select(irradiance, f32x8::ZERO);
                }
                let Some(st) = aim else {
                    let dir = (centre - p).normalize();
                    let origin = offset_origin(p, n, dir);
                    let reach = (centre - origin).length_squared().sqrt() * f32x8::splat(1.0 - CONNECTION_REL);
                    let blocked = occluded(self.scene, &RayX8 { origin, dir }, limit_where(lit, reach));
                    return (lit & !blocked).select(irradiance, f32x8::ZERO);
                };
                // `area_aims::shadow_sample` per lane: the pass's point y, and
                // what it stands for, taken where it is hidden.
                let [a, b, c] = *vertices;
                let y = Vec3x8::splat(on_triangle(*vertices, *st));
                let d = y - p;
                let cos_p = n.dot(d);
                let cos_y = -Vec3x8::splat((b - a).cross(c - a).normalize()).dot(d);
                let r2 = d.length_squared();
                let share = f32x8::splat(power / PI) * cos_p * cos_y.max(f32x8::ZERO) / (r2 * r2);
                let sampled = lit & gt(cos_p, f32x8::ZERO);
                if !sampled.any() {
                    return lit.select(irradiance, f32x8::ZERO);
                }
                let dir = d.normalize();
                let origin = offset_origin(p, n, dir);
                let reach = (y - origin).length_squared().sqrt() * f32x8::splat(1.0 - CONNECTION_REL);
                let blocked = occluded(self.scene, &RayX8 { origin, dir }, limit_where(sampled, reach));
                lit.select(irradiance - (sampled & blocked).select(share, f32x8::ZERO), f32x8::ZERO)
            }
            Light::Environment { .. } => unreachable!("an environment shines as its suns (PreparedScene::lights)"),
        }
    }

    /// Direction to a point light, distance, surface cosine and the lanes
    /// that see it (facing it and not in shadow).
    fn toward_light(
        &self,
        light: Vec3,
        p: Vec3x8,
        n: Vec3x8,
        mask: f32x8,
        shadows: bool,
    ) -> (Vec3x8, f32x8, f32x8, f32x8) {
        let to = Vec3x8::splat(light) - p;
        let dist = to.length_squared().sqrt();
        let l = to / dist;
        let cos_s = l.dot(n);
        let facing = mask & gt(cos_s, f32x8::ZERO);
        if !facing.any() || !shadows {
            return (l, dist, cos_s, facing);
        }
        let origin = offset_origin(p, n, l);
        let reach = (Vec3x8::splat(light) - origin).length_squared().sqrt();
        let blocked = occluded(self.scene, &RayX8 { origin, dir: l }, limit_where(facing, reach));
        (l, dist, cos_s, facing & !blocked)
    }
}

/// Queues the Fresnel-weighted reflection and refraction of `r` at a glass
/// surface point `p` (outward normal `outward`; the path's index and the
/// glass), as the reference recurses (with `one_branch`, a sampled path:
/// the one branch its number chooses, as photons choose; on rough glass,
/// whose `facets` are `Some`, off the facet the ray's numbers draw).
fn spawn_at_glass(
    r: &ViewRay,
    p: Vec3,
    outward: Vec3,
    (face, glass, facets): (Face, &DielectricOptics, Option<Ggx>),
    one_branch: bool,
    queue: &mut Vec<ViewRay>,
) {
    if let Some(ggx) = facets {
        let crossing = glass.sheet_crossing_rgb(r.band);
        let mut follow = |out: Ray, weight: f32, crossed: bool| {
            let f = if crossed { crossing * weight } else { Vec3::splat(weight) };
            let (weight, tint, depth) = (r.weight * f.max_element(), r.tint * f, r.depth + 1);
            if weight > MIN_VIEW_WEIGHT {
                queue.push(ViewRay { origin: out.origin, dir: out.direction, weight, tint, depth, ..*r });
            }
        };
        let facet = r.facets.facet(r.hero, r.depth);
        if let Some(sampler) = r.sampler.filter(|_| one_branch) {
            let u = sampler.branch(r.hero, r.depth);
            if let Some(b) = scatter_rough_dielectric(r.dir, (p, outward), face, ggx, facet, u) {
                follow(b.ray, b.unshadowed, b.crossed);
            }
            return;
        }
        let split = split_rough_dielectric(r.dir, (p, outward), face, ggx, facet);
        if let Some((ray, w)) = split.reflected {
            follow(ray, w, false);
        }
        if let Some((ray, w)) = split.crossed {
            follow(ray, w, true);
        }
        return;
    }
    let crossed = crossed_sheet(glass.sheet_crossing_rgb(r.band));
    if let Some(sampler) = r.sampler.filter(|_| one_branch) {
        let next = scatter_dielectric(r.dir, p, outward, face, sampler.branch(r.hero, r.depth));
        let ray = ViewRay { origin: next.origin, dir: next.direction, depth: r.depth + 1, ..*r };
        queue.push(if glass.thin && next.direction == r.dir { crossed(ray) } else { ray });
        return;
    }
    let split = scatter::split_dielectric(r.dir, p, outward, face);
    let f = split.reflectance;
    if f * r.weight > MIN_VIEW_WEIGHT {
        let (origin, dir) = (split.reflected.origin, split.reflected.direction);
        queue.push(ViewRay { origin, dir, weight: r.weight * f, tint: r.tint * f, depth: r.depth + 1, ..*r });
    }
    let t = 1.0 - f;
    if t * r.weight > MIN_VIEW_WEIGHT
        && let Some(refracted) = split.refracted
    {
        let (origin, dir) = (refracted.origin, refracted.direction);
        queue.push(crossed(ViewRay { origin, dir, weight: r.weight * t, tint: r.tint * t, depth: r.depth + 1, ..*r }));
    }
}

/// What crossing a sheet that keeps `crossing` of each channel does to a
/// view ray (nothing for a clear sheet and for solid glass, whose crossing is 1).
fn crossed_sheet(crossing: Vec3) -> impl Fn(ViewRay) -> ViewRay {
    move |r| ViewRay { weight: r.weight * crossing.max_element(), tint: r.tint * crossing, ..r }
}

/// [`spawn_at_glass`] for the packet lanes in `lanes_at_glass`, the Fresnel
/// factors and directions computed for all eight lanes at once (the
/// glass's index, sheet mask and sheet crossing per lane).
fn spawn_packet_at_glass(
    rays: &[ViewRay],
    lanes_at_glass: u32,
    point: Vec3x8,
    outward: Vec3x8,
    (ior, thin, crossing): (f32x8, f32x8, [Vec3; 8]),
    one_branch: bool,
    queue: &mut Vec<ViewRay>,
) {
    let d = Vec3x8::from_lanes(&core::array::from_fn(|i| rays[i.min(rays.len() - 1)].dir));
    let split = split_dielectric(d, point, outward, ior, thin);
    let f = split.reflectance.to_array();
    let tir = split.tir.to_bitmask();
    let sheets = thin.to_bitmask();
    for (i, r) in rays.iter().enumerate().filter(|(i, _)| lanes_at_glass & (1 << i) != 0) {
        let crossed = crossed_sheet(crossing[i]);
        if let Some(sampler) = r.sampler.filter(|_| one_branch) {
            // The one branch the path's number chooses, as `scatter_dielectric` chooses.
            let (origin, dir) = split.choose(i, sampler.branch(r.hero, r.depth));
            let ray = ViewRay { origin, dir, depth: r.depth + 1, ..*r };
            queue.push(if sheets & (1 << i) != 0 && dir == r.dir { crossed(ray) } else { ray });
            continue;
        }
        if f[i] * r.weight > MIN_VIEW_WEIGHT {
            let (origin, dir) = (split.reflected.0.lane(i), split.reflected.1.lane(i));
            queue.push(ViewRay { origin, dir, weight: r.weight * f[i], tint: r.tint * f[i], depth: r.depth + 1, ..*r });
        }
        let t = 1.0 - f[i];
        if t * r.weight > MIN_VIEW_WEIGHT && tir & (1 << i) == 0 {
            let (origin, dir) = (split.refracted.0.lane(i), split.refracted.1.lane(i));
            let ray = ViewRay { origin, dir, weight: r.weight * t, tint: r.tint * t, depth: r.depth + 1, ..*r };
            queue.push(crossed(ray));
        }
    }
}

/// Indices of the lanes set in `mask`.
#[inline]
fn lanes(mask: f32x8) -> impl Iterator<Item = usize> {
    let bits = mask.to_bitmask();
    (0..8).filter(move |i| bits & (1 << i) != 0)
}
