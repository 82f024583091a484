//! The pass schedule: what photon pass `k` of a render traces and within
//! which radii it gathers, the same on every backend.
//!
//! With progressive radii ([`RadiusMode::Progressive`]) this is the
//! memoryless form of Knaus & Zwicker (2011): pass k (from 1) gathers with
//! r_k² = r_1² · Π_{j=1}^{k−1} (j + α)/(j + 1), and the image is the plain
//! mean of the passes' estimates. With 0 < α < 1 both the variance and the
//! bias of the mean go to zero, so the mean converges to the true caustic,
//! which a fixed radius never does (it stays blurred by r). Hachisuka's
//! α ≈ 0.7 is the usual compromise between the two.
//!
//! Each visible point has its own r_1: a pilot pass (its own seed, an
//! eighth of the photons) counts the photons within the scene's radius R
//! around the point, and r_1 is the radius that would hold the scene's
//! `neighbours` photon paths of a full pass at that density, between
//! R·[`MIN_RADIUS_FRACTION`] and R. A path is what one white photon
//! leaves: N band photons when it splits into all N bands (they land
//! together until the glass fans them out), one otherwise. Dense caustics
//! get small radii (sharp, and each gather visits few photons); sparse
//! regions keep R.
//!
//! With [`RadiusMode::Fixed`] there is no pilot: every pass gathers within
//! R at every point (the paper's frame).
//!
//! Passes share nothing but the visible points and their r_1, both fixed by
//! the scene and seed, so any set of passes can be rendered anywhere and
//! summed later ([`crate::render::accumulation`]).

use crate::model::scene::RadiusMode;
use crate::plan::prepared::PreparedScene;
use crate::util::math::sqrt;
use crate::util::rng::random_u32;

/// The smallest first radius, as a fraction of the scene's radius: it
/// bounds the grid levels a pass needs (see [`level_of`]).
pub const MIN_RADIUS_FRACTION: f32 = 1.0 / 32.0;

/// The pilot pass traces this fraction (1/N) of a pass's photons.
pub const PILOT_PHOTON_DIVISOR: u32 = 8;

/// Grid levels of a pass: level l has cells for radius R_k / 4^l, so a
/// point of radius r uses the finest level whose radius is still ≥ r.
pub const GRID_LEVELS: usize = 3;

/// The factor s_k by which the radii of pass `k` (1-based) are those of
/// pass 1: r_k = r_1 · s_k.
pub fn shrink(alpha: f32, k: u32) -> f32 {
    let mut r2 = 1.0f64;
    for j in 1..k {
        r2 *= (f64::from(j) + f64::from(alpha)) / (f64::from(j) + 1.0);
    }
    sqrt(r2 as f32)
}

/// The radius of pass `k` (1-based) when pass 1 uses `r1`.
pub fn pass_radius(r1: f32, alpha: f32, k: u32) -> f32 {
    r1 * shrink(alpha, k)
}

/// The radius scale of pass `pass` (0-based): what every first radius is
/// multiplied by (1 with fixed radii).
pub fn pass_shrink(scene: &PreparedScene, pass: u32) -> f32 {
    match scene.scene.render.radius_mode {
        RadiusMode::Progressive => shrink(scene.scene.render.alpha, pass.saturating_add(1)),
        RadiusMode::Fixed => 1.0,
    }
}

/// The scene of photon pass `pass` (0-based): its own seed (derived from
/// the scene's, so passes are independent), as its radius the pass's
/// largest radius R·s_k (k = pass + 1; R with fixed radii), and its
/// lights of the pass where they change each pass (drawn suns, area
/// lights' aims: [`PreparedScene::lights_of_pass`]).
pub fn pass_scene(scene: &PreparedScene, pass: u32) -> PreparedScene {
    let k = pass.saturating_add(1);
    let mut photons = scene.lights_of_pass(pass).unwrap_or_else(|| scene.clone());
    let r = &mut photons.scene.render;
    r.seed = random_u32(r.seed, k, u32::MAX);
    if r.radius_mode == RadiusMode::Progressive {
        r.radius = pass_radius(r.radius, r.alpha, k);
    }
    photons
}

