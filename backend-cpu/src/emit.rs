//! Packet emission: `prismatic_core::photons::emit::emit` for eight photon indices at once.

use crate::optics::offset_origin;
use crate::simd::{Vec3x8, basis_x8, cone_direction, ge, gt, photon_f32, sin_cos_turns};
use prismatic_core::geometry::primitive::basis;
use prismatic_core::model::scene::{Light, PhotonSequence};
use prismatic_core::plan::prepared::PreparedScene;
use prismatic_core::plan::projection::Targets;
use prismatic_core::sampling::spot_cone::SpotCone;
use prismatic_core::util::rng::dim;
use std::f32::consts::PI;
use wide::{f32x8, u32x8};

/// A light with its frame precomputed (the scalar `emit` computes the same values per photon).
#[derive(Clone, Copy, Debug)]
enum Emitter {
    Spot {
        position: Vec3x8,
        axis: Vec3x8,
        t: Vec3x8,
        b: Vec3x8,
        cos_max: f32x8,
        cone: SpotCone,
    },
    Point {
        position: Vec3x8,
    },
    Beam {
        position: Vec3x8,
        axis: Vec3x8,
        t: Vec3x8,
        b: Vec3x8,
        radius: f32x8,
    },
    /// A triangle: a corner, its edges from there, its front normal and the normal's basis.
    Area {
        corner: Vec3x8,
        e1: Vec3x8,
        e2: Vec3x8,
        normal: Vec3x8,
        t: Vec3x8,
        b: Vec3x8,
    },
}

/// A light's projection map with its vectors splatted (see `prismatic_core::plan::projection`).
struct ProjectionX8 {
    /// Cone targets: axis, its basis (t, b), cosine of the half-angle.
    cones: Vec<(Vec3x8, Vec3x8, Vec3x8, f32x8)>,
    /// Disc targets: centre and radius.
    discs: Vec<(Vec3x8, f32x8)>,
    /// Sphere targets of an area light: centre, radius, probability.
    spheres: Vec<(Vec3x8, f32x8, f32x8)>,
    /// Cumulative target probabilities.
    cdf: Vec<f32x8>,
    scale: f32x8,
}

/// The scene's lights, ready to emit packets.
pub struct Emitters {
    lights: Vec<Emitter>,
    projections: Vec<Option<ProjectionX8>>,
    cdf: Vec<f32x8>,
    seed: u32,
    sequence: PhotonSequence,
}

