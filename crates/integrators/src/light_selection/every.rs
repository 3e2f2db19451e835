//! Every light sampled at every vertex: no choice at all.
//!
//! **What it is.** Where a scene has a few lights of similar importance (two lamps and a
//! window light), choosing one per vertex adds the variance of the choice: a vertex lit by
//! one lamp is estimated from the other lamp's sample half of the time. Sampling each light
//! once per vertex removes that variance and pays one shadow ray per light instead. All lights
//! take the vertex's one point number: each light's estimate is unbiased alone, so their sum
//! is, and the sampler's dimensions stay those of one light sample (without the choice's).
//! Rotating the number per light (Cranley–Patterson, by multiples of the R2 sequence's step) to
//! decorrelate the lights measured worse with Sobol (the pilot's variance on `gen-1-02` 0.24 →
//! 0.27 of power's, on Veach's scene 0.42 → 0.57): a rotation modulo 1 breaks the net's strata
//! where it wraps.
//!
//! **The lecture's formula.** The dice example with both dice rolled: 6·D1 + D2 estimated by
//! one roll of each, no division by a choice probability,
//!
//! ```text
//! L ≈ Σ_k Le_k · f · cos θ_k / pdf_k(ω_k)
//! ```
//!
//! and in MIS a BSDF sample that finds light k is weighed against that light's one sample, of
//! density `pdf_k` (probability of choosing it: 1).
//!
//! **When `auto` uses it.** One of `auto`'s trials wherever there are two to
//! [`MAX_EVERY_LIGHT`] lights, kept when the pilot measures it more efficient than the
//! power-proportional choice beyond noise (its extra shadow rays count in the cost).

use super::{ChosenLight, SampledLights, evaluate};
use glam::{Vec2, Vec3};
use world::SurfaceHit;

/// The most lights for which `auto` tries sampling every light: beyond, the shadow rays cost
/// more than the choice's variance does.
pub const MAX_EVERY_LIGHT: usize = 8;

/// A sample of each of the `sampled` lights (indices into `lights`) by `u_point`, seen from
/// `surface` in the direction `wo` (local frame), passed to `visit` in that order; each weighted
/// 1 / pdf per steradian. Lights whose sample carries nothing are skipped.
#[inline(always)]
pub(super) fn sample_each(
    sampled: &[u32],
    lights: &SampledLights<'_>,
    surface: &SurfaceHit<'_>,
    wo: Vec3,
    u_point: Vec2,
    mut visit: impl FnMut(ChosenLight),
) {
    for &index in sampled {
        if let Some(sample) = evaluate(&lights[index as usize], 1.0, surface, wo, u_point) {
            visit(ChosenLight {
                weight: 1.0 / sample.sample.pdf_solid_angle,
                ..sample
            });
        }
    }
}
