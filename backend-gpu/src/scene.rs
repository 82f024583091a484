//! A prepared scene encoded into the device buffers of bind group 0:
//! objects, surfaces, lights, bands, geometry records and float tables.
//! Values that the reference derives once (normalised axes, cone cosines,
//! bases, CDFs, per-band indices) are computed here with the core's own
//! functions, so the shaders start from the same bits.

use crate::context::GpuContext;
use crate::layout::{GpuBand, GpuLight, GpuObject, GpuSurface, Params};
use crate::shaders::code;
use crate::shaders::kind::*;
use bytemuck::Pod;
use glam::Vec3;
use prismatic_core::geometry::camera::PinholeCamera;
use prismatic_core::geometry::primitive::{Primitive, basis};
use prismatic_core::geometry::texture::{linear_channel, srgb_to_linear};
use prismatic_core::model::scene::{Filter, Light, MaterialKind, Sampler, Texture, Wrap};
use prismatic_core::model::wavelength_rgb;
use prismatic_core::optics::surface::Surface;
use prismatic_core::photons::indirect::indirect_flux;
use prismatic_core::photons::trace::photon_flux;
use prismatic_core::plan::area::area;
use prismatic_core::plan::projection::Targets;
use prismatic_core::sampling::spot_cone::SpotCone;
use prismatic_core::{BackendError, PreparedScene};
use std::collections::HashMap;

/// A sampler's filter and wraps as surface flags.
fn texture_flags(s: Sampler) -> u32 {
    let wrap = |w: Wrap| match w {
        Wrap::Repeat => WRAP_REPEAT,
        Wrap::ClampToEdge => WRAP_CLAMP_TO_EDGE,
        Wrap::MirroredRepeat => WRAP_MIRRORED_REPEAT,
    };
    let nearest = if s.filter == Filter::Nearest { SURFACE_TEXTURE_NEAREST } else { 0 };
    nearest | wrap(s.wrap_u) << TEXTURE_WRAP_U_SHIFT | wrap(s.wrap_v) << TEXTURE_WRAP_V_SHIFT
}

/// The scene's records, ready to upload.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EncodedScene {
    /// Settings (chunk, grid and pixel fields are filled in per dispatch).
    pub params: Params,
    /// One per object.
    pub objects: Vec<GpuObject>,
    /// One per object.
    pub surfaces: Vec<GpuSurface>,
    /// One per light.
    pub lights: Vec<GpuLight>,
    /// One per band.
    pub bands: Vec<GpuBand>,
    /// Convex faces, triangles and projection targets.
    pub geometry: Vec<[f32; 4]>,
    /// Per-band indices, n(λ) curves, CDFs.
    pub tables: Vec<f32>,
}

fn v3(v: Vec3) -> [f32; 3] {
    v.to_array()
}

fn v4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

/// Marks the record `l` of scene light `light` (whose emitter a sun's beam
/// is) as a sun with its drawn suns' mean direction (zero: not drawn).
fn mark_sun(l: &mut GpuLight, light: &Light) {
    if let Light::Sun { mean_toward, .. } = light {
        l.sun = 1;
        l.mean_toward = v3(mean_toward.unwrap_or(Vec3::ZERO));
    }
}

impl EncodedScene {
    /// The scene's tables (indices, spectra, textures, the environment
    /// map) fit one storage binding of `device`; otherwise what to shrink.
    pub fn fits(&self, device: &wgpu::Device) -> Result<(), BackendError> {
        let (bytes, limit) = (self.tables.len() as u64 * 4, device.limits().max_storage_buffer_binding_size);
        if bytes <= limit {
            return Ok(());
        }
        Err(BackendError::OutOfMemory(format!(
            "the scene's textures and environment map take {} MiB, more than this device binds at once ({} MiB): \
             use smaller images",
            bytes >> 20,
            limit >> 20
        )))
    }

