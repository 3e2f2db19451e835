//! Which light transport, sampler and budget a `strata render` runs with: the command line's
//! flags on top of the scene file's settings, and the `auto` choice from the scene's features.

use crate::cli::{
    Cli, Command, IntegratorPreset, RenderArgs, ReuseFlag, SamplerKind as SamplerFlag,
};
use crate::driver::RenderBudget;
use clap::Parser;
use integrators::reference::ReferenceSettings;
use integrators::{
    DirectSamples, LightSelectionMode, Mis, PathReuse, PathSettings, RussianRoulette,
};
use sampling::sampler::SamplerKind;
use scene::{IntegratorKind, RenderScene, SamplerKind as SceneSampler, SceneDesc, SceneFeatures};

/// Candidates per RIS light choice in the `ris` preset and in `auto`. Measured on the
/// many-lights scene at 32 spp (efficiency relative to power-proportional selection): 4
/// candidates 1.41x with the independent sampler and 1.87x with blue noise, 8 candidates 1.34x
/// and 1.64x (each candidate costs about 4% of a path there).
pub const RIS_CANDIDATES: u32 = 4;

/// Block edge of the path reuse `auto` turns on: on the Cornell box 4 × 4 blocks cut the relMSE
/// at equal time 2.6× and 2 × 2 blocks 1.9× (2026-12-03); where reuse does not pay, the larger
/// blocks lose more (`manylights`: 1.2× against 1.02× higher relMSE).
pub const AUTO_REUSE_BLOCK: u32 = 4;

/// With at least this many lights, `auto` selects lights by RIS rather than by power.
pub const AUTO_RIS_MIN_LIGHTS: usize = 16;

/// With glossy materials and at least this many area lights, `auto` selects lights by RIS,
/// whose target there follows the glossy lobe towards each light: on Veach's scene (four sphere
/// lights) efficiency 1.3–1.4× over power-proportional selection. An environment does not count:
/// it lies in every lobe, and BSDF sampling finds it; with one area light and the environment
/// (tests/crosscheck/twosided-sides.xml) RIS was 0.62× as efficient as power there, with a point
/// light and the environment (the point-light scene) 0.3×.
pub const AUTO_RIS_MIN_GLOSSY_LIGHTS: usize = 2;

/// Nominal sample count given to samplers when only a time budget bounds the render: strata are
/// laid out for this many samples, and any prefix of them is still unbiased.
pub const TIME_BUDGET_NOMINAL_SPP: u32 = 4096;

/// The light transport algorithm of a render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Transport {
    /// The reference path tracer (no tricks).
    Reference(ReferenceSettings),
    /// The variance-reduction path tracer with these switches.
    Path(PathSettings),
}

impl Transport {
    /// Names of the techniques that are on, for the stats and reports.
    pub fn technique_names(&self) -> Vec<String> {
        match self {
            Transport::Reference(_) => vec!["reference".to_string()],
            Transport::Path(settings) => settings.technique_names(),
        }
    }
}

/// Everything that decides a render besides the scene itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderPlan {
    /// The light transport.
    pub transport: Transport,
    /// The sampling pattern.
    pub sampler: SamplerKind,
    /// The sampler seed.
    pub seed: u32,
    /// When to stop.
    pub budget: RenderBudget,
    /// Sample count the sampler lays its pattern out for.
    pub sampler_spp: u32,
    /// Adaptive sampling: a pilot render decides how many samples each pixel gets (see
    /// [`crate::adaptive`]).
    pub adaptive: bool,
}

impl RenderPlan {
    /// Exactly `spp` samples per pixel, the sampler's pattern laid out for them.
    pub fn fixed_spp(transport: Transport, sampler: SamplerKind, seed: u32, spp: u32) -> Self {
        Self {
            transport,
            sampler,
            seed,
            budget: RenderBudget::spp(spp),
            sampler_spp: spp,
            adaptive: false,
        }
    }
}

/// The sample counts of a scene's `direct` integrator, `None` for `path`.
pub fn direct_samples(kind: IntegratorKind) -> Option<DirectSamples> {
    match kind {
        IntegratorKind::Direct {
            emitter_samples,
            bsdf_samples,
        } => Some(DirectSamples {
            light: emitter_samples,
            bsdf: bsdf_samples,
        }),
        IntegratorKind::Path => None,
    }
}

