//! Every struct shared with WGSL, defined once here: `#[repr(C)]`, `Pod`,
//! explicit padding and a size assertion. Each has a twin of the same name
//! in `shaders/common.wgsl`; `tests/layout.rs` parses the WGSL with naga and
//! checks that sizes and field offsets match.
//!
//! A WGSL `vec3<f32>` is 16-byte aligned, so every `[f32; 3]` here starts at
//! a multiple of 16 and is followed by a 4-byte scalar that fills its slot.

use bytemuck::{Pod, Zeroable};

/// Per-dispatch settings (a uniform buffer): what to trace and how to render.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Params {
    /// The render's seed.
    pub seed: u32,
    /// First emission index of the current trace chunk.
    pub chunk_start: u32,
    /// Emissions in the current trace chunk.
    pub chunk_len: u32,
    /// Scratch slots per emission (the most photons one stores).
    pub slots: u32,
    /// Number of bands.
    pub band_count: u32,
    /// Specular interactions before a path ends.
    pub max_depth: u32,
    /// 0 split, 1 random band, 2 continuous.
    pub wavelengths: u32,
    /// Objects in the scene.
    pub object_count: u32,
    /// Lights in the scene.
    pub light_count: u32,
    /// Index of the light-selection CDF in the tables buffer.
    pub light_cdf: u32,
    /// 0 paper, 1 density.
    pub estimator: u32,
    /// Photons per window of a photon array (see `photons.rs`).
    pub window: u32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// First pixel of the current render chunk.
    pub pixel_offset: u32,
    /// Pixels in the current render chunk.
    pub pixel_count: u32,
    /// Photons in the map (for the grid and the gather).
    pub stored: u32,
    /// Bucket mask of the grid.
    pub grid_mask: u32,
    /// Photon capacity of the map (scatter drops what does not fit).
    pub capacity: u32,
    /// Visible points the current chunk's array holds.
    pub point_capacity: u32,
    /// Photons of each bucket skipped by the current gather pass.
    pub gather_first: u32,
    /// Photons of each bucket the current gather pass reads (at most).
    pub gather_span: u32,
    /// A gather's sums (colour) are in fixed point of 2^`sum_shift` per unit.
    pub sum_shift: i32,
    /// A gather's flux sum is in fixed point of 2^`flux_shift` per watt.
    pub flux_shift: i32,
    /// Flux of one emitted white photon.
    pub flux: f32,
    /// Gather radius.
    pub radius: f32,
    /// 1 / grid cell size.
    pub inv_cell: f32,
    /// Exposure multiplier.
    pub exposure: f32,
    /// Ambient light.
    pub ambient: [f32; 3],
    /// 1 when caustics the camera sees directly are light traced.
    pub light_tracing: u32,
    /// Background radiance.
    pub background: [f32; 3],
    /// A light-traced photon's scale: exposure / (π · pixel area).
    pub splat_scale: f32,
    /// Camera eye point.
    pub cam_origin: [f32; 3],
    /// 0 random, 1 scrambled Sobol emission and spectrum.
    pub photon_sequence: u32,
    /// Image-plane step per pixel to the right.
    pub cam_right: [f32; 3],
    /// The render's seed, for the sampled view paths' numbers (`seed` is the photon pass's).
    pub view_seed: u32,
    /// Image-plane step per pixel downward.
    pub cam_down: [f32; 3],
    /// The pass whose sampled view paths the view pass traces.
    pub view_pass: u32,
    /// Direction through the top-left image corner.
    pub cam_corner: [f32; 3],
    /// 0 view rays through pixel centres, 1 sampled view paths.
    pub view_paths: u32,
    /// The optical axis (unit).
    pub cam_forward: [f32; 3],
    /// 1 when paths take their colour from their wavelength (the band
    /// buffer's rows after the bands), 0 when from their band's weight.
    pub colour_by_wavelength: u32,
    /// `PreparedScene::white_balance`: what each channel is scaled by.
    pub white_balance: [f32; 3],
    /// The environment's radiance multiplier (0: none, the background).
    pub env_strength: f32,
    /// Its map's first texel (three floats each, row by row from the
    /// zenith) in the tables buffer.
    pub env_first: u32,
    /// Its map's texels per row.
    pub env_width: u32,
    /// Its map's rows.
    pub env_height: u32,
    /// Its turn about +y, as a fraction of a full turn.
    pub env_turn: f32,
    /// Emission indices below this are caustic photons, the rest indirect
    /// light's (`prismatic_core::photons::indirect`).
    pub caustic_photons: u32,
    /// Flux of one indirect photon.
    pub indirect_flux: f32,
    /// 1 when caustic photons are recorded on rough surfaces (`EffectPlan::rough_records`).
    pub rough_records: u32,
    /// 1 when visible points on rough-enough surfaces gather them (`EffectPlan::rough_gathers`).
    pub rough_gathers: u32,
}
const _: () = assert!(core::mem::size_of::<Params>() == 272);