    /// Encodes `scene`.
    pub fn new(scene: &PreparedScene) -> Self {
        let mut e = EncodedScene::default();
        // Each image once, however many objects show it (keyed by its
        // shared texels and whether they are read as sRGB).
        let mut textures: HashMap<(*const u32, bool), u32> = HashMap::new();
        for (i, (prim, normals)) in scene.primitives.iter().zip(&scene.vertex_normals).enumerate() {
            let mut o = e.object(prim);
            // A smooth mesh's normal records follow its own (so `rb` is
            // never NO_VERTEX_NORMALS, the default 0, for one).
            if o.kind == OBJECT_MESH && !normals.is_empty() {
                o.rb = f32::from_bits(e.geometry.len() as u32);
                e.geometry.extend(normals.iter().flat_map(|n| [v4(n.n0, 0.0), v4(n.d1, 0.0), v4(n.d2, 0.0)]));
            }
            // A normal-mapped mesh's map records follow too (so `ra` is
            // never NO_NORMAL_MAP): the image, the scale, then per triangle
            // its texture coordinates and tangents (scattering_normal).
            let map = &scene.scene.materials[scene.scene.objects[i].material].normal_map;
            if let (Some(map), OBJECT_MESH) = (map, o.kind) {
                let t = &map.texture;
                let first = *textures.entry((t.texels.as_ptr(), false)).or_insert_with(|| e.texture(t, false));
                o.ra = f32::from_bits(e.geometry.len() as u32);
                let bits = [first, t.width, t.height, texture_flags(t.sampler)].map(f32::from_bits);
                e.geometry.extend([bits, [map.scale, 0.0, 0.0, 0.0]]);
                for (uv, k) in scene.texture_uvs[i].iter().zip(&scene.normal_tangents[i]) {
                    e.geometry.extend([
                        [uv.uv0.x, uv.uv0.y, uv.du1.x, uv.du1.y],
                        [uv.du2.x, uv.du2.y, 0.0, 0.0],
                        v4(k.t0, k.sign),
                        v4(k.d1, 0.0),
                        v4(k.d2, 0.0),
                    ]);
                }
            }
            e.objects.push(o);
        }
        for (i, (surface, uvs)) in scene.surfaces.iter().zip(&scene.texture_uvs).enumerate() {
            let mut s = e.surface(surface);
            // A base colour (sRGB), or a metal's or rough glass's roughness map (linear).
            let texture = match surface {
                Surface::Diffuse { texture: Some(t), .. } => Some((t, true)),
                Surface::Metal(_) | Surface::Dielectric(_) => {
                    scene.scene.materials[scene.scene.objects[i].material].roughness_map.as_ref().map(|t| (t, false))
                }
                _ => None,
            };
            if let Some((t, srgb)) = texture {
                s.flags |= SURFACE_HAS_TEXTURE | texture_flags(t.sampler);
                s.texture_width = t.width;
                s.texture_height = t.height;
                s.texture_first = *textures.entry((t.texels.as_ptr(), srgb)).or_insert_with(|| e.texture(t, srgb));
            }
            // A metal's colour texture, its reference in the checker's fields (a metal has no checker).
            if let MaterialKind::Metal { texture: Some(t), .. } =
                &scene.scene.materials[scene.scene.objects[i].material].kind
            {
                s.flags |= SURFACE_HAS_COLOUR_MAP;
                let first = *textures.entry((t.texels.as_ptr(), true)).or_insert_with(|| e.texture(t, true));
                s.checker_albedo = [first, t.width, t.height].map(f32::from_bits);
                s.checker_size = f32::from_bits(texture_flags(t.sampler));
            }
            // A film's maps: the film's record again, then the minimum
            // thickness and each map's reference (start, width, height and
            // sampler flags, as bits; a missing one's unread).
            let material = &scene.scene.materials[scene.scene.objects[i].material];
            let (filmed, layered) =
                (s.flags & SURFACE_HAS_FILM != 0, s.kind == SURFACE_METAL && s.checker_offset[1] > 0.0);
            // A map's reference (start, width, height and sampler flags, as
            // bits; a missing one's unread), its flag set.
            let mut reference = |t: &Option<Texture>, flag: u32, srgb: bool| match t {
                Some(t) => {
                    s.flags |= flag;
                    let first = *textures.entry((t.texels.as_ptr(), srgb)).or_insert_with(|| e.texture(t, srgb));
                    [first, t.width, t.height, texture_flags(t.sampler)].map(f32::from_bits)
                }
                None => [0.0; 4],
            };
            // A film's maps: the film's record again, then the minimum
            // thickness and each map's reference.
            let film_maps = material.film_map.as_ref().filter(|_| filmed).map(|map| {
                let thickness = reference(&map.thickness, SURFACE_FILM_THICKNESS_MAP, false);
                (map.min_nm, thickness, reference(&map.factor, SURFACE_FILM_FACTOR_MAP, false))
            });
            // A metal's layer's maps: the unclipped F0, then each map's
            // reference (the weight's, the colour's).
            let layer_maps = material.specular_map.as_ref().filter(|_| layered).map(|map| {
                let weight = reference(&map.weight, SURFACE_SPECULAR_MAP, false);
                (map.color_f0, weight, reference(&map.color, SURFACE_SPECULAR_COLOUR_MAP, true))
            });
            if let Some((min_nm, thickness, factor)) = film_maps {
                let film = s.film_first as usize;
                let record: [f32; 3] = e.tables[film..film + 3].try_into().expect("a film's record");
                s.film_first = e.tables.len() as u32;
                e.tables.extend(record.into_iter().chain([min_nm]).chain(thickness).chain(factor));
            }
            if let Some((color_f0, weight, color)) = layer_maps {
                s.absorption_first = e.tables.len() as u32;
                e.tables.extend(v4(color_f0, 0.0).into_iter().chain(weight).chain(color));
            }
            let maps = SURFACE_FILM_THICKNESS_MAP | SURFACE_FILM_FACTOR_MAP | SURFACE_SPECULAR_MAPS;
            if !uvs.is_empty() && s.flags & (SURFACE_HAS_TEXTURE | SURFACE_HAS_COLOUR_MAP | maps) != 0 {
                s.uv_first = e.geometry.len() as u32;
                for uv in uvs {
                    e.geometry.extend([[uv.uv0.x, uv.uv0.y, uv.du1.x, uv.du1.y], [uv.du2.x, uv.du2.y, 0.0, 0.0]]);
                }
            }
            e.surfaces.push(s);
        }
        let light_cdf = e.tables.len() as u32;
        e.tables.extend_from_slice(&scene.light_cdf);
        for (i, (light, emitter)) in scene.lights.iter().zip(&scene.emitters).enumerate() {
            let shadows = scene.plan.shadows.get(i).is_some_and(|s| s.on);
            let mut l = e.light(emitter, scene.plan.projections.get(i).and_then(Option::as_ref), shadows);
            let spectrum = &scene.light_spectra[i];
            [l.reflected_r, l.reflected_g, l.reflected_b] = spectrum.reflected.to_cols_array_2d();
            if !spectrum.is_uniform() {
                let (cdf, start, width) = spectrum.entries();
                l.spectrum_len = cdf.len() as u32;
                l.spectrum_first = e.tables.len() as u32;
                for column in [cdf, start, width, &spectrum.band_shares[..]] {
                    e.tables.extend_from_slice(column);
                }
            }
            mark_sun(&mut l, light);
            e.lights.push(l);
        }
        for band in scene.bands.bands() {
            e.bands.push(GpuBand {
                weight: v3(band.weight),
                lambda_nm: band.lambda_nm,
                lo_nm: band.interval_nm.0,
                hi_nm: band.interval_nm.1,
                max_weight: band.weight.abs().max_element(),
                _pad: 0.0,
            });
        }
        let colours = scene.bands.wavelength_colours().cloned().unwrap_or_default();
        for (i, row) in colours.rows().iter().enumerate() {
            let lambda_nm = wavelength_rgb::FIRST_NM + wavelength_rgb::STEP_NM * i as f32;
            e.bands.push(GpuBand {
                weight: v3(*row),
                lambda_nm,
                max_weight: row.abs().max_element(),
                ..GpuBand::default()
            });
        }
        let primaries = scene.bands.reflectance_primaries().cloned().unwrap_or_default();
        for (i, row) in primaries.rows().iter().enumerate() {
            let lambda_nm = wavelength_rgb::FIRST_NM + wavelength_rgb::STEP_NM * i as f32;
            e.bands.push(GpuBand { weight: v3(*row), lambda_nm, max_weight: row.max_element(), ..GpuBand::default() });
        }
        let r = &scene.scene.render;
        let camera = PinholeCamera::new(&scene.scene.camera, r.width, r.height);
        e.params = Params {
            seed: r.seed,
            band_count: scene.bands.len() as u32,
            colour_by_wavelength: u32::from(scene.bands.wavelength_colours().is_some()),
            max_depth: scene.plan.max_depth,
            wavelengths: code::wavelengths(r.wavelengths),
            photon_sequence: code::photon_sequence(r.photon_sequence),
            object_count: e.objects.len() as u32,
            light_count: e.lights.len() as u32,
            light_cdf,
            estimator: code::estimator(r.estimator),
            width: r.width,
            height: r.height,
            flux: photon_flux(scene),
            caustic_photons: scene.caustic_photons(),
            indirect_flux: indirect_flux(scene),
            radius: r.radius,
            inv_cell: 1.0 / (2.0 * r.radius),
            exposure: r.exposure,
            white_balance: v3(scene.white_balance),
            ambient: [r.ambient; 3],
            light_tracing: u32::from(r.light_tracing),
            rough_records: u32::from(scene.plan.rough_records),
            rough_gathers: u32::from(scene.plan.rough_gathers),
            background: v3(r.background),
            splat_scale: prismatic_core::photons::light_tracing::importance_scale(r.exposure, &camera),
            cam_origin: v3(camera.origin),
            cam_right: v3(camera.right),
            cam_down: v3(camera.down),
            cam_corner: v3(camera.corner),
            cam_forward: v3(camera.forward),
            view_seed: r.seed,
            view_paths: code::view_paths(r.view_paths),
            ..Params::default()
        };
        if let Some(env) = &scene.environment {
            e.params.env_strength = env.strength;
            e.params.env_first = e.tables.len() as u32;
            (e.params.env_width, e.params.env_height, e.params.env_turn) = (env.map.width, env.map.height, env.turn);
            e.tables.extend(env.map.texels.iter().flat_map(|t| t.to_array()));
        }
        e
    }

