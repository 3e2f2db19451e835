//! `cargo xtask vs-mitsuba [SCENE ...] [--no-suite] [--generate N [--seed S] [--res PIXELS]]
//! [--time SECONDS] [--runs N] [--by-time] [--variant V] [--strata-flags "FLAGS"]
//! [--mitsuba-ref SPP] [--strata-ref SPP]`: Strata against Mitsuba 3 at equal wall time, with Strata's defaults and
//! with tuned flags, on the suite's scenes and on scenes generated fresh from a seed.
//!
//! **Scenes.** The named scene files, or the suite's `cbox`, `cbox-glass` and `veach-mis` (none
//! with `--no-suite`), plus with `--generate N` the scenes `0..N` of seed `--seed` (default 1)
//! written by [`super::generate`] to `target/vs-mitsuba/generated/` at `--res` pixels square
//! (default 128). Every scene must load in Strata (`scene::load`) and in Mitsuba before anything
//! is rendered.
//!
//! **Strata's two rows.** *Defaults* is a plain `strata render` with no flag but the budget and
//! seed: `auto` chooses the sampler, adaptive sampling and the techniques by itself (its
//! technique pilot and adaptive pilot are part of the render, and of its reported time).
//! *Tuned* adds `--strata-flags` (default `--sampler sobol --adaptive`, the flags the README's
//! figures were once made with; `--strata-flags ""` leaves the row out).
//!
//! **Equal time.** Per scene, Mitsuba loads the file once and renders a warm-up image (its JIT
//! variants compile kernels on the first render); a 16-spp render gives a first sample count for
//! `--time` seconds (default 2). For each Strata row a render with that time budget (`--time`,
//! seed 0) gives a first count, pilots included (printed: it is what a user's `--time` render
//! reaches). Each count is then refined by renders at fixed counts (seed 0) until one takes
//! `--time` ([`refine`]). Each of `--runs` rounds (default 5) renders Mitsuba and each Strata row
//! at their counts with the round's seed, in turn, so all see the same machine load. Fixed counts
//! keep Strata's samplers laid out for the samples actually taken and its pilots sized for them;
//! `--by-time` renders Strata's rows with `--time` in every round instead, as a user would. The
//! renderers' times still differ a little, so Strata's relMSE is scaled to Mitsuba's time of the
//! same round (× Strata's seconds ÷ Mitsuba's, since relMSE falls as 1 / time); Strata's seconds
//! include its technique and adaptive pilots. Both read resolution and `max_depth` from the same
//! file and use every core.
//!
//! **References.** A suite scene is compared against its stored reference
//! `scenes/refs/NAME.exr` (Strata's, 15k–33k spp); a generated one against a Mitsuba render at
//! `--mitsuba-ref` samples (default 4096), which suite scenes get too when the option is given.
//! Mitsuba's reference is rendered in chunks of at most 256 spp (its wavefront holds every sample
//! of a render at once) summed into two halves with seeds of their own, and kept in
//! `target/vs-mitsuba/` under a name holding a hash of the scene file and the variant. The
//! halves give the relMSE the reference's own noise adds to every error measured against it
//! ([`noise::noise_term`]), which is subtracted from both renderers' errors before their ratio is
//! taken (a stored reference's noise is not known and taken as zero: its sample count is 100 to
//! 300 times those compared).
//!
//! **Agreement.** Where there is a Mitsuba reference, a high-sample-count Strata image is
//! compared with it: for a generated scene a defaults render at `--strata-ref` samples (default
//! 1024) in two halves, for a suite scene the stored reference (its noise taken as zero). Its
//! relMSE less the two images' noise terms estimates the squared bias between the renderers; when
//! that exceeds [`noise::DISAGREEMENT_SHARE`] of Strata's equal-time error, the renderers do not
//! render the scene alike, and the scene gets no verdict ("disagree") rather than a win that
//! may rest on a difference.
//!
//! **Report.** One block per scene as it is done, then a table: Mitsuba's and Strata's (defaults)
//! samples per pixel, the relMSE ratios Strata ÷ Mitsuba at equal time for both rows, the
//! agreement, what `auto` chose (sampler, adaptive sampling, technique pilot's label; with the
//! count of rounds when they differ) and whether the goal (defaults ratio ≤ [`GOAL`]) is met.
//! Everything reported is a median over the rounds. The exit status is 1 unless every scene meets
//! the goal. Never in CI: needs `pip install mitsuba` and, for the default `llvm_ad_rgb` variant,
//! `DRJIT_LIBLLVM_PATH` naming libLLVM (see the performance page of the book).

