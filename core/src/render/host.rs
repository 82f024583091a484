//! The render protocol on the host: [`HostRender`] drives three kernels
//! (view rays, photon trace, gather at the visible points) through the pass
//! schedule and keeps the exact sums. The scalar reference and the CPU's
//! packets are both this driver over their own kernels.

use crate::model::image::Image;
use crate::model::photon::{PhotonMap, TraceStats};
use crate::photons::light_tracing::Splat;
use crate::plan::prepared::PreparedScene;
use crate::plan::schedule::{PilotScale, pass_scene, pass_shrink, pilot_scene};
use crate::render::accumulation::Accumulation;
use crate::render::layer::{LayerFrame, layer_splats};
use crate::render::protocol::{BackendError, Change, Render, RenderStats};
use crate::render::visible::{VisiblePoint, VisiblePoints};
use crate::util::progress::{Progress, StageTimes};
use alloc::vec;
use alloc::vec::Vec;
use glam::Vec3;

/// What one pass's gather found at each visible point.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PassGather {
    /// Caustic irradiance (linear RGB, before the point's weight).
    pub irradiance: Vec<Vec3>,
    /// Photons accepted within the point's radius.
    pub photons: Vec<u32>,
    /// The light-traced photons' contributions (with light tracing).
    pub splats: Vec<Splat>,
    /// What the pass's photon trace did.
    pub stats: TraceStats,
}

/// The stages a host backend implements; [`HostRender`] runs the rest.
/// Each has a scalar twin of the same job in the reference
/// ([`crate::render::reference`]).
pub trait HostKernels: Send {
    /// The backend's name.
    fn name(&self) -> &'static str;

    /// Traces every pixel's view rays (pass `pass`'s paths when
    /// [`crate::model::scene::ViewPaths::per_pass`], the same for every pass otherwise): the
    /// image without caustics and the visible points that need them (in an
    /// order that does not depend on the thread count).
    fn visible_points(&mut self, scene: &PreparedScene, pass: u32, progress: &mut dyn Progress) -> VisiblePoints;

    /// Traces `scene`'s photons (its seed and count) into the caustic map, in canonical order.
    fn trace(&mut self, scene: &PreparedScene, progress: &mut dyn Progress) -> PhotonMap;

    /// One pass: traces `scene`'s photons, gathers them at `points`, each
    /// within its own radius (`radii`, at most the scene's radius), and
    /// with light tracing connects them to the camera
    /// ([`crate::photons::light_tracing::splat_photons`]).
    fn pass(&mut self, scene: &PreparedScene, points: &[VisiblePoint], radii: &[f32]) -> PassGather;

    /// Host time per stage of the last pass, where the kernels measure it.
    fn stage_times(&self) -> Option<StageTimes> {
        None
    }
}

/// A live render on the host: the visible points and first radii of the
/// current scene, and the sums of the passes run since they were traced.
///
/// With per-pass view paths ([`crate::model::scene::ViewPaths::per_pass`]) each pass traces its
/// own view; the visible points kept are pass 0's, which the pilot gathers
/// at, and the first radii are per pixel (stochastic progressive photon
/// mapping's per-pixel radius: the smallest first radius of the pilot's
/// points in the pixel, the scene's radius where it had none).
pub struct HostRender<K> {
    kernels: K,
    scene: PreparedScene,
    /// What the next pass or read-out must redo.
    stale: Change,
    view: VisiblePoints,
    /// Per visible point, or per pixel with sampled view paths.
    radii: Vec<f32>,
    /// Visible points of the last view traced (a pass's own, with sampled view paths).
    last_view_points: usize,
    sums: Accumulation,
    trace: TraceStats,
    /// The engine's frame the caustic is drawn into as a layer, if any.
    layer: Option<LayerFrame>,
}