    fn object(&mut self, prim: &Primitive) -> GpuObject {
        let first = self.geometry.len() as u32;
        let o = GpuObject { first, ..GpuObject::default() };
        match prim {
            Primitive::Sphere { center, radius } => GpuObject { kind: OBJECT_SPHERE, a: v3(*center), ra: *radius, ..o },
            Primitive::Plane { point, normal } => GpuObject { kind: OBJECT_PLANE, a: v3(*point), n: v3(*normal), ..o },
            Primitive::Disk { center, normal, radius2, inner_radius2 } => {
                GpuObject { kind: OBJECT_DISK, a: v3(*center), n: v3(*normal), ra: *radius2, rb: *inner_radius2, ..o }
            }
            Primitive::Convex { faces } => {
                self.geometry.extend(faces.iter().map(|f| v4(f.normal, f.offset)));
                GpuObject { kind: OBJECT_CONVEX, count: faces.len() as u32, ..o }
            }
            Primitive::Mesh(bvh) => {
                for n in &bvh.nodes {
                    self.geometry.extend([v4(n.lo, f32::from_bits(n.first)), v4(n.hi, f32::from_bits(n.count))]);
                }
                let second = self.geometry.len() as u32;
                for t in &bvh.triangles {
                    self.geometry.extend([v4(t.v0, 0.0), v4(t.e1, 0.0), v4(t.e2, 0.0), v4(t.normal, 0.0)]);
                }
                GpuObject { kind: OBJECT_MESH, count: bvh.triangles.len() as u32, second, ..o }
            }
        }
    }

