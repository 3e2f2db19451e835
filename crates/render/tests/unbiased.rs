//! Every technique switch, and every choice `auto` can make, converges to the reference
//! integrator's image on every scene of the suite; and light-only, BSDF-only and MIS converge
//! to the same image.
//!
//! **Oracle.** The reference integrator (uniform directions, emission on hit, no tricks) with
//! the independent sampler, at the depth of the scene's test version. It never shares an
//! estimator with the configuration under test.
//!
//! **Test.** Each configuration and the oracle are rendered [`REPLICATES`] times with different
//! seeds, and `common::compare` compares their replicate means on the whole image, on 8 × 8
//! regions and on 4 × 4 blocks with Welch's t-test, the variance of each from the spread over
//! the replicates (which stay independent whatever a render correlates: path reuse's blocks,
//! light tracing's splats, the samplers' patterns). Significance: a family-wise α =
//! [`SCENE_ALPHA`] (0.01) per scene version over every comparison its test makes (Bonferroni
//! over at most [`MAX_COMPARISONS`], so [`ALPHA`] ≈ 3.8e-4 per comparison of a configuration
//! with the oracle), a third of that per level (Bonferroni), Šidák's correction within a level.
//! Every test must pass. Over the suite's 24 scene versions, a new realisation of every sample
//! (a change of seeds or of the dimension order) fails a correct renderer somewhere with
//! probability at most 1 − 0.99²⁴ ≈ 21%; at 0.01 per comparison (the first version of this
//! test) it was expected to fail about three of its ~340 comparisons.
//!
//! **Configurations.** Every switch of the path integrator on MIS (power heuristic,
//! power-proportional light choice) with the Sobol sampler, `auto`'s default, whose stratified
//! pixel positions keep the edges of directly seen lights from dominating the image's variance;
//! the other samplers as configurations of their own; switches that change nothing on a scene
//! (light tracing without a light it can trace from, uniform light choice with one light) left
//! out. On the scenes that exercise `auto`'s trials, every candidate its pilot can choose and
//! `auto` end to end (see [`check_auto`]).
//!
//! **Power.** Each comparison is repeated on the configuration's image × (1 + bias) and on it
//! with a typical 4 × 4 block × (1 + bias), and must reject both (see `common::compare`): 0.5%
//! of the image and 5% of a block (`common::compare::POWER`), on every scene. The budgets ([`Budget`]) were
//! chosen from the standard errors measured on each scene, so that each bias is about 6
//! standard errors or more of the image test and 7.3 of the block test, where the thresholds
//! are about 4.3 and 5.5 (Student's t at these levels with 30–60 degrees of freedom); a run
//! prints each comparison's standard errors and how many standard errors each bias is. Where
//! the reference integrator converges too slowly for that, the scene's test version has larger
//! lights or rougher surfaces (see **Scene versions**), never less power.
//!
//! **Scene versions.** Scenes are rendered at [`SIZE`]² pixels. Where the reference integrator
//! cannot find a scene's lights often enough to converge in the time of a test run (its
//! standard error falls as one over the square root of the samples, and a small light is found
//! by a uniform direction once in hundreds or thousands, and a narrow glossy lobe as rarely),
//! the test renders a version of the scene with larger lights (of the same power) or rougher
//! surfaces, named in each test with the edit; the code paths are the same.
//!
//! **Replay.** Seeds are fixed (oracle from [`ORACLE_SEED`], configurations from
//! [`CONFIG_SEED`]); a failure names the scene, the configuration, both replicate sets (seeds,
//! samples per pixel, size) and the worst unit of each level.

mod common;

use common::compare::{Replicates, check_unbiased, compare};
use common::{Configuration, configurations_with, load_version, mis_power, scenes_dir};
use integrators::{LightSelection, LightTracer, LightTracing, Mis, PathReuse, PathSettings};
use render::auto::{REUSE_BLOCK, Trials};
use render::plan::{RIS_CANDIDATES, RenderPlan, Transport, plan_from_flags};
use sampling::sampler::SamplerKind;
use scene::RenderScene;

