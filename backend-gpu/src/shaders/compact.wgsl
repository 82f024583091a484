// Compaction: twin of the canonical ordering in prismatic_core (the CPU
// backend's `canonical_order`). After the trace pass, `offsets` holds the
// exclusive prefix sum of `counts` over the chunk's emissions, so emission
// k's j-th stored photon goes to cursor + offsets[k] + j: the chunk lands in
// (emission, band, bounces) order after the chunks before it, with no atomics and no
// trip to the host. Photons past `capacity` are dropped; the cursor still
// counts them, so the host sees the overflow.

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
    let dest = cursor[0] + offsets[k] + j;
    if dest < params.capacity {
        map_store(dest, scratch[s]);
    }
}

// Moves the cursor past the chunk (saturating, so an overflow stays visible).
@compute @workgroup_size(1)
fn advance() {
    let next = cursor[0] + chunk_total[0];
    cursor[0] = select(next, 0xffffffffu, next < cursor[0]);
}
