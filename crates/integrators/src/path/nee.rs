//! Next event estimation: at every non-delta vertex, one shadow ray to a sampled point on a
//! chosen light.
//!
//! **What it is.** The light arriving at a vertex is split into direct light, from the light
//! sources, and indirect light, from everything else. Direct light is estimated by a light
//! sample (or one per light: [`crate::light_selection::every`]): [`crate::light_selection`]
//! chooses a light and a point on it, the BSDF is evaluated
//! towards it, and a shadow ray decides whether it is seen; the walk's BSDF sample then carries
//! the indirect light. Small lights, which a BSDF sample rarely hits, are found at every vertex.
//! Light that the BSDF sample finds as well is weighted by [MIS](super::mis). Without light
//! sampling ([`crate::PathSettings::sample_lights`] off, and in the reference integrator), a
//! vertex still connects to every delta light ([`delta_lights`]): no sampled direction can hit
//! a point light.
//!
//! **The lecture's formula.** For a point on a light at distance d in direction L (unit), with
//! normals N at the shading point and N_light at the light, area A, one of `lightCount` lights
//! picked uniformly:
//!
//! ```text
//! solidAngle = (N_light · −L) · A / d²        (lightPdf = 1 / solidAngle)
//! direct     = Le · solidAngle · BRDF · (N · L) · lightCount
//! ```
//!
//! rejected when N · L ≤ 0, N_light · −L ≤ 0 or the shadow ray is blocked. Strata divides by the
//! light selection probability and the light's density per steradian instead
//! ([`crate::light_selection`]), so the same estimate holds for every kind of light.
//!
//! **When `auto` uses it.** Whenever the scene has a light and a material that is not a pure
//! delta (a mirror or smooth glass cannot use a light sample); off where every BSDF is a delta
//! or there are no lights.

use super::PathIntegrator;
use super::mis::{ONE_EACH, StrategyCounts};
use super::state::PathState;
use crate::light_selection::sample_lights;
use crate::optional_draw::next_1d_if;
use geometry::{Ray, SpawnPoint};
use glam::{Vec2, Vec3};
use sampling::Sampler;
use world::{RayTally, SurfaceHit, World, shadow_ray};

/// Direct light a light sample brings to a vertex if its shadow ray is not blocked. The walk
/// traces the shadow ray only once it has drawn the vertex's next direction, so that the ray
/// starts from inputs long computed and the next ray's set-up overlaps with it: traced where it
/// is built, the path loop measured 5–15% slower (`cargo bench -p render --bench render --
/// samples`, issue 34).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShadowedLight {
    /// The shadow ray from the vertex towards the light's point.
    ray: Ray,
    /// Where the shadow ray ends (world units; ∞ for lights at infinity).
    t_max: f32,
    /// Radiance (W m⁻² sr⁻¹, RGB) the light reflects towards the vertex's outgoing direction,
    /// divided by the sample's densities and MIS-weighted (and in the walk times the path's
    /// throughput): what the estimate gains when the shadow ray is not blocked.
    radiance: Vec3,
}

impl ShadowedLight {
    /// `radiance` if nothing blocks the shadow ray (told to `counters`), else `None`.
    #[inline(always)]
    pub(crate) fn unoccluded(self, world: &World, counters: &mut impl RayTally) -> Option<Vec3> {
        world
            .ray_unoccluded(&self.ray, self.t_max, counters)
            .then_some(self.radiance)
    }
}

impl PathIntegrator {
    /// The walk's next event estimation at `surface` (whose point is `point`, seen from `wo`,
    /// local frame) on `path`: its light samples, their radiance times the path's throughput;
    /// the last one's shadow ray is left for the walk to trace once it has drawn the next
    /// direction (see [`ShadowedLight`]), the others' (sampling every light) traced here. Without
    /// light sampling, the light of every delta light, added to the path's estimate at once.
    /// `None` where there is no shadow ray left to trace.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn next_event(
        &self,
        world: &World,
        surface: &SurfaceHit<'_>,
        point: &SpawnPoint,
        wo: Vec3,
        path: &mut PathState,
        sampler: &mut impl Sampler,
        counters: &mut impl RayTally,
    ) -> Option<ShadowedLight> {
        if self.settings.sample_lights {
            let mut deferred = None;
            self.light_samples_drawn(world, surface, point, wo, sampler, ONE_EACH, |light| {
                let light = ShadowedLight {
                    radiance: path.throughput * light.radiance,
                    ..light
                };
                if let Some(earlier) = deferred.replace(light)
                    && let Some(direct) = earlier.unoccluded(world, counters)
                {
                    path.radiance += direct;
                }
            });
            deferred
        } else {
            if !surface.bsdf.flags().is_delta() {
                path.radiance +=
                    path.throughput * delta_lights(world, surface, point, wo, counters);
            }
            None
        }
    }

    /// The light samples at `surface` (one, or one per light: [`sample_lights`]), each
    /// MIS-weighted against `counts` samples of each strategy, with the shadow ray that decides
    /// it, passed to `visit`. It draws its numbers wherever it is asked, so that a vertex draws
    /// the same dimensions whatever surface it is on; nothing is visited at a delta surface or
    /// for samples that carry nothing.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn light_samples_drawn(
        &self,
        world: &World,
        surface: &SurfaceHit<'_>,
        point: &SpawnPoint,
        wo: Vec3,
        sampler: &mut impl Sampler,
        counts: StrategyCounts,
        mut visit: impl FnMut(ShadowedLight),
    ) {
        let Some(selector) = self.selector.as_ref() else {
            return;
        };
        let u_choice = self.light_numbers(sampler);
        let u_point = sampler.next_2d();
        if surface.bsdf.flags().is_delta() {
            return;
        }
        let mode = self.settings.light_selection;
        sample_lights(
            mode,
            selector,
            &self.sampled_lights(world),
            surface,
            wo,
            u_choice,
            u_point,
            |chosen| {
                let (ray, t_max) = shadow_ray(point, &chosen.sample);
                let mis_weight = self.light_sample_weight(&chosen, surface, wo, counts);
                visit(ShadowedLight {
                    ray,
                    t_max,
                    radiance: chosen.f_cos * chosen.sample.radiance * (chosen.weight * mis_weight),
                });
            },
        );
    }

    /// The numbers a light sample chooses its light with: the light choice, and RIS's reservoir
    /// choice (each 0.5 when not drawn).
    #[inline(always)]
    fn light_numbers(&self, sampler: &mut impl Sampler) -> Vec2 {
        let choice = next_1d_if(sampler, self.draws_light_choice);
        let reservoir = next_1d_if(sampler, self.draws_reservoir_choice);
        Vec2::new(choice, reservoir)
    }
}

/// Light from every delta light at `surface` (whose point is `point`) towards `wo` (local
/// frame; W m⁻² sr⁻¹, RGB), each by its one shadow ray. Without light sampling this is the only
/// way to see a point light: no sampled direction can hit it.
pub(crate) fn delta_lights(
    world: &World,
    surface: &SurfaceHit<'_>,
    point: &SpawnPoint,
    wo: Vec3,
    counters: &mut impl RayTally,
) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for &index in world.delta_lights() {
        let Some(s) =
            world.lights()[index as usize].sample_li(surface.hit.p, Vec2::ZERO, surface.hit.time)
        else {
            continue;
        };
        let wi = surface.frame.to_local(s.wi);
        let f = surface.bsdf.eval(wo, wi);
        if f != Vec3::ZERO && world.light_unoccluded(point, &s, counters) {
            sum += f * wi.z.abs() * s.radiance / s.pdf_solid_angle;
        }
    }
    sum
}
