//! Render statistics, written as JSON next to the image (`strata render --stats OUT.json`).

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::atomic_write::{WriteError, write_bytes_atomically};
use crate::driver::RenderOutput;
use crate::plan::RenderPlan;
use world::RayCounters;

/// What a render did and what it cost. Field names are part of the command-line contract.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RenderStats {
    /// Wall-clock seconds spent rendering (scene loading excluded).
    pub seconds: f64,
    /// Wall-clock seconds spent loading and preparing the scene.
    pub load_seconds: f64,
    /// Samples per pixel rendered, including any resumed from a saved state; with adaptive
    /// sampling the mean over pixels, the pilot's samples included.
    pub spp: u32,
    /// Samples per pixel of the adaptive-sampling pilot (rendered, not in the image); 0 without.
    #[serde(default)]
    pub pilot_spp: u32,
    /// Samples per pixel taken over from a saved state (`--resume`), or the first sample index
    /// of a `--samples START..END` piece (whose samples are `resumed_spp .. spp`); 0 for a fresh
    /// render.
    #[serde(default)]
    pub resumed_spp: u32,
    /// Whether Ctrl-C stopped the render before its budget was spent.
    #[serde(default)]
    pub interrupted: bool,
    /// Passes the samples were rendered in.
    pub passes: u32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Rendering threads.
    pub threads: usize,
    /// Closest-hit rays traced (camera and continuation rays).
    pub rays: u64,
    /// Occlusion (shadow) rays traced.
    pub shadow_rays: u64,
    /// Samples left out of the image because a channel was NaN.
    pub nan_count: u64,
    /// Samples left out of the image because a channel was infinite (and none NaN).
    pub inf_count: u64,
    /// The techniques that were on, e.g. `"nee"`, `"mis-power"`, `"russian-roulette"`.
    pub techniques: Vec<String>,
    /// `auto`'s technique pilot: what it measured and chose (see `render::auto`); absent for
    /// the other presets.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub auto_choice: Option<String>,
    /// Seconds the technique pilot took (counted in `seconds`); 0 without one.
    #[serde(default)]
    pub auto_pilot_seconds: f64,
    /// Why adaptive sampling was asked for but not done, if it was not.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub adaptive_skipped: Option<String>,
}

impl RenderStats {
    /// The statistics the driver knows from `output`; `load_seconds`, `rays`, `shadow_rays`
    /// and `techniques` are left for the caller to fill in.
    pub fn from_output(output: &RenderOutput) -> Self {
        Self {
            seconds: output.seconds,
            spp: output.spp,
            pilot_spp: output.pilot_spp,
            resumed_spp: output.resumed_spp,
            interrupted: output.interrupted,
            passes: output.passes,
            width: output.film.width(),
            height: output.film.height(),
            threads: output.threads,
            nan_count: output.non_finite.nan,
            inf_count: output.non_finite.inf,
            auto_choice: output.auto.as_ref().map(|a| a.choice.reason()),
            auto_pilot_seconds: output.auto.as_ref().map_or(0.0, |a| a.seconds),
            adaptive_skipped: output.adaptive_skipped.clone(),
            ..Self::default()
        }
    }

    /// The statistics of a render as `plan` said (of a scene whose camera has a lens when
    /// `has_lens`) that made `output` and traced `counters`: [`from_output`](Self::from_output)
    /// with the rays and the techniques that rendered it (those `auto`'s pilot chose, where it
    /// ran), `load_seconds` left for the caller.
    pub fn of_render(
        output: &RenderOutput,
        counters: RayCounters,
        plan: &RenderPlan,
        has_lens: bool,
    ) -> Self {
        let mut stats = Self::from_output(output);
        stats.rays = counters.rays;
        stats.shadow_rays = counters.shadow_rays;
        stats.techniques = output.rendered_plan(plan).transport.technique_names();
        if has_lens {
            stats.techniques.push("thin-lens".to_string());
        }
        if output.pilot_spp > 0 {
            stats.techniques.push("adaptive".to_string());
        }
        stats
    }

    /// The statistics as pretty-printed JSON, fields in declaration order.
    pub fn to_json(&self) -> String {
        // Serialising plain numbers, strings and a list of strings cannot fail; non-finite
        // floats become `null`.
        serde_json::to_string_pretty(self).expect("RenderStats serialises to JSON")
    }

    /// Writes [`to_json`](Self::to_json) plus a final newline to `path` atomically.
    pub fn write_json(&self, path: &Path) -> Result<(), WriteError> {
        write_bytes_atomically(path, format!("{}\n", self.to_json()).as_bytes())
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::driver::{RenderBudget, RenderOptions, render};

    #[test]
    fn json_has_the_contract_fields_and_round_trips() {
        let stats = RenderStats {
            seconds: 1.5,
            load_seconds: 0.25,
            spp: 64,
            pilot_spp: 0,
            resumed_spp: 16,
            interrupted: true,
            passes: 3,
            width: 320,
            height: 240,
            threads: 2,
            rays: 1000,
            shadow_rays: 500,
            nan_count: 1,
            inf_count: 2,
            techniques: vec!["nee".into(), "mis-power".into()],
            auto_choice: Some("chose base".into()),
            auto_pilot_seconds: 0.125,
            adaptive_skipped: None,
        };
        let value: serde_json::Value = serde_json::from_str(&stats.to_json()).unwrap();
        for field in [
            "seconds",
            "load_seconds",
            "spp",
            "resumed_spp",
            "interrupted",
            "width",
            "height",
            "threads",
            "rays",
            "shadow_rays",
            "nan_count",
            "inf_count",
            "techniques",
        ] {
            assert!(value.get(field).is_some(), "missing {field}");
        }
        assert_eq!(value["load_seconds"], 0.25);
        assert_eq!(value["techniques"][1], "mis-power");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("stats.json");
        stats.write_json(&path).unwrap();
        let back: RenderStats =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert_eq!(back, stats);
    }

    #[test]
    fn from_output_copies_the_drivers_counts() {
        let sample = |_: &mut (), _, index: u32| if index == 0 { Vec3::NAN } else { Vec3::ONE };
        let output = render(
            3,
            2,
            &RenderBudget::spp(4),
            &RenderOptions::quiet(),
            || (),
            sample,
        )
        .unwrap();
        let stats = RenderStats::from_output(&output);
        assert_eq!((stats.width, stats.height, stats.spp), (3, 2, 4));
        assert_eq!((stats.passes, stats.resumed_spp), (output.passes, 0));
        assert!(!stats.interrupted);
        assert_eq!((stats.nan_count, stats.inf_count), (6, 0));
        assert_eq!(stats.threads, output.threads);
        assert_eq!(stats.seconds, output.seconds);
    }
}
