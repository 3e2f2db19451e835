//! Shared set-up of the render-level statistical tests: loading scenes at test resolution,
//! rendering in-process, the technique configurations, and per-block z-tests between films.

#![allow(dead_code)] // Each test file uses part of this module.

pub mod compare;

use glam::{UVec2, Vec3};
use integrators::reference::ReferenceSettings;
use integrators::{LightSelection, LightTracing, Mis, PathReuse, PathSettings, RussianRoulette};
use render::driver::{RenderOptions, RenderOutput};
use render::film::Film;
use render::plan::{RenderPlan, Transport};
use render::session::{film_filter, render_scene};
use sampling::sampler::SamplerKind;
use sampling::ztest::{sidak_alpha, two_sided_threshold};
use scene::RenderScene;
use std::path::{Path, PathBuf};

/// The scene suite's folder.
pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

/// The suite's scene files (`scenes/*.xml`), sorted by name.
pub fn suite_scenes() -> Vec<PathBuf> {
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .expect("scenes/ exists")
        .map(|e| e.expect("readable entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    scenes.sort();
    scenes
}

/// Loads `path` with `overrides` of its `<default>` values and the film set to `width × height`.
pub fn load_file(path: &Path, overrides: &[(&str, &str)], width: u32, height: u32) -> RenderScene {
    let overrides: Vec<(String, String)> = overrides
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    let mut desc = scene::parse_file(path, &overrides).unwrap_or_else(|e| panic!("{e}"));
    desc.film = desc.film.resized(width, height);
    scene::build(desc).unwrap_or_else(|e| panic!("{e}"))
}

/// A test version of a scene file: the file with `replacements` of its text (each `(from, to)`
/// must occur in it; every occurrence is replaced), `overrides` of its `<default>` values, the
/// film set to `size × size` and, when given, the integrator's `max_depth` set to `max_depth`.
/// The edited text is loaded from a temporary file beside the original (so that its relative
/// paths still resolve), removed once loaded.
pub fn load_version(
    path: &Path,
    replacements: &[(&str, &str)],
    overrides: &[(&str, &str)],
    size: u32,
    max_depth: Option<i32>,
) -> RenderScene {
    let overrides: Vec<(String, String)> = overrides
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    let mut desc = if replacements.is_empty() {
        scene::parse_file(path, &overrides)
    } else {
        let mut text =
            std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for (from, to) in replacements {
            assert!(
                text.contains(from),
                "{}: `{from}` is not in the file (its test version is out of date)",
                path.display()
            );
            text = text.replace(from, to);
        }
        let dir = path.parent().expect("a scene file has a folder");
        let mut file = tempfile::Builder::new()
            .prefix(".test-version-")
            .suffix(".xml")
            .tempfile_in(dir)
            .expect("temporary scene file");
        std::io::Write::write_all(&mut file, text.as_bytes()).expect("temporary scene file");
        scene::parse_file(file.path(), &overrides)
    }
    .unwrap_or_else(|e| panic!("{e}"));
    desc.film = desc.film.resized(size, size);
    if let Some(depth) = max_depth {
        desc.integrator.max_depth = depth;
    }
    scene::build(desc).unwrap_or_else(|e| panic!("{e}"))
}

/// Writes `xml` to `dir/name.xml` and loads it at `size × size`.
pub fn load_xml(dir: &Path, name: &str, xml: &str, size: u32) -> RenderScene {
    let path = dir.join(format!("{name}.xml"));
    std::fs::write(&path, xml).expect("temporary scene file");
    load_file(&path, &[], size, size)
}

/// Mitsuba's default near clip distance of the perspective camera.
pub const NEAR_CLIP: f32 = 1e-2;

/// A scene file: the path integrator with `max_depth` and `hide_emitters`, a pinhole camera with
/// `to_world` elements `camera`, its field of view (degrees) and near clip distance, a box
/// filter, and `body`. The film's size is the loader's ([`load_xml`], [`load_file`]).
pub fn scene_xml(
    max_depth: i32,
    hide_emitters: bool,
    camera: &str,
    fov: f32,
    near_clip: f32,
    body: &str,
) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="path">
        <integer name="max_depth" value="{max_depth}"/>
        <boolean name="hide_emitters" value="{hide_emitters}"/>
    </integrator>
    <sensor type="perspective">
        <float name="fov" value="{fov}"/>
        <float name="near_clip" value="{near_clip}"/>
        <transform name="to_world">{camera}</transform>
        <film type="hdrfilm"><rfilter type="box"/></film>
    </sensor>
{body}
</scene>
"#
    )
}

/// The scene file's depth as `strata render` reads it.
pub fn max_depth(scene: &RenderScene) -> Option<u32> {
    u32::try_from(scene.desc.integrator.max_depth).ok()
}

