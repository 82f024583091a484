// Signed 64-bit integers as two u32 words (x = lo + hi · 2^32, two's
// complement), for sums in fixed point: WGSL has no 64-bit integers, and
// integer sums do not depend on the order of their terms, so a gather's
// sums are the same bits whatever order the grid's atomics left the
// photons in, and a pixel's sums are those of prismatic_core::accumulation
// (same scale, same truncation toward zero, same saturation).

const I64_MAX: vec2<u32> = vec2<u32>(0xffffffffu, 0x7fffffffu);
const I64_MIN: vec2<u32> = vec2<u32>(0u, 0x80000000u);

fn i64_neg(a: vec2<u32>) -> vec2<u32> {
    let lo = ~a.x + 1u;
    return vec2<u32>(lo, ~a.y + select(0u, 1u, lo == 0u));
}

// a + b, saturating at the i64 range (i64::saturating_add).
fn i64_add(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let lo = a.x + b.x;
    let hi = a.y + b.y + select(0u, 1u, lo < a.x);
    let sign_a = a.y >> 31u;
    if sign_a == (b.y >> 31u) && (hi >> 31u) != sign_a {
        return select(I64_MAX, I64_MIN, sign_a == 1u);
    }
    return vec2<u32>(lo, hi);
}

// x · 2^shift as an i64, truncated toward zero, saturating, NaN → 0: the
// twin of Rust's `(f64::from(x) * 2^shift) as i64` (accumulation::to_fixed
// for shift 32). Subnormal x counts 0 (below one unit for every shift the
// backend uses, which stay under 126).
fn to_fixed(x: f32, shift: i32) -> vec2<u32> {
    let bits = bitcast<u32>(x);
    let negative = (bits >> 31u) != 0u;
    let biased = i32((bits >> 23u) & 0xffu);
    if biased == 255 {
        if (bits & 0x7fffffu) != 0u {
            return vec2<u32>(0u);
        }
        return select(I64_MAX, I64_MIN, negative);
    }
    if biased == 0 {
        return vec2<u32>(0u);
    }
    // |x| · 2^shift = m · 2^e with m a 24-bit integer.
    let m = (bits & 0x7fffffu) | 0x800000u;
    let e = biased - 150 + shift;
    if e >= 40 {
        return select(I64_MAX, I64_MIN, negative);
    }
    var magnitude = vec2<u32>(0u);
    if e >= 32 {
        magnitude = vec2<u32>(0u, m << u32(e - 32));
    } else if e > 0 {
        magnitude = vec2<u32>(m << u32(e), m >> u32(32 - e));
    } else if e > -24 {
        magnitude = vec2<u32>(m >> u32(-e), 0u);
    }
    return select(magnitude, i64_neg(magnitude), negative);
}

// sum + trunc(x · 2^shift) where |x · 2^shift| < 2^31 (a gather's terms:
// the host's shifts keep each below 2^30): the same value as
// i64_add(sum, to_fixed(x, shift)) for such terms, in a few operations
// (the inner loop of every gather runs it). Clamped rather than wrapped
// should a term ever exceed that.
fn add_term(sum: vec2<u32>, x: f32, shift: i32) -> vec2<u32> {
    let v = i32(clamp(ldexp(x, shift), -2147483520.0, 2147483520.0));
    let lo = sum.x + bitcast<u32>(v);
    let carry = select(0u, 1u, lo < sum.x);
    return vec2<u32>(lo, sum.y + select(0u, 0xffffffffu, v < 0) + carry);
}

// An i64 as the nearest f32 (or close to it: two roundings).
fn i64_to_f32(a: vec2<u32>) -> f32 {
    return f32(bitcast<i32>(a.y)) * 4294967296.0 + f32(a.x);
}

// A fixed-point sum of `shift` as a float: the sum · 2^-shift.
fn from_fixed(a: vec2<u32>, shift: i32) -> f32 {
    return ldexp(i64_to_f32(a), -shift);
}