/// The plan for rendering `desc` (with `features`) as `args` ask.
pub fn plan(args: &RenderArgs, desc: &SceneDesc, features: &SceneFeatures) -> RenderPlan {
    let direct = direct_samples(desc.integrator.kind);
    let max_depth = match (args.max_depth, direct) {
        (Some(depth), _) => Some(depth),
        (None, Some(_)) => Some(2),
        (None, None) => u32::try_from(desc.integrator.max_depth).ok(),
    };
    // `--max-depth` other than 2 turns a direct scene into a path-traced one.
    let direct_samples = direct.filter(|_| max_depth == Some(2));
    let hide_emitters = desc.integrator.hide_emitters;
    let skip_null_vertices = desc.integrator.skip_null_vertices;
    let roulette = Some(RussianRoulette {
        start_depth: desc.integrator.rr_depth.max(1),
    });
    let nee = PathSettings {
        max_depth,
        hide_emitters,
        sample_lights: true,
        sample_bsdf: true,
        mis: Mis::Off,
        light_selection: LightSelectionMode::Power,
        russian_roulette: roulette,
        light_tracing: false,
        direct_samples,
        skip_null_vertices,
        path_reuse: None,
    };
    let mis = PathSettings {
        mis: Mis::Power,
        ..nee
    };
    let mut transport = match args.integrator {
        IntegratorPreset::Reference => Transport::Reference(ReferenceSettings {
            max_depth,
            hide_emitters,
            direct_samples,
            skip_null_vertices,
        }),
        IntegratorPreset::Nee => Transport::Path(nee),
        IntegratorPreset::Mis => Transport::Path(mis),
        IntegratorPreset::Ris => Transport::Path(PathSettings {
            light_selection: LightSelectionMode::Ris {
                candidates: RIS_CANDIDATES,
            },
            ..mis
        }),
        IntegratorPreset::Auto => Transport::Path(auto_settings(mis, features)),
    };
    if let (Transport::Path(settings), Some(rr)) = (&mut transport, args.rr) {
        settings.russian_roulette = if rr.is_on() { roulette } else { None };
    }
    if let Transport::Path(settings) = &mut transport {
        // `auto` traces caustics from the lights wherever that applies.
        let auto_traces = args.integrator == IntegratorPreset::Auto;
        settings.light_tracing = (args.light_tracing || auto_traces)
            && light_tracing_applies(
                features,
                settings.max_depth,
                !desc.sensor.orthographic,
                settings.skip_null_vertices,
            )
            && !settings.hide_emitters;
        let auto_reuses = auto_traces && path_reuse_pays(features, settings.max_depth);
        let block = match args.path_reuse {
            Some(ReuseFlag::Block(block)) => Some(block),
            Some(ReuseFlag::Off) => None,
            None => auto_reuses.then_some(AUTO_REUSE_BLOCK),
        };
        settings.path_reuse = block
            .map(|block| PathReuse { block })
            .filter(|_| settings.reuse_applies());
    }

    let sampler = match args.sampler {
        Some(SamplerFlag::Independent) => SamplerKind::Independent,
        Some(SamplerFlag::Stratified) => SamplerKind::Stratified,
        Some(SamplerFlag::BlueNoise) => SamplerKind::BlueNoise,
        Some(SamplerFlag::Sobol) => SamplerKind::Sobol,
        None => match desc.sampler.kind {
            SceneSampler::Independent => SamplerKind::Independent,
            SceneSampler::Stratified | SceneSampler::Multijitter | SceneSampler::Orthogonal => {
                SamplerKind::Stratified
            }
            // Mitsuba's `ldsampler` is a scrambled (0, 2)-sequence with per-dimension shuffles.
            SceneSampler::Ldsampler => SamplerKind::Sobol,
        },
    };
    let seed = args.seed.map_or(desc.sampler.seed, fold_seed);
    let budget = match (args.spp, args.time) {
        (None, None) => RenderBudget::spp(desc.sampler.sample_count),
        (spp, time) => RenderBudget {
            max_spp: spp,
            max_seconds: time,
        },
    };
    RenderPlan {
        transport,
        sampler,
        seed,
        budget,
        sampler_spp: budget.max_spp.unwrap_or(TIME_BUDGET_NOMINAL_SPP),
        adaptive: args.adaptive,
    }
}

/// The plan `strata render` makes for `scene` with the extra command-line `flags` (e.g.
/// `["--integrator", "mis", "--spp", "4"]`), for tools and benchmarks that render in-process.
/// Flags that only concern files (`--out`, `--png`, `--stats`) and `--threads` have no effect.
pub fn plan_from_flags(scene: &RenderScene, flags: &[&str]) -> Result<RenderPlan, String> {
    let command_line = ["strata", "render", "scene.xml", "--out", "out.exr"]
        .into_iter()
        .chain(flags.iter().copied());
    match Cli::try_parse_from(command_line)
        .map_err(|e| e.to_string())?
        .command
    {
        Command::Render(args) => Ok(plan(&args, &scene.desc, &scene.features)),
        other => Err(format!("not a render command: {other:?}")),
    }
}

/// `auto`: the MIS preset minus what the scene cannot use. No light sampling where every BSDF
/// is a delta or there are no lights; no MIS where every light is a delta light; uniform choice
/// (no table) for one light, RIS for many, and for several hittable lights seen in glossy
/// materials.
pub fn auto_settings(mis: PathSettings, features: &SceneFeatures) -> PathSettings {
    let sample_lights = features.light_count > 0 && features.has_non_delta_bsdfs;
    let glossy_choice =
        features.has_glossy_bsdfs && features.area_light_count >= AUTO_RIS_MIN_GLOSSY_LIGHTS;
    let light_selection = match features.light_count {
        0 | 1 => LightSelectionMode::Uniform,
        n if n >= AUTO_RIS_MIN_LIGHTS || glossy_choice => LightSelectionMode::Ris {
            candidates: RIS_CANDIDATES,
        },
        _ => LightSelectionMode::Power,
    };
    PathSettings {
        sample_lights,
        mis: if sample_lights && features.has_hittable_lights() {
            Mis::Power
        } else {
            Mis::Off
        },
        light_selection,
        ..mis
    }
}

