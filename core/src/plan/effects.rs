//! The effect plan: which passes a scene needs, decided once from the
//! validated scene, with a reason for each decision. Backends follow it;
//! none of them decides on its own.
//!
//! Reachability is judged with bounding spheres, conservatively: an effect
//! is only skipped when it provably cannot contribute.

use crate::model::scene::{Light, Scene, WavelengthSampling};
use crate::optics::microfacet::GATHER_ALPHA;
use crate::optics::surface::Surface;
use crate::plan::projection::Projection;
use crate::plan::reach::{bounds, camera_sees, light_reaches};
use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;
use glam::Vec3;

/// One decision: is the effect simulated, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Effect {
    /// Simulated or skipped.
    pub on: bool,
    /// Why, in a few words.
    pub reason: String,
}

impl Effect {
    fn on(reason: impl Into<String>) -> Self {
        Effect { on: true, reason: reason.into() }
    }
    fn off(reason: impl Into<String>) -> Self {
        Effect { on: false, reason: reason.into() }
    }
}

/// What a render of a scene simulates.
#[derive(Clone, Debug, PartialEq)]
pub struct EffectPlan {
    /// The caustic photon pass.
    pub caustics: Effect,
    /// Indirect light: photons that bounce off diffuse surfaces
    /// ([`crate::photons::indirect`]).
    pub indirect: Effect,
    /// Splitting white photons into bands at dispersive, coloured or coated glass.
    pub band_splitting: Effect,
    /// Splitting view rays into bands at dispersive or coated glass.
    pub view_dispersion: Effect,
    /// Shadow rays, per light.
    pub shadows: Vec<Effect>,
    /// Projection maps (emission aimed at mirrors and glass); see [`crate::plan::projection`].
    pub projection: Effect,
    /// Each light's projection map (`None`: emit over its whole distribution).
    pub projections: Vec<Option<Projection>>,
    /// The largest useful number of specular interactions on a path.
    pub max_depth: u32,
    /// Why that depth.
    pub depth_reason: String,
    /// Whether caustic photons are recorded where they meet rough metal or
    /// glass ([`records_on_rough`]).
    pub rough_records: bool,
    /// Whether visible points on rough-enough metal and glass gather those
    /// photons: caustics are traced and recorded, and a surface is rough
    /// enough ([`crate::optics::microfacet::Ggx::gathers`]).
    pub rough_gathers: bool,
}

