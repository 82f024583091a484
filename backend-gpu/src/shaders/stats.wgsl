// A pass's photon-trace tallies (one per workgroup of the trace, see
// trace.wgsl) added to the render's running totals on the device, so that
// a pass reads nothing back and the statistics are read once, when asked
// for. One workgroup: each invocation sums a stride of the tallies (counts
// as u64, fixed.wgsl), then the first adds the workgroup's sums.

@group(0) @binding(0) var<storage, read> tallies: array<Tally>;
@group(0) @binding(1) var<storage, read_write> run_stats: RunStats;

var<workgroup> part_counts: array<array<vec2<u32>, TALLY_COUNTS>, WORKGROUP_SIZE>;
var<workgroup> part_flux: array<array<f32, TALLY_FLUXES>, WORKGROUP_SIZE>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn fold_tallies(@builtin(local_invocation_index) lid: u32) {
    var counts: array<vec2<u32>, TALLY_COUNTS>;
    var flux: array<f32, TALLY_FLUXES>;
    let n = arrayLength(&tallies);
    for (var i = lid; i < n; i += WORKGROUP_SIZE) {
        let t = tallies[i];
        for (var j = 0u; j < TALLY_COUNTS; j++) {
            counts[j] = i64_add(counts[j], vec2<u32>(t.counts[j], 0u));
        }
        for (var j = 0u; j < TALLY_FLUXES; j++) {
            flux[j] += t.flux[j];
        }
    }
    part_counts[lid] = counts;
    part_flux[lid] = flux;
    workgroupBarrier();
    if lid != 0u {
        return;
    }
    for (var i = 1u; i < WORKGROUP_SIZE; i++) {
        for (var j = 0u; j < TALLY_COUNTS; j++) {
            counts[j] = i64_add(counts[j], part_counts[i][j]);
        }
        for (var j = 0u; j < TALLY_FLUXES; j++) {
            flux[j] += part_flux[i][j];
        }
    }
    for (var j = 0u; j < TALLY_COUNTS; j++) {
        run_stats.counts[j] = i64_add(run_stats.counts[j], counts[j]);
    }
    for (var j = 0u; j < TALLY_FLUXES; j++) {
        run_stats.flux[j] += flux[j];
    }
}
