//! The WGSL sources of every pipeline, assembled from the files under
//! `shaders/` behind a prelude of constants written from the Rust ones
//! (tolerances, RNG dimensions, band and workgroup sizes), so that the two
//! languages cannot drift apart.

use prismatic_core::geometry::texture::TEXEL_LIMIT;
use prismatic_core::model::bands::VISIBLE_NM;
use prismatic_core::model::photon::WHITE_BAND;
use prismatic_core::model::scene::{
    Estimator, HERO_WAVELENGTHS, MAX_DEPTH, PhotonSequence, ViewPaths, WavelengthSampling,
};
use prismatic_core::model::{metals, wavelength_rgb};
use prismatic_core::sampling::pixel_sample;
use prismatic_core::util::math::{COS_COEFFS, SIN_COEFFS};
use prismatic_core::util::rng::dim;
use prismatic_core::util::tolerance::{
    BARYCENTRIC_EPS, CONNECTION_REL, LAYER_PLANE_REL, MIN_VIEW_WEIGHT, SURFACE_OFFSET_ABS, SURFACE_OFFSET_REL,
    SURFACE_SKIN_FACTOR,
};
use std::fmt::Write as _;

/// Invocations per workgroup of the per-photon and per-pixel passes.
pub const WORKGROUP_SIZE: u32 = 64;
/// Workgroups per dispatch dimension (WebGPU's guaranteed minimum); larger
/// dispatches are split over two dimensions.
pub const MAX_WORKGROUPS: u32 = 65_535;
/// Invocations per workgroup of the prefix sum.
pub const SCAN_THREADS: u32 = 256;
/// Elements each prefix-sum invocation scans.
pub const SCAN_PER_THREAD: u32 = 4;
/// Elements per prefix-sum workgroup.
pub const SCAN_BLOCK: u32 = SCAN_THREADS * SCAN_PER_THREAD;
/// Bindings a photon array is split over (each at most one binding's size).
pub const WINDOWS: u32 = 4;