    fn surface(&mut self, surface: &Surface) -> GpuSurface {
        match surface {
            Surface::Diffuse { albedo, checker, emission, .. } => {
                let mut s = GpuSurface {
                    kind: SURFACE_DIFFUSE,
                    albedo: v3(*albedo),
                    emission: v3(*emission),
                    ..GpuSurface::default()
                };
                if let Some(c) = checker {
                    s.flags |= SURFACE_HAS_CHECKER;
                    s.checker_albedo = v3(c.albedo);
                    s.checker_size = c.size;
                    s.checker_offset = v3(c.offset);
                }
                s
            }
            Surface::Mirror => GpuSurface { kind: SURFACE_MIRROR, ..GpuSurface::default() },
            Surface::Metal(m) => {
                let mut s = GpuSurface {
                    kind: SURFACE_METAL,
                    albedo: v3(m.f0),
                    white_ior: m.ggx.map_or(0.0, |g| g.alpha),
                    ..GpuSurface::default()
                };
                if m.is_blended() {
                    s.flags |= SURFACE_BLENDED;
                    s.checker_offset[0] = m.metalness.factor;
                    if m.metalness.mapped {
                        s.flags |= SURFACE_METALNESS_MAP;
                    }
                }
                if let Some(layer) = m.metalness.layer {
                    s.absorption = v3(layer.f0);
                    (s.checker_offset[1], s.checker_offset[2]) = (layer.f90, layer.ior);
                }
                if let Some(metal) = m.measured {
                    s.flags |= SURFACE_MEASURED;
                    s.curve_first = self.tables.len() as u32;
                    self.tables.extend(metal.rows().iter().flatten());
                }
                if let Some(film) = &m.film {
                    s.flags |= SURFACE_HAS_FILM;
                    s.film_first = self.tables.len() as u32;
                    self.tables.extend_from_slice(&[film.ior, film.thickness_nm, film.factor]);
                }
                s
            }
            Surface::Dielectric(g) => {
                let mut s = GpuSurface {
                    kind: SURFACE_DIELECTRIC,
                    ior_first: self.tables.len() as u32,
                    white_ior: g.white_ior,
                    albedo: [g.ggx.map_or(0.0, |g| g.alpha), 0.0, 0.0],
                    ..GpuSurface::default()
                };
                self.tables.extend_from_slice(&g.band_ior);
                if g.splits_photons {
                    s.flags |= SURFACE_SPLITS_PHOTONS;
                }
                if g.splits_view_rays {
                    s.flags |= SURFACE_SPLITS_VIEW_RAYS;
                }
                if g.thin {
                    s.flags |= SURFACE_THIN;
                }
                if let Some(film) = &g.film {
                    s.flags |= SURFACE_HAS_FILM;
                    s.film_first = self.tables.len() as u32;
                    self.tables.extend_from_slice(&[film.ior, film.thickness_nm, film.factor]);
                }
                if let Some(a) = &g.absorption {
                    s.flags |= SURFACE_ABSORBS;
                    s.absorption = v3(a.rgb);
                    s.absorption_first = self.tables.len() as u32;
                    self.tables.extend_from_slice(&a.band);
                }
                if let Some(curve) = &g.spectrum {
                    s.flags |= SURFACE_HAS_CURVE;
                    s.curve_first = self.tables.len() as u32;
                    s.curve_len = curve.samples().len() as u32;
                    self.tables.extend_from_slice(curve.samples());
                }
                s
            }
        }
    }

