//! Band tables and dispersion models against the paper's tables and published indices.

use prismatic_core::Vec3;
use prismatic_core::model::bands::{BandSpec, BandTable, MAX_BANDS};
use prismatic_core::model::dispersion::{Dispersion, Glass};

#[test]
fn paper3_is_table_1() {
    let t = BandTable::new(BandSpec::Paper3);
    let weights: Vec<Vec3> = t.bands().iter().map(|b| b.weight).collect();
    assert_eq!(weights, vec![Vec3::X, Vec3::Y, Vec3::Z]);
    let n: Vec<f32> = (0..3).map(|i| Dispersion::Paper.ior_for_band(&t, i)).collect();
    assert_eq!(n, vec![1.515, 1.550, 1.564]);
}

#[test]
fn paper7_is_table_3_with_its_corrections() {
    let t = BandTable::new(BandSpec::Paper7);
    let expected = [
        ("red", 1.515, [0.265, 0.0, 0.0]),
        ("orange", 1.536, [0.263, 0.244, 0.0]),
        ("yellow", 1.547, [0.263, 0.377, 0.0]),
        ("green", 1.550, [0.0, 0.379, 0.0]),
        ("blue", 1.564, [0.0, 0.0, 0.498]),
        ("indigo", 1.578, [0.077, 0.0, 0.253]),
        ("violet", 1.582, [0.132, 0.0, 0.249]),
    ];
    for (i, (name, n, w)) in expected.into_iter().enumerate() {
        let band = t.band(i);
        assert_eq!(band.name, Some(name));
        assert_eq!(band.weight, Vec3::from(w), "{name}");
        assert_eq!(Dispersion::Paper.ior_for_band(&t, i), n, "{name}");
    }
    // Each channel sums to exactly 1 in decimal; in f32 to within an ulp or two.
    assert!((t.white() - Vec3::ONE).abs().max_element() < 1e-6);
}

#[test]
fn every_band_table_sums_to_white() {
    let mut specs = vec![BandSpec::Paper3, BandSpec::Paper7];
    specs.extend((1..=MAX_BANDS as u16).map(BandSpec::Physical));
    for spec in specs {
        let t = BandTable::new(spec);
        let white = t.white();
        assert!((white - Vec3::ONE).abs().max_element() < 1e-5, "{spec}: bands sum to {white}");
        assert!(t.bands().iter().all(|b| b.weight.is_finite()), "{spec}");
    }
}

#[test]
fn physical_bands_tile_the_visible_range_in_order() {
    for n in [1u16, 7, 64, 256] {
        let t = BandTable::new(BandSpec::Physical(n));
        assert_eq!(t.len(), usize::from(n));
        assert_eq!(t.band(0).interval_nm.0, 380.0);
        assert!((t.band(t.len() - 1).interval_nm.1 - 780.0).abs() < 1e-3);
        for w in t.bands().windows(2) {
            assert!((w[0].interval_nm.1 - w[1].interval_nm.0).abs() < 1e-3);
            assert!(w[0].lambda_nm < w[1].lambda_nm);
        }
    }
    assert_eq!(BandTable::new(BandSpec::Physical(1)).band(0).weight, Vec3::ONE);
}

/// PHYSICS.md: Schott BK7 at the mercury h, hydrogen F, helium d and hydrogen C lines.
#[test]
fn bk7_matches_published_indices() {
    let bk7 = Glass::Bk7.dispersion();
    for (lambda, n) in [(404.7, 1.53023), (486.13, 1.52238), (587.56, 1.51680), (656.27, 1.51432)] {
        let got = bk7.ior_at(lambda).unwrap();
        assert!((got - n).abs() < 5e-5, "BK7 at {lambda} nm: {got}, expected {n}");
    }
}

/// PHYSICS.md: water at 20 °C (Daimon & Masumura 2007).
#[test]
fn water_matches_published_indices() {
    let water = Glass::Water.dispersion();
    for (lambda, n) in [(404.7, 1.34312), (486.13, 1.33749), (587.56, 1.33340), (656.27, 1.33151), (700.0, 1.33052)] {
        let got = water.ior_at(lambda).unwrap();
        assert!((got - n).abs() < 1e-4, "water at {lambda} nm: {got}, expected {n}");
    }
}

#[test]
fn abbe_form_gives_nd_at_the_d_line_and_normal_dispersion() {
    let d = Dispersion::Abbe { nd: 1.5168, vd: 64.17 };
    assert!((d.ior_at(587.56).unwrap() - 1.5168).abs() < 1e-4);
    // n_F − n_C = (n_d − 1)/V_d by definition of the Abbe number.
    let dn = d.ior_at(486.13).unwrap() - d.ior_at(656.27).unwrap();
    assert!((dn - 0.5168 / 64.17).abs() < 2e-4, "{dn}");
}

#[test]
fn every_glass_gives_every_band_table_an_index() {
    for glass in Glass::ALL {
        for spec in [BandSpec::Paper3, BandSpec::Paper7, BandSpec::Physical(1), BandSpec::Physical(64)] {
            let t = BandTable::new(spec);
            let d = glass.dispersion();
            let n: Vec<f32> = (0..t.len()).map(|i| d.ior_for_band(&t, i)).collect();
            assert!(n.iter().all(|&n| n.is_finite() && (1.0..3.0).contains(&n)), "{glass} with {spec}: {n:?}");
            if t.len() > 1 {
                let spread = n.iter().copied().fold(f32::MIN, f32::max) - n.iter().copied().fold(f32::MAX, f32::min);
                assert!(spread > 1e-3, "{glass} with {spec} does not disperse: {n:?}");
            }
        }
    }
}