/// The pilot pass of a render with progressive radii: a seed no photon
/// pass uses, the scene's radius, and 1/[`PILOT_PHOTON_DIVISOR`] of the
/// photons, caustic and indirect. `None` with fixed radii (every first
/// radius is R).
pub fn pilot_scene(scene: &PreparedScene) -> Option<PreparedScene> {
    if scene.scene.render.radius_mode == RadiusMode::Fixed {
        return None;
    }
    let mut pilot = scene.clone();
    let r = &mut pilot.scene.render;
    r.seed = random_u32(r.seed, 0, u32::MAX);
    r.photons = (r.photons / PILOT_PHOTON_DIVISOR).max(1);
    if r.indirect_photons > 0 {
        r.indirect_photons = (r.indirect_photons / PILOT_PHOTON_DIVISOR).max(1);
    }
    Some(pilot)
}

/// How the pilot's counts become first radii: a full pass traces `scale`
/// times the pilot's photons, and a first radius should hold `neighbours`
/// of its photons. Backends that compute the radii elsewhere (a GPU) take
/// these two numbers with them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PilotScale {
    /// A full pass's photons per pilot photon.
    pub scale: f32,
    /// Photons a first radius should hold: neighbours × photons per path.
    pub neighbours: f32,
}

impl PilotScale {
    /// The pilot of `scene` (whose pilot scene is `pilot`).
    pub fn new(scene: &PreparedScene, pilot: &PreparedScene) -> Self {
        let r = &scene.scene.render;
        PilotScale {
            scale: scene.traced_photons() as f32 / pilot.traced_photons().max(1) as f32,
            neighbours: (r.neighbours * photons_per_path(scene)) as f32,
        }
    }

    /// A point's first radius from the photons its pilot gather found within `r0`.
    pub fn first_radius(&self, r0: f32, pilot_photons: u32) -> f32 {
        initial_radius(r0, pilot_photons, self.scale, self.neighbours)
    }
}

/// A point's first radius from the photons its pilot gather found within
/// `r0`, when a full pass has `scale` times the pilot's photons and the
/// radius should hold `neighbours` of them.
pub fn initial_radius(r0: f32, pilot_photons: u32, scale: f32, neighbours: f32) -> f32 {
    let expected = pilot_photons as f32 * scale;
    if expected <= neighbours {
        return r0;
    }
    (r0 * sqrt(neighbours / expected)).clamp(r0 * MIN_RADIUS_FRACTION, r0)
}

/// Stored photons per independent photon path: a white photon split into
/// N bands (or M hero wavelengths) leaves N photons that travel together
/// until the glass fans them.
pub fn photons_per_path(scene: &PreparedScene) -> u32 {
    scene.scene.render.wavelengths.paths(scene.bands.len())
}

/// The grid radius of `level` in a pass whose largest radius is `r_pass`.
pub fn level_radius(r_pass: f32, level: usize) -> f32 {
    r_pass / (1u32 << (2 * level)) as f32
}

/// The finest grid level whose radius is at least `r` (≤ `r_pass`).
pub fn level_of(r: f32, r_pass: f32) -> usize {
    let mut level = 0;
    while level + 1 < GRID_LEVELS && r <= level_radius(r_pass, level + 1) {
        level += 1;
    }
    level
}

/// Which grid levels a pass whose largest radius is `r_pass` needs for
/// points of radii `radii` (the rest are not built).
pub fn levels_used(radii: &[f32], r_pass: f32) -> [bool; GRID_LEVELS] {
    let mut used = [false; GRID_LEVELS];
    for &r in radii {
        used[level_of(r, r_pass)] = true;
    }
    used
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radius_shrinks_as_the_closed_form_says() {
        assert_eq!(pass_radius(0.1, 0.7, 1), 0.1);
        // r_2² = r_1² (1 + α)/2.
        assert!((pass_radius(0.1, 0.7, 2) - 0.1 * (0.85f32).sqrt()).abs() < 1e-8);
        // Π (j+α)/(j+1) ~ Γ(2)/Γ(1+α) · k^(α−1): r_k² falls like k^(−0.3).
        let r = |k| f64::from(pass_radius(1.0, 0.7, k)).powi(2);
        let slope = (r(4000) / r(1000)).ln() / 4f64.ln();
        assert!((slope + 0.3).abs() < 1e-3, "slope {slope}");
        // α = 1 keeps the radius.
        assert_eq!(pass_radius(0.1, 1.0, 50), 0.1);
    }
}
