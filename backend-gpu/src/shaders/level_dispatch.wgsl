// The arguments of a pass's indirect gather dispatches, one (x, y, z) per
// grid level: workgroups for the points session.wgsl's `begin_pass`
// counted at that level, over two dimensions past MAX_WORKGROUPS (as
// pipelines::dispatch splits a direct dispatch).

// The first words of the chunk's level lists: points per level.
@group(0) @binding(0) var<storage, read> level_counts: array<u32, GRID_LEVELS>;
@group(0) @binding(1) var<storage, read_write> level_args: array<u32>;

@compute @workgroup_size(GRID_LEVELS)
fn level_dispatches(@builtin(local_invocation_index) level: u32) {
    let groups = (level_counts[level] + WORKGROUP_SIZE - 1u) / WORKGROUP_SIZE;
    level_args[3u * level] = min(groups, MAX_WORKGROUPS);
    level_args[3u * level + 1u] = (groups + MAX_WORKGROUPS - 1u) / MAX_WORKGROUPS;
    level_args[3u * level + 2u] = 1u;
}
