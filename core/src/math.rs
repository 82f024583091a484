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
    /// `sqrt_f64` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn sqrt_f64(x: f64) -> f64 {
        x.sqrt()
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
    /// `sqrt_f64` of the platform (std) or of libm (no_std).
    #[inline]
    pub fn sqrt_f64(x: f64) -> f64 {
        libm::sqrt(x)
    }
}

pub use imp::*;

/// Degrees to radians.
#[inline]
pub fn radians(deg: f32) -> f32 {
    deg * (core::f32::consts::PI / 180.0)
}

/// Radians to degrees.
#[inline]
pub fn degrees(rad: f32) -> f32 {
    rad * (180.0 / core::f32::consts::PI)
}
