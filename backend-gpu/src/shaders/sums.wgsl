// The pixels' exact sums (group 1, binding 0 of the session's passes and
// of light tracing): per pixel of the chunk, three i64 sums (R, G, B) of
// caustic radiance in 2^32 per unit, as `[lo, hi]` words, added to with
// atomics (exact, in any order: prismatic_core::Accumulation's sums).
@group(1) @binding(0) var<storage, read_write> accum: array<atomic<u32>>;

// Adds the i64 `v` to the sum whose low word is `accum[word]`: exact
// modulo 2^64 whatever order the points come in (a carry out of the low
// word goes into the high one). Unlike the host's saturating sums it wraps
// past 2^31 units of radiance, which no render reaches.
fn add_to_sum(word: u32, v: vec2<u32>) {
    let old = atomicAdd(&accum[word], v.x);
    let high = v.y + select(0u, 1u, old > ~v.x);
    if high != 0u {
        atomicAdd(&accum[word + 1u], high);
    }
}