/// Surface and light kinds and flags, as `GpuSurface` and `GpuLight` encode them.
pub mod kind {
    /// Lambertian surface.
    pub const SURFACE_DIFFUSE: u32 = 0;
    /// Mirror.
    pub const SURFACE_MIRROR: u32 = 1;
    /// Dielectric.
    pub const SURFACE_DIELECTRIC: u32 = 2;
    /// Metal: F0 in `albedo`, its GGX α in `white_ior` (0: polished).
    pub const SURFACE_METAL: u32 = 3;
    /// White photons split into bands here.
    pub const SURFACE_SPLITS_PHOTONS: u32 = 1;
    /// White view rays split into bands here.
    pub const SURFACE_SPLITS_VIEW_RAYS: u32 = 2;
    /// The diffuse surface has a checker.
    pub const SURFACE_HAS_CHECKER: u32 = 4;
    /// The dielectric has an n(λ) curve.
    pub const SURFACE_HAS_CURVE: u32 = 8;
    /// The dielectric absorbs (coloured glass).
    pub const SURFACE_ABSORBS: u32 = 16;
    /// The diffuse surface has a texture.
    pub const SURFACE_HAS_TEXTURE: u32 = 32;
    /// Its texture is read by nearest texel (else bilinearly).
    pub const SURFACE_TEXTURE_NEAREST: u32 = 64;
    /// The dielectric is a thin sheet (rays pass straight through).
    pub const SURFACE_THIN: u32 = 128;
    /// Where the texture's wrap along u sits in the flags (two bits, `WRAP_*`).
    pub const TEXTURE_WRAP_U_SHIFT: u32 = 8;
    /// Where the texture's wrap along v sits in the flags (two bits, `WRAP_*`).
    pub const TEXTURE_WRAP_V_SHIFT: u32 = 10;
    /// The dielectric or metal has a thin film (its index, thickness and factor in the tables at `film_first`).
    pub const SURFACE_HAS_FILM: u32 = 4096;
    /// The metal is measured: its n and k per row of `model::metals` in the tables at `curve_first`.
    pub const SURFACE_MEASURED: u32 = 8192;
    /// The metal's F0 is scaled by its colour texture: the texture's start,
    /// width and height in `checker_albedo`, its sampler's flags in
    /// `checker_size` (all as bits).
    pub const SURFACE_HAS_COLOUR_MAP: u32 = 16384;
    /// The metal is blended with a diffuse surface of its colour: its
    /// metalness factor in `checker_offset.x` (`MetalOptics::is_blended`).
    pub const SURFACE_BLENDED: u32 = 32768;
    /// The blended metal's metalness is scaled by the blue channel of its
    /// texture (the roughness map; `Metalness::mapped`).
    pub const SURFACE_METALNESS_MAP: u32 = 65536;
    /// The film's thickness varies by the green channel of a texture: its
    /// minimum and the texture's start, width, height and sampler flags
    /// (as bits) follow the film's record at `film_first`.
    pub const SURFACE_FILM_THICKNESS_MAP: u32 = 131072;
    /// The film's factor varies by the red channel of a texture, whose
    /// reference follows the thickness map's.
    pub const SURFACE_FILM_FACTOR_MAP: u32 = 262144;
    /// The film's thickness and factor at a hit are in `emission.xy` (a
    /// surface copy `surface_at` made; its map flags cleared).
    pub const SURFACE_FILM_AT_HIT: u32 = 524288;
    /// The metal's specular layer's weight varies by the red channel of a
    /// texture: the layer's unclipped F0 (`SpecularMap::color_f0`) and
    /// the texture's reference (start, width, height and sampler flags, as
    /// bits) are in the tables at `absorption_first`.
    pub const SURFACE_SPECULAR_MAP: u32 = 1 << 20;
    /// The layer's colour varies by a texture (sRGB), whose reference
    /// follows the weight map's.
    pub const SURFACE_SPECULAR_COLOUR_MAP: u32 = 1 << 21;
    /// Either of the layer's maps.
    pub const SURFACE_SPECULAR_MAPS: u32 = SURFACE_SPECULAR_MAP | SURFACE_SPECULAR_COLOUR_MAP;
    /// `Wrap::Repeat`.
    pub const WRAP_REPEAT: u32 = 0;
    /// `Wrap::ClampToEdge`.
    pub const WRAP_CLAMP_TO_EDGE: u32 = 1;
    /// `Wrap::MirroredRepeat`.
    pub const WRAP_MIRRORED_REPEAT: u32 = 2;
    /// Sphere.
    pub const OBJECT_SPHERE: u32 = 0;
    /// Infinite plane.
    pub const OBJECT_PLANE: u32 = 1;
    /// Disk (or annulus).
    pub const OBJECT_DISK: u32 = 2;
    /// Convex polyhedron of half-spaces (a prism).
    pub const OBJECT_CONVEX: u32 = 3;
    /// Triangle mesh in its hierarchy.
    pub const OBJECT_MESH: u32 = 4;
    /// A mesh's `rb` bits when it has no vertex normals (flat triangles):
    /// its normal records follow its triangles', so never start at 0.
    pub const NO_VERTEX_NORMALS: u32 = 0;
    /// A mesh's `ra` bits when it has no normal map: its map's records
    /// follow its triangles', so never start at 0.
    pub const NO_NORMAL_MAP: u32 = 0;
    /// Spot light.
    pub const LIGHT_SPOT: u32 = 0;
    /// Point light.
    pub const LIGHT_POINT: u32 = 1;
    /// Beam.
    pub const LIGHT_BEAM: u32 = 2;
    /// Emitting triangle.
    pub const LIGHT_AREA: u32 = 3;
    /// No projection map.
    pub const PROJECTION_NONE: u32 = 0;
    /// Projection onto cones of directions.
    pub const PROJECTION_CONES: u32 = 1;
    /// Projection onto discs of the beam's plane.
    pub const PROJECTION_DISCS: u32 = 2;
    /// Projection of an area light onto spheres, a cone from each photon's start.
    pub const PROJECTION_SPHERES: u32 = 3;
}

