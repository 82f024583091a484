// The scene on the device: bind group 0.

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> objects: array<GpuObject>;
@group(0) @binding(2) var<storage, read> surfaces: array<GpuSurface>;
@group(0) @binding(3) var<storage, read> lights: array<GpuLight>;
@group(0) @binding(4) var<storage, read> bands: array<GpuBand>;
// Convex faces (normal, offset), mesh nodes (lo, first; hi, count as bits),
// triangles (v0, e1, e2, normal), textured triangles' coordinates (uv0,
// du1; du2), projection targets.
@group(0) @binding(5) var<storage, read> geometry: array<vec4<f32>>;
// Per-band indices, n(λ) curves, light and projection CDFs, textures (the
// sRGB decoding table, then the texels as exact integers r + 256 g + 65536 b).
@group(0) @binding(6) var<storage, read> tables: array<f32>;

