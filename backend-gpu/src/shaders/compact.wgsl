// Compaction: twin of the canonical ordering in prismatic_core (the CPU
// backend's `canonical_order`). After the trace pass, `offsets` holds the
// exclusive prefix sum of `counts` over the chunk's emissions, so emission
// k's stored photon of rank j among its own in (band, bounces) order goes
// to cursor + offsets[k] + j: the chunk lands in (emission, band, bounces)
// order after the chunks before it, with no atomics and no trip to the
// host. A path stores in that order but for a white path's photons met on
// rough surfaces before it splits, which come after its bands'. Photons
// past `capacity` are dropped; the cursor still counts them, so the host
// sees the overflow.

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> scratch: array<Photon>;
@group(0) @binding(2) var<storage, read> counts: array<u32>;
@group(0) @binding(3) var<storage, read> offsets: array<u32>;
@group(0) @binding(4) var<storage, read_write> cursor: array<u32>;
@group(0) @binding(5) var<storage, read> chunk_total: array<u32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn scatter(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let s = flat_index(wid, nwg, lid);
    if s >= params.chunk_len * params.slots {
        return;
    }
    let k = s / params.slots;
    let j = s - k * params.slots;
    if j >= counts[k] {
        return;
    }
    let first = k * params.slots;
    let key = canonical_key(scratch[s]);
    var rank = 0u;
    for (var i = 0u; i < min(counts[k], params.slots); i++) {
        rank += select(0u, 1u, canonical_key(scratch[first + i]) < key);
    }
    let dest = cursor[0] + offsets[k] + rank;
    if dest < params.capacity {
        map_store(dest, scratch[s]);
    }
}

// Photon::key within an emission: the band (white last), then the bounces
// with the rough-surface mark as their lowest bit (rotated left by one).
fn canonical_key(p: Photon) -> u32 {
    let bounces = p.band_bounces >> 16u;
    return ((p.band_bounces & 0xffffu) << 16u) | (((bounces << 1u) | (bounces >> 15u)) & 0xffffu);
}

// Moves the cursor past the chunk (saturating, so an overflow stays visible).
@compute @workgroup_size(1)
fn advance() {
    let next = cursor[0] + chunk_total[0];
    cursor[0] = select(next, 0xffffffffu, next < cursor[0]);
}