/// The codes of the render settings' enums in `Params` (`scene.rs` writes
/// them, the prelude names them for the shaders): one `match` each, so a
/// new variant does not compile until it has a code.
pub mod code {
    use prismatic_core::model::scene::{Estimator, PhotonSequence, ViewPaths, WavelengthSampling};

    /// `Params::wavelengths`.
    pub fn wavelengths(w: WavelengthSampling) -> u32 {
        match w {
            WavelengthSampling::Split => 0,
            WavelengthSampling::RandomBand => 1,
            WavelengthSampling::Continuous => 2,
            WavelengthSampling::Hero => 3,
        }
    }

    /// `Params::photon_sequence`.
    pub fn photon_sequence(s: PhotonSequence) -> u32 {
        match s {
            PhotonSequence::Random => 0,
            PhotonSequence::Sobol => 1,
        }
    }

    /// `Params::estimator`.
    pub fn estimator(e: Estimator) -> u32 {
        match e {
            Estimator::Paper => 0,
            Estimator::Density => 1,
        }
    }

    /// `Params::view_paths`.
    pub fn view_paths(v: ViewPaths) -> u32 {
        match v {
            ViewPaths::Centre => 0,
            ViewPaths::Sampled => 1,
            ViewPaths::Hero => 2,
        }
    }
}

/// The view-ray stack of the render pass: one pending sibling per depth
/// (the other Fresnel branch), two at the deepest, the rest of one band
/// split and a spare; at least the stack of the default depth (12), so
/// that every scene of that depth or less shares one view pipeline. Each
/// size is a pipeline of its own, and its first compile on lavapipe took
/// about 25 s at 7, 8 and 16 entries alike, and at depth 64 (68 entries)
/// about 200 s with whole entries on the stack, 94 to 100 s with view.wgsl's
/// 12-word `Stacked` ones (2026-11-29, 2-core container).
pub fn stack_size(max_depth: u32) -> u32 {
    (max_depth.min(MAX_DEPTH) + 4).max(16)
}

