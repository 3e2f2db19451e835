//! The reference path tracer: no tricks, short and obviously right.
//!
//! **What it is.** Directions are sampled uniformly over the hemisphere on the side the path
//! arrived from (the whole sphere for a BSDF that transmits; delta lobes by their delta),
//! emission is counted where a path hits it, and paths end at `max_depth` vertices. No next
//! event estimation, no MIS, no Russian roulette. Delta lights (points) cannot be hit by a
//! random ray, so each vertex connects to them explicitly (`path/nee.rs`'s delta-light
//! shadow rays): the only unbiased way to see them. Every other configuration is tested against
//! this one.
//!
//! **The lecture's formula.** The plain Monte Carlo estimate of the rendering equation, one
//! direction per vertex with the uniform density p(ω) = 1/2π (1/4π through the sphere):
//!
//! ```text
//! E += T · Le,     T *= f · cos θ / p(ω)
//! ```
//!
//! **When `auto` uses it.** Never: it is the `reference` preset, the oracle of the checks and
//! the report.

use crate::path::nee::delta_lights;
use crate::settings::DirectSamples;
use crate::uniform_direction::sample_without_importance;
use geometry::SpawnPoint;
use glam::Vec3;
use materials::BsdfFlags;
use sampling::Sampler;
use world::{BsdfSlot, CameraRay, RayTally, World};

/// Paths with an unbounded `max_depth` stop after this many vertices: the reference has no
/// roulette, and the energy left after this many bounces is far below any test's noise.
pub const UNBOUNDED_DEPTH_CAP: u32 = 256;

/// What the reference integrator is asked to do.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReferenceSettings {
    /// Largest number of path vertices after the camera (Mitsuba's `max_depth`: 1 shows only
    /// emitters seen directly, 2 adds direct lighting); `None` is unbounded.
    pub max_depth: Option<u32>,
    /// Hide emitters seen directly by the camera, as Mitsuba 3 does: camera rays pass through
    /// area emitters to the first surface that does not emit, and find no environment.
    pub hide_emitters: bool,
    /// Mitsuba's `direct` integrator's sample counts (with `max_depth` 2). The reference takes
    /// no light or BSDF samples, so the counts only say what they leave out: with no light
    /// samples, delta lights; with no BSDF samples, what a delta surface at the first vertex
    /// reflects or transmits.
    pub direct_samples: Option<DirectSamples>,
    /// Mitsuba's volumetric path tracers' rule: a pass straight through a null lobe is not a
    /// path vertex ([`crate::PathSettings::skip_null_vertices`]).
    pub skip_null_vertices: bool,
}

/// Radiance (W m⁻² sr⁻¹, RGB) arriving at the camera along `ray`, one path's estimate.
///
/// Per vertex it draws, in this order, one 1D sample (delta lobe choice) and one 2D sample
/// (direction), whether or not they are used, so the dimension order is fixed.
pub fn radiance(
    world: &World,
    camera_ray: CameraRay,
    sampler: &mut impl Sampler,
    settings: &ReferenceSettings,
    counters: &mut impl RayTally,
) -> Vec3 {
    let max_depth = settings.max_depth.unwrap_or(UNBOUNDED_DEPTH_CAP);
    let mut radiance = Vec3::ZERO;
    let mut throughput = Vec3::ONE;
    let CameraRay {
        mut ray, mut t_max, ..
    } = camera_ray;
    // Whether every bounce so far was by a delta lobe: emission found next is seen by the shading
    // normal, as the path tracer sees what neither light sampling nor light tracing reaches.
    let mut seen_through_delta = true;
    let mut slot = BsdfSlot::default();
    // The number of the vertex the ray is about to find (passes through null lobes do not count
    // with `skip_null_vertices`).
    let mut depth = 1;
    loop {
        let hidden = depth == 1 && settings.hide_emitters;
        let found = if hidden {
            world.intersect_past_emitters(
                &CameraRay {
                    ray,
                    t_max,
                    ..camera_ray
                },
                counters,
                &mut slot,
            )
        } else {
            world.intersect_within(&ray, t_max, counters, &mut slot)
        };
        let Some(surface) = found else {
            if !hidden {
                radiance += throughput * world.background(ray.dir);
            }
            break;
        };
        if !hidden {
            radiance += throughput * world.emitted(&surface, -ray.dir, seen_through_delta);
        }
        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        // At the last vertex only a pass through a null lobe goes on.
        let last = depth == max_depth;
        if last && !(settings.skip_null_vertices && surface.bsdf.flags().contains(BsdfFlags::NULL))
        {
            break;
        }
        let point = SpawnPoint::of(&surface.hit);
        let wo = surface.frame.to_local(-ray.dir);

        let first_direct = settings.direct_samples.filter(|_| depth == 1);
        if !last && first_direct.is_none_or(|s| s.light > 0) {
            radiance += throughput * delta_lights(world, &surface, &point, wo, counters);
        }

        let Some(step) = sample_without_importance(surface.bsdf, wo, u_lobe, u_dir) else {
            break;
        };
        let passes_null = settings.skip_null_vertices && step.is_null;
        if last && !passes_null {
            break;
        }
        if step.is_delta && first_direct.is_some_and(|s| s.bsdf == 0) {
            break;
        }
        seen_through_delta &= step.is_delta;
        let (wi, weight) = (step.wi, step.weight);
        throughput *= weight;
        if throughput == Vec3::ZERO {
            break;
        }
        ray = point.spawn(surface.frame.to_world(wi));
        t_max = f32::INFINITY;
        depth += u32::from(!passes_null);
    }
    radiance
}
