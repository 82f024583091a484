// A session's passes at resident visible points: twin of the core's host
// driver (prismatic_core::host) over prismatic_core::schedule. The view
// pass leaves each pixel's direct light (kept as `base`) and its visible
// points; the pilot's gather at the scene's radius R gives each point its
// first radius (`first_radius`, as a fraction of R) and marks the grid
// levels those radii fall in; each pass empties the points' sums, sets
// their radii and counts the points of each grid level (`begin_pass`),
// lists them level by level (`list_points`), gathers each level's list in
// its grid (`gather_level`, dispatched indirectly over that list alone),
// adds each point's caustic to its pixel's exact sums (`accumulate`) and
// shows base + mean (`show`). With sampled view paths each pass's view
// (its direct light, in `base`) is added to the sums too (`add_view`), and
// the base left empty; the pilot marks each pixel's first radius, which
// the view pass gives the pixel's point of every pass.

struct SessionParams {
    // A full pass's photons per pilot photon.
    pilot_scale: f32,
    // Photons a first radius should hold (neighbours × photons per path).
    neighbours: f32,
    // 1 / passes summed, this pass included.
    inv_passes: f32,
    // 1 when every point gathers within the pass radius (the pilot, fixed radii).
    whole_radius: u32,
    // The grid level this gather dispatch serves (params.inv_cell is its cell).
    level: u32,
    // Bit l set when level l's grid is built (bit 0 always is).
    built_levels: u32,
    // 1 with sampled view paths: the pilot marks each pixel's first radius.
    sampled_view: u32,
    _pad1: u32,
}

@group(1) @binding(1) var<storage, read> base: array<vec4<f32>>;
@group(1) @binding(2) var<uniform> session: SessionParams;
// Bit l set when some point's first radius falls in grid level l.
@group(1) @binding(3) var<storage, read_write> levels_used: atomic<u32>;
@group(1) @binding(4) var<storage, read_write> run_stats: RunStats;

// This pass's points by grid level: how many each level has, a cursor
// each for listing them, and the points' indices, level 0's first.
struct LevelLists {
    counts: array<atomic<u32>, GRID_LEVELS>,
    cursors: array<atomic<u32>, GRID_LEVELS>,
    points: array<u32>,
}
@group(1) @binding(5) var<storage, read_write> level_lists: LevelLists;
// Per pixel of the chunk: the complement of the bits of its smallest first
// radius fraction (0: none yet; a larger complement is a smaller radius).
@group(1) @binding(6) var<storage, read_write> pixel_ratios: array<atomic<u32>>;

// schedule::level_of: the finest grid level whose radius (r_pass / 4^l)
// is at least r.
fn level_of(r: f32, r_pass: f32) -> u32 {
    var level = 0u;
    while level + 1u < GRID_LEVELS && r <= r_pass / f32(1u << (2u * (level + 1u))) {
        level++;
    }
    return level;
}

// schedule::initial_radius over R: the fraction of R that would hold
// `neighbours` photons of a full pass, given what the pilot found within R.
@compute @workgroup_size(WORKGROUP_SIZE)
fn first_radius(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    if !is_point(i) {
        return;
    }
    let expected = f32(points[i].found) * session.pilot_scale;
    var ratio = 1.0;
    if expected > session.neighbours {
        ratio = clamp(sqrt(session.neighbours / expected), MIN_RADIUS_FRACTION, 1.0);
    }
    points[i].ratio = ratio;
    let bit = 1u << level_of(ratio * params.radius, params.radius);
    // Most points find their level marked already: a load, not a write, to one address.
    if (atomicLoad(&levels_used) & bit) == 0u {
        atomicOr(&levels_used, bit);
    }
    // Positive floats order as their bits.
    let bits = bitcast<u32>(ratio);
    if bits < atomicLoad(&run_stats.min_ratio) {
        atomicMin(&run_stats.min_ratio, bits);
    }
    if bits > atomicLoad(&run_stats.max_ratio) {
        atomicMax(&run_stats.max_ratio, bits);
    }
    if session.sampled_view != 0u {
        atomicMax(&pixel_ratios[points[i].pixel], ~bits);
    }
}

