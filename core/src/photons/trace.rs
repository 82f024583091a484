//! The scalar reference photon tracer: the specification every backend's
//! photon pass is compared with.
//!
//! White photons leave the lights (a sun's from its beam, see
//! [`PreparedScene::emitters`]); at the first dispersive or coloured
//! dielectric a white photon splits into one photon per band (each with 1/N
//! of the flux) and each band continues with its own index of refraction
//! and absorption; clear non-dispersive glass and mirrors never split. With
//! hero sampling it splits into M hero wavelengths instead (see
//! [`split_bands`]); with random-band or continuous sampling it does not
//! split but continues as one random band with all its flux (see
//! [`sample_band`]; the wavelengths in [`crate::photons::wavelengths`]). A
//! photon that reaches a diffuse surface after at least one specular
//! interaction is stored (the dispersion caustic map, L S+ D paths); one
//! that reaches it directly is direct light, which the renderer ray traces
//! instead (on a blended metal, the photon is stored as on a diffuse
//! surface and the path goes on as the metal with the probability of its
//! metalness, [`crate::optics::metal`]; so there the stored and direct
//! flux are not part of the energy balance). When the render light traces, a
//! hidden light's path past its first specular interaction is also recorded
//! on every rough metal or glass it meets, and goes on
//! ([`crate::model::photon::ON_ROUGH_SURFACE`]).
//! Inside coloured glass a path survives each segment with its
//! band's Beer–Lambert transmittance (see [`crate::photons::path::absorbed`],
//! a path's steps). A coloured light's photons (a spectrum other than equal
//! energy) are never white: they start as their bands or wavelengths at the
//! light (see [`emission_paths`]). Fresnel chooses
//! reflection or refraction with a counter-based random number, so the
//! result is a pure function of the scene and the seed. A pass's indirect
//! photons follow its caustic ones ([`crate::photons::indirect`]).

use crate::geometry::primitive::Ray;
use crate::model::photon::{ON_ROUGH_SURFACE, Photon, PhotonMap, TraceStats, WHITE_BAND};
use crate::optics::surface::Surface;
use crate::photons::emit::emit;
use crate::photons::indirect;
use crate::photons::path::{Crossing, Path, arrives_at_specular, cross_specular, goes_on_as_metal};
use crate::photons::wavelengths::{emission_paths, sample_band, split_bands};
use crate::plan::prepared::{Hit, PreparedScene};
use crate::util::progress::{Progress, Stage};
use alloc::vec::Vec;

/// Traces every white photon of the scene's render settings, reporting
/// progress about a hundred times.
pub fn trace_photons(scene: &PreparedScene, progress: &mut dyn Progress) -> PhotonMap {
    let total = scene.traced_photons();
    let chunk = (total / 100).max(1024);
    let mut map = PhotonMap::default();
    let mut start = 0;
    while start < total {
        let end = start.saturating_add(chunk).min(total);
        trace_range(scene, start..end, &mut map.photons, &mut map.stats);
        progress.advance(Stage::Photons, u64::from(end), u64::from(total));
        start = end;
    }
    // Path order: a white photon met on a blended metal before its bands.
    map.sort_canonical();
    map
}

/// Flux of one emitted white photon.
pub fn photon_flux(scene: &PreparedScene) -> f32 {
    match scene.scene.render.photons {
        0 => 0.0,
        n => scene.total_power / n as f32,
    }
}

/// Traces photons `range` (emission indices: caustic, then indirect),
/// appending stored photons in canonical order. Backends use it for chunks
/// and scalar tails.
pub fn trace_range(scene: &PreparedScene, range: core::ops::Range<u32>, out: &mut Vec<Photon>, stats: &mut TraceStats) {
    let (flux, caustic) = (photon_flux(scene), scene.caustic_photons());
    for index in range {
        if index < caustic {
            trace_emitted(scene, index, flux, out, stats);
        } else {
            indirect::trace_indirect(scene, index, out, stats);
        }
    }
}

/// Traces white photon `index` and all the band photons it splits into.
pub fn trace_emitted(scene: &PreparedScene, index: u32, flux: f32, out: &mut Vec<Photon>, stats: &mut TraceStats) {
    let e = emit(scene, scene.scene.render.seed, index);
    stats.emitted += 1;
    let flux = flux * e.weight;
    if e.weight == 0.0 {
        return; // a projection-map sample outside its light: nothing to trace
    }
    stats.paths += 1;
    stats.flux_emitted += f64::from(flux);
    let source = Source {
        range: scene.emitters[e.light].range(),
        recorded_on_rough: scene.plan.rough_records && scene.lights[e.light].is_hidden(),
    };
    if !scene.light_spectra[e.light].is_uniform() {
        // A coloured light's photon takes its wavelengths as it leaves.
        let paths = emission_paths(scene, e.light, index);
        stats.paths += paths.len() as u64 - 1;
        for (band, lambda_nm, share) in paths {
            let ray = Ray { origin: e.origin, direction: e.direction };
            let path = Path { ray, flux: flux * share, band, lambda_nm, bounces: 0 };
            trace_path(scene, index, path, source, out, stats);
        }
        return;
    }
    let path = Path {
        ray: Ray { origin: e.origin, direction: e.direction },
        flux,
        band: WHITE_BAND,
        lambda_nm: None,
        bounces: 0,
    };
    trace_path(scene, index, path, source, out, stats);
}

