//! One render of a built scene as planned, on the current thread pool: the part of
//! `strata render` that tests and tools call in-process.

use crate::driver::{BudgetError, RenderOptions, RenderOutput, render};
use crate::filter::{Filter, FilterError};
use crate::technique::{RenderPlan, Transport};
use glam::{UVec2, Vec2, Vec3};
use integrators::{PathIntegrator, RayCounters, reference};
use sampling::Sampler;
use sampling::sampler::AnySampler;
use scene::{Camera, FilterDesc, RenderScene};
use std::sync::atomic::{AtomicU64, Ordering};

/// The light transport of a render, built for its world.
enum Integrator {
    Reference(reference::ReferenceSettings),
    Path(PathIntegrator),
}

/// Per-worker state: the sampler and ray counts, added to the shared totals when dropped.
struct Worker<'a> {
    sampler: AnySampler,
    counters: RayCounters,
    totals: &'a RayTotals,
}

/// Ray counts over all workers.
#[derive(Default)]
struct RayTotals {
    rays: AtomicU64,
    shadow_rays: AtomicU64,
}

impl Drop for Worker<'_> {
    fn drop(&mut self) {
        self.totals
            .rays
            .fetch_add(self.counters.rays, Ordering::Relaxed);
        self.totals
            .shadow_rays
            .fetch_add(self.counters.shadow_rays, Ordering::Relaxed);
    }
}

/// Renders `scene` as `plan` says with `filter`, on the current rayon pool (use
/// `ThreadPool::install` to choose the threads); returns the film and the rays traced.
pub fn render_scene(
    scene: &RenderScene,
    plan: &RenderPlan,
    filter: &Filter,
    options: &RenderOptions,
) -> Result<(RenderOutput, RayCounters), BudgetError> {
    let totals = RayTotals::default();
    let output = render_image(scene, plan, filter, options, &totals)?;
    let counters = RayCounters {
        rays: totals.rays.load(Ordering::Relaxed),
        shadow_rays: totals.shadow_rays.load(Ordering::Relaxed),
    };
    Ok((output, counters))
}

/// Renders the image on the current thread pool.
fn render_image(
    scene: &RenderScene,
    plan: &RenderPlan,
    filter: &Filter,
    options: &RenderOptions,
    totals: &RayTotals,
) -> Result<RenderOutput, BudgetError> {
    let world = &scene.world;
    let camera: &Camera = &scene.camera;
    let integrator = match plan.transport {
        Transport::Reference(settings) => Integrator::Reference(settings),
        Transport::Path(settings) => Integrator::Path(PathIntegrator::new(world, settings)),
    };
    let has_lens = camera.has_lens();
    render(
        scene.desc.film.width,
        scene.desc.film.height,
        &plan.budget,
        options,
        || Worker {
            sampler: AnySampler::new(plan.sampler, plan.seed, plan.sampler_spp),
            counters: RayCounters::default(),
            totals,
        },
        |worker: &mut Worker<'_>, pixel: UVec2, sample_index: u32| -> Vec3 {
            let sampler = &mut worker.sampler;
            sampler.start_pixel_sample(pixel, sample_index);
            let film_position = filter.sample_film_position(pixel, sampler.next_2d());
            let u_lens = if has_lens {
                sampler.next_2d()
            } else {
                Vec2::ZERO
            };
            let ray = camera.generate_ray(film_position, u_lens);
            match &integrator {
                Integrator::Reference(settings) => {
                    reference::radiance(world, ray, sampler, settings, &mut worker.counters)
                }
                Integrator::Path(path) => path.radiance(world, ray, sampler, &mut worker.counters),
            }
        },
    )
}

/// The reconstruction filter a scene's film names.
pub fn film_filter(desc: FilterDesc) -> Result<Filter, FilterError> {
    match desc {
        FilterDesc::Box => Ok(Filter::Box),
        FilterDesc::Tent { radius } => Filter::tent(radius),
        FilterDesc::Gaussian { stddev } => Filter::gaussian(stddev),
    }
}
