//! `cargo xtask render-all`: every configuration of each scene's ladder at a geometric series of
//! time budgets, measured against the stored reference.

use super::error_map::error_map;
use super::ladder::{Configuration, ladder};
use super::preview::{exposed, exposure};
use super::report::{
    AUTO, AutoRecord, Measurement, RunInfo, Rung, STORED_REFERENCE, SceneReport, write_report,
};
use super::{SuiteScene, command_output, parse_scene_list, reference_path, scene_files};
use render::auto::MAX_PILOT_SHARE;
use render::driver::{RenderBudget, RenderOptions, RenderOutput};
use render::image::Image;
use render::metrics::{relmse, rmse};
use render::plan::{AUTO_ADAPTIVE_MIN_SPP, RenderPlan, TIME_BUDGET_NOMINAL_SPP, plan_from_flags};
use render::progress::Progress;
use render::session::{film_filter, render_scene};
use std::path::Path;

/// Time budgets in seconds of the full run. Three budgets of three seeds each fit the run in
/// its 10 minutes on 2 cores (four budgets up to 2 s did with one seed); a 4× range still
/// shows the convergence slope.
const FULL_BUDGETS: &[f64] = &[0.2, 0.4, 0.8];

/// Time budgets in seconds of `--quick` (within 2 minutes for the whole suite).
const QUICK_BUDGETS: &[f64] = &[0.05, 0.15];

/// Seeds rendered at every budget: with three, the flag "auto worse than the best beyond the
/// spread" has a 5% chance when the two are alike (see `SceneSummary::auto_flagged`).
const SEEDS: u32 = 3;

/// Seed of render `replica` at budget index `budget`: distinct for every render of a
/// configuration, and below the references' seed (1000) for any budget series this short.
fn seed(budget: usize, replica: u32) -> u32 {
    1 + budget as u32 * SEEDS + replica
}