use super::generate;
use super::mitsuba_server::{self, MitsubaServer};
use super::noise::{self, Agreement};
use super::{median, positive, scene_path};
use render::driver::{RenderOptions, RenderOutput};
use render::image::Image;
use render::metrics::relmse;
use render::plan::plan_from_flags;
use render::session::{film_filter, render_scene};
use scene::RenderScene;
use std::path::{Path, PathBuf};

/// Scenes compared when none are named.
const DEFAULT_SCENES: [&str; 3] = ["cbox", "cbox-glass", "veach-mis"];

/// The tuned row's flags when `--strata-flags` is not given.
const DEFAULT_TUNED_FLAGS: &str = "--sampler sobol --adaptive";

/// Samples per pixel of Mitsuba's first calibration render.
const CALIBRATION_SPP: u32 = 16;

/// Most renders that refine a sample count towards `--time` ([`refine`]).
const CALIBRATION_STEPS: u32 = 3;

/// A refined sample count is kept once a step moves it by at most this share.
const CALIBRATION_TOLERANCE: f64 = 0.05;

/// The goal: Strata's defaults at most this share of Mitsuba's relMSE at equal time.
pub const GOAL: f64 = 0.25;

/// Samples per pixel of Mitsuba's reference for a generated scene when `--mitsuba-ref` is not
/// given.
const GENERATED_REFERENCE_SPP: u32 = 4096;

/// Samples per pixel of Strata's agreement render of a generated scene, unless `--strata-ref`.
const STRATA_REFERENCE_SPP: u32 = 1024;

/// Largest Mitsuba render of a reference, samples per pixel (more in one render would hold
/// every sample of the image in memory at once).
const REFERENCE_CHUNK_SPP: u32 = 256;

/// First seed of Mitsuba's reference chunks (the rounds use seeds 1 to `--runs`).
const MITSUBA_REFERENCE_SEED: u32 = 1_000_000;

/// Seed of the first half of Strata's agreement render (the second has the next one).
const STRATA_REFERENCE_SEED: u32 = 2_000_000;

/// Options of one comparison.
struct Options {
    scenes: Vec<PathBuf>,
    /// `--generate N --seed S`: (N, S).
    generate: Option<(u32, u32)>,
    resolution: u32,
    seconds: f64,
    runs: u32,
    variant: String,
    tuned_flags: Vec<String>,
    mitsuba_reference_spp: Option<u32>,
    strata_reference_spp: u32,
    /// `--by-time`: Strata's rows render with `--time` in every round.
    by_time: bool,
    out_dir: PathBuf,
}

/// One scene to compare.
struct Case {
    name: String,
    path: PathBuf,
    generated: bool,
}

/// A reference image and the relMSE its own noise adds to any image's error against it.
struct Reference {
    label: String,
    image: Image,
    noise: f64,
}

/// A Strata configuration: a label and the flags on top of the budget and seed.
struct Config {
    label: String,
    flags: Vec<String>,
}

/// One Strata render of a round.
struct StrataRound {
    seconds: f64,
    spp: u32,
    /// Raw relMSE against each reference.
    errors: Vec<f64>,
    /// What `auto` chose (sampler, adaptive sampling, techniques).
    choice: String,
}

/// One round of one scene.
struct Round {
    mitsuba_seconds: f64,
    /// Raw relMSE against each reference.
    mitsuba_errors: Vec<f64>,
    /// One per [`Config`].
    strata: Vec<StrataRound>,
}

/// A scene's line in the final table.
struct Outcome {
    name: String,
    mitsuba_spp: u32,
    strata_spp: f64,
    ratios: Vec<f64>,
    agreement: Option<Agreement>,
    choice: String,
}

impl Outcome {
    /// `met`, `not met`, or `disagree` when the renderers do not agree on the scene.
    fn verdict(&self) -> &'static str {
        if self.agreement.is_some_and(|a| !a.agrees()) {
            "disagree"
        } else if self.ratios[0] <= GOAL {
            "met"
        } else {
            "not met"
        }
    }
}

