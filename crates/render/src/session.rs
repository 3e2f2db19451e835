//! One render of a built scene as planned, on the current thread pool: the part of
//! `strata render` that tests and tools call in-process.

use crate::adaptive::{Allocation, PixelCosts, pilot_seed, split_budget};
use crate::driver::{
    BudgetError, LightPaths, MAX_BLOCK_PIXELS, RenderBudget, RenderOptions, RenderOutput,
    render_blocks, render_with_light_paths,
};
use crate::filter::{Filter, FilterError};
use crate::technique::{RenderPlan, Transport};
use glam::{UVec2, Vec2, Vec3};
use integrators::path_reuse::{self, ReusablePath};
use integrators::{
    BsdfSlot, LightTracer, PathIntegrator, RayCounters, RayLog, RayTally, reference,
};
use sampling::Sampler;
use sampling::sampler::{
    BlueNoiseSampler, IndependentSampler, PrefixSampler, SamplerKind, SobolSampler,
    StratifiedSampler,
};
use scene::{Camera, FilterDesc, RenderScene};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

/// The light transport of a render, built for its world.
enum Integrator {
    Reference(reference::ReferenceSettings),
    Path(PathIntegrator),
}

/// Per-worker state: the sampler and what it tells about rays, handed to `finish` when the
/// worker is dropped.
struct Worker<'a, S, T> {
    sampler: S,
    tally: T,
    /// Room for a textured hit's BSDF, for all the worker's paths.
    slot: BsdfSlot,
    finish: &'a (dyn Fn(&mut T) + Sync),
}

impl<S, T> Drop for Worker<'_, S, T> {
    fn drop(&mut self) {
        (self.finish)(&mut self.tally);
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
    let rays = AtomicU64::new(0);
    let shadow_rays = AtomicU64::new(0);
    let finish = |counters: &mut RayCounters| {
        rays.fetch_add(counters.rays, Ordering::Relaxed);
        shadow_rays.fetch_add(counters.shadow_rays, Ordering::Relaxed);
    };
    let output = render_image(scene, plan, filter, options, &finish)?;
    let counters = RayCounters {
        rays: rays.load(Ordering::Relaxed),
        shadow_rays: shadow_rays.load(Ordering::Relaxed),
    };
    Ok((output, counters))
}

/// [`render_scene`], recording every ray traced: the same image and the same rays as
/// `render_scene` with the same plan (the rays grouped by worker, each worker's in the order
/// traced). Needs memory for every ray (24 or 28 bytes each); meant for measuring the
/// ray-casting limit, not for rendering.
pub fn render_scene_recording(
    scene: &RenderScene,
    plan: &RenderPlan,
    filter: &Filter,
    options: &RenderOptions,
) -> Result<(RenderOutput, RayLog), BudgetError> {
    let log = Mutex::new(RayLog::default());
    let finish = |worker_log: &mut RayLog| {
        log.lock()
            .unwrap_or_else(PoisonError::into_inner)
            .append(worker_log);
    };
    let output = render_image(scene, plan, filter, options, &finish)?;
    Ok((
        output,
        log.into_inner().unwrap_or_else(PoisonError::into_inner),
    ))
}