fn prelude(stack: u32) -> String {
    let mut s = String::from("// Written by prismatic_gpu::shaders from the Rust constants.\n");
    let mut u = |name: &str, v: u32| writeln!(s, "const {name}: u32 = {v}u;").unwrap();
    u("WORKGROUP_SIZE", WORKGROUP_SIZE);
    u("MAX_WORKGROUPS", MAX_WORKGROUPS);
    u("SCAN_THREADS", SCAN_THREADS);
    u("SCAN_PER_THREAD", SCAN_PER_THREAD);
    u("SCAN_BLOCK", SCAN_BLOCK);
    u("STACK_SIZE", stack);
    u("WHITE_BAND", u32::from(WHITE_BAND));
    u("DIM_LIGHT", dim::LIGHT);
    u("DIM_DIRECTION", dim::DIRECTION);
    u("DIM_TARGET", dim::TARGET);
    u("DIM_SPECTRUM", dim::SPECTRUM);
    u("DIM_AREA", dim::AREA);
    u("DIM_PATH", dim::PATH);
    u("DIM_PER_BAND", dim::PER_BAND);
    u("DIM_ABSORB", dim::ABSORB);
    u("DIM_BOUNCE", dim::BOUNCE);
    u("DIM_CHOOSE", dim::CHOOSE);
    u("DIM_METAL_PART", dim::METAL_PART);
    u("DIM_BASE_BOUNCE", dim::BASE_BOUNCE);
    u("SEQUENCE_SOBOL", code::photon_sequence(PhotonSequence::Sobol));
    u("WAVELENGTHS_SPLIT", code::wavelengths(WavelengthSampling::Split));
    u("WAVELENGTHS_RANDOM_BAND", code::wavelengths(WavelengthSampling::RandomBand));
    u("WAVELENGTHS_CONTINUOUS", code::wavelengths(WavelengthSampling::Continuous));
    u("WAVELENGTHS_HERO", code::wavelengths(WavelengthSampling::Hero));
    u("VIEW_PATHS_CENTRE", code::view_paths(ViewPaths::Centre));
    u("VIEW_PATHS_SAMPLED", code::view_paths(ViewPaths::Sampled));
    u("HERO_WAVELENGTHS", HERO_WAVELENGTHS);
    u("PIXEL_SCRAMBLE", pixel_sample::PIXEL_SCRAMBLE);
    u("VIEW_BRANCH", pixel_sample::BRANCH);
    u("VIEW_PER_PATH", pixel_sample::PER_PATH);
    u("VIEW_FACET", pixel_sample::FACET);
    u("ESTIMATOR_PAPER", code::estimator(Estimator::Paper));
    u("ESTIMATOR_DENSITY", code::estimator(Estimator::Density));
    u("OBJECT_SPHERE", kind::OBJECT_SPHERE);
    u("OBJECT_PLANE", kind::OBJECT_PLANE);
    u("OBJECT_DISK", kind::OBJECT_DISK);
    u("OBJECT_CONVEX", kind::OBJECT_CONVEX);
    u("OBJECT_MESH", kind::OBJECT_MESH);
    u("NO_VERTEX_NORMALS", kind::NO_VERTEX_NORMALS);
    u("NO_NORMAL_MAP", kind::NO_NORMAL_MAP);
    u("SURFACE_DIFFUSE", kind::SURFACE_DIFFUSE);
    u("SURFACE_MIRROR", kind::SURFACE_MIRROR);
    u("SURFACE_DIELECTRIC", kind::SURFACE_DIELECTRIC);
    u("SURFACE_METAL", kind::SURFACE_METAL);
    u("SURFACE_SPLITS_PHOTONS", kind::SURFACE_SPLITS_PHOTONS);
    u("SURFACE_SPLITS_VIEW_RAYS", kind::SURFACE_SPLITS_VIEW_RAYS);
    u("SURFACE_HAS_CHECKER", kind::SURFACE_HAS_CHECKER);
    u("SURFACE_HAS_CURVE", kind::SURFACE_HAS_CURVE);
    u("SURFACE_ABSORBS", kind::SURFACE_ABSORBS);
    u("SURFACE_HAS_TEXTURE", kind::SURFACE_HAS_TEXTURE);
    u("SURFACE_TEXTURE_NEAREST", kind::SURFACE_TEXTURE_NEAREST);
    u("SURFACE_THIN", kind::SURFACE_THIN);
    u("SURFACE_HAS_FILM", kind::SURFACE_HAS_FILM);
    u("SURFACE_MEASURED", kind::SURFACE_MEASURED);
    u("SURFACE_HAS_COLOUR_MAP", kind::SURFACE_HAS_COLOUR_MAP);
    u("SURFACE_BLENDED", kind::SURFACE_BLENDED);
    u("SURFACE_METALNESS_MAP", kind::SURFACE_METALNESS_MAP);
    u("SURFACE_FILM_THICKNESS_MAP", kind::SURFACE_FILM_THICKNESS_MAP);
    u("SURFACE_FILM_FACTOR_MAP", kind::SURFACE_FILM_FACTOR_MAP);
    u("SURFACE_FILM_AT_HIT", kind::SURFACE_FILM_AT_HIT);
    u("SURFACE_SPECULAR_MAP", kind::SURFACE_SPECULAR_MAP);
    u("SURFACE_SPECULAR_COLOUR_MAP", kind::SURFACE_SPECULAR_COLOUR_MAP);
    u("METAL_ROWS", metals::ROWS as u32);
    u("TEXTURE_WRAP_U_SHIFT", kind::TEXTURE_WRAP_U_SHIFT);
    u("TEXTURE_WRAP_V_SHIFT", kind::TEXTURE_WRAP_V_SHIFT);
    u("WRAP_CLAMP_TO_EDGE", kind::WRAP_CLAMP_TO_EDGE);
    u("WRAP_MIRRORED_REPEAT", kind::WRAP_MIRRORED_REPEAT);
    u("LIGHT_SPOT", kind::LIGHT_SPOT);
    u("LIGHT_POINT", kind::LIGHT_POINT);
    u("LIGHT_BEAM", kind::LIGHT_BEAM);
    u("LIGHT_AREA", kind::LIGHT_AREA);
    u("ON_ROUGH_SURFACE", u32::from(prismatic_core::model::photon::ON_ROUGH_SURFACE));
    u("ROUGH_POINT", crate::layout::ROUGH_POINT);
    u("PROJECTION_NONE", kind::PROJECTION_NONE);
    u("PROJECTION_CONES", kind::PROJECTION_CONES);
    u("PROJECTION_DISCS", kind::PROJECTION_DISCS);
    u("PROJECTION_SPHERES", kind::PROJECTION_SPHERES);
    u("WAVELENGTH_RGB_ROWS", wavelength_rgb::ROWS as u32);
    u("GRID_LEVELS", prismatic_core::plan::schedule::GRID_LEVELS as u32);
    u("MAX_BVH_DEPTH", prismatic_core::geometry::bvh::MAX_DEPTH as u32);
    let mut f = |name: &str, v: f32| writeln!(s, "const {name}: f32 = {v:e};").unwrap();
    f("PI", std::f32::consts::PI);
    f("BIG", f32::MAX);
    f("MAX_FILMED_F0", prismatic_core::optics::metal::MAX_FILMED_F0);
    f("SURFACE_OFFSET_REL", SURFACE_OFFSET_REL);
    f("SURFACE_OFFSET_ABS", SURFACE_OFFSET_ABS);
    f("SURFACE_SKIN_FACTOR", SURFACE_SKIN_FACTOR);
    f("TEXEL_LIMIT", TEXEL_LIMIT);
    f("BARYCENTRIC_EPS", BARYCENTRIC_EPS);
    f("MIN_REFLECTED_LIFT", prismatic_core::geometry::shading::MIN_REFLECTED_LIFT);
    f("MIN_TANGENT_SHARE", prismatic_core::geometry::normal_map::MIN_TANGENT_SHARE);
    f("MIN_ALPHA", prismatic_core::optics::microfacet::MIN_ALPHA);
    f("GATHER_ALPHA", prismatic_core::optics::microfacet::GATHER_ALPHA);
    f("MIN_MAPPED_LENGTH", prismatic_core::geometry::normal_map::MIN_MAPPED_LENGTH);
    f("BOX_MARGIN", prismatic_core::geometry::bvh::BOX_MARGIN);
    f("MIN_VIEW_WEIGHT", MIN_VIEW_WEIGHT);
    f("CONNECTION_REL", CONNECTION_REL);
    f("LAYER_PLANE_REL", LAYER_PLANE_REL);
    f("VISIBLE_NM_LO", VISIBLE_NM.0);
    f("WAVELENGTH_RGB_FIRST_NM", wavelength_rgb::FIRST_NM);
    f("WAVELENGTH_RGB_STEP_NM", wavelength_rgb::STEP_NM);
    f("METAL_FIRST_NM", metals::FIRST_NM);
    f("METAL_STEP_NM", metals::STEP_NM);
    f("MIN_RADIUS_FRACTION", prismatic_core::plan::schedule::MIN_RADIUS_FRACTION);
    for (i, c) in SIN_COEFFS.iter().enumerate() {
        f(&format!("SIN_C{i}"), *c);
    }
    for (i, c) in COS_COEFFS.iter().enumerate() {
        f(&format!("COS_C{i}"), *c);
    }
    s
}

