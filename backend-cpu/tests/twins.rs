//! The CPU's packet optics (`prismatic_cpu::optics`) are the core's
//! (`prismatic_core::optics::fresnel`) bit for bit, lane by lane, on generated rays:
//! grazing incidence, total internal reflection, indices within 1e-6 of 1,
//! glass in a denser medium (`prismatic_conformance::twins`).

use prismatic_conformance::scenes::lit_by_every_light_kind;
use prismatic_conformance::twins::{
    Agreement, ScatterCase, SurfaceAnswer, SurfaceCase, check_surface, config, scatter_case, surface_case,
};
use prismatic_core::Vec3;
use prismatic_core::model::scene::PhotonSequence;
use prismatic_core::optics::scatter;
use prismatic_cpu::optics::{
    fresnel, interface, offset_origin, reflect, refract, scatter_dielectric, split_dielectric,
};
use prismatic_cpu::simd::Vec3x8;
use proptest::prelude::*;
use wide::f32x8;

/// The packet optics on eight cases at once, one per lane.
fn packet(cases: &[SurfaceCase; 8]) -> [SurfaceAnswer; 8] {
    let d = Vec3x8::from_lanes(&cases.map(|c| c.d));
    let outward = Vec3x8::from_lanes(&cases.map(|c| c.outward));
    let (n, n1, n2) = interface(d, outward, f32x8::new(cases.map(|c| c.ior)));
    let fresnel = fresnel(-d.dot(n), n1, n2).to_array();
    let reflected = reflect(d, n);
    let (tir, refracted) = refract(d, n, n1, n2);
    let (n1, n2, tir) = (n1.to_array(), n2.to_array(), tir.to_bitmask());
    std::array::from_fn(|i| SurfaceAnswer {
        normal: n.lane(i),
        n1: n1[i],
        n2: n2[i],
        fresnel: fresnel[i],
        reflected: reflected.lane(i),
        refracted: (tir & (1 << i) == 0).then(|| refracted.lane(i)),
    })
}

proptest! {
    #![proptest_config(config(2048, 0x0971c5))]

    #[test]
    fn packet_optics_are_the_cores_bit_for_bit(cases in prop::array::uniform8(surface_case())) {
        for (case, got) in cases.iter().zip(packet(&cases)) {
            if let Err(e) = check_surface(case, &got, Agreement::Exact) {
                return Err(TestCaseError::fail(e));
            }
        }
    }
}

/// A ray: (origin, direction).
type Ray = (Vec3, Vec3);

/// One lane's scattering: `scatter_dielectric`'s ray, the ray
/// `BranchesX8::choose` takes for the same number, R, and the refracted ray.
type LaneScatter = (Ray, Ray, f32, Option<Ray>);

/// The packet scattering at glass on eight cases: each lane's one branch
/// (origin, direction) for its own number, and both branches with R.
fn packet_scatter(cases: &[ScatterCase; 8]) -> [LaneScatter; 8] {
    let d = Vec3x8::from_lanes(&cases.map(|c| c.surface.d));
    let outward = Vec3x8::from_lanes(&cases.map(|c| c.surface.outward));
    let point = Vec3x8::from_lanes(&cases.map(|c| c.point));
    let ior = f32x8::new(cases.map(|c| c.surface.ior));
    let thin = f32x8::new(cases.map(|c| if c.thin { f32::from_bits(u32::MAX) } else { 0.0 }));
    let (n, dir) = scatter_dielectric(d, outward, ior, thin, f32x8::new(cases.map(|c| c.u)));
    let origin = offset_origin(point, n, dir);
    let split = split_dielectric(d, point, outward, ior, thin);
    let (r, tir) = (split.reflectance.to_array(), split.tir.to_bitmask());
    std::array::from_fn(|i| {
        let refracted = (tir & (1 << i) == 0).then(|| (split.refracted.0.lane(i), split.refracted.1.lane(i)));
        ((origin.lane(i), dir.lane(i)), split.choose(i, cases[i].u), r[i], refracted)
    })
}

