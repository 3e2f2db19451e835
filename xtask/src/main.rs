//! `cargo xtask <job>`: the project's automation, one subcommand per job.
//!
//! - `refs [--scenes A,B]`: render and store each scene's high-sample reference image under
//!   `scenes/refs/`.
//! - `render-all [--quick] [--scenes A,B]`: every technique configuration of each scene at a
//!   series of time budgets, measured against the stored references; report in `target/report/`.
//! - `report-check`: load `target/report/index.html` in headless Chromium; fail on a broken image
//!   or a console message; keep a screenshot at `target/report/screenshot.png`.
//! - `check [--quick]`: the statistical and stiff-case checks (the workspace's tests, with the
//!   slow ones that `cargo test` skips unless `--quick`), one pass/fail line each with its figures.
//! - `gains`: what each technique buys on the scene built to show it, one pass/fail line per
//!   claim of the path integrator's issue (part of the full `check`).
//! - `crosscheck [--spp N] [--integrator PRESET] [SCENE.xml ...]`: Strata (the reference
//!   integrator unless `--integrator` says otherwise) against Mitsuba 3, block by block (needs
//!   `pip install mitsuba`; never run in CI).
//! - `raycast-limit [SCENE] [--spp N] [--threads N] [--runs N] [--no-embree]`: render time against
//!   the time to trace the same rays alone, the speed-up over one thread, and Strata's rays per
//!   second against Embree 4's on the same rays (installs `embreex` into a virtual environment
//!   under `target/`; never run in CI).
//! - `vs-mitsuba [SCENE ...] [--no-suite] [--generate N [--seed S] [--res PIXELS]] [--time S]
//!   [--runs N] [--by-time] [--variant V] [--strata-flags F] [--mitsuba-ref SPP]
//!   [--strata-ref SPP]`: relMSE of Strata (its defaults and tuned flags) and Mitsuba 3 at equal
//!   wall time, on the suite's scenes and on generated ones (never in CI).

mod check;
mod crosscheck;
mod gains;
mod perf;
mod render_all;

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

const USAGE: &str = "usage: cargo xtask <refs [--scenes A,B] | render-all [--quick] [--scenes A,B] | report-check | check [--quick] | \
     gains | crosscheck [--spp N] [--integrator PRESET] [SCENE.xml ...] | raycast-limit [SCENE] [--spp N] [--threads N] [--runs N] [--no-embree] | \
     vs-mitsuba [SCENE ...] [--no-suite] [--generate N [--seed S] [--res PIXELS]] [--time S] [--runs N] [--by-time] \
     [--variant V] [--strata-flags F] [--mitsuba-ref SPP] [--strata-ref SPP]>";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("refs") => render_all::refs(&workspace_root(), &args[1..]),
        Some("render-all") => render_all::render_all(&workspace_root(), &args[1..]),
        Some("report-check") => render_all::report_check(&workspace_root(), &args[1..]),
        Some("check") => check::check(&workspace_root(), &args[1..]),
        Some("crosscheck") => crosscheck(&args[1..]),
        Some("gains") => gains::gains(&workspace_root()),
        Some("raycast-limit") => perf::raycast_limit(&workspace_root(), &args[1..]),
        Some("vs-mitsuba") => perf::vs_mitsuba(&workspace_root(), &args[1..]),
        _ => Err(USAGE.to_string()),
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(message) => {
            eprintln!("xtask: {message}");
            ExitCode::from(2)
        }
    }
}

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace")
        .to_path_buf()
}

/// Builds the `strata` binary in release mode and returns its path.
fn build_strata() -> Result<PathBuf, String> {
    let root = workspace_root();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let status = Command::new(cargo)
        .current_dir(&root)
        .args([
            "build",
            "--quiet",
            "--release",
            "--package",
            "render",
            "--bin",
            "strata",
        ])
        .status()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !status.success() {
        return Err("building strata failed".to_string());
    }
    Ok(root.join("target/release/strata"))
}

fn crosscheck(args: &[String]) -> Result<bool, String> {
    let mut spp = 256;
    let mut integrator = "reference".to_string();
    let mut scenes = Vec::new();
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        if arg == "--spp" {
            spp = rest
                .next()
                .and_then(|v| v.parse().ok())
                .filter(|&n| n > 0)
                .ok_or("--spp takes a positive whole number")?;
        } else if arg == "--integrator" {
            integrator = rest
                .next()
                .ok_or("--integrator takes a preset name (reference, nee, mis, ris, auto)")?
                .clone();
        } else {
            scenes.push(PathBuf::from(arg));
        }
    }
    if scenes.is_empty() {
        let dir = workspace_root().join("scenes");
        let entries = std::fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        scenes = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "xml"))
            .collect();
        scenes.sort();
    }
    let strata = build_strata()?;
    crosscheck::run(
        &strata,
        &crosscheck::Options {
            scenes,
            spp,
            integrator,
            out_dir: workspace_root().join("target/crosscheck"),
        },
    )
}