/// Runs `cargo xtask vs-mitsuba`; prints one block per scene and a summary table. False if some
/// scene does not meet the goal.
pub fn vs_mitsuba(root: &Path, args: &[String]) -> Result<bool, String> {
    let options = parse(root, args)?;
    std::fs::create_dir_all(&options.out_dir)
        .map_err(|e| format!("{}: {e}", options.out_dir.display()))?;
    let mut cases: Vec<Case> = options
        .scenes
        .iter()
        .map(|path| Case {
            name: stem(path),
            path: path.clone(),
            generated: false,
        })
        .collect();
    if let Some((count, seed)) = options.generate {
        let scenes = generate::generate(seed, count, options.resolution);
        let paths = generate::write(&options.out_dir.join("generated"), &scenes)?;
        cases.extend(scenes.iter().zip(paths).map(|(scene, path)| Case {
            name: scene.name.clone(),
            path,
            generated: true,
        }));
    }
    if cases.is_empty() {
        return Err("vs-mitsuba: no scenes (--no-suite without --generate)".to_string());
    }
    // Every scene loads in both renderers before anything is rendered.
    for case in &cases {
        scene::load(&case.path, &[]).map_err(|e| e.to_string())?;
    }
    let paths: Vec<PathBuf> = cases.iter().map(|c| c.path.clone()).collect();
    mitsuba_server::check_loads(&paths, &options.variant)?;

    let mut configs = vec![Config {
        label: "defaults".to_string(),
        flags: Vec::new(),
    }];
    if !options.tuned_flags.is_empty() {
        configs.push(Config {
            label: format!("tuned ({})", options.tuned_flags.join(" ")),
            flags: options.tuned_flags.clone(),
        });
    }
    println!(
        "Mitsuba 3 {} against Strata's defaults{}, about {} s per render, medians of {} rounds",
        options.variant,
        configs
            .get(1)
            .map_or(String::new(), |c| format!(" and {}", c.label)),
        options.seconds,
        options.runs
    );
    let mut outcomes = Vec::new();
    for case in &cases {
        outcomes.push(compare(case, &configs, &options)?);
    }
    print_table(&outcomes, &configs);
    Ok(outcomes.iter().all(|o| o.verdict() == "met"))
}

fn parse(root: &Path, args: &[String]) -> Result<Options, String> {
    let mut options = Options {
        scenes: Vec::new(),
        generate: None,
        resolution: 128,
        seconds: 2.0,
        runs: 5,
        variant: "llvm_ad_rgb".to_string(),
        tuned_flags: split_flags(DEFAULT_TUNED_FLAGS),
        mitsuba_reference_spp: None,
        strata_reference_spp: STRATA_REFERENCE_SPP,
        by_time: false,
        out_dir: root.join("target/vs-mitsuba"),
    };
    let mut suite = true;
    let mut count = None;
    let mut seed = 1;
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        match arg.as_str() {
            "--time" => options.seconds = positive("--time", rest.next())?,
            "--runs" => options.runs = positive("--runs", rest.next())?,
            "--mitsuba-ref" => {
                options.mitsuba_reference_spp = Some(positive("--mitsuba-ref", rest.next())?)
            }
            "--strata-ref" => {
                options.strata_reference_spp = positive("--strata-ref", rest.next())?;
            }
            "--variant" => {
                options.variant = rest.next().ok_or("--variant takes a name")?.clone();
            }
            "--strata-flags" => {
                let flags = rest.next().ok_or("--strata-flags takes a quoted list")?;
                options.tuned_flags = split_flags(flags);
            }
            "--generate" => count = Some(positive("--generate", rest.next())?),
            "--seed" => {
                seed = rest
                    .next()
                    .and_then(|s| s.parse().ok())
                    .ok_or("--seed takes a whole number")?;
            }
            "--res" => options.resolution = positive("--res", rest.next())?,
            "--no-suite" => suite = false,
            "--by-time" => options.by_time = true,
            other if !other.starts_with("--") => options.scenes.push(scene_path(root, other)),
            other => return Err(format!("vs-mitsuba: unknown argument {other}")),
        }
    }
    if let Some(flag) = options
        .tuned_flags
        .iter()
        .find(|f| ["--spp", "--time", "--seed"].contains(&f.as_str()))
    {
        return Err(format!(
            "--strata-flags: {flag} is vs-mitsuba's to set (the budget and seed are equal for both rows)"
        ));
    }
    if options.runs >= MITSUBA_REFERENCE_SEED {
        return Err(format!(
            "--runs takes fewer than {MITSUBA_REFERENCE_SEED} (the references' seeds)"
        ));
    }
    if options.strata_reference_spp < 2 {
        return Err("--strata-ref takes 2 or more (it is rendered in two halves)".to_string());
    }
    options.generate = count.map(|count| (count, seed));
    if options.scenes.is_empty() && suite {
        options.scenes = DEFAULT_SCENES
            .iter()
            .map(|name| scene_path(root, name))
            .collect();
    }
    Ok(options)
}

