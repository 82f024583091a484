//! Area lights' shadows drawn anew each pass: with per-pass view paths,
//! pass k draws one point y of each area light, uniformly by area, from
//! the light's own Owen-scrambled Sobol sequence over the passes. A
//! visible point keeps the closed form E of the light's unblocked
//! irradiance, and where y is hidden from it, it loses what y stands for:
//! L·A·G(y), with G(y) = cos θ_p cos θ_y / r² (zero behind its horizon).
//! E − L·A·G(y)·[y hidden] is a control variate. Its mean over y is
//! E − L∫G(1 − V) dA = L∫G·V dA, exactly the shadowed irradiance. Where
//! the light is seen whole it is E with no noise at all. In a penumbra it
//! is noisy, and a pass can make it negative where a hidden y stands for
//! more than the mean; the passes' mean cannot. Aiming every shadow ray at
//! the centre of the part a point sees, as view paths shared by every pass
//! still do, lit or hid a piece whole: a penumbra in steps, biased. Any
//! pass is made alone, so split and merged renders agree.

use crate::model::scene::Light;
use crate::sampling::sobol::sobol_f32;
use crate::util::math::sqrt;
use crate::util::rng::{dim, random_u32};
use core::f32::consts::PI;
use glam::Vec3;

/// Draws the area lights' points among `lights` (a scene's lights or
/// emitters, in the same order) for pass `pass` (`seed`: the render's).
pub fn aim(lights: &mut [Light], seed: u32, pass: u32) {
    for (i, light) in lights.iter_mut().enumerate() {
        if let Light::Area { aim, .. } = light {
            let stream = random_u32(seed, i as u32, dim::AIM);
            *aim = Some(uniform_on_triangle(sobol_f32(stream, pass, 0), sobol_f32(stream, pass, 1)));
        }
    }
}

/// Barycentric (s, t) along (b − a, c − a) of a point uniform on a triangle
/// by area, from two uniform numbers.
pub fn uniform_on_triangle(u1: f32, u2: f32) -> [f32; 2] {
    let r = sqrt(u1);
    [r * (1.0 - u2), r * u2]
}

/// The point of triangle `[a, b, c]` at barycentric `[s, t]`.
pub fn on_triangle([a, b, c]: [Vec3; 3], [s, t]: [f32; 2]) -> Vec3 {
    a + (b - a) * s + (c - a) * t
}

/// The pass's point y of area light `vertices` (flux `power`) at
/// barycentric `aim`, and what its shadow takes from the irradiance at `p`
/// (unit normal `n`, in front of the light): L·A·G(y) =
/// (power / π)·cos θ_p cos θ_y / r². `None` where `p` sees y on or behind
/// its horizon (G = 0: nothing to take, no shadow ray).
pub fn shadow_sample(vertices: [Vec3; 3], power: f32, aim: [f32; 2], p: Vec3, n: Vec3) -> Option<(Vec3, f32)> {
    let y = on_triangle(vertices, aim);
    let d = y - p;
    let cos_p = n.dot(d);
    if cos_p <= 0.0 {
        return None;
    }
    let [a, b, c] = vertices;
    let cos_y = -(b - a).cross(c - a).normalize().dot(d);
    let r2 = d.length_squared();
    Some((y, power / PI * cos_p * cos_y.max(0.0) / (r2 * r2)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::spectrum::Spectrum;

    #[test]
    fn the_aims_of_the_passes_cover_the_light_evenly() {
        // Over 256 passes, each quarter of the triangle (cut at its edges'
        // midpoints) gets a quarter of the aims.
        let vertices = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let mut lights = [Light::Area { vertices, power: 1.0, spectrum: Spectrum::default(), aim: None }];
        let mut quarters = [0u32; 4];
        for pass in 0..256 {
            aim(&mut lights, 7, pass);
            let Light::Area { aim: Some(st), .. } = lights[0] else { panic!("aimed") };
            let p = on_triangle(vertices, st);
            assert!(p.x >= 0.0 && p.y >= 0.0 && p.x + p.y <= 1.0, "{p} on the triangle");
            let q = if p.x > 0.5 {
                1
            } else if p.y > 0.5 {
                2
            } else if p.x + p.y < 0.5 {
                0
            } else {
                3
            };
            quarters[q] += 1;
        }
        assert!(quarters.iter().all(|&n| (56..=72).contains(&n)), "{quarters:?}");
    }
}
