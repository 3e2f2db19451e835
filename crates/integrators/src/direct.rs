//! Mitsuba's `direct` integrator: direct illumination only, by a fixed number of light samples
//! and BSDF samples at the camera ray's first hit.
//!
//! **What it is.** At the first vertex, `emitter_samples` light samples (next event estimation,
//! [`crate::path::nee`]) and `bsdf_samples` BSDF samples, each BSDF sample traced to the
//! emission it finds; the two kinds are combined by the preset's MIS heuristic over count ×
//! density ([`crate::path::mis`]) and each sample is divided by its count. Nothing is found
//! beyond the next vertex: the expectation is the path tracer's with `max_depth` 2. Zero samples
//! of a kind leave out what only that kind reaches, as in Mitsuba ([`DirectSamples`]).
//!
//! **The lecture's formula.** Next event estimation's direct light and the MIS weights with
//! sample counts n_light and n_bsdf:
//!
//! ```text
//! L ≈ Σ_i w_light(x_i) · f · Le · cos θ / (n_light · p_light(x_i))
//!   + Σ_j w_bsdf(ω_j) · f · Le · cos θ / (n_bsdf · p_bsdf(ω_j)),
//! w_a = (n_a p_a)^β / Σ_b (n_b p_b)^β      (β = 1 balance, 2 power)
//! ```
//!
//! **When `auto` uses it.** When the scene file asks for `<integrator type="direct">`: `auto`
//! and every preset then keep its sample counts and choose the rest (light selection, MIS
//! heuristic, sampler) as for a path.

use crate::path::PathIntegrator;
use crate::path::mis::{PreviousVertex, StrategyCounts};
use crate::path::nee::delta_lights;
use crate::settings::DirectSamples;
use geometry::SpawnPoint;
use glam::Vec3;
use sampling::Sampler;
use world::{BsdfSlot, RayTally, SurfaceHit, World};

impl PathIntegrator {
    /// Mitsuba's `direct` integrator at the camera ray's hit `surface` (whose point is `point`,
    /// seen from `wo`, local frame): the radiance (W m⁻² sr⁻¹, RGB) of `samples.light` light
    /// samples and `samples.bsdf` BSDF samples, each MIS-weighted by the counts and divided by
    /// its count. The light samples draw their numbers first, then the BSDF samples.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn direct_samples(
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
        // The light samples, or without light sampling the delta lights' shadow rays.
        if self.settings().sample_lights {
            for _ in 0..samples.light {
                self.light_samples_drawn(world, surface, point, wo, sampler, counts, |light| {
                    if let Some(direct) = light.unoccluded(world, counters) {
                        radiance += direct / counts.light;
                    }
                });
            }
        } else if samples.light > 0 && !surface.bsdf.flags().is_delta() {
            radiance += delta_lights(world, surface, point, wo, counters);
        }
        // The BSDF samples, each traced to the emission it finds.
        let mut slot = BsdfSlot::default();
        for _ in 0..samples.bsdf {
            let Some(next) = self.sample_direction(surface, wo, sampler) else {
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
}