fn split_flags(flags: &str) -> Vec<String> {
    flags.split_whitespace().map(str::to_string).collect()
}

fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    )
}

/// Compares the renderers on one scene and prints its block.
fn compare(case: &Case, configs: &[Config], options: &Options) -> Result<Outcome, String> {
    let name = &case.name;
    let scene = scene::load(&case.path, &[]).map_err(|e| e.to_string())?;
    let out = |what: &str| options.out_dir.join(format!("{name}-{what}.exr"));
    let mut mitsuba = MitsubaServer::start(&case.path, &options.variant)?;

    // The references: the verdict's first; the Mitsuba reference's index; Strata's image
    // compared with it and that image's noise term.
    let mut references = Vec::new();
    let mut stored = None;
    if !case.generated {
        let path = case
            .path
            .parent()
            .map(|dir| dir.join("refs").join(format!("{name}.exr")))
            .ok_or("the scene has no directory")?;
        let image = read(&path)?;
        let spp = stored_spp(&path.with_extension("txt"));
        references.push(Reference {
            label: format!("stored reference ({spp})"),
            image: image.clone(),
            noise: 0.0,
        });
        stored = Some(image);
    }
    let mitsuba_spp_ref = options
        .mitsuba_reference_spp
        .or(case.generated.then_some(GENERATED_REFERENCE_SPP));
    let mut agreement_input = None;
    if let Some(spp) = mitsuba_spp_ref {
        let (a, b, taken) = mitsuba_reference(&mut mitsuba, case, spp, options)?;
        let image = noise::mean_of(&a, &b)?;
        let reference_noise = noise::noise_term(&a, &b, &image)?;
        let (strata_image, strata_noise, what) = match stored.take() {
            Some(stored) => (stored, 0.0, "the stored reference".to_string()),
            None => {
                let half = options.strata_reference_spp / 2;
                eprintln!("{name}: rendering Strata's defaults at 2 × {half} spp for agreement");
                let mut halves = Vec::new();
                for seed in [STRATA_REFERENCE_SEED, STRATA_REFERENCE_SEED + 1] {
                    let (half_image, _) = strata(&scene, &[], Budget::Spp(half), seed)?;
                    half_image
                        .write_exr(&out(&format!("strata-ref-{seed}")))
                        .map_err(|e| e.to_string())?;
                    halves.push(half_image);
                }
                let mean = noise::mean_of(&halves[0], &halves[1])?;
                let noise = noise::noise_term(&halves[0], &halves[1], &image)?;
                (
                    mean,
                    noise,
                    format!("Strata's defaults at {} spp", 2 * half),
                )
            }
        };
        let agreement_relmse = relmse(&strata_image, &image).map_err(|e| e.to_string())?;
        agreement_input = Some((
            references.len(),
            agreement_relmse,
            strata_noise + reference_noise,
            what,
        ));
        references.push(Reference {
            label: format!("Mitsuba {taken} spp"),
            image,
            noise: reference_noise,
        });
    }

    // Equal time: each renderer's sample count refined until a render at it takes `--time`.
    let target = options.seconds;
    let calibration = mitsuba.render(CALIBRATION_SPP, 0, &out("mitsuba-calibration"))?;
    let first = ((f64::from(CALIBRATION_SPP) * target / calibration).round() as u32).max(1);
    let mitsuba_spp = refine(first, target, |spp| {
        mitsuba.render(spp, 0, &out("mitsuba-calibration"))
    })?;
    let mut budgets = Vec::new();
    let mut time_budget_spp = Vec::new();
    for config in configs {
        let flags: Vec<&str> = config.flags.iter().map(String::as_str).collect();
        let (_, output) = strata(&scene, &flags, Budget::Seconds(target), 0)?;
        time_budget_spp.push(output.spp);
        budgets.push(if options.by_time {
            Budget::Seconds(target)
        } else {
            Budget::Spp(refine(output.spp.max(1), target, |spp| {
                Ok(strata(&scene, &flags, Budget::Spp(spp), 0)?.1.seconds)
            })?)
        });
    }

    let errors_of = |image: &Image| -> Result<Vec<f64>, String> {
        references
            .iter()
            .map(|r| relmse(image, &r.image).map_err(|e| e.to_string()))
            .collect()
    };
    let mut rounds = Vec::new();
    let mut reason = String::new();
    for seed in 1..=options.runs {
        let mitsuba_file = out(&format!("mitsuba-{seed}"));
        let mitsuba_seconds = mitsuba.render(mitsuba_spp, seed, &mitsuba_file)?;
        let mitsuba_errors = errors_of(&read(&mitsuba_file)?)?;
        let mut strata_rounds = Vec::new();
        for (i, config) in configs.iter().enumerate() {
            let flags: Vec<&str> = config.flags.iter().map(String::as_str).collect();
            let (image, output) = strata(&scene, &flags, budgets[i], seed)?;
            image
                .write_exr(&out(&format!(
                    "strata-{}-{seed}",
                    if i == 0 { "defaults" } else { "tuned" }
                )))
                .map_err(|e| e.to_string())?;
            if i == 0 && seed == 1 {
                reason = output
                    .auto
                    .as_ref()
                    .map_or("no technique pilot".to_string(), |a| {
                        format!(
                            "{} (pilot {:.3} s of {:.3} s)",
                            a.choice.reason(),
                            a.seconds,
                            output.seconds
                        )
                    });
            }
            strata_rounds.push(StrataRound {
                seconds: output.seconds,
                spp: output.spp,
                errors: errors_of(&image)?,
                choice: choice_label(&scene, &flags, &output)?,
            });
        }
        eprintln!(
            "{name} round {seed}: Mitsuba {mitsuba_spp} spp {mitsuba_seconds:.3} s relMSE {:.3e}; {}",
            mitsuba_errors[0],
            strata_rounds
                .iter()
                .zip(configs)
                .map(|(s, c)| format!(
                    "Strata {} {} spp {:.3} s relMSE {:.3e}",
                    c.label, s.spp, s.seconds, s.errors[0]
                ))
                .collect::<Vec<_>>()
                .join("; ")
        );
        rounds.push(Round {
            mitsuba_seconds,
            mitsuba_errors,
            strata: strata_rounds,
        });
    }

    // The block.
    let med = |f: &dyn Fn(&Round) -> f64| median(&rounds.iter().map(f).collect::<Vec<_>>());
    println!(
        "{name}: Mitsuba {mitsuba_spp} spp in {:.3} s; {}",
        med(&|r| r.mitsuba_seconds),
        configs
            .iter()
            .enumerate()
            .map(|(i, c)| format!(
                "Strata {} {} spp in {:.3} s (a `--time {target}` render: {} spp)",
                c.label,
                med(&|r| f64::from(r.strata[i].spp)),
                med(&|r| r.strata[i].seconds),
                time_budget_spp[i]
            ))
            .collect::<Vec<_>>()
            .join("; ")
    );
    let choice = most_common(
        &rounds
            .iter()
            .map(|r| r.strata[0].choice.clone())
            .collect::<Vec<_>>(),
    );
    println!("  auto chose {choice}: {reason}");
    for (i, config) in configs.iter().enumerate().skip(1) {
        let labels: Vec<String> = rounds.iter().map(|r| r.strata[i].choice.clone()).collect();
        println!("  {} ran {}", config.label, most_common(&labels));
    }
    let mut verdict_ratios = Vec::new();
    for (r, reference) in references.iter().enumerate() {
        let mitsuba_error = med(&|round| round.mitsuba_errors[r] - reference.noise);
        let noise = if reference.noise > 0.0 {
            format!("its noise {:.2e} removed", reference.noise)
        } else {
            "its noise not known, taken as 0".to_string()
        };
        println!(
            "  against {} ({noise}): relMSE Mitsuba {mitsuba_error:.3e}",
            reference.label
        );
        for (i, config) in configs.iter().enumerate() {
            let raw = med(&|round| round.strata[i].errors[r] - reference.noise);
            let scaled_of = |round: &Round| {
                (round.strata[i].errors[r] - reference.noise) * round.strata[i].seconds
                    / round.mitsuba_seconds
            };
            let scaled = med(&scaled_of);
            let ratios: Vec<f64> = rounds
                .iter()
                .map(|round| scaled_of(round) / (round.mitsuba_errors[r] - reference.noise))
                .collect();
            let (least, most) = ratios
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
                    (lo.min(x), hi.max(x))
                });
            let ratio = scaled / mitsuba_error;
            println!(
                "    Strata {}: relMSE {raw:.3e} (scaled to equal time {scaled:.3e}); \
                 Strata / Mitsuba = {ratio:.3} (rounds {least:.2}–{most:.2})",
                config.label
            );
            if r == 0 {
                verdict_ratios.push(ratio);
            }
        }
    }
    let agreement = agreement_input.map(|(r, relmse, noise, what)| {
        let agreement = Agreement {
            relmse,
            noise,
            strata_error: med(&|round| round.strata[0].errors[r] - references[r].noise),
        };
        println!(
            "  agreement: {what} against {}: relMSE {relmse:.3e}, noise {noise:.3e}, excess \
             {:.2e} = {:.1}% of Strata's equal-time error: {}",
            references[r].label,
            agreement.excess(),
            100.0 * agreement.share(),
            if agreement.agrees() {
                "the renderers agree"
            } else {
                "THE RENDERERS DISAGREE: no verdict"
            }
        );
        agreement
    });
    Ok(Outcome {
        name: name.clone(),
        mitsuba_spp,
        strata_spp: med(&|r| f64::from(r.strata[0].spp)),
        ratios: verdict_ratios,
        agreement,
        choice,
    })
}

