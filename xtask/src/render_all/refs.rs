//! `cargo xtask refs`: renders each scene's reference image at a fixed high sample count and
//! stores it, with a note of how it was made, under `scenes/refs/`.
//!
//! The references use MIS with the balance heuristic, which no configuration of render-all's
//! ladder uses (its MIS rungs use the power heuristic): an error shared by a configuration and
//! the image it is measured against would go unseen, so no configuration is measured against an
//! image made by itself. That MIS converges to the reference integrator's image is checked by
//! the unbiasedness tests.

use super::{SuiteScene, command_output, parse_scene_list, reference_path, scene_files};
use integrators::{Mis, PathSettings};
use render::atomic_write::write_bytes_atomically;
use render::driver::RenderOptions;
use render::plan::{RenderPlan, Transport};
use render::session::{film_filter, render_scene};
use sampling::sampler::SamplerKind;
use std::path::Path;

/// Sampler seed of the references (render-all's configurations use other seeds).
pub const REFERENCE_SEED: u32 = 1000;

/// Samples per pixel of each scene's reference: about 80 s of rendering each on 2 threads, so
/// that its own noise is a small part of the error measured at render-all's largest budget
/// (0.8 s, so at most 1/100 of the reference's samples). The three scenes that `vs-mitsuba`
/// compares have four times that (2026-12-02): the Cornell box's reference at 3,680 spp carried
/// about a tenth of the errors compared there, which pulled the ratio of the two renderers'
/// errors towards 1.
const REFERENCE_SPP: &[(&str, u32)] = &[
    ("cbox", 14720),
    ("cbox-glass", 16384),
    ("cbox-mesh", 3200),
    ("cbox-smalllight", 3840),
    ("furnace", 2048),
    ("manylights", 15200),
    ("motion", 3072),
    ("pointlight", 18400),
    ("softshadow", 15200),
    ("thinlens", 16000),
    ("veach-mis", 32768),
];

/// Samples per pixel for a scene missing from the table.
const DEFAULT_SPP: u32 = 1024;

/// Runs `cargo xtask refs [--scenes A,B] [--spp N]` (`--spp` overrides the table, for timing).
pub fn refs(root: &Path, args: &[String]) -> Result<bool, String> {
    let mut only = Vec::new();
    let mut spp_override = None;
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        match arg.as_str() {
            "--scenes" => only = parse_scene_list(rest.next())?,
            "--spp" => {
                spp_override = Some(
                    rest.next()
                        .and_then(|v| v.parse::<u32>().ok())
                        .filter(|&n| n > 0)
                        .ok_or("--spp takes a positive whole number")?,
                );
            }
            other => return Err(format!("refs: unknown argument {other}")),
        }
    }
    let commit = command_output("git", &["-C", &root.to_string_lossy(), "rev-parse", "HEAD"]);
    for file in scene_files(root, &only)? {
        let suite = SuiteScene::load(&file)?;
        let spp = spp_override.unwrap_or_else(|| {
            REFERENCE_SPP
                .iter()
                .find(|(name, _)| *name == suite.name)
                .map_or(DEFAULT_SPP, |&(_, spp)| spp)
        });
        let settings = PathSettings {
            mis: Mis::Balance,
            ..suite.transport().mis()
        };
        let plan = RenderPlan::fixed_spp(
            Transport::Path(settings),
            SamplerKind::Independent,
            REFERENCE_SEED,
            spp,
        );
        let filter = film_filter(suite.scene.desc.film.filter).map_err(|e| e.to_string())?;
        let (output, _) = render_scene(&suite.scene, &plan, &filter, &RenderOptions::quiet())
            .map_err(|e| e.to_string())?;
        let path = reference_path(root, &suite.name);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        output
            .film
            .to_image()
            .write_exr(&path)
            .map_err(|e| e.to_string())?;
        let note = format!(
            "command: cargo xtask refs\n\
             scene: scenes/{name}.xml\n\
             settings: {settings:?}\n\
             sampler: independent, seed {REFERENCE_SEED}\n\
             spp: {spp}\n\
             seconds: {seconds:.2}\n\
             threads: {threads}\n\
             non-finite samples: {nan} NaN, {inf} inf\n\
             date: {date}\n\
             commit: {commit}\n",
            name = suite.name,
            seconds = output.seconds,
            threads = output.threads,
            nan = output.non_finite.nan,
            inf = output.non_finite.inf,
            date = command_output("date", &["-u", "+%Y-%m-%dT%H:%M:%SZ"]),
        );
        write_bytes_atomically(&path.with_extension("txt"), note.as_bytes())
            .map_err(|e| e.to_string())?;
        println!(
            "{:<16} {spp:>6} spp {:>7.2} s  -> {}",
            suite.name,
            output.seconds,
            path.display()
        );
    }
    Ok(true)
}