impl Emitters {
    /// Precomputes the light frames.
    pub fn new(scene: &PreparedScene) -> Self {
        let lights = scene
            .emitters
            .iter()
            .map(|l| match l {
                Light::Spot { position, direction, cone_deg, inner_cone_deg, .. } => {
                    let axis = direction.normalize();
                    let (t, b) = basis(axis);
                    let cone = SpotCone::new(*cone_deg, *inner_cone_deg);
                    Emitter::Spot {
                        position: Vec3x8::splat(*position),
                        axis: Vec3x8::splat(axis),
                        t: Vec3x8::splat(t),
                        b: Vec3x8::splat(b),
                        cos_max: f32x8::splat(cone.cos_outer),
                        cone,
                    }
                }
                Light::Point { position, .. } => Emitter::Point { position: Vec3x8::splat(*position) },
                Light::Beam { position, direction, radius, .. } => {
                    let axis = direction.normalize();
                    let (t, b) = basis(axis);
                    Emitter::Beam {
                        position: Vec3x8::splat(*position),
                        axis: Vec3x8::splat(axis),
                        t: Vec3x8::splat(t),
                        b: Vec3x8::splat(b),
                        radius: f32x8::splat(*radius),
                    }
                }
                Light::Area { vertices: [a, b, c], .. } => {
                    let normal = (*b - *a).cross(*c - *a).normalize();
                    let (t, bt) = basis(normal);
                    Emitter::Area {
                        corner: Vec3x8::splat(*a),
                        e1: Vec3x8::splat(*b - *a),
                        e2: Vec3x8::splat(*c - *a),
                        normal: Vec3x8::splat(normal),
                        t: Vec3x8::splat(t),
                        b: Vec3x8::splat(bt),
                    }
                }
                Light::Sun { .. } | Light::Environment { .. } => {
                    unreachable!("a sun emits as its beam, an environment as its suns' (PreparedScene::emitters)")
                }
            })
            .collect();
        let cdf = scene.light_cdf.iter().map(|&c| f32x8::splat(c)).collect();
        let projections = scene
            .plan
            .projections
            .iter()
            .map(|p| {
                p.as_ref().map(|p| {
                    let (mut cones, mut discs, mut spheres) = (Vec::new(), Vec::new(), Vec::new());
                    match &p.targets {
                        Targets::Cones { axis, cos_max } => {
                            for (a, c) in axis.iter().zip(cos_max) {
                                let (t, b) = basis(*a);
                                cones.push((Vec3x8::splat(*a), Vec3x8::splat(t), Vec3x8::splat(b), f32x8::splat(*c)));
                            }
                        }
                        Targets::Discs { center, radius } => {
                            for (c, r) in center.iter().zip(radius) {
                                discs.push((Vec3x8::splat(*c), f32x8::splat(*r)));
                            }
                        }
                        Targets::Spheres { center, radius, probability } => {
                            for ((c, r), p) in center.iter().zip(radius).zip(probability) {
                                spheres.push((Vec3x8::splat(*c), f32x8::splat(*r), f32x8::splat(*p)));
                            }
                        }
                    }
                    ProjectionX8 {
                        cones,
                        discs,
                        spheres,
                        cdf: p.cdf.iter().map(|&c| f32x8::splat(c)).collect(),
                        scale: f32x8::splat(p.scale),
                    }
                })
            })
            .collect();
        let r = &scene.scene.render;
        Emitters { lights, projections, cdf, seed: r.seed, sequence: r.photon_sequence }
    }

    /// Origins, directions and flux weights of white photons `index`.
    #[inline]
    pub fn emit(&self, index: u32x8) -> (Vec3x8, Vec3x8, f32x8) {
        self.emit_with(index, true)
    }

    /// Origins and directions of photons `index` over their lights' whole
    /// distributions (`prismatic_core::photons::emit::emit_unaimed`,
    /// indirect light's photons).
    #[inline]
    pub fn emit_unaimed(&self, index: u32x8) -> (Vec3x8, Vec3x8) {
        let (origin, dir, _) = self.emit_with(index, false);
        (origin, dir)
    }

    #[inline]
    fn emit_with(&self, index: u32x8, aimed: bool) -> (Vec3x8, Vec3x8, f32x8) {
        let rnd = |d: u32| crate::simd::random_f32(self.seed, index, u32x8::splat(d));
        // The light's own sample: a direction, or a point on a beam's disc.
        let sample = |d: u32| photon_f32(self.sequence, self.seed, index, d);
        let (u1, u2) = (sample(dim::DIRECTION), sample(dim::DIRECTION + 1));
        if self.lights.len() == 1 {
            return self.emit_from(0, index, u1, u2, aimed);
        }
        // Light k is the first whose cumulative probability exceeds u.
        let u = rnd(dim::LIGHT);
        let mut chosen = f32x8::ZERO;
        for c in &self.cdf[..self.cdf.len() - 1] {
            chosen += ge(u, *c) & f32x8::ONE;
        }
        let (mut origin, mut dir, mut weight) = (Vec3x8::ZERO, Vec3x8::ZERO, f32x8::ZERO);
        for k in 0..self.lights.len() {
            let mine = chosen.simd_eq(f32x8::splat(k as f32));
            if mine.any() {
                let (o, d, w) = self.emit_from(k, index, u1, u2, aimed);
                origin = Vec3x8::select(mine, o, origin);
                dir = Vec3x8::select(mine, d, dir);
                weight = mine.select(w, weight);
            }
        }
        (origin, dir, weight)
    }