/// How long a Strata render runs.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Budget {
    /// `--spp N`.
    Spp(u32),
    /// `--time SECONDS`.
    Seconds(f64),
}

/// Strata in-process: the scene with `flags`, `budget` and `seed`.
fn strata(
    scene: &RenderScene,
    flags: &[&str],
    budget: Budget,
    seed: u32,
) -> Result<(Image, RenderOutput), String> {
    let (budget_flag, amount) = match budget {
        Budget::Spp(spp) => ("--spp", spp.to_string()),
        Budget::Seconds(seconds) => ("--time", seconds.to_string()),
    };
    let seed = seed.to_string();
    let mut flags = flags.to_vec();
    flags.extend([budget_flag, &amount, "--seed", &seed]);
    let plan = plan_from_flags(scene, &flags)?;
    let (output, _) = render_scene(scene, &plan, &filter(scene)?, &RenderOptions::quiet())
        .map_err(|e| e.to_string())?;
    Ok((output.film.to_image(), output))
}

fn filter(scene: &RenderScene) -> Result<render::filter::Filter, String> {
    film_filter(scene.desc.film.filter).map_err(|e| e.to_string())
}

/// What a render with `flags` ran with: sampler, adaptive sampling, and `auto`'s label.
fn choice_label(
    scene: &RenderScene,
    flags: &[&str],
    output: &RenderOutput,
) -> Result<String, String> {
    let plan = plan_from_flags(scene, flags)?;
    let sampler = plan.sampler.to_string();
    let adaptive = if output.pilot_spp > 0 {
        " adaptive"
    } else {
        ""
    };
    let label = output
        .auto
        .as_ref()
        .map_or("(no auto)".to_string(), |a| a.choice.label.clone());
    Ok(format!("{sampler}{adaptive} {label}"))
}