/// A photon array split over [`WINDOWS`] bindings `first..first + WINDOWS`
/// of `group`, with `{name}_load(i)` (and `{name}_store(i, p)` when
/// writable) over the whole array; `params.window` photons per binding.
fn photon_windows(name: &str, group: u32, first: u32, writable: bool) -> String {
    let access = if writable { "read_write" } else { "read" };
    let mut s = String::new();
    for w in 0..WINDOWS {
        writeln!(s, "@group({group}) @binding({}) var<storage, {access}> {name}{w}: array<Photon>;", first + w)
            .unwrap();
    }
    writeln!(
        s,
        "fn {name}_load(i: u32) -> Photon {{\n    let w = i / params.window;\n    let k = i - w * params.window;"
    )
    .unwrap();
    for w in 0..WINDOWS - 1 {
        writeln!(s, "    if w == {w}u {{ return {name}{w}[k]; }}").unwrap();
    }
    writeln!(s, "    return {name}{}[k];\n}}", WINDOWS - 1).unwrap();
    if writable {
        writeln!(
            s,
            "fn {name}_store(i: u32, p: Photon) {{\n    let w = i / params.window;\n    let k = i - w * params.window;"
        )
        .unwrap();
        for w in 0..WINDOWS {
            writeln!(s, "    if w == {w}u {{ {name}{w}[k] = p; }}").unwrap();
        }
        s.push_str("}\n");
    }
    s
}

