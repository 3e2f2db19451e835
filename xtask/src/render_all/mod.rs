//! `cargo xtask refs` and `cargo xtask render-all`: stored high-sample references of the scene
//! suite, and every configuration of the technique ladder rendered at a series of time budgets
//! and measured against them; `cargo xtask report-check`: the report loaded in a real browser.

mod browser;
mod error_map;
mod ladder;
mod plot;
mod preview;
mod refs;
mod report;
mod run;
mod summary;

pub use browser::report_check;
pub use refs::refs;
pub use run::render_all;

use integrators::RussianRoulette;
use ladder::SceneTransport;
use render::plan::{direct_samples, light_tracing_applies};
use scene::RenderScene;
use std::path::{Path, PathBuf};

/// A scene of the suite, loaded and built.
struct SuiteScene {
    /// File stem, e.g. `cbox`.
    name: String,
    /// The built scene.
    scene: RenderScene,
}

impl SuiteScene {
    /// Loads and builds `path`.
    fn load(path: &Path) -> Result<Self, String> {
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .ok_or_else(|| format!("{}: no file name", path.display()))?;
        let scene = scene::load(path, &[]).map_err(|e| e.to_string())?;
        Ok(Self { name, scene })
    }

    /// What the scene file fixes for every configuration (depth as `strata render` reads it).
    fn transport(&self) -> SceneTransport {
        let integrator = &self.scene.desc.integrator;
        let direct_samples = direct_samples(integrator);
        let max_depth = match direct_samples {
            Some(_) => Some(2),
            None => u32::try_from(integrator.max_depth).ok(),
        };
        SceneTransport {
            max_depth,
            direct_samples,
            hide_emitters: integrator.hide_emitters,
            roulette: RussianRoulette {
                start_depth: integrator.rr_depth.max(1),
            },
            light_tracing: light_tracing_applies(
                &self.scene.features,
                max_depth,
                self.scene.camera.connects(),
                integrator.skip_null_vertices,
            ),
            skip_null_vertices: integrator.skip_null_vertices,
            path_reuse: self.scene.features.has_diffuse_bsdfs && !self.scene.features.has_motion,
        }
    }
}

/// The scene files under `scenes/`, sorted, limited to `only` (file stems) when it is not empty.
fn scene_files(root: &Path, only: &[String]) -> Result<Vec<PathBuf>, String> {
    let dir = root.join("scenes");
    let entries = std::fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    files.sort();
    if only.is_empty() {
        return Ok(files);
    }
    let stem = |p: &PathBuf| p.file_stem().map(|s| s.to_string_lossy().into_owned());
    for name in only {
        if !files
            .iter()
            .any(|p| stem(p).as_deref() == Some(name.as_str()))
        {
            return Err(format!("no scene scenes/{name}.xml"));
        }
    }
    files.retain(|p| stem(p).is_some_and(|s| only.contains(&s)));
    Ok(files)
}

/// The value of `--scenes A,B,...` split at commas.
fn parse_scene_list(value: Option<&String>) -> Result<Vec<String>, String> {
    let value = value.ok_or("--scenes takes a comma-separated list of scene names")?;
    Ok(value
        .split(',')
        .filter(|s| !s.is_empty())
        .map(|s| s.trim_end_matches(".xml").to_string())
        .collect())
}

/// Where a scene's stored reference image lives.
fn reference_path(root: &Path, name: &str) -> PathBuf {
    root.join("scenes/refs").join(format!("{name}.exr"))
}

/// The trimmed standard output of a command, or `unknown` when it cannot run.
fn command_output(program: &str, args: &[&str]) -> String {
    std::process::Command::new(program)
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map_or_else(
            || "unknown".to_string(),
            |o| String::from_utf8_lossy(&o.stdout).trim().to_string(),
        )
}
