//! Visible points on rough metal and glass rough enough
//! (`prismatic_core::optics::microfacet::Ggx::gathers`) gather the photons
//! of hidden lights met there, with the surface's BSDF: the light that
//! mirrors, metals and glass bring there, which no view ray finds. They
//! show it where the camera sees the surface through a mirror or glass,
//! and, without light tracing, where it sees it directly; across the
//! threshold the caustic keeps its energy (light tracing takes it below).

use prismatic_core::optics::microfacet::GATHER_ALPHA;
use prismatic_core::{Material, Vec3};
use prismatic_cpu::CpuBackend;
use prismatic_tests::backends::{every_backend, image_after};
use prismatic_tests::rough::{
    ball_top_radiance, beam_in_a_frosted_ball, beam_on_a_rough_floor, frosted, image_sum, rough_metal,
};

#[test]
fn a_caustic_on_a_rough_floor_keeps_its_energy_across_the_gather_threshold() {
    // A beam folded by a mirror onto a rough floor (a metal, a frosted
    // sheet): just below the threshold its caustic is light traced, just
    // above it is gathered at visible points (without light tracing).
    // Each must show what the beam straight onto the floor shows as the
    // view's highlight (CPU, 16 passes), and the two the same energy:
    // summed over the image, within 2.5 %.
    let edge = GATHER_ALPHA.sqrt();
    let metal = |roughness| rough_metal(Vec3::new(0.9, 0.6, 0.3), roughness);
    let sheet = |roughness| frosted(1.5, roughness, true);
    let floors: [(&str, &dyn Fn(f32) -> Material); 2] = [("a rough metal", &metal), ("a frosted sheet", &sheet)];
    for (what, floor) in floors {
        let (below, above) = (floor(edge * 0.999), floor(edge * 1.001));
        let highlight = |floor: &Material| {
            let sum = image_sum(&mut CpuBackend::new(), &beam_on_a_rough_floor(floor.clone(), false, false, false), 16);
            assert!(sum > 1.0, "{what}: the beam's highlight {sum:.3}");
            sum
        };
        let (highlight_below, highlight_above) = (highlight(&below), highlight(&above));
        for mut backend in every_backend() {
            let name = backend.name();
            let traced = image_sum(backend.as_mut(), &beam_on_a_rough_floor(below.clone(), false, true, true), 4);
            let gathered = image_sum(backend.as_mut(), &beam_on_a_rough_floor(above.clone(), false, true, false), 8);
            let (below, above) = (traced / highlight_below, gathered / highlight_above);
            assert!((below - 1.0).abs() < 0.02, "{name}, {what}: light traced below, {below:.4} of the highlight");
            assert!((above - 1.0).abs() < 0.025, "{name}, {what}: gathered above, {above:.4} of the highlight");
            assert!(
                (gathered / traced - 1.0).abs() < 0.025,
                "{name}, {what}: gathered {gathered:.3}, traced {traced:.3}"
            );
        }
    }
}

#[test]
fn gathered_light_leaving_rough_glass_has_walters_radiance_seen_directly_and_in_a_mirror() {
    // The top of a frosted ball lit from inside by a beam, gathered at
    // visible points: seen directly without light tracing, and in a mirror
    // with it (light tracing cannot reach the camera through a mirror).
    // Every pixel's gather disc lies within the beam's spot, where the
    // light is uniform: the gather's blur costs nothing.
    let want = ball_top_radiance();
    for (light_tracing, in_a_mirror) in [(false, false), (true, true)] {
        let scene = beam_in_a_frosted_ball(light_tracing, in_a_mirror);
        for mut backend in every_backend() {
            let name = backend.name();
            let image = image_after(backend.as_mut(), &scene, 4);
            let got = image.pixels.iter().map(|p| f64::from(p.element_sum()) / 3.0).sum::<f64>() / 64.0;
            let how = if in_a_mirror { "in a mirror" } else { "directly" };
            assert!((got / want - 1.0).abs() < 0.02, "{name}, {how}: gathered {got:.3}, Walter's {want:.3}");
        }
    }
}
