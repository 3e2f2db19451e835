//! The variance-reduction path tracer: every technique of the lecture as a switch in
//! [`PathSettings`], each switch unbiased on its own and in any combination.
//!
//! Without light sampling, point lights (which no sampled direction can hit) are still connected
//! by one shadow ray each, as in the reference integrator.
//!
//! Sampler dimensions per vertex, in this order and only for the techniques switched on and what
//! the scene needs (so a configuration consumes a fixed, documented sequence for a scene, the
//! same at every vertex whatever surface it is on): light choice (1D, with next event
//! estimation when the scene has more than one light), RIS's reservoir choice (1D, with RIS
//! light selection when the scene has more than one light) and light point (2D, with next event
//! estimation); BSDF lobe (1D, when some material chooses between lobes: a dielectric) and BSDF
//! direction (2D) always; roulette (1D, with Russian roulette from its start depth on). With
//! [`DirectSamples`] (Mitsuba's `direct` integrator) the first vertex draws the light numbers once
//! per light sample, then the BSDF numbers once per BSDF sample, and nothing else is drawn.

use crate::delta_lights::delta_lights;
use crate::light_selection::choose_light;
use crate::next_direction::NextDirection;
use crate::optional_draw::next_1d_if;
use crate::path_reuse::{FirstVertex, ReusablePath, SecondVertex};
use crate::reference::UNBOUNDED_DEPTH_CAP;
use crate::settings::{DirectSamples, Mis, PathSettings};
use crate::uniform_direction::{sample_without_importance, uniform_direction_pdf};
use geometry::{Ray, SpawnPoint};
use glam::{Vec2, Vec3};
use lights::{LightSelection, LightSelector};
use materials::BsdfFlags;
use sampling::Sampler;
use sampling::mis::{balance_heuristic, power_heuristic};
use world::{BsdfSlot, CameraRay, RayTally, SurfaceHit, World, shadow_ray};

/// How many samples of each strategy are combined at a vertex, for the MIS weights.
#[derive(Clone, Copy, Debug)]
struct StrategyCounts {
    light: f32,
    bsdf: f32,
}

/// The walk's counts: one light sample and one BSDF sample per vertex.
const ONE_EACH: StrategyCounts = StrategyCounts {
    light: 1.0,
    bsdf: 1.0,
};

/// The path tracer configured for one world: the settings and the light selection table.
#[derive(Clone, Debug)]
pub struct PathIntegrator {
    settings: PathSettings,
    selector: Option<LightSelector>,
    /// Whether light sampling draws a number to choose among more than one light.
    draws_light_choice: bool,
    /// Whether a light sample draws the number its RIS reservoir chooses with (RIS with more
    /// than one light).
    draws_reservoir_choice: bool,
    /// Whether some material draws a number to choose its lobe.
    draws_lobe_choice: bool,
}

/// What the walk remembers about the vertex it just left, to weight emission it finds.
#[derive(Clone, Copy, Debug)]
struct PreviousVertex {
    p: Vec3,
    /// Density per steradian of the direction that was sampled there.
    pdf_dir: f32,
    /// True at the camera and after a delta bounce: light sampling could not have found this
    /// emission, so it counts in full.
    delta: bool,
}

/// Direct light a light sample brings to a vertex if its shadow ray is not blocked: the walk
/// traces that ray only once it has drawn the vertex's next direction, so that the shadow ray
/// starts from inputs long computed and the next ray's setup overlaps with its end.
#[derive(Clone, Copy, Debug)]
struct ShadowedLight {
    /// The shadow ray from the vertex towards the light's point.
    ray: Ray,
    /// Where the shadow ray ends (world units; ∞ for lights at infinity).
    t_max: f32,
    /// Radiance (W m⁻² sr⁻¹, RGB) the light adds to the estimate when unblocked, throughput and
    /// MIS weight included.
    radiance: Vec3,
}

