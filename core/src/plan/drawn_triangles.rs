//! Emissive triangles drawn anew each pass: with more emissive triangles
//! than the render's `area_lights` budget (an emissive texture on a model
//! of thousands), the budget's lights are a choice of them by power,
//! each carrying Φ/budget. One choice for the whole render would light
//! the scene from those few triangles only, which is biased. With per-pass
//! view paths, pass k makes its own choice by systematic sampling: its
//! lights are the triangles at (j + ξ_k)/budget of the power's CDF,
//! j = 0 … budget − 1, with ξ_k one Owen-scrambled Sobol sequence over the
//! passes. A triangle of power P is then chosen budget·P/Φ times per pass
//! on average, so the passes' mean has each triangle's own light, its
//! photons and its shadows included. The ξ_k are stratified, so over n
//! passes every triangle is chosen within one of its expected n·budget·P/Φ
//! times. Any pass is made alone, so split and merged renders agree.

use crate::model::scene::Light;
use crate::model::spectrum::Spectrum;
use crate::sampling::sobol::sobol_f32;
use crate::util::rng::{dim, random_u32};
use alloc::sync::Arc;
use alloc::vec::Vec;
use core::ops::Range;
use glam::Vec3;

/// An emissive mesh's triangles to choose the area lights from by power.
#[derive(Clone, Debug, PartialEq)]
pub struct TriangleChoice {
    /// Each triangle of non-zero power: its vertices and its emission's index.
    pub triangles: Vec<([Vec3; 3], usize)>,
    /// The emissions' spectra (each material's, [`Spectrum::from_rgb`]).
    pub spectra: Vec<Spectrum>,
    /// The triangles' cumulative power (the last is Φ).
    pub cdf: Vec<f64>,
    /// How many lights a choice makes (the render's `area_lights`).
    pub budget: usize,
}

impl TriangleChoice {
    /// The choice at offset `xi` ∈ [0, 1): `budget` area lights, the j-th
    /// the triangle at (j + xi)/budget of the power's CDF, each with flux
    /// Φ/budget (a triangle chosen twice is two lights).
    pub fn lights(&self, xi: f32) -> Vec<Light> {
        let total = self.cdf.last().copied().unwrap_or(0.0);
        let share = (total / self.budget as f64) as f32;
        (0..self.budget)
            .map(|j| {
                let u = (j as f64 + f64::from(xi)) / self.budget as f64 * total;
                let k = self.cdf.partition_point(|&c| c <= u).min(self.triangles.len() - 1);
                let (vertices, emission) = self.triangles[k];
                Light::Area { vertices, power: share, spectrum: self.spectra[emission].clone(), aim: None }
            })
            .collect()
    }
}

/// What a pass needs to draw its choice of emissive triangles.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawnTriangles {
    /// The triangles to choose from (shared by the passes' scenes).
    pub choice: Arc<TriangleChoice>,
    /// The index of the choice's first light in the scene's lights and
    /// emitters; the choice's `budget` lights follow it.
    pub first: usize,
    /// The mirrors' and glass's spheres, which projection maps aim at.
    pub aimed_at: Vec<(Vec3, f32)>,
}

impl DrawnTriangles {
    /// The indices of the chosen lights in the scene's lights and emitters.
    pub fn slots(&self) -> Range<usize> {
        self.first..self.first + self.choice.budget
    }

    /// Puts the choice of pass `pass` (`seed`: the render's) into a scene's
    /// `lights` and `emitters` (an area light emits as itself).
    pub fn draw(&self, lights: &mut [Light], emitters: &mut [Light], seed: u32, pass: u32) {
        let xi = sobol_f32(random_u32(seed, 0, dim::TRIANGLES), pass, 0);
        let chosen = self.choice.lights(xi);
        lights[self.slots()].clone_from_slice(&chosen);
        emitters[self.slots()].clone_from_slice(&chosen);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of `n` triangles along x, the k-th of power 1 + k % 3.
    fn strip(n: usize, budget: usize) -> TriangleChoice {
        let mut acc = 0.0;
        let (triangles, cdf) = (0..n)
            .map(|k| {
                acc += 1.0 + (k % 3) as f64;
                let x = k as f32;
                (([Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 0.0, 0.0), Vec3::new(x, 0.0, 1.0)], 0), acc)
            })
            .unzip();
        TriangleChoice { triangles, spectra: Vec::from([Spectrum::default()]), cdf, budget }
    }

    #[test]
    fn over_the_passes_each_triangle_is_chosen_as_often_as_its_power_says() {
        let (n, budget, passes) = (40, 8, 64u32);
        let choice = Arc::new(strip(n, budget));
        let total = choice.cdf[n - 1];
        let drawn = DrawnTriangles { choice: choice.clone(), first: 1, aimed_at: Vec::new() };
        let mut lights = alloc::vec![Light::Area { vertices: [Vec3::ZERO; 3], power: 0.0, spectrum: Spectrum::default(), aim: None }; budget + 1];
        let mut emitters = lights.clone();
        let mut chosen = alloc::vec![0u32; n];
        for pass in 0..passes {
            drawn.draw(&mut lights, &mut emitters, 3, pass);
            assert_eq!(lights, emitters, "pass {pass}: an area light emits as itself");
            assert!(matches!(lights[0], Light::Area { power: 0.0, .. }), "pass {pass}: the light before the slots");
            for light in &lights[1..] {
                let Light::Area { vertices, power, .. } = light else { panic!("an area light") };
                assert!((f64::from(*power) - total / budget as f64).abs() < 1e-5, "each carries Φ/budget");
                chosen[vertices[0].x as usize] += 1;
            }
        }
        for (k, &times) in chosen.iter().enumerate() {
            let expected = f64::from(passes) * budget as f64 * (1.0 + (k % 3) as f64) / total;
            assert!(
                (f64::from(times) - expected).abs() <= 1.0,
                "triangle {k}: chosen {times} times, {expected} expected"
            );
        }
    }
}
