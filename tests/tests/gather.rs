//! The gather estimators against fields of photons with a known answer.

use prismatic_core::model::bands::{BandSpec, BandTable};
use prismatic_core::model::photon::{WHITE_BAND, oct_pack};
use prismatic_core::model::scene::Estimator;
use prismatic_core::photons::gather::{GatherQuery, GatherSums, finish, gather};
use prismatic_core::photons::grid::PhotonGrid;
use prismatic_core::util::rng::random_f32;
use prismatic_core::{Photon, Vec3};

/// `count` photons spread uniformly over the square [-1, 1]² of the plane
/// y = 0, arriving from above, band `band(i)` of the paper's seven (at its
/// wavelength), flux `flux` each.
fn field(count: u32, flux: f32, band: impl Fn(u32) -> u16) -> Vec<Photon> {
    let paper7 = BandTable::new(BandSpec::Paper7);
    (0..count)
        .map(|i| Photon {
            position: [2.0 * random_f32(5, i, 0) - 1.0, 0.0, 2.0 * random_f32(5, i, 1) - 1.0],
            flux,
            direction_oct: oct_pack(-Vec3::Y),
            lambda_nm: paper7.bands().get(usize::from(band(i))).map_or(0.0, |b| b.lambda_nm),
            emission: i,
            band: band(i),
            bounces: 1,
        })
        .collect()
}

fn query(radius: f32) -> GatherQuery {
    GatherQuery { point: Vec3::new(0.1, 0.0, -0.2), normal: Vec3::Y, radius, albedo: Vec3::ONE }
}

#[test]
fn density_estimate_of_uniform_white_light_is_its_irradiance() {
    // 400,000 photons of 1e-5 W on 4 m²: E = 1 W/m². Within r = 0.1 about
    // 3,140 photons: Poisson noise 1.8 %; allow 4σ.
    let photons = field(400_000, 1e-5, |_| WHITE_BAND);
    let grid = PhotonGrid::build(&photons, 0.1);
    let bands = BandTable::new(BandSpec::Paper7);
    let e = gather(&grid, &photons, &bands, Estimator::Density, &query(0.1));
    assert!((e - Vec3::ONE).abs().max_element() < 0.072, "{e}");
}

#[test]
fn paper_and_density_agree_on_evenly_split_light() {
    let bands = BandTable::new(BandSpec::Paper7);
    // 400,000 white photons of 1e-5 W on 4 m² (E = 1), each split into the
    // seven bands with 1/7 of the flux.
    let photons = field(2_800_000, 1e-5 / 7.0, |i| (i % 7) as u16);
    let grid = PhotonGrid::build(&photons, 0.1);
    let paper = gather(&grid, &photons, &bands, Estimator::Paper, &query(0.1));
    let density = gather(&grid, &photons, &bands, Estimator::Density, &query(0.1));
    assert!((paper - Vec3::ONE).abs().max_element() < 0.1, "{paper}");
    assert!((paper - density).abs().max_element() < 0.1, "{paper} vs {density}");
}

#[test]
fn the_paper_hue_is_w_over_total_scaled_so_white_is_white() {
    let bands = BandTable::new(BandSpec::Paper7);
    // A disc of unit area, and photons whose flux sums to 1: the estimate is the hue.
    let radius = (1.0 / std::f32::consts::PI).sqrt();
    let hue = |g: &GatherSums| finish(Estimator::Paper, 7, g, radius);
    let gathered = |photons: &[u16]| {
        let mut g = GatherSums::default();
        for &band in photons {
            let lambda_nm = bands.bands().get(usize::from(band)).map_or(0.0, |b| b.lambda_nm);
            g.add(Estimator::Paper, &bands, band, lambda_nm, 1.0 / photons.len() as f32, Vec3::ONE);
        }
        g
    };
    assert_eq!(hue(&GatherSums::default()), Vec3::ZERO, "no photons: black, not NaN");
    let red = hue(&gathered(&[0; 10]));
    assert!((red - Vec3::new(7.0 * 0.265, 0.0, 0.0)).length() < 1e-6, "{red}");
    // White photons count once in every band.
    assert!((hue(&gathered(&[WHITE_BAND; 3])) - Vec3::ONE).length() < 1e-6);
    // Counts beyond 2^24 stay exact: integer counting.
    let many = f64::from((1u32 << 24) + 1);
    let g = GatherSums {
        sums: bands.band(4).weight.as_dvec3() * many + bands.band(3).weight.as_dvec3(),
        total: (1 << 24) + 2,
        flux: 1.0,
        found: (1 << 24) + 2,
    };
    let expected_b = 7.0 * 0.498 * many / f64::from((1u32 << 24) + 2);
    assert!((f64::from(hue(&g).z) - expected_b).abs() < 1e-6 * expected_b, "{}", hue(&g));
}

#[test]
fn photons_behind_the_surface_do_not_count() {
    let mut photons = field(10_000, 1e-3, |_| WHITE_BAND);
    for p in &mut photons {
        p.direction_oct = oct_pack(Vec3::Y); // arriving from below
    }
    let grid = PhotonGrid::build(&photons, 0.2);
    let bands = BandTable::new(BandSpec::Paper3);
    assert_eq!(gather(&grid, &photons, &bands, Estimator::Density, &query(0.2)), Vec3::ZERO);
}

#[test]
fn grid_finds_exactly_the_photons_within_the_radius() {
    let photons = field(50_000, 1.0, |_| 0);
    for radius in [0.003, 0.05, 0.3] {
        let grid = PhotonGrid::build(&photons, radius);
        for k in 0..50 {
            let p = Vec3::new(2.0 * random_f32(9, k, 0) - 1.0, 0.0, 2.0 * random_f32(9, k, 1) - 1.0);
            let mut found = Vec::new();
            grid.for_each_candidate(p, radius, |i| {
                if (photons[i as usize].pos() - p).length_squared() <= radius * radius {
                    found.push(i)
                }
            });
            found.sort_unstable();
            let brute: Vec<u32> = (0..photons.len() as u32)
                .filter(|&i| (photons[i as usize].pos() - p).length_squared() <= radius * radius)
                .collect();
            assert_eq!(found, brute, "radius {radius}, query {p}");
        }
    }
}
