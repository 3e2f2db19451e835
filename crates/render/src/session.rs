//! One render of a built scene as planned, on the current thread pool: the part of
//! `strata render` that tests and tools call in-process.

use crate::adaptive::{Allocation, MIN_PILOT_SPP, PixelCosts, pilot_seed, split_budget};
use crate::auto::{self, AutoChoice, PilotRenders, TechniquePilot, Trials};
use crate::caustic_variance::caustic_variance;
use crate::driver::{
    BudgetError, LightPaths, MAX_BLOCK_PIXELS, RenderBudget, RenderOptions, RenderOutput,
    render_blocks_splatting,
};
use crate::filter::{Filter, FilterError, Splatter};
use crate::image::Image;
use crate::plan::{RenderPlan, Transport};
use glam::{UVec2, Vec2, Vec3};
use integrators::path_reuse::{self, ReusablePath};
use integrators::{CameraSplat, LightTracer, PathIntegrator, reference};
use sampling::Sampler;
use sampling::sampler::{PrefixSampler, SamplerModel, SamplerVisitor};
use scene::{Camera, FilterDesc, RenderScene};
use std::sync::{Arc, Mutex, PoisonError};
use world::{BsdfSlot, RayCounters, RayLog, RayTally};

/// A render's [`Transport`] built for its world (the path tracer with its light selection table).
enum BuiltTransport {
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
    let total = Mutex::new(RayCounters::default());
    let finish = |counters: &mut RayCounters| counted(&total).add(*counters);
    let output = render_image(scene, plan, filter, options, &finish)?;
    let mut counters = total.into_inner().unwrap_or_else(PoisonError::into_inner);
    if let Some(pilot) = &output.auto {
        counters.add(pilot.rays);
    }
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
/// that is handed to `finish` when the worker is done. For `auto` ([`RenderPlan::trials`]), the
/// technique pilot first chooses the settings ([`crate::auto`]); with adaptive sampling, a pilot
/// (whose rays are told too) then allocates the image's samples.
fn render_image<T: RayTally + Default + Send>(
    scene: &RenderScene,
    plan: &RenderPlan,
    filter: &Filter,
    options: &RenderOptions,
    finish: &(dyn Fn(&mut T) + Sync),
) -> Result<RenderOutput, BudgetError> {
    plan.budget.validate()?;
    let Some(choice) = choose_techniques(scene, plan, filter, options)? else {
        return render_adaptive(scene, plan, filter, options, finish);
    };
    let chosen = RenderPlan {
        transport: Transport::Path(choice.choice.settings),
        trials: Trials::default(),
        budget: RenderBudget {
            max_seconds: plan
                .budget
                .max_seconds
                .map(|s| (s - choice.seconds).max(0.0)),
            ..plan.budget
        },
        ..*plan
    };
    let mut output = render_adaptive(scene, &chosen, filter, options, finish)?;
    output.seconds += choice.seconds;
    output.auto = Some(choice);
    Ok(output)
}

/// Runs `auto`'s technique pilot when `plan` has trials (`None` otherwise), or keeps the base
/// when the sample budget cannot pay for it. The pilot renders a thumbnail with the independent
/// sampler and seeds of its own, so none of its samples is in the image.
fn choose_techniques(
    scene: &RenderScene,
    plan: &RenderPlan,
    filter: &Filter,
    options: &RenderOptions,
) -> Result<Option<TechniquePilot>, BudgetError> {
    let Transport::Path(base) = plan.transport else {
        return Ok(None);
    };
    if !plan.trials.any() {
        return Ok(None);
    }
    let (width, height) = (scene.desc.film.width, scene.desc.film.height);
    // The whole render's samples per pixel: a `--samples` piece lays its sampler out for the
    // render it is a piece of, and must choose as that render does, whatever its own range
    // (otherwise pieces of one render could choose differently, and not merge into it).
    let whole_spp = plan.budget.max_spp.map(|_| plan.sampler_spp);
    let start = std::time::Instant::now();
    let quiet = RenderOptions {
        stop: options.stop.clone(),
        max_pass_seconds: options.max_pass_seconds,
        ..RenderOptions::quiet()
    };
    let skipped = |reason: String| {
        Ok(Some(TechniquePilot {
            choice: AutoChoice::unmeasured(base, reason),
            seconds: start.elapsed().as_secs_f64(),
            rays: RayCounters::default(),
        }))
    };
    let thumbnail =
        |most_pixels| auto::thumbnail_size(width, height, &plan.trials, whole_spp, most_pixels);
    let mut most_pixels = f64::INFINITY;
    if let Some(budget_seconds) = plan.budget.max_seconds
        && let Some(probe) = thumbnail(most_pixels)
    {
        // Time one sample per pixel of the base on the largest thumbnail; a pilot sample costs
        // about that, a trial's up to half as much again.
        let camera = Camera::new(&scene.desc.sensor, probe.0, probe.1);
        let probe_plan = RenderPlan {
            transport: Transport::Path(base),
            seed: auto::pilot_seed(plan.seed, 2),
            budget: RenderBudget::spp(1),
            sampler_spp: 1,
            adaptive: false,
            trials: Trials::default(),
            ..*plan
        };
        let ignore = |_: &mut RayCounters| {};
        let context = Context {
            view: View {
                camera: &camera,
                width: probe.0,
                height: probe.1,
            },
            ..Context::new(scene, &probe_plan, filter, &quiet, &ignore)
        };
        let seconds = render_sampled(&context)?.seconds.max(1e-6);
        let per_sample = 1.5 * seconds / f64::from(probe.0 * probe.1);
        most_pixels = auto::MAX_PILOT_SHARE * budget_seconds
            / (per_sample * auto::pilot_samples_per_pixel(&plan.trials));
    }
    let Some(thumbnail) = thumbnail(most_pixels) else {
        return skipped(match whole_spp {
            Some(spp) => format!(
                "{spp} spp: a pilot of {} pixels or more would take more than {}% of the samples",
                auto::MIN_PILOT_PIXELS,
                auto::MAX_PILOT_SHARE * 100.0
            ),
            None => format!(
                "a pilot of {} pixels or more would take more than {}% of the time",
                auto::MIN_PILOT_PIXELS,
                auto::MAX_PILOT_SHARE * 100.0
            ),
        });
    };
    // What the first round leaves of the pilot's share pays for further rounds: a share of the
    // image's samples, or of the time, counting what the first round took.
    let first_round_start = std::time::Instant::now();
    let extension_renders = || match (whole_spp, plan.budget.max_seconds) {
        (Some(spp), _) => {
            let affordable = auto::pilot_sample_share(width, height, spp);
            auto::extension_renders(&plan.trials, thumbnail, affordable)
        }
        (None, Some(budget_seconds)) => auto::extension_renders_in_time(
            &plan.trials,
            first_round_start.elapsed().as_secs_f64(),
            auto::MAX_PILOT_SHARE * budget_seconds - start.elapsed().as_secs_f64(),
        ),
        (None, None) => usize::MAX,
    };
    let camera = Camera::new(&scene.desc.sensor, thumbnail.0, thumbnail.1);
    let view = View {
        camera: &camera,
        width: thumbnail.0,
        height: thumbnail.1,
    };
    let total = Mutex::new(RayCounters::default());
    let count = |counters: &mut RayCounters| counted(&total).add(*counters);
    // The light tracer of the base, for the caustics that candidates without it leave out.
    let base_tracer =
        LightTracer::new(&scene.world, &base, camera.traits()).filter(|_| camera.connects());
    let mut caustics: Option<Vec<Vec3>> = None;
    let choice = auto::choose(
        base,
        &plan.trials,
        thumbnail,
        extension_renders,
        |settings, round| {
            let before = *counted(&total);
            let caustics_left_out = settings.light_tracing.is_none() && base_tracer.is_some();
            let mut images = Vec::with_capacity(2);
            for replica in auto::round_replicas(round) {
                let pilot_plan = RenderPlan {
                    transport: Transport::Path(*settings),
                    sampler: plan.sampler,
                    seed: auto::pilot_seed(plan.seed, replica),
                    budget: RenderBudget::spp(auto::PILOT_SPP),
                    sampler_spp: auto::PILOT_SPP,
                    adaptive: false,
                    trials: Trials::default(),
                    independent_time: plan.independent_time,
                };
                let context = Context {
                    view,
                    caustics_left_out,
                    shared_camera_samples: Some(auto::camera_sample_seed(plan.seed, round)),
                    ..Context::new(scene, &pilot_plan, filter, &quiet, &count)
                };
                images.push(render_sampled(&context)?.film.to_image());
            }
            let after = *counted(&total);
            // The caustics' variance, from light paths, once for every candidate that leaves them
            // out (not in a candidate's cost: the candidate traces none).
            let caustics = match &base_tracer {
                Some(tracer) if caustics_left_out => Some(
                    caustics
                        .get_or_insert_with(|| {
                            let mut probe = RayCounters::default();
                            let variance = caustic_variance(
                                &scene.world,
                                tracer,
                                &camera,
                                thumbnail,
                                filter,
                                auto::pilot_seed(plan.seed, 3),
                                auto::PILOT_SPP,
                                &mut probe,
                            );
                            count(&mut probe);
                            variance
                        })
                        .clone(),
                ),
                _ => None,
            };
            let [a, b]: [Image; 2] = images.try_into().expect("two renders");
            Ok(PilotRenders {
                images: [a, b],
                rays: after.since(before),
                samples: 2 * u64::from(auto::PILOT_SPP) * u64::from(thumbnail.0 * thumbnail.1),
                caustic_variance: caustics,
            })
        },
    )?;
    Ok(Some(TechniquePilot {
        choice,
        seconds: start.elapsed().as_secs_f64(),
        rays: total.into_inner().unwrap_or_else(PoisonError::into_inner),
    }))
}

/// The counts of rays that the workers of a render add to (a worker that panicked leaves them
/// whole: it adds once, when done).
fn counted(total: &Mutex<RayCounters>) -> std::sync::MutexGuard<'_, RayCounters> {
    total.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Renders the image as `plan` says, with an adaptive-sampling pilot first where the plan asks
/// for one and the budget can be split.
fn render_adaptive<T: RayTally + Default + Send>(
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
        let mut output = render_sampled(&Context::new(scene, plan, filter, options, finish))?;
        if plan.adaptive && options.resume.is_none() {
            output.adaptive_skipped = Some(format!(
                "{} spp is too few to split into a pilot of {MIN_PILOT_SPP} and the image",
                plan.budget.max_spp.unwrap_or(0)
            ));
        }
        return Ok(output);
    };
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
        allocation: Some(Arc::new({
            let allocation = Allocation::from_pilot(&pilot.film, &costs);
            let allocation = match reuse_block(plan) {
                Some(block) => allocation.blockwise(block),
                None => allocation,
            };
            // Splatted samples weigh 1 / (their pixel's samples per round), known before the
            // render, where the final count is not (see `Splatter`).
            let (width, height) = (scene.desc.film.width, scene.desc.film.height);
            if Splatter::new(filter, width, height).is_some() {
                allocation.in_rounds()
            } else {
                allocation
            }
        })),
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

/// The block edge of `plan`'s path reuse, if it reuses paths.
fn reuse_block(plan: &RenderPlan) -> Option<u32> {
    match plan.transport {
        Transport::Path(settings) => settings.path_reuse.map(|reuse| reuse.block),
        Transport::Reference(_) => None,
    }
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
    let built = Integrators::new(context.scene, context.plan, context.caustics_left_out);
    let prefix = built.pattern_dimensions(
        context.view.camera.has_lens(),
        context.scene.world.has_motion() || context.view.camera.moves(),
    );
    context.plan.sampler.visit(RenderSampled {
        context,
        built: &built,
        prefix,
    })
}

/// [`render_with`] for the sampler type a [`SamplerKind`](sampling::SamplerKind) names: its
/// pattern for the first `prefix` dimensions of each pixel sample and independent numbers
/// after ([`PrefixSampler`]), or the sampler alone where its numbers are independent already.
struct RenderSampled<'c, 'a, T> {
    context: &'c Context<'a, T>,
    built: &'c Integrators,
    prefix: u32,
}

impl<T: RayTally + Default + Send> SamplerVisitor for RenderSampled<'_, '_, T> {
    type Output = Result<RenderOutput, BudgetError>;