/// An object's primitive. Kinds: 0 sphere (`a` centre, `ra` radius), 1 plane
/// (`a` point, `n` normal), 2 disc (`a` centre, `n` normal, `ra` radius²,
/// `rb` hole radius²), 3 convex (`count` faces from `first` in the geometry
/// buffer), 4 mesh (hierarchy nodes of 2 vec4s from `first`, `count`
/// triangles of 4 vec4s from `second`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuObject {
    /// Primitive kind.
    pub kind: u32,
    /// First record in the geometry buffer.
    pub first: u32,
    /// Number of records.
    pub count: u32,
    /// Second list's first record (a mesh's triangles).
    pub second: u32,
    /// Centre or point.
    pub a: [f32; 3],
    /// First radius-like value; a mesh's first normal-map record as bits
    /// (`NO_NORMAL_MAP`: none).
    pub ra: f32,
    /// Normal.
    pub n: [f32; 3],
    /// Second radius-like value; a mesh's first vertex-normal record as
    /// bits (`NO_VERTEX_NORMALS`: flat triangles).
    pub rb: f32,
}
const _: () = assert!(core::mem::size_of::<GpuObject>() == 48);

/// An object's surface. Kinds: 0 diffuse, 1 mirror, 2 dielectric.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuSurface {
    /// Surface kind.
    pub kind: u32,
    /// Bit flags, see `SURFACE_*` in the shader prelude.
    pub flags: u32,
    /// Index of the per-band indices in the tables buffer.
    pub ior_first: u32,
    /// Index of the n(λ) curve in the tables buffer; a measured metal's
    /// optical constants (see `SURFACE_MEASURED`).
    pub curve_first: u32,
    /// Diffuse albedo; a metal's reflectance at normal incidence; rough
    /// glass's GGX α in x (0: polished glass).
    pub albedo: [f32; 3],
    /// Index for white light; a metal's GGX α (0: polished).
    pub white_ior: f32,
    /// Albedo of the checker's odd cells; a metal's colour texture's
    /// start, width and height, as bits (see `SURFACE_HAS_COLOUR_MAP`).
    pub checker_albedo: [f32; 3],
    /// Checker cell size; a metal's colour texture's sampler flags, as bits.
    pub checker_size: f32,
    /// Checker offset; a blended metal's metalness factor in x (see
    /// `SURFACE_BLENDED`), its specular layer's F90 in y (0: none) and
    /// its base's index in z.
    pub checker_offset: [f32; 3],
    /// Samples in the n(λ) curve.
    pub curve_len: u32,
    /// Absorption coefficient per RGB channel (coloured glass); a metal's
    /// specular layer's F0 per channel.
    pub absorption: [f32; 3],
    /// Index of the per-band absorption coefficients in the tables buffer;
    /// of a metal's specular layer's maps (see `SURFACE_SPECULAR_MAP`).
    pub absorption_first: u32,
    /// Index of the texture in the tables buffer (a diffuse surface's base
    /// colour, a metal's or rough glass's roughness map): 256 decoding
    /// entries (sRGB, or linear), then the texels (see `SURFACE_HAS_TEXTURE`).
    pub texture_first: u32,
    /// Texels per row.
    pub texture_width: u32,
    /// Rows.
    pub texture_height: u32,
    /// Record of the first triangle's texture coordinates in the geometry buffer.
    pub uv_first: u32,
    /// Radiance its front faces emit (an area light's glow).
    pub emission: [f32; 3],
    /// Index of a dielectric's or metal's film's index (relative to the
    /// outside), thickness (nm) and factor in the tables buffer (see `SURFACE_HAS_FILM`).
    pub film_first: u32,
}
const _: () = assert!(core::mem::size_of::<GpuSurface>() == 112);