/// Sample count whose render takes about `target` seconds, starting from `spp`: `render(n)`
/// renders `n` samples per pixel and returns its seconds, and the count is scaled by target ÷
/// seconds until it moves by at most [`CALIBRATION_TOLERANCE`] or after [`CALIBRATION_STEPS`]
/// renders (fixed costs such as pilots make time not quite proportional to samples).
fn refine(
    mut spp: u32,
    target: f64,
    mut render: impl FnMut(u32) -> Result<f64, String>,
) -> Result<u32, String> {
    for _ in 0..CALIBRATION_STEPS {
        let seconds = render(spp)?;
        let next = ((f64::from(spp) * target / seconds.max(1e-6)).round() as u32).max(1);
        let moved = (f64::from(next) - f64::from(spp)).abs() / f64::from(spp);
        spp = next;
        if moved <= CALIBRATION_TOLERANCE {
            break;
        }
    }
    Ok(spp)
}

/// The most frequent of `labels`, with its count of rounds when they are not all the same.
fn most_common(labels: &[String]) -> String {
    let mut best: Option<(&String, usize)> = None;
    for label in labels {
        let count = labels.iter().filter(|l| *l == label).count();
        if best.is_none_or(|(_, most)| count > most) {
            best = Some((label, count));
        }
    }
    match best {
        None => String::new(),
        Some((label, count)) if count == labels.len() => label.clone(),
        Some((label, count)) => format!("{label} ({count}/{})", labels.len()),
    }
}

