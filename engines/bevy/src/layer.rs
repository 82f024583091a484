//! The caustic layer in Bevy's own frame: a [`CausticLayer`] camera's depth
//! and normal prepass are the frame prismatic's session draws the caustic
//! irradiance into, between Bevy's prepass and its main pass, and
//! [`CausticMaterial`] (a `StandardMaterial` with the [`CausticReceiver`]
//! extension) adds it to Bevy's own lighting on the surfaces that receive it.
//!
//! Why a material extension and not a lighting pass of our own: the
//! caustic is light, reflected by each surface's own diffuse colour, and
//! must pass through Bevy's exposure, fog and tone mapping like the rest of
//! its lighting; the extension adds it inside `StandardMaterial`'s shading
//! (irradiance × base colour × (1 − metallic) / π, before the tone map),
//! where a pass after the main pass would have to undo the tone map.

use crate::{CausticImage, CausticScene, CausticStats, LiveSession};
use bevy::asset::{AssetPath, embedded_asset, embedded_path};
use bevy::core_pipeline::prepass::{DepthPrepass, NormalPrepass, ViewPrepassTextures};
use bevy::pbr::{ExtendedMaterial, MaterialExtension, StandardMaterial};
use bevy::prelude::*;
use bevy::render::RenderApp;
use bevy::render::extract_resource::ExtractResource;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::AsBindGroup;
use bevy::render::renderer::{RenderContext, RenderDevice, RenderQueue, ViewQuery};
use bevy::render::sync_world::MainEntity;
use bevy::render::texture::GpuImage;
use bevy::shader::ShaderRef;
use prismatic_gpu::{DepthEncoding, FrameTextures, NormalEncoding};

/// Draws prismatic's caustic as a layer in this `Camera3d`'s frame (its
/// depth and normal prepass, which it requires; with MSAA, a pixel's
/// samples averaged): the camera is the scene's camera, its target's size
/// the layer's, and the [`CausticImage`] holds the caustic irradiance at its
/// pixels for the [`CausticMaterial`] surfaces to reflect. One camera at a
/// time. Each frame is one pass of photons, folded into each pixel's
/// running mean since its surface last changed (see
/// `prismatic_gpu::GpuSession::layer_frame`).
#[derive(Component, Clone, Copy, Debug)]
#[require(DepthPrepass, NormalPrepass)]
pub struct CausticLayer {
    /// Frames a still caustic's mean spans at most (then an exponential
    /// window of as many frames).
    pub history: u32,
    /// Frames it spans in a frame where the lights, glass or camera moved:
    /// fewer follow the caustic sooner, more average more noise away.
    pub moving_history: u32,
    /// Lux per W/m² of prismatic's irradiance: its lights' powers are
    /// watts of their spectra, Bevy's lighting is photometric (lux, then
    /// its camera's exposure).
    pub lux_per_watt: f32,
}

impl Default for CausticLayer {
    /// 256 frames while still, 4 while moving, and the luminous efficacy
    /// of equal-energy white light over 380–780 nm (683 lm/W × ∫ȳ dλ / 400
    /// nm, about 183 lm/W), prismatic's default light spectrum.
    fn default() -> Self {
        CausticLayer { history: 256, moving_history: 4, lux_per_watt: equal_energy_efficacy() }
    }
}

/// Lumens per watt of equal-energy white light over the visible range.
pub fn equal_energy_efficacy() -> f32 {
    let (lo, hi) = prismatic_core::model::cie::VISIBLE_NM;
    let y = prismatic_core::model::cie::integrate(f64::from(lo), f64::from(hi)).y;
    (683.0 * y / f64::from(hi - lo)) as f32
}

/// The `StandardMaterial` extension of surfaces that receive the caustic
/// layer: its `irradiance` is the [`CausticImage`] (the plugin sets it on
/// every [`CausticMaterial`] that lacks it). The surfaces must also be in
/// prismatic's scene for photons to land on them: a [`CausticMaterial`]
/// entity with a `Mesh3d` is mirrored as a diffuse receiver of its base
/// colour (a metal of that colour where most of it is metallic, which
/// reflects photons on instead), with its maps (`standard`).
#[derive(Asset, AsBindGroup, TypePath, Clone, Debug, Default)]
pub struct CausticReceiver {
    /// The caustic irradiance in the layer camera's frame.
    #[texture(100, sample_type = "float", filterable = false)]
    pub irradiance: Option<Handle<Image>>,
}