/// Renders the image on the current thread pool, each worker telling its rays to a fresh `T`
/// that is handed to `finish` when the worker is done; with adaptive sampling, first the pilot
/// (whose rays are told too) and then the image with the pilot's allocation.
fn render_image<T: RayTally + Default + Send>(
    scene: &RenderScene,
    plan: &RenderPlan,
    filter: &Filter,
    options: &RenderOptions,
    finish: &(dyn Fn(&mut T) + Sync),
) -> Result<RenderOutput, BudgetError> {
    let split = if plan.adaptive && options.resume.is_none() {
        split_budget(&plan.budget)
    } else {
        None
    };
    let Some((pilot_budget, image_budget)) = split else {
        return render_sampled(&Context::new(scene, plan, filter, options, finish));
    };
    plan.budget.validate()?;
    let pilot_spp = pilot_budget.max_spp.unwrap_or(1);
    let pilot_plan = RenderPlan {
        seed: pilot_seed(plan.seed),
        budget: pilot_budget,
        sampler_spp: pilot_spp,
        ..*plan
    };
    let costs = PixelCosts::new(scene.desc.film.width, scene.desc.film.height);
    let pilot = render_sampled(&Context {
        pilot_costs: Some(&costs),
        ..Context::new(scene, &pilot_plan, filter, options, finish)
    })?;
    if pilot.interrupted {
        return Ok(pilot);
    }
    let image_plan = RenderPlan {
        budget: RenderBudget {
            max_seconds: image_budget
                .max_seconds
                .map(|s| (s - pilot.seconds).max(0.0)),
            ..image_budget
        },
        sampler_spp: image_budget.max_spp.unwrap_or(plan.sampler_spp),
        ..*plan
    };
    let image_options = RenderOptions {
        allocation: Some(Arc::new(Allocation::from_pilot(&pilot.film, &costs))),
        ..options.clone()
    };
    let mut output = render_sampled(&Context::new(
        scene,
        &image_plan,
        filter,
        &image_options,
        finish,
    ))?;
    output.pilot_spp = pilot.spp;
    output.spp += pilot.spp;
    output.seconds += pilot.seconds;
    output.passes += pilot.passes;
    output.non_finite.merge(pilot.non_finite);
    Ok(output)
}

/// Path vertices whose sampler dimensions come from the sampler's pattern (with the camera's);
/// deeper vertices draw independent numbers ([`PrefixSampler`]). On the Cornell box (128 spp,
/// Sobol, four seeds) the relMSE × spp was 0.1408 with every dimension from the pattern, 0.1403
/// with two vertices and 0.1436 with one, while the deeper dimensions cost 2.5% of the render's
/// instructions.
const PATTERN_VERTICES: u32 = 2;

/// [`render_image`] without a pilot, as `context` says. The per-sample code is compiled once per
/// sampler type, so that sampling is inlined into the integrator rather than dispatched per call.
fn render_sampled<T: RayTally + Default + Send>(
    context: &Context<'_, T>,
) -> Result<RenderOutput, BudgetError> {
    let (seed, spp) = (context.plan.seed, context.plan.sampler_spp);
    let built = Integrators::new(context.scene, context.plan);
    let prefix = built.pattern_dimensions(context.scene.camera.has_lens());
    match context.plan.sampler {
        SamplerKind::Independent => {
            render_with(context, &built, || IndependentSampler::new(seed, spp))
        }
        SamplerKind::Stratified => render_with(context, &built, || {
            PrefixSampler::new(StratifiedSampler::new(seed, spp), prefix, seed)
        }),
        SamplerKind::BlueNoise => render_with(context, &built, || {
            PrefixSampler::new(BlueNoiseSampler::new(seed, spp), prefix, seed)
        }),
        SamplerKind::Sobol => render_with(context, &built, || {
            PrefixSampler::new(SobolSampler::new(seed, spp), prefix, seed)
        }),
    }
}

/// The integrator a render runs and, with caustics by light tracing, its light tracer.
struct Integrators {
    integrator: Integrator,
    light_tracer: Option<LightTracer>,
}

impl Integrators {
    fn new(scene: &RenderScene, plan: &RenderPlan) -> Self {
        let world = &scene.world;
        match plan.transport {
            Transport::Reference(settings) => Self {
                integrator: Integrator::Reference(settings),
                light_tracer: None,
            },
            Transport::Path(mut settings) => {
                let light_tracer = if settings.light_tracing {
                    LightTracer::new(world, &settings, scene.camera.has_lens())
                } else {
                    None
                };
                // Without the tracer the path tracer must keep every path.
                settings.light_tracing = light_tracer.is_some();
                Self {
                    integrator: Integrator::Path(PathIntegrator::new(world, settings)),
                    light_tracer,
                }
            }
        }
    }