/// Mitsuba's reference for `case` at about `spp` samples per pixel, as two halves of equal
/// sample counts, from `target/vs-mitsuba/` when made before; also the samples taken in all.
fn mitsuba_reference(
    mitsuba: &mut MitsubaServer,
    case: &Case,
    spp: u32,
    options: &Options,
) -> Result<(Image, Image, u32), String> {
    let text = std::fs::read(&case.path).map_err(|e| format!("{}: {e}", case.path.display()))?;
    let key = fnv1a(&[&text, options.variant.as_bytes()]);
    let chunks = spp.div_ceil(REFERENCE_CHUNK_SPP).max(2).next_multiple_of(2);
    let chunk_spp = spp.div_ceil(chunks);
    let half_spp = chunk_spp * chunks / 2;
    let file = |half: &str| {
        options.out_dir.join(format!(
            "{}-mitsuba-ref-{spp}-{key:016x}-{half}.exr",
            case.name
        ))
    };
    let (file_a, file_b) = (file("a"), file("b"));
    let cached = |path: &Path| {
        Image::read_exr_with_spp(path)
            .ok()
            .filter(|(_, recorded)| *recorded == Some(half_spp))
            .map(|(image, _)| image)
    };
    if let (Some(a), Some(b)) = (cached(&file_a), cached(&file_b)) {
        return Ok((a, b, 2 * half_spp));
    }
    eprintln!(
        "{}: rendering the Mitsuba reference, {chunks} × {chunk_spp} spp",
        case.name
    );
    let chunk_file = options
        .out_dir
        .join(format!("{}-mitsuba-chunk.exr", case.name));
    let mut halves: [Option<Image>; 2] = [None, None];
    for chunk in 0..chunks {
        mitsuba.render(chunk_spp, MITSUBA_REFERENCE_SEED + chunk, &chunk_file)?;
        let image = read(&chunk_file)?;
        let half = &mut halves[(chunk % 2) as usize];
        match half {
            None => *half = Some(image),
            Some(sum) => {
                for (s, x) in sum.data.iter_mut().zip(&image.data) {
                    *s += *x;
                }
            }
        }
    }
    let _ = std::fs::remove_file(&chunk_file);
    let scale = 2.0 / chunks as f32;
    let [Some(mut a), Some(mut b)] = halves else {
        unreachable!("at least two chunks");
    };
    for image in [&mut a, &mut b] {
        image.data.iter_mut().for_each(|p| *p *= scale);
    }
    a.write_exr_with_spp(&file_a, half_spp)
        .map_err(|e| e.to_string())?;
    b.write_exr_with_spp(&file_b, half_spp)
        .map_err(|e| e.to_string())?;
    Ok((a, b, 2 * half_spp))
}

/// FNV-1a, 64 bits, over `parts` in turn: the cache key of a reference.
fn fnv1a(parts: &[&[u8]]) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for byte in parts.iter().flat_map(|p| p.iter()) {
        hash ^= u64::from(*byte);
        hash = hash.wrapping_mul(0x0100_0000_01b3);
    }
    hash
}

/// "N spp" from a stored reference's `NAME.txt` (`spp: N`), or "spp unknown".
fn stored_spp(path: &Path) -> String {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|text| {
            text.lines().find_map(|line| {
                line.strip_prefix("spp: ")
                    .map(|n| format!("{} spp", n.trim()))
            })
        })
        .unwrap_or_else(|| "spp unknown".to_string())
}