    fn visit<S: SamplerModel>(self) -> Self::Output {
        let (seed, spp) = (self.context.plan.seed, self.context.plan.sampler_spp);
        if S::INDEPENDENT_DIMENSIONS {
            render_with(self.context, self.built, || S::new(seed, spp))
        } else {
            render_with(self.context, self.built, || {
                PrefixSampler::new(S::new(seed, spp), self.prefix, seed)
            })
        }
    }
}

/// The integrator a render runs and, with caustics by light tracing, its light tracer.
struct Integrators {
    integrator: BuiltTransport,
    light_tracer: Option<LightTracer>,
}

impl Integrators {
    /// The integrators `plan` names for `scene`; with `caustics_left_out`, the path tracer
    /// without the paths light tracing contributes, and no light tracer (see
    /// [`Context::caustics_left_out`]).
    fn new(scene: &RenderScene, plan: &RenderPlan, caustics_left_out: bool) -> Self {
        let world = &scene.world;
        match plan.transport {
            Transport::Reference(settings) => Self {
                integrator: BuiltTransport::Reference(settings),
                light_tracer: None,
            },
            Transport::Path(settings) if caustics_left_out => Self {
                integrator: BuiltTransport::Path(
                    PathIntegrator::new(world, settings).leaving_caustics(),
                ),
                light_tracer: None,
            },
            Transport::Path(mut settings) => {
                let light_tracer = LightTracer::new(world, &settings, scene.camera.traits());
                // Without the tracer the path tracer must keep every path.
                settings.light_tracing = settings.light_tracing.filter(|_| light_tracer.is_some());
                Self {
                    integrator: BuiltTransport::Path(PathIntegrator::new(world, settings)),
                    light_tracer,
                }
            }
        }
    }