/// Runs `cargo xtask render-all [--quick] [--scenes A,B]`; writes the report under
/// `target/report/`.
pub fn render_all(root: &Path, args: &[String]) -> Result<bool, String> {
    let mut budgets = FULL_BUDGETS;
    let mut only = Vec::new();
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        match arg.as_str() {
            "--quick" => budgets = QUICK_BUDGETS,
            "--scenes" => only = parse_scene_list(rest.next())?,
            other => return Err(format!("render-all: unknown argument {other}")),
        }
    }
    let out_dir = root.join("target/report");
    let mut reports = Vec::new();
    let files = scene_files(root, &only)?;
    let progress = Progress::new(true);
    for (scene_index, file) in files.iter().enumerate() {
        let suite = SuiteScene::load(file)?;
        let reference_file = reference_path(root, &suite.name);
        let reference = Image::read_exr(&reference_file).map_err(|e| {
            format!(
                "{e}\nno stored reference for {}: run `cargo xtask refs` first",
                suite.name
            )
        })?;
        let scene_dir = out_dir.join(&suite.name);
        std::fs::create_dir_all(&scene_dir).map_err(|e| format!("{}: {e}", scene_dir.display()))?;
        let scene_exposure = exposure(&reference);
        let write_images = |name: &str, image: &Image| -> Result<(), String> {
            exposed(image, scene_exposure)
                .write_png(&scene_dir.join(format!("{name}.png")))
                .map_err(|e| e.to_string())?;
            image
                .write_exr(&scene_dir.join(format!("{name}.exr")))
                .map_err(|e| e.to_string())
        };
        write_images(STORED_REFERENCE, &reference)?;
        let auto = plan_from_flags(&suite.scene, &[])?;
        let configurations = ladder(&suite.transport(), &suite.scene.features, &auto);
        let mut measurements = Vec::new();
        let mut auto_choices = Vec::new();
        for (c, configuration) in configurations.iter().enumerate() {
            progress.set_message(format!("{} / {}", suite.name, configuration.name));
            let mut rate = None;
            for (i, &seconds) in budgets.iter().enumerate() {
                let last_budget = i + 1 == budgets.len();
                // Samples per pixel that fit the budget: at the rate of the previous budget's
                // renders, or measured by a short render. `auto`'s technique pilot takes up to
                // `MAX_PILOT_SHARE` of the samples of a render of known samples per pixel
                // (fewer where the budget cannot pay for it), so `auto` is measured afresh at
                // every budget and its image given the rest.
                let spp_per_second = match rate {
                    Some(rate) if !configuration.trials.any() => rate,
                    _ => measure_rate(&suite, configuration, seconds, seed(i, 0))?,
                };
                let share = if configuration.trials.any() {
                    1.0 - MAX_PILOT_SHARE
                } else {
                    1.0
                };
                let mut spp = ((spp_per_second * seconds * share) as u32)
                    .clamp(1, TIME_BUDGET_NOMINAL_SPP * 16);
                let mut rates = Vec::new();
                let mut recalibrated = false;
                let mut replica = 0;
                while replica < SEEDS {
                    let seed = seed(i, replica);
                    let (measurement, output) =
                        measure(&suite, configuration, &reference, seed, spp, seconds)?;
                    // The estimate can miss (a pilot run at another size than in the rate
                    // render, a change in the machine's load): when the first seed's time is
                    // off the budget by more than 30% below or 40% above, the samples are
                    // rescaled once and the seeds started again.
                    let off = output.seconds / seconds;
                    let rescaled = ((f64::from(spp) / off.max(1e-6)) as u32)
                        .clamp(1, TIME_BUDGET_NOMINAL_SPP * 16);
                    if replica == 0 && !recalibrated && !(0.7..=1.4).contains(&off) {
                        recalibrated = true;
                        if rescaled != spp {
                            spp = rescaled;
                            continue;
                        }
                    }
                    rates.push(f64::from(output.spp) / output.seconds.max(1e-6));
                    if last_budget && configuration.name == AUTO {
                        auto_choices.push(auto_record(seed, configuration, &output));
                    }
                    if last_budget && replica + 1 == SEEDS {
                        let image = output.film.to_image();
                        write_images(&configuration.name, &image)?;
                        error_map(&image, &reference)?
                            .write_png(&scene_dir.join(format!("{}-error.png", configuration.name)))
                            .map_err(|e| e.to_string())?;
                    }
                    progress.println(progress_line(&suite.name, &measurement));
                    measurements.push(measurement);
                    replica += 1;
                }
                // The next budget's samples per second: the median of these renders'.
                rates.sort_by(f64::total_cmp);
                rate = Some(rates[rates.len() / 2]);
                let done_in_scene = (c * budgets.len() + i + 1) as f64
                    / (configurations.len() * budgets.len()) as f64;
                progress.set_fraction((scene_index as f64 + done_in_scene) / files.len() as f64);
            }
        }
        reports.push(SceneReport {
            scene: suite.name.clone(),
            rungs: configurations
                .iter()
                .map(|c| Rung {
                    name: c.name.clone(),
                    builds_on: c.builds_on.clone(),
                    techniques: c.techniques(),
                })
                .collect(),
            auto_choices,
            measurements,
            exposure: scene_exposure,
        });
    }
    progress.finish();
    let run = RunInfo {
        commit: command_output("git", &["-C", &root.to_string_lossy(), "rev-parse", "HEAD"]),
        budgets: budgets.to_vec(),
        seeds: SEEDS,
    };
    write_report(&out_dir, &reports, &run)?;
    Ok(true)
}

/// One line of progress: the scene, configuration, budget, seed, samples and relMSE.
fn progress_line(scene: &str, m: &Measurement) -> String {
    format!(
        "{:<16} {:<15} {:>5.2} s budget, seed {:>2}: {:>5} spp relMSE {:.3e}{}",
        scene,
        m.configuration,
        m.budget,
        m.seed,
        m.spp,
        m.relmse,
        if m.non_finite > 0 {
            format!(" ({} NaN or infinite samples left out)", m.non_finite)
        } else {
            String::new()
        }
    )
}

/// What the `auto` rung rendered with, seeded `seed`: the settings its pilot chose (its base
/// where nothing was to be tried), the sampler, and adaptive sampling where it ran.
fn auto_record(seed: u32, configuration: &Configuration, output: &RenderOutput) -> AutoRecord {
    let (label, mut techniques, reason) = match &output.auto {
        Some(pilot) => (
            pilot.choice.label.clone(),
            pilot.choice.settings.technique_names(),
            pilot.choice.reason(),
        ),
        None => (
            "base".to_string(),
            configuration.transport.technique_names(),
            "no pilot: nothing for it to try on this scene".to_string(),
        ),
    };
    techniques.push(format!("sampler-{}", configuration.sampler));
    if output.pilot_spp > 0 {
        techniques.push("adaptive-sampling".to_string());
    }
    AutoRecord {
        seed,
        label,
        techniques,
        reason,
    }
}