/// Whether `auto` turns path reuse on: where some material is diffuse (else nothing is
/// shared), in a scene lit by area lights only, closed (no environment) and with paths of at
/// least 4 vertices. Path reuse shares what second vertices reflect, so it pays where indirect
/// light holds much of the noise. Measured at equal time (2 s, `--sampler sobol --adaptive`,
/// 4 × 4 blocks, 2026-12-03): relMSE 2.6× lower on the Cornell box, 2.3× on its small-light
/// variant, 1.5× on its mesh variant, 7.7× in the furnace, unchanged on Veach's scene; but
/// 1.2× higher on `manylights` (`max_depth` 3: one indirect bounce), 1.1× with a point light
/// and 1.2× on `thinlens` (an environment: many first bounces escape and share nothing).
pub fn path_reuse_pays(features: &SceneFeatures, max_depth: Option<u32>) -> bool {
    features.has_diffuse_bsdfs
        && !features.has_delta_lights()
        && !features.has_environment
        && max_depth.is_none_or(|depth| depth >= 4)
}

/// Whether caustics by light tracing can find anything in the scene: a delta BSDF to make
/// caustics, a light with a surface to trace from and a camera that light paths can connect to
/// (`camera_connects`: any but the orthographic one; a thin lens's connections go through a
/// sampled point of its aperture), with any reconstruction filter (a light path splats into
/// every pixel whose camera samples can reach its film position, weighted by the filter).
/// A caustic path needs three vertices after the camera (diffuse, delta, light), so none fits
/// a `max_depth` of 2 or less. The light tracer counts every pass through a null lobe as a
/// vertex, so it is left out where `skip_null_vertices` (Mitsuba's `volpath`) meets null lobes.
pub fn light_tracing_applies(
    features: &SceneFeatures,
    max_depth: Option<u32>,
    camera_connects: bool,
    skip_null_vertices: bool,
) -> bool {
    camera_connects
        && features.has_delta_bsdfs
        && features.has_hittable_lights()
        && max_depth.is_none_or(|depth| depth >= 3)
        && !(skip_null_vertices && features.has_null_lobes)
}

/// A 64-bit seed from the command line folded into the sampler's 32 bits.
fn fold_seed(seed: u64) -> u32 {
    (seed as u32) ^ ((seed >> 32) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `lights` lights of which `area` are area lights, plus the environment when `environment`.
    fn features(lights: usize, area: usize, environment: bool, glossy: bool) -> SceneFeatures {
        SceneFeatures {
            light_count: lights,
            has_non_delta_bsdfs: true,
            has_delta_bsdfs: false,
            area_light_count: area,
            has_environment: environment,
            has_glossy_bsdfs: glossy,
            has_null_lobes: false,
            has_diffuse_bsdfs: true,
        }
    }

    fn selection(features: &SceneFeatures) -> LightSelectionMode {
        let mis = PathSettings {
            sample_lights: true,
            mis: Mis::Power,
            ..PathSettings::default()
        };
        auto_settings(mis, features).light_selection
    }

    #[test]
    fn auto_resamples_lights_for_many_lights_and_for_several_seen_in_glossy_materials() {
        let ris = LightSelectionMode::Ris {
            candidates: RIS_CANDIDATES,
        };
        assert_eq!(
            selection(&features(1, 1, false, true)),
            LightSelectionMode::Uniform
        );
        // Veach's scene: four spheres and the environment on rough metal.
        assert_eq!(selection(&features(5, 4, true, true)), ris);
        assert_eq!(
            selection(&features(5, 4, true, false)),
            LightSelectionMode::Power
        );
        // One sphere light and the environment; a point light and the environment.
        assert_eq!(
            selection(&features(2, 1, true, true)),
            LightSelectionMode::Power
        );
        assert_eq!(
            selection(&features(2, 0, true, true)),
            LightSelectionMode::Power
        );
        assert_eq!(
            selection(&features(AUTO_RIS_MIN_LIGHTS, 16, false, false)),
            ris
        );
    }

    #[test]
    fn auto_reuses_paths_in_closed_scenes_lit_by_area_lights_with_deep_paths() {
        let cbox = features(1, 1, false, false);
        assert!(path_reuse_pays(&cbox, Some(8)));
        assert!(path_reuse_pays(&cbox, None));
        assert!(!path_reuse_pays(&cbox, Some(3)), "one indirect bounce");
        assert!(
            !path_reuse_pays(&features(2, 1, true, false), Some(8)),
            "environment"
        );
        assert!(
            !path_reuse_pays(&features(2, 1, false, false), Some(8)),
            "point light"
        );
        let no_diffuse = SceneFeatures {
            has_diffuse_bsdfs: false,
            ..cbox
        };
        assert!(!path_reuse_pays(&no_diffuse, Some(8)));
    }
}
