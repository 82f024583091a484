// Hash-grid build by counting sort: twin of prismatic_core::grid (the
// photons a gather takes).
// `count` counts photons per bucket; the host scans the counts into bucket
// starts and copies them to `cursor`; `scatter` copies each photon into its
// bucket's range of the sorted map, which the gather reads; `widest` finds
// the largest bucket (for devices whose gathers go in segments). Within a bucket
// the order is the atomics' (the gather's sums do not depend on it beyond
// float rounding).

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read_write> cells: array<atomic<u32>>;
@group(0) @binding(2) var<storage, read_write> cursor: array<atomic<u32>>;
@group(0) @binding(11) var<storage, read_write> widest_bucket: atomic<u32>;

// Whether a gather may take photon `p`: one met on a rough surface
// (Photon::on_rough_surface) only where visible points on rough surfaces
// gather (params.rough_gathers: the grid holds both kinds, and each
// point's gather takes its own, gather.wgsl), else light tracing alone
// takes those.
fn gathered(p: Photon) -> bool {
    return params.rough_gathers != 0u || ((p.band_bounces >> 16u) & ON_ROUGH_SURFACE) == 0u;
}

fn bucket_of_point(p: vec3<f32>) -> u32 {
    return bucket_of(cell_of(p, params.inv_cell), params.grid_mask);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn count(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    if i < params.stored {
        let p = map_load(i);
        if gathered(p) {
            atomicAdd(&cells[bucket_of_point(p.position)], 1u);
        }
    }
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn scatter(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    if i < params.stored {
        let p = map_load(i);
        if gathered(p) {
            let slot = atomicAdd(&cursor[bucket_of_point(p.position)], 1u);
            sorted_store(slot, p);
        }
    }
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn widest(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let b = flat_index(wid, nwg, lid);
    if b <= params.grid_mask {
        let size = atomicLoad(&cells[b + 1u]) - atomicLoad(&cells[b]);
        if size > atomicLoad(&widest_bucket) {
            atomicMax(&widest_bucket, size);
        }
    }
}
