//! Emissive meshes as lights: each triangle of a mesh whose material emits
//! becomes a Lambertian area light, and the most powerful are cut into
//! four until the render's `area_lights` budget is spent; more emissive
//! triangles than the budget are a choice of them by power that carries
//! the whole flux ([`crate::plan::drawn_triangles`]).

use crate::model::scene::{Light, Scene, Shape};
use crate::model::spectrum::Spectrum;
use crate::plan::drawn_triangles::TriangleChoice;
use alloc::vec::Vec;
use core::f32::consts::PI;
use glam::Vec3;

/// A scene's emissive meshes as area lights.
#[derive(Clone, Debug, PartialEq)]
pub enum AreaLights {
    /// As many triangles as the budget or fewer: each is lit, cut into pieces.
    Pieces(Vec<Light>),
    /// More: the budget's lights are a choice of them by power
    /// ([`TriangleChoice::lights`]).
    Chosen(TriangleChoice),
}

/// The area lights of `scene`'s emissive meshes, in object and triangle
/// order: one per triangle of non-zero area, the most powerful cut at its
/// edges' midpoints into four of equal power while at most
/// `render.area_lights` pieces result. Each carries the smooth spectrum of
/// its material's emission ([`Spectrum::from_rgb`]) and the flux
/// π · area · L out of its front face, L the emission's factor.
///
/// With more emissive triangles than `render.area_lights` (an emissive
/// mesh of thousands, which as many lights would make every visible point
/// trace thousands of shadow rays), the triangles to choose that many from
/// by power ([`crate::plan::drawn_triangles`]); the camera still sees every
/// triangle glow.
pub fn area_lights(scene: &Scene) -> AreaLights {
    let mut pieces: Vec<([Vec3; 3], usize)> = Vec::new();
    let mut emissions: Vec<(Spectrum, f32)> = Vec::new();
    let budget = scene.render.area_lights as usize;
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
    pieces.retain(|p| power(p) > 0.0);
    if pieces.len() > budget {
        let mut acc = 0.0f64;
        let cdf = pieces
            .iter()
            .map(|p| {
                acc += f64::from(power(p));
                acc
            })
            .collect();
        let spectra = emissions.into_iter().map(|(spectrum, _)| spectrum).collect();
        return AreaLights::Chosen(TriangleChoice { triangles: pieces, spectra, cdf, budget });
    }
    while pieces.len() + 3 <= budget {
        let strongest = (0..pieces.len()).max_by(|&a, &b| power(&pieces[a]).total_cmp(&power(&pieces[b])));
        let Some(k) = strongest else { break };
        let ([a, b, c], e) = pieces[k];
        let (ab, bc, ca) = ((a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5);
        pieces[k] = ([ab, bc, ca], e);
        pieces.extend([([a, ab, ca], e), ([ab, b, bc], e), ([ca, bc, c], e)]);
    }
    AreaLights::Pieces(
        pieces
            .iter()
            .map(|p| Light::Area { vertices: p.0, power: power(p), spectrum: emissions[p.1].0.clone(), aim: None })
            .collect(),
    )
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
            normal_map: None,
            roughness_map: None,
            film_map: None,
            specular_map: None,
        }]);
        let positions = Vec::from([Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 2.0), Vec3::new(0.0, 0.0, 2.0)]);
        let triangles = Vec::from([[0, 1, 2], [0, 2, 3]]);
        let objects = Vec::from([Object {
            shape: Shape::Mesh { positions, triangles, uvs: Vec::new(), normals: Vec::new(), tangents: Vec::new() },
            material: 0,
        }]);
        Scene { render, camera, lights: Vec::new(), materials, objects }
    }

    #[test]
    fn more_triangles_than_the_budget_are_chosen_by_power_with_the_whole_flux() {
        // A strip of 40 triangles, every other one twice as wide.
        let mut scene = panel_scene(8);
        let positions: Vec<Vec3> = (0..=40)
            .flat_map(|i| {
                let x = i as f32 * 0.1;
                [Vec3::new(x, 0.0, 0.0), Vec3::new(x, 0.0, 1.0 + (i % 2) as f32)]
            })
            .collect();
        let triangles: Vec<[u32; 3]> = (0..40u32).map(|i| [2 * i, 2 * i + 1, 2 * i + 2]).collect();
        let total: f32 = triangles.iter().map(|t| area(&t.map(|i| positions[i as usize]))).sum::<f32>() * PI * 2.0;
        scene.objects[0].shape =
            Shape::Mesh { positions, triangles, uvs: Vec::new(), normals: Vec::new(), tangents: Vec::new() };
        let AreaLights::Chosen(choice) = area_lights(&scene) else { panic!("40 triangles, a budget of 8") };
        assert_eq!(choice.triangles.len(), 40);
        for xi in [0.0, 0.5, 0.99] {
            let lights = choice.lights(xi);
            assert_eq!(lights.len(), 8, "offset {xi}");
            let flux: f32 = lights.iter().map(Light::power).sum();
            assert!((flux - total).abs() < 1e-4 * total, "offset {xi}: {flux} vs {total}");
        }
    }

    #[test]
    fn cutting_keeps_the_flux_and_spends_the_budget() {
        for (budget, pieces) in [(1, 1), (2, 2), (5, 5), (16, 14), (64, 62)] {
            // The two triangles with a budget of 1: a choice of one, carrying both's flux.
            let lights = match area_lights(&panel_scene(budget)) {
                AreaLights::Pieces(lights) => lights,
                AreaLights::Chosen(choice) => choice.lights(0.5),
            };
            assert_eq!(lights.len(), pieces, "budget {budget}");
            let flux: f32 = lights.iter().map(Light::power).sum();
            // A white emission of 2: the equal-energy spectrum at factor 2, over 2 m².
            assert!((flux - PI * 2.0 * 2.0).abs() < 1e-4, "budget {budget}: {flux}");
        }
    }
}
