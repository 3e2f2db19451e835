//! `strata render`: load the scene, render it as planned (continuing a saved state if asked),
//! write the image, the saved state and the stats.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use crate::cli::RenderArgs;
use crate::commands::CommandError;
use crate::driver::{RenderOptions, RenderOutput, ResumePoint};
use crate::film_exr::write_film_exr;
use crate::fingerprint::scene_fingerprint;
use crate::plan::{self, RenderPlan, plan};
use crate::session::{film_filter, render_scene};
use crate::shard;
use crate::state::{FORMAT, RenderState, StateHeader, VERSION};
use crate::stats::RenderStats;
use crate::stop::StopSignal;
use crate::summary::summary_line;
use scene::SceneDesc;
use scene::limits::MAX_FILM_PIXELS;

/// Runs `strata render` as `args` say; stops early once `stop` is raised.
pub fn run(args: &RenderArgs, stop: &StopSignal) -> Result<(), CommandError> {
    let out = output_path(args)?;
    let load_start = Instant::now();
    let scene_bytes =
        scene::read_scene_file(&args.scene).map_err(|e| CommandError::BadInput(e.to_string()))?;
    let mut desc = scene::parse_bytes(&scene_bytes, &args.scene, &args.defines)
        .map_err(|e| CommandError::BadInput(e.to_string()))?;
    if let (Some(width), Some(height)) = (args.width, args.height) {
        if u64::from(width) * u64::from(height) > MAX_FILM_PIXELS {
            return Err(CommandError::BadInput(format!(
                "--width {width} --height {height}: {width}x{height} pixels is more than the \
                 supported {MAX_FILM_PIXELS}"
            )));
        }
        desc.film = desc.film.resized(width, height);
    }
    // The image's header records the scene's fingerprint, as a saved state does.
    let scene_hash = scene_fingerprint(&desc);
    let scene = scene::build(desc).map_err(|e| CommandError::BadInput(e.to_string()))?;
    let mut plan = plan(args, &scene.desc, &scene.features);
    let filter =
        film_filter(scene.desc.film.filter).map_err(|e| CommandError::BadInput(e.to_string()))?;
    let identity = Identity {
        scene_hash: scene_hash.clone(),
        settings: settings_text(&plan, &scene.desc),
    };
    let resume = match &args.resume {
        Some(path) => Some(resume_point(path, &identity, &mut plan)?),
        None => None,
    };
    let (width, height) = (scene.desc.film.width, scene.desc.film.height);
    let piece = match args.samples.clone() {
        Some(range) => Some(shard::start_piece(
            range, args.spp, &mut plan, width, height,
        )?),
        None => None,
    };
    let resume = resume.or(piece);
    let load_seconds = load_start.elapsed().as_secs_f64();

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.map_or(0, |t| t as usize))
        .build()
        .map_err(|e| CommandError::Failed(format!("cannot start the render threads: {e}")))?;
    let options = RenderOptions {
        progress: !args.quiet,
        stop: Some(stop.clone()),
        resume,
        ..RenderOptions::default()
    };
    let (output, counters) = pool
        .install(|| render_scene(&scene, &plan, &filter, &options))
        .map_err(|e| CommandError::BadInput(format!("{}: {e}", args.scene.display())))?;

    let first_sample = args.samples.as_ref().map_or(0, |range| range.start);
    let record = shard::film_record(scene_hash, &plan, &scene.desc, first_sample, &output);
    write_film_exr(&out, &output.film, &record).map_err(CommandError::Failed)?;
    let image = output.film.to_image();
    if let Some(png) = &args.png {
        image
            .write_png_with_exposure(png, args.exposure)
            .map_err(|e| CommandError::Failed(e.to_string()))?;
    }
    if let Some(path) = &args.state {
        saved_state(&output, &plan, identity)
            .write(path)
            .map_err(|e| CommandError::Failed(e.to_string()))?;
    }
    let mut stats = RenderStats::of_render(&output, counters, &plan, scene.camera.has_lens());
    stats.load_seconds = load_seconds;
    if let Some(reason) = &stats.adaptive_skipped {
        eprintln!("warning: no adaptive sampling: {reason}");
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
    if output.interrupted {
        return Err(CommandError::Interrupted(format!(
            "interrupted: wrote '{}' with {} samples per pixel{}",
            out.display(),
            output.spp,
            plan.budget
                .max_spp
                .map_or(String::new(), |max| format!(" of {max}"))
        )));
    }
    if !args.quiet {
        eprintln!(
            "{}",
            summary_line(&out, &stats, plan::preset(args, &scene.desc))
        );
    }
    Ok(())
}

