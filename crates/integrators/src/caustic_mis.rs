//! Caustics one bounce from the camera, weighted between the path tracer and the light tracer.
//!
//! **What it is.** A caustic seen on the first surface the camera sees (camera → x₁ → a chain of
//! delta bounces → light, x₁ non-delta) is found by both strategies: the path tracer when the
//! direction it samples at x₁ runs through the chain into the light, the light tracer by
//! following the light through the chain and joining x₁ to the camera. Neither is best
//! everywhere. On a diffuse x₁ the light tracer wins by orders of magnitude; on a glossy one (a
//! rough metal that mirrors a light through glass) the path tracer's BSDF sample follows the
//! narrow lobe, while the light tracer's connection lands on it by chance. Each such path is
//! therefore weighted by the power heuristic between the two strategies' densities, as
//! bidirectional path tracing weighs its strategies (Veach 1997, ch. 10). Longer caustic paths
//! (x₁ → x₂ → … → chain → light) stay the light tracer's alone: the path tracer drops them.
//!
//! **The formula** (beyond the lecture). Both densities are of the pair (x₁, y), y the point on
//! the light, per unit area at each. The chain between them contributes the same generalised
//! geometry term to both, which cancels from their ratio:
//!
//! ```text
//! p_PT ∝ W(x₁) |cos θ_cam| · p_bsdf(ω₁) / |cos θ₁|      p_LT ∝ P(light) p_A(y) · p_emit(ω_y) / |cos θ_y|
//! ```
//!
//! W(x₁) = 1 / (A cos³θ r²) is the camera's importance at x₁ (the density per unit area of the
//! camera ray's end, over |cos θ_cam| at x₁ towards the camera); p_bsdf(ω₁) / |cos θ₁| converts
//! x₁'s sampled direction to area at the light; P(light) p_A(y) is the light tracer's choice of
//! the light and its point; p_emit = cos θ_y / π is its cosine-distributed direction. With
//! r = p_LT / p_PT and ρ light paths per camera sample
//! ([`crate::LightTracing::paths_per_sample`]), the power heuristic over the two strategies'
//! sample counts gives
//!
//! ```text
//! w_LT = (ρ r)² / (1 + (ρ r)²)        w_PT = 1 − w_LT
//! ```
//!
//! Each side computes the same function of the same path, so the weights sum to one and the
//! estimate stays unbiased; what the densities leave out (the delta lobes' choice
//! probabilities, roulette, a refraction's η² in the geometry term) only changes how well they
//! split the paths. With [`crate::PathSettings::sample_bsdf`] off the path tracer's directions
//! are uniform and the light tracer keeps every caustic path.
//!
//! **When `auto` uses it.** Wherever it uses light tracing.

use crate::caster_cones::CasterCones;
use glam::Vec3;
use sampling::distribution::CdfTable;
use std::f32::consts::FRAC_1_PI;
use world::World;

/// How the path tracer counts emission that ends a caustic chain: a first vertex after the
/// camera left by a non-delta lobe, then a delta bounce into a light (the paths the light tracer
/// contributes).
#[derive(Clone, Debug)]
pub(crate) enum CausticPaths {
    /// In full: no light tracer takes them.
    Kept,
    /// Not at all: a light tracer takes each whole (light tracing without BSDF sampling), or
    /// `auto`'s pilot estimates their variance apart.
    Left,
    /// Shared with the light tracer: one bounce from the camera by the weights of this module,
    /// longer ones left to it whole (boxed: the path tracer reads it only at a caustic's end).
    Shared(Box<LightPathStarts>),
}

impl CausticPaths {
    /// The path tracer's share of the emission of `world`'s light `light` met at `hit` at the
    /// end of a caustic chain, reached along `dir`: 1 − [`LightPathStarts::light_tracer_weight`]
    /// for a caustic one bounce from the camera (`through_deltas`: every bounce after the first
    /// by a delta lobe; `camera_side` as [`camera_side`] gives it for the path's first vertex),
    /// else 0 or 1 as the variant says.
    #[inline]
    pub(crate) fn share(
        &self,
        world: &World,
        light: u32,
        hit: &geometry::Hit,
        dir: Vec3,
        through_deltas: bool,
        camera_side: f32,
    ) -> f32 {
        match self {
            CausticPaths::Kept => 1.0,
            CausticPaths::Left => 0.0,
            CausticPaths::Shared(_) if !through_deltas => 0.0,
            CausticPaths::Shared(starts) => {
                let light_side = starts.density_at(world, light, (hit.p, hit.ng, -dir), hit.time);
                1.0 - starts.light_tracer_weight(light_side, camera_side)
            }
        }
    }
}

