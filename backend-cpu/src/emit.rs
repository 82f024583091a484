//! Packet emission: `prismatic_core::emit::emit` for eight photon indices at once.

use crate::simd::{Vec3x8, ge, sin_cos_turns};
use prismatic_core::geometry::basis;
use prismatic_core::math::{cos, radians};
use prismatic_core::prepared::PreparedScene;
use prismatic_core::rng::dim;
use prismatic_core::scene::Light;
use wide::{f32x8, u32x8};

/// A light with its frame precomputed (the scalar `emit` computes the same values per photon).
#[derive(Clone, Copy, Debug)]
enum Emitter {
    Spot { position: Vec3x8, axis: Vec3x8, t: Vec3x8, b: Vec3x8, cos_max: f32x8 },
    Point { position: Vec3x8 },
    Beam { position: Vec3x8, axis: Vec3x8, t: Vec3x8, b: Vec3x8, radius: f32x8 },
}

/// The scene's lights, ready to emit packets.
pub struct Emitters {
    lights: Vec<Emitter>,
    cdf: Vec<f32x8>,
    seed: u32,
}

impl Emitters {
    /// Precomputes the light frames.
    pub fn new(scene: &PreparedScene) -> Self {
        let lights = scene
            .scene
            .lights
            .iter()
            .map(|l| match l {
                Light::Spot { position, direction, cone_deg, .. } => {
                    let axis = direction.normalize();
                    let (t, b) = basis(axis);
                    Emitter::Spot {
                        position: Vec3x8::splat(*position),
                        axis: Vec3x8::splat(axis),
                        t: Vec3x8::splat(t),
                        b: Vec3x8::splat(b),
                        cos_max: f32x8::splat(cos(radians(*cone_deg))),
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
            })
            .collect();
        let cdf = scene.light_cdf.iter().map(|&c| f32x8::splat(c)).collect();
        Emitters { lights, cdf, seed: scene.scene.render.seed }
    }

    /// Origins and directions of white photons `index`.
    #[inline]
    pub fn emit(&self, index: u32x8) -> (Vec3x8, Vec3x8) {
        let rnd = |d: u32| crate::simd::random_f32(self.seed, index, u32x8::splat(d));
        let (u1, u2) = (rnd(dim::DIRECTION), rnd(dim::DIRECTION + 1));
        if self.lights.len() == 1 {
            return self.emit_from(&self.lights[0], index, u1, u2);
        }
        // Light k is the first whose cumulative probability exceeds u.
        let u = rnd(dim::LIGHT);
        let mut chosen = f32x8::ZERO;
        for c in &self.cdf[..self.cdf.len() - 1] {
            chosen += ge(u, *c) & f32x8::ONE;
        }
        let (mut origin, mut dir) = (Vec3x8::ZERO, Vec3x8::ZERO);
        for (k, light) in self.lights.iter().enumerate() {
            let mine = chosen.simd_eq(f32x8::splat(k as f32));
            if mine.any() {
                let (o, d) = self.emit_from(light, index, u1, u2);
                origin = Vec3x8::select(mine, o, origin);
                dir = Vec3x8::select(mine, d, dir);
            }
        }
        (origin, dir)
    }

    #[inline]
    fn emit_from(&self, light: &Emitter, index: u32x8, u1: f32x8, u2: f32x8) -> (Vec3x8, Vec3x8) {
        match *light {
            Emitter::Spot { position, axis, t, b, cos_max } => {
                let cos_t = f32x8::ONE - u1 * (f32x8::ONE - cos_max);
                let sin_t = (f32x8::ONE - cos_t * cos_t).max(f32x8::ZERO).sqrt();
                let (sin_phi, cos_phi) = sin_cos_turns(u2);
                (position, (t * (sin_t * cos_phi) + b * (sin_t * sin_phi) + axis * cos_t).normalize())
            }
            Emitter::Point { position } => {
                let z = f32x8::ONE - f32x8::splat(2.0) * u1;
                let r = (f32x8::ONE - z * z).max(f32x8::ZERO).sqrt();
                let (sin_phi, cos_phi) = sin_cos_turns(u2);
                (position, Vec3x8 { x: r * cos_phi, y: r * sin_phi, z })
            }
            Emitter::Beam { position, axis, t, b, radius } => {
                let rnd = |d: u32| crate::simd::random_f32(self.seed, index, u32x8::splat(d));
                let r = radius * rnd(dim::POSITION).sqrt();
                let (sin_phi, cos_phi) = sin_cos_turns(rnd(dim::POSITION + 1));
                (position + (t * cos_phi + b * sin_phi) * r, axis)
            }
        }
    }
}
