//! The configuration ladder of a scene: the reference integrator, then one technique added per
//! rung, plus `auto`; rungs that cannot apply to the scene are left out.

use integrators::reference::ReferenceSettings;
use integrators::{
    DirectSamples, LightSelection, LightTracing, MAX_EVERY_LIGHT, Mis, PathReuse, PathSettings,
    RussianRoulette,
};
use render::auto::{REUSE_BLOCK, Trials};
use render::plan::{RIS_CANDIDATES, RenderPlan, Transport};
use sampling::sampler::SamplerKind;
use scene::SceneFeatures;

/// Name of the reference integrator's configuration (the one others are compared with).
pub const REFERENCE: &str = "reference";

/// One rung: a named light transport and sampler.
#[derive(Clone, Debug, PartialEq)]
pub struct Configuration {
    /// Short name used in the CSV, file names and tables.
    pub name: String,
    /// The light transport.
    pub transport: Transport,
    /// The sampling pattern.
    pub sampler: SamplerKind,
    /// Adaptive sampling (a pilot render allocates samples per pixel).
    pub adaptive: bool,
    /// What `auto` measures before rendering (nothing for the other rungs).
    pub trials: Trials,
    /// The rung this one adds a technique to (`None` for the reference integrator and `auto`,
    /// which stand on their own). Not always the rung above it: `+roulette` builds on `mis`,
    /// not on the light-selection rungs listed between them.
    pub builds_on: Option<String>,
    /// Whether each camera sample's time comes from independent numbers rather than the
    /// sampler's pattern (see `RenderPlan::independent_time`).
    pub independent_time: bool,
}

impl Configuration {
    /// Every technique the rung renders with: the light transport's, then the sampler and
    /// adaptive sampling; for `auto`, its base and what its pilot tries
    /// (`pilot-tries-…`), since the pilot decides the rest on the scene.
    pub fn techniques(&self) -> Vec<String> {
        let mut names = self.transport.technique_names();
        names.push(format!("sampler-{}", self.sampler));
        if self.independent_time {
            names.push("time-independent".to_string());
        }
        if self.adaptive {
            names.push("adaptive-sampling".to_string());
        }
        let trials = [
            (self.trials.ris, "ris-lights"),
            (self.trials.uniform_lights, "uniform-lights"),
            (self.trials.every_light, "every-light"),
            (self.trials.no_roulette, "no-roulette"),
            (self.trials.no_light_tracing, "no-light-tracing"),
            (self.trials.sparse_light_paths, "sparse-light-paths"),
            (self.trials.path_reuse, "path-reuse"),
        ];
        names.extend(
            trials
                .iter()
                .filter(|(on, _)| *on)
                .map(|(_, name)| format!("pilot-tries-{name}")),
        );
        names
    }
}

/// What the scene file fixes for every configuration.
#[derive(Clone, Copy, Debug)]
pub struct SceneTransport {
    /// Longest path in vertices (None: unbounded).
    pub max_depth: Option<u32>,
    /// Whether emitters seen directly by the camera are hidden.
    pub hide_emitters: bool,
    /// The scene's Russian roulette start depth.
    pub roulette: RussianRoulette,
    /// Whether caustics by light tracing apply (`render::plan::light_tracing_applies`).
    pub light_tracing: bool,
    /// The sample counts of a `direct` integrator (`None` for `path`).
    pub direct_samples: Option<DirectSamples>,
    /// Whether a pass through a null lobe is not a path vertex (Mitsuba's `volpath`).
    pub skip_null_vertices: bool,
    /// Whether path reuse has something to share: a diffuse material.
    pub path_reuse: bool,
}

impl SceneTransport {
    /// The path tracer with MIS (power heuristic), NEE, power light selection, no roulette: the
    /// preset the stored references are rendered with.
    pub fn mis(&self) -> PathSettings {
        PathSettings {
            max_depth: self.max_depth,
            hide_emitters: self.hide_emitters,
            sample_lights: true,
            sample_bsdf: true,
            mis: Mis::Power,
            light_selection: LightSelection::Power,
            russian_roulette: None,
            light_tracing: None,
            direct_samples: self.direct_samples,
            skip_null_vertices: self.skip_null_vertices,
            delta_splitting: false,
            path_reuse: None,
        }
    }
}