/// The light tracer's choice of the light a path starts on: the area lights with power, by
/// power times selection weight (as light sampling chooses them).
#[derive(Clone, Debug)]
pub(crate) struct LightPathStarts {
    /// Indices into [`World::lights`] of the lights chosen among.
    lights: Vec<u32>,
    /// The choice among `lights`.
    selection: CdfTable,
    /// The probability of each light of the world (0 for those not chosen among).
    pmf_by_light: Box<[f32]>,
    /// Light paths traced per camera sample, ρ.
    paths_per_sample: f32,
    /// Where light paths aim besides the cosine distribution; `None` without casters.
    casters: Option<CasterCones>,
}

impl LightPathStarts {
    /// The choice among `world`'s area lights, for `paths_per_sample` light paths per camera
    /// sample; `None` without an area light with power.
    pub(crate) fn new(world: &World, paths_per_sample: f32) -> Option<Self> {
        let lights: Vec<u32> = (0..world.lights().len() as u32)
            .filter(|&i| world.lights()[i as usize].is_area())
            .collect();
        let powers: Vec<f32> = lights
            .iter()
            .map(|&i| world.lights()[i as usize].power() * world.light_weights()[i as usize])
            .collect();
        let selection = CdfTable::new(&powers).ok()?;
        let mut pmf_by_light = vec![0.0; world.lights().len()].into_boxed_slice();
        for (k, &light) in lights.iter().enumerate() {
            pmf_by_light[light as usize] = selection.pmf(k);
        }
        Some(Self {
            lights,
            selection,
            pmf_by_light,
            paths_per_sample,
            casters: CasterCones::new(world),
        })
    }

    /// The light `u` ∈ [0, 1) chooses (index into [`World::lights`]) and its probability.
    #[inline]
    pub(crate) fn sample(&self, u: f32) -> (u32, f32) {
        let (chosen, pmf, _) = self.selection.sample(u);
        (self.lights[chosen], pmf)
    }

    /// Whether there is more than one light to choose from, so a path draws a number for it.
    pub(crate) fn chooses(&self) -> bool {
        self.lights.len() > 1
    }

    /// The light tracer's density of a path's start at the point `p_light` of `world`'s light
    /// `light` with geometric normal `n_light` at `time`, leaving along `w`: the light's
    /// probability times its density per unit area (m⁻²) times the direction's density over the
    /// cosine distribution's ([`Self::aim`]).
    #[inline]
    pub(crate) fn density_at(
        &self,
        world: &World,
        light: u32,
        (p_light, n_light, w): (Vec3, Vec3, Vec3),
        time: f32,
    ) -> f32 {
        let aim = self.aim(p_light, n_light, w);
        self.density_aimed(world, light, n_light, time, aim)
    }

    /// [`Self::density_at`] for a start whose direction's density over the cosine
    /// distribution's is `aim` (from [`Self::aim`]), for a caller that has it already.
    #[inline]
    pub(crate) fn density_aimed(
        &self,
        world: &World,
        light: u32,
        n_light: Vec3,
        time: f32,
        aim: f32,
    ) -> f32 {
        let pmf = self.pmf_by_light[light as usize];
        if pmf == 0.0 {
            return 0.0;
        }
        let area = world.lights()[light as usize].pdf_emission_area(n_light, time);
        pmf * area * aim
    }

    /// The density of a light path's direction `w` from `p_light` (normal `n_light`) over the
    /// cosine distribution's ([`CasterCones::relative_density`]); 1 without casters.
    #[inline]
    pub(crate) fn aim(&self, p_light: Vec3, n_light: Vec3, w: Vec3) -> f32 {
        self.casters
            .as_ref()
            .map_or(1.0, |casters| casters.relative_density(p_light, n_light, w))
    }

    /// The casters light paths aim at, if any.
    #[inline]
    pub(crate) fn casters(&self) -> Option<&CasterCones> {
        self.casters.as_ref()
    }