    /// The leading dimensions of each pixel sample drawn from the sampler's pattern: the
    /// camera's (film position, the lens point with a lens, the time with motion) and the first
    /// [`PATTERN_VERTICES`] vertices' of the path tracer; all of them for the reference
    /// integrator, which has no tricks. A light path drawn with the same sampler gets as many.
    fn pattern_dimensions(&self, has_lens: bool, has_motion: bool) -> u32 {
        match &self.integrator {
            BuiltTransport::Reference(_) => u32::MAX,
            BuiltTransport::Path(path) => {
                1 + u32::from(has_lens)
                    + u32::from(has_motion)
                    + path.sampler_dimensions(PATTERN_VERTICES)
            }
        }
    }
}

/// One render without a pilot: the scene, plan, filter and options, where each worker's rays
/// go when it is done, and whether this is an adaptive-sampling pilot.
struct Context<'a, T> {
    scene: &'a RenderScene,
    /// The camera and image size rendered: the scene's, or a pilot's thumbnail.
    view: View<'a>,
    plan: &'a RenderPlan,
    filter: &'a Filter,
    options: &'a RenderOptions,
    finish: &'a (dyn Fn(&mut T) + Sync),
    /// For an adaptive-sampling pilot, where each sample's rays are added. A pilot estimates the
    /// noise of the path tracer's samples only, so it traces no light paths.
    pilot_costs: Option<&'a PixelCosts>,
    /// For `auto`'s pilot of a candidate without light tracing where the base has it: the path
    /// tracer leaves out the paths light tracing would contribute, whose variance the pilot
    /// estimates from light paths ([`crate::caustic_variance`]).
    caustics_left_out: bool,
    /// For `auto`'s pilot: the seed of the camera samples (film position, lens point, time)
    /// that the two renders of a round share ([`auto::camera_sample_seed`]), in place of the
    /// sampler's.
    shared_camera_samples: Option<u32>,
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
            view: View {
                camera: &scene.camera,
                width: scene.desc.film.width,
                height: scene.desc.film.height,
            },
            plan,
            filter,
            options,
            finish,
            pilot_costs: None,
            caustics_left_out: false,
            shared_camera_samples: None,
        }
    }
}