    /// Appends the decoding table (from sRGB, or linear: a normal map's)
    /// and the texels (exact integers r + 256 g + 65536 b) to the tables;
    /// returns where they start.
    fn texture(&mut self, t: &Texture, srgb: bool) -> u32 {
        let first = self.tables.len() as u32;
        self.tables.extend((0..256).map(if srgb { srgb_to_linear } else { linear_channel }));
        self.tables.extend(t.texels.iter().map(|&x| x as f32));
        first
    }

    fn light(
        &mut self,
        light: &Light,
        projection: Option<&prismatic_core::plan::projection::Projection>,
        shadows: bool,
    ) -> GpuLight {
        let mut l = GpuLight { shadows: u32::from(shadows), power: light.power(), ..GpuLight::default() };
        match light {
            Light::Spot { position, direction, cone_deg, inner_cone_deg, range, .. } => {
                let axis = direction.normalize();
                let cone = SpotCone::new(*cone_deg, *inner_cone_deg);
                l.kind = LIGHT_SPOT;
                l.position = v3(*position);
                l.axis = v3(axis);
                l.cos_max = cone.cos_outer;
                l.cos_inner = cone.cos_inner;
                l.range = range.unwrap_or(0.0);
            }
            Light::Point { position, range, .. } => {
                l.kind = LIGHT_POINT;
                l.position = v3(*position);
                l.range = range.unwrap_or(0.0);
            }
            Light::Beam { position, direction, radius, .. } => {
                let axis = direction.normalize();
                let (t, b) = basis(axis);
                l.kind = LIGHT_BEAM;
                l.position = v3(*position);
                l.axis = v3(axis);
                l.tangent = v3(t);
                l.bitangent = v3(b);
                l.radius = *radius;
            }
            Light::Area { vertices: [a, b, c], power, aim, .. } => {
                l.kind = LIGHT_AREA;
                if let Some(st) = aim {
                    (l.aimed, l.aim) = (1, *st);
                }
                l.position = v3(*a);
                l.tangent = v3(*b - *a);
                l.bitangent = v3(*c - *a);
                l.axis = v3((*b - *a).cross(*c - *a).normalize());
                l.radius = power / (core::f32::consts::PI * area(&[*a, *b, *c]));
            }
            Light::Sun { .. } | Light::Environment { .. } => {
                unreachable!("a sun emits as its beam, an environment as its suns' (PreparedScene::emitters)")
            }
        }
        if let Some(p) = projection {
            l.proj_first = self.geometry.len() as u32;
            match &p.targets {
                Targets::Cones { axis, cos_max } => {
                    l.proj_kind = PROJECTION_CONES;
                    self.geometry.extend(axis.iter().zip(cos_max).map(|(a, c)| v4(*a, *c)));
                }
                Targets::Discs { center, radius } => {
                    l.proj_kind = PROJECTION_DISCS;
                    self.geometry.extend(center.iter().zip(radius).map(|(c, r)| v4(*c, *r)));
                }
                Targets::Spheres { center, radius, .. } => {
                    l.proj_kind = PROJECTION_SPHERES;
                    self.geometry.extend(center.iter().zip(radius).map(|(c, r)| v4(*c, *r)));
                }
            }
            l.proj_count = p.cdf.len() as u32;
            l.proj_cdf = self.tables.len() as u32;
            l.proj_scale = p.scale;
            self.tables.extend_from_slice(&p.cdf);
            // A sphere target's probability follows its CDF.
            if let Targets::Spheres { probability, .. } = &p.targets {
                self.tables.extend_from_slice(probability);
            }
        }
        l
    }

