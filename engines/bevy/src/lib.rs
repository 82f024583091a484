//! prismatic-bevy: live dispersion caustics in a Bevy app, rendered by a
//! [`prismatic_gpu::GpuSession`] on Bevy's own `RenderDevice` and
//! `RenderQueue` (Bevy 0.20 and prismatic share wgpu 30: no second device,
//! no copy through the CPU).
//!
//! The scene is ordinary entities: a [`CausticCamera`], [`CausticLight`]s,
//! and objects with a [`CausticShape`] that are [`Glass`] or a
//! [`Receiver`], all placed by their `Transform`s. Each frame the plugin
//! mirrors them into a prismatic scene; when it differs from the last one,
//! the session is updated (and redoes only what the change invalidates,
//! see [`prismatic_core::Change`]), then one progressive pass runs and the
//! image is copied on the device into [`CausticImage`], a linear
//! `Rgba32Float` Bevy image the app shows as it likes (a sprite, a UI
//! node, a material's texture).
//!
//! Two ways to show it:
//! - **a caustic layer** in Bevy's own frame (a camera with
//!   [`CausticLayer`]): the caustic falls on Bevy's own surfaces, under its
//!   lighting, shadows, fog and tone mapping. The surfaces that receive it
//!   use [`CausticMaterial`]; glass is a [`Glass`] entity with a `Mesh3d`
//!   (the same mesh Bevy draws). The session draws the caustic irradiance
//!   in the camera's frame between Bevy's prepass and main pass
//!   (`layer`): light tracing and hero wavelengths, no view rays.
//! - **the whole image** (a [`CausticCamera`], no [`CausticLayer`]):
//!   prismatic's own picture in [`CausticImage`], the refraction through
//!   the glass included, for tools that show it as it is.

mod images;
mod layer;
mod mirror;
mod standard;

pub use layer::{CausticLayer, CausticLayerView, CausticMaterial, CausticReceiver};
pub use mirror::{CausticCamera, CausticLight, CausticShape, Glass, Receiver};
pub use prismatic_core;
pub use prismatic_core::StageTimes;

use bevy::asset::RenderAssetUsages;
use bevy::core_pipeline::{Core3d, Core3dSystems};
use bevy::image::Image;
use bevy::pbr::MaterialPlugin;
use bevy::prelude::*;
use bevy::render::extract_resource::{ExtractResource, ExtractResourcePlugin};
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat, TextureUsages};
use bevy::render::renderer::{RenderDevice, RenderQueue};
use bevy::render::texture::GpuImage;
use bevy::render::{Render, RenderApp, RenderSystems};
use prismatic_core::model::scene::RenderSettings;
use prismatic_core::{NoProgress, PreparedScene, Render as _};
use prismatic_gpu::{GpuContext, GpuOptions, GpuSession};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Adds live caustics: mirrors the scene's entities, runs a session pass a
/// frame in the render world (in the [`CausticLayer`] camera's frame, or the
/// whole image), fills [`CausticImage`] and [`CausticStats`].
#[derive(Default)]
pub struct PrismaticPlugin;

impl Plugin for PrismaticPlugin {
    fn build(&self, app: &mut App) {
        layer::embed_shader(app);
        app.init_resource::<CausticSettings>()
            .init_resource::<CausticStats>()
            .add_plugins((
                MaterialPlugin::<CausticMaterial>::default(),
                ExtractResourcePlugin::<CausticScene>::default(),
                ExtractResourcePlugin::<CausticImage>::default(),
                ExtractResourcePlugin::<CausticStats>::default(),
                ExtractResourcePlugin::<CausticLayerView>::default(),
            ))
            .add_systems(
                PostUpdate,
                (mirror::mirror_scene, size_image, layer::attach_layer).chain().after(TransformSystems::Propagate),
            );
        app.sub_app_mut(RenderApp)
            .init_resource::<LiveSession>()
            .add_systems(Render, render_caustics.in_set(RenderSystems::Prepare))
            .add_systems(Core3d, layer::draw_layer.after(Core3dSystems::Prepass).before(Core3dSystems::MainPass));
    }
}

