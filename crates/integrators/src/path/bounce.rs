//! The walk's bounce: the BSDF sample for the next direction, then Russian roulette.
//!
//! **What it is.** The next direction is drawn by the BSDF's own sampling routine
//! ([`materials::Bsdf::sample`], importance sampling f · cos θ), or uniformly over the side the
//! path arrived from with [`crate::PathSettings::sample_bsdf`] off; the path's throughput takes
//! its weight f · |cos θ| / pdf. From the roulette's start depth on, the path then survives with
//! a probability that follows its throughput, and a survivor's throughput is divided by it, so
//! the estimate stays unbiased while dim paths stop early.
//!
//! **The lecture's formula.** T *= f · cos θ / pdf(ω) for the sampled ω; then, with
//! p = clamp(max(T_r, T_g, T_b) · η², 0, 1), continue with probability p and T /= p (η² undoes
//! the radiance scaling of refractions, pbrt-v4's `etaScale`).
//!
//! **When `auto` uses it.** BSDF sampling always, as every preset but `reference`; Russian
//! roulette from the scene's `rr_depth` on (Mitsuba's, 5 by default), switched off as one of
//! `auto`'s trials where `max_depth` bounds the paths beyond that depth.

use super::PathIntegrator;
use super::state::PathState;
use crate::next_direction::NextDirection;
use crate::optional_draw::next_1d_if;
use crate::uniform_direction::sample_without_importance;
use geometry::{Ray, SpawnPoint};
use glam::Vec3;
use materials::Bsdf;
use sampling::Sampler;
use world::SurfaceHit;

impl PathIntegrator {
    /// The next direction at `surface` seen from `wo` (local frame), drawing its numbers (the
    /// lobe choice where some material needs one, then the direction): by the BSDF's sampling
    /// routine, or uniform with [`crate::PathSettings::sample_bsdf`] off.
    #[inline(always)]
    pub(crate) fn sample_direction(
        &self,
        surface: &SurfaceHit<'_>,
        wo: Vec3,
        sampler: &mut impl Sampler,
    ) -> Option<NextDirection> {
        let u_lobe = next_1d_if(sampler, self.draws_lobe_choice);
        let u_dir = sampler.next_2d();
        if self.settings.sample_bsdf {
            // Speed only: a diffuse BSDF's sample (a cosine-weighted direction) inlined, which
            // with the mesh-light arm of `light_selection::evaluate` is worth 6-8% of the
            // Cornell box's samples per second (`cargo bench -p render --bench render --
            // samples/cbox`); inside `Bsdf::sample`'s dispatch it measured no gain.
            let sampled = match surface.bsdf {
                Bsdf::Diffuse(diffuse) => diffuse.sample(wo, u_dir),
                bsdf => bsdf.sample(wo, u_lobe, u_dir),
            };
            sampled.map(NextDirection::from)
        } else {
            sample_without_importance(surface.bsdf, wo, u_lobe, u_dir)
        }
    }

    /// The walk's step from the vertex at `surface` (whose point is `point`, seen from `wo`,
    /// local frame): the BSDF sample for the next direction, then Russian roulette; the ray that
    /// continues `path`, or `None` where it ends. At the `last` vertex only a pass through a
    /// null lobe goes on.
    #[inline(always)]
    pub(super) fn next_ray(
        &self,
        path: &mut PathState,
        surface: &SurfaceHit<'_>,
        point: &SpawnPoint,
        wo: Vec3,
        last: bool,
        sampler: &mut impl Sampler,
    ) -> Option<Ray> {
        path.chosen_delta = None;
        let next = self.sample_direction(surface, wo, sampler)?;
        let passes_null = self.settings.skip_null_vertices && next.is_null;
        if last && !passes_null {
            return None;
        }
        path.bounce(&next, surface.hit.p);
        if !self.survives_roulette(path, sampler) || path.throughput == Vec3::ZERO {
            return None;
        }
        path.depth += u32::from(!passes_null);
        Some(point.spawn_unit(surface.frame.to_world(next.wi)))
    }

    /// Russian roulette on `path` after a bounce: from the start depth on, one number decides
    /// whether it survives with probability clamp(max(r, g, b) of throughput × η²) (the
    /// throughput with path reuse's prefix), and a survivor's throughput is divided by it.
    /// True when the path goes on.
    #[inline(always)]
    fn survives_roulette(&self, path: &mut PathState, sampler: &mut impl Sampler) -> bool {
        let Some(roulette) = self.settings.russian_roulette else {
            return true;
        };
        if path.depth < roulette.start_depth {
            return true;
        }
        let u_survive = sampler.next_1d();
        let survival =
            ((path.throughput * path.prefix).max_element() * path.eta_scale).clamp(0.0, 1.0);
        if u_survive >= survival {
            return false;
        }
        path.throughput /= survival;
        true
    }
}