/// What a render looks through: a camera and the image size it was made for.
#[derive(Clone, Copy)]
struct View<'a> {
    camera: &'a Camera,
    width: u32,
    height: u32,
}

/// [`render_sampled`] with the integrators `built` and the samplers `new_sampler` makes.
fn render_with<S: Sampler + Send, T: RayTally + Default + Send>(
    context: &Context<'_, T>,
    built: &Integrators,
    new_sampler: impl Fn() -> S + Sync + Send,
) -> Result<RenderOutput, BudgetError> {
    let Context {
        scene,
        view,
        plan,
        filter,
        options,
        finish,
        pilot_costs: costs,
        shared_camera_samples,
        ..
    } = *context;
    let world = &scene.world;
    let camera: &Camera = view.camera;
    let (width, height) = (view.width, view.height);
    let Integrators {
        integrator,
        light_tracer,
    } = built;
    let trace_light_path = |worker: &mut Worker<'_, S, T>,
                            pixel: UVec2,
                            sample_index: u32,
                            splats: &mut Vec<(UVec2, Vec3)>| {
        let Some(tracer) = &light_tracer else {
            return false;
        };
        let Some(path_index) = tracer.path_of_sample(pixel, sample_index) else {
            return false;
        };
        // A key no image pixel has, so the light path's numbers are independent of the pixel
        // sample's own.
        let key = UVec2::new(pixel.x, pixel.y + height);
        worker.sampler.start_pixel_sample(key, path_index);
        let mut add = |splat: CameraSplat| {
            filter.for_each_pixel_at(splat.film, width, height, |pixel, weight| {
                splats.push((pixel, splat.value * weight));
            });
        };
        tracer.trace(
            world,
            &mut worker.sampler,
            &|p, u_lens, time| {
                if camera.moves() {
                    camera.at_time(time).connect(p, filter.radius(), u_lens)
                } else {
                    camera.connect(p, filter.radius(), u_lens)
                }
            },
            &mut worker.tally,
            &mut add,
        );
        true
    };
    let light_paths: Option<&LightPaths<'_, Worker<'_, S, T>>> =
        (costs.is_none() && light_tracer.is_some()).then_some(&trace_light_path);
    let has_lens = camera.has_lens();
    let has_motion = world.has_motion() || camera.moves();
    // For `RenderPlan::independent_time`: the time from a stream of its own, keyed like the
    // sampler by (pixel, sample index), never from the pattern.
    let time_seed = plan.independent_time.then_some(plan.seed ^ 0x7135_9e37);
    let signed_filter = filter.has_negative_lobes();
    let new_worker = || Worker {
        sampler: new_sampler(),
        tally: T::default(),
        slot: BsdfSlot::default(),
        finish,
    };
    // Filters wider than a pixel splat each camera sample, taken uniformly in its pixel, into
    // every pixel they cover (see `Splatter`), which at equal samples has about a third of the
    // variance of filter importance sampling for the default gaussian where path noise
    // dominates. An adaptive-sampling pilot (`costs`) only estimates its pixels' own noise and
    // splats nothing, but takes its samples where the image will.
    let splatter = Splatter::new(filter, width, height);
    let uniform_in_pixel = splatter.is_some();
    let splatter = if costs.is_none() { splatter } else { None };
    // The camera ray of `pixel`'s sample `sample_index`, and where on the film it starts.
    let camera_ray = |sampler: &mut S, pixel: UVec2, sample_index: u32| {
        sampler.start_pixel_sample(pixel, sample_index);
        let mut u = sampler.next_2d();
        let mut u_lens = if has_lens {
            sampler.next_2d()
        } else {
            Vec2::ZERO
        };
        // The time the whole path sees the scene at, uniform over the shutter.
        let mut time = match (has_motion, time_seed) {
            (false, _) => 0.0,
            (true, None) => sampler.next_1d(),
            (true, Some(seed)) => sampling::Rng::for_sample(pixel, sample_index, seed).next_f32(),
        };
        // `auto`'s pilot: numbers its renders share, in place of the sampler's (drawn all the
        // same, so that the path's dimensions stay where they are).
        if let Some(seed) = shared_camera_samples {
            let mut shared = sampling::Rng::for_sample(pixel, sample_index, seed);
            u = Vec2::new(shared.next_f32(), shared.next_f32());
            if has_lens {
                u_lens = Vec2::new(shared.next_f32(), shared.next_f32());
            }
            if has_motion {
                time = shared.next_f32();
            }
        }
        let film_position = if uniform_in_pixel {
            Splatter::film_position(pixel, u)
        } else {
            filter.sample_film_position(pixel, u, width, height)
        };
        let mut camera_ray = if has_motion && camera.moves() {
            camera.at_time(time).generate_ray(film_position, u_lens)
        } else {
            camera.generate_ray(film_position, u_lens)
        };
        camera_ray.ray.time = time;
        (camera_ray, film_position)
    };
    let filter_weight = |radiance: Vec3, film_position: Vec2, pixel: UVec2| {
        if signed_filter && !uniform_in_pixel {
            radiance * filter.sample_weight(film_position, pixel, width, height)
        } else {
            radiance
        }
    };
    if let BuiltTransport::Path(path) = integrator
        && let Some(reuse) = path.settings().path_reuse
    {
        return render_blocks_splatting(
            width,
            height,
            &plan.budget,
            options,
            reuse.block,
            splatter.as_ref(),
            new_worker,
            |worker: &mut Worker<'_, S, T>,
             pixels: &[UVec2],
             sample_index: u32,
             values: &mut [Vec3],
             positions: &mut [Vec2]| {
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
                        connection_rays: connections.connection_rays / paths.len() as u64,
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
                positions.copy_from_slice(&film_positions[..pixels.len()]);
            },
            light_paths,
        );
    }
    render_blocks_splatting(
        width,
        height,
        &plan.budget,
        options,
        1,
        splatter.as_ref(),
        new_worker,
        |worker: &mut Worker<'_, S, T>,
         pixels: &[UVec2],
         sample_index: u32,
         values: &mut [Vec3],
         positions: &mut [Vec2]| {
            let pixel = pixels[0];
            let (ray, film_position) = camera_ray(&mut worker.sampler, pixel, sample_index);
            positions[0] = film_position;
            let sampler = &mut worker.sampler;
            let rays_before = costs.map(|_| worker.tally.counts());
            let radiance = match &integrator {
                BuiltTransport::Reference(settings) => {
                    reference::radiance(world, ray, sampler, settings, &mut worker.tally)
                }
                BuiltTransport::Path(path) => {
                    path.radiance(world, ray, sampler, &mut worker.tally, &mut worker.slot)
                }
            };
            if let (Some(costs), Some(before)) = (costs, rays_before) {
                costs.add(pixel, worker.tally.counts().since(before));
            }
            values[0] = filter_weight(radiance, film_position, pixel);
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