/// The reference integrator at the scene's depth.
pub fn reference(scene: &RenderScene) -> Transport {
    Transport::Reference(ReferenceSettings {
        max_depth: max_depth(scene),
        hide_emitters: scene.desc.integrator.hide_emitters,
        direct_samples: None,
        skip_null_vertices: scene.desc.integrator.skip_null_vertices,
    })
}

/// A render of `scene` at `spp` with `seed`; panics (naming `label`) if any sample was NaN or
/// infinite.
pub fn render(
    scene: &RenderScene,
    transport: Transport,
    sampler: SamplerKind,
    spp: u32,
    seed: u32,
    label: &str,
) -> Film {
    render_plan(
        scene,
        &RenderPlan::fixed_spp(transport, sampler, seed, spp),
        label,
    )
    .film
}

/// A render of `scene` as `plan` says; panics (naming `label`) if any sample was NaN or
/// infinite.
pub fn render_plan(scene: &RenderScene, plan: &RenderPlan, label: &str) -> RenderOutput {
    let filter = film_filter(scene.desc.film.filter).expect("valid filter");
    let (output, _) = render_scene(scene, plan, &filter, &RenderOptions::quiet()).expect("renders");
    assert_eq!(
        (output.non_finite.nan, output.non_finite.inf),
        (0, 0),
        "{label}: NaN and infinite samples ({} spp, seed {})",
        output.spp,
        plan.seed
    );
    output
}

/// One technique configuration of the path integrator.
pub struct Configuration {
    /// What it is called in failure messages and figures.
    pub label: &'static str,
    /// The integrator's switches.
    pub settings: PathSettings,
    /// The sampler.
    pub sampler: SamplerKind,
}

/// MIS with the power heuristic and power-proportional light selection, no roulette.
pub fn mis_power(max_depth: Option<u32>, hide_emitters: bool) -> PathSettings {
    PathSettings {
        max_depth,
        hide_emitters,
        sample_lights: true,
        sample_bsdf: true,
        mis: Mis::Power,
        light_selection: LightSelection::Power,
        russian_roulette: None,
        light_tracing: None,
        direct_samples: None,
        skip_null_vertices: false,
        delta_splitting: false,
        path_reuse: None,
    }
}

/// Every switch of the path integrator turned on its own against `base` (MIS, power heuristic,
/// power-proportional selection, independent sampler): BSDF-only, light-only, uniform directions,
/// balance heuristic, uniform, every-light and RIS selection, roulette, and every other sampler
/// ([`SamplerKind::ALL`]).
pub fn configurations(base: PathSettings) -> Vec<Configuration> {
    configurations_with(base, SamplerKind::Independent)
}

/// [`configurations`] with `sampler` as the base's sampler: every switch is rendered with it,
/// and each of the other samplers is a configuration of its own (labelled by its name).
pub fn configurations_with(base: PathSettings, sampler: SamplerKind) -> Vec<Configuration> {
    let mut list = switches(base, sampler);
    for kind in SamplerKind::ALL {
        if kind != sampler {
            list.push(Configuration {
                label: kind.name(),
                settings: base,
                sampler: kind,
            });
        }
    }
    list
}

/// The switches of [`configurations_with`], each with `sampler`.
fn switches(base: PathSettings, sampler: SamplerKind) -> Vec<Configuration> {
    let switch = |label, settings| Configuration {
        label,
        settings,
        sampler,
    };
    vec![
        switch(
            "bsdf-only",
            PathSettings {
                sample_lights: false,
                mis: Mis::Off,
                ..base
            },
        ),
        switch(
            "light-only (nee, no mis)",
            PathSettings {
                mis: Mis::Off,
                ..base
            },
        ),
        switch(
            "nee uniform directions",
            PathSettings {
                sample_bsdf: false,
                mis: Mis::Off,
                ..base
            },
        ),
        switch(
            "mis balance",
            PathSettings {
                mis: Mis::Balance,
                ..base
            },
        ),
        switch("mis power", base),
        switch(
            "mis power uniform selection",
            PathSettings {
                light_selection: LightSelection::Uniform,
                ..base
            },
        ),
        switch(
            "mis power every light",
            PathSettings {
                light_selection: LightSelection::All,
                ..base
            },
        ),
        switch(
            "ris 8",
            PathSettings {
                light_selection: LightSelection::Ris { candidates: 8 },
                ..base
            },
        ),
        switch(
            "roulette from 2",
            PathSettings {
                russian_roulette: Some(RussianRoulette { start_depth: 2 }),
                ..base
            },
        ),
        switch(
            "light tracing",
            PathSettings {
                light_tracing: Some(LightTracing::SPARSE),
                ..base
            },
        ),
        switch(
            "delta splitting",
            PathSettings {
                delta_splitting: true,
                ..base
            },
        ),
        switch(
            "path reuse 4x4",
            PathSettings {
                path_reuse: Some(PathReuse { block: 4 }),
                ..base
            },
        ),
    ]
}