/// What a saved state must match to be resumed: the scene's content and the sample-deciding
/// settings.
struct Identity {
    scene_hash: String,
    settings: String,
}

/// Everything besides the scene file that decides the value of sample `i` of a pixel: image
/// size, filter, light transport, sampler and seed.
fn settings_text(plan: &RenderPlan, desc: &SceneDesc) -> String {
    format!(
        "{}x{} {:?}; {:?}; sampler {:?} seed {}",
        desc.film.width,
        desc.film.height,
        desc.film.filter,
        plan.transport,
        plan.sampler,
        plan.seed
    )
}

/// Reads the state at `path`, checks it belongs to this scene and these settings, and makes the
/// plan continue its sampler layout.
fn resume_point(
    path: &Path,
    identity: &Identity,
    plan: &mut RenderPlan,
) -> Result<Arc<ResumePoint>, CommandError> {
    let state = RenderState::read(path).map_err(CommandError::BadInput)?;
    let header = &state.header;
    if header.scene_hash != identity.scene_hash {
        return Err(CommandError::BadInput(format!(
            "render state '{}' was saved for a different scene (fingerprint {}, this scene's is {}): \
             the scene file or a mesh file it reads has changed",
            path.display(),
            header.scene_hash,
            identity.scene_hash
        )));
    }
    if header.settings != identity.settings {
        return Err(CommandError::BadInput(format!(
            "render state '{}' was saved with other settings; give the same flags\n  saved: {}\n  now:   {}",
            path.display(),
            header.settings,
            identity.settings
        )));
    }
    plan.sampler_spp = header.sampler_spp;
    Ok(Arc::new(state.resume_point()))
}

/// The state to save after `output`.
fn saved_state(output: &RenderOutput, plan: &RenderPlan, identity: Identity) -> RenderState {
    RenderState {
        header: StateHeader {
            format: FORMAT.to_string(),
            version: VERSION,
            width: output.film.width(),
            height: output.film.height(),
            spp: output.spp,
            passes: output.passes,
            nan_count: output.non_finite.nan,
            inf_count: output.non_finite.inf,
            light_paths: output.film.light_paths(),
            filtered: output.film.filtered().is_some(),
            sampler_spp: plan.sampler_spp,
            scene_hash: identity.scene_hash,
            settings: identity.settings,
        },
        film: output.film.clone(),
    }
}

/// The image file to write ([`RenderArgs::out_path`]); bad input when there is none, or when
/// it or another output file (`--png`, `--stats`, `--state`) is the scene file itself.
fn output_path(args: &RenderArgs) -> Result<PathBuf, CommandError> {
    let out = args.out_path().ok_or_else(|| {
        CommandError::BadInput(format!(
            "'{}' has no file name to name the image after; give --out",
            args.scene.display()
        ))
    })?;
    let outputs = [
        (
            args.out.as_ref().map_or(
                "the image (default: the scene's name with .exr)",
                |_| "--out",
            ),
            Some(&out),
        ),
        ("--png", args.png.as_ref()),
        ("--stats", args.stats.as_ref()),
        ("--state", args.state.as_ref()),
    ];
    for (flag, path) in outputs {
        if let Some(path) = path
            && is_same_file(path, &args.scene)
        {
            return Err(CommandError::BadInput(format!(
                "{flag} '{}' is the scene file '{}'; refusing to write over it",
                path.display(),
                args.scene.display()
            )));
        }
    }
    Ok(out)
}

/// Whether `a` and `b` both exist and name the same file (after resolving links and `..`).
fn is_same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}