const COMMON: &str = include_str!("shaders/common.wgsl");
const FIXED: &str = include_str!("shaders/fixed.wgsl");
/// The scene's bindings and what reads them: intersection, shading normals, textures.
const SCENE: &str = concat!(
    include_str!("shaders/scene_bindings.wgsl"),
    include_str!("shaders/scene.wgsl"),
    include_str!("shaders/texture.wgsl")
);
/// What reads the scene, without its bindings (the gather declares its own).
const SCENE_FUNCTIONS: &str = concat!(include_str!("shaders/scene.wgsl"), include_str!("shaders/texture.wgsl"));
/// What a surface sends toward an eye of a photon's light.
const REFLECTS: &str = include_str!("shaders/reflects.wgsl");
const ALBEDO: &str = include_str!("shaders/albedo.wgsl");
const SUMS: &str = include_str!("shaders/sums.wgsl");
const COLOUR: &str = include_str!("shaders/colour.wgsl");
const CONNECT: &str = include_str!("shaders/connect.wgsl");
const METAL: &str = include_str!("shaders/metal.wgsl");

/// The functions every pipeline shares (RNG, optics, the estimator's last
/// step, fixed-point sums) behind the prelude, with no bindings and no
/// entry point: tests append an entry point that runs them on their own.
pub fn library() -> String {
    [prelude(0), COMMON.into(), FIXED.into()].concat()
}

/// Emit + trace (entry `main`).
pub fn trace() -> String {
    [emission(), COLOUR.into(), ALBEDO.into(), METAL.into(), include_str!("shaders/trace.wgsl").into()].concat()
}

/// The scene's bindings (group 0) and photon emission (`emit`): the first
/// part of [`trace`], and on its own the library of the emission twin test.
pub fn emission() -> String {
    [prelude(0), COMMON.into(), SCENE.into(), include_str!("shaders/emit.wgsl").into()].concat()
}

/// Compaction into canonical order (entries `scatter`, `advance`); the map is bindings 6–9.
pub fn compact() -> String {
    [prelude(0), COMMON.into(), include_str!("shaders/compact.wgsl").into(), photon_windows("map", 0, 6, true)].concat()
}

/// Exclusive prefix sum (entries `scan_blocks`, `add_sums`).
pub fn scan() -> String {
    [prelude(0), COMMON.into(), include_str!("shaders/scan.wgsl").into()].concat()
}

/// Grid build (entries `count`, `scatter`, `widest`); the map is bindings
/// 3–6, the sorted copy 7–10, the widest bucket's size 11.
pub fn grid() -> String {
    [
        prelude(0),
        COMMON.into(),
        include_str!("shaders/grid.wgsl").into(),
        photon_windows("map", 0, 3, false),
        photon_windows("sorted", 0, 7, true),
    ]
    .concat()
}

