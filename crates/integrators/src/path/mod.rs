//! The variance-reduction path tracer's walk: every technique of the lecture as a switch in
//! [`crate::PathSettings`], each unbiased on its own and in any combination. This file is the
//! walk alone, its steps named; each step is a technique of its own file: emission weighted
//! against light sampling (`mis.rs`), next event estimation (`nee.rs`), the BSDF sample and
//! Russian roulette (`bounce.rs`), path reuse's split ([`crate::path_reuse`]) and Mitsuba's
//! `direct` integrator (`direct.rs`). The entry points and the sampler dimensions drawn are in
//! `integrator.rs`, what the walk carries in `state.rs`.
//!
//! **The lecture's formula** (iterative): T = 1, E = 0; at each vertex E += T · (Le · w_mis +
//! direct), then T *= f · cos θ / pdf(ω) for the next direction ω, and from the roulette's start
//! depth on the path survives with probability p = clamp(max(T_r, T_g, T_b) · η², 0, 1), T /= p.
//!
//! **When `auto` uses it.** Always: `auto` and every preset but `reference` run this walk, with
//! the steps the scene can use switched on (see each step's file).

mod bounce;
mod delta_splitting;
mod integrator;
pub(crate) mod mis;
pub(crate) mod nee;
mod state;

pub use integrator::PathIntegrator;

use crate::caustic_mis::CausticPaths;
use crate::path_reuse::{ReusablePath, WalkSplit};
use crate::reference::UNBOUNDED_DEPTH_CAP;
use geometry::SpawnPoint;
use materials::BsdfFlags;
use mis::ONE_EACH;
use sampling::Sampler;
use state::PathState;
use world::{BsdfSlot, CameraRay, RayTally, World};

impl PathIntegrator {
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
        let CameraRay {
            mut ray, mut t_max, ..
        } = camera_ray;
        let mut path = PathState::at_camera(ray.origin);
        let mut split = WalkSplit::default();
        loop {
            // Intersect: the camera ray passes hidden emitters, every other ray stops at the
            // first surface.
            let hidden = path.depth == 1 && settings.hide_emitters;
            let found = if hidden {
                world.intersect_past_emitters(
                    &CameraRay {
                        ray,
                        t_max,
                        ..camera_ray
                    },
                    counters,
                    slot,
                )
            } else {
                world.intersect_within(&ray, t_max, counters, slot)
            };

            // Emission seen by the BSDF ray, MIS-weighted: the environment where the ray
            // escapes, else the surface's, unless it ends a caustic chain left to light tracing.
            let Some(surface) = &found else {
                if !hidden {
                    let (previous, throughput) = (&path.previous, path.throughput);
                    path.radiance +=
                        self.background_found(world, ray.dir, previous, ONE_EACH, throughput);
                }
                break;
            };
            let share = match surface.light {
                Some(light) if path.caustic_chain => self.caustic_paths.share(
                    world,
                    light,
                    &surface.hit,
                    ray.dir,
                    path.through_deltas,
                    path.camera_side,
                ),
                _ => 1.0,
            };
            if !hidden && share > 0.0 {
                let (previous, delta) = (&path.previous, path.seen_through_delta);
                let throughput = path.throughput * (share * path.emission_scale);
                path.radiance += self.emission_found(
                    world, surface, ray.dir, previous, delta, ONE_EACH, throughput,
                );
            }
            // The path tracer's side of the weights of caustics it shares with light tracing:
            // the camera's importance at the first vertex.
            if path.depth == 1 && matches!(self.caustic_paths, CausticPaths::Shared(_)) {
                path.camera_side =
                    camera_ray.importance_at(surface.hit.p) * surface.hit.ng.dot(ray.dir).abs();
            }
            // At the last vertex only a pass through a null lobe goes on.
            let last = path.depth == max_depth;
            let passes = |b: BsdfFlags| settings.skip_null_vertices && b.contains(BsdfFlags::NULL);
            if last && !passes(surface.bsdf.flags()) {
                break;
            }
            let wo = surface.frame.to_local(-ray.dir);
            let point = SpawnPoint::of(&surface.hit);

            // Path reuse: keep the first vertex, and at the second restart the estimate.
            if REUSE && split.keep(path.depth, surface, &point, wo, path.radiance) {
                path.restart_at_second_vertex();
            }

            // Mitsuba's `direct` integrator: its samples at the first vertex, and no further.
            if let Some(samples) = settings.direct_samples {
                path.radiance +=
                    self.direct_samples(world, surface, &point, wo, samples, sampler, counters);
                break;
            }

            // Next event estimation, except at the last vertex (one vertex too many there).
            let shadowed = (!last)
                .then(|| self.next_event(world, surface, &point, wo, &mut path, sampler, counters))
                .flatten();

            // Sample the BSDF for the next direction, then Russian roulette.
            let (throughput, splits) = (path.throughput, !last && self.splits_at(surface, &path));
            let next_ray = self.next_ray(&mut path, surface, &point, wo, last, sampler);

            // Delta splitting: the emission seen through the delta lobes not chosen.
            if splits {
                self.split_delta_lobes(world, surface, &point, wo, throughput, &mut path, counters);
            }

            // Trace next event estimation's shadow ray (after the bounce: see `nee.rs`).
            if let Some(direct) = shadowed.and_then(|light| light.unoccluded(world, counters)) {
                path.radiance += direct;
            }
            let Some(next_ray) = next_ray else {
                break;
            };
            ray = next_ray;
            t_max = f32::INFINITY;
        }
        split.finish(path.radiance)
    }
}
