//! The path tracer's face to the renderer: [`PathIntegrator`], configured once for a world, and
//! its two entry points, one path's estimate whole or split for path reuse. The walk itself is
//! `path/mod.rs`.
//!
//! Sampler dimensions per vertex, in this order and only for the techniques switched on and what
//! the scene needs (so a configuration consumes a fixed, documented sequence for a scene, the
//! same at every vertex whatever surface it is on): light choice (1D, with next event
//! estimation when it has more than one light to sample: under MIS a constant environment is
//! left to BSDF samples), RIS's reservoir choice (1D, with RIS light selection and more than one
//! light to sample) and light point (2D, with next event estimation and a light to sample); BSDF
//! lobe (1D, when some material chooses between lobes: a dielectric) and BSDF direction (2D)
//! always; roulette (1D, with Russian roulette from its start depth on). With
//! [`DirectSamples`] (Mitsuba's `direct` integrator) the first vertex draws the light numbers once
//! per light sample, then the BSDF numbers once per BSDF sample, and nothing else is drawn.

use crate::caustic_mis::{CausticPaths, LightPathStarts};
use crate::light_selection::SampledLights;
use crate::path_reuse::ReusablePath;
use crate::settings::{DirectSamples, Mis, PathSettings};
use glam::Vec3;
use lights::{Light, LightSelection, LightSelector};
use sampling::Sampler;
use world::{BsdfSlot, CameraRay, RayTally, World};

/// The path tracer configured for one world: the settings and the light selection table.
#[derive(Clone, Debug)]
pub struct PathIntegrator {
    pub(super) settings: PathSettings,
    pub(super) selector: Option<LightSelector>,
    /// The light that light sampling samples in a form of its own, by index, and that form
    /// ([`lights::Light::compensated`]: an environment map where MIS weighs BSDF samples).
    /// (Boxed: a light is large, and the integrator is moved by value.)
    compensated: Option<(usize, Box<Light>)>,
    /// Whether light sampling draws a number to choose among more than one light.
    pub(super) draws_light_choice: bool,
    /// Whether a light sample draws the number its RIS reservoir chooses with (RIS with more
    /// than one light).
    pub(super) draws_reservoir_choice: bool,
    /// Whether some material draws a number to choose its lobe.
    pub(super) draws_lobe_choice: bool,
    /// How emission at the end of a caustic chain counts: in full without light tracing,
    /// shared with the light tracer where BSDF samples can find it (`caustic_mis`).
    pub(super) caustic_paths: CausticPaths,
}

impl PathIntegrator {
    /// The integrator for `world` with `settings`, without path reuse where something moves
    /// (it joins paths of different pixels, which see the scene at different times).
    pub fn new(world: &World, mut settings: PathSettings) -> Self {
        if world.has_motion() {
            settings.path_reuse = None;
        }
        let bsdf_finds_lights = bsdf_finds_lights(&settings);
        // An environment map under MIS is sampled by its excess over its mean.
        let compensated = world
            .lights()
            .iter()
            .enumerate()
            .filter(|_| bsdf_finds_lights)
            .find_map(|(index, light)| Some((index, Box::new(light.compensated()?))));
        let sampled = SampledLights::new(world.lights(), &compensated);
        let powers: Vec<f32> = (0..world.lights().len())
            .map(|index| sampled[index].power())
            .collect();
        let selector = LightSelector::with_powers(
            &powers,
            &sampling_weights(world, bsdf_finds_lights),
            settings.light_selection,
        );
        let choices = selector.as_ref().is_some_and(|s| s.sampled().len() > 1);
        Self {
            settings,
            selector,
            compensated,
            draws_light_choice: choices && settings.light_selection != LightSelection::All,
            draws_reservoir_choice: choices
                && matches!(settings.light_selection, LightSelection::Ris { .. }),
            draws_lobe_choice: world.has_lobe_choice(),
            caustic_paths: match settings
                .light_tracing
                .map(|tracing| LightPathStarts::new(world, tracing.paths_per_sample()))
            {
                None => CausticPaths::Kept,
                Some(Some(starts)) if settings.sample_bsdf => {
                    CausticPaths::Shared(Box::new(starts))
                }
                Some(_) => CausticPaths::Left,
            },
        }
    }

    /// This integrator with the paths light tracing contributes left out entirely (emission met
    /// by a delta bounce after a first vertex left by a non-delta lobe), as if a light tracer
    /// took each of them whole, whatever the settings: the image then lacks them. For `auto`'s
    /// pilot, which estimates the variance they add from light paths instead
    /// ([`CameraSplat::path_tracer_ratio`](crate::CameraSplat::path_tracer_ratio)), since a
    /// short render meets them too rarely to show it.
    pub fn leaving_caustics(mut self) -> Self {
        self.caustic_paths = CausticPaths::Left;
        self
    }