/// How the caustics are rendered: the image size (a [`CausticLayer`]
/// camera's target size replaces it), photons per frame (one pass), bands,
/// wavelengths, estimator, radius and the rest of prismatic's `[render]`
/// settings. Changing it restarts the accumulation.
#[derive(Resource, Clone, Debug, PartialEq)]
pub struct CausticSettings(pub RenderSettings);

impl Default for CausticSettings {
    /// 960×540, 100k white photons a frame, the default render's light
    /// transport (light tracing, hero wavelengths and view paths, which win
    /// at equal error), radius 0.03.
    fn default() -> Self {
        CausticSettings(RenderSettings {
            width: 960,
            height: 540,
            photons: 100_000,
            radius: 0.03,
            ambient: 0.06,
            exposure: 1.6,
            ..RenderSettings::default()
        })
    }
}

/// The image the caustics are rendered into (linear `Rgba32Float`, the
/// settings' size; the plugin makes it and makes it again on a resize).
#[derive(Resource, Clone, Debug, ExtractResource)]
#[extract_app(RenderApp)]
pub struct CausticImage(pub Handle<Image>);

/// The scene the entities make, with a generation that grows when it changes.
#[derive(Resource, Clone, ExtractResource)]
#[extract_app(RenderApp)]
pub struct CausticScene {
    /// The prepared scene.
    pub scene: Arc<PreparedScene>,
    /// Bumped on every change.
    pub generation: u64,
}

/// What the render world reports back: passes, photons, timings, errors.
#[derive(Resource, Clone, Default, ExtractResource)]
#[extract_app(RenderApp)]
pub struct CausticStats(pub Arc<Mutex<Stats>>);

/// One frame's figures.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    /// Passes in the image now.
    pub passes: u32,
    /// White photons a frame's pass emits.
    pub photons: u64,
    /// Seconds between the last two frames' passes (the app's frame time).
    pub frame_seconds: f64,
    /// Seconds the last frame's submit took on the host.
    pub submit_seconds: f64,
    /// The GPU time of each stage of a recent frame (timestamps come back
    /// a frame or two late), where the device has timestamp queries (Bevy's
    /// default device settings ask for every feature the adapter has).
    pub gpu: Option<StageTimes>,
    /// Scene generation the image shows.
    pub generation: u64,
    /// Why the scene or the session failed, if it did (the last good
    /// image stays on screen).
    pub error: Option<String>,
    /// What the scene leaves out of the app's materials, one line each
    /// (a texture the plugin cannot read, a metallic surface's base colour
    /// texture, a metalness between 0 and 1): drawn without it.
    pub left_out: Vec<String>,
}

impl CausticStats {
    /// A copy of the latest figures.
    pub fn get(&self) -> Stats {
        self.0.lock().map(|s| s.clone()).unwrap_or_default()
    }

    fn set(&self, edit: impl FnOnce(&mut Stats)) {
        if let Ok(mut s) = self.0.lock() {
            edit(&mut s);
        }
    }
}

/// Makes [`CausticImage`] (again) when there is none or the scene's image
/// size changed.
fn size_image(
    mut commands: Commands,
    settings: Res<CausticSettings>,
    scene: Option<Res<CausticScene>>,
    image: Option<Res<CausticImage>>,
    mut images: ResMut<Assets<Image>>,
) {
    let r = scene.as_ref().map_or(&settings.0, |s| &s.scene.scene.render);
    let (w, h) = (r.width.max(1), r.height.max(1));
    if let Some(image) = &image
        && images.get(&image.0).is_some_and(|i| (i.width(), i.height()) == (w, h))
    {
        return;
    }
    let mut target = Image::new_uninit(
        Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        TextureDimension::D2,
        TextureFormat::Rgba32Float,
        RenderAssetUsages::RENDER_WORLD,
    );
    target.texture_descriptor.usage =
        TextureUsages::STORAGE_BINDING | TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_SRC;
    commands.insert_resource(CausticImage(images.add(target)));
}