impl ShadowedLight {
    /// `radiance` if nothing blocks the shadow ray (told to `counters`), else zero.
    #[inline(always)]
    fn traced(self, world: &World, counters: &mut impl RayTally) -> Vec3 {
        if world.ray_unoccluded(&self.ray, self.t_max, counters) {
            self.radiance
        } else {
            Vec3::ZERO
        }
    }
}

impl PathIntegrator {
    /// The integrator for `world` with `settings`, without path reuse where something moves
    /// (it joins paths of different pixels, which see the scene at different times).
    pub fn new(world: &World, mut settings: PathSettings) -> Self {
        if world.has_motion() {
            settings.path_reuse = None;
        }
        Self {
            settings,
            selector: LightSelector::new(
                world.lights(),
                world.light_weights(),
                settings.light_selection,
            ),
            draws_light_choice: world.lights().len() > 1,
            draws_reservoir_choice: world.lights().len() > 1
                && matches!(settings.light_selection, LightSelection::Ris { .. }),
            draws_lobe_choice: world.has_lobe_choice(),
        }
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
        let per_light_sample = u32::from(settings.sample_lights)
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

    /// The path walk behind [`Self::radiance`] and, with `REUSE`, [`Self::radiance_reusable`].
    #[inline(always)]
    fn walk<const REUSE: bool>(
        &self,
        world: &World,
        camera_ray: CameraRay,
        sampler: &mut impl Sampler,
        counters: &mut impl RayTally,
        slot: &mut BsdfSlot,
    ) -> ReusablePath {
        let settings = &self.settings;
        let max_depth = settings.max_depth.unwrap_or(UNBOUNDED_DEPTH_CAP);
        let mut radiance = Vec3::ZERO;
        let mut throughput = Vec3::ONE;
        // Product of η² over the refractions so far: refraction scales radiance by 1/η², which
        // roulette must not mistake for absorption (pbrt-v4's `etaScale`, Mitsuba's `eta`).
        let mut eta_scale = 1.0_f32;
        let CameraRay { mut ray, mut t_max } = camera_ray;
        let mut previous = PreviousVertex {
            p: ray.origin,
            pdf_dir: 0.0,
            delta: true,
        };
        // Whether the path's first vertex was left by a non-delta lobe and its last by a delta
        // one: emission it meets next is the light tracer's with `light_tracing` on.
        let mut caustic_chain = false;
        let mut first_vertex_non_delta = false;
        // Whether every bounce so far was by a delta lobe: what the path finds next, neither light
        // sampling nor the light tracer can reach.
        let mut seen_through_delta = true;
        // The number of the vertex the ray is about to find: one more per bounce, not per pass
        // through a null lobe with `skip_null_vertices`.
        let mut depth = 1;
        // For path reuse: the first vertex where it is diffuse, the second once it is found
        // diffuse, and then the estimate up to the second vertex (`own`) and the throughput to
        // it (`prefix`), while `radiance` and `throughput` go on from the second vertex alone.
        let mut first: Option<FirstVertex> = None;
        let mut second: Option<SecondVertex> = None;
        let mut own = Vec3::ZERO;
        let mut prefix = Vec3::ONE;
        loop {
            let hidden = depth == 1 && settings.hide_emitters;
            let found = if hidden {
                world.intersect_past_emitters(&CameraRay { ray, t_max }, counters, slot)
            } else {
                world.intersect_within(&ray, t_max, counters, slot)
            };
            let Some(surface) = &found else {
                if !hidden {
                    radiance +=
                        self.background_found(world, ray.dir, &previous, ONE_EACH, throughput);
                }
                break;
            };
            let left_to_light_tracer = settings.light_tracing && caustic_chain;
            if !hidden && !left_to_light_tracer {
                radiance += self.emission_found(
                    world,
                    surface,
                    ray.dir,
                    &previous,
                    seen_through_delta,
                    ONE_EACH,
                    throughput,
                );
            }
            // At the last vertex only a pass through a null lobe goes on.
            let last = depth == max_depth;
            if last
                && !(settings.skip_null_vertices && surface.bsdf.flags().contains(BsdfFlags::NULL))
            {
                break;
            }
            let wo = surface.frame.to_local(-ray.dir);
            let point = SpawnPoint::of(&surface.hit);
            if REUSE {
                if depth == 1 {
                    first = FirstVertex::at(surface, &point, wo);
                } else if depth == 2
                    && first.is_some()
                    && let Some(found) = SecondVertex::at(surface, &point)
                {
                    second = Some(found);
                    own = radiance;
                    radiance = Vec3::ZERO;
                    prefix = throughput;
                    throughput = Vec3::ONE;
                }
            }
            if let Some(samples) = settings.direct_samples {
                radiance +=
                    self.direct_samples(world, surface, &point, wo, samples, sampler, counters);
                break;
            }

            // No light sampling at the last vertex: the light would be one vertex too many.
            let mut shadowed = None;
            if !last {
                if settings.sample_lights {
                    shadowed = self
                        .light_sample_at_vertex(world, surface, &point, wo, sampler)
                        .map(|light| ShadowedLight {
                            radiance: throughput * light.radiance,
                            ..light
                        });
                } else if !surface.bsdf.flags().is_delta() {
                    radiance += throughput * delta_lights(world, surface, &point, wo, counters);
                }
            }
            let next_ray = 'next: {
                let u_lobe = next_1d_if(sampler, self.draws_lobe_choice);
                let u_dir = sampler.next_2d();
                let Some(next) = self.next_direction(surface, wo, u_lobe, u_dir) else {
                    break 'next None;
                };
                let passes_null = settings.skip_null_vertices && next.is_null;
                if last && !passes_null {
                    break 'next None;
                }
                throughput *= next.weight;
                eta_scale *= next.eta * next.eta;
                seen_through_delta &= next.is_delta;
                if depth == 1 {
                    first_vertex_non_delta = !next.is_delta;
                } else {
                    caustic_chain = first_vertex_non_delta && next.is_delta;
                }
                if let Some(roulette) = settings.russian_roulette
                    && depth >= roulette.start_depth
                {
                    let u_survive = sampler.next_1d();
                    let survival =
                        ((throughput * prefix).max_element() * eta_scale).clamp(0.0, 1.0);
                    if u_survive >= survival {
                        break 'next None;
                    }
                    throughput /= survival;
                }
                if throughput == Vec3::ZERO {
                    break 'next None;
                }
                previous = PreviousVertex {
                    p: surface.hit.p,
                    pdf_dir: next.pdf_solid_angle,
                    delta: next.is_delta,
                };
                depth += u32::from(!passes_null);
                Some(point.spawn_unit(surface.frame.to_world(next.wi)))
            };
            if let Some(light) = shadowed {
                radiance += light.traced(world, counters);
            }
            let Some(next_ray) = next_ray else {
                break;
            };
            ray = next_ray;
            t_max = f32::INFINITY;
        }
        match second {
            Some(mut second) => {
                second.reflected = radiance;
                ReusablePath {
                    own,
                    first,
                    second: Some(second),
                }
            }
            None => ReusablePath {
                own: radiance,
                first,
                second: None,
            },
        }
    }

