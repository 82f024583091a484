//! Reflection, Snell refraction, dielectric Fresnel and total internal reflection.

use crate::util::math::sqrt;
use glam::Vec3;

/// Mirror reflection of unit `d` about unit normal `n` (either side).
#[inline]
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - n * (2.0 * d.dot(n))
}

/// Refraction of unit `d` through a surface with unit normal `n` facing the
/// incoming ray (`dot(d, n) < 0`), from index `n1` into `n2`. `None` on total
/// internal reflection (sin θ_t > 1).
#[inline]
pub fn refract(d: Vec3, n: Vec3, n1: f32, n2: f32) -> Option<Vec3> {
    let eta = n1 / n2;
    let cos_i = (-d.dot(n)).clamp(0.0, 1.0);
    let cos2_t = cos2_transmitted(cos_i, n1, n2);
    if cos2_t < 0.0 {
        return None;
    }
    let cos_t = sqrt(cos2_t);
    Some((d * eta + n * (eta * cos_i - cos_t)).normalize())
}

/// Unpolarised Fresnel reflectance of a smooth dielectric interface for a ray
/// arriving with cosine `cos_i` (against the facing normal) from `n1` into `n2`;
/// 1 under total internal reflection. Transmittance is `1 − R`.
#[inline]
pub fn fresnel(cos_i: f32, n1: f32, n2: f32) -> f32 {
    if n1 == n2 {
        return 0.0; // index-matched: no interface at all (exact, also at grazing angles)
    }
    let cos_i = cos_i.clamp(0.0, 1.0);
    let cos2_t = cos2_transmitted(cos_i, n1, n2);
    if cos2_t <= 0.0 {
        return 1.0;
    }
    let cos_t = sqrt(cos2_t);
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    (0.5 * (rs * rs + rp * rp)).clamp(0.0, 1.0)
}

/// cos² θ_t = 1 − η²(1 − cos² θ_i) for η = n1/n2, arranged as
/// (n2 − n1)(n2 + n1)/n2² + η² cos² θ_i so that it keeps its precision at
/// grazing incidence when the indices nearly match. The textbook form rounds
/// 1 − cos² θ_i to 1 there and loses the whole answer; 1 − η² would lose it
/// to η's rounding (one ulp of η is 3e-4 of 1 − η² at n = 1.0002, and a
/// GPU's division may be 2.5 ulps off), where n2 − n1 is exact. Negative
/// means total internal reflection.
#[inline]
pub fn cos2_transmitted(cos_i: f32, n1: f32, n2: f32) -> f32 {
    let eta = n1 / n2;
    (n2 - n1) * (n2 + n1) / (n2 * n2) + eta * eta * cos_i * cos_i
}

/// Reflectance of a thin sheet (glTF's thin-walled transmission: two
/// parallel faces no distance apart) whose faces each reflect `r`: the light
/// that bounces between the faces sums to 2R/(1 + R) reflected and
/// (1 − R)/(1 + R) transmitted (incoherently, nothing absorbed).
#[inline]
pub fn sheet_reflectance(r: f32) -> f32 {
    2.0 * r / (1.0 + r)
}

/// The indices on both sides of a dielectric surface hit by a ray travelling
/// along `d`, whose outward normal is `outward`: returns the normal facing the
/// ray and (n_incident, n_transmitted). The outside of every dielectric is air.
#[inline]
pub fn interface(d: Vec3, outward: Vec3, ior: f32) -> (Vec3, f32, f32) {
    if d.dot(outward) < 0.0 { (outward, 1.0, ior) } else { (-outward, ior, 1.0) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_incidence_reflectance() {
        // ((n-1)/(n+1))^2 = 0.04 for n = 1.5
        assert!((fresnel(1.0, 1.0, 1.5) - 0.04).abs() < 1e-6);
        assert!((fresnel(1.0, 1.5, 1.0) - 0.04).abs() < 1e-6);
    }

    #[test]
    fn a_sheet_reflects_both_faces_and_what_bounces_between_them() {
        // Geometric series R + (1−R)²R + (1−R)²R³ + … = 2R/(1+R).
        let r = 0.04f32;
        let series: f32 = r + (0..40).map(|k| (1.0 - r) * (1.0 - r) * r.powi(2 * k + 1)).sum::<f32>();
        assert!((sheet_reflectance(r) - series).abs() < 1e-7);
        assert_eq!(sheet_reflectance(0.0), 0.0);
        assert_eq!(sheet_reflectance(1.0), 1.0);
    }

    #[test]
    fn brewster_angle_has_only_s_reflection() {
        let n = 1.5f32;
        let theta_b = n.atan();
        let cos_i = theta_b.cos();
        // At Brewster's angle rp = 0, so R = rs²/2.
        let cos_t = (1.0 - (theta_b.sin() / n).powi(2)).sqrt();
        let rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
        assert!((fresnel(cos_i, 1.0, n) - 0.5 * rs * rs).abs() < 1e-6);
    }

    #[test]
    fn cos2_transmitted_keeps_its_digits_when_the_indices_nearly_match() {
        // Against f64 at grazing incidence: 1 − η² from a rounded η would be
        // 1e-4 of itself off at n = 1.0002 (an ulp of η over 4e-4).
        for n in [1.0000356f32, 1.0002084, 1.01, 1.5] {
            for (n1, n2) in [(1.0, n), (n, 1.0)] {
                for cos_i in [0.0f32, 1e-4, 0.02, 0.5] {
                    let eta = f64::from(n1) / f64::from(n2);
                    let c = f64::from(cos_i);
                    let exact = 1.0 - eta * eta * (1.0 - c * c);
                    let got = f64::from(cos2_transmitted(cos_i, n1, n2));
                    let rel = (got - exact).abs() / exact.abs();
                    assert!(rel < 1e-6, "n1 {n1}, n2 {n2}, cos {cos_i}: {got} against {exact} ({rel:e})");
                }
            }
        }
    }
}
