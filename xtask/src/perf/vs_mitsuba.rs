//! `cargo xtask vs-mitsuba [SCENE ...] [--time SECONDS] [--runs N] [--variant V]
//! [--strata-flags "FLAGS"] [--mitsuba-ref SPP]`: Strata against Mitsuba 3 at equal wall time.
//!
//! For each scene (default: cbox, cbox-glass, veach-mis) Mitsuba loads the scene file once and
//! renders a warm-up image (its JIT variants compile kernels on the first render); a 16-spp render
//! then calibrates the sample count that takes Mitsuba about `--time` seconds (default 2), and a
//! Strata render with that time budget (`auto` with `--sampler sobol --adaptive` unless
//! `--strata-flags` say otherwise) gives Strata's sample count for the same time. Each of `--runs` rounds (default 5) then renders
//! Mitsuba and Strata (in-process) at their sample counts with the round's seed, alternating so
//! both see the same machine load. Fixed sample counts rather than Strata's `--time` keep its
//! stratified and blue-noise samplers laid out for the samples actually taken (under a time
//! budget they are laid out for 4096). Both read resolution and `max_depth` from the same file;
//! both use every core.
//!
//! Error is relMSE against the stored reference `scenes/refs/NAME.exr`; with `--mitsuba-ref SPP`
//! also against a Mitsuba render at SPP samples (made once, kept in `target/vs-mitsuba/`), and
//! the two references' relMSE to each other is printed so a disagreement between the renderers
//! shows up as a floor. The two renderers' times differ a little from round to round, so
//! Strata's relMSE is also given scaled to Mitsuba's time of the same round (relMSE × Strata's
//! seconds ÷ Mitsuba's seconds, since relMSE falls as 1 / time), and the verdict uses that
//! scaled figure.
//! Everything reported is a median over the rounds. Never in CI: needs `pip install mitsuba` and,
//! for the default `llvm_ad_rgb` variant, `DRJIT_LIBLLVM_PATH` pointing at libLLVM (see README).

use super::mitsuba_server::MitsubaServer;
use super::{median, positive, scene_path};
use render::driver::{RenderOptions, RenderOutput};
use render::image::Image;
use render::metrics::relmse;
use render::session::{film_filter, render_scene};
use render::technique::plan_from_flags;
use std::path::{Path, PathBuf};

/// Scenes compared when none are named.
const DEFAULT_SCENES: [&str; 3] = ["cbox", "cbox-glass", "veach-mis"];

/// Strata's flags when `--strata-flags` is not given: the `auto` integrator (the default, with
/// caustics by light tracing where they apply) and what is not a switch of the integrator: the
/// Sobol sampler (the scene files ask for `independent`, which Mitsuba uses) and adaptive
/// sampling.
const DEFAULT_STRATA_FLAGS: [&str; 3] = ["--sampler", "sobol", "--adaptive"];

/// Samples per pixel of the calibration render.
const CALIBRATION_SPP: u32 = 16;

/// Seed of the Mitsuba reference render (above any round's seed).
const REFERENCE_SEED: u32 = 1000;

/// Options of one comparison.
struct Options {
    scenes: Vec<PathBuf>,
    seconds: f64,
    runs: u32,
    variant: String,
    strata_flags: Vec<String>,
    mitsuba_reference_spp: Option<u32>,
    out_dir: PathBuf,
}

/// One round of one scene.
struct Round {
    mitsuba_seconds: f64,
    strata_seconds: f64,
    strata_spp: u32,
    /// relMSE against each reference: (Mitsuba, Strata).
    errors: Vec<(f64, f64)>,
}

/// Runs `cargo xtask vs-mitsuba`; prints one block per scene. False if Strata's time-scaled
/// relMSE is not below Mitsuba's on every scene against the stored reference.
pub fn vs_mitsuba(root: &Path, args: &[String]) -> Result<bool, String> {
    let options = parse(root, args)?;
    std::fs::create_dir_all(&options.out_dir)
        .map_err(|e| format!("{}: {e}", options.out_dir.display()))?;
    println!(
        "Mitsuba 3 {} against Strata {:?}, about {} s per render, medians of {} rounds",
        options.variant, options.strata_flags, options.seconds, options.runs
    );
    let mut all_lower = true;
    for scene in &options.scenes {
        all_lower &= compare(scene, &options)?;
    }
    Ok(all_lower)
}

fn parse(root: &Path, args: &[String]) -> Result<Options, String> {
    let mut options = Options {
        scenes: Vec::new(),
        seconds: 2.0,
        runs: 5,
        variant: "llvm_ad_rgb".to_string(),
        strata_flags: DEFAULT_STRATA_FLAGS.iter().map(|f| f.to_string()).collect(),
        mitsuba_reference_spp: None,
        out_dir: root.join("target/vs-mitsuba"),
    };
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        match arg.as_str() {
            "--time" => options.seconds = positive("--time", rest.next())?,
            "--runs" => options.runs = positive("--runs", rest.next())?,
            "--mitsuba-ref" => {
                options.mitsuba_reference_spp = Some(positive("--mitsuba-ref", rest.next())?)
            }
            "--variant" => {
                options.variant = rest.next().ok_or("--variant takes a name")?.clone();
            }
            "--strata-flags" => {
                let flags = rest.next().ok_or("--strata-flags takes a quoted list")?;
                options.strata_flags = flags.split_whitespace().map(str::to_string).collect();
            }
            other if !other.starts_with("--") => options.scenes.push(scene_path(root, other)),
            other => return Err(format!("vs-mitsuba: unknown argument {other}")),
        }
    }
    if options.scenes.is_empty() {
        options.scenes = DEFAULT_SCENES
            .iter()
            .map(|name| scene_path(root, name))
            .collect();
    }
    Ok(options)
}