    /// The lights of `world` as light sampling samples them, and as MIS weighs emission by.
    #[inline(always)]
    pub(crate) fn sampled_lights<'a>(&'a self, world: &'a World) -> SampledLights<'a> {
        SampledLights::new(world.lights(), &self.compensated)
    }

    /// The settings this integrator runs with.
    pub fn settings(&self) -> &PathSettings {
        &self.settings
    }

    /// The sampler dimensions [`Self::radiance`] draws at its first `vertices` path vertices, in
    /// the order of the module documentation: a dimension is one `next_1d` or `next_2d` call. A
    /// path that ends sooner draws fewer, never other ones; with
    /// [`PathSettings::skip_null_vertices`] a pass through a null lobe draws a vertex's
    /// dimensions without being a vertex.
    pub fn sampler_dimensions(&self, vertices: u32) -> u32 {
        let settings = &self.settings;
        let per_light_sample = u32::from(settings.sample_lights && self.selector.is_some())
            * (1 + u32::from(self.draws_light_choice) + u32::from(self.draws_reservoir_choice));
        let per_bsdf_sample = u32::from(self.draws_lobe_choice) + 1;
        if let Some(DirectSamples { light, bsdf }) = settings.direct_samples {
            return if vertices == 0 {
                0
            } else {
                light * per_light_sample + bsdf * per_bsdf_sample
            };
        }
        let per_vertex = per_light_sample + per_bsdf_sample;
        (1..=vertices)
            .map(|depth| {
                let roulette = settings
                    .russian_roulette
                    .is_some_and(|r| depth >= r.start_depth);
                per_vertex + u32::from(roulette)
            })
            .sum()
    }

    /// Radiance (W m⁻² sr⁻¹, RGB) arriving at the camera along `camera_ray`: one path's estimate.
    /// `slot` holds the BSDF of a textured hit while the path is there; the caller keeps one for
    /// all its paths, so that a path costs nothing for it when the scene has no textures.
    pub fn radiance(
        &self,
        world: &World,
        camera_ray: CameraRay,
        sampler: &mut impl Sampler,
        counters: &mut impl RayTally,
        slot: &mut BsdfSlot,
    ) -> Vec3 {
        self.walk::<false>(world, camera_ray, sampler, counters, slot)
            .own
    }

    /// [`Self::radiance`] split for path reuse ([`crate::path_reuse`]): the same path, drawing
    /// the same sampler dimensions, with its first and second vertices kept where both are
    /// diffuse and the radiance the second reflects towards the first kept apart from the rest
    /// of the estimate. [`crate::path_reuse::combine`] then connects the paths of a block.
    /// Without [`PathSettings::path_reuse`] (or where [`PathSettings::reuse_applies`] is false)
    /// nothing is split and `own` is the whole estimate.
    pub fn radiance_reusable(
        &self,
        world: &World,
        camera_ray: CameraRay,
        sampler: &mut impl Sampler,
        counters: &mut impl RayTally,
        slot: &mut BsdfSlot,
    ) -> ReusablePath {
        if self.settings.path_reuse.is_some() && self.settings.reuse_applies() {
            self.walk::<true>(world, camera_ray, sampler, counters, slot)
        } else {
            self.walk::<false>(world, camera_ray, sampler, counters, slot)
        }
    }
}

/// Each light's weight for light sampling: the scene's selection weight, or 0 for a light
/// [left to BSDF samples](lights::Light::left_to_bsdf_samples) where the walk's BSDF samples find
/// emission and MIS weighs them. Emission that no light sample could have found counts in
/// full, so the estimate stays unbiased.
fn sampling_weights(world: &World, bsdf_finds_lights: bool) -> Vec<f32> {
    world
        .lights()
        .iter()
        .zip(world.light_weights())
        .map(|(light, &weight)| {
            if bsdf_finds_lights && light.left_to_bsdf_samples() {
                0.0
            } else {
                weight
            }
        })
        .collect()
}

/// Whether BSDF samples continue the walk and MIS weighs the emission they find against light
/// samples: then a light may be left to them, or sampled in a form of its own.
fn bsdf_finds_lights(settings: &PathSettings) -> bool {
    settings.sample_bsdf
        && settings.mis != Mis::Off
        && settings.direct_samples.is_none_or(|d| d.bsdf > 0)
}