/// The ladder for a scene with `features`, each rung naming the one it builds on
/// ([`Configuration::builds_on`]): reference; BSDF sampling only; NEE without MIS; MIS; uniform
/// and RIS light selection (with more than one light) and + roulette, each on MIS (on NEE where
/// no light can be hit, on BSDF sampling where none can be sampled); + stratified, + blue noise
/// and + Sobol, each a sampler swapped into + roulette; + adaptive sampling on + Sobol; + light
/// tracing (where it applies) and + path reuse (where a diffuse material gives it something to
/// share), each on + adaptive; and `auto`: the plan `strata render` makes without flags, whose
/// pilot chooses its techniques on the scene. BSDF-only is left out when the scene has delta
/// lights (paths cannot hit them) or no lights; the NEE and MIS rungs when no light can be
/// sampled; MIS when no light can be hit (it equals NEE there). Where something moves, a Sobol
/// rung with independent times (`sobol-random-time`) comes between + roulette and + Sobol, so
/// that + Sobol's gain is what stratifying time buys; path reuse then does not apply.
pub fn ladder(
    transport: &SceneTransport,
    features: &SceneFeatures,
    auto: &RenderPlan,
) -> Vec<Configuration> {
    let rung =
        |name: &str, settings: PathSettings, sampler, builds_on: Option<&str>| Configuration {
            name: name.to_string(),
            transport: Transport::Path(settings),
            sampler,
            adaptive: false,
            trials: Trials::default(),
            builds_on: builds_on.map(str::to_string),
            independent_time: false,
        };
    let independent = SamplerKind::Independent;
    let mis = transport.mis();
    let mut rungs = vec![Configuration {
        name: REFERENCE.to_string(),
        transport: Transport::Reference(ReferenceSettings {
            max_depth: transport.max_depth,
            hide_emitters: transport.hide_emitters,
            direct_samples: transport.direct_samples,
            skip_null_vertices: transport.skip_null_vertices,
        }),
        sampler: independent,
        adaptive: false,
        trials: Trials::default(),
        builds_on: None,
        independent_time: false,
    }];
    let no_nee = PathSettings {
        sample_lights: false,
        mis: Mis::Off,
        ..mis
    };
    if features.light_count > 0 && !features.has_delta_lights() {
        rungs.push(rung("bsdf", no_nee, independent, Some(REFERENCE)));
    }
    let can_sample_lights = features.light_count > 0 && features.has_non_delta_bsdfs;
    let last = |rungs: &[Configuration]| rungs.last().map(|c| c.name.clone());
    if can_sample_lights {
        let below = last(&rungs);
        rungs.push(rung(
            "nee",
            PathSettings {
                mis: Mis::Off,
                ..mis
            },
            independent,
            below.as_deref(),
        ));
        if features.has_hittable_lights() {
            rungs.push(rung("mis", mis, independent, Some("nee")));
        }
    }
    let (best, best_name) = if can_sample_lights && features.has_hittable_lights() {
        (mis, "mis")
    } else if can_sample_lights {
        (
            PathSettings {
                mis: Mis::Off,
                ..mis
            },
            "nee",
        )
    } else {
        (no_nee, "bsdf")
    };
    // The rung the later ones build on, when the ladder has it (a scene with only delta lights
    // and no BSDF to sample them has neither `bsdf` nor `nee`).
    let best_name = rungs
        .iter()
        .any(|c| c.name == best_name)
        .then_some(best_name);
    // Lights that `best` samples: under MIS, not a constant environment.
    let sampled = if best.mis == Mis::Off {
        features.light_count
    } else {
        features.lights_sampled_under_mis()
    };
    if can_sample_lights && sampled > 1 {
        let uniform = LightSelection::Uniform;
        let ris = LightSelection::Ris {
            candidates: RIS_CANDIDATES,
        };
        let every = (sampled <= MAX_EVERY_LIGHT).then_some(("every-light", LightSelection::All));
        let selections = [("uniform-lights", uniform), ("ris-lights", ris)];
        for (name, light_selection) in selections.into_iter().chain(every) {
            let settings = PathSettings {
                light_selection,
                ..best
            };
            rungs.push(rung(name, settings, independent, best_name));
        }
    }
    let roulette = PathSettings {
        russian_roulette: Some(transport.roulette),
        ..best
    };
    let on_roulette = Some("+roulette");
    rungs.push(rung("+roulette", roulette, independent, best_name));
    rungs.push(rung(
        "+stratified",
        roulette,
        SamplerKind::Stratified,
        on_roulette,
    ));
    rungs.push(rung(
        "+bluenoise",
        roulette,
        SamplerKind::BlueNoise,
        on_roulette,
    ));
    if features.has_motion {
        // What stratifying time buys (the lecture's motion blur): Sobol with the time from
        // independent numbers, which `+sobol` then builds on.
        rungs.push(Configuration {
            independent_time: true,
            ..rung(
                "sobol-random-time",
                roulette,
                SamplerKind::Sobol,
                on_roulette,
            )
        });
        rungs.push(rung(
            "+sobol",
            roulette,
            SamplerKind::Sobol,
            Some("sobol-random-time"),
        ));
    } else {
        rungs.push(rung("+sobol", roulette, SamplerKind::Sobol, on_roulette));
    }
    rungs.push(Configuration {
        adaptive: true,
        ..rung("+adaptive", roulette, SamplerKind::Sobol, Some("+sobol"))
    });
    if transport.light_tracing {
        let traced = PathSettings {
            light_tracing: Some(LightTracing::SPARSE),
            ..roulette
        };
        rungs.push(Configuration {
            adaptive: true,
            ..rung(
                "+light-tracing",
                traced,
                SamplerKind::Sobol,
                Some("+adaptive"),
            )
        });
    }
    let reusing = PathSettings {
        path_reuse: Some(PathReuse { block: REUSE_BLOCK }),
        ..roulette
    };
    if transport.path_reuse && reusing.reuse_applies() {
        rungs.push(Configuration {
            adaptive: true,
            ..rung(
                "+path-reuse",
                reusing,
                SamplerKind::Sobol,
                Some("+adaptive"),
            )
        });
    }
    // `auto` as `strata render` runs it without flags: the pilot picks its techniques.
    rungs.push(Configuration {
        name: "auto".to_string(),
        transport: auto.transport,
        sampler: auto.sampler,
        adaptive: auto.adaptive,
        trials: auto.trials,
        builds_on: None,
        independent_time: false,
    });
    rungs
}