impl EffectPlan {
    /// Decides the plan for `scene`, whose objects have `surfaces` and whose
    /// lights emit photons as `emitters` (a sun as its beam).
    pub fn new(scene: &Scene, emitters: &[Light], surfaces: &[Surface]) -> Self {
        let bounds: Vec<(Vec3, f32)> = scene.objects.iter().map(|o| bounds(&o.shape)).collect();
        let specular: Vec<usize> = (0..surfaces.len()).filter(|&k| surfaces[k].focuses_light()).collect();
        let dispersive = |k: usize| matches!(&surfaces[k], Surface::Dielectric(g) if g.is_dispersive());
        let chromatic = |k: usize| match &surfaces[k] {
            Surface::Dielectric(g) => g.is_chromatic(),
            Surface::Metal(m) => m.is_chromatic(),
            _ => false,
        };
        let coated = |k: usize| matches!(&surfaces[k], Surface::Dielectric(g) if g.film.is_some());
        let lit: Vec<usize> = specular
            .iter()
            .copied()
            .filter(|&k| emitters.iter().any(|l| light_reaches(l, bounds[k].0, bounds[k].1)))
            .collect();
        let has_diffuse = surfaces.iter().any(Surface::stores_photons);
        // Light tracing and rough visible points take caustic photons on rough surfaces too.
        let rough_records = records_on_rough(scene, surfaces);
        let receives = |s: &Surface| s.stores_photons() || (rough_records && s.facets().is_some());
        let n_bands = crate::model::bands::BandTable::new(scene.render.bands).len();

        let caustics = if specular.is_empty() {
            Effect::off("no mirror or glass in the scene")
        } else if lit.is_empty() {
            Effect::off(format!(
                "no light reaches a mirror or glass ({} outside every light's cone, beam or range)",
                name_list(&specular)
            ))
        } else if !surfaces.iter().any(receives) {
            Effect::off("no diffuse surface (nor a rough one, gathered or light traced) to receive caustics")
        } else if scene.render.photons == 0 {
            Effect::off("0 photons requested")
        } else {
            let kind = if specular.iter().any(|&k| dispersive(k)) { "dispersive" } else { "white" };
            Effect::on(format!(
                "{kind}, {n_bands} band{}, {} of {} specular object{} lit",
                plural(n_bands),
                lit.len(),
                specular.len(),
                plural(specular.len())
            ))
        };
        // Light that reaches one mirror or glass may go on to any other, so
        // every dispersive glass counts once any specular object is lit.
        let band_splitting = if !caustics.on {
            Effect::off("no photon pass")
        } else if specular.iter().any(|&k| chromatic(k)) {
            let glass = if specular.iter().any(|&k| dispersive(k)) {
                "dispersive glass"
            } else if specular.iter().any(|&k| coated(k)) {
                "coated glass"
            } else if specular.iter().any(|&k| matches!(&surfaces[k], Surface::Dielectric(g) if g.is_chromatic())) {
                "coloured glass"
            } else {
                "coloured metal"
            };
            match scene.render.wavelengths {
                WavelengthSampling::Split => Effect::on(format!("{n_bands} bands at {glass}")),
                WavelengthSampling::Hero => Effect::on(format!(
                    "{} hero wavelengths of {n_bands} bands per photon at {glass}",
                    WavelengthSampling::Hero.paths(n_bands)
                )),
                w => Effect::on(format!("one of {n_bands} bands per photon at {glass} ({})", w.name())),
            }
        } else {
            Effect::off("no glass disperses or absorbs (constant index, clear): photons stay white")
        };
        let aspect = scene.render.width as f32 / scene.render.height as f32;
        let seen = |k: usize| camera_sees(&scene.camera, aspect, bounds[k].0, bounds[k].1);
        // Glass that sends view rays of each wavelength its own way (by
        // dispersion) or with its own weight (by a film's colours).
        let colouring: Vec<usize> = specular.iter().copied().filter(|&k| dispersive(k) || coated(k)).collect();
        let glass = match (colouring.iter().any(|&k| dispersive(k)), colouring.iter().any(|&k| coated(k))) {
            (true, true) => "dispersive or coated glass",
            (false, true) => "coated glass",
            _ => "dispersive glass",
        };
        let view_dispersion = if colouring.is_empty() {
            Effect::off("no dispersive glass")
        } else if colouring.iter().any(|&k| seen(k)) {
            Effect::on(format!("{glass} in view"))
        } else if specular.iter().any(|&k| seen(k)) {
            Effect::on(format!("{glass} may be seen through a mirror or glass in view"))
        } else {
            Effect::off(format!("no {glass} visible"))
        };
        // One per light that shines (an environment's suns each), as the emitters are.
        let indirect = if scene.render.indirect_photons == 0 {
            Effect::off("render.indirect_photons = 0")
        } else if !has_diffuse {
            Effect::off("no diffuse surface to bounce light")
        } else if emitters.is_empty() {
            Effect::off("no light")
        } else {
            let diffuse = surfaces.iter().filter(|s| s.stores_photons()).count();
            Effect::on(format!(
                "{} photons bounce off {diffuse} diffuse object{}",
                scene.render.indirect_photons,
                plural(diffuse)
            ))
        };
        let shadows = emitters
            .iter()
            .map(|_| {
                if scene.objects.len() < 2 {
                    Effect::off("one object cannot shadow itself")
                } else {
                    Effect::on(format!("{} objects can occlude", scene.objects.len()))
                }
            })
            .collect();
        let (max_depth, depth_reason) = if indirect.on {
            (scene.render.max_depth, String::from("render.max_depth (indirect light bounces count too)"))
        } else if surfaces.iter().all(|s| matches!(s, Surface::Diffuse { .. })) {
            (0, String::from("no mirror or glass: paths end at the first surface"))
        } else {
            (scene.render.max_depth, String::from("render.max_depth"))
        };
        let mut projections: Vec<Option<Projection>> = emitters.iter().map(|_| None).collect();
        let projection = if !caustics.on {
            Effect::off("no photon pass")
        } else if !scene.render.projection_maps {
            Effect::off("render.projection_maps = false")
        } else {
            let spheres: Vec<(Vec3, f32)> = specular.iter().map(|&k| bounds[k]).collect();
            projections = emitters.iter().map(|l| Projection::new(l, &spheres)).collect();
            let aimed: Vec<f32> = projections.iter().flatten().map(|p| p.scale).collect();
            if aimed.is_empty() {
                Effect::off("no gain: the lights' mirrors and glass fill their emission")
            } else {
                let share = aimed.iter().sum::<f32>() / aimed.len() as f32;
                Effect::on(format!(
                    "{} of {} light{} aimed, {:.1} % of the emission",
                    aimed.len(),
                    projections.len(),
                    plural(projections.len()),
                    share * 100.0
                ))
            }
        };
        let rough_gathers = caustics.on && rough_records && gathers_on_any(surfaces);
        EffectPlan {
            caustics,
            indirect,
            band_splitting,
            view_dispersion,
            shadows,
            projection,
            projections,
            max_depth,
            depth_reason,
            rough_gathers,
            rough_records,
        }
    }