/// The view rays into pixels and visible points (entry `main`) with a
/// view-ray stack of `stack` entries.
pub fn view(stack: u32) -> String {
    [
        prelude(stack),
        COMMON.into(),
        SCENE.into(),
        COLOUR.into(),
        ALBEDO.into(),
        METAL.into(),
        include_str!("shaders/view.wgsl").into(),
    ]
    .concat()
}

/// A session's passes (entries `first_radius`, `begin_pass`,
/// `list_points`, `gather_level`, `gather_rough_level`, `accumulate`, `add_view`, `show`): the
/// gather's bindings in group 0 (the sorted photons are bindings 6–9, the
/// scene's objects, surfaces, geometry and tables 10–13) and
/// group 1 (the pixels' sums, their direct light, session params, levels
/// used, statistics, the points' lists by level, the pixels' first radii).
pub fn session() -> String {
    [
        library(),
        SCENE_FUNCTIONS.into(),
        ALBEDO.into(),
        METAL.into(),
        REFLECTS.into(),
        include_str!("shaders/gather.wgsl").into(),
        COLOUR.into(),
        photon_windows("sorted", 0, 6, false),
        SUMS.into(),
        include_str!("shaders/session.wgsl").into(),
    ]
    .concat()
}

/// Light tracing (entry `splat`): the scene in group 0; in group 1 the
/// pixels' sums (binding 0), the stored count (1) and the map (2–5).
pub fn splat() -> String {
    [
        library(),
        SCENE.into(),
        COLOUR.into(),
        ALBEDO.into(),
        METAL.into(),
        REFLECTS.into(),
        SUMS.into(),
        CONNECT.into(),
        include_str!("shaders/splat.wgsl").into(),
        photon_windows("map", 1, 2, false),
    ]
    .concat()
}

/// The caustic layer (entry `layer_splat`): the scene's params and bands in
/// group 0; in group 1 the pixels' sums (binding 0), the stored count (1),
/// the map (2–5) and the engine's frame (6).
pub fn layer() -> String {
    [
        library(),
        SCENE.into(),
        COLOUR.into(),
        SUMS.into(),
        CONNECT.into(),
        include_str!("shaders/layer.wgsl").into(),
        photon_windows("map", 1, 2, false),
    ]
    .concat()
}

/// An engine's frame from its depth and normal textures (entry
/// `frame_from_textures`): its own parameters, the two textures
/// (`multisampled`: a pixel's samples averaged) and the layer's frame in group 0.
pub fn frame(multisampled: bool) -> String {
    let mut source = include_str!("shaders/frame.wgsl").to_string();
    source = if multisampled {
        source
            .replace("texture_depth_2d", "texture_depth_multisampled_2d")
            .replace("texture_2d<f32>", "texture_multisampled_2d<f32>")
            .replace("SAMPLES", "textureNumSamples(depth_texture)")
    } else {
        source.replace("SAMPLES", "1u")
    };
    [prelude(0), COMMON.into(), source].concat()
}

/// A caustic layer's temporal accumulation (entry `blend_history`).
pub fn history() -> String {
    [prelude(0), COMMON.into(), include_str!("shaders/history.wgsl").into()].concat()
}

/// The gathers' indirect dispatch arguments, per grid level (entry `level_dispatches`).
pub fn level_dispatch() -> String {
    [prelude(0), include_str!("shaders/level_dispatch.wgsl").into()].concat()
}

/// A pass's trace tallies added to the render's statistics (entry `fold_tallies`).
pub fn stats() -> String {
    [library(), include_str!("shaders/stats.wgsl").into()].concat()
}

/// Copies a rendered pixel buffer into a storage texture of `format` (a WGSL texel format).
pub fn to_texture(format: &str) -> String {
    [prelude(0), COMMON.into(), include_str!("shaders/to_texture.wgsl").replace("TEXEL_FORMAT", format)].concat()
}