/// The result of a per-block z-test between two films.
#[derive(Clone, Copy, Debug)]
pub struct ZTest {
    /// Fraction of block-channels whose |z| is below the threshold.
    pub pass_fraction: f64,
    /// The largest |z|.
    pub worst_z: f64,
    /// The top-left pixel of the block with the largest |z|.
    pub worst_block: UVec2,
    /// Its channel (0 red, 1 green, 2 blue).
    pub worst_channel: usize,
    /// The Šidák-corrected two-sided threshold on |z|.
    pub threshold: f64,
}

impl std::fmt::Display for ZTest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:.2}% of block-channels pass |z| < {:.2}; worst |z| {:.1} at the block from pixel {} channel {}",
            100.0 * self.pass_fraction,
            self.threshold,
            self.worst_z,
            self.worst_block,
            self.worst_channel
        )
    }
}

/// What a film is z-tested against.
pub enum Target<'a> {
    /// Another film, with its own variance.
    Film(&'a Film),
    /// The exact expected value of each pixel (no variance).
    Exact(&'a dyn Fn(UVec2) -> Vec3),
}

/// Per `block × block` pixels and channel, z = (Σ mean_a − Σ mean_b) / √(Σ var_a + Σ var_b),
/// with each film's unbiased per-pixel variance of the mean (pixels are independent) and a floor
/// for `f32` rounding (1e-5 relative: a path's value goes through dozens of `f32` operations). Blocks rather than pixels because heavy-tailed estimates
/// (a rare hit on a small light) make a block's mean closer to normal. The threshold is two-sided
/// for a family-wise `alpha` with Šidák correction over all block-channels.
pub fn z_test(a: &Film, b: Target<'_>, block: u32, alpha: f64) -> ZTest {
    z_test_with(a, b, block, alpha, false)
}

/// [`z_test`] for a film `a` whose pixels within a block may be correlated (path reuse shares
/// paths between the pixels of its blocks): its block's variance is bounded by (Σ √var_a)²,
/// which holds whatever the correlation, so the test stays valid and only loses power.
pub fn z_test_correlated(a: &Film, b: Target<'_>, block: u32, alpha: f64) -> ZTest {
    z_test_with(a, b, block, alpha, true)
}

/// [`z_test`], with `a`'s block variance bounded as [`z_test_correlated`] says when `correlated`.
fn z_test_with(a: &Film, b: Target<'_>, block: u32, alpha: f64, correlated: bool) -> ZTest {
    let blocks = UVec2::new(a.width() / block, a.height() / block);
    let tests = (blocks.x * blocks.y * 3) as usize;
    let threshold = two_sided_threshold(sidak_alpha(alpha, tests));
    let mut result = ZTest {
        pass_fraction: 0.0,
        worst_z: 0.0,
        worst_block: UVec2::ZERO,
        worst_channel: 0,
        threshold,
    };
    let mut passed = 0usize;
    for by in 0..blocks.y {
        for bx in 0..blocks.x {
            let origin = UVec2::new(bx, by) * block;
            for c in 0..3 {
                let (mut difference, mut variance, mut magnitude) = (0.0, 0.0, 0.0_f64);
                let mut deviation_a = 0.0_f64;
                for dy in 0..block {
                    for dx in 0..block {
                        let pixel = origin + UVec2::new(dx, dy);
                        let (mean_b, var_b) = match &b {
                            Target::Film(b) => {
                                (b.pixel_value(pixel)[c], b.pixel_variance(pixel)[c])
                            }
                            Target::Exact(value) => (value(pixel)[c], 0.0),
                        };
                        difference += f64::from(a.pixel_value(pixel)[c]) - f64::from(mean_b);
                        let var_a = f64::from(a.pixel_variance(pixel)[c]);
                        if correlated {
                            deviation_a += var_a.sqrt();
                            variance += f64::from(var_b);
                        } else {
                            variance += var_a + f64::from(var_b);
                        }
                        magnitude = magnitude.max(f64::from(mean_b).abs());
                    }
                }
                variance += deviation_a * deviation_a;
                let rounding = 1e-5 * magnitude * f64::from(block * block);
                let z = difference.abs() / (variance + rounding * rounding).sqrt().max(1e-30);
                if z <= threshold {
                    passed += 1;
                }
                if z > result.worst_z {
                    (result.worst_z, result.worst_block, result.worst_channel) = (z, origin, c);
                }
            }
        }
    }
    result.pass_fraction = passed as f64 / tests as f64;
    result
}

/// The mean of every pixel and channel of `film`.
pub fn film_mean(film: &Film) -> f64 {
    let mut sum = 0.0;
    for y in 0..film.height() {
        for x in 0..film.width() {
            sum += film.pixel_value(UVec2::new(x, y)).as_dvec3().element_sum();
        }
    }
    sum / f64::from(3 * film.width() * film.height())
}
