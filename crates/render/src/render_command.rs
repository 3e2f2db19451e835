//! `strata render`: load the scene, render it as planned, write the image and the stats.

use crate::cli::RenderArgs;
use crate::commands::CommandError;
use crate::driver::RenderOptions;
use crate::session::{film_filter, render_scene};
use crate::stats::RenderStats;
use crate::technique::plan;
use std::time::Instant;

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
    let filter =
        film_filter(scene.desc.film.filter).map_err(|e| CommandError::BadInput(e.to_string()))?;
    let load_seconds = load_start.elapsed().as_secs_f64();

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.map_or(0, |t| t as usize))
        .build()
        .map_err(|e| CommandError::Failed(format!("cannot start the render threads: {e}")))?;
    let (output, counters) = pool
        .install(|| render_scene(&scene, &plan, &filter, &RenderOptions::default()))
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
    stats.rays = counters.rays;
    stats.shadow_rays = counters.shadow_rays;
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
