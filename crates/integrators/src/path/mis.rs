//! Multiple importance sampling between next event estimation's light sample and the BSDF
//! sample that continues the walk.
//!
//! **What it is.** A light that both strategies can reach is counted by both, each sample
//! weighted so that the weights of the two strategies sum to one for every path: light sampling
//! wins for small lights on rough surfaces, BSDF sampling for large lights on glossy ones, and
//! the weights keep the better of the two at every vertex. The light sample's weight is
//! [`PathIntegrator::light_sample_weight`]; emission found by the BSDF ray gets
//! [`PathIntegrator::emission_found`]'s (and [`PathIntegrator::background_found`]'s). Without
//! MIS ([`Mis::Off`]) emission that light sampling could have found counts zero, the lecture's
//! split; emission it could not have found (seen from the camera, after a delta bounce, from a
//! delta light) counts in full either way. The heuristics themselves are
//! [`sampling::mis`].
//!
//! **The lecture's formula.** A sample drawn by strategy a with density p_a, which strategy b
//! would have drawn with density p_b, is weighted by the balance heuristic (the lecture's
//! `Mis2`) or the power heuristic; with n_a and n_b samples of each (Mitsuba's `direct`
//! integrator), over n · p:
//!
//! ```text
//! w_a = n_a p_a / (n_a p_a + n_b p_b)        w_a = (n_a p_a)² / ((n_a p_a)² + (n_b p_b)²)
//! ```
//!
//! The light strategy's density per steradian includes the light selection probability. A light
//! that light sampling never chooses (one [left to BSDF
//! samples](lights::Light::left_to_bsdf_samples)) has density 0 there, so the BSDF sample that
//! finds it gets weight 1; an environment map's density is its [compensated
//! copy's](lights::Light::compensated), the form light sampling samples it in.
//!
//! **When `auto` uses it.** The power heuristic wherever lights are sampled and some light can
//! be hit by a BSDF sample (an area light or an environment); off where every light is a delta
//! light, which no BSDF sample can hit.

use super::PathIntegrator;
use crate::light_selection::ChosenLight;
use crate::settings::Mis;
use crate::uniform_direction::uniform_direction_pdf;
use glam::Vec3;
use sampling::mis::{balance_heuristic, power_heuristic};
use world::{SurfaceHit, World};

/// How many samples of each strategy are combined at a vertex, for the MIS weights.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StrategyCounts {
    /// Light samples at the vertex.
    pub light: f32,
    /// BSDF samples at the vertex.
    pub bsdf: f32,
}

/// The walk's counts: one light sample and one BSDF sample per vertex.
pub(crate) const ONE_EACH: StrategyCounts = StrategyCounts {
    light: 1.0,
    bsdf: 1.0,
};

/// What the walk remembers about the vertex it just left, to weight emission it finds.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PreviousVertex {
    /// Where the vertex is (world space).
    pub p: Vec3,
    /// Density per steradian of the direction that was sampled there.
    pub pdf_dir: f32,
    /// True at the camera and after a delta bounce: light sampling could not have found this
    /// emission, so it counts in full.
    pub delta: bool,
}

impl PathIntegrator {
    /// The environment's radiance found by a ray that left `previous` in the unit direction
    /// `dir`, times `throughput` and its MIS weight.
    #[inline(always)]
    pub(crate) fn background_found(
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
            world.environment().map_or(0.0, |e| {
                self.sampled_lights(world)[e as usize].pdf_li_environment(dir)
            })
        });
        throughput * background * weight
    }

    /// The emission of `surface` towards `-dir` found by a ray that left `previous`, times
    /// `throughput` and its MIS weight; `seen_through_delta` as [`World::emitted`] takes it.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn emission_found(
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
            self.sampled_lights(world)[light as usize].pdf_li_surface(
                previous.p,
                surface.hit.p,
                surface.hit.ng,
                surface.hit.time,
            )
        });
        throughput * emitted * weight
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

    /// Weight of the light sample `chosen` at `surface` seen from `wo` (local frame), against
    /// `counts` samples of each strategy: 1 for a delta light (no BSDF sample can find it) and
    /// without MIS, the MIS weight of the light strategy otherwise, against the density with
    /// which the walk's next direction (BSDF-sampled, or uniform) would have found it.
    #[inline(always)]
    pub(crate) fn light_sample_weight(
        &self,
        chosen: &ChosenLight,
        surface: &SurfaceHit<'_>,
        wo: Vec3,
        counts: StrategyCounts,
    ) -> f32 {
        if chosen.sample.is_delta {
            return 1.0;
        }
        let pdf_direction = if self.settings.sample_bsdf {
            chosen.pdf_bsdf_solid_angle
        } else {
            uniform_direction_pdf(surface.bsdf, wo, chosen.wi_local)
        };
        self.heuristic(counts.light, chosen.pdf_for_mis, counts.bsdf, pdf_direction)
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
