//! Which light transport, sampler and budget a `strata render` runs with: the command line's
//! flags on top of the scene file's settings, and the `auto` choice from the scene's features.

use crate::auto::{self, Trials};
use crate::cli::{Cli, Command, RenderArgs, ReuseFlag};
use crate::driver::RenderBudget;
use clap::Parser;
use integrators::reference::ReferenceSettings;
use integrators::{
    DirectSamples, LightSelection, LightTracing, MAX_EVERY_LIGHT, Mis, PathReuse, PathSettings,
    RussianRoulette,
};
use sampling::sampler::SamplerKind;
use scene::{IntegratorDesc, IntegratorPreset, RenderScene, SceneDesc, SceneFeatures};

/// Candidates per RIS light choice in the `ris` preset, in `auto`'s trial of RIS and with
/// `--lights ris`. Measured on the many-lights scene at 32 spp (efficiency relative to
/// power-proportional selection): 4 candidates 1.41x with the independent sampler and 1.87x
/// with blue noise, 8 candidates 1.34x and 1.64x (each candidate costs about 4% of a path
/// there).
pub const RIS_CANDIDATES: u32 = 4;

/// Samples per pixel from which `auto` turns adaptive sampling on by itself: its pilot then
/// takes at most 1/16 of the budget ([`crate::adaptive::split_budget`]).
pub const AUTO_ADAPTIVE_MIN_SPP: u32 = 32;

/// Nominal sample count given to samplers when only a time budget bounds the render: strata are
/// laid out for this many samples, and any prefix of them is still unbiased.
pub const TIME_BUDGET_NOMINAL_SPP: u32 = 4096;

/// The light transport algorithm of a render, with every setting: what [`plan`] resolves the
/// [`IntegratorPreset`] asked for (by `--integrator` or the scene) into, together with the
/// scene's integrator settings, the other flags and, for `auto`, the scene's features.
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
    /// What `auto` measures on the scene before rendering (see [`crate::auto`]); nothing for
    /// the other presets. `transport` is then the base the trials switch from.
    pub trials: Trials,
    /// Where something moves, draw each camera sample's time from independent numbers instead
    /// of the sampler's pattern: how `render-all` measures what stratifying time buys. Off in
    /// every render a user asks for.
    pub independent_time: bool,
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
            trials: Trials::default(),
            independent_time: false,
        }
    }
}

/// The sample counts of a scene's `direct` integrator, `None` for the path tracers.
pub fn direct_samples(integrator: &IntegratorDesc) -> Option<DirectSamples> {
    integrator.direct.map(|direct| DirectSamples {
        light: direct.emitter_samples,
        bsdf: direct.bsdf_samples,
    })
}

/// The preset a render runs: `--integrator`'s, or else the scene's.
pub fn preset(args: &RenderArgs, desc: &SceneDesc) -> IntegratorPreset {
    args.integrator.unwrap_or(desc.integrator.preset)
}