    #[inline]
    fn emit_from(&self, k: usize, index: u32x8, u1: f32x8, u2: f32x8, aimed: bool) -> (Vec3x8, Vec3x8, f32x8) {
        if let Some(p) = self.projections[k].as_ref().filter(|_| aimed) {
            return self.emit_projected(&self.lights[k], p, index, u1, u2);
        }
        let (origin, dir) = self.emit_whole(&self.lights[k], index, u1, u2);
        (origin, dir, f32x8::ONE)
    }

    /// `Projection::sample` for eight photons.
    #[inline]
    fn emit_projected(
        &self,
        light: &Emitter,
        p: &ProjectionX8,
        index: u32x8,
        u1: f32x8,
        u2: f32x8,
    ) -> (Vec3x8, Vec3x8, f32x8) {
        let rnd = |d: u32| crate::simd::random_f32(self.seed, index, u32x8::splat(d));
        let n = p.cdf.len();
        if n == 0 {
            return (Vec3x8::ZERO, Vec3x8 { x: f32x8::ZERO, y: f32x8::ZERO, z: f32x8::ONE }, f32x8::ZERO);
        }
        let u_target = rnd(dim::TARGET);
        let mut target = f32x8::ZERO;
        for c in &p.cdf[..n - 1] {
            target += ge(u_target, *c) & f32x8::ONE;
        }
        if let Emitter::Area { .. } = light {
            return self.emit_aimed_area(light, p, target, index, u1, u2);
        }
        let (mut origin, mut dir) = (Vec3x8::ZERO, Vec3x8::ZERO);
        let mut covering = f32x8::ZERO;
        let mut soft = f32x8::ONE;
        // Spot and point lights: a direction in the chosen target's cone.
        for (j, (a, t, b, c)) in p.cones.iter().enumerate() {
            let cos_t = f32x8::ONE - u1 * (f32x8::ONE - *c);
            let d = cone_direction(*a, *t, *b, cos_t, u2);
            dir = Vec3x8::select(target.simd_eq(f32x8::splat(j as f32)), d, dir);
        }
        let inside;
        match *light {
            Emitter::Spot { position, axis: light_axis, cos_max, cone, .. } => {
                origin = position;
                inside = ge(dir.dot(light_axis), cos_max);
                if cone.cos_inner != cone.cos_outer {
                    // The soft edge's density over a uniform cone's, lane by lane.
                    let c = dir.dot(light_axis).to_array();
                    let ratio = (1.0 - cone.cos_outer) / cone.measure();
                    soft = f32x8::new(core::array::from_fn(|i| cone.falloff(c[i]) * ratio));
                }
            }
            Emitter::Point { position } => {
                origin = position;
                inside = f32x8::splat(f32::from_bits(u32::MAX));
            }
            Emitter::Area { .. } => unreachable!("an area light is aimed by emit_aimed_area (above)"),
            Emitter::Beam { position, axis, t, b, radius } => {
                let (sin_phi, cos_phi) = sin_cos_turns(u2);
                for (j, (c, r)) in p.discs.iter().enumerate() {
                    let o = *c + (t * cos_phi + b * sin_phi) * (*r * u1.sqrt());
                    origin = Vec3x8::select(target.simd_eq(f32x8::splat(j as f32)), o, origin);
                }
                dir = axis;
                inside = !(origin - position).length_squared().simd_gt(radius * radius);
            }
        }
        for (a, _, _, c) in &p.cones {
            covering += ge(dir.dot(*a), *c) & f32x8::ONE;
        }
        for (c, r) in &p.discs {
            covering += !(origin - *c).length_squared().simd_gt(*r * *r) & f32x8::ONE;
        }
        let weight = inside.select(p.scale / covering.max(f32x8::ONE), f32x8::ZERO);
        (origin, dir, weight * soft)
    }