    /// The light tracer's weight w_LT for a caustic path whose light side is `light_side` (from
    /// [`Self::density_at`]) and whose camera side is `camera_side` (from [`camera_side`]), at
    /// this tracer's light paths per camera sample; the path tracer's is 1 minus it. 0 where the
    /// light tracer cannot start the path, 1 where the path tracer cannot sample it.
    #[inline]
    pub(crate) fn light_tracer_weight(&self, light_side: f32, camera_side: f32) -> f32 {
        power_heuristic_weight(self.paths_per_sample * light_side, camera_side)
    }
}

/// The path tracer's side of the densities' ratio at x₁ (see the module documentation):
/// `importance` · |cos θ_cam| · p_bsdf / |cos θ₁|, from the camera's importance at x₁, the
/// cosine there towards the camera (geometric normal), the density per steradian of the
/// direction sampled at x₁ and its cosine (shading normal).
#[inline]
pub(crate) fn camera_side(importance: f32, cos_camera: f32, pdf_bsdf: f32, cos_bsdf: f32) -> f32 {
    importance * cos_camera * pdf_bsdf / cos_bsdf
}

/// The ratio r = p_LT / p_PT of the light tracer's density of a caustic path to the path
/// tracer's, per path, from the two sides as [`LightPathStarts::light_tracer_weight`] takes
/// them; 0 where either density is 0 or the ratio is not finite (the path tracer cannot find the
/// path, or the light tracer cannot start it).
#[inline]
pub(crate) fn density_ratio(light_side: f32, camera_side: f32) -> f32 {
    let ratio = FRAC_1_PI * light_side / camera_side;
    if ratio.is_finite() { ratio } else { 0.0 }
}

/// The power heuristic's w_LT = (ρ r)² / (1 + (ρ r)²), from a light side already scaled by ρ.
#[inline]
fn power_heuristic_weight(light_side: f32, camera_side: f32) -> f32 {
    // 1 / (ρ r) = p_PT / (ρ p_LT); the weight is 1 / (1 + 1 / (ρ r)²), finite at both ends.
    let inverse = camera_side / (FRAC_1_PI * light_side);
    let weight = 1.0 / (1.0 + inverse * inverse);
    if weight.is_nan() { 0.0 } else { weight }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weights_follow_the_densities_and_stay_finite() {
        // Equal densities share the path; the light side's density is p_A / π.
        assert!((power_heuristic_weight(std::f32::consts::PI, 1.0) - 0.5).abs() < 1e-6);
        // Ten times the density: the power heuristic's 100 / 101.
        let w = power_heuristic_weight(10.0 * std::f32::consts::PI, 1.0);
        assert!((w - 100.0 / 101.0).abs() < 1e-6, "{w}");
        assert_eq!(power_heuristic_weight(0.0, 1.0), 0.0);
        assert_eq!(power_heuristic_weight(1.0, 0.0), 1.0);
        assert_eq!(power_heuristic_weight(0.0, 0.0), 0.0);
        assert_eq!(power_heuristic_weight(f32::INFINITY, 1.0), 1.0);
        assert_eq!(power_heuristic_weight(1.0, f32::INFINITY), 0.0);
    }

    #[test]
    fn fewer_light_paths_per_sample_weigh_the_light_tracer_less() {
        let starts = |paths_per_sample| LightPathStarts {
            lights: vec![0],
            selection: CdfTable::new(&[1.0]).expect("one weight"),
            pmf_by_light: Box::new([1.0]),
            paths_per_sample,
            casters: None,
        };
        let pi = std::f32::consts::PI;
        // Equal densities per path: one path per sample shares, one per four gives the light
        // tracer (1/4)² / (1 + (1/4)²) = 1/17.
        assert!((starts(1.0).light_tracer_weight(pi, 1.0) - 0.5).abs() < 1e-6);
        let w = starts(0.25).light_tracer_weight(pi, 1.0);
        assert!((w - 1.0 / 17.0).abs() < 1e-6, "{w}");
        // Four times the density per path at a quarter of the paths: shared again.
        assert!((starts(0.25).light_tracer_weight(4.0 * pi, 1.0) - 0.5).abs() < 1e-6);
    }
}
