//! A validated scene with everything derived that tracing and rendering need:
//! the band table, each object's primitive and surface (per-band indices of
//! refraction), the light-selection distribution and the effect plan.

use crate::geometry::normal_map::{TriangleTangents, mapped_normal};
use crate::geometry::primitive::{Primitive, Ray, prism_faces};
use crate::geometry::shading::{TriangleNormals, shading_normal};
use crate::geometry::texture::{TriangleUv, sample, sample_linear};
use crate::model::bands::BandTable;
use crate::model::metalness::{Metalness, SpecularLayer};
use crate::model::scene::{Light, MaterialKind, Scene, SceneError, Shape, ThinFilm};
use crate::model::spectrum::Spectrum;
use crate::optics::metal::{MetalOptics, filmed_layer_tint};
use crate::optics::microfacet::Ggx;
use crate::optics::scatter::Face;
use crate::optics::surface::{DielectricOptics, Surface};
use crate::plan::area::AreaLights;
use crate::plan::drawn_suns::DrawnSuns;
use crate::plan::drawn_triangles::DrawnTriangles;
use crate::plan::effects::EffectPlan;
use crate::plan::projection::Projection;
use crate::plan::{area, area_aims, reach};
use crate::sampling::environment::{EnvironmentCut, EnvironmentLookup};
use crate::sampling::light_spectrum::LightSpectrum;
use alloc::sync::Arc;
use alloc::vec::Vec;
use glam::{Vec2, Vec3};

/// A hit with the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Ray parameter.
    pub t: f32,
    /// World point.
    pub point: Vec3,
    /// Outward geometric unit normal.
    pub normal: Vec3,
    /// Index of the object hit.
    pub object: usize,
    /// The mesh triangle hit (see [`crate::geometry::primitive::SurfaceHit::triangle`]).
    pub triangle: u32,
}

/// A validated scene plus the tables derived from it.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedScene {
    /// The scene as given.
    pub scene: Scene,
    /// The render's band table.
    pub bands: BandTable,
    /// One primitive per object.
    pub primitives: Vec<Primitive>,
    /// One surface per object.
    pub surfaces: Vec<Surface>,
    /// Per object, the texture coordinates of its mesh's triangles in the
    /// hierarchy's order; empty unless its surface has a texture or its
    /// material a normal map.
    pub texture_uvs: Vec<Vec<TriangleUv>>,
    /// Per object, the vertex normals of its mesh's triangles in the
    /// hierarchy's order; empty for flat triangles (a mesh without normals).
    pub vertex_normals: Vec<Vec<TriangleNormals>>,
    /// Per object, the tangent frames of its mesh's triangles in the
    /// hierarchy's order (its vertex tangents, or each triangle's from its
    /// texture coordinates); empty unless its material has a normal map.
    pub normal_tangents: Vec<Vec<TriangleTangents>>,
    /// The lights that shine: the scene's, each environment replaced by
    /// the suns of its median cut ([`EnvironmentLookup::cut`], as
    /// many as `render.environment_lights`), then the emissive meshes'
    /// area lights ([`area::area_lights`]). Backends light with these.
    /// With per-pass view paths the suns are pass 0's draw
    /// ([`PreparedScene::drawn_suns`]), and so are the area lights' aims
    /// ([`PreparedScene::draws_aims`]) and a choice of emissive triangles
    /// ([`PreparedScene::drawn_triangles`]).
    pub lights: Vec<Light>,
    /// The environment rays that leave the scene see (`None`: the
    /// background colour).
    pub environment: Option<EnvironmentLookup>,
    /// What each light emits photons as: the light itself, or for a sun
    /// the beam over the scene's mirrors and glass, with indirect light over
    /// every bounded object ([`crate::plan::reach::sun_beam`]).
    pub emitters: Vec<Light>,
    /// What each emitter's photons' wavelengths are drawn from, and its
    /// colour and shares of the bands.
    pub light_spectra: Vec<LightSpectrum>,
    /// Cumulative light-selection probabilities (by power).
    pub light_cdf: Vec<f32>,
    /// Σ light power.
    pub total_power: f32,
    /// What each channel of the image is scaled by so that the white
    /// point's light is neutral: 1 / its colour ((1, 1, 1) for E).
    pub white_balance: Vec3,
    /// What the render simulates; backends follow it.
    pub plan: EffectPlan,
    /// With an environment and per-pass view paths, how each pass draws
    /// its suns ([`crate::plan::drawn_suns`]); `None`: the suns stay fixed.
    pub drawn_suns: Option<DrawnSuns>,
    /// With area lights that cast shadows and per-pass view paths, whether
    /// each pass aims their shadow rays anew ([`crate::plan::area_aims`]).
    pub draws_aims: bool,
    /// With more emissive triangles than `render.area_lights` and per-pass
    /// view paths, how each pass chooses its area lights among them
    /// ([`crate::plan::drawn_triangles`]); `None`: the lights stay fixed.
    pub drawn_triangles: Option<DrawnTriangles>,
}