/// The render world's session, made on the first frame that has a scene.
#[derive(Resource, Default)]
struct LiveSession {
    session: Option<GpuSession>,
    generation: u64,
    last_pass: Option<Instant>,
    /// The generation the session failed on: not tried again until the scene changes.
    failed: Option<u64>,
    /// Frames a caustic layer has drawn (each its own pass).
    frames: u32,
}

impl LiveSession {
    /// One frame of `scene` into `target` (the [`CausticImage`]'s texture,
    /// of the scene's image size: a resized one arrives a frame later):
    /// the session made when there is none or updated when the scene
    /// changed, then `work` with whether it changed. Figures and errors go
    /// to `stats`, never a panic; a failed session is dropped and not tried
    /// again until the scene changes.
    fn frame(
        &mut self,
        scene: &CausticScene,
        stats: &CausticStats,
        device: &RenderDevice,
        queue: &RenderQueue,
        target: &bevy::render::render_resource::Texture,
        work: impl FnOnce(&mut GpuSession, bool) -> Result<(), prismatic_core::BackendError>,
    ) {
        let r = &scene.scene.scene.render;
        if (target.width(), target.height()) != (r.width, r.height) || self.failed == Some(scene.generation) {
            return;
        }
        let start = Instant::now();
        let result = (|| {
            let changed = match &mut self.session {
                Some(session) if self.generation != scene.generation => {
                    session.update(&scene.scene)?;
                    true
                }
                Some(_) => false,
                None => {
                    let ctx = GpuContext::from_device(device.wgpu_device().clone(), (**queue).clone())?;
                    let options = GpuOptions { stage_times: true, ..GpuOptions::default() };
                    self.session = Some(GpuSession::new(ctx, &scene.scene, options)?);
                    true
                }
            };
            self.generation = scene.generation;
            let session = self.session.as_mut().expect("made above");
            work(session, changed)?;
            let passes = session.passes().iter().map(|(a, b)| b - a).sum();
            Ok::<_, prismatic_core::BackendError>((passes, session.stage_times()))
        })();
        let now = Instant::now();
        let interval = self.last_pass.map_or(0.0, |t| (now - t).as_secs_f64());
        self.last_pass = Some(now);
        match result {
            Ok((passes, gpu)) => stats.set(|s| {
                *s = Stats {
                    passes,
                    photons: u64::from(r.photons),
                    frame_seconds: interval,
                    submit_seconds: start.elapsed().as_secs_f64(),
                    gpu,
                    generation: scene.generation,
                    error: None,
                    // The mirror's, set when the scene is built.
                    left_out: std::mem::take(&mut s.left_out),
                }
            }),
            Err(e) => {
                (self.session, self.failed) = (None, Some(scene.generation));
                stats.set(|s| s.error = Some(e.to_string()));
            }
        }
    }
}

/// The whole image (no [`CausticLayer`] camera): one progressive pass into
/// the image (after updating the session when the scene changed), before
/// Bevy's cameras draw.
#[allow(clippy::too_many_arguments)]
fn render_caustics(
    mut live: ResMut<LiveSession>,
    scene: Option<Res<CausticScene>>,
    image: Option<Res<CausticImage>>,
    layer: Option<Res<CausticLayerView>>,
    stats: Res<CausticStats>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    images: Res<RenderAssets<GpuImage>>,
) {
    let (Some(scene), Some(image), None) = (scene, image, layer) else { return };
    let Some(target) = images.get(&image.0) else { return };
    live.frame(&scene, &stats, &device, &queue, &target.texture, |session, _| {
        session.next_pass(&mut NoProgress)?;
        session.copy_to_texture(&target.texture)
    });
}