/// The plan for rendering `desc` (with `features`) as `args` ask.
pub fn plan(args: &RenderArgs, desc: &SceneDesc, features: &SceneFeatures) -> RenderPlan {
    let preset = preset(args, desc);
    let direct = direct_samples(&desc.integrator);
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
        light_selection: LightSelection::Power,
        russian_roulette: roulette,
        light_tracing: None,
        direct_samples,
        skip_null_vertices,
        delta_splitting: false,
        path_reuse: None,
    };
    let mis = PathSettings {
        mis: Mis::Power,
        ..nee
    };
    let mut transport = match preset {
        IntegratorPreset::Reference => Transport::Reference(ReferenceSettings {
            max_depth,
            hide_emitters,
            direct_samples,
            skip_null_vertices,
        }),
        IntegratorPreset::Nee => Transport::Path(nee),
        IntegratorPreset::Mis => Transport::Path(mis),
        IntegratorPreset::Ris => Transport::Path(PathSettings {
            light_selection: LightSelection::Ris {
                candidates: RIS_CANDIDATES,
            },
            ..mis
        }),
        IntegratorPreset::Auto => Transport::Path(auto_settings(mis, features)),
    };
    if let (Transport::Path(settings), Some(rr)) = (&mut transport, args.rr) {
        settings.russian_roulette = if rr.is_on() { roulette } else { None };
    }
    if let (Transport::Path(settings), Some(lights)) = (&mut transport, args.lights) {
        settings.light_selection = lights.selection();
    }
    if let (Transport::Path(settings), Some(splitting)) = (&mut transport, args.delta_splitting) {
        settings.delta_splitting = splitting.is_on();
    }
    let is_auto = preset == IntegratorPreset::Auto;
    let mut trials = Trials::default();
    if let Transport::Path(settings) = &mut transport {
        let tracing_applies = light_tracing_applies(
            features,
            settings.max_depth,
            !desc.sensor.orthographic,
            settings.skip_null_vertices,
        ) && !settings.hide_emitters;
        // `auto` traces caustics from the lights wherever that applies, unless the user pinned
        // path reuse (the two exclude each other); its pilot may find that switching it off, or
        // tracing fewer light paths, pays.
        let reuse_pinned = matches!(args.path_reuse, Some(ReuseFlag::Block(_)));
        settings.light_tracing = match args.light_tracing {
            Some(samples_per_path) => Some(LightTracing { samples_per_path }),
            None if is_auto && !reuse_pinned => Some(LightTracing::DENSE),
            None => None,
        }
        .filter(|_| tracing_applies);
        settings.path_reuse = match args.path_reuse {
            Some(ReuseFlag::Block(block)) => Some(PathReuse { block }),
            Some(ReuseFlag::Off) | None => None,
        }
        // Path reuse joins paths of different pixels, which in a scene with motion see it at
        // different times.
        .filter(|_| settings.reuse_applies() && !features.has_motion);
        // A saved or resumed render keeps the base: its parts may have different budgets, and
        // a pilot's choice could differ between them. What the user pinned is not tried.
        if is_auto && args.state.is_none() && args.resume.is_none() {
            let lights = features.lights_sampled_under_mis();
            let many_lights = settings.sample_lights
                && lights >= 2
                && settings.direct_samples.is_none()
                && args.lights.is_none();
            let reusing = PathSettings {
                path_reuse: Some(PathReuse {
                    block: auto::REUSE_BLOCK,
                }),
                light_tracing: None,
                ..*settings
            };
            // Light tracing `auto` put in the base, not one the user asked for.
            let tries_light_tracing =
                settings.light_tracing.is_some() && args.light_tracing.is_none();
            trials = Trials {
                ris: many_lights,
                uniform_lights: many_lights,
                every_light: many_lights && lights <= MAX_EVERY_LIGHT,
                no_roulette: args.rr.is_none()
                    && settings.direct_samples.is_none()
                    && settings
                        .russian_roulette
                        .zip(settings.max_depth)
                        .is_some_and(|(rr, depth)| depth > rr.start_depth),
                no_light_tracing: tries_light_tracing,
                sparse_light_paths: tries_light_tracing,
                path_reuse: args.path_reuse.is_none()
                    && args.light_tracing.is_none()
                    && !features.has_motion
                    && features.has_diffuse_bsdfs
                    && reusing.reuse_applies(),
            };
        }
    }

    // Without a sampler on the command line, the scene's; where the scene names none (it says
    // `independent`, Mitsuba's default, which carries no intent), `auto` takes the sampler it
    // measures best (Sobol, whose prefixes stay stratified under a time budget).
    let sampler = args.sampler.or(desc.sampler.kind).unwrap_or(if is_auto {
        SamplerKind::Sobol
    } else {
        SamplerKind::Independent
    });
    let seed = args.seed.map_or(desc.sampler.seed, fold_seed);
    let budget = match (args.spp, args.time) {
        (None, None) => RenderBudget::spp(desc.sampler.sample_count),
        (spp, time) => RenderBudget {
            max_spp: spp,
            max_seconds: time,
        },
    };
    // `auto` samples adaptively where the pilot costs at most a sixteenth of the budget; a saved
    // or resumed render and a piece of one (`--samples`) cannot (their samples must not depend
    // on a pilot whose budget differs between the parts).
    let adaptive = match args.adaptive {
        Some(switch) => switch.is_on(),
        None => {
            is_auto
                && args.state.is_none()
                && args.resume.is_none()
                && args.samples.is_none()
                && budget
                    .max_spp
                    .is_none_or(|spp| spp >= AUTO_ADAPTIVE_MIN_SPP)
        }
    };
    RenderPlan {
        transport,
        sampler,
        seed,
        budget,
        sampler_spp: budget.max_spp.unwrap_or(TIME_BUDGET_NOMINAL_SPP),
        adaptive,
        trials,
        independent_time: false,
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

/// `auto`'s base: the MIS preset minus what the scene cannot use. No light sampling where every
/// BSDF is a delta or there are no lights to sample (a constant environment is left to BSDF
/// samples); no MIS where no light can be hit; uniform choice (no table) for one light. The
/// techniques whose payoff depends on the scene are measured on it before the render
/// ([`crate::auto`]).
pub fn auto_settings(mis: PathSettings, features: &SceneFeatures) -> PathSettings {
    let lights = features.lights_sampled_under_mis();
    let sample_lights = lights > 0 && features.has_non_delta_bsdfs;
    let light_selection = match lights {
        0 | 1 => LightSelection::Uniform,
        _ => LightSelection::Power,
    };
    PathSettings {
        sample_lights,
        mis: if sample_lights && features.has_hittable_lights() {
            Mis::Power
        } else {
            Mis::Off
        },
        light_selection,
        delta_splitting: features.has_delta_lobe_choice,
        ..mis
    }
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

    /// `lights` lights of which `area` are area lights, and one a constant environment when
    /// `environment`.
    fn features(lights: usize, area: usize, environment: bool) -> SceneFeatures {
        SceneFeatures {
            light_count: lights,
            has_non_delta_bsdfs: true,
            has_delta_bsdfs: false,
            area_light_count: area,
            has_environment: environment,
            lights_left_to_bsdf: usize::from(environment),
            has_glossy_bsdfs: false,
            has_delta_lobe_choice: false,
            has_null_lobes: false,
            has_diffuse_bsdfs: true,
            has_motion: false,
        }
    }

    fn base(features: &SceneFeatures) -> PathSettings {
        let mis = PathSettings {
            sample_lights: true,
            mis: Mis::Power,
            ..PathSettings::default()
        };
        auto_settings(mis, features)
    }

    #[test]
    fn auto_base_picks_one_light_uniformly_and_several_by_power() {
        assert_eq!(
            base(&features(1, 1, false)).light_selection,
            LightSelection::Uniform
        );
        // Veach's scene: four spheres and the environment. RIS is a trial, not the base.
        assert_eq!(
            base(&features(5, 4, true)).light_selection,
            LightSelection::Power
        );
    }

    #[test]
    fn auto_base_leaves_out_mis_where_no_light_can_be_hit() {
        let point_light = base(&features(1, 0, false));
        assert!(point_light.sample_lights);
        assert_eq!(point_light.mis, Mis::Off);
        assert_eq!(base(&features(1, 1, false)).mis, Mis::Power);
        let no_lights = base(&features(0, 0, false));
        assert!(!no_lights.sample_lights);
    }

    #[test]
    fn auto_base_leaves_a_constant_sky_to_bsdf_samples() {
        // The sky alone: nothing for light sampling; BSDF samples find it in full.
        let sky = base(&features(1, 0, true));
        assert!(!sky.sample_lights);
        assert_eq!(sky.mis, Mis::Off);
        // The sky and one area light: one light to sample, nothing to choose.
        let sky_and_lamp = base(&features(2, 1, true));
        assert!(sky_and_lamp.sample_lights);
        assert_eq!(sky_and_lamp.mis, Mis::Power);
        assert_eq!(sky_and_lamp.light_selection, LightSelection::Uniform);
    }
}