impl<K: HostKernels> HostRender<K> {
    /// A render of `scene` on `kernels`; nothing is traced yet.
    pub fn new(kernels: K, scene: &PreparedScene) -> Self {
        let r = &scene.scene.render;
        HostRender {
            kernels,
            scene: scene.clone(),
            stale: Change::View,
            view: VisiblePoints { base: Image::new(r.width, r.height), points: Vec::new() },
            radii: Vec::new(),
            last_view_points: 0,
            sums: Accumulation::new(r.width, r.height),
            trace: TraceStats::default(),
            layer: None,
        }
    }

    /// The visible points (traced when stale).
    pub fn visible_points(&mut self, progress: &mut dyn Progress) -> &VisiblePoints {
        self.bring_up_to_date(progress);
        &self.view
    }

    /// Each visible point's first radius, or each pixel's with sampled
    /// view paths (traced when stale).
    pub fn first_radii(&mut self, progress: &mut dyn Progress) -> &[f32] {
        self.bring_up_to_date(progress);
        &self.radii
    }

    /// Redoes what the last update invalidated: the view rays, the pilot.
    fn bring_up_to_date(&mut self, progress: &mut dyn Progress) {
        let stale = core::mem::take(&mut self.stale);
        if stale >= Change::View {
            self.view = match self.layer {
                // A layer has no view rays: the engine's frame is its view.
                Some(_) => {
                    let r = &self.scene.scene.render;
                    VisiblePoints { base: Image::new(r.width, r.height), points: Vec::new() }
                }
                None => self.kernels.visible_points(&self.scene, 0, progress),
            };
            self.last_view_points = self.view.points.len();
        }
        if stale >= Change::Photons {
            self.radii = self.first_radii_now();
        }
    }

    /// The pilot pass: each point's first radius from the photons it finds
    /// within the scene's radius (the scene's radius with fixed radii), or
    /// each pixel's with sampled view paths.
    fn first_radii_now(&mut self) -> Vec<f32> {
        let points = &self.view.points;
        let r0 = self.scene.scene.render.radius;
        let per_point = match pilot_scene(&self.scene) {
            Some(pilot) if !points.is_empty() => {
                let scale = PilotScale::new(&self.scene, &pilot);
                let found = self.kernels.pass(&pilot, points, &vec![r0; points.len()]);
                found.photons.iter().map(|&n| scale.first_radius(r0, n)).collect()
            }
            _ => vec![r0; points.len()],
        };
        if !self.sampled() {
            return per_point;
        }
        let mut per_pixel = vec![r0; self.view.base.pixels.len()];
        for (p, r) in points.iter().zip(per_point) {
            let pixel = &mut per_pixel[p.pixel as usize];
            *pixel = pixel.min(r);
        }
        per_pixel
    }

    /// Whether each pass traces its own view paths (a layer traces none).
    fn sampled(&self) -> bool {
        self.layer.is_none() && self.scene.scene.render.view_paths.per_pass()
    }

    /// A layer's pass: its photons traced and splatted into the engine's frame.
    fn layer_pass(&mut self, pass: u32, progress: &mut dyn Progress) {
        let Some(frame) = &self.layer else { return };
        let scene = pass_scene(&self.scene, pass);
        let map = self.kernels.trace(&scene, progress);
        self.sums.add_pass(pass, &[], &[], &layer_splats(&scene, frame, &map.photons));
        self.trace.merge(&map.stats);
    }

    /// Empties the sums and statistics: the passes start again.
    fn restart_passes(&mut self) {
        let r = &self.scene.scene.render;
        self.sums = Accumulation::new(r.width, r.height);
        self.trace = TraceStats::default();
    }
}

