//! Light selection for next event estimation: which light a shadow ray goes to, and the point
//! on it.
//!
//! **What it is.** [Next event estimation](crate::path::nee) sends one shadow ray per vertex,
//! so with several lights it must choose one. Any choice is unbiased if the sample is divided by
//! the probability of the choice; the closer the choice follows each light's contribution, the
//! lower the variance.
//!
//! **The lecture's formula.** The dice example: estimate 6·D1 + D2 by rolling one die, chosen
//! with probability p and weighted by 1/p. For lights,
//!
//! ```text
//! L ≈ L_k(x) / P(k)
//! ```
//!
//! with P(k) a fixed probability mass function, uniform 1/N or proportional to power
//! Φ_k / Σ_j Φ_j ([`power`]), or resampled from several candidates by their estimated
//! contribution at the shading point ([`ris`]); or no choice at all, one sample of every light
//! ([`every`]).
//!
//! **When `auto` uses it.** Uniform choice for one light (there is nothing to choose), power for
//! several; RIS, uniform choice and every light are trials of `auto`'s pilot wherever there are
//! several lights, kept when measured more efficient.
//!
//! Each choice is followed by one point on the chosen light and the BSDF evaluated towards it
//! ([`evaluate`]), which is what the shadow ray's contribution needs.

pub mod every;
mod power;
mod ris;

use glam::{Vec2, Vec3};
use lights::LightSelection;
use lights::{Light, LightSample, LightSelector};
use materials::Bsdf;
use std::ops::Index;
use world::SurfaceHit;

/// The scene's lights as light sampling samples them: the world's, with one replaced by the
/// copy light sampling uses instead ([`Light::compensated`]: an environment map under MIS).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SampledLights<'a> {
    /// The world's lights.
    pub lights: &'a [Light],
    /// The index of the light replaced and its replacement.
    pub replaced: Option<(usize, &'a Light)>,
}

impl<'a> SampledLights<'a> {
    /// `lights` with light `index` replaced by `light`, for `replaced` = `(index, light)`.
    #[inline(always)]
    pub fn new(lights: &'a [Light], replaced: &'a Option<(usize, Box<Light>)>) -> Self {
        Self {
            lights,
            replaced: replaced.as_ref().map(|(index, light)| (*index, &**light)),
        }
    }
}

impl Index<usize> for SampledLights<'_> {
    type Output = Light;

    #[inline(always)]
    fn index(&self, index: usize) -> &Light {
        match self.replaced {
            Some((replaced, light)) if replaced == index => light,
            _ => &self.lights[index],
        }
    }
}

/// A light sample chosen for a shadow ray, with the BSDF already evaluated towards it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ChosenLight {
    /// The sampled direction and radiance.
    pub sample: LightSample,
    /// f(wo, wi) · |cos θi| towards the sample, RGB.
    pub f_cos: Vec3,
    /// Factor that makes `f_cos · radiance · weight` an unbiased estimate of direct light:
    /// 1 / (pmf · pdf) for a fixed pmf, the RIS contribution weight W for RIS.
    pub weight: f32,
    /// The light strategy's density per steradian used in MIS weights: pmf · pdf_solid_angle of
    /// the selection pmf (for RIS, of its power-proportional candidate source).
    pub pdf_for_mis: f32,
    /// The direction to the light in the shading frame (unit length).
    pub wi_local: Vec3,
    /// The BSDF's sampling density per steradian towards the light (computed with f, which
    /// shares its work; what MIS weighs the light sample against).
    pub pdf_bsdf_solid_angle: f32,
}

/// The light samples of one vertex as `mode` says, passed to `visit`: a light and a point on
/// it (or, for [`LightSelection::All`], a point on each light), from the shading point of
/// `surface` with outgoing direction `wo` (local frame). `u_choice` (the light choice, and
/// RIS's reservoir choice) and `u_point` come from the sampler, each from its own dimension.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn sample_lights(
    mode: LightSelection,
    selector: &LightSelector,
    lights: &SampledLights<'_>,
    surface: &SurfaceHit<'_>,
    wo: Vec3,
    u_choice: Vec2,
    u_point: Vec2,
    mut visit: impl FnMut(ChosenLight),
) {
    let chosen = match mode {
        LightSelection::Uniform | LightSelection::Power => {
            power::choose(selector, lights, surface, wo, u_choice.x, u_point)
        }
        LightSelection::Ris { candidates } => {
            ris::choose(candidates, selector, lights, surface, wo, u_choice, u_point)
        }
        LightSelection::All => {
            if let LightSelector::Every { sampled } = selector {
                every::sample_each(sampled, lights, surface, wo, u_point, visit);
            }
            return;
        }
    };
    if let Some(chosen) = chosen {
        visit(chosen);
    }
}

/// One candidate: a point on `light` by `u_point` and the BSDF of `surface` towards it, seen
/// from `wo` (local frame); `None` if it carries nothing. `weight` is left 0 for the caller,
/// whose choice decides it; `pdf_for_mis` is `pmf` times the point's density per steradian.
#[inline(always)]
fn evaluate(
    light: &Light,
    pmf: f32,
    surface: &SurfaceHit<'_>,
    wo: Vec3,
    u_point: Vec2,
) -> Option<ChosenLight> {
    // Speed only (see `path/bounce.rs`): an area light on a mesh seen from a diffuse surface
    // inlined. Each arm finishes on its own: joined, both samples would go through the memory
    // the out-of-line call returns in, and the inline one, stored and reloaded in pieces that
    // straddle how it was stored, would stall.
    match light {
        Light::Mesh(mesh) => with_bsdf(mesh.sample_li(surface.hit.p, u_point)?, pmf, surface, wo),
        light => with_bsdf(
            light.sample_li(surface.hit.p, u_point, surface.hit.time)?,
            pmf,
            surface,
            wo,
        ),
    }
}

/// [`evaluate`] once the light has given its `sample`.
#[inline(always)]
fn with_bsdf(
    sample: LightSample,
    pmf: f32,
    surface: &SurfaceHit<'_>,
    wo: Vec3,
) -> Option<ChosenLight> {
    let wi = surface.frame.to_local(sample.wi);
    let (f, pdf_bsdf_solid_angle) = match surface.bsdf {
        Bsdf::Diffuse(diffuse) => diffuse.eval_with_pdf(wo, wi),
        bsdf => bsdf.eval_with_pdf(wo, wi),
    };
    let f_cos = f * wi.z.abs();
    if f_cos == Vec3::ZERO || sample.radiance == Vec3::ZERO {
        return None;
    }
    Some(ChosenLight {
        sample,
        f_cos,
        weight: 0.0,
        pdf_for_mis: pmf * sample.pdf_solid_angle,
        wi_local: wi,
        pdf_bsdf_solid_angle,
    })
}