/// Prints the summary table of `outcomes`.
fn print_table(outcomes: &[Outcome], configs: &[Config]) {
    println!();
    println!(
        "Strata ÷ Mitsuba relMSE at equal time (medians); goal: defaults ≤ {GOAL}{}",
        configs
            .get(1)
            .map_or(String::new(), |c| format!("; tuned = {}", c.label))
    );
    println!(
        "{:<16} {:>9} {:>9} {:>9} {:>9} {:>10}  {:<38} goal",
        "scene", "Mitsuba", "Strata", "defaults", "tuned", "bias²/err", "auto chose"
    );
    for o in outcomes {
        let tuned = o
            .ratios
            .get(1)
            .map_or("-".to_string(), |r| format!("{r:.3}"));
        let agreement = o
            .agreement
            .map_or("-".to_string(), |a| format!("{:.1}%", 100.0 * a.share()));
        println!(
            "{:<16} {:>9} {:>9} {:>9.3} {:>9} {:>10}  {:<38} {}",
            o.name,
            o.mitsuba_spp,
            o.strata_spp,
            o.ratios[0],
            tuned,
            agreement,
            o.choice,
            o.verdict()
        );
    }
    println!(
        "(Mitsuba / Strata: samples per pixel at equal time; bias²/err: the renderers' estimated \
         squared difference as a share of Strata's error, '-' without a Mitsuba reference)"
    );
}

fn read(path: &Path) -> Result<Image, String> {
    Image::read_exr(path).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn defaults_are_the_suite_and_a_tuned_row() {
        let options = parse(Path::new("/r"), &[]).unwrap();
        assert_eq!(options.scenes.len(), 3);
        assert_eq!(options.tuned_flags, ["--sampler", "sobol", "--adaptive"]);
        assert_eq!(options.generate, None);
        let options = parse(
            Path::new("/r"),
            &args(&[
                "--no-suite",
                "--generate",
                "5",
                "--seed",
                "9",
                "--strata-flags",
                "",
            ]),
        )
        .unwrap();
        assert!(options.scenes.is_empty());
        assert_eq!(options.generate, Some((5, 9)));
        assert!(options.tuned_flags.is_empty());
    }

    #[test]
    fn the_budget_and_seed_are_not_tuned_flags() {
        for flag in ["--spp", "--time", "--seed"] {
            let error = parse(
                Path::new("/r"),
                &args(&["--strata-flags", &format!("{flag} 4")]),
            );
            assert!(error.is_err_and(|e| e.contains(flag)), "{flag}");
        }
        assert!(parse(Path::new("/r"), &args(&["--generate", "0"])).is_err());
        assert!(parse(Path::new("/r"), &args(&["--bogus"])).is_err());
    }

    #[test]
    fn the_verdict_needs_the_goal_and_agreement() {
        let outcome = |ratio: f64, relmse: Option<f64>| Outcome {
            name: String::new(),
            mitsuba_spp: 1,
            strata_spp: 1.0,
            ratios: vec![ratio],
            agreement: relmse.map(|relmse| Agreement {
                relmse,
                noise: 1e-4,
                strata_error: 1e-3,
            }),
            choice: String::new(),
        };
        assert_eq!(outcome(0.2, None).verdict(), "met");
        assert_eq!(outcome(0.3, None).verdict(), "not met");
        assert_eq!(outcome(0.2, Some(1.5e-4)).verdict(), "met");
        // An excess of 40% of Strata's error: a win on this scene would not count.
        assert_eq!(outcome(0.2, Some(5e-4)).verdict(), "disagree");
    }

    /// A renderer with a fixed cost of 0.3 s and 0.01 s per sample: 2 s take 170 samples.
    #[test]
    fn refining_finds_the_count_that_takes_the_target_time() {
        let mut renders = 0;
        let spp = refine(40, 2.0, |spp| {
            renders += 1;
            Ok(0.3 + 0.01 * f64::from(spp))
        })
        .unwrap();
        assert!((160..=180).contains(&spp), "{spp}");
        assert!(renders <= CALIBRATION_STEPS);
        // Proportional time: one render finds it.
        renders = 0;
        let spp = refine(50, 2.0, |spp| {
            renders += 1;
            Ok(0.01 * f64::from(spp))
        })
        .unwrap();
        assert_eq!((spp, renders), (200, 2));
    }

    #[test]
    fn the_most_common_label_says_when_rounds_differ() {
        let labels = args(&["a", "b", "a"]);
        assert_eq!(most_common(&labels), "a (2/3)");
        assert_eq!(most_common(&args(&["b", "b"])), "b");
    }

    #[test]
    fn the_cache_key_follows_every_byte() {
        assert_ne!(fnv1a(&[b"scene", b"llvm"]), fnv1a(&[b"scene", b"scalar"]));
        assert_ne!(fnv1a(&[b"a"]), fnv1a(&[b"b"]));
        // The published FNV-1a 64 test vector for "a".
        assert_eq!(fnv1a(&[b"a"]), 0xaf63_dc4c_8601_ec8c);
    }
}