    /// Whether a pass traces photons at all (caustic or indirect).
    pub fn photon_pass(&self) -> bool {
        self.caustics.on || self.indirect.on
    }

    /// Turns every effect on and projection maps off: the scene simulated in
    /// full, for comparisons (what the plan saves, and that it skips nothing
    /// that shows). `surfaces` are the scene's, whose glass then splits
    /// wherever it disperses.
    pub fn simulate_everything(&mut self, max_depth: u32, surfaces: &mut [Surface]) {
        for e in [&mut self.caustics, &mut self.band_splitting, &mut self.view_dispersion]
            .into_iter()
            .chain(&mut self.shadows)
        {
            *e = Effect::on("forced on");
        }
        self.projection = Effect::off("forced off");
        self.projections.iter_mut().for_each(|p| *p = None);
        self.max_depth = max_depth;
        for s in surfaces {
            if let Surface::Dielectric(g) = s {
                (g.splits_photons, g.splits_view_rays) = (g.is_chromatic(), g.colours_view_rays());
            }
        }
    }

    /// One line: what is simulated and what is skipped.
    pub fn summary(&self) -> String {
        let lights_shadowed = self.shadows.iter().filter(|s| s.on).count();
        let mut on = Vec::new();
        let mut off = Vec::new();
        let mut put = |name: &str, e: &Effect| {
            let item = format!("{name} ({})", e.reason);
            if e.on { on.push(item) } else { off.push(item) }
        };
        put("caustics", &self.caustics);
        put("indirect light", &self.indirect);
        if self.caustics.on {
            put("band splitting", &self.band_splitting);
            put("projection maps", &self.projection);
        }
        put("view dispersion", &self.view_dispersion);
        if lights_shadowed > 0 {
            on.push(format!("shadows ({lights_shadowed} light{})", plural(lights_shadowed)));
        } else {
            off.push(String::from("shadows (nothing can occlude)"));
        }
        let mut line =
            format!("effects: {}", if on.is_empty() { String::from("direct light only") } else { on.join(", ") });
        if !off.is_empty() {
            line += &format!("; skipped: {}", off.join(", "));
        }
        line
    }

    /// Every decision with its reason, one per line.
    pub fn explain(&self) -> String {
        let yes = |e: &Effect| if e.on { "yes" } else { "no " };
        let mut s = format!(
            "caustic photon pass: {} {}\nindirect light:      {} {}\nprojection maps:     {} {}\nband splitting:      {} {}\nview dispersion:     {} {}\n",
            yes(&self.caustics),
            self.caustics.reason,
            yes(&self.indirect),
            self.indirect.reason,
            yes(&self.projection),
            self.projection.reason,
            yes(&self.band_splitting),
            self.band_splitting.reason,
            yes(&self.view_dispersion),
            self.view_dispersion.reason
        );
        for (i, e) in self.shadows.iter().enumerate() {
            s += &format!("shadows of light[{i}]: {} {}\n", yes(e), e.reason);
        }
        s += &format!("max depth:           {} ({})\n", self.max_depth, self.depth_reason);
        let rough = match (self.rough_records, self.rough_gathers) {
            (_, true) => format!(
                "caustic photons recorded; gathered where α ≥ {GATHER_ALPHA} (with light tracing, light traced where \
                 seen directly)"
            ),
            (true, false) => "caustic photons recorded; light traced where the camera sees them".into(),
            _ => "caustic photons pass (no hidden light, or no light tracing and none rough enough to gather)".into(),
        };
        s += &format!("rough surfaces:      {rough}\n");
        s
    }
}

/// Whether caustic photons are recorded on the rough metal and glass they
/// meet ([`crate::model::photon::ON_ROUGH_SURFACE`]): a hidden light
/// ([`Light::is_hidden`]: no view ray meets it, so only photons bring its
/// light there) sends them, and either the render light traces (it
/// connects them to the camera) or a surface of `surfaces` is rough
/// enough for visible points to gather them
/// ([`crate::optics::microfacet::Ggx::gathers`]).
pub fn records_on_rough(scene: &Scene, surfaces: &[Surface]) -> bool {
    scene.lights.iter().any(Light::is_hidden) && (scene.render.light_tracing || gathers_on_any(surfaces))
}

/// Whether any of `surfaces` is rough enough for visible points to gather
/// there (a roughness map only lowers its roughness).
fn gathers_on_any(surfaces: &[Surface]) -> bool {
    surfaces.iter().any(|s| s.facets().is_some_and(|g| g.gathers()))
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

fn name_list(objects: &[usize]) -> String {
    let names: Vec<String> = objects.iter().map(|k| format!("object[{k}]")).collect();
    names.join(", ")
}