// A pass's start: sums emptied, radius r_1 · s_k (params.radius is R · s_k);
// the pass radius where every point gathers within it. The point's grid
// level is its radius's, or the next coarser one built (level 0, the pass
// radius, always is); each level's points are counted (level_lists.counts
// and cursors are zero before).
@compute @workgroup_size(WORKGROUP_SIZE)
fn begin_pass(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    if !is_point(i) {
        return;
    }
    var vp = points[i];
    vp.total = 0u;
    vp.found = 0u;
    vp.sums = array<vec2<u32>, 3>(vec2<u32>(0u), vec2<u32>(0u), vec2<u32>(0u));
    vp.flux = vec2<u32>(0u);
    vp.widest = 0u;
    vp.radius = select(vp.ratio * params.radius, params.radius, session.whole_radius != 0u);
    vp.level = level_of(vp.radius, params.radius);
    while vp.level > 0u && (session.built_levels & (1u << vp.level)) == 0u {
        vp.level--;
    }
    points[i] = vp;
    atomicAdd(&level_lists.counts[vp.level], 1u);
}

// The first entry of `level`'s points in level_lists.points.
fn level_start(level: u32) -> u32 {
    var start = 0u;
    for (var l = 0u; l < level; l++) {
        start += atomicLoad(&level_lists.counts[l]);
    }
    return start;
}

// Then each point's index into its level's list (in no particular order:
// every point gathers into its own sums).
@compute @workgroup_size(WORKGROUP_SIZE)
fn list_points(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    if !is_point(i) {
        return;
    }
    let level = points[i].level;
    let slot = level_start(level) + atomicAdd(&level_lists.cursors[level], 1u);
    level_lists.points[slot] = i;
}

// A pass's gather at the points on diffuse surfaces of grid level
// `session.level`, one invocation per point of its list (level_dispatch.wgsl
// sized the dispatch).
@compute @workgroup_size(WORKGROUP_SIZE)
fn gather_level(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    gather_at(flat_index(wid, nwg, lid), false);
}

// The same at the points on rough metal and glass (dispatched where the
// plan gathers there: EffectPlan::rough_gathers).
@compute @workgroup_size(WORKGROUP_SIZE)
fn gather_rough_level(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    gather_at(flat_index(wid, nwg, lid), true);
}

// The gather of invocation `j` of `session.level`'s list, at its point if
// that is on a rough surface as `rough` says (a constant, see
// gather_segment) and the earlier segments did not read its buckets to
// the end.
fn gather_at(j: u32, rough: bool) {
    if j >= atomicLoad(&level_lists.counts[session.level]) {
        return;
    }
    let i = level_lists.points[level_start(session.level) + j];
    let done = params.gather_first > 0u && points[i].widest <= params.gather_first;
    if done || ((points[i].rough & ROUGH_POINT) != 0u) != rough {
        return;
    }
    var vp = points[i];
    gather_segment(&vp, rough);
    points[i] = vp;
}

// A pass's end, per point: weight × caustic added to its pixel's sums in
// fixed point (Accumulation::add_pass).
@compute @workgroup_size(WORKGROUP_SIZE)
fn accumulate(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let i = flat_index(wid, nwg, lid);
    if !is_point(i) {
        return;
    }
    let vp = points[i];
    let c = vp.weight * point_caustic(vp);
    for (var ch = 0u; ch < 3u; ch++) {
        add_to_sum(6u * vp.pixel + 2u * ch, to_fixed(c[ch], 32));
    }
}

// Sampled view paths, per pixel: the pass's own view (its direct light)
// added to the pixel's sums (Accumulation::add_view).
@compute @workgroup_size(WORKGROUP_SIZE)
fn add_view(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let k = flat_index(wid, nwg, lid);
    if k >= params.pixel_count {
        return;
    }
    for (var ch = 0u; ch < 3u; ch++) {
        add_to_sum(6u * k + 2u * ch, to_fixed(base[k][ch], 32));
    }
}

// Then, per pixel: its direct light plus the mean caustic of the passes so far.
@compute @workgroup_size(WORKGROUP_SIZE)
fn show(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let k = flat_index(wid, nwg, lid);
    if k >= params.pixel_count {
        return;
    }
    var mean = vec3<f32>(0.0);
    for (var ch = 0u; ch < 3u; ch++) {
        let word = 6u * k + 2u * ch;
        let sum = vec2<u32>(atomicLoad(&accum[word]), atomicLoad(&accum[word + 1u]));
        mean[ch] = from_fixed(sum, 32) * session.inv_passes;
    }
    pixels[k] = vec4<f32>(base[k].xyz + mean, 1.0);
}