#[cfg(test)]
mod tests {
    use super::*;

    fn transport() -> SceneTransport {
        SceneTransport {
            max_depth: Some(8),
            hide_emitters: false,
            roulette: RussianRoulette { start_depth: 5 },
            light_tracing: false,
            direct_samples: None,
            skip_null_vertices: false,
            path_reuse: false,
        }
    }

    fn features(light_count: usize, has_delta_lights: bool) -> SceneFeatures {
        SceneFeatures {
            light_count,
            has_non_delta_bsdfs: true,
            has_delta_bsdfs: false,
            area_light_count: if has_delta_lights { 0 } else { light_count },
            has_environment: false,
            lights_left_to_bsdf: 0,
            has_glossy_bsdfs: false,
            has_delta_lobe_choice: false,
            has_null_lobes: false,
            has_diffuse_bsdfs: true,
            has_motion: false,
        }
    }

    /// A plan as `auto` makes one: Sobol, adaptive, RIS and path reuse to be tried.
    fn auto_plan() -> RenderPlan {
        RenderPlan {
            adaptive: true,
            trials: Trials {
                ris: true,
                path_reuse: true,
                ..Trials::default()
            },
            ..RenderPlan::fixed_spp(
                Transport::Path(PathSettings::default()),
                SamplerKind::Sobol,
                1,
                64,
            )
        }
    }

    fn names(rungs: &[Configuration]) -> Vec<&str> {
        rungs.iter().map(|c| c.name.as_str()).collect()
    }

    #[test]
    fn light_selection_rungs_only_with_several_lights() {
        let one = ladder(&transport(), &features(1, false), &auto_plan());
        assert_eq!(
            names(&one),
            [
                "reference",
                "bsdf",
                "nee",
                "mis",
                "+roulette",
                "+stratified",
                "+bluenoise",
                "+sobol",
                "+adaptive",
                "auto"
            ]
        );
        let many = ladder(&transport(), &features(4, false), &auto_plan());
        assert!(names(&many).contains(&"uniform-lights"));
        assert!(names(&many).contains(&"ris-lights"));
        assert!(names(&many).contains(&"every-light"));
        let crowd = ladder(&transport(), &features(9, false), &auto_plan());
        assert!(!names(&crowd).contains(&"every-light"));
    }