impl<K: HostKernels> Render for HostRender<K> {
    fn backend(&self) -> &'static str {
        self.kernels.name()
    }

    fn scene(&self) -> &PreparedScene {
        &self.scene
    }

    fn update(&mut self, scene: &PreparedScene) -> Result<Change, BackendError> {
        let change = Change::between(&self.scene.scene, &scene.scene);
        self.scene = scene.clone();
        if change >= Change::Photons {
            // The passes start again (the points and radii follow when needed).
            self.restart_passes();
        }
        if change >= Change::Size {
            self.layer = None;
        }
        self.stale = self.stale.max(change);
        Ok(change)
    }

    fn set_layer(&mut self, frame: Option<&LayerFrame>) -> Result<(), BackendError> {
        if let Some(frame) = frame.filter(|f| !f.fits(&self.scene)) {
            return Err(BackendError::frame_size(frame, &self.scene));
        }
        self.layer = frame.cloned();
        self.restart_passes();
        self.stale = self.stale.max(Change::View);
        Ok(())
    }

    fn ready(&mut self, progress: &mut dyn Progress) -> Result<(), BackendError> {
        self.bring_up_to_date(progress);
        Ok(())
    }

    fn run_pass(&mut self, pass: u32, progress: &mut dyn Progress) -> Result<(), BackendError> {
        self.bring_up_to_date(progress);
        if self.sums.contains(pass) {
            return Err(BackendError::PassRepeated(pass));
        }
        if self.layer.is_some() {
            self.layer_pass(pass, progress);
            return Ok(());
        }
        // A pass's own view is lit by the pass's lights (drawn suns, aimed shadows).
        let own_view = (self.sampled() && pass != 0).then(|| {
            let lights = self.scene.lights_of_pass(pass);
            self.kernels.visible_points(lights.as_ref().unwrap_or(&self.scene), pass, progress)
        });
        let view = own_view.as_ref().unwrap_or(&self.view);
        let points = &view.points;
        self.last_view_points = points.len();
        if self.sampled() {
            self.sums.add_view(&view.base);
        }
        if points.is_empty() && !(self.scene.scene.render.light_tracing && self.scene.plan.photon_pass()) {
            self.sums.add_pass(pass, &[], &[], &[]);
            return Ok(());
        }
        let scene = pass_scene(&self.scene, pass);
        let shrink = pass_shrink(&self.scene, pass);
        let r_pass = scene.scene.render.radius;
        // The first radii are per pixel with sampled view paths, per point otherwise.
        let per_pixel = self.sampled();
        let first = |i: usize, p: &VisiblePoint| self.radii[if per_pixel { p.pixel as usize } else { i }];
        let radii: Vec<f32> = points.iter().enumerate().map(|(i, p)| (first(i, p) * shrink).min(r_pass)).collect();
        let found = self.kernels.pass(&scene, points, &radii);
        self.sums.add_pass(pass, points, &found.irradiance, &found.splats);
        self.trace.merge(&found.stats);
        Ok(())
    }

    fn passes(&self) -> &[(u32, u32)] {
        &self.sums.passes
    }

    fn base(&mut self) -> Result<Image, BackendError> {
        let base = self.visible_points(&mut crate::util::progress::NoProgress).base.clone();
        Ok(if self.sampled() { Image::new(base.width, base.height) } else { base })
    }

    fn sums(&mut self) -> Result<Accumulation, BackendError> {
        self.bring_up_to_date(&mut crate::util::progress::NoProgress);
        Ok(self.sums.clone())
    }

    fn photon_map(&mut self, pass: u32, progress: &mut dyn Progress) -> Result<PhotonMap, BackendError> {
        Ok(self.kernels.trace(&pass_scene(&self.scene, pass), progress))
    }

    fn stats(&mut self) -> Result<RenderStats, BackendError> {
        self.bring_up_to_date(&mut crate::util::progress::NoProgress);
        let first_radii = self
            .radii
            .iter()
            .fold(None, |range: Option<(f32, f32)>, &r| Some(range.map_or((r, r), |(lo, hi)| (lo.min(r), hi.max(r)))));
        Ok(RenderStats {
            passes: self.sums.pass_count(),
            trace: self.trace,
            visible_points: self.last_view_points as u64,
            first_radii,
            view_paths_cut: 0,
            uploaded: 0,
            read_back: 0,
        })
    }

    fn stage_times(&self) -> Option<StageTimes> {
        self.kernels.stage_times()
    }
}