/// What a photon's paths keep of the light they left.
#[derive(Clone, Copy, Debug)]
struct Source {
    /// The light's range, which windows a path's first segment.
    range: Option<f32>,
    /// A hidden light's caustic photon when the render light traces: met
    /// on rough surfaces, it is recorded there ([`record_on_rough`]; the
    /// view's rays meet the other lights' light behind a rough surface
    /// themselves).
    recorded_on_rough: bool,
}

/// Records path `p` of white photon `index` (of a light whose photons are
/// [`Source::recorded_on_rough`]) where it meets a rough metal or glass
/// (or a blended metal's rough specular part) at `hit` after at least one
/// specular interaction, for light tracing: a photon marked
/// [`ON_ROUGH_SURFACE`], counted as stored but not its flux (the path goes
/// on). Where a white photon splits, each of its paths is recorded.
fn record_on_rough(
    scene: &PreparedScene,
    index: u32,
    p: &Path,
    hit: &Hit,
    out: &mut Vec<Photon>,
    stats: &mut TraceStats,
) {
    if p.bounces > 0 && scene.facets(hit).is_some() {
        stats.stored += 1;
        let photon = p.photon(scene, hit.point, index);
        out.push(Photon { bounces: photon.bounces | ON_ROUGH_SURFACE, ..photon });
    }
}

/// Follows path `p` of white photon `index` from its light `source` and
/// the band paths it splits into.
fn trace_path(
    scene: &PreparedScene,
    index: u32,
    mut p: Path,
    source: Source,
    out: &mut Vec<Photon>,
    stats: &mut TraceStats,
) {
    let settings = &scene.scene.render;
    let recorded = |surface: &Surface| source.recorded_on_rough && !surface.stores_photons();
    loop {
        stats.segments += 1;
        let Some(hit) = scene.intersect(&p.ray, f32::INFINITY) else {
            stats.flux_escaped += f64::from(p.flux);
            return;
        };
        if !p.reach(source.range, hit.t, stats) {
            return;
        }
        let surface = &scene.surfaces[hit.object];
        if surface.stores_photons() {
            if p.bounces == 0 {
                stats.flux_direct += f64::from(p.flux);
            } else {
                stats.count_stored(p.flux);
                out.push(p.photon(scene, hit.point, index));
                if source.recorded_on_rough {
                    // What a blended metal's specular part reflects of it.
                    record_on_rough(scene, index, &p, &hit, out, stats);
                }
            }
            // A blended metal's metal part goes on with its metalness's probability.
            if matches!(surface, Surface::Diffuse { .. }) || !goes_on_as_metal(scene, index, &p, &hit) {
                return;
            }
        }
        if !arrives_at_specular(scene, index, &p, &hit, stats) {
            return;
        }
        if p.bounces == 0 {
            stats.specular_paths += 1;
        }
        // (A band path never splits: only white light looks up a textured metal's colour here.)
        let splits = p.band == WHITE_BAND
            && match surface {
                Surface::Dielectric(glass) => glass.splits_photons,
                Surface::Metal(metal) => scene.metal_is_chromatic_at(metal, &hit),
                _ => false,
            };
        if splits {
            // The bands leave here differently (dispersive, coloured or
            // coated glass, a coloured metal): the white photon splits
            // into its bands or hero wavelengths, or goes on as one band.
            let paths = settings.wavelengths.paths(scene.bands.len());
            if paths == 1 {
                (p.band, p.lambda_nm) = sample_band(scene, index);
            } else {
                stats.paths += u64::from(paths) - 1;
                for (band, lambda_nm) in split_bands(scene, index) {
                    let mut child = Path { band, lambda_nm, flux: p.flux / paths as f32, ..p };
                    if recorded(surface) {
                        record_on_rough(scene, index, &child, &hit, out, stats);
                    }
                    if cross_specular(scene, index, &mut child, &hit, stats) == Crossing::On {
                        child.bounces += 1;
                        trace_path(scene, index, child, source, out, stats);
                    }
                }
                return;
            }
        }
        if recorded(surface) {
            record_on_rough(scene, index, &p, &hit, out, stats);
        }
        // A path a layer passes to its base was stored there already.
        if cross_specular(scene, index, &mut p, &hit, stats) != Crossing::On {
            return;
        }
        p.bounces += 1;
    }
}