    /// The numbers a light sample chooses its light with: the light choice, and RIS's reservoir
    /// choice (0 when not drawn).
    #[inline(always)]
    fn light_numbers(&self, sampler: &mut impl Sampler) -> Vec2 {
        let choice = next_1d_if(sampler, self.draws_light_choice);
        let reservoir = next_1d_if(sampler, self.draws_reservoir_choice);
        Vec2::new(choice, reservoir)
    }

    /// Next event estimation at `surface` (drawing its numbers at every vertex, as the walk's
    /// light sample): the light it reflects towards `wo` if the shadow ray is not blocked;
    /// `None` at a delta surface or where the sample carries nothing.
    #[inline(always)]
    fn light_sample_at_vertex(
        &self,
        world: &World,
        surface: &SurfaceHit<'_>,
        point: &SpawnPoint,
        wo: Vec3,
        sampler: &mut impl Sampler,
    ) -> Option<ShadowedLight> {
        let u_choice = self.light_numbers(sampler);
        let u_point = sampler.next_2d();
        if surface.bsdf.flags().is_delta() {
            return None;
        }
        self.light_sample(world, surface, point, wo, u_choice, u_point, ONE_EACH)
    }

    /// Mitsuba's `direct` integrator at the camera ray's hit `surface`: `samples.light` light
    /// samples and `samples.bsdf` BSDF samples, each traced to the emission it finds, MIS-weighted
    /// by their counts and each divided by its count.
    #[allow(clippy::too_many_arguments)]
    fn direct_samples(
        &self,
        world: &World,
        surface: &SurfaceHit<'_>,
        point: &SpawnPoint,
        wo: Vec3,
        samples: DirectSamples,
        sampler: &mut impl Sampler,
        counters: &mut impl RayTally,
    ) -> Vec3 {
        let counts = StrategyCounts {
            light: samples.light as f32,
            bsdf: samples.bsdf as f32,
        };
        let mut radiance = Vec3::ZERO;
        let mut slot = BsdfSlot::default();
        if self.settings.sample_lights {
            for _ in 0..samples.light {
                let u_choice = self.light_numbers(sampler);
                let u_point = sampler.next_2d();
                if !surface.bsdf.flags().is_delta()
                    && let Some(light) =
                        self.light_sample(world, surface, point, wo, u_choice, u_point, counts)
                {
                    radiance += light.traced(world, counters) / counts.light;
                }
            }
        } else if samples.light > 0 && !surface.bsdf.flags().is_delta() {
            radiance += delta_lights(world, surface, point, wo, counters);
        }
        for _ in 0..samples.bsdf {
            let u_lobe = next_1d_if(sampler, self.draws_lobe_choice);
            let u_dir = sampler.next_2d();
            let Some(next) = self.next_direction(surface, wo, u_lobe, u_dir) else {
                continue;
            };
            let previous = PreviousVertex {
                p: surface.hit.p,
                pdf_dir: next.pdf_solid_angle,
                delta: next.is_delta,
            };
            let ray = point.spawn_unit(surface.frame.to_world(next.wi));
            let weight = next.weight / counts.bsdf;
            radiance += match world.intersect(&ray, counters, &mut slot) {
                Some(found) => self.emission_found(
                    world,
                    &found,
                    ray.dir,
                    &previous,
                    next.is_delta,
                    counts,
                    weight,
                ),
                None => self.background_found(world, ray.dir, &previous, counts, weight),
            };
        }
        radiance
    }