/// Compares the renderers on `path`; true if Strata's scaled relMSE is the lower one.
fn compare(path: &Path, options: &Options) -> Result<bool, String> {
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .ok_or_else(|| format!("{}: no file name", path.display()))?;
    let scene = scene::load(path, &[]).map_err(|e| e.to_string())?;
    let filter = film_filter(scene.desc.film.filter).map_err(|e| e.to_string())?;
    let stored = path
        .parent()
        .map(|dir| dir.join("refs").join(format!("{name}.exr")))
        .ok_or("the scene has no directory")?;
    let mut references = vec![("stored reference".to_string(), read(&stored)?)];

    let mut mitsuba = MitsubaServer::start(path, &options.variant)?;
    let out = |what: &str| options.out_dir.join(format!("{name}-{what}.exr"));
    if let Some(spp) = options.mitsuba_reference_spp {
        let file = out(&format!("mitsuba-ref-{spp}"));
        if !file.exists() {
            eprintln!("{name}: rendering the Mitsuba reference at {spp} spp");
            mitsuba.render(spp, REFERENCE_SEED, &file)?;
        }
        let mitsuba_reference = read(&file)?;
        let agreement = relmse(&mitsuba_reference, &references[0].1).map_err(|e| e.to_string())?;
        println!("{name}: relMSE of the Mitsuba reference against the stored one: {agreement:.3e}");
        references.push((format!("Mitsuba {spp} spp"), mitsuba_reference));
    }
    let calibration = mitsuba.render(CALIBRATION_SPP, 0, &out("mitsuba-calibration"))?;
    let mitsuba_spp =
        ((f64::from(CALIBRATION_SPP) * options.seconds / calibration).round() as u32).max(1);
    let strata = |flags: &[&str]| -> Result<(Image, RenderOutput), String> {
        let mut flags = flags.to_vec();
        flags.extend(options.strata_flags.iter().map(String::as_str));
        let plan = plan_from_flags(&scene, &flags)?;
        let (output, _) = render_scene(&scene, &plan, &filter, &RenderOptions::quiet())
            .map_err(|e| e.to_string())?;
        Ok((output.film.to_image(), output))
    };
    let strata_spp = strata(&["--time", &options.seconds.to_string(), "--seed", "0"])?
        .1
        .spp
        .to_string();

    let mut rounds = Vec::new();
    for seed in 1..=options.runs {
        let mitsuba_file = out(&format!("mitsuba-{seed}"));
        let mitsuba_seconds = mitsuba.render(mitsuba_spp, seed, &mitsuba_file)?;
        let mitsuba_image = read(&mitsuba_file)?;

        let (strata_image, output) = strata(&["--spp", &strata_spp, "--seed", &seed.to_string()])?;
        strata_image
            .write_exr(&out(&format!("strata-{seed}")))
            .map_err(|e| e.to_string())?;

        let errors = references
            .iter()
            .map(|(_, reference)| {
                Ok((
                    relmse(&mitsuba_image, reference)?,
                    relmse(&strata_image, reference)?,
                ))
            })
            .collect::<Result<Vec<_>, render::metrics::SizeMismatch>>()
            .map_err(|e| e.to_string())?;
        eprintln!(
            "{name} round {seed}: Mitsuba {mitsuba_spp} spp {mitsuba_seconds:.3} s relMSE {:.3e}; \
             Strata {} spp {:.3} s relMSE {:.3e}",
            errors[0].0, output.spp, output.seconds, errors[0].1
        );
        rounds.push(Round {
            mitsuba_seconds,
            strata_seconds: output.seconds,
            strata_spp: output.spp,
            errors,
        });
    }
    Ok(summarise(&name, &references, &rounds, mitsuba_spp))
}

/// Prints the medians of `rounds`; true if Strata's scaled relMSE against the first reference is
/// below Mitsuba's.
fn summarise(
    name: &str,
    references: &[(String, Image)],
    rounds: &[Round],
    mitsuba_spp: u32,
) -> bool {
    let med = |f: &dyn Fn(&Round) -> f64| median(&rounds.iter().map(f).collect::<Vec<_>>());
    println!(
        "{name}: Mitsuba {mitsuba_spp} spp in {:.3} s; Strata {} spp in {:.3} s",
        med(&|r| r.mitsuba_seconds),
        med(&|r| f64::from(r.strata_spp)),
        med(&|r| r.strata_seconds),
    );
    let mut lower = true;
    for (i, (reference, _)) in references.iter().enumerate() {
        let mitsuba = med(&|r| r.errors[i].0);
        let strata = med(&|r| r.errors[i].1);
        let scaled_of = |r: &Round| r.errors[i].1 * r.strata_seconds / r.mitsuba_seconds;
        let scaled = med(&scaled_of);
        // The spread of the rounds' own ratios shows how far the machine's load moved them.
        let ratios: Vec<f64> = rounds
            .iter()
            .map(|r| scaled_of(r) / r.errors[i].0)
            .collect();
        let (least, most) = ratios
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
                (lo.min(x), hi.max(x))
            });
        println!(
            "  against {reference}: relMSE Mitsuba {mitsuba:.3e}, Strata {strata:.3e} \
             (scaled to equal time {scaled:.3e}); Strata / Mitsuba = {:.2} \
             (rounds {least:.2}–{most:.2})",
            scaled / mitsuba
        );
        if i == 0 {
            lower = scaled < mitsuba;
        }
    }
    lower
}

fn read(path: &Path) -> Result<Image, String> {
    Image::read_exr(path).map_err(|e| format!("{}: {e}", path.display()))
}
