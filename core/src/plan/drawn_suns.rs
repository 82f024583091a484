//! An environment's suns drawn anew each pass: with per-pass view paths the
//! regions of the median cut are strata, and pass k's sun of a region
//! points along a direction drawn there with probability ∝ radiance
//! ([`EnvironmentCut::draw`]), with the region's whole Σ L dω as
//! irradiance. Its direct light and shadows at the pass's visible points,
//! and the beam its caustic photons leave from, follow that direction, so
//! the passes' mean converges to the map's light: the horizon a surface
//! cuts a region with and the soft shadows it casts included, where the
//! fixed suns of the cut keep a bias. Each region's numbers are its own
//! Owen-scrambled Sobol sequence over the passes, so the draws are
//! stratified across passes and any pass is made alone (split and merged
//! renders agree).
//!
//! A drawn sun's direct light at a visible point is a control variate.
//! With E its irradiance, ω its direction and m̄ the draws' mean direction
//! ([`crate::sampling::environment::CutRegion::mean_toward`]), E n·ω has the
//! known mean E n·m̄, so the estimate E cos⁺θ V − E cos θ + E n·m̄ has the
//! same mean as E cos⁺θ V and is E n·m̄ exactly wherever the draw is above
//! the horizon and seen. It is taken where n·m̄ > 0, and E cos⁺θ V (0
//! wholly below) elsewhere; which one is taken changes the noise, never
//! the mean. A pass can be negative in a shadow; the passes' mean cannot.

use crate::model::scene::Light;
use crate::plan::projection::Projection;
use crate::plan::reach::sun_beam;
use crate::sampling::environment::EnvironmentCut;
use crate::sampling::sobol::sobol_f32;
use crate::util::rng::{dim, random_u32};
use alloc::sync::Arc;
use alloc::vec::Vec;
use glam::Vec3;

/// What a pass needs to draw an environment's suns.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawnSuns {
    /// The cut the suns are drawn from (shared by the passes' scenes).
    pub cut: Arc<EnvironmentCut>,
    /// Per drawn sun: its index in the scene's lights and emitters, and its region.
    pub suns: Vec<(usize, usize)>,
    /// The spheres a sun's beam covers ([`sun_beam`]'s targets).
    pub beam_targets: Vec<(Vec3, f32)>,
    /// Every object's bounding sphere (the beam starts beyond them).
    pub bounds: Vec<(Vec3, f32)>,
    /// The mirrors' and glass's spheres, which projection maps aim at.
    pub aimed_at: Vec<(Vec3, f32)>,
}

impl DrawnSuns {
    /// The direction toward sun `sun`'s light in pass `pass` (`seed`: the
    /// render's seed).
    fn toward(&self, sun: usize, seed: u32, pass: u32) -> Vec3 {
        let region = self.suns[sun].1;
        let stream = random_u32(seed, region as u32, dim::SKY);
        self.cut.draw(region, sobol_f32(stream, pass, 0), sobol_f32(stream, pass, 1))
    }

    /// Points a scene's drawn suns along their directions of pass `pass`
    /// (`seed`: the render's): its `lights`, the beams they emit from
    /// (`emitters`) and those beams' `projections` where the plan aims them.
    pub fn point(
        &self,
        (lights, emitters, projections): (&mut [Light], &mut [Light], &mut [Option<Projection>]),
        seed: u32,
        pass: u32,
    ) {
        for (sun, &(i, region)) in self.suns.iter().enumerate() {
            let Light::Sun { irradiance, spectrum, .. } = &lights[i] else {
                unreachable!("light {i} is an environment's sun")
            };
            let direction = -self.toward(sun, seed, pass);
            let beam = sun_beam(direction, *irradiance, spectrum, &self.beam_targets, &self.bounds);
            if projections[i].is_some() {
                projections[i] = Projection::new(&beam, &self.aimed_at);
            }
            let mean_toward = Some(self.cut.regions[region].mean_toward);
            lights[i] = Light::Sun { direction, irradiance: *irradiance, spectrum: spectrum.clone(), mean_toward };
            emitters[i] = beam;
        }
    }
}