/// Image edge, pixels, of every scene's test version.
const SIZE: u32 = 16;
/// Family-wise significance level of one scene version's test: of every comparison it makes.
const SCENE_ALPHA: f64 = 0.01;
/// The most comparisons one scene version makes: 15 configurations, light-only and BSDF-only
/// against MIS, 8 of `auto`'s candidates and `auto` end to end (26); `check_scene` asserts it.
const MAX_COMPARISONS: usize = 26;
/// Family-wise significance level of one comparison (Bonferroni over the scene's comparisons).
const ALPHA: f64 = SCENE_ALPHA / MAX_COMPARISONS as f64;
/// Independent renders of each configuration and of the oracle.
const REPLICATES: u32 = 32;
/// Independent renders of `auto` end to end (each runs its pilots, so each needs enough samples
/// per pixel for them: [`Auto::spp`]).
const AUTO_REPLICATES: u32 = 16;
/// First seed of the oracle's replicates.
const ORACLE_SEED: u32 = 1000;
/// First seed of every configuration's replicates.
const CONFIG_SEED: u32 = 2000;

/// The seeds of a replicate set starting at `first`.
fn seeds(first: u32) -> std::ops::Range<u32> {
    first..first + REPLICATES
}

/// The test version of a scene file.
#[derive(Clone, Copy)]
struct Version {
    /// The file, relative to `scenes/`.
    file: &'static str,
    /// Edits of its text (see `common::load_version`).
    replace: &'static [(&'static str, &'static str)],
    /// Its `$NAME` defaults set.
    overrides: &'static [(&'static str, &'static str)],
    /// The integrator's `max_depth`, when not the file's.
    max_depth: Option<i32>,
}

impl Version {
    /// The scene file as it is.
    const fn file(file: &'static str) -> Self {
        Self {
            file,
            replace: &[],
            overrides: &[],
            max_depth: None,
        }
    }

    fn load(&self) -> RenderScene {
        load_version(
            &scenes_dir().join(self.file),
            self.replace,
            self.overrides,
            SIZE,
            self.max_depth,
        )
    }
}

/// Samples per pixel of each replicate.
#[derive(Clone, Copy)]
struct Budget {
    /// Of the oracle.
    oracle: u32,
    /// Of each configuration.
    config: u32,
    /// Of the configurations whose estimators are poor on the scene (without MIS, or with the
    /// independent sampler, whose random pixel positions make the edges of directly seen lights
    /// noisy), as a multiple of `config`.
    heavy_factor: u32,
    /// Configurations whose estimators are poor on this scene alone, by label, with the
    /// multiple of `config` they are rendered at (instead of `heavy_factor`'s rule).
    factors: &'static [(&'static str, u32)],
}

impl Budget {
    /// Samples per pixel of the oracle, of each configuration, and the multiple of the latter
    /// for the configurations poor on most scenes; no configuration poor on this scene alone.
    const fn new(oracle: u32, config: u32, heavy_factor: u32) -> Self {
        Self {
            oracle,
            config,
            heavy_factor,
            factors: &[],
        }
    }

    /// Samples per pixel of each replicate of `configuration`: [`Budget::factors`]' multiple
    /// of `config` where it names the configuration, else `heavy_factor`'s where the estimator
    /// is poor on most scenes (without MIS, or with the independent sampler), else `config`.
    fn config_spp(&self, configuration: &Configuration) -> u32 {
        let heavy = configuration.settings.mis == Mis::Off
            || configuration.sampler == SamplerKind::Independent;
        let factor = self
            .factors
            .iter()
            .find(|(label, _)| *label == configuration.label)
            .map_or(if heavy { self.heavy_factor } else { 1 }, |&(_, f)| f);
        self.config * factor
    }
}

/// What `auto` is tested with on a scene (see [`check_auto`]).
#[derive(Clone, Copy)]
struct Auto {
    /// The trials its plan must make on the scene.
    trials: Trials,
    /// Samples per pixel of each end-to-end replicate (the technique pilot runs only where it
    /// takes at most a tenth of them).
    spp: u32,
}

/// The oracle's replicates.
fn oracle(scene: &RenderScene, budget: Budget) -> Replicates {
    Replicates::render(
        scene,
        "reference",
        seeds(ORACLE_SEED),
        budget.oracle,
        |seed| {
            RenderPlan::fixed_spp(
                common::reference(scene),
                SamplerKind::Independent,
                seed,
                budget.oracle,
            )
        },
    )
}

/// Whether `configuration` renders the same estimator as MIS on `scene` (a switch that finds
/// nothing to do), so that rendering it again would test nothing new.
fn changes_nothing(scene: &RenderScene, configuration: &Configuration) -> bool {
    let settings = &configuration.settings;
    match configuration.label {
        "light tracing" => {
            LightTracer::new(&scene.world, settings, scene.camera.traits()).is_none()
        }
        "delta splitting" => !scene.features.has_delta_lobe_choice,
        "mis power uniform selection" | "mis power every light" => {
            scene.features.lights_sampled_under_mis() <= 1
        }
        _ => false,
    }
}