impl PreparedScene {
    /// Validates `scene` and derives the tables.
    pub fn new(scene: Scene) -> Result<Self, SceneError> {
        Self::prepare(scene, None)
    }

    /// [`PreparedScene::new`] of `scene`, a changed version of this one (an
    /// engine's next frame): a mesh whose triangles are this one's keeps its
    /// hierarchy, shared when its vertices stayed and refitted when they
    /// moved ([`crate::geometry::bvh_build::refit`]); only new meshes are built (and
    /// checked: see [`Scene::validate_since`]). The result traces as a
    /// fresh preparation would.
    pub fn update(&self, scene: Scene) -> Result<Self, SceneError> {
        Self::prepare(scene, Some(self))
    }

    fn prepare(scene: Scene, previous: Option<&PreparedScene>) -> Result<Self, SceneError> {
        scene.validate_since(previous.map(|p| &p.scene))?;
        let bands = BandTable::new(scene.render.bands).colour_by_wavelength(scene.render.wavelengths.continuous());
        let primitives: Vec<Primitive> = scene
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| previous.and_then(|p| p.reuse(i, &o.shape)).unwrap_or_else(|| primitive(&o.shape)))
            .collect();
        let surfaces: Vec<Surface> =
            scene.objects.iter().map(|o| &scene.materials[o.material]).map(|m| Surface::new(m, &bands)).collect();
        let texture_uvs: Vec<Vec<TriangleUv>> = scene
            .objects
            .iter()
            .zip(&primitives)
            .zip(&surfaces)
            .map(|((o, p), s)| match (&o.shape, p) {
                (Shape::Mesh { triangles, uvs, .. }, Primitive::Mesh(bvh))
                    if matches!(s, Surface::Diffuse { texture: Some(_), .. })
                        || matches!(s, Surface::Metal(m) if m.textured)
                        || scene.materials[o.material].normal_map.is_some()
                        || scene.materials[o.material].roughness_map.is_some()
                        || scene.materials[o.material].film_map.is_some()
                        || scene.materials[o.material].specular_map.is_some() =>
                {
                    bvh.sources
                        .iter()
                        .map(|&k| TriangleUv::new(triangles[k as usize].map(|i| uvs[i as usize])))
                        .collect()
                }
                _ => Vec::new(),
            })
            .collect();
        let normal_tangents = scene
            .objects
            .iter()
            .zip(&primitives)
            .zip(&texture_uvs)
            .map(|((o, p), uvs)| match (&o.shape, p) {
                (Shape::Mesh { triangles, tangents, .. }, Primitive::Mesh(bvh))
                    if scene.materials[o.material].normal_map.is_some() =>
                {
                    let frame = |(j, &k): (usize, &u32)| match tangents.is_empty() {
                        true => TriangleTangents::from_uvs(&bvh.triangles[j], &uvs[j]),
                        false => TriangleTangents::from_vertices(triangles[k as usize].map(|i| tangents[i as usize])),
                    };
                    bvh.sources.iter().enumerate().map(frame).collect()
                }
                _ => Vec::new(),
            })
            .collect();
        let vertex_normals = scene
            .objects
            .iter()
            .zip(&primitives)
            .map(|(o, p)| match (&o.shape, p) {
                (Shape::Mesh { triangles, normals, .. }, Primitive::Mesh(bvh)) if !normals.is_empty() => {
                    let corners = |k: u32| triangles[k as usize].map(|i| normals[i as usize]);
                    bvh.sources.iter().map(|&k| TriangleNormals::new(corners(k))).collect()
                }
                _ => Vec::new(),
            })
            .collect();
        let bounds: Vec<(Vec3, f32)> = scene.objects.iter().map(|o| reach::bounds(&o.shape)).collect();
        // A sun's beam covers the mirrors and glass, or with indirect light
        // every bounded object (the light they bounce counts too).
        let beam_targets: Vec<(Vec3, f32)> = bounds
            .iter()
            .zip(&surfaces)
            .filter(|(_, s)| s.focuses_light() && scene.render.indirect_photons == 0)
            .map(|(b, _)| *b)
            .collect();
        let environment = scene.lights.iter().find_map(|l| match l {
            Light::Environment { map, strength, rotation_deg, .. } => {
                Some(EnvironmentLookup::new(map.clone(), *strength, *rotation_deg))
            }
            _ => None,
        });
        // Drawn each pass with per-pass view paths, fixed along the cut otherwise.
        let draw = scene.render.view_paths.per_pass();
        let mut lights: Vec<Light> = Vec::new();
        let mut sky: Option<(EnvironmentCut, Vec<(usize, usize)>)> = None;
        for l in &scene.lights {
            match (l, &environment) {
                (Light::Environment { spectrum, .. }, Some(env)) => {
                    let cut = env.cut(scene.render.environment_lights as usize);
                    let suns = environment_suns(&cut, spectrum, draw);
                    let first = lights.len();
                    let drawn = suns.iter().enumerate().map(|(k, (_, region))| (first + k, *region)).collect();
                    lights.extend(suns.into_iter().map(|(sun, _)| sun));
                    sky = Some((cut, drawn));
                }
                _ => lights.push(l.clone()),
            }
        }
        let first_area = lights.len();
        let choice = match area::area_lights(&scene) {
            AreaLights::Pieces(pieces) => {
                lights.extend(pieces);
                None
            }
            AreaLights::Chosen(choice) => {
                // The middle of the strata; with per-pass view paths pass 0's draw replaces it.
                lights.extend(choice.lights(0.5));
                Some(choice)
            }
        };
        let emitters: Vec<Light> = lights
            .iter()
            .map(|l| match l {
                Light::Sun { direction, irradiance, spectrum, .. } => {
                    reach::sun_beam(*direction, *irradiance, spectrum, &beam_targets, &bounds)
                }
                other => other.clone(),
            })
            .collect();
        let light_spectra = emitters.iter().map(|l| LightSpectrum::new(l.spectrum(), &bands)).collect();
        let white_balance = Vec3::ONE / LightSpectrum::new(&scene.render.white_point.spectrum(), &bands).rgb;
        let total_power: f32 = emitters.iter().map(|l| l.power()).sum();
        let mut acc = 0.0;
        let mut light_cdf: Vec<f32> = emitters
            .iter()
            .map(|l| {
                acc += l.power();
                acc / total_power
            })
            .collect();
        if let Some(last) = light_cdf.last_mut() {
            *last = 1.0;
        }
        let mut surfaces = surfaces;
        let plan = EffectPlan::new(&scene, &emitters, &surfaces);
        for s in &mut surfaces {
            if let Surface::Dielectric(g) = s {
                g.splits_photons = g.is_chromatic() && plan.band_splitting.on;
                g.splits_view_rays = g.colours_view_rays() && plan.view_dispersion.on;
            }
        }
        let aimed_at: Vec<(Vec3, f32)> =
            bounds.iter().zip(&surfaces).filter(|(_, s)| s.focuses_light()).map(|(b, _)| *b).collect();
        let drawn_triangles = choice.filter(|_| draw).map(|choice| DrawnTriangles {
            choice: Arc::new(choice),
            first: first_area,
            aimed_at: aimed_at.clone(),
        });
        let drawn_suns = sky.filter(|_| draw).map(|(cut, suns)| DrawnSuns {
            cut: Arc::new(cut),
            suns,
            beam_targets,
            aimed_at,
            bounds,
        });
        let draws_aims = draw && lights.iter().zip(&plan.shadows).any(|(l, s)| matches!(l, Light::Area { .. }) && s.on);
        let mut prepared = PreparedScene {
            scene,
            bands,
            primitives,
            surfaces,
            texture_uvs,
            vertex_normals,
            normal_tangents,
            lights,
            environment,
            emitters,
            light_spectra,
            light_cdf,
            total_power,
            white_balance,
            plan,
            drawn_suns,
            draws_aims,
            drawn_triangles,
        };
        prepared.point_lights(0);
        Ok(prepared)
    }

    /// This scene with its lights of pass `pass`: its environment's suns
    /// drawn ([`crate::plan::drawn_suns`]), its emissive triangles chosen
    /// ([`crate::plan::drawn_triangles`]) and its area lights' shadows
    /// aimed ([`crate::plan::area_aims`]) for that pass. `None` when its
    /// lights are the same every pass (none of those, or view paths that
    /// every pass shares).
    pub fn lights_of_pass(&self, pass: u32) -> Option<PreparedScene> {
        if self.drawn_suns.is_none() && self.drawn_triangles.is_none() && !self.draws_aims {
            return None;
        }
        let mut moved = self.clone();
        moved.point_lights(pass);
        Some(moved)
    }

    /// Points the drawn suns, chooses the emissive triangles and aims the
    /// area lights' shadows (those drawn) for pass `pass`.
    fn point_lights(&mut self, pass: u32) {
        let seed = self.scene.render.seed;
        if let Some(drawn) = &self.drawn_suns {
            drawn.point((&mut self.lights[..], &mut self.emitters[..], &mut self.plan.projections[..]), seed, pass);
        }
        if let Some(drawn) = &self.drawn_triangles {
            let was: Vec<Light> = self.emitters[drawn.slots()].to_vec();
            drawn.draw(&mut self.lights, &mut self.emitters, seed, pass);
            for (i, old) in drawn.slots().zip(&was) {
                let light = &self.emitters[i];
                if light.spectrum() != old.spectrum() {
                    self.light_spectra[i] = LightSpectrum::new(light.spectrum(), &self.bands);
                }
                if self.plan.projection.on {
                    self.plan.projections[i] = Projection::new(light, &drawn.aimed_at);
                }
            }
        }
        if self.draws_aims {
            area_aims::aim(&mut self.lights, seed, pass);
            area_aims::aim(&mut self.emitters, seed, pass);
        }
    }

    /// What the camera multiplies radiance by, per channel: the exposure
    /// times the white balance.
    pub fn camera_response(&self) -> Vec3 {
        self.white_balance * self.scene.render.exposure
    }

    /// The primitive of `shape`, object `index` of a changed scene, from
    /// this scene's: a mesh with the same triangles as this scene's object
    /// `index` (or, failing that, as any of its meshes) keeps its hierarchy,
    /// shared or refitted. `None`: build it.
    fn reuse(&self, index: usize, shape: &Shape) -> Option<Primitive> {
        let Shape::Mesh { positions, triangles, .. } = shape else { return None };
        let same_triangles =
            |i: &usize| matches!(&self.scene.objects[*i].shape, Shape::Mesh { triangles: t, .. } if t == triangles);
        let i = Some(index)
            .filter(|i| *i < self.scene.objects.len() && same_triangles(i))
            .or_else(|| (0..self.scene.objects.len()).find(same_triangles))?;
        let (Shape::Mesh { positions: before, .. }, Primitive::Mesh(bvh)) =
            (&self.scene.objects[i].shape, &self.primitives[i])
        else {
            return None;
        };
        if before == positions {
            return Some(Primitive::Mesh(Arc::clone(bvh)));
        }
        crate::geometry::bvh_build::refit(bvh, positions, triangles).map(|refitted| Primitive::Mesh(Arc::new(refitted)))
    }

    /// The caustic photons a pass traces: emission indices 0 to this (none
    /// when the effect plan skips caustics).
    pub fn caustic_photons(&self) -> u32 {
        if self.plan.caustics.on { self.scene.render.photons } else { 0 }
    }

    /// The indirect photons a pass traces, emission indices after the
    /// caustic ones (none when the plan has no indirect light).
    pub fn indirect_photons(&self) -> u32 {
        if self.plan.indirect.on { self.scene.render.indirect_photons } else { 0 }
    }

    /// The photons a pass traces: the caustic ones, then indirect light's.
    pub fn traced_photons(&self) -> u32 {
        self.caustic_photons() + self.indirect_photons()
    }

    /// Simulates every effect, ignoring the plan (see [`EffectPlan::simulate_everything`]).
    pub fn simulate_everything(&mut self) {
        self.plan.simulate_everything(self.scene.render.max_depth, &mut self.surfaces);
    }

    /// The nearest hit along `ray` closer than `t_max`. Rays start off their
    /// surface (see [`offset_origin`](crate::optics::scatter::offset_origin)), so any positive distance counts.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut limit = t_max;
        for (object, prim) in self.primitives.iter().enumerate() {
            if let Some(h) = prim.intersect(ray, 0.0, limit) {
                limit = h.t;
                best = Some(Hit { t: h.t, point: ray.at(h.t), normal: h.normal, object, triangle: h.triangle });
            }
        }
        best
    }

    /// The albedo of diffuse `object` at `point` (unit normal `normal`) on
    /// its mesh triangle `triangle`: the surface's albedo (with its
    /// checker), times its texture at the point's texture coordinates; a
    /// metal's diffuse part's, its F0 there ([`PreparedScene::metal_at`]).
    #[inline]
    pub fn albedo_at(&self, object: usize, triangle: u32, point: Vec3, normal: Vec3) -> Vec3 {
        if let Surface::Metal(metal) = &self.surfaces[object] {
            return self.metal_colour_at(metal, &Hit { t: 0.0, point, normal, object, triangle }).f0;
        }
        let uv = match (&self.primitives[object], self.texture_uvs[object].get(triangle as usize)) {
            (Primitive::Mesh(bvh), Some(uv)) => uv.at(&bvh.triangles[triangle as usize], point),
            _ => Vec2::ZERO,
        };
        self.surfaces[object].albedo_at(point, normal, uv)
    }

    /// The optics of `metal` (the surface of the object `hit` met) at
    /// `hit`: its facets ([`PreparedScene::facets`]) and its reflectance at
    /// normal incidence times its colour texture there, read as a diffuse
    /// surface's base colour is (sRGB decoded, bilinearly or by nearest
    /// texel as its sampler says, at the mesh's texture coordinates), and
    /// its film there ([`PreparedScene::film_at`]), and its metalness there
    /// ([`PreparedScene::metalness_at`], no longer mapped).
    #[inline]
    pub fn metal_at(&self, metal: &MetalOptics, hit: &Hit) -> MetalOptics {
        MetalOptics {
            ggx: self.facets(hit),
            film: self.film_at(metal.film, hit),
            metalness: self.metalness_at(metal, hit),
            layer_textured: false,
            ..self.metal_colour_at(metal, hit)
        }
    }

    /// What a path of `band` (at its own wavelength `lambda_nm` when it has
    /// one) meets where `hit` is on `glass` (the surface of the object it
    /// met): [`DielectricOptics::face`] with the film as it is there
    /// ([`PreparedScene::film_at`]).
    #[inline]
    pub fn face(&self, glass: &DielectricOptics, hit: &Hit, band: u16, lambda_nm: Option<f32>) -> Face {
        let face = glass.face(band, lambda_nm, &self.bands);
        Face { film: self.film_at(face.film, hit), ..face }
    }

    /// The film `film` of the surface of the object `hit` met, as it is at
    /// `hit`: its thickness and factor as its material's film map says
    /// there ([`FilmMap`](crate::model::scene::FilmMap), read as linear values, bilinearly or by nearest
    /// texel as each map's sampler says, at the mesh's texture
    /// coordinates), else as it is everywhere.
    #[inline]
    pub fn film_at(&self, film: Option<ThinFilm>, hit: &Hit) -> Option<ThinFilm> {
        let film = film?;
        let material = &self.scene.materials[self.scene.objects[hit.object].material];
        let (Some(map), Primitive::Mesh(bvh), Some(uv)) =
            (&material.film_map, &self.primitives[hit.object], self.texture_uvs[hit.object].get(hit.triangle as usize))
        else {
            return Some(film);
        };
        let uv = uv.at(&bvh.triangles[hit.triangle as usize], hit.point);
        let thickness_nm = match &map.thickness {
            Some(t) => map.min_nm + sample_linear(t, uv).y * (film.thickness_nm - map.min_nm),
            None => film.thickness_nm,
        };
        let factor = match &map.factor {
            Some(t) => film.factor * sample_linear(t, uv).x,
            None => film.factor,
        };
        Some(ThinFilm { thickness_nm, factor, ..film })
    }

    /// The metalness of `metal` (the surface of the object `hit` met) at
    /// `hit`, no longer mapped: its factor, times the blue channel of its
    /// material's roughness map there (linear, at the mesh's texture
    /// coordinates) where [`Metalness::mapped`], and its specular layer
    /// there ([`PreparedScene::layer_at`]).
    #[inline]
    pub fn metalness_at(&self, metal: &MetalOptics, hit: &Hit) -> Metalness {
        let metalness = metal.metalness;
        let layer = self.layer_at(metalness.layer, hit);
        let map = &self.scene.materials[self.scene.objects[hit.object].material].roughness_map;
        let factor = match (map, &self.primitives[hit.object], self.texture_uvs[hit.object].get(hit.triangle as usize))
        {
            (Some(map), Primitive::Mesh(bvh), Some(uv)) if metalness.mapped => {
                metalness.at(sample_linear(map, uv.at(&bvh.triangles[hit.triangle as usize], hit.point)).z)
            }
            _ => metalness.factor,
        };
        Metalness { factor, mapped: false, layer }
    }

    /// The specular layer `layer` of the surface of the object `hit` met,
    /// as it is at `hit`: its weight w and colour as its material's
    /// specular map says there ([`SpecularMap`](crate::model::scene::SpecularMap): the weight map's red
    /// channel, linear, scales F90; the colour map, sRGB decoded, scales
    /// `color_f0` before it is clipped to 1; each read bilinearly or by
    /// nearest texel as its sampler says, at the mesh's texture
    /// coordinates), else as it is everywhere; `None` where it has none
    /// (or w is 0 there).
    #[inline]
    pub fn layer_at(&self, layer: Option<SpecularLayer>, hit: &Hit) -> Option<SpecularLayer> {
        let layer = layer?;
        let material = &self.scene.materials[self.scene.objects[hit.object].material];
        let (Some(map), Primitive::Mesh(bvh), Some(uv)) = (
            &material.specular_map,
            &self.primitives[hit.object],
            self.texture_uvs[hit.object].get(hit.triangle as usize),
        ) else {
            return Some(layer);
        };
        let uv = uv.at(&bvh.triangles[hit.triangle as usize], hit.point);
        let w = map.weight.as_ref().map_or(1.0, |t| sample_linear(t, uv).x);
        let f0 = match &map.color {
            Some(t) => (map.color_f0 * sample(t, uv)).min(Vec3::ONE) * layer.f90,
            None => layer.f0,
        };
        (w > 0.0).then_some(SpecularLayer { f0: f0 * w, f90: layer.f90 * w, ..layer })
    }

    /// The share of the light the diffuse part of `metal` (of metalness
    /// `at` at `hit`, [`PreparedScene::metalness_at`]) reflects toward a
    /// viewer at cosine `cos`, on a path of band `band` at `lambda_nm`:
    /// [`Metalness::diffuse_share`], (1 − m) (1 − max F_layer(cos)), where
    /// under a film on the layer (as the film is at `hit`) F_layer is the
    /// film's ([`filmed_layer_tint`]: at the path's wavelength, a white
    /// path's per RGB channel).
    #[inline]
    pub fn diffuse_share_at(
        &self,
        metal: &MetalOptics,
        hit: &Hit,
        at: Metalness,
        cos: f32,
        band: u16,
        lambda_nm: f32,
    ) -> f32 {
        let filmed = at.layer.and_then(|layer| Some((layer, self.film_at(metal.film, hit)?)));
        match filmed {
            Some((layer, film)) => {
                let tint = filmed_layer_tint(layer, film, cos, band, lambda_nm, &self.bands);
                (1.0 - at.factor) * (1.0 - tint.max_element())
            }
            None => at.diffuse_share(cos),
        }
    }

    /// Whether `metal` reflects wavelengths differently at `hit` (where a
    /// white photon splits): [`MetalOptics::is_chromatic`] of its colour
    /// and its layer there, without its facets (its metalness the
    /// surface's).
    #[inline]
    pub fn metal_is_chromatic_at(&self, metal: &MetalOptics, hit: &Hit) -> bool {
        let metalness = Metalness { layer: self.layer_at(metal.metalness.layer, hit), ..metal.metalness };
        MetalOptics { metalness, layer_textured: false, ..self.metal_colour_at(metal, hit) }.is_chromatic()
    }

    /// `metal` with F0 times its colour texture at `hit` (and `textured`
    /// unset); its facets are the surface's, unscaled by a roughness map.
    #[inline]
    fn metal_colour_at(&self, metal: &MetalOptics, hit: &Hit) -> MetalOptics {
        if !metal.textured {
            return *metal;
        }
        let texture = match &self.scene.materials[self.scene.objects[hit.object].material].kind {
            MaterialKind::Metal { texture: Some(t), .. } => Some(t),
            _ => None,
        };
        let f0 = match (texture, &self.primitives[hit.object], self.texture_uvs[hit.object].get(hit.triangle as usize))
        {
            (Some(t), Primitive::Mesh(bvh), Some(uv)) => {
                metal.f0 * sample(t, uv.at(&bvh.triangles[hit.triangle as usize], hit.point))
            }
            _ => metal.f0,
        };
        MetalOptics { f0, textured: false, ..*metal }
    }

    /// The GGX facets of the metal or rough glass at `hit`: its surface's,
    /// their roughness scaled by its roughness map's green channel there
    /// ([`Ggx::scaled`]); `None` where it is polished (and on other
    /// surfaces).
    #[inline]
    pub fn facets(&self, hit: &Hit) -> Option<Ggx> {
        self.facets_at(hit.object, hit.triangle, hit.point)
    }

    /// [`PreparedScene::facets`] at `point` on `object`'s mesh triangle `triangle`.
    #[inline]
    pub fn facets_at(&self, object: usize, triangle: u32, point: Vec3) -> Option<Ggx> {
        let ggx = self.surfaces[object].facets()?;
        let map = &self.scene.materials[self.scene.objects[object].material].roughness_map;
        match (map, &self.primitives[object], self.texture_uvs[object].get(triangle as usize)) {
            (Some(map), Primitive::Mesh(bvh), Some(uv)) => {
                ggx.scaled(sample_linear(map, uv.at(&bvh.triangles[triangle as usize], point)).y)
            }
            _ => Some(ggx),
        }
    }

    /// The normal a ray arriving along unit `direction` at `hit` scatters
    /// about off a mirror, metal or glass, and that a diffuse surface takes
    /// its lights' cosines with: the mesh's vertex normals interpolated
    /// there (else its triangle's), tilted by its material's normal map
    /// ([`mapped_normal`]), and bent where they must be ([`shading_normal`]);
    /// the geometric normal of flat triangles without a map and of other
    /// shapes. Which side of the surface a ray is on stays the geometric
    /// normal's (coloured glass's absorption, where photons are stored and
    /// gathered, the bounces of indirect light's photons).
    #[inline]
    pub fn scattering_normal(&self, hit: &Hit, direction: Vec3) -> Vec3 {
        self.scattering_normal_at(hit.object, hit.triangle, hit.point, hit.normal, direction)
    }

    /// [`PreparedScene::scattering_normal`] at `point` on `object`'s mesh
    /// triangle `triangle` (geometric normal `geometric`).
    #[inline]
    pub fn scattering_normal_at(
        &self,
        object: usize,
        triangle: u32,
        point: Vec3,
        geometric: Vec3,
        direction: Vec3,
    ) -> Vec3 {
        let Primitive::Mesh(bvh) = &self.primitives[object] else {
            return geometric;
        };
        let tri = &bvh.triangles[triangle as usize];
        let (normals, tangents) =
            (self.vertex_normals[object].get(triangle as usize), self.normal_tangents[object].get(triangle as usize));
        if normals.is_none() && tangents.is_none() {
            return geometric;
        }
        let interpolated = normals.map_or(geometric, |n| n.at(tri, point));
        let tilted = match (tangents, &self.scene.materials[self.scene.objects[object].material].normal_map) {
            (Some(frame), Some(map)) => {
                // The map tilts the outward normal; shading_normal turns the
                // result to the ray's side (or drops it, where it disagrees
                // with the winding).
                let uv = self.texture_uvs[object][triangle as usize].at(tri, point);
                let texel = sample_linear(&map.texture, uv);
                mapped_normal(interpolated.normalize_or(geometric), frame.at(tri, point), frame.sign, texel, map.scale)
            }
            _ => interpolated,
        };
        shading_normal(direction, geometric, tilted)
    }

    /// Does `object` scatter about other normals than its triangles' (a
    /// mesh with vertex normals or a normal map)?
    #[inline]
    pub fn bends_normals(&self, object: usize) -> bool {
        !self.vertex_normals[object].is_empty() || !self.normal_tangents[object].is_empty()
    }

    /// Radiance that a ray leaving the scene along unit `direction` sees:
    /// the environment's, else the background colour.
    #[inline]
    pub fn background(&self, direction: Vec3) -> Vec3 {
        match &self.environment {
            Some(env) => env.radiance(direction),
            None => self.scene.render.background,
        }
    }

    /// True when something blocks the segment from `origin` along unit `dir` before `dist`.
    pub fn occluded(&self, origin: Vec3, dir: Vec3, dist: f32) -> bool {
        let ray = Ray { origin, direction: dir };
        self.primitives.iter().any(|p| p.hits(&ray, 0.0, dist))
    }
}

