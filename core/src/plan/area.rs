//! Emissive meshes as lights: each triangle of a mesh whose material emits
//! becomes a Lambertian area light, and the most powerful are cut into
//! four until the render's `area_lights` budget is spent.

use crate::model::scene::{Light, Scene, Shape};
use crate::model::spectrum::Spectrum;
use alloc::vec::Vec;
use core::f32::consts::PI;
use glam::Vec3;

/// The area lights of `scene`'s emissive meshes, in object and triangle
/// order: one per triangle of non-zero area, the most powerful cut at its
/// edges' midpoints into four of equal power while at most
/// `render.area_lights` pieces result. Each carries the smooth spectrum of
/// its material's emission ([`Spectrum::from_rgb`]) and the flux
/// π · area · L out of its front face, L the emission's factor.
pub fn area_lights(scene: &Scene) -> Vec<Light> {
    let mut pieces: Vec<([Vec3; 3], usize)> = Vec::new();
    let mut emissions: Vec<(Spectrum, f32)> = Vec::new();
    for object in scene.objects.iter().filter(|o| scene.emits(o)) {
        let Shape::Mesh { positions, triangles, .. } = &object.shape else { continue };
        let (spectrum, radiance) = Spectrum::from_rgb(scene.materials[object.material].kind.emission().to_array());
        emissions.push((spectrum, radiance));
        for t in triangles {
            let v = t.map(|i| positions[i as usize]);
            if area(&v) > 0.0 {
                pieces.push((v, emissions.len() - 1));
            }
        }
    }
    let power = |&(v, e): &([Vec3; 3], usize)| PI * area(&v) * emissions[e].1;
    while pieces.len() + 3 <= scene.render.area_lights as usize {
        let strongest = (0..pieces.len()).max_by(|&a, &b| power(&pieces[a]).total_cmp(&power(&pieces[b])));
        let Some(k) = strongest else { break };
        let ([a, b, c], e) = pieces[k];
        let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5);
        pieces[k] = ([ab, bc, ca], e);
        pieces.extend([([a, ab, ca], e), ([ab, b, bc], e), ([ca, bc, c], e)]);
    }
    pieces
        .iter()
        .filter(|p| power(p) > 0.0)
        .map(|p| Light::Area { vertices: p.0, power: power(p), spectrum: emissions[p.1].0.clone() })
        .collect()
}

/// The area of triangle `v`.
pub fn area(v: &[Vec3; 3]) -> f32 {
    0.5 * (v[1] - v[0]).cross(v[2] - v[0]).length()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scene::{Camera, Material, MaterialKind, Object};

    fn panel_scene(budget: u32) -> Scene {
        let render = crate::RenderSettings { area_lights: budget, ..Default::default() };
        let camera = Camera { position: Vec3::new(0.0, 1.0, 5.0), look_at: Vec3::ZERO, up: Vec3::Y, fov_deg: 40.0 };
        let materials = Vec::from([Material {
            name: "panel".into(),
            kind: MaterialKind::Diffuse {
                albedo: Vec3::ZERO,
                checker: None,
                texture: None,
                emission: Vec3::splat(2.0),
            },
        }]);
        let positions = Vec::from([Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 2.0), Vec3::new(0.0, 0.0, 2.0)]);
        let triangles = Vec::from([[0, 1, 2], [0, 2, 3]]);
        let objects = Vec::from([Object { shape: Shape::Mesh { positions, triangles, uvs: Vec::new() }, material: 0 }]);
        Scene { render, camera, lights: Vec::new(), materials, objects }
    }

    #[test]
    fn cutting_keeps_the_flux_and_spends_the_budget() {
        for (budget, pieces) in [(1, 2), (2, 2), (5, 5), (16, 14), (64, 62)] {
            let lights = area_lights(&panel_scene(budget));
            assert_eq!(lights.len(), pieces, "budget {budget}");
            let flux: f32 = lights.iter().map(Light::power).sum();
            // A white emission of 2: the equal-energy spectrum at factor 2, over 2 m².
            assert!((flux - PI * 2.0 * 2.0).abs() < 1e-4, "budget {budget}: {flux}");
        }
    }
}
