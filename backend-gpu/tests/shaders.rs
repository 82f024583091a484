//! The WGSL of every pipeline parses and validates (naga, as wgpu does),
//! and every struct shared with Rust has the same size and field offsets
//! on both sides.

use naga::valid::{Capabilities, ValidationFlags, Validator};
use prismatic_gpu::layout::{
    GpuBand, GpuLight, GpuObject, GpuSurface, Params, RunStats, ScanParams, SessionParams, Tally, VisiblePoint,
};
use prismatic_gpu::shaders;
use std::mem::{offset_of, size_of};

fn module(name: &str, source: &str) -> naga::Module {
    let module =
        naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
    module
}

fn sources() -> Vec<(&'static str, String)> {
    vec![
        ("trace", shaders::trace()),
        ("compact", shaders::compact()),
        ("scan", shaders::scan()),
        ("grid", shaders::grid()),
        ("view", shaders::view(shaders::stack_size(12))),
        ("view-deepest", shaders::view(shaders::stack_size(prismatic_core::model::scene::MAX_DEPTH))),
        ("session", shaders::session()),
        ("splat", shaders::splat()),
        ("stats", shaders::stats()),
        ("to_texture", shaders::to_texture("rgba16float")),
    ]
}

#[test]
fn every_shader_parses_and_validates() {
    for (name, source) in sources() {
        module(name, &source);
    }
}

/// (size, [(field, offset)]) of struct `name` in `module`.
fn wgsl_layout(module: &naga::Module, name: &str) -> (u32, Vec<(String, u32)>) {
    let (_, ty) =
        module.types.iter().find(|(_, t)| t.name.as_deref() == Some(name)).unwrap_or_else(|| panic!("no {name}"));
    let naga::TypeInner::Struct { members, span } = &ty.inner else { panic!("{name} is not a struct") };
    (*span, members.iter().map(|m| (m.name.clone().unwrap_or_default(), m.offset)).collect())
}

macro_rules! rust_layout {
    ($t:ty { $($field:ident),* $(,)? }) => {
        (size_of::<$t>() as u32, vec![$((stringify!($field).to_string(), offset_of!($t, $field) as u32)),*])
    };
}

#[test]
fn shared_structs_have_the_same_layout_in_rust_and_wgsl() {
    let trace = module("trace", &shaders::trace());
    let scan = module("scan", &shaders::scan());
    let session = module("session", &shaders::session());
    let photon = rust_layout!(prismatic_core::Photon { position, flux, direction_oct, lambda_nm, emission, band });
    let (size, mut fields) = wgsl_layout(&trace, "Photon");
    // WGSL packs the two u16s (band, bounces) into one u32 at the band's offset.
    assert_eq!(fields.pop(), Some(("band_bounces".into(), photon.1[5].1)));
    assert_eq!((size, fields), (photon.0, photon.1[..5].to_vec()), "Photon");
    let cases = [
        (
            "Params",
            &trace,
            rust_layout!(Params {
                seed,
                chunk_start,
                chunk_len,
                slots,
                band_count,
                max_depth,
                wavelengths,
                object_count,
                light_count,
                light_cdf,
                estimator,
                window,
                width,
                height,
                pixel_offset,
                pixel_count,
                stored,
                grid_mask,
                capacity,
                point_capacity,
                gather_first,
                gather_span,
                sum_shift,
                flux_shift,
                flux,
                radius,
                inv_cell,
                exposure,
                ambient,
                light_tracing,
                background,
                splat_scale,
                cam_origin,
                photon_sequence,
                cam_right,
                view_seed,
                cam_down,
                view_pass,
                cam_corner,
                view_paths,
                cam_forward,
                colour_by_wavelength,
                white_balance,
                env_strength,
                env_first,
                env_width,
                env_height,
                env_turn,
                caustic_photons,
                indirect_flux,
                rough_records,
                rough_gathers,
            }),
        ),
        ("GpuObject", &trace, rust_layout!(GpuObject { kind, first, count, second, a, ra, n, rb })),
        (
            "GpuSurface",
            &trace,
            rust_layout!(GpuSurface {
                kind,
                flags,
                ior_first,
                curve_first,
                albedo,
                white_ior,
                checker_albedo,
                checker_size,
                checker_offset,
                curve_len,
                absorption,
                absorption_first,
                texture_first,
                texture_width,
                texture_height,
                uv_first,
                emission,
                film_first,
            }),
        ),
        (
            "GpuLight",
            &trace,
            rust_layout!(GpuLight {
                kind,
                shadows,
                proj_kind,
                proj_count,
                position,
                power,
                axis,
                cos_max,
                tangent,
                radius,
                bitangent,
                proj_scale,
                proj_first,
                proj_cdf,
                sun,
                spectrum_len,
                reflected_r,
                spectrum_first,
                reflected_g,
                cos_inner,
                reflected_b,
                aimed,
                aim,
                _pad1,
                mean_toward,
                range,
            }),
        ),
        ("GpuBand", &trace, rust_layout!(GpuBand { weight, lambda_nm, lo_nm, hi_nm, max_weight, _pad })),
        ("Tally", &trace, rust_layout!(Tally { counts, _pad0, flux, _pad1 })),
        (
            "SessionParams",
            &session,
            rust_layout!(SessionParams {
                pilot_scale,
                neighbours,
                inv_passes,
                whole_radius,
                level,
                built_levels,
                sampled_view,
                _pad1
            }),
        ),
        ("ScanParams", &scan, rust_layout!(ScanParams { n, _pad0, _pad1, _pad2 })),
        (
            "VisiblePoint",
            &session,
            rust_layout!(VisiblePoint {
                position,
                total,
                normal,
                radius,
                weight,
                found,
                sums,
                flux,
                pixel,
                ratio,
                level,
                widest,
                albedo,
                rough,
                toward,
                triangle
            }),
        ),
        ("RunStats", &session, rust_layout!(RunStats { counts, flux, min_ratio, max_ratio })),
    ];
    for (name, module, rust) in cases {
        assert_eq!(wgsl_layout(module, name), rust, "{name}: WGSL (size, offsets) vs Rust");
    }
}
