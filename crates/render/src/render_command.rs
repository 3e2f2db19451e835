//! `strata render`: load the scene, render it as planned, write the image and the stats.

use crate::cli::RenderArgs;
use crate::commands::CommandError;
use crate::driver::{RenderOptions, render};
use crate::filter::Filter;
use crate::stats::RenderStats;
use crate::technique::{RenderPlan, Transport, plan};
use glam::{UVec2, Vec2, Vec3};
use integrators::{PathIntegrator, RayCounters, reference};
use sampling::Sampler;
use sampling::sampler::AnySampler;
use scene::{Camera, FilterDesc, RenderScene};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

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

/// Runs `strata render` as `args` say.
pub fn run(args: &RenderArgs) -> Result<(), CommandError> {
    let load_start = Instant::now();
    let mut desc =
        scene::parse_file(&args.scene, &[]).map_err(|e| CommandError::BadInput(e.to_string()))?;
    if let (Some(width), Some(height)) = (args.width, args.height) {
        desc.film.width = width;
        desc.film.height = height;
    }
    let scene = scene::build(desc).map_err(|e| CommandError::BadInput(e.to_string()))?;
    let plan = plan(args, &scene.desc, &scene.features);
    let filter = filter(scene.desc.film.filter)?;
    let load_seconds = load_start.elapsed().as_secs_f64();

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.map_or(0, |t| t as usize))
        .build()
        .map_err(|e| CommandError::Failed(format!("cannot start the render threads: {e}")))?;
    let totals = RayTotals::default();
    let output = pool
        .install(|| render_image(&scene, &plan, &filter, &totals))
        .map_err(|e| CommandError::BadInput(format!("{}: {e}", args.scene.display())))?;

    let image = output.film.to_image();
    image
        .write_exr(&args.out)
        .map_err(|e| CommandError::Failed(e.to_string()))?;
    if let Some(png) = &args.png {
        image
            .write_png(png)
            .map_err(|e| CommandError::Failed(e.to_string()))?;
    }
    let mut stats = RenderStats::from_output(&output);
    stats.load_seconds = load_seconds;
    stats.rays = totals.rays.load(Ordering::Relaxed);
    stats.shadow_rays = totals.shadow_rays.load(Ordering::Relaxed);
    stats.techniques = plan.transport.technique_names();
    if scene.camera.has_lens() {
        stats.techniques.push("thin-lens".to_string());
    }
    if stats.nan_count > 0 || stats.inf_count > 0 {
        eprintln!(
            "warning: {} NaN and {} infinite samples were left out of the image",
            stats.nan_count, stats.inf_count
        );
    }
    if let Some(path) = &args.stats {
        stats
            .write_json(path)
            .map_err(|e| CommandError::Failed(e.to_string()))?;
    }
    Ok(())
}

/// Renders the image on the current thread pool.
fn render_image(
    scene: &RenderScene,
    plan: &RenderPlan,
    filter: &Filter,
    totals: &RayTotals,
) -> Result<crate::driver::RenderOutput, crate::driver::BudgetError> {
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
        &RenderOptions::default(),
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

/// The reconstruction filter the scene's film names.
fn filter(desc: FilterDesc) -> Result<Filter, CommandError> {
    let filter = match desc {
        FilterDesc::Box => Ok(Filter::Box),
        FilterDesc::Tent { radius } => Filter::tent(radius),
        FilterDesc::Gaussian { stddev } => Filter::gaussian(stddev),
    };
    filter.map_err(|e| CommandError::BadInput(e.to_string()))
}
