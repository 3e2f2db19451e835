//! `cargo xtask render-all`: every configuration of each scene's ladder at a geometric series of
//! time budgets, measured against the stored reference.

use super::ladder::{Configuration, ladder};
use super::report::{Measurement, SceneReport, write_report};
use super::{SuiteScene, parse_scene_list, reference_path, scene_files};
use render::driver::{RenderBudget, RenderOptions};
use render::image::Image;
use render::metrics::{relmse, rmse};
use render::session::{film_filter, render_scene};
use render::technique::{RenderPlan, TIME_BUDGET_NOMINAL_SPP};
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
    for file in scene_files(root, &only)? {
        let suite = SuiteScene::load(&file)?;
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
        let configurations = ladder(&suite.transport(), &suite.scene.features);
        let mut measurements = Vec::new();
        for configuration in &configurations {
            for (i, &seconds) in budgets.iter().enumerate() {
                let (measurement, image) =
                    measure(&suite, configuration, &reference, seconds, seed(i))?;
                if i + 1 == budgets.len() {
                    image
                        .write_png(&scene_dir.join(format!("{}.png", configuration.name)))
                        .map_err(|e| e.to_string())?;
                }
                eprintln!(
                    "{:<16} {:<15} {:>5.2} s budget: {:>5} spp relMSE {:.3e}",
                    suite.name, configuration.name, seconds, measurement.spp, measurement.relmse
                );
                measurements.push(measurement);
            }
        }
        reports.push(SceneReport {
            scene: suite.name.clone(),
            auto_techniques: configurations
                .iter()
                .find(|c| c.name == "auto")
                .map(|c| c.transport.technique_names())
                .unwrap_or_default(),
            configurations: configurations.iter().map(|c| c.name.clone()).collect(),
            measurements,
        });
    }
    write_report(&out_dir, &reports)?;
    Ok(true)
}

/// Renders `configuration` for `seconds` and measures it against `reference`.
fn measure(
    suite: &SuiteScene,
    configuration: &Configuration,
    reference: &Image,
    seconds: f64,
    seed: u32,
) -> Result<(Measurement, Image), String> {
    let plan = RenderPlan {
        transport: configuration.transport,
        sampler: configuration.sampler,
        seed,
        budget: RenderBudget {
            max_spp: None,
            max_seconds: Some(seconds),
        },
        sampler_spp: TIME_BUDGET_NOMINAL_SPP,
    };
    let filter = film_filter(suite.scene.desc.film.filter).map_err(|e| e.to_string())?;
    let (output, _) = render_scene(&suite.scene, &plan, &filter, &RenderOptions::quiet())
        .map_err(|e| e.to_string())?;
    let image = output.film.to_image();
    let mismatch = |e| format!("{}: {e} (re-run `cargo xtask refs`)", suite.name);
    let measurement = Measurement {
        configuration: configuration.name.clone(),
        budget: seconds,
        spp: output.spp,
        seconds: output.seconds,
        rmse: rmse(&image, reference).map_err(mismatch)?,
        relmse: relmse(&image, reference).map_err(mismatch)?,
    };
    Ok((measurement, image))
}
