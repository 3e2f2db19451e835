//! `cargo xtask raycast-limit [SCENE] [--spp N] [--threads N] [--runs N] [--no-embree]`: how
//! close a render comes to the time it takes to trace its rays alone, and how fast Strata traces
//! those rays against Embree.
//!
//! The scene is rendered once while recording every ray (`auto`, the scene's sampler, seed 1).
//! Then, `--runs` times in turn: the same render without recording (same seed, so the same rays;
//! the counts are checked), timed; and the recorded closest-hit rays (camera and bounce rays,
//! `Accel::intersect`) and shadow rays (`Accel::occluded`) traced alone, in recorded order, on
//! the same number of threads, timed. Reported: the medians, their ratio (render / ray casting; 1 would mean shading,
//! sampling and film cost nothing), and the render's speed-up on `--threads` threads over one.
//!
//! Then (unless `--no-embree`) the same rays are traced by Strata and by Embree 4 on the scene's
//! triangles, on one thread and on `--threads`, and compared ray by ray ([`super::embree`]):
//! Strata's closest-hit and occlusion rays per second ÷ Embree's, the goal being ≥ 0.8. This
//! needs `python3` and network access on first use (it installs `embreex` into
//! `target/embree-venv/`).

use super::embree::{self, median_times};
use super::{median, pool, positive, scene_path};
use geometry::Accel;
use rayon::prelude::*;
use render::driver::RenderOptions;
use render::plan::plan_from_flags;
use render::session::{film_filter, render_scene, render_scene_recording};
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;
use world::{RayCounters, RayLog};

/// Rays per parallel work item when tracing recorded rays.
const CHUNK: usize = 4096;

/// Runs `cargo xtask raycast-limit`; prints the figures.
pub fn raycast_limit(root: &Path, args: &[String]) -> Result<bool, String> {
    let mut scene_arg = "cbox".to_string();
    let mut spp: u32 = 32;
    let mut threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut runs: usize = 5;
    let mut with_embree = true;
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        match arg.as_str() {
            "--spp" => spp = positive("--spp", rest.next())?,
            "--threads" => threads = positive("--threads", rest.next())?,
            "--runs" => runs = positive("--runs", rest.next())?,
            "--no-embree" => with_embree = false,
            other if !other.starts_with("--") => scene_arg = other.to_string(),
            other => return Err(format!("raycast-limit: unknown argument {other}")),
        }
    }
    let path = scene_path(root, &scene_arg);
    let scene = scene::load(&path, &[]).map_err(|e| e.to_string())?;
    let spp_flag = spp.to_string();
    let plan = plan_from_flags(&scene, &["--spp", &spp_flag, "--seed", "1"])?;
    let filter = film_filter(scene.desc.film.filter).map_err(|e| e.to_string())?;
    let options = RenderOptions::quiet();
    // `auto`'s technique pilot is left out of both sides: its rays are not recorded (they
    // belong to throwaway renders), so the render's time and rays here are the image's alone.
    let render_once = |threads: usize| -> Result<(f64, RayCounters), String> {
        let (output, counters) = pool(threads)?
            .install(|| render_scene(&scene, &plan, &filter, &options))
            .map_err(|e| e.to_string())?;
        let (pilot_seconds, pilot_rays) = output
            .auto
            .as_ref()
            .map_or((0.0, RayCounters::default()), |a| (a.seconds, a.rays));
        Ok((output.seconds - pilot_seconds, counters.since(pilot_rays)))
    };

    let (recorded, log) = pool(threads)?
        .install(|| render_scene_recording(&scene, &plan, &filter, &options))
        .map_err(|e| e.to_string())?;
    println!(
        "{}: {}x{} at {spp} spp, techniques {:?}, {threads} threads, medians of {runs} runs",
        path.display(),
        scene.desc.film.width,
        scene.desc.film.height,
        recorded.rendered_plan(&plan).transport.technique_names(),
    );

    // Rendering and tracing alternate, so that a change in the machine's load hits both alike.
    let tracing = pool(threads)?;
    let mut render_times = Vec::new();
    let mut closest_times = Vec::new();
    let mut shadow_times = Vec::new();
    for _ in 0..runs {
        let (seconds, counters) = render_once(threads)?;
        if counters != log.counters {
            return Err(format!(
                "the recording render traced {:?}, the normal one {counters:?}: not the same rays",
                log.counters
            ));
        }
        render_times.push(seconds);
        let (closest, shadow) = tracing.install(|| trace_alone(scene.world.accel(), &log));
        closest_times.push(closest);
        shadow_times.push(shadow);
    }
    let render_seconds = median(&render_times);
    let closest = median(&closest_times);
    let shadow = median(&shadow_times);
    let rays = log.closest.len() + log.shadow.len();
    println!(
        "render         {render_seconds:8.3} s  {:6.2} M rays/s",
        rays as f64 / render_seconds / 1e6
    );
    println!(
        "closest-hit    {closest:8.3} s  {:6.2} M rays/s  ({} rays)",
        log.closest.len() as f64 / closest / 1e6,
        log.closest.len()
    );
    println!(
        "occlusion      {shadow:8.3} s  {:6.2} M rays/s  ({} rays)",
        log.shadow.len() as f64 / shadow / 1e6,
        log.shadow.len()
    );
    println!(
        "ray casting    {:8.3} s  render / ray casting = {:.2}",
        closest + shadow,
        render_seconds / (closest + shadow)
    );
    if threads > 1 {
        let single = median(
            &(0..runs)
                .map(|_| render_once(1).map(|r| r.0))
                .collect::<Result<Vec<_>, _>>()?,
        );
        println!(
            "1 thread       {single:8.3} s  speed-up on {threads} threads = {:.2}",
            single / render_seconds
        );
    }
    if with_embree {
        let thread_counts = if threads > 1 {
            vec![1, threads]
        } else {
            vec![1]
        };
        return embree::compare(
            root,
            scene.world.accel().shapes(),
            &log,
            &thread_counts,
            runs,
            |accel, threads| {
                let pool = pool(threads)?;
                Ok(median_times(runs, || {
                    pool.install(|| trace_alone(accel, &log))
                }))
            },
        );
    }
    Ok(true)
}

/// Seconds to trace the recorded closest-hit rays and the recorded shadow rays of `log` through
/// `accel`, on the current thread pool.
fn trace_alone(accel: &Accel, log: &RayLog) -> (f64, f64) {
    let start = Instant::now();
    let hits: usize = log
        .closest
        .par_chunks(CHUNK)
        .map(|rays| {
            rays.iter()
                .filter(|r| black_box(accel.intersect(r, f32::INFINITY)).is_some())
                .count()
        })
        .sum();
    let closest = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let blocked: usize = log
        .shadow
        .par_chunks(CHUNK)
        .map(|rays| {
            rays.iter()
                .filter(|s| accel.occluded(&s.ray, s.t_max))
                .count()
        })
        .sum();
    let shadow = start.elapsed().as_secs_f64();
    black_box((hits, blocked));
    (closest, shadow)
}