    /// The leading dimensions of each pixel sample drawn from the sampler's pattern: the
    /// camera's (film position, and the lens point with a lens) and the first
    /// [`PATTERN_VERTICES`] vertices' of the path tracer; all of them for the reference
    /// integrator, which has no tricks. A light path drawn with the same sampler gets as many.
    fn pattern_dimensions(&self, has_lens: bool) -> u32 {
        match &self.integrator {
            Integrator::Reference(_) => u32::MAX,
            Integrator::Path(path) => {
                1 + u32::from(has_lens) + path.sampler_dimensions(PATTERN_VERTICES)
            }
        }
    }
}

/// One render without a pilot: the scene, plan, filter and options, where each worker's rays
/// go when it is done, and whether this is an adaptive-sampling pilot.
struct Context<'a, T> {
    scene: &'a RenderScene,
    plan: &'a RenderPlan,
    filter: &'a Filter,
    options: &'a RenderOptions,
    finish: &'a (dyn Fn(&mut T) + Sync),
    /// For an adaptive-sampling pilot, where each sample's rays are added. A pilot estimates the
    /// noise of the path tracer's samples only, so it traces no light paths.
    pilot_costs: Option<&'a PixelCosts>,
}

impl<'a, T> Context<'a, T> {
    /// A render that is not a pilot.
    fn new(
        scene: &'a RenderScene,
        plan: &'a RenderPlan,
        filter: &'a Filter,
        options: &'a RenderOptions,
        finish: &'a (dyn Fn(&mut T) + Sync),
    ) -> Self {
        Self {
            scene,
            plan,
            filter,
            options,
            finish,
            pilot_costs: None,
        }
    }
}

