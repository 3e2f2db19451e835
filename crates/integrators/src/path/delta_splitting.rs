//! Delta splitting: at a vertex seen from the camera through delta bounces only, the emission
//! seen through every delta lobe of a BSDF that chooses among lobes, one ray per lobe, instead
//! of through the one lobe the bounce chose.
//!
//! **What it is.** A glass surface reflects a few percent of the light and refracts the rest; a
//! plastic's coat reflects a few percent over its diffuse base. A path chooses one lobe and
//! divides by the probability of the choice, so the reflection of a small bright light in a
//! glass ball or a plastic box, seen from the camera, is found by one sample in twenty with
//! twenty times its value: a firefly. Neither light sampling nor the light tracer can find such
//! paths (camera → delta lobes → light): both Strata's path tracer and Mitsuba's find them by
//! the choice alone. Splitting traces a ray along each delta lobe the bounce did not choose and
//! adds the emission it meets with the lobe's whole weight; the chosen delta lobe's emission is
//! counted at the next vertex scaled by its choice probability, so each lobe's emission is
//! counted once in expectation and the estimate stays unbiased. Only emitters met are counted
//! this way: light from the environment is smooth and stays with the chosen lobe, as does
//! everything found beyond the next vertex.
//!
//! **The formula.** For delta lobes k with throughputs w_k and choice probabilities P_k, the
//! emission seen through them is Σ_k w_k Le(ω_k). With lobe c chosen,
//!
//! ```text
//! estimate = (w_c / P_c) · P_c · Le(ω_c) + Σ_{k ≠ c} w_k Le(ω_k)
//! ```
//!
//! and E over the choice of c gives Σ_k P_k w_k Le(ω_k) + Σ_k (1 − P_k) w_k Le(ω_k) = Σ_k w_k
//! Le(ω_k). The variance of the choice is gone from the emission; a ray per unchosen lobe is
//! its cost.
//!
//! **When `auto` uses it.** In its base wherever some material chooses between a delta lobe
//! and another (glass, smooth plastic); it costs a ray only where the camera sees one.

use super::PathIntegrator;
use super::mis::{ONE_EACH, PreviousVertex};
use super::state::PathState;
use geometry::SpawnPoint;
use glam::Vec3;
use world::{BsdfSlot, RayTally, SurfaceHit, World};

impl PathIntegrator {
    /// Whether the walk splits at `surface`: splitting is on, the path got here through delta
    /// bounces only, and the BSDF chooses between a delta lobe and another lobe.
    #[inline(always)]
    pub(super) fn splits_at(&self, surface: &SurfaceHit<'_>, path: &PathState) -> bool {
        self.settings.delta_splitting
            && path.seen_through_delta
            && surface.bsdf.flags().chooses_delta_lobe()
    }

    /// The emission seen through the delta lobes of `surface` (whose point is `point`, seen
    /// from `wo`, local frame) that the bounce did not choose, each by a ray of its own and
    /// times `throughput` (the path's before the bounce) and the lobe's whole weight, added to
    /// `path`'s estimate; and the share of the next vertex's emission the walk still counts,
    /// the chosen delta lobe's probability (1 after a non-delta bounce).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn split_delta_lobes(
        &self,
        world: &World,
        surface: &SurfaceHit<'_>,
        point: &SpawnPoint,
        wo: Vec3,
        throughput: Vec3,
        path: &mut PathState,
        counters: &mut impl RayTally,
    ) {
        let previous = PreviousVertex {
            p: surface.hit.p,
            pdf_dir: 1.0,
            delta: true,
        };
        let mut slot = BsdfSlot::default();
        for lobe in surface.bsdf.delta_lobes(wo).into_iter().flatten() {
            // One delta lobe per side of the surface: the chosen one is on its side.
            if path
                .chosen_delta
                .is_some_and(|chosen| chosen.z * lobe.wi.z > 0.0)
            {
                path.emission_scale = lobe.pdf_solid_angle;
                continue;
            }
            let ray = point.spawn_unit(surface.frame.to_world(lobe.wi));
            let Some(found) = world.intersect(&ray, counters, &mut slot) else {
                continue;
            };
            if found.light.is_some() {
                let weight = throughput * lobe.f * lobe.wi.z.abs();
                path.radiance +=
                    self.emission_found(world, &found, ray.dir, &previous, true, ONE_EACH, weight);
            }
        }
    }
}
