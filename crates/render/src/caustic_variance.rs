//! For `auto`'s technique pilot: the variance that caustics add to a render without light
//! tracing, estimated from light paths.
//!
//! A path tracer without light tracing finds a caustic (camera → surface → mirror or glass →
//! light) only when a BSDF sample runs through the chain into the light: rarely, and brightly.
//! A pilot of a few samples per pixel mostly misses such samples, so its estimate of the
//! candidate's variance is mostly far too small, which would make switching light tracing off
//! look cheap at no cost in noise. The pilot therefore renders such candidates without those
//! paths ([`PathIntegrator::leaving_caustics`](integrators::PathIntegrator::leaving_caustics)) and
//! adds the variance they cause, estimated here from light paths, which find them readily.
//!
//! **The formula.** For a caustic one bounce from the camera, a light path's contribution `c`
//! (before its MIS weight) and the ratio `r` of the light tracer's density of the path to the
//! path tracer's ([`CameraSplat::path_tracer_ratio`](integrators::CameraSplat::path_tracer_ratio))
//! give the path tracer's own sample of the same path, `v = c · r`. With `n` light paths per
//! pixel, as many as the path tracer's samples, `E[Σ c² r] = n · E[v²]` over the path tracer's
//! samples (importance sampling by the light paths). Per pixel and channel, with `w` the
//! filter's splat weight, the variance these caustics add to a path tracer's render of `n`
//! samples per pixel is then
//!
//! ```text
//! Var ≈ Σ (c w)² r / n²  −  κ I² / n          I = Σ c w / n
//! ```
//!
//! the second moment less the squared mean: `I` is the caustics' share of the pixel, and κ the
//! sum over the pixels a camera sample splats into of its mean weight squared (1 for the box
//! filter, less for wider ones), since the samples of neighbouring pixels are independent.
//! Where the path tracer finds a caustic often (a glossy surface that mirrors a light through
//! glass) the two terms nearly cancel; where it finds it rarely (a diffuse floor under a glass
//! ball) the first dominates. Longer caustic paths (camera → x₁ → x₂ → … → chain → light) have
//! no such estimate and stay unseen.

use crate::filter::Filter;
use glam::{DVec3, UVec2, Vec3};
use integrators::{CameraSplat, LightTracer};
use sampling::Sampler;
use sampling::sampler::IndependentSampler;
use scene::Camera;
use world::{RayTally, World};

/// Per pixel (row order) and channel, the variance that caustics one bounce from the camera add
/// to a `width × height` render through `camera` of `spp` samples per pixel by the path tracer
/// alone, estimated from `spp` light paths per pixel traced by `tracer` with the independent
/// sampler seeded with `seed` (rays counted in `tally`). One thread, in a fixed order: the same
/// figures on every machine.
#[allow(clippy::too_many_arguments)]
pub fn caustic_variance(
    world: &World,
    tracer: &LightTracer,
    camera: &Camera,
    (width, height): (u32, u32),
    filter: &Filter,
    seed: u32,
    spp: u32,
    tally: &mut impl RayTally,
) -> Vec<Vec3> {
    let pixels = (width * height) as usize;
    let (mut moments, mut means) = (vec![DVec3::ZERO; pixels], vec![DVec3::ZERO; pixels]);
    let mut sampler = IndependentSampler::new(seed, spp);
    let connect = |p, u_lens, time| {
        if camera.moves() {
            camera.at_time(time).connect(p, filter.radius(), u_lens)
        } else {
            camera.connect(p, filter.radius(), u_lens)
        }
    };
    let mut add = |splat: CameraSplat| {
        if splat.path_tracer_ratio == 0.0 {
            return;
        }
        filter.for_each_pixel_at(splat.film, width, height, |pixel, weight| {
            let c = (splat.unweighted * weight).as_dvec3();
            let index = (pixel.y * width + pixel.x) as usize;
            moments[index] += c * c * f64::from(splat.path_tracer_ratio);
            means[index] += c;
        });
    };
    for y in 0..height {
        for x in 0..width {
            for sample in 0..spp {
                sampler.start_pixel_sample(UVec2::new(x, y), sample);
                tracer.trace(world, &mut sampler, &connect, tally, &mut add);
            }
        }
    }
    let n = f64::from(spp);
    let kappa = splat_weight_spread(filter);
    moments
        .into_iter()
        .zip(means)
        .map(|(moment, sum)| {
            let mean = sum / n;
            (moment / (n * n) - kappa * mean * mean / n)
                .max(DVec3::ZERO)
                .as_vec3()
        })
        .collect()
}

/// κ of the module documentation for `filter`: over the pixels that the camera samples of one
/// pixel splat into, the sum of the squares of their mean weights (a camera sample is uniform
/// in its pixel; 1 for the box filter).
pub fn splat_weight_spread(filter: &Filter) -> f64 {
    const STEPS: u32 = 16;
    let reach = filter.radius().ceil() as u32 + 1;
    let size = 2 * reach + 1;
    let mut sums = vec![0.0f64; (size * size) as usize];
    for i in 0..STEPS {
        for j in 0..STEPS {
            let offset = glam::Vec2::new(
                (i as f32 + 0.5) / STEPS as f32,
                (j as f32 + 0.5) / STEPS as f32,
            );
            let film = glam::Vec2::splat(reach as f32) + offset;
            filter.for_each_pixel_at(film, size, size, |pixel, weight| {
                sums[(pixel.y * size + pixel.x) as usize] += f64::from(weight);
            });
        }
    }
    let samples = f64::from(STEPS * STEPS);
    sums.iter().map(|s| (s / samples) * (s / samples)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The box filter puts each camera sample in its own pixel with weight 1; a gaussian spreads
    /// it over several, so the squares of the mean weights sum to less.
    #[test]
    fn the_weight_spread_is_one_for_the_box_and_less_for_wider_filters() {
        assert!((splat_weight_spread(&Filter::Box) - 1.0).abs() < 1e-9);
        let gaussian = splat_weight_spread(&Filter::gaussian(0.5).expect("valid"));
        assert!(gaussian > 0.05 && gaussian < 0.9, "{gaussian}");
    }
}