    /// Encodes again, in place, the lights of `scene` that change each pass
    /// (this encoding's scene with its lights of another pass,
    /// [`PreparedScene::lights_of_pass`]): each drawn sun's record and its
    /// projection map's targets and CDF, and each area light's aim. Returns
    /// the elements that changed (lights, geometry records, table entries),
    /// or `None` when a projection map changed its size or the pass chose
    /// other emissive triangles (then encode the scene again).
    pub fn point_lights(&mut self, scene: &PreparedScene) -> Option<PointedLights> {
        if scene.drawn_triangles.is_some() {
            // Each chosen light's triangle, spectrum and projection map may differ.
            return None;
        }
        let mut changed = PointedLights::default();
        if scene.draws_aims {
            for (i, light) in scene.emitters.iter().enumerate() {
                if let Light::Area { aim: Some(st), .. } = light {
                    (self.lights[i].aimed, self.lights[i].aim) = (1, *st);
                    changed.lights.push(i);
                }
            }
        }
        let suns = scene.drawn_suns.as_ref().map_or(&[][..], |d| &d.suns[..]);
        for &(i, _) in suns {
            let old = self.lights[i];
            let shadows = old.shadows != 0;
            let mut scratch = EncodedScene::default();
            let mut l = scratch.light(&scene.emitters[i], scene.plan.projections[i].as_ref(), shadows);
            // The same kind and number of targets take the same room.
            if (l.proj_kind, l.proj_count) != (old.proj_kind, old.proj_count) {
                return None;
            }
            let (geometry, tables) = (scratch.geometry.len(), scratch.tables.len());
            (l.proj_first, l.proj_cdf) = (old.proj_first, old.proj_cdf);
            (l.reflected_r, l.reflected_g, l.reflected_b) = (old.reflected_r, old.reflected_g, old.reflected_b);
            (l.spectrum_len, l.spectrum_first) = (old.spectrum_len, old.spectrum_first);
            mark_sun(&mut l, &scene.lights[i]);
            self.lights[i] = l;
            changed.lights.push(i);
            if geometry > 0 {
                let at = l.proj_first as usize;
                self.geometry[at..at + geometry].copy_from_slice(&scratch.geometry);
                changed.geometry.push(at..at + geometry);
            }
            if tables > 0 {
                let at = l.proj_cdf as usize;
                self.tables[at..at + tables].copy_from_slice(&scratch.tables);
                changed.tables.push(at..at + tables);
            }
        }
        Some(changed)
    }
}

/// What [`EncodedScene::point_lights`] changed: light indices, and ranges of
/// geometry records and table entries.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointedLights {
    /// The records: drawn suns', aimed area lights'.
    pub lights: Vec<usize>,
    /// Their projection targets.
    pub geometry: Vec<std::ops::Range<usize>>,
    /// Their projection CDFs.
    pub tables: Vec<std::ops::Range<usize>>,
}

/// The scene's buffers on the device and their bind group (group 0 of the
/// trace and render pipelines).
pub struct SceneBuffers {
    /// The host copy of the settings, updated per dispatch.
    pub params: Params,
    /// The uniform buffer behind `params`.
    pub params_buffer: wgpu::Buffer,
    /// Bind group 0.
    pub bind_group: wgpu::BindGroup,
    /// Objects, surfaces, lights, bands, geometry, tables (bindings 1–6).
    storage: Vec<wgpu::Buffer>,
}

/// The storage buffers of bind group 0, bindings 1–6.
const STORAGE_LABELS: [&str; 6] = [
    "prismatic objects",
    "prismatic surfaces",
    "prismatic lights",
    "prismatic bands",
    "prismatic geometry",
    "prismatic tables",
];