/// The suns an environment shines as, each with its region of `cut`: one
/// per region, with the smooth spectrum of its region's colour (with the
/// environment's `spectrum` other than equal energy: that spectrum at the
/// region's luminance). Fixed suns point along the region's vector
/// irradiance with its length; suns to be drawn each pass (`drawn`) carry
/// the region's whole Σ L dω (their direction is the draw's).
fn environment_suns(cut: &EnvironmentCut, spectrum: &Spectrum, drawn: bool) -> Vec<(Light, usize)> {
    cut.regions
        .iter()
        .enumerate()
        .filter_map(|(k, region)| {
            let rgb = if drawn { region.rgb } else { region.fixed.rgb };
            let (spectrum, irradiance) = match spectrum {
                Spectrum::EqualEnergy => Spectrum::from_rgb(rgb.to_array()),
                other => (other.clone(), crate::model::color::luminance(rgb)),
            };
            let sun = Light::Sun { direction: -region.fixed.toward, irradiance, spectrum, mean_toward: None };
            (irradiance > 0.0).then_some((sun, k))
        })
        .collect()
}

fn primitive(shape: &Shape) -> Primitive {
    match shape {
        Shape::Sphere { center, radius } => Primitive::Sphere { center: *center, radius: *radius },
        Shape::Plane { point, normal } => Primitive::Plane { point: *point, normal: normal.normalize() },
        Shape::Disk { center, normal, radius, inner_radius } => Primitive::Disk {
            center: *center,
            normal: normal.normalize(),
            radius2: radius * radius,
            inner_radius2: inner_radius * inner_radius,
        },
        Shape::Prism { vertices, extrude } => Primitive::Convex { faces: prism_faces(*vertices, *extrude) },
        Shape::Mesh { positions, triangles, .. } => Primitive::mesh(positions, triangles),
    }
}