    #[test]
    fn each_rung_builds_on_the_rung_whose_settings_it_changes() {
        let rungs = ladder(
            &SceneTransport {
                light_tracing: true,
                path_reuse: true,
                ..transport()
            },
            &features(4, false),
            &auto_plan(),
        );
        let on = |name: &str| {
            rungs
                .iter()
                .find(|c| c.name == name)
                .unwrap_or_else(|| panic!("no rung {name}"))
                .builds_on
                .as_deref()
        };
        for (name, base) in [
            (REFERENCE, None),
            ("bsdf", Some(REFERENCE)),
            ("nee", Some("bsdf")),
            ("mis", Some("nee")),
            ("uniform-lights", Some("mis")),
            ("ris-lights", Some("mis")),
            ("every-light", Some("mis")),
            ("+roulette", Some("mis")),
            ("+stratified", Some("+roulette")),
            ("+bluenoise", Some("+roulette")),
            ("+sobol", Some("+roulette")),
            ("+adaptive", Some("+sobol")),
            ("+light-tracing", Some("+adaptive")),
            ("+path-reuse", Some("+adaptive")),
            ("auto", None),
        ] {
            assert_eq!(on(name), base, "{name}");
        }
        // A rung differs from its base by what its name adds, and keeps everything else: the
        // technique lists say so.
        let techniques = |name: &str| {
            rungs
                .iter()
                .find(|c| c.name == name)
                .expect("rung")
                .techniques()
        };
        let roulette = techniques("+roulette");
        let mis = techniques("mis");
        assert_eq!(roulette.len(), mis.len() + 1);
        assert!(mis.iter().all(|t| roulette.contains(t)), "{roulette:?}");
        assert!(roulette.iter().any(|t| t.starts_with("russian-roulette")));
        assert!(techniques("+adaptive").contains(&"adaptive-sampling".to_string()));
        assert!(techniques("+sobol").contains(&"sampler-sobol".to_string()));
        assert!(techniques("auto").contains(&"pilot-tries-path-reuse".to_string()));
    }

    #[test]
    fn with_delta_lights_nee_builds_on_the_reference() {
        let rungs = ladder(&transport(), &features(1, true), &auto_plan());
        let nee = rungs.iter().find(|c| c.name == "nee").expect("nee rung");
        assert_eq!(nee.builds_on.as_deref(), Some(REFERENCE));
        let roulette = rungs.iter().find(|c| c.name == "+roulette").expect("rung");
        assert_eq!(roulette.builds_on.as_deref(), Some("nee"));
    }

    #[test]
    fn point_lights_drop_bsdf_only_and_mis() {
        let rungs = ladder(&transport(), &features(1, true), &auto_plan());
        let names = names(&rungs);
        assert!(!names.contains(&"bsdf") && !names.contains(&"mis"));
        assert!(names.contains(&"nee"));
        let Transport::Path(roulette) =
            rungs[names.iter().position(|n| *n == "+roulette").unwrap()].transport
        else {
            panic!("+roulette is a path configuration");
        };
        assert_eq!(roulette.mis, Mis::Off);
        assert!(roulette.russian_roulette.is_some());
    }

    #[test]
    fn light_tracing_rung_only_where_it_applies() {
        let without = ladder(&transport(), &features(1, false), &auto_plan());
        assert!(!names(&without).contains(&"+light-tracing"));
        let with = ladder(
            &SceneTransport {
                light_tracing: true,
                ..transport()
            },
            &features(1, false),
            &auto_plan(),
        );
        assert!(names(&with).contains(&"+light-tracing"));
    }

    #[test]
    fn path_reuse_rung_where_reuse_has_diffuse_surfaces_to_share() {
        let reusing = SceneTransport {
            path_reuse: true,
            ..transport()
        };
        for (scene, expected) in [
            (transport(), false),
            (reusing, true),
            (
                SceneTransport {
                    light_tracing: true,
                    ..reusing
                },
                true,
            ),
            (
                SceneTransport {
                    max_depth: Some(2),
                    ..reusing
                },
                false,
            ),
        ] {
            let rungs = ladder(&scene, &features(1, false), &auto_plan());
            assert_eq!(
                names(&rungs).contains(&"+path-reuse"),
                expected,
                "{scene:?}"
            );
        }
    }

    #[test]
    fn the_auto_rung_is_the_default_plan_with_its_trials() {
        let plan = auto_plan();
        let rungs = ladder(&transport(), &features(4, false), &plan);
        let auto = rungs.last().expect("auto is last");
        assert_eq!(auto.name, "auto");
        assert_eq!(
            (auto.transport, auto.sampler, auto.adaptive, auto.trials),
            (plan.transport, plan.sampler, plan.adaptive, plan.trials)
        );
    }
}