/// A storage buffer holding `items` (at least one element: bindings cannot be empty).
pub fn storage_init<T: Pod + Default>(ctx: &GpuContext, label: &str, items: &[T]) -> wgpu::Buffer {
    let fallback = [T::default()];
    let items = if items.is_empty() { &fallback[..] } else { items };
    ctx.buffer_with(label, bytemuck::cast_slice(items), wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST)
}

impl SceneBuffers {
    /// Uploads `encoded` and binds it with `layout`.
    pub fn upload(ctx: &GpuContext, layout: &wgpu::BindGroupLayout, encoded: &EncodedScene) -> Self {
        let params_buffer = ctx.buffer_with(
            "prismatic params",
            bytemuck::bytes_of(&encoded.params),
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        let [objects, surfaces, lights, bands, geometry, tables] = STORAGE_LABELS;
        let storage = vec![
            storage_init(ctx, objects, &encoded.objects),
            storage_init(ctx, surfaces, &encoded.surfaces),
            storage_init(ctx, lights, &encoded.lights),
            storage_init(ctx, bands, &encoded.bands),
            storage_init(ctx, geometry, &encoded.geometry),
            storage_init(ctx, tables, &encoded.tables),
        ];
        SceneBuffers::bind(&ctx.device, layout, params_buffer, storage, encoded.params)
    }

    /// The bind group over `params_buffer` and the six `storage` buffers.
    fn bind(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        params_buffer: wgpu::Buffer,
        storage: Vec<wgpu::Buffer>,
        params: Params,
    ) -> Self {
        let mut entries = vec![wgpu::BindGroupEntry { binding: 0, resource: params_buffer.as_entire_binding() }];
        entries.extend(
            storage
                .iter()
                .enumerate()
                .map(|(i, b)| wgpu::BindGroupEntry { binding: i as u32 + 1, resource: b.as_entire_binding() }),
        );
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("prismatic scene"),
            layout,
            entries: &entries,
        });
        SceneBuffers { params, params_buffer, bind_group, storage }
    }

    /// Writes what [`EncodedScene::point_lights`] changed in `encoded`.
    pub fn write_lights(&self, ctx: &GpuContext, encoded: &EncodedScene, changed: &PointedLights) {
        fn write<T: Pod>(ctx: &GpuContext, buffer: &wgpu::Buffer, items: &[T], range: std::ops::Range<usize>) {
            let size = std::mem::size_of::<T>();
            ctx.write(buffer, (range.start * size) as u64, bytemuck::cast_slice(&items[range]));
        }
        for &i in &changed.lights {
            write(ctx, &self.storage[2], &encoded.lights, i..i + 1);
        }
        for range in &changed.geometry {
            write(ctx, &self.storage[4], &encoded.geometry, range.clone());
        }
        for range in &changed.tables {
            write(ctx, &self.storage[5], &encoded.tables, range.clone());
        }
    }

    /// Makes the buffers hold `new` where they held `old`: each storage
    /// buffer gets only the byte range that differs, written in place, or
    /// is allocated again when `new` no longer fits (and the bind group
    /// with it). Returns whether the band table was allocated again
    /// (other stages' bind groups hold it).
    pub fn update(
        &mut self,
        ctx: &GpuContext,
        layout: &wgpu::BindGroupLayout,
        old: &EncodedScene,
        new: &EncodedScene,
    ) -> bool {
        fn bytes<T: Pod>(items: &[T]) -> &[u8] {
            bytemuck::cast_slice(items)
        }
        let pairs: [(&[u8], &[u8]); 6] = [
            (bytes(&old.objects), bytes(&new.objects)),
            (bytes(&old.surfaces), bytes(&new.surfaces)),
            (bytes(&old.lights), bytes(&new.lights)),
            (bytes(&old.bands), bytes(&new.bands)),
            (bytes(&old.geometry), bytes(&new.geometry)),
            (bytes(&old.tables), bytes(&new.tables)),
        ];
        let mut reallocated = [false; 6];
        for (i, (was, now)) in pairs.into_iter().enumerate() {
            if now.len() as u64 > self.storage[i].size() {
                reallocated[i] = true;
                self.storage[i] =
                    ctx.buffer_with(STORAGE_LABELS[i], now, wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST);
            } else if let Some((start, end)) = changed_range(was, now) {
                ctx.write(&self.storage[i], start as u64, &now[start..end]);
            }
        }
        self.params = new.params;
        self.write_params(ctx);
        if reallocated.contains(&true) {
            *self = SceneBuffers::bind(
                &ctx.device,
                layout,
                self.params_buffer.clone(),
                std::mem::take(&mut self.storage),
                self.params,
            );
        }
        reallocated[3]
    }

    /// The band table (binding 4), which the gather binds too.
    pub fn bands(&self) -> &wgpu::Buffer {
        &self.storage[3]
    }

    /// What a gather reads of the scene for the BSDF of points on rough
    /// surfaces: objects, surfaces, geometry and tables (gather.wgsl's
    /// bindings 10–13).
    pub fn surface_buffers(&self) -> [&wgpu::Buffer; 4] {
        [&self.storage[0], &self.storage[1], &self.storage[4], &self.storage[5]]
    }

    /// Writes the host copy of the settings to the device (visible to the next submit).
    pub fn write_params(&self, ctx: &GpuContext) {
        ctx.write(&self.params_buffer, 0, bytemuck::bytes_of(&self.params));
    }
}

