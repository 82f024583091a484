//! Every float function the core uses, in one place: `std` or `libm` is decided here.
//!
//! With the `std` feature the platform's functions are used; without it (a
//! `no_std` build) the `libm` crate provides them. Nothing else in the core
//! calls `f32::sqrt` and friends directly.

#[cfg(feature = "std")]
mod imp {
    /// `sqrt` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn sqrt(x: f32) -> f32 {
        x.sqrt()
    }
    /// `sin` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn sin(x: f32) -> f32 {
        x.sin()
    }
    /// `cos` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn cos(x: f32) -> f32 {
        x.cos()
    }
    /// `tan` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn tan(x: f32) -> f32 {
        x.tan()
    }
    /// `asin` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn asin(x: f32) -> f32 {
        x.asin()
    }
    /// `acos` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn acos(x: f32) -> f32 {
        x.acos()
    }
    /// `atan2` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn atan2(y: f32, x: f32) -> f32 {
        y.atan2(x)
    }
    /// `powf` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn powf(x: f32, y: f32) -> f32 {
        x.powf(y)
    }
    /// `floor` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn floor(x: f32) -> f32 {
        x.floor()
    }
    /// `exp` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn exp(x: f32) -> f32 {
        x.exp()
    }
    /// Natural `ln` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn ln(x: f32) -> f32 {
        x.ln()
    }
    /// `log2` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn log2(x: f32) -> f32 {
        x.log2()
    }
    /// `sqrt_f64` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn sqrt_f64(x: f64) -> f64 {
        x.sqrt()
    }
    /// `exp_f64` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn exp_f64(x: f64) -> f64 {
        x.exp()
    }
}

#[cfg(not(feature = "std"))]
mod imp {
    /// `sqrt` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
    /// `sin` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn sin(x: f32) -> f32 {
        libm::sinf(x)
    }
    /// `cos` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn cos(x: f32) -> f32 {
        libm::cosf(x)
    }
    /// `tan` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn tan(x: f32) -> f32 {
        libm::tanf(x)
    }
    /// `asin` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn asin(x: f32) -> f32 {
        libm::asinf(x)
    }
    /// `acos` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn acos(x: f32) -> f32 {
        libm::acosf(x)
    }
    /// `atan2` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn atan2(y: f32, x: f32) -> f32 {
        libm::atan2f(y, x)
    }
    /// `powf` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn powf(x: f32, y: f32) -> f32 {
        libm::powf(x, y)
    }
    /// `floor` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn floor(x: f32) -> f32 {
        libm::floorf(x)
    }
    /// `exp` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn exp(x: f32) -> f32 {
        libm::expf(x)
    }
    /// Natural `ln` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn ln(x: f32) -> f32 {
        libm::logf(x)
    }
    /// `log2` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn log2(x: f32) -> f32 {
        libm::log2f(x)
    }
    /// `sqrt_f64` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn sqrt_f64(x: f64) -> f64 {
        libm::sqrt(x)
    }
    /// `exp_f64` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn exp_f64(x: f64) -> f64 {
        libm::exp(x)
    }
}

pub use imp::*;

/// Taylor coefficients of sin x (x, x³, …, x¹¹) and cos x (1, x², …, x¹²).
pub const SIN_COEFFS: [f32; 6] = [1.0, -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362_880.0, -1.0 / 39_916_800.0];
/// See [`SIN_COEFFS`].
pub const COS_COEFFS: [f32; 7] =
    [1.0, -0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40_320.0, -1.0 / 3_628_800.0, 1.0 / 479_001_600.0];

/// (sin 2πu, cos 2πu) with only +, −, × and `floor`, so that the packet
/// (SIMD) and shader (WGSL) twins compute the same bits as this scalar
/// version. The angle is reduced to a half-angle h ∈ [−π/2, π/2], where the
/// Taylor series above are accurate to 1e-7, then doubled:
/// sin 2h = 2·sin h·cos h, cos 2h = 1 − 2·sin² h. Used for emission azimuths.
#[inline]
pub fn sin_cos_turns(u: f32) -> (f32, f32) {
    let h = (u - floor(u + 0.5)) * core::f32::consts::PI;
    let h2 = h * h;
    let s = h
        * (SIN_COEFFS[0]
            + h2 * (SIN_COEFFS[1]
                + h2 * (SIN_COEFFS[2] + h2 * (SIN_COEFFS[3] + h2 * (SIN_COEFFS[4] + h2 * SIN_COEFFS[5])))));
    let c = COS_COEFFS[0]
        + h2 * (COS_COEFFS[1]
            + h2 * (COS_COEFFS[2]
                + h2 * (COS_COEFFS[3] + h2 * (COS_COEFFS[4] + h2 * (COS_COEFFS[5] + h2 * COS_COEFFS[6])))));
    (2.0 * s * c, 1.0 - 2.0 * s * s)
}

/// Degrees to radians.
#[inline]
pub fn radians(deg: f32) -> f32 {
    deg * (core::f32::consts::PI / 180.0)
}

#[cfg(test)]
mod tests {
    #[test]
    fn sin_cos_turns_is_accurate() {
        for k in 0..=10_000 {
            let u = k as f32 / 10_000.0;
            let (s, c) = super::sin_cos_turns(u);
            let a = f64::from(u) * core::f64::consts::TAU;
            // Within about 8 f32 ulps of the true values.
            assert!((f64::from(s) - a.sin()).abs() < 1e-6 && (f64::from(c) - a.cos()).abs() < 1e-6, "u = {u}");
        }
    }
}
