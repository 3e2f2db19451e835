//! `cargo xtask render-all`: every configuration of each scene's ladder at a geometric series of
//! time budgets, measured against the stored reference.

use super::error_map::error_map;
use super::ladder::{Configuration, ladder};
use super::report::{Measurement, SceneReport, write_report};
use super::{SuiteScene, parse_scene_list, reference_path, scene_files};
use render::auto::TechniquePilot;
use render::driver::{RenderBudget, RenderOptions};
use render::image::Image;
use render::metrics::{relmse, rmse};
use render::progress::Progress;
use render::session::{film_filter, render_scene};
use render::technique::{
    AUTO_ADAPTIVE_MIN_SPP, RenderPlan, TIME_BUDGET_NOMINAL_SPP, plan_from_flags,
};
use std::path::Path;

/// Time budgets in seconds of the full run.
const FULL_BUDGETS: &[f64] = &[0.25, 0.5, 1.0, 2.0];

/// Time budgets in seconds of `--quick`.
const QUICK_BUDGETS: &[f64] = &[0.1, 0.3];

/// Seed of the render at budget index `i`: distinct per budget, and below the references' seed
/// (1000) for any budget series this short.
fn seed(i: usize) -> u32 {
    1 + i as u32
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
        reference
            .write_png(&scene_dir.join("stored-reference.png"))
            .map_err(|e| e.to_string())?;
        let auto = plan_from_flags(&suite.scene, &[])?;
        let configurations = ladder(&suite.transport(), &suite.scene.features, &auto);
        let mut measurements = Vec::new();
        let mut auto_techniques = Vec::new();
        for (c, configuration) in configurations.iter().enumerate() {
            for (i, &seconds) in budgets.iter().enumerate() {
                progress.set_message(format!("{} / {}", suite.name, configuration.name));
                let (measurement, image, choice) =
                    measure(&suite, configuration, &reference, seconds, seed(i))?;
                if let Some(pilot) = choice.filter(|_| i + 1 == budgets.len()) {
                    auto_techniques = pilot.choice.settings.technique_names();
                    auto_techniques.push(format!("({})", pilot.choice.reason()));
                }
                if i + 1 == budgets.len() {
                    let name = &configuration.name;
                    image
                        .write_png(&scene_dir.join(format!("{name}.png")))
                        .map_err(|e| e.to_string())?;
                    error_map(&image, &reference)?
                        .write_png(&scene_dir.join(format!("{name}-error.png")))
                        .map_err(|e| e.to_string())?;
                }
                progress.println(format!(
                    "{:<16} {:<15} {:>5.2} s budget: {:>5} spp relMSE {:.3e}{}",
                    suite.name,
                    configuration.name,
                    seconds,
                    measurement.spp,
                    measurement.relmse,
                    if measurement.non_finite > 0 {
                        format!(
                            " ({} NaN or infinite samples left out)",
                            measurement.non_finite
                        )
                    } else {
                        String::new()
                    }
                ));
                measurements.push(measurement);
                let done_in_scene = (c * budgets.len() + i + 1) as f64
                    / (configurations.len() * budgets.len()) as f64;
                progress.set_fraction((scene_index as f64 + done_in_scene) / files.len() as f64);
            }
        }
        reports.push(SceneReport {
            scene: suite.name.clone(),
            auto_techniques,
            configurations: configurations.iter().map(|c| c.name.clone()).collect(),
            measurements,
        });
    }
    progress.finish();
    write_report(&out_dir, &reports)?;
    Ok(true)
}

/// Renders `configuration` for about `seconds` and measures it against `reference`.
///
/// A pilot render of a tenth of the budget (at least 0.05 s, so that thread start-up does not
/// dominate it) measures the configuration's samples per second;
/// the measured render then asks for the whole number of samples per pixel that fits the
/// budget, so stratified and blue-noise samplers lay out their complete pattern for exactly the
/// samples they take (a time budget alone could stop anywhere inside one). Its actual time is
/// what is reported.
fn measure(
    suite: &SuiteScene,
    configuration: &Configuration,
    reference: &Image,
    seconds: f64,
    seed: u32,
) -> Result<(Measurement, Image, Option<TechniquePilot>), String> {
    let filter = film_filter(suite.scene.desc.film.filter).map_err(|e| e.to_string())?;
    let render = |budget: RenderBudget, sampler_spp: u32| {
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
        };
        render_scene(&suite.scene, &plan, &filter, &RenderOptions::quiet())
            .map(|(output, _)| output)
            .map_err(|e| e.to_string())
    };
    let pilot = render(
        RenderBudget {
            max_spp: None,
            max_seconds: Some((0.1 * seconds).max(0.05)),
        },
        TIME_BUDGET_NOMINAL_SPP,
    )?;
    let rate = f64::from(pilot.spp) / pilot.seconds.max(1e-6);
    let spp = ((rate * seconds) as u32).clamp(1, TIME_BUDGET_NOMINAL_SPP * 16);
    let output = render(RenderBudget::spp(spp), spp)?;
    let image = output.film.to_image();
    let mismatch = |e| format!("{}: {e} (re-run `cargo xtask refs`)", suite.name);
    let measurement = Measurement {
        configuration: configuration.name.clone(),
        budget: seconds,
        spp: output.spp,
        seconds: output.seconds,
        rmse: rmse(&image, reference).map_err(mismatch)?,
        relmse: relmse(&image, reference).map_err(mismatch)?,
        non_finite: output.non_finite.nan + output.non_finite.inf,
    };
    Ok((measurement, image, output.auto))
}
