//! Light selection by a fixed probability mass function: power-proportional, or uniform.
//!
//! **What it is.** A light is chosen with a probability that does not depend on the shading
//! point, from the alias table of [`lights::LightSelector`]: proportional to each light's
//! emitted power times its `sampling_weight` (`LightSelection::Power`), or to the weights
//! alone (`LightSelection::Uniform`, equal for lights without one). Bright lights get more
//! shadow rays; the choice costs one table look-up.
//!
//! **The lecture's formula.** Pick a light with probability proportional to its estimated
//! contribution, here its power, and divide by that probability:
//!
//! ```text
//! P(k) = Φ_k / Σ_j Φ_j,     L ≈ Le · f · cos θ / (P(k) · pdf_solid_angle)
//! ```
//!
//! **When `auto` uses it.** Uniform with one light, power-proportional with several (the `nee`,
//! `mis` presets and `auto`'s base); uniform choice among several lights is one of `auto`'s
//! trials.

use super::{ChosenLight, SampledLights, evaluate};
use glam::{Vec2, Vec3};
use lights::LightSelector;
use world::SurfaceHit;

/// The light `selector`'s table picks with `u_choice`, and a point on it by `u_point`, seen
/// from `surface` in the direction `wo` (local frame); the weight is 1 / (pmf · pdf per
/// steradian). `None` where the sample carries nothing.
#[inline(always)]
pub(super) fn choose(
    selector: &LightSelector,
    lights: &SampledLights<'_>,
    surface: &SurfaceHit<'_>,
    wo: Vec3,
    u_choice: f32,
    u_point: Vec2,
) -> Option<ChosenLight> {
    let (index, pmf) = selector.select(u_choice);
    let candidate = evaluate(&lights[index], pmf, surface, wo, u_point)?;
    let pdf = pmf * candidate.sample.pdf_solid_angle;
    Some(ChosenLight {
        weight: 1.0 / pdf,
        pdf_for_mis: pdf,
        ..candidate
    })
}