/// A light. Kinds: 0 spot, 1 point, 2 beam (a sun is the beam it emits
/// from, with `sun` set: lit everywhere, not only inside the disc), 3 area
/// (a triangle: `position` its first corner, `tangent` and `bitangent` its
/// edges from there, `axis` its unit front normal, `radius` its radiance).
/// Projection kinds: 0 none,
/// 1 cones, 2 discs (targets are vec4s in the geometry buffer: axis and
/// cos θ_max, or centre and radius; their CDF is in the tables buffer).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    /// Light kind.
    pub kind: u32,
    /// 1 when shadow rays are traced toward it.
    pub shadows: u32,
    /// Projection-map kind.
    pub proj_kind: u32,
    /// Projection targets.
    pub proj_count: u32,
    /// Position (spot, point) or centre of the emitting disc (beam).
    pub position: [f32; 3],
    /// Power in W.
    pub power: f32,
    /// Unit axis (spot, beam).
    pub axis: [f32; 3],
    /// cos of the spot's half-angle.
    pub cos_max: f32,
    /// First basis vector around the axis.
    pub tangent: [f32; 3],
    /// Beam radius.
    pub radius: f32,
    /// Second basis vector around the axis.
    pub bitangent: [f32; 3],
    /// Projection weight of a sample covered once.
    pub proj_scale: f32,
    /// First target in the geometry buffer.
    pub proj_first: u32,
    /// First CDF entry in the tables buffer.
    pub proj_cdf: u32,
    /// 1 for a sun.
    pub sun: u32,
    /// Entries of its wavelength table in the tables buffer (0: the
    /// equal-energy spectrum, drawn uniformly).
    pub spectrum_len: u32,
    /// Column 0 of `LightSpectrum::reflected`: the colour a diffuse
    /// surface reflects of its light per unit of irradiance and of the
    /// albedo's red primary (columns 1 and 2 below).
    pub reflected_r: [f32; 3],
    /// First entry of its wavelength table: `spectrum_len` cumulative
    /// probabilities, as many starts and widths (nm), then its N bands' shares.
    pub spectrum_first: u32,
    /// Column 1 of `LightSpectrum::reflected` (the green primary).
    pub reflected_g: [f32; 3],
    /// cos of the spot's inner half-angle (`cos_max` for a hard edge).
    pub cos_inner: f32,
    /// Column 2 of `LightSpectrum::reflected` (the blue primary).
    pub reflected_b: [f32; 3],
    /// 1 when an area light's shadow rays aim at `aim` this pass
    /// (`prismatic_core::plan::area_aims`).
    pub aimed: u32,
    /// The aim's barycentric (s, t) along (`tangent`, `bitangent`).
    pub aim: [f32; 2],
    /// Padding.
    pub _pad1: [u32; 2],
    /// A drawn sun's mean direction toward its light over the draws
    /// (`Light::Sun::mean_toward`; zero for any other light, which its
    /// control variate's test n · m̄ > 0 then never takes).
    pub mean_toward: [f32; 3],
    /// A spot or point light's range (`prismatic_core::model::light_range`);
    /// 0: none.
    pub range: f32,
}
const _: () = assert!(core::mem::size_of::<GpuLight>() == 176);

/// A spectral band; after a table's N bands, the band buffer holds the
/// rows of the colour of each wavelength
/// ([`prismatic_core::model::wavelength_rgb`], in `weight`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuBand {
    /// Linear RGB weight C_i.
    pub weight: [f32; 3],
    /// Wavelength the band is traced at.
    pub lambda_nm: f32,
    /// Interval start.
    pub lo_nm: f32,
    /// Interval end.
    pub hi_nm: f32,
    /// Largest |weight| channel (the band's share of a pixel).
    pub max_weight: f32,
    /// Padding.
    pub _pad: f32,
}
const _: () = assert!(core::mem::size_of::<GpuBand>() == 32);

/// What one workgroup of the photon pass did, summed over chunks; the host
/// adds the workgroups up in u64/f64 for [`prismatic_core::TraceStats`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Tally {
    /// Emitted, paths, segments, specular paths, stored.
    pub counts: [u32; 5],
    /// Padding.
    pub _pad0: [u32; 3],
    /// Flux emitted, stored, escaped, direct, depth limited, absorbed.
    pub flux: [f32; 6],
    /// Padding.
    pub _pad1: [u32; 2],
}
const _: () = assert!(core::mem::size_of::<Tally>() == 64);