    #[inline]
    fn emit_whole(&self, light: &Emitter, index: u32x8, u1: f32x8, u2: f32x8) -> (Vec3x8, Vec3x8) {
        match *light {
            Emitter::Spot { position, axis, t, b, cos_max, cone } => {
                let cos_t = if cone.cos_inner == cone.cos_outer {
                    f32x8::ONE - u1 * (f32x8::ONE - cos_max)
                } else {
                    let u = u1.to_array();
                    f32x8::new(core::array::from_fn(|i| cone.sample_cos(u[i])))
                };
                (position, cone_direction(axis, t, b, cos_t, u2))
            }
            Emitter::Point { position } => {
                let z = f32x8::ONE - f32x8::splat(2.0) * u1;
                let r = (f32x8::ONE - z * z).max(f32x8::ZERO).sqrt();
                let (sin_phi, cos_phi) = sin_cos_turns(u2);
                (position, Vec3x8 { x: r * cos_phi, y: r * sin_phi, z })
            }
            Emitter::Beam { position, axis, t, b, radius } => {
                let r = radius * u1.sqrt();
                let (sin_phi, cos_phi) = sin_cos_turns(u2);
                (position + (t * cos_phi + b * sin_phi) * r, axis)
            }
            Emitter::Area { normal, t, b, .. } => {
                let cos_t = (f32x8::ONE - u1).sqrt();
                (self.area_origin(light, index), cone_direction(normal, t, b, cos_t, u2))
            }
        }
    }

    /// `prismatic_core::photons::emit::area_origin` for eight photons.
    #[inline]
    fn area_origin(&self, light: &Emitter, index: u32x8) -> Vec3x8 {
        let Emitter::Area { corner, e1, e2, normal, .. } = *light else { unreachable!("an area light") };
        let rnd = |d: u32| crate::simd::random_f32(self.seed, index, u32x8::splat(d));
        let (s, w2) = (rnd(dim::AREA).sqrt(), rnd(dim::AREA + 1));
        let point = corner + e1 * (s * (f32x8::ONE - w2)) + e2 * (s * w2);
        offset_origin(point, normal, normal)
    }

    /// `Projection::sample_area` for eight photons (`target`: the sphere each aims at).
    #[inline]
    fn emit_aimed_area(
        &self,
        light: &Emitter,
        p: &ProjectionX8,
        target: f32x8,
        index: u32x8,
        u1: f32x8,
        u2: f32x8,
    ) -> (Vec3x8, Vec3x8, f32x8) {
        let Emitter::Area { normal, .. } = *light else { unreachable!("an area light") };
        let origin = self.area_origin(light, index);
        let cones: Vec<(Vec3x8, f32x8)> = p.spheres.iter().map(|(c, r, _)| sphere_cone(origin, *c, *r)).collect();
        let (mut axis, mut gap) = (Vec3x8::ZERO, f32x8::ZERO);
        for (j, (a, g)) in cones.iter().enumerate() {
            let mine = target.simd_eq(f32x8::splat(j as f32));
            axis = Vec3x8::select(mine, *a, axis);
            gap = mine.select(*g, gap);
        }
        let (t, b) = basis_x8(axis);
        let dir = cone_direction(axis, t, b, f32x8::ONE - u1 * gap, u2);
        let mut density = f32x8::ZERO;
        for ((a, g), (_, _, probability)) in cones.iter().zip(&p.spheres) {
            let inside = ge(dir.dot(*a), f32x8::ONE - *g);
            density += inside & (*probability / (f32x8::splat(2.0 * PI) * *g));
        }
        let cos_n = dir.dot(normal);
        let lit = gt(cos_n, f32x8::ZERO) & gt(density, f32x8::ZERO);
        (origin, dir, lit.select(cos_n / f32x8::splat(PI) / density, f32x8::ZERO))
    }
}

/// `prismatic_core::plan::projection::sphere_cone` for eight points.
#[inline]
fn sphere_cone(p: Vec3x8, c: Vec3x8, r: f32x8) -> (Vec3x8, f32x8) {
    let to = c - p;
    let d = to.length_squared().sqrt();
    let s2 = (r / d) * (r / d);
    (to / d, s2 / (f32x8::ONE + (f32x8::ONE - s2).sqrt()))
}