/// Every configuration (switches on MIS with the Sobol sampler, and the other samplers) against
/// the oracle on `version` of `name`, light-only and BSDF-only against MIS, and `auto` when
/// `auto` says how.
fn check_scene(name: &str, version: Version, budget: Budget, auto: Option<Auto>) {
    let scene = version.load();
    let oracle = oracle(&scene, budget);
    let base = PathSettings {
        skip_null_vertices: scene.desc.integrator.skip_null_vertices,
        ..mis_power(
            common::max_depth(&scene),
            scene.desc.integrator.hide_emitters,
        )
    };
    let mut failures = Vec::new();
    let mut comparisons = 0;
    let mut rendered = Vec::new();
    for configuration in configurations_with(base, SamplerKind::Sobol) {
        if changes_nothing(&scene, &configuration) {
            continue;
        }
        let spp = budget.config_spp(&configuration);
        let Configuration {
            label,
            settings,
            sampler,
        } = configuration;
        let replicates = Replicates::render(&scene, label, seeds(CONFIG_SEED), spp, |seed| {
            RenderPlan::fixed_spp(Transport::Path(settings), sampler, seed, spp)
        });
        comparisons += 1;
        if let Err(failure) = check_unbiased(name, &replicates, &oracle, ALPHA) {
            failures.push(failure);
        }
        rendered.push(replicates);
    }
    let find = |label: &str| {
        rendered
            .iter()
            .find(|r| r.label == label)
            .unwrap_or_else(|| panic!("{label} was rendered"))
    };
    // A factor whose label names no rendered configuration (a typo) fails here.
    for (label, _) in budget.factors {
        find(label);
    }
    let mis = find("mis power");
    for other in ["bsdf-only", "light-only (nee, no mis)"] {
        comparisons += 1;
        let outcome = compare(find(other), mis, ALPHA);
        println!("figure: {name} / {other} vs mis power: {outcome}");
        if !outcome.passed() {
            failures.push(format!(
                "{name}: {} and {} differ: {outcome}",
                find(other).replay(),
                mis.replay()
            ));
        }
    }
    if let Some(auto) = auto {
        let (auto_failures, auto_comparisons) = check_auto(name, &scene, &oracle, budget, auto);
        failures.extend(auto_failures);
        comparisons += auto_comparisons;
    }
    assert!(
        comparisons <= MAX_COMPARISONS,
        "{name}: {comparisons} comparisons, but ALPHA is shared by {MAX_COMPARISONS}"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn point_light_and_rough_metal() {
    check_scene(
        "pointlight",
        Version::file("pointlight.xml"),
        Budget::new(384, 160, 8),
        None,
    );
}

/// The glass and mirror Cornell box with its ceiling light enlarged from 0.46 × 0.38 to
/// 1.8 × 1.8 (of the 2 × 2 ceiling): the reference integrator finds the original light with
/// one uniform direction in about a hundred, which needs about 10⁸ samples for the image's
/// standard error to reach 0.1%.
#[test]
fn glass_and_mirror_cornell_box() {
    check_scene(
        "cbox-glass",
        LARGE_LIGHT_GLASS,
        Budget::new(1024, 112, 2),
        Some(Auto {
            trials: Trials {
                no_roulette: true,
                no_light_tracing: true,
                sparse_light_paths: true,
                path_reuse: true,
                ..Trials::default()
            },
            spp: 512,
        }),
    );
}

/// The glass and mirror Cornell box of [`glass_and_mirror_cornell_box`] with both spheres
/// moving while the shutter is open (motion blur): every configuration sees the scene at each
/// camera sample's time, light tracing's paths and camera connections at their own.
#[test]
fn moving_glass_and_mirror() {
    check_scene(
        "cbox-glass-motion",
        MOVING_GLASS,
        Budget::new(1024, 96, 2),
        None,
    );
}

/// [`LARGE_LIGHT_GLASS`] with the shutter open from 0 to 1, the glass sphere sliding 0.25 along
/// x and the mirror sphere rising 0.2.
const MOVING_GLASS: Version = Version {
    file: "cbox-glass.xml",
    replace: &[
        LARGE_CEILING_LIGHT,
        (
            r#"<sensor type="perspective">"#,
            r#"<sensor type="perspective"><float name="shutter_close" value="1"/>"#,
        ),
        (
            r#"<ref id="glass"/>"#,
            r#"<ref id="glass"/><animation name="to_world"><transform time="0"/><transform time="1"><translate x="0.25"/></transform></animation>"#,
        ),
        (
            r#"<ref id="mirror"/>
    </shape>"#,
            r#"<ref id="mirror"/><animation name="to_world"><transform time="0"/><transform time="1"><translate y="0.2"/></transform></animation>
    </shape>"#,
        ),
    ],
    overrides: &[],
    max_depth: Some(6),
};

/// [`LARGE_LIGHT_GLASS`] with a rough gold floor (GGX, α 0.3) at `max_depth` 4: the glass and
/// mirror spheres' caustics on the floor are found both by the path tracer's BSDF samples of
/// the glossy floor and by light tracing, each path weighted between the two (`caustic_mis`)
/// with weights well inside (0, 1), so that weights that do not sum to one show.
#[test]
fn caustics_on_a_rough_metal_floor() {
    check_scene(
        "cbox-glass-rough-floor",
        Version {
            replace: &[
                LARGE_CEILING_LIGHT,
                (
                    r#"<translate y="-1"/>
        </transform>
        <ref id="white"/>"#,
                    r#"<translate y="-1"/>
        </transform>
        <bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.3"/></bsdf>"#,
                ),
            ],
            max_depth: Some(4),
            ..Version::file("cbox-glass.xml")
        },
        Budget::new(2048, 112, 4),
        None,
    );
}

/// `cbox-glass.xml` with a large ceiling light.
const LARGE_LIGHT_GLASS: Version = Version {
    file: "cbox-glass.xml",
    replace: &[LARGE_CEILING_LIGHT],
    overrides: &[],
    max_depth: Some(6),
};

/// The Cornell boxes' ceiling light (0.46 × 0.38) scaled to 1.8 × 1.8.
const LARGE_CEILING_LIGHT: (&str, &str) = (
    r#"<scale x="0.23" y="0.19" z="0.19"/>"#,
    r#"<scale x="0.9" y="0.9" z="0.19"/>"#,
);

/// Mitsuba's `plastic` (a delta lobe and a diffuse one in one BSDF, which the reference and the
/// uniform-direction configuration reach by choosing between the mirror and a uniform
/// direction), from the Mitsuba crosscheck scenes.
#[test]
fn plastic() {
    check_scene(
        "plastic",
        Version::file("../tests/crosscheck/plastic.xml"),
        Budget::new(2048, 48, 16),
        None,
    );
}

/// Mitsuba's `envmap` (an OpenEXR sky with a small bright sun, rotated and scaled, seen
/// directly, through glass and in a mirror, with an area light besides), from the Mitsuba
/// crosscheck scenes, at `max_depth` 3.
#[test]
fn environment_map() {
    check_scene(
        "envmap",
        Version {
            max_depth: Some(3),
            ..Version::file("../tests/crosscheck/envmap.xml")
        },
        Budget::new(14336, 640, 4),
        Some(Auto {
            trials: Trials {
                ris: true,
                uniform_lights: true,
                every_light: true,
                no_light_tracing: true,
                sparse_light_paths: true,
                path_reuse: true,
                ..Trials::default()
            },
            spp: 640,
        }),
    );
}

/// Mitsuba's `blendbsdf` with delta lobes among its BSDFs (a mirror, glass and a plastic each
/// blended with a diffuse or glossy one), from the Mitsuba crosscheck scenes.
#[test]
fn blend() {
    check_scene(
        "blend",
        Version {
            overrides: &[
                ("metal", "conductor"),
                ("glass", "dielectric"),
                ("coat", "plastic"),
            ],
            ..Version::file("../tests/crosscheck/blend.xml")
        },
        Budget::new(1152, 96, 4),
        None,
    );
}

/// Mitsuba's `checkerboard` as diffuse reflectances (a tiled floor, a sphere, a twosided card, a
/// cube) and as the base of a plastic wall and a rough plastic ball, from the Mitsuba crosscheck
/// scenes.
#[test]
fn checkerboard() {
    check_scene(
        "checkerboard",
        Version::file("../tests/crosscheck/checkerboard.xml"),
        Budget::new(1920, 128, 4),
        None,
    );
}

/// Mitsuba's `blendbsdf` with textured weights (an 8-bit PNG's luminance, a 16-bit grey PNG, a
/// checkerboard), from the Mitsuba crosscheck scenes.
#[test]
fn blend_weight_textures() {
    check_scene(
        "blend-texture",
        Version::file("../tests/crosscheck/blend-texture.xml"),
        Budget::new(1536, 128, 4),
        None,
    );
}

/// Mitsuba's `null` BSDF (an invisible card before the camera, an invisible sphere around a
/// ball, an emitting sphere that lets what is behind it show), from the Mitsuba crosscheck
/// scenes.
#[test]
fn null_bsdf() {
    check_scene(
        "null",
        Version::file("../tests/crosscheck/null.xml"),
        Budget::new(5376, 320, 2),
        None,
    );
}

/// Opacity masks (a bitmap's, a checkerboard's, the default ½ and a constant, over diffuse,
/// rough gold and a mirror), from the Mitsuba crosscheck scenes, at `max_depth` 3.
#[test]
fn mask() {
    check_scene(
        "mask",
        Version {
            replace: &[LARGE_CROSSCHECK_LIGHT],
            max_depth: Some(3),
            ..Version::file("../tests/crosscheck/mask.xml")
        },
        Budget {
            factors: &[("nee uniform directions", 5)],
            ..Budget::new(4608, 272, 2)
        },
        None,
    );
}

/// The rectangular light of the mask and textured-blend scenes with its edges doubled and its
/// radiance a quarter (the same power).
const LARGE_CROSSCHECK_LIGHT: (&str, &str) = (
    r#"<scale x="1.0" y="0.6"/><rotate x="1" angle="60"/><translate x="-0.4" y="1.7" z="-0.6"/></transform>
        <emitter type="area"><rgb name="radiance" value="3, 2.8, 2.6"/></emitter>"#,
    r#"<scale x="2.0" y="1.2"/><rotate x="1" angle="60"/><translate x="-0.4" y="1.7" z="-0.6"/></transform>
        <emitter type="area"><rgb name="radiance" value="0.75, 0.7, 0.65"/></emitter>"#,
);

/// Blends and masks of BSDFs with bitmap albedos (Mitsuba's leaf: a bitmap mask around a
/// twosided diffuse with a bitmap reflectance; a JPEG diffuse blended with rough gold; a rough
/// plastic with an OpenEXR base blended by a PNG), from the Mitsuba crosscheck scenes.
#[test]
fn textured_blends() {
    check_scene(
        "textured-blend",
        Version {
            replace: &[LARGE_CROSSCHECK_LIGHT],
            ..Version::file("../tests/crosscheck/textured-blend.xml")
        },
        Budget::new(1024, 80, 3),
        None,
    );
}

/// Mitsuba's `volpath` on surfaces, where passes through null lobes (an invisible card, a
/// thin pane, a mask, a glowing null sphere) are not path vertices, at `max_depth` 3 with and
/// without hidden emitters, from the Mitsuba crosscheck scenes.
#[test]
fn volpath_null_vertices() {
    let file = Version {
        // The ceiling light's edges ×2 and ×1.8, its radiance ÷ 3.6 (the same power).
        replace: &[(
            r#"<scale x="0.8" y="0.5"/><rotate x="1" angle="90"/><translate x="0.2" y="1.8" z="-0.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="6, 5.6, 5"/></emitter>"#,
            r#"<scale x="1.6" y="0.9"/><rotate x="1" angle="90"/><translate x="0.2" y="1.8" z="-0.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="1.6667, 1.5556, 1.3889"/></emitter>"#,
        )],
        ..Version::file("../tests/crosscheck/volpath.xml")
    };
    let hidden = Budget {
        factors: &[("roulette from 2", 2)],
        ..Budget::new(6144, 416, 3)
    };
    check_scene("volpath", file, hidden, None);
    check_scene(
        "volpath (emitters shown)",
        Version {
            overrides: &[("hide", "false")],
            ..file
        },
        Budget::new(2048, 192, 3),
        None,
    );
}

/// Mitsuba's `bitmap` as diffuse and plastic reflectances (8-bit sRGB and 16-bit grey PNGs, a
/// JPEG and a float OpenEXR image with every filter and wrap mode, on rectangles, a sphere, an OBJ
/// quad, a twosided card and a plastic cube), from the Mitsuba crosscheck scenes.
#[test]
fn bitmap() {
    check_scene(
        "bitmap",
        Version::file("../tests/crosscheck/bitmap.xml"),
        Budget::new(1024, 96, 4),
        None,
    );
}

/// Mitsuba's `roughplastic` (a glossy coating over a diffuse base, seen directly and through
/// the twosided wrapper), from the Mitsuba crosscheck scenes, every roughness at 0.3.
#[test]
fn rough_plastic() {
    check_scene(
        "rough-plastic",
        Version {
            overrides: &[
                ("floor_alpha", "0.3"),
                ("ball_alpha", "0.3"),
                ("card_alpha", "0.3"),
            ],
            ..Version::file("../tests/crosscheck/rough-plastic.xml")
        },
        Budget::new(1024, 32, 8),
        None,
    );
}

/// Mitsuba's `roughdielectric` (reflection and refraction by microfacets, seen through, lit
/// through and lighting through), from the Mitsuba crosscheck scenes, every roughness at 0.5,
/// at `max_depth` 3: uniform directions are heavy-tailed through rough refraction (where the
/// half vector degenerates, f grows as 1 / (wo·m + η wi·m)² while GGX's D stays finite), and
/// chains of rough refractions make the reference's image converge too slowly to test.
#[test]
fn rough_glass() {
    check_scene(
        "rough-glass",
        Version {
            overrides: &[
                ("ball_alpha", "0.5"),
                ("slab_alpha", "0.5"),
                ("pane_alpha", "0.5"),
            ],
            // The light's edges ×3, its radiance ÷ 9 (the same power).
            replace: &[(
                r#"<scale x="0.8" y="0.5"/><rotate x="1" angle="90"/><translate x="0.2" y="2.0" z="0"/></transform>
        <emitter type="area"><rgb name="radiance" value="4, 3.6, 3.2"/></emitter>"#,
                r#"<scale x="2.4" y="1.5"/><rotate x="1" angle="90"/><translate x="0.2" y="2.0" z="0"/></transform>
        <emitter type="area"><rgb name="radiance" value="0.4444, 0.4, 0.3556"/></emitter>"#,
            )],
            max_depth: Some(3),
            ..Version::file("../tests/crosscheck/rough-glass.xml")
        },
        Budget {
            factors: &[
                ("nee uniform directions", 18),
                ("light-only (nee, no mis)", 16),
            ],
            ..Budget::new(6400, 176, 4)
        },
        None,
    );
}

/// The Cornell box with a large ceiling light (see [`glass_and_mirror_cornell_box`]), at
/// `max_depth` 6 (roulette starts at 5), with hidden emitters so that the light's own pixels
/// do not make most of the image's mean.
///
/// `cbox-smalllight.xml` is `cbox.xml` with a smaller, brighter light: its test version (the
/// light enlarged) would be this scene's, so this test covers it.
#[test]
fn cornell_box() {
    check_scene(
        "cbox",
        LARGE_LIGHT_BOX,
        Budget::new(8192, 384, 2),
        Some(Auto {
            trials: Trials {
                no_roulette: true,
                path_reuse: true,
                ..Trials::default()
            },
            spp: 512,
        }),
    );
}

/// `cbox.xml` with a large ceiling light and hidden emitters.
const LARGE_LIGHT_BOX: Version = Version {
    file: "cbox.xml",
    replace: &[LARGE_CEILING_LIGHT, HIDE_EMITTERS],
    overrides: &[],
    max_depth: Some(6),
};

/// The Cornell boxes' integrator with hidden emitters.
const HIDE_EMITTERS: (&str, &str) = (
    r#"<integer name="max_depth" value="$max_depth"/>"#,
    r#"<integer name="max_depth" value="$max_depth"/><boolean name="hide_emitters" value="true"/>"#,
);

/// The Cornell box with an OBJ mesh and rough gold, with a large ceiling light and hidden
/// emitters (see [`cornell_box`]).
#[test]
fn mesh_and_rough_gold_cornell_box() {
    check_scene(
        "cbox-mesh",
        Version {
            file: "cbox-mesh.xml",
            ..LARGE_LIGHT_BOX
        },
        Budget::new(6656, 304, 5),
        None,
    );
}

#[test]
fn furnace() {
    check_scene(
        "furnace",
        Version::file("furnace.xml"),
        Budget::new(128, 16, 1),
        None,
    );
}

#[test]
fn thin_lens() {
    check_scene(
        "thinlens",
        Version::file("thinlens.xml"),
        Budget::new(3072, 80, 4),
        None,
    );
}

/// The soft shadows scene under a constant sky (radiance 0.5) besides its square light (edge
/// 2.4 instead of 1.6), at `max_depth` 3: where MIS is on, light sampling leaves the sky to
/// BSDF samples, which then count in full; light-only keeps sampling it.
#[test]
fn soft_shadow_under_a_sky() {
    check_scene(
        "softshadow-sky",
        Version {
            replace: &[
                (
                    r#"<scale value="0.8"/>
            <rotate x="1" angle="90"/>"#,
                    r#"<scale value="1.2"/>
            <rotate x="1" angle="90"/>"#,
                ),
                (
                    "</scene>",
                    r#"<emitter type="constant"><rgb name="radiance" value="0.5"/></emitter></scene>"#,
                ),
            ],
            max_depth: Some(3),
            ..Version::file("softshadow.xml")
        },
        Budget::new(8192, 80, 32),
        None,
    );
}

/// The soft shadows scene with its square light's edge 2.4 instead of 1.6.
#[test]
fn soft_shadow() {
    check_scene(
        "softshadow",
        Version {
            replace: &[(
                r#"<scale value="0.8"/>
            <rotate x="1" angle="90"/>"#,
                r#"<scale value="1.2"/>
            <rotate x="1" angle="90"/>"#,
            )],
            ..Version::file("softshadow.xml")
        },
        Budget::new(8192, 80, 32),
        None,
    );
}

/// Veach's scene with sphere lights of radius 0.9 to 1.2 (equal power) instead of 0.03 to
/// 0.9, plates of roughness 0.6 to 0.3 instead of 0.25 to 0.005, and hidden emitters.
#[test]
fn veach_mis() {
    check_scene(
        "veach-mis",
        Version {
            replace: &[
                // The largest first, so that the smallest, which takes its place, is not edited
                // again.
                (
                    r#"<float name="radius" value="0.9"/>"#,
                    r#"<float name="radius" value="1.2"/>"#,
                ),
                (r#"value="0.03"/>"#, r#"value="0.9"/>"#),
                (r#"value="888.8889""#, r#"value="1""#),
                (
                    r#"<float name="radius" value="0.1"/>"#,
                    r#"<float name="radius" value="1.0"/>"#,
                ),
                (r#"value="80.0000""#, r#"value="0.81""#),
                (
                    r#"<float name="radius" value="0.3"/>"#,
                    r#"<float name="radius" value="1.1"/>"#,
                ),
                (r#"value="8.8889""#, r#"value="0.67""#),
                (r#"value="0.9877""#, r#"value="0.5625""#),
                (r#""alpha" value="0.25""#, r#""alpha" value="0.6""#),
                (r#""alpha" value="0.08""#, r#""alpha" value="0.5""#),
                (r#""alpha" value="0.02""#, r#""alpha" value="0.4""#),
                (r#""alpha" value="0.005""#, r#""alpha" value="0.3""#),
                (
                    r#"<integer name="max_depth" value="3"/>"#,
                    r#"<integer name="max_depth" value="3"/><boolean name="hide_emitters" value="true"/>"#,
                ),
            ],
            ..Version::file("veach-mis.xml")
        },
        Budget::new(53248, 960, 4),
        None,
    );
}

/// The many-lights scene with sphere lights of radius 0.6 instead of 0.04, and hidden emitters.
#[test]
fn many_lights() {
    check_scene(
        "manylights",
        Version {
            replace: &[
                (
                    r#"<float name="radius" value="0.04"/>"#,
                    r#"<float name="radius" value="0.6"/>"#,
                ),
                (
                    r#"<integer name="max_depth" value="3"/>"#,
                    r#"<integer name="max_depth" value="3"/><boolean name="hide_emitters" value="true"/>"#,
                ),
            ],
            ..Version::file("manylights.xml")
        },
        // Uniform choice and BSDF sampling alone meet a light 10⁴ times brighter than most
        // one sample in a few hundred: heavy tails.
        Budget {
            factors: &[("mis power uniform selection", 4), ("bsdf-only", 8)],
            ..Budget::new(6144, 304, 4)
        },
        None,
    );
}

/// One of `auto`'s trials in [`check_auto`]: whether the plan makes it, its label, and the
/// settings it switches.
type Switch<'a> = (bool, &'static str, &'a dyn Fn(PathSettings) -> PathSettings);

/// `auto` on `scene`: every candidate its technique pilot can choose (the base, the base with
/// each trial the plan makes switched, and every trial switched at once, path reuse then turning
/// light tracing off), each rendered as the image would be (with the plan's sampler), and `auto`
/// end to end (`plan_from_flags` with only `--spp` and `--seed`, which runs the pilot and
/// samples adaptively), against `oracle`. The plan's trials must be `auto.trials`, so that the
/// scenes keep covering every choice. Returns the failures and the number of comparisons.
fn check_auto(
    name: &str,
    scene: &RenderScene,
    oracle: &Replicates,
    budget: Budget,
    auto: Auto,
) -> (Vec<String>, usize) {
    let plan = |spp: u32, seed: Option<u32>| {
        let spp = spp.to_string();
        let seed = seed.map(|s| s.to_string());
        let mut flags = vec!["--spp", spp.as_str()];
        if let Some(seed) = &seed {
            flags.extend(["--seed", seed.as_str()]);
        }
        plan_from_flags(scene, &flags).expect("a plan")
    };
    let candidate_plan = plan(budget.config, None);
    let trials = auto.trials;
    assert_eq!(
        candidate_plan.trials, trials,
        "{name}: the trials auto makes"
    );
    let Transport::Path(base) = candidate_plan.transport else {
        panic!("{name}: auto renders with the path tracer");
    };
    let ris = |s: PathSettings| PathSettings {
        light_selection: LightSelection::Ris {
            candidates: RIS_CANDIDATES,
        },
        ..s
    };
    let uniform_lights = |s: PathSettings| PathSettings {
        light_selection: LightSelection::Uniform,
        ..s
    };
    let every_light = |s: PathSettings| PathSettings {
        light_selection: LightSelection::All,
        ..s
    };
    let no_roulette = |s: PathSettings| PathSettings {
        russian_roulette: None,
        ..s
    };
    let no_light_tracing = |s: PathSettings| PathSettings {
        light_tracing: None,
        ..s
    };
    let sparse_light_paths = |s: PathSettings| PathSettings {
        light_tracing: s.light_tracing.map(|_| LightTracing::SPARSE),
        ..s
    };
    let path_reuse = |s: PathSettings| PathSettings {
        path_reuse: Some(PathReuse { block: REUSE_BLOCK }),
        light_tracing: None,
        ..s
    };
    // The light selections exclude each other (the pilot keeps the best), so "every trial"
    // takes the first one on, RIS, and the others are tried on their own.
    let switches: [Switch; 7] = [
        (trials.ris, "+ris", &ris),
        (trials.uniform_lights, "+uniform-lights", &uniform_lights),
        (trials.every_light, "+every-light", &every_light),
        (trials.no_roulette, "-roulette", &no_roulette),
        (
            trials.sparse_light_paths,
            "+sparse-light-paths",
            &sparse_light_paths,
        ),
        (trials.no_light_tracing, "-light-tracing", &no_light_tracing),
        (trials.path_reuse, "+path-reuse", &path_reuse),
    ];
    let mut candidates = vec![("auto base".to_string(), base)];
    let mut every = base;
    let mut light_selection_taken = false;
    for (on, label, switch) in switches {
        if on {
            candidates.push((format!("auto base {label}"), switch(base)));
            let selects_lights = ["+ris", "+uniform-lights", "+every-light"].contains(&label);
            if !(selects_lights && light_selection_taken) {
                every = switch(every);
            }
            light_selection_taken |= selects_lights;
        }
    }
    candidates.push(("auto base, every trial".to_string(), every));
    let mut failures = Vec::new();
    for (label, settings) in &candidates {
        let spp = budget.config;
        let replicates = Replicates::render(scene, label, seeds(CONFIG_SEED), spp, |seed| {
            RenderPlan::fixed_spp(
                Transport::Path(*settings),
                candidate_plan.sampler,
                seed,
                spp,
            )
        });
        if let Err(failure) = check_unbiased(name, &replicates, oracle, ALPHA) {
            failures.push(failure);
        }
    }
    let auto_spp = auto.spp;
    let mut choices = Vec::new();
    let end_to_end = Replicates::render_with(
        scene,
        "auto",
        CONFIG_SEED..CONFIG_SEED + AUTO_REPLICATES,
        auto_spp,
        |seed| plan(auto_spp, Some(seed)),
        |output| {
            let pilot = output.auto.as_ref().expect("auto runs its technique pilot");
            assert_eq!(
                pilot.choice.skipped, None,
                "{name}: auto's pilot must run at {auto_spp} spp"
            );
            assert!(output.pilot_spp > 0, "{name}: auto samples adaptively");
            choices.push(pilot.choice.label.clone());
        },
    );
    println!("figure: {name} / auto chose {choices:?}");
    if let Err(failure) = check_unbiased(name, &end_to_end, oracle, ALPHA) {
        failures.push(failure);
    }
    (failures, candidates.len() + 1)
}
