//! Reading a texture at a hit: the point's texture coordinates from its
//! triangle's corners, and the sampler's wrap and filter over 8-bit texels,
//! a base colour's decoded from sRGB to linear light, a normal map's read
//! as linear values. The CPU backend calls these functions; `albedo.wgsl`
//! mirrors them operation for operation.

use crate::geometry::triangle::Triangle;
use crate::model::scene::{Filter, Texture, Wrap};
use crate::util::math::{floor, powf};
use glam::{Vec2, Vec3};

/// A texel coordinate beyond this (in texels) is clamped before it is
/// wrapped: f32 has no fractional part there, and every backend converts
/// the same bounded value to an integer.
pub const TEXEL_LIMIT: f32 = 16_777_216.0;

/// A triangle's texture coordinates, stored for interpolation: the first
/// corner's and the differences to the other two (along the edges `e1`, `e2`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TriangleUv {
    /// At the first corner.
    pub uv0: Vec2,
    /// Second corner's minus the first's.
    pub du1: Vec2,
    /// Third corner's minus the first's.
    pub du2: Vec2,
}

impl TriangleUv {
    /// From the three corners' coordinates.
    pub fn new(corners: [Vec2; 3]) -> Self {
        TriangleUv { uv0: corners[0], du1: corners[1] - corners[0], du2: corners[2] - corners[0] }
    }

    /// The coordinates at `p`, a point on `tri` ([`Triangle::barycentrics`]).
    #[inline]
    pub fn at(&self, tri: &Triangle, p: Vec3) -> Vec2 {
        let (b1, b2) = tri.barycentrics(p);
        self.uv0 + self.du1 * b1 + self.du2 * b2
    }
}

/// Linear light of an 8-bit sRGB-encoded channel (IEC 61966-2-1).
#[inline]
pub fn srgb_to_linear(byte: u32) -> f32 {
    let c = byte as f32 / 255.0;
    if c <= 0.04045 { c / 12.92 } else { powf((c + 0.055) / 1.055, 2.4) }
}

/// The value of an 8-bit linear channel (a normal map's): 0..255 as 0..1.
#[inline]
pub fn linear_channel(byte: u32) -> f32 {
    byte as f32 / 255.0
}

/// The texel index along one axis of `size` texels for integer coordinate `i`.
#[inline]
pub fn wrap_texel(i: i32, size: u32, wrap: Wrap) -> u32 {
    let n = size as i32;
    (match wrap {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::ClampToEdge => i.clamp(0, n - 1),
        Wrap::MirroredRepeat => {
            let m = i.rem_euclid(2 * n);
            if m >= n { 2 * n - 1 - m } else { m }
        }
    }) as u32
}

/// The texture's linear RGB at texture coordinates `uv` (u to the right,
/// v down the image; texel centres at half-integers times the texel size),
/// its texels sRGB-encoded (a base colour).
pub fn sample(texture: &Texture, uv: Vec2) -> Vec3 {
    sample_decoded(texture, uv, srgb_to_linear)
}

/// [`sample`] of a texture whose texels hold linear values (a normal map).
pub fn sample_linear(texture: &Texture, uv: Vec2) -> Vec3 {
    sample_decoded(texture, uv, linear_channel)
}