/// The samples per pixel per second `output` rendered its image at, leaving out `auto`'s
/// technique pilot, and the seconds that pilot took.
fn image_rate_of(output: &RenderOutput) -> (f64, f64) {
    let pilot = output.auto.as_ref().map_or(0.0, |p| p.seconds);
    let image_seconds = (output.seconds - pilot).max(1e-6);
    (f64::from(output.spp) / image_seconds, pilot)
}

/// The samples per pixel per second of `configuration`'s image ([`image_rate_of`]), from a
/// render of a tenth of `seconds` (at least 0.05 s, so that thread start-up does not dominate
/// it). When `auto`'s technique pilot (run at full size under a time budget) leaves that render
/// less than 0.03 s for the image, it is rendered again with 0.05 s more than the pilot took.
fn measure_rate(
    suite: &SuiteScene,
    configuration: &Configuration,
    seconds: f64,
    seed: u32,
) -> Result<f64, String> {
    let budget = |seconds| RenderBudget {
        max_spp: None,
        max_seconds: Some(seconds),
    };
    let first = render(
        suite,
        configuration,
        seed,
        budget((0.1 * seconds).max(0.05)),
        TIME_BUDGET_NOMINAL_SPP,
    )?;
    let (rate, pilot) = image_rate_of(&first);
    if first.seconds - pilot >= 0.03 {
        return Ok(rate);
    }
    let again = render(
        suite,
        configuration,
        seed,
        budget(pilot + 0.05),
        TIME_BUDGET_NOMINAL_SPP,
    )?;
    Ok(image_rate_of(&again).0)
}

/// Renders `configuration` with `budget`, its sampler's pattern laid out for `sampler_spp`.
fn render(
    suite: &SuiteScene,
    configuration: &Configuration,
    seed: u32,
    budget: RenderBudget,
    sampler_spp: u32,
) -> Result<RenderOutput, String> {
    let filter = film_filter(suite.scene.desc.film.filter).map_err(|e| e.to_string())?;
    let plan = RenderPlan {
        transport: configuration.transport,
        sampler: configuration.sampler,
        seed,
        budget,
        sampler_spp,
        // `auto` samples adaptively where the budget pays for the pilot, as on the command
        // line.
        adaptive: configuration.adaptive
            && (!configuration.trials.any()
                || budget
                    .max_spp
                    .is_none_or(|spp| spp >= AUTO_ADAPTIVE_MIN_SPP)),
        trials: configuration.trials,
        independent_time: configuration.independent_time,
    };
    render_scene(&suite.scene, &plan, &filter, &RenderOptions::quiet())
        .map(|(output, _)| output)
        .map_err(|e| e.to_string())
}

/// Renders `configuration` with `spp` samples per pixel and measures it against `reference`.
///
/// A render asks for a whole number of samples per pixel (chosen from the samples per second
/// measured before, to fit the budget), so stratified and blue-noise samplers lay out their
/// complete pattern for exactly the samples they take (a time budget alone could stop anywhere
/// inside one). Its actual time, pilots included, is what is reported.
fn measure(
    suite: &SuiteScene,
    configuration: &Configuration,
    reference: &Image,
    seed: u32,
    spp: u32,
    budget: f64,
) -> Result<(Measurement, RenderOutput), String> {
    let output = render(suite, configuration, seed, RenderBudget::spp(spp), spp)?;
    let image = output.film.to_image();
    let mismatch = |e| format!("{}: {e} (re-run `cargo xtask refs`)", suite.name);
    let measurement = Measurement {
        configuration: configuration.name.clone(),
        budget,
        seed,
        spp: output.spp,
        seconds: output.seconds,
        rmse: rmse(&image, reference).map_err(mismatch)?,
        relmse: relmse(&image, reference).map_err(mismatch)?,
        non_finite: output.non_finite.nan + output.non_finite.inf,
    };
    Ok((measurement, output))
}