/// [`render_sampled`] with the integrators `built` and the samplers `new_sampler` makes.
fn render_with<S: Sampler + Send, T: RayTally + Default + Send>(
    context: &Context<'_, T>,
    built: &Integrators,
    new_sampler: impl Fn() -> S + Sync + Send,
) -> Result<RenderOutput, BudgetError> {
    let Context {
        scene,
        plan,
        filter,
        options,
        finish,
        pilot_costs: costs,
    } = *context;
    let world = &scene.world;
    let camera: &Camera = &scene.camera;
    let (width, height) = (scene.desc.film.width, scene.desc.film.height);
    let Integrators {
        integrator,
        light_tracer,
    } = built;
    let trace_light_path = |worker: &mut Worker<'_, S, T>,
                            pixel: UVec2,
                            sample_index: u32,
                            splats: &mut Vec<(UVec2, Vec3)>| {
        let Some(tracer) = &light_tracer else {
            return;
        };
        // A key no image pixel has, so the light path's numbers are independent of the pixel
        // sample's own.
        let key = UVec2::new(pixel.x, pixel.y + height);
        worker.sampler.start_pixel_sample(key, sample_index);
        let mut add = |film: Vec2, value: Vec3| {
            filter.for_each_pixel_at(film, width, height, |pixel, weight| {
                splats.push((pixel, value * weight));
            });
        };
        tracer.trace(
            world,
            &mut worker.sampler,
            &|p, u_lens| camera.connect(p, filter.radius(), u_lens),
            &mut worker.tally,
            &mut add,
        );
    };
    let light_paths: Option<&LightPaths<'_, Worker<'_, S, T>>> =
        (costs.is_none() && light_tracer.is_some()).then_some(&trace_light_path);
    let has_lens = camera.has_lens();
    let signed_filter = filter.has_negative_lobes();
    let new_worker = || Worker {
        sampler: new_sampler(),
        tally: T::default(),
        slot: BsdfSlot::default(),
        finish,
    };
    // The camera ray of `pixel`'s sample `sample_index`, and where on the film it starts.
    let camera_ray = |sampler: &mut S, pixel: UVec2, sample_index: u32| {
        sampler.start_pixel_sample(pixel, sample_index);
        let film_position = filter.sample_film_position(pixel, sampler.next_2d(), width, height);
        let u_lens = if has_lens {
            sampler.next_2d()
        } else {
            Vec2::ZERO
        };
        (camera.generate_ray(film_position, u_lens), film_position)
    };
    let filter_weight = |radiance: Vec3, film_position: Vec2, pixel: UVec2| {
        if signed_filter {
            radiance * filter.sample_weight(film_position, pixel, width, height)
        } else {
            radiance
        }
    };
    if let Integrator::Path(path) = integrator
        && let Some(reuse) = path.settings().path_reuse
    {
        return render_blocks(
            width,
            height,
            &plan.budget,
            options,
            reuse.block,
            new_worker,
            |worker: &mut Worker<'_, S, T>,
             pixels: &[UVec2],
             sample_index: u32,
             values: &mut [Vec3]| {
                let mut paths = [ReusablePath::default(); MAX_BLOCK_PIXELS];
                let mut film_positions = [Vec2::ZERO; MAX_BLOCK_PIXELS];
                for ((&pixel, reusable), film_position) in
                    pixels.iter().zip(&mut paths).zip(&mut film_positions)
                {
                    let rays_before = costs.map(|_| worker.tally.counts());
                    let (ray, position) = camera_ray(&mut worker.sampler, pixel, sample_index);
                    *reusable = path.radiance_reusable(
                        world,
                        ray,
                        &mut worker.sampler,
                        &mut worker.tally,
                        &mut worker.slot,
                    );
                    *film_position = position;
                    if let (Some(costs), Some(before)) = (costs, rays_before) {
                        costs.add(pixel, worker.tally.counts().since(before));
                    }
                }
                let rays_before = costs.map(|_| worker.tally.counts());
                let paths = &paths[..pixels.len()];
                path_reuse::combine(world, paths, &mut worker.tally, values);
                if let (Some(costs), Some(before)) = (costs, rays_before) {
                    // The connections' rays, shared out evenly (the pilot only weighs costs).
                    let connections = worker.tally.counts().since(before);
                    let share = RayCounters {
                        rays: connections.rays / paths.len() as u64,
                        shadow_rays: connections.shadow_rays / paths.len() as u64,
                    };
                    for &pixel in pixels {
                        costs.add(pixel, share);
                    }
                }
                for ((value, &pixel), &film_position) in
                    values.iter_mut().zip(pixels).zip(&film_positions)
                {
                    *value = filter_weight(*value, film_position, pixel);
                }
            },
            light_paths,
        );
    }
    render_with_light_paths(
        width,
        height,
        &plan.budget,
        options,
        new_worker,
        |worker: &mut Worker<'_, S, T>, pixel: UVec2, sample_index: u32| -> Vec3 {
            let (ray, film_position) = camera_ray(&mut worker.sampler, pixel, sample_index);
            let sampler = &mut worker.sampler;
            let rays_before = costs.map(|_| worker.tally.counts());
            let radiance = match &integrator {
                Integrator::Reference(settings) => {
                    reference::radiance(world, ray, sampler, settings, &mut worker.tally)
                }
                Integrator::Path(path) => {
                    path.radiance(world, ray, sampler, &mut worker.tally, &mut worker.slot)
                }
            };
            if let (Some(costs), Some(before)) = (costs, rays_before) {
                costs.add(pixel, worker.tally.counts().since(before));
            }
            filter_weight(radiance, film_position, pixel)
        },
        light_paths,
    )
}

/// The reconstruction filter a scene's film names.
pub fn film_filter(desc: FilterDesc) -> Result<Filter, FilterError> {
    match desc {
        FilterDesc::Box => Ok(Filter::Box),
        FilterDesc::Tent { radius } => Filter::tent(radius),
        FilterDesc::Gaussian { stddev } => Filter::gaussian(stddev),
        FilterDesc::Mitchell { b, c } => Filter::mitchell(b, c),
        FilterDesc::CatmullRom => Ok(Filter::catmull_rom()),
        FilterDesc::Lanczos { lobes } => Filter::lanczos(lobes),
    }
}