    /// The environment's radiance found by a ray that left `previous` in the unit direction
    /// `dir`, times `throughput` and its MIS weight.
    #[inline(always)]
    fn background_found(
        &self,
        world: &World,
        dir: Vec3,
        previous: &PreviousVertex,
        counts: StrategyCounts,
        throughput: Vec3,
    ) -> Vec3 {
        let background = world.background(dir);
        if background == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let weight = self.emission_weight(previous, world.environment(), counts, || {
            world
                .environment()
                .map_or(0.0, |e| world.lights()[e as usize].pdf_li_environment(dir))
        });
        throughput * background * weight
    }

    /// The emission of `surface` towards `-dir` found by a ray that left `previous`, times
    /// `throughput` and its MIS weight; `seen_through_delta` as [`World::emitted`] takes it.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn emission_found(
        &self,
        world: &World,
        surface: &SurfaceHit<'_>,
        dir: Vec3,
        previous: &PreviousVertex,
        seen_through_delta: bool,
        counts: StrategyCounts,
        throughput: Vec3,
    ) -> Vec3 {
        let Some(light) = surface.light else {
            return Vec3::ZERO;
        };
        let emitted = world.emitted(surface, -dir, seen_through_delta);
        if emitted == Vec3::ZERO {
            return Vec3::ZERO;
        }
        let weight = self.emission_weight(previous, Some(light), counts, || {
            world.lights()[light as usize].pdf_li_surface(
                previous.p,
                surface.hit.p,
                surface.hit.ng,
                surface.hit.time,
            )
        });
        throughput * emitted * weight
    }

    /// Direct light at `surface` by one light sample, MIS-weighted (against `counts` samples of
    /// each strategy) if MIS is on, with the shadow ray that decides it; `None` where the
    /// sample carries nothing.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn light_sample(
        &self,
        world: &World,
        surface: &SurfaceHit<'_>,
        point: &SpawnPoint,
        wo: Vec3,
        u_choice: Vec2,
        u_point: Vec2,
        counts: StrategyCounts,
    ) -> Option<ShadowedLight> {
        let selector = self.selector.as_ref()?;
        let chosen = choose_light(
            self.settings.light_selection,
            selector,
            world.lights(),
            surface,
            wo,
            u_choice,
            u_point,
        )?;
        let sample = chosen.sample;
        let (ray, t_max) = shadow_ray(point, &sample);
        let mis_weight = if sample.is_delta {
            1.0
        } else {
            let pdf_direction = if self.settings.sample_bsdf {
                chosen.pdf_bsdf_solid_angle
            } else {
                uniform_direction_pdf(surface.bsdf, wo, chosen.wi_local)
            };
            self.heuristic(counts.light, chosen.pdf_for_mis, counts.bsdf, pdf_direction)
        };
        Some(ShadowedLight {
            ray,
            t_max,
            radiance: chosen.f_cos * sample.radiance * (chosen.weight * mis_weight),
        })
    }

    /// The next direction of the walk: by the BSDF's sampling routine or without importance.
    #[inline(always)]
    fn next_direction(
        &self,
        surface: &SurfaceHit<'_>,
        wo: Vec3,
        u_lobe: f32,
        u_dir: Vec2,
    ) -> Option<NextDirection> {
        if self.settings.sample_bsdf {
            surface
                .bsdf
                .sample(wo, u_lobe, u_dir)
                .map(NextDirection::from)
        } else {
            sample_without_importance(surface.bsdf, wo, u_lobe, u_dir)
        }
    }

    /// Weight of emission found by the walk: 1 where light sampling could not have found it
    /// (or took no sample), 0 where it did and MIS is off, the MIS weight of the BSDF strategy
    /// (against `counts` samples of each) otherwise.
    fn emission_weight(
        &self,
        previous: &PreviousVertex,
        light: Option<u32>,
        counts: StrategyCounts,
        pdf_light_solid_angle: impl FnOnce() -> f32,
    ) -> f32 {
        if !self.settings.sample_lights || previous.delta || counts.light == 0.0 {
            return 1.0;
        }
        let (Some(selector), Some(light)) = (&self.selector, light) else {
            return 1.0;
        };
        if self.settings.mis == Mis::Off {
            return 0.0;
        }
        let pdf_light = selector.pmf(light as usize) * pdf_light_solid_angle();
        self.heuristic(counts.bsdf, previous.pdf_dir, counts.light, pdf_light)
    }

    /// The MIS weight of one of `n_f` samples with density `pdf_f` against `n_g` samples of the
    /// other strategy with density `pdf_g`.
    #[inline]
    fn heuristic(&self, n_f: f32, pdf_f: f32, n_g: f32, pdf_g: f32) -> f32 {
        match self.settings.mis {
            Mis::Off => 1.0,
            Mis::Balance => balance_heuristic(n_f, pdf_f, n_g, pdf_g),
            Mis::Power => power_heuristic(n_f, pdf_f, n_g, pdf_g),
        }
    }
}