proptest! {
    #![proptest_config(config(1024, 0x5ca7))]

    /// `scatter_dielectric`, `split_dielectric` (and its branch choice) and
    /// `offset_origin` on eight lanes are the core's, bit for bit.
    #[test]
    fn packet_scattering_is_the_cores_bit_for_bit(cases in prop::array::uniform8(scatter_case(false))) {
        for (case, (one, chosen, r, refracted)) in cases.iter().zip(packet_scatter(&cases)) {
            let want = case.scattered();
            prop_assert!(bits(one) == bits(want), "scatter_dielectric: {:?}, the core says {:?}, for {:?}", one, want, case);
            prop_assert!(bits(chosen) == bits(want), "BranchesX8::choose: {:?}, the core says {:?}, for {:?}", chosen, want, case);
            let split = case.branches();
            prop_assert_eq!(r.to_bits(), split.reflectance.to_bits(), "reflectance for {:?}", case);
            let want_refracted = split.refracted.map(|ray| (ray.origin, ray.direction));
            prop_assert!(refracted.map(bits) == want_refracted.map(bits), "refracted {:?} vs {:?} for {:?}", refracted, want_refracted, case);
            let (n, _, _) = prismatic_core::optics::fresnel::interface(case.surface.d, case.surface.outward, case.surface.ior);
            let lane = offset_origin(Vec3x8::splat(case.point), Vec3x8::splat(n), Vec3x8::splat(want.1)).lane(0);
            prop_assert!(bits((lane, n)) == bits((scatter::offset_origin(case.point, n, want.1), n)), "offset_origin for {:?}", case);
        }
    }
}

/// A ray's bits, so that -0.0 and 0.0 differ and NaN equals itself.
fn bits((origin, dir): Ray) -> [u32; 6] {
    let [a, b, c] = origin.to_array().map(f32::to_bits);
    let [d, e, f] = dir.to_array().map(f32::to_bits);
    [a, b, c, d, e, f]
}

proptest! {
    #![proptest_config(config(64, 0xe317))]

    /// Packet emission (`prismatic_cpu::emit::Emitters`) is the core's
    /// `emit` bit for bit: origin, direction and weight of each lane's
    /// photon, for any index, from every light kind, with and without
    /// projection maps, Sobol and random numbers.
    #[test]
    fn packet_emission_is_the_cores_bit_for_bit(
        first in prop_oneof![0u32..4096, any::<u32>()],
        projection_maps in any::<bool>(),
        sobol in any::<bool>(),
    ) {
        let sequence = if sobol { PhotonSequence::Sobol } else { PhotonSequence::Random };
        let scene = lit_by_every_light_kind(projection_maps, sequence);
        let emitters = prismatic_cpu::emit::Emitters::new(&scene);
        let index: [u32; 8] = std::array::from_fn(|i| first.wrapping_add(i as u32));
        let (origin, dir, weight) = emitters.emit(wide::u32x8::new(index));
        let weight = weight.to_array();
        for (i, &k) in index.iter().enumerate() {
            let want = prismatic_core::photons::emit::emit(&scene, scene.scene.render.seed, k);
            prop_assert!(
                bits((origin.lane(i), dir.lane(i))) == bits((want.origin, want.direction)) && weight[i].to_bits() == want.weight.to_bits(),
                "photon {}: ({}, {}, {}), the core says {:?}", k, origin.lane(i), dir.lane(i), weight[i], want
            );
        }
    }
}

/// A lane copy that drifts fails here: a packet whose Fresnel term is off
/// by one ulp in one lane is not the core's.
#[test]
fn a_drifted_lane_is_caught() {
    let case = SurfaceCase { d: prismatic_core::Vec3::new(0.6, -0.8, 0.0), outward: prismatic_core::Vec3::Y, ior: 1.5 };
    let mut got = packet(&[case; 8])[3];
    assert!(check_surface(&case, &got, Agreement::Exact).is_ok());
    got.fresnel = f32::from_bits(got.fresnel.to_bits() + 1);
    assert!(check_surface(&case, &got, Agreement::Exact).is_err());
}
