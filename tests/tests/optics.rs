//! Snell, Fresnel and total internal reflection: invariants over a sweep of
//! angles and indices (including grazing incidence and n = 1).

use prismatic_core::Vec3;
use prismatic_core::optics::{fresnel, reflect, refract};

/// Indices on either side: air, water, glasses, diamond, equal indices.
const INDICES: [f32; 6] = [1.0, 1.333, 1.5, 1.62, 2.42, 1.0001];

fn sweep() -> impl Iterator<Item = (f32, f32, f32)> {
    INDICES.into_iter().flat_map(|n1| {
        INDICES
            .into_iter()
            .flat_map(move |n2| (0..=180).map(move |k| (n1, n2, (k as f32 / 180.0) * 89.99_f32.to_radians())))
    })
}

/// Incoming direction at angle `theta` to the normal +y, in the xy-plane.
fn incoming(theta: f32) -> Vec3 {
    Vec3::new(theta.sin(), -theta.cos(), 0.0)
}

#[test]
fn snell_law_holds_and_directions_are_unit() {
    for (n1, n2, theta) in sweep() {
        let d = incoming(theta);
        let r = reflect(d, Vec3::Y);
        assert!((r.length() - 1.0).abs() < 1e-6);
        assert!((r.y + d.y).abs() < 1e-6 && (r.x - d.x).abs() < 1e-6, "mirror angle");
        if let Some(t) = refract(d, Vec3::Y, n1, n2) {
            assert!((t.length() - 1.0).abs() < 1e-5, "unit length");
            assert!(t.y < 0.0, "continues through the surface");
            let (s1, s2) = (theta.sin(), t.x);
            assert!((n1 * s1 - n2 * s2).abs() < 2e-5, "n1 sin θ1 = n2 sin θ2: {n1} {s1} {n2} {s2}");
            assert!(t.x * d.x >= 0.0, "stays in the plane of incidence, same side");
        }
    }
}

#[test]
fn total_internal_reflection_exactly_when_sin_theta_t_exceeds_one() {
    for (n1, n2, theta) in sweep() {
        let sin_t = n1 / n2 * theta.sin();
        let t = refract(incoming(theta), Vec3::Y, n1, n2);
        // Exactly at the critical angle rounding may go either way; stay 1e-5 clear of it.
        if sin_t > 1.0 + 1e-5 {
            assert!(t.is_none(), "TIR expected at sin θt = {sin_t}");
            assert_eq!(fresnel(theta.cos(), n1, n2), 1.0);
        } else if sin_t < 1.0 - 1e-5 {
            assert!(t.is_some(), "refraction expected at sin θt = {sin_t}");
        }
    }
}

#[test]
fn fresnel_reflectance_plus_transmittance_is_one() {
    for (n1, n2, theta) in sweep() {
        let cos_i = theta.cos();
        let r = fresnel(cos_i, n1, n2);
        assert!((0.0..=1.0).contains(&r));
        let Some(t) = refract(incoming(theta), Vec3::Y, n1, n2) else { continue };
        // Transmittance from the Fresnel transmission amplitudes, independently of R.
        let cos_t = -t.y;
        let ts = 2.0 * n1 * cos_i / (n1 * cos_i + n2 * cos_t);
        let tp = 2.0 * n1 * cos_i / (n2 * cos_i + n1 * cos_t);
        let transmittance = (n2 * cos_t) / (n1 * cos_i) * 0.5 * (ts * ts + tp * tp);
        assert!((r + transmittance - 1.0).abs() < 1e-4, "R + T = {} at n1={n1} n2={n2} θ={theta}", r + transmittance);
    }
}

#[test]
fn refraction_is_reversible() {
    for (n1, n2, theta) in sweep() {
        // Within 1e-5 of grazing, the reverse ray's sin θ rounds to ≥ 1 in f32.
        if theta.sin() > 1.0 - 1e-5 {
            continue;
        }
        let d = incoming(theta);
        let Some(t) = refract(d, Vec3::Y, n1, n2) else { continue };
        // Send the refracted ray back: it must leave along −d.
        let back = refract(-t, -Vec3::Y, n2, n1).expect("the reverse path exists");
        assert!((back + d).length() < 2e-4, "{back} vs {}", -d);
    }
}

#[test]
fn equal_indices_do_not_bend_or_reflect() {
    for k in 0..90 {
        let d = incoming((k as f32).to_radians());
        assert!((refract(d, Vec3::Y, 1.5, 1.5).unwrap() - d).length() < 1e-6);
        assert!(fresnel(d.y.abs(), 1.5, 1.5) < 1e-12);
    }
}