/// A view ray's diffuse (or rough) hit waiting for its caustic gather (progressive
/// photon mapping's "hit point"): where, facing which way, within which
/// radius, what the caustic radiance there is worth to its pixel, and the
/// gather's running sums in fixed point (i64 as `[lo, hi]` words: integer
/// sums do not depend on the order the photons come in).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct VisiblePoint {
    /// The hit point.
    pub position: [f32; 3],
    /// Photons gathered so far, in bands (a white photon counts N).
    pub total: u32,
    /// The surface normal on the side the view ray came from.
    pub normal: [f32; 3],
    /// The gather radius at this point in this pass.
    pub radius: f32,
    /// tint × white balance × exposure / π: pixel radiance per unit of
    /// reflected caustic irradiance.
    pub weight: [f32; 3],
    /// Photons accepted so far (a white photon counts once).
    pub found: u32,
    /// Density estimator: Σ C_b Φ N; paper estimator: Σ C_b; in 2^`sum_shift` per unit.
    pub sums: [[u32; 2]; 3],
    /// Σ Φ in 2^`flux_shift` per watt.
    pub flux: [u32; 2],
    /// The pixel it belongs to, within its chunk.
    pub pixel: u32,
    /// Its first radius as a fraction of the scene's radius.
    pub ratio: f32,
    /// The grid level it gathers in this pass.
    pub level: u32,
    /// Photons in the fullest bucket its disc touches this pass (set by a
    /// pass's first gather segment: later segments skip the point past it).
    pub widest: u32,
    /// The surface's RGB albedo, whose reflectance reflects each photon gathered.
    pub albedo: [f32; 3],
    /// On rough metal or glass ([`ROUGH_POINT`] set): the object; 0 on a
    /// diffuse surface. A rough point's `normal` is the shading normal
    /// there, on either side.
    pub rough: u32,
    /// A rough point's view ray direction.
    pub toward: [f32; 3],
    /// A rough point's mesh triangle.
    pub triangle: u32,
}
const _: () = assert!(core::mem::size_of::<VisiblePoint>() == 128);

/// The bit of [`VisiblePoint::rough`] that marks a point on rough metal or glass.
pub const ROUGH_POINT: u32 = 1 << 31;

/// A render's statistics on the device: the passes' trace tallies summed
/// (counts as `[lo, hi]` u64 words, flux in f32; the order of [`Tally`]),
/// and the smallest and largest first-radius ratio (f32 bits: positive
/// floats order as their bits).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct RunStats {
    /// Emitted, paths, segments, specular paths, stored.
    pub counts: [[u32; 2]; 5],
    /// Flux emitted, stored, escaped, direct, depth limited, absorbed.
    pub flux: [f32; 6],
    /// Smallest first radius / R, as f32 bits.
    pub min_ratio: u32,
    /// Largest first radius / R, as f32 bits.
    pub max_ratio: u32,
}
const _: () = assert!(core::mem::size_of::<RunStats>() == 72);

/// A live session's per-pass settings (group 1 of its progressive entries).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct SessionParams {
    /// A full pass's photons per pilot photon.
    pub pilot_scale: f32,
    /// Photons a first radius should hold (neighbours × photons per path).
    pub neighbours: f32,
    /// 1 / passes summed, this pass included.
    pub inv_passes: f32,
    /// 1 when every point gathers within the pass radius (the pilot, fixed radii).
    pub whole_radius: u32,
    /// The grid level a `gather_level` dispatch serves.
    pub level: u32,
    /// Bit l set when grid level l is built (bit 0 always is).
    pub built_levels: u32,
    /// 1 when each pass traces its own view (sampled view paths): the
    /// pilot also marks each pixel's first radius.
    pub sampled_view: u32,
    /// Padding.
    pub _pad1: u32,
}
const _: () = assert!(core::mem::size_of::<SessionParams>() == 32);

/// The settings of one prefix-sum level.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ScanParams {
    /// Elements to scan.
    pub n: u32,
    /// Padding (uniform buffers are 16-byte granular).
    pub _pad0: u32,
    /// Padding.
    pub _pad1: u32,
    /// Padding.
    pub _pad2: u32,
}
const _: () = assert!(core::mem::size_of::<ScanParams>() == 16);
