// Exclusive prefix sum of u32s, in place: twin of the counting sort's
// first half in prismatic_core::grid::bucket_starts (and of the CPU
// backend's per-chunk offsets). Each workgroup scans SCAN_BLOCK elements
// and writes its total to `sums`; the host scans `sums` the same way (one
// level per 1024× more elements) and `add_sums` adds each block's offset.

@group(0) @binding(0) var<uniform> scan: ScanParams;
@group(0) @binding(1) var<storage, read_write> data: array<u32>;
@group(0) @binding(2) var<storage, read_write> sums: array<u32>;

var<workgroup> partial: array<u32, SCAN_THREADS>;

@compute @workgroup_size(SCAN_THREADS)
fn scan_blocks(@builtin(workgroup_id) wid: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let base = wid.x * SCAN_BLOCK + lid * SCAN_PER_THREAD;
    var local_: array<u32, SCAN_PER_THREAD>;
    var total = 0u;
    for (var i = 0u; i < SCAN_PER_THREAD; i++) {
        var v = 0u;
        if base + i < scan.n {
            v = data[base + i];
        }
        local_[i] = total;
        total += v;
    }
    partial[lid] = total;
    workgroupBarrier();
    // Hillis–Steele inclusive scan of the threads' totals.
    for (var stride = 1u; stride < SCAN_THREADS; stride *= 2u) {
        var add = 0u;
        if lid >= stride {
            add = partial[lid - stride];
        }
        workgroupBarrier();
        partial[lid] += add;
        workgroupBarrier();
    }
    let before = partial[lid] - total;
    for (var i = 0u; i < SCAN_PER_THREAD; i++) {
        if base + i < scan.n {
            data[base + i] = before + local_[i];
        }
    }
    if lid == SCAN_THREADS - 1u {
        sums[wid.x] = partial[lid];
    }
}

@compute @workgroup_size(SCAN_THREADS)
fn add_sums(@builtin(workgroup_id) wid: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let base = wid.x * SCAN_BLOCK + lid * SCAN_PER_THREAD;
    let add = sums[wid.x];
    for (var i = 0u; i < SCAN_PER_THREAD; i++) {
        if base + i < scan.n {
            data[base + i] += add;
        }
    }
}