/// The 4-byte-aligned byte range where `now` differs from `was` (all of
/// `now` past `was`'s end counts as changed); `None` when equal.
fn changed_range(was: &[u8], now: &[u8]) -> Option<(usize, usize)> {
    let first = was.iter().zip(now).position(|(a, b)| a != b).unwrap_or(was.len().min(now.len()));
    if first == now.len() {
        return None;
    }
    let last = if now.len() > was.len() {
        now.len()
    } else {
        now.len() - now.iter().rev().zip(was[..now.len()].iter().rev()).position(|(a, b)| a != b).unwrap_or(0)
    };
    Some((first / 4 * 4, last.next_multiple_of(4).min(now.len())))
}

#[cfg(test)]
mod tests {
    use super::{EncodedScene, Light, changed_range};

    #[test]
    fn suns_pointed_in_place_are_the_pass_encoded_afresh() {
        // The ball alone fills its beams; with indirect light (the scene's)
        // they cover the floor too, and their projection maps aim at the ball.
        for indirect_photons in [0, 2_000] {
            let mut sky = prismatic_conformance::scenes::sky_lit_sphere().scene;
            sky.render.view_paths = prismatic_core::model::scene::ViewPaths::Hero;
            sky.render.indirect_photons = indirect_photons;
            let scene = prismatic_core::PreparedScene::new(sky).unwrap();
            let mut encoded = EncodedScene::new(&scene);
            for pass in [3, 1, 0] {
                let moved = scene.lights_of_pass(pass).expect("suns drawn each pass");
                let changed = encoded.point_lights(&moved).expect("the projection maps keep their size");
                assert_eq!(changed.lights.len(), 8, "pass {pass}");
                let aimed = !changed.geometry.is_empty() && !changed.tables.is_empty();
                assert_eq!(aimed, indirect_photons > 0, "pass {pass}: projection maps written");
                assert!(encoded == EncodedScene::new(&moved), "pass {pass}: pointed in place differs from afresh");
            }
        }
    }

    #[test]
    fn area_lights_aimed_in_place_are_the_pass_encoded_afresh() {
        let mut panel = prismatic_conformance::scenes::panel_lit_sphere().scene;
        panel.render.view_paths = prismatic_core::model::scene::ViewPaths::Hero;
        // Cut into pieces (a choice of triangles is encoded again each pass).
        panel.render.area_lights = 16;
        let scene = prismatic_core::PreparedScene::new(panel).unwrap();
        assert!(scene.draws_aims);
        let areas = scene.lights.iter().filter(|l| matches!(l, Light::Area { .. })).count();
        let mut encoded = EncodedScene::new(&scene);
        for pass in [3, 1, 0] {
            let moved = scene.lights_of_pass(pass).expect("aims drawn each pass");
            let changed = encoded.point_lights(&moved).expect("area lights keep their room");
            assert_eq!(changed.lights.len(), areas, "pass {pass}");
            assert!(encoded == EncodedScene::new(&moved), "pass {pass}: aimed in place differs from afresh");
        }
    }

    #[test]
    fn only_the_changed_bytes_are_written() {
        let was = [0u8, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11];
        assert_eq!(changed_range(&was, &was), None);
        let mut now = was;
        now[5] = 99;
        assert_eq!(changed_range(&was, &now), Some((4, 8)));
        now[9] = 99;
        assert_eq!(changed_range(&was, &now), Some((4, 12)));
        // Grown: everything from the first difference to the new end.
        let longer = [0u8, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15];
        assert_eq!(changed_range(&was, &longer), Some((12, 16)));
        // Shrunk and equal on the common part: nothing to write.
        assert_eq!(changed_range(&was, &was[..8]), None);
    }
}