impl MaterialExtension for CausticReceiver {
    fn fragment_shader() -> ShaderRef {
        ShaderRef::Path(
            AssetPath::from_path_buf(embedded_path!("shaders/caustic_receiver.wesl")).with_source("embedded"),
        )
    }
}

/// A `StandardMaterial` that adds the caustic layer to Bevy's lighting.
pub type CausticMaterial = ExtendedMaterial<StandardMaterial, CausticReceiver>;

/// Embeds the receiver's shader.
pub(crate) fn embed_shader(app: &mut App) {
    embedded_asset!(app, "shaders/caustic_receiver.wesl");
}

/// Which view draws the layer, for the render world: the main world's
/// camera entity, its perspective's near plane (Bevy's depth is reversed Z
/// with an infinite far plane) and its [`CausticLayer`]'s history lengths.
#[derive(Resource, Clone, Copy, Debug, PartialEq, ExtractResource)]
#[extract_app(RenderApp)]
pub struct CausticLayerView {
    /// The [`CausticLayer`] camera.
    pub camera: Entity,
    /// Its near plane's distance.
    pub near: f32,
    /// [`CausticLayer::history`].
    pub history: u32,
    /// [`CausticLayer::moving_history`].
    pub moving_history: u32,
    /// [`CausticLayer::lux_per_watt`].
    pub lux_per_watt: f32,
}

/// Points every [`CausticMaterial`] that lacks it at the [`CausticImage`].
pub(crate) fn attach_layer(image: Option<Res<CausticImage>>, mut materials: ResMut<Assets<CausticMaterial>>) {
    let Some(image) = image else { return };
    let stale: Vec<AssetId<CausticMaterial>> =
        materials.iter().filter(|(_, m)| m.extension.irradiance.as_ref() != Some(&image.0)).map(|(id, _)| id).collect();
    for id in stale {
        if let Some(mut m) = materials.get_mut(id) {
            m.extension.irradiance = Some(image.0.clone());
        }
    }
}

/// Between Bevy's prepass and main pass of the [`CausticLayer`] camera:
/// the session reads the frame from the prepass, runs the frame's pass,
/// folds it into the history and writes the irradiance into the
/// [`CausticImage`], all recorded into Bevy's command buffers of the frame,
/// in order.
#[allow(clippy::too_many_arguments)]
pub(crate) fn draw_layer(
    view: ViewQuery<(&MainEntity, &ViewPrepassTextures)>,
    layer: Option<Res<CausticLayerView>>,
    mut live: ResMut<LiveSession>,
    scene: Option<Res<CausticScene>>,
    image: Option<Res<CausticImage>>,
    images: Res<RenderAssets<GpuImage>>,
    stats: Res<CausticStats>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    mut ctx: RenderContext,
) {
    let (main, prepass) = view.into_inner();
    let (Some(layer), Some(scene), Some(image)) = (layer, scene, image) else { return };
    if main.id() != layer.camera {
        return;
    }
    let Some(target) = images.get(&image.0) else { return };
    let (Some(depth), Some(normal)) = (prepass.depth_only_view(), prepass.normal_view()) else {
        return stats.set(|s| s.error = Some("the CausticLayer camera has no depth or normal prepass".into()));
    };
    let textures = FrameTextures {
        depth,
        depth_encoding: DepthEncoding::ReverseInfinite { near: layer.near },
        normal,
        normal_encoding: NormalEncoding::Unorm,
    };
    let frame = live.frames;
    live.frames = live.frames.wrapping_add(1);
    live.frame(&scene, &stats, &device, &queue, &target.texture, |session, changed| {
        let cap = if changed { layer.moving_history } else { layer.history };
        let (done, buffers) = session.record(|s| {
            s.layer_frame(&textures, frame, cap)?;
            s.copy_to_texture(&target.texture)
        });
        for buffer in buffers {
            ctx.add_command_buffer(buffer);
        }
        done
    });
}
