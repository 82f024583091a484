// A live session's progressive passes at resident visible points: twin of
// prismatic_core::progressive. The view pass leaves each pixel's direct
// light (kept as `base`) and its visible points; the pilot's gather at the
// scene's radius R gives each point its first radius (`first_radius`, as a
// fraction of R); each pass empties the points' sums and sets their radii
// (`begin_pass`), gathers (gather.wgsl's `gather`), then adds each pixel's
// caustic to its running sum and writes base + mean (`accumulate`).

struct SessionParams {
    // A full pass's photons per pilot photon.
    pilot_scale: f32,
    // Photons a first radius should hold (neighbours × photons per path).
    neighbours: f32,
    // 1 / passes summed, this pass included.
    inv_passes: f32,
    // 1 for the pilot pass: every radius the scene's.
    pilot: u32,
}

@group(1) @binding(0) var<storage, read_write> radius_ratio: array<f32>;
@group(1) @binding(1) var<storage, read_write> accum: array<vec4<f32>>;
@group(1) @binding(2) var<storage, read> base: array<vec4<f32>>;
@group(1) @binding(3) var<uniform> session: SessionParams;

// progressive::initial_radius over R: the fraction of R that would hold
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
    radius_ratio[i] = ratio;
}

// A pass's start: sums emptied, radius r_1 · s_k (params.radius is R · s_k);
// the pilot's radius is R.
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
    vp.flux = 0.0;
    vp.sums = vec3<f32>(0.0);
    vp.flux_c = 0.0;
    vp.sums_c = vec3<f32>(0.0);
    vp.found = 0u;
    vp.radius = select(radius_ratio[i] * params.radius, params.radius, session.pilot != 0u);
    points[i] = vp;
}

// A pass's end: each pixel's points' caustic added to its sum; the pixel
// is its direct light plus the mean caustic of the passes so far.
@compute @workgroup_size(WORKGROUP_SIZE)
fn accumulate(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) nwg: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let k = flat_index(wid, nwg, lid);
    if k >= params.pixel_count {
        return;
    }
    let sum = accum[k].xyz + pixel_caustic(k);
    accum[k] = vec4<f32>(sum, 0.0);
    pixels[k] = vec4<f32>(base[k].xyz + sum * session.inv_passes, 1.0);
}