/// The texture at `uv`, each 8-bit channel decoded by `decode` before the
/// filter blends texels.
fn sample_decoded(texture: &Texture, uv: Vec2, decode: fn(u32) -> f32) -> Vec3 {
    let (w, h) = (texture.width, texture.height);
    let s = texture.sampler;
    // Texel space, bounded (a NaN coordinate reads texel 0).
    let texel_space = |x: f32, size: u32| {
        let t = x * size as f32;
        if t.is_nan() { 0.0 } else { t.clamp(-TEXEL_LIMIT, TEXEL_LIMIT) }
    };
    let (x, y) = (texel_space(uv.x, w), texel_space(uv.y, h));
    let fetch = |i: i32, j: i32| -> Vec3 {
        let (col, row) = (wrap_texel(i, w, s.wrap_u), wrap_texel(j, h, s.wrap_v));
        let t = texture.texels[(row * w + col) as usize];
        Vec3::new(decode(t & 255), decode((t >> 8) & 255), decode(t >> 16))
    };
    match s.filter {
        Filter::Nearest => fetch(floor(x) as i32, floor(y) as i32),
        Filter::Linear => {
            let (x, y) = (x - 0.5, y - 0.5);
            let (x0, y0) = (floor(x), floor(y));
            let (fx, fy) = (x - x0, y - y0);
            let (i, j) = (x0 as i32, y0 as i32);
            let top = fetch(i, j) * (1.0 - fx) + fetch(i + 1, j) * fx;
            let bottom = fetch(i, j + 1) * (1.0 - fx) + fetch(i + 1, j + 1) * fx;
            top * (1.0 - fy) + bottom * fy
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::scene::Sampler;
    use alloc::string::ToString;
    use alloc::vec::Vec;

    fn texture(width: u32, height: u32, texels: Vec<u32>, filter: Filter, wrap: Wrap) -> Texture {
        Texture {
            name: "test".to_string(),
            width,
            height,
            texels: texels.into(),
            sampler: Sampler { filter, wrap_u: wrap, wrap_v: wrap },
        }
    }

    #[test]
    fn srgb_decoding_matches_the_standard_at_its_end_points_and_mid_grey() {
        assert_eq!(srgb_to_linear(0), 0.0);
        assert_eq!(srgb_to_linear(255), 1.0);
        assert!((srgb_to_linear(188) - 0.5029).abs() < 1e-4);
        assert!((srgb_to_linear(10) - 10.0 / 255.0 / 12.92).abs() < 1e-7);
    }

    #[test]
    fn wrap_modes_repeat_clamp_and_mirror() {
        let idx = |wrap| (-4..8).map(|i| wrap_texel(i, 3, wrap)).collect::<Vec<_>>();
        assert_eq!(idx(Wrap::Repeat), [2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1]);
        assert_eq!(idx(Wrap::ClampToEdge), [0, 0, 0, 0, 0, 1, 2, 2, 2, 2, 2, 2]);
        assert_eq!(idx(Wrap::MirroredRepeat), [2, 2, 1, 0, 0, 1, 2, 2, 1, 0, 0, 1]);
    }

    #[test]
    fn nearest_reads_the_texel_a_point_falls_in_and_linear_blends_neighbours() {
        // Two texels: black, then white (sRGB 255 = linear 1).
        let white = 255 | 255 << 8 | 255 << 16;
        let near = texture(2, 1, Vec::from([0, white]), Filter::Nearest, Wrap::ClampToEdge);
        assert_eq!(sample(&near, Vec2::new(0.49, 0.5)), Vec3::ZERO);
        assert_eq!(sample(&near, Vec2::new(0.51, 0.5)), Vec3::ONE);
        let linear = texture(2, 1, Vec::from([0, white]), Filter::Linear, Wrap::ClampToEdge);
        // Texel centres at u = 0.25 and 0.75; halfway between them is grey 0.5 in linear light.
        assert_eq!(sample(&linear, Vec2::new(0.25, 0.5)), Vec3::ZERO);
        assert_eq!(sample(&linear, Vec2::new(0.75, 0.5)), Vec3::ONE);
        assert!((sample(&linear, Vec2::new(0.5, 0.5)) - Vec3::splat(0.5)).abs().max_element() < 1e-6);
        // Clamped beyond the edges; repeated, the edge blends with the far side.
        assert_eq!(sample(&linear, Vec2::new(-3.0, 9.0)), Vec3::ZERO);
        let tiled = texture(2, 1, Vec::from([0, white]), Filter::Linear, Wrap::Repeat);
        assert!((sample(&tiled, Vec2::new(0.0, 0.5)) - Vec3::splat(0.5)).abs().max_element() < 1e-6);
        // Channels are packed r | g << 8 | b << 16.
        let red = texture(1, 1, Vec::from([255]), Filter::Linear, Wrap::Repeat);
        assert_eq!(sample(&red, Vec2::new(f32::NAN, 1e30)), Vec3::X);
        // A linear texture (a normal map's) reads its bytes as they are: 188 is not mid grey.
        let grey = texture(1, 1, Vec::from([188 | 188 << 8 | 188 << 16]), Filter::Linear, Wrap::Repeat);
        assert_eq!(sample_linear(&grey, Vec2::splat(0.5)), Vec3::splat(188.0 / 255.0));
    }

    #[test]
    fn coordinates_interpolate_across_a_triangle() {
        let tri = Triangle { v0: Vec3::ZERO, e1: Vec3::X * 2.0, e2: Vec3::Y, normal: Vec3::Z };
        let uv = TriangleUv::new([Vec2::new(0.1, 0.2), Vec2::new(0.9, 0.2), Vec2::new(0.1, 0.7)]);
        assert!((uv.at(&tri, Vec3::ZERO) - Vec2::new(0.1, 0.2)).abs().max_element() < 1e-6);
        assert!((uv.at(&tri, Vec3::new(1.0, 0.5, 0.0)) - Vec2::new(0.5, 0.45)).abs().max_element() < 1e-6);
        // Off the plane by a rounding error: the nearest point's coordinates.
        assert!((uv.at(&tri, Vec3::new(2.0, 0.0, 1e-6)) - Vec2::new(0.9, 0.2)).abs().max_element() < 1e-6);
    }
}
