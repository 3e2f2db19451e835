//! Scenes render pixel for pixel the same far from the world's origin and at extreme scales.
//!
//! Every scene of the suite, and two with thin features — the Cornell box's light 0.002 (0.1% of
//! the box) below its ceiling, and two boxes 1e-3 apart, each seen up close — is rewritten as a
//! Mitsuba file translated by 1e5 and by 1e6 along (1, 1, 1), and scaled by 1e-4 and by 1e4 about
//! the world's origin, camera included ([`placed_xml`]: every shape's `to_world` gets the
//! placement appended, each keyframe's for a moving shape; the camera's `lookat` points move,
//! its clip and focus distances and lens scale; point lights move and their intensity scales by
//! the square of the scale). The loader reads the rewritten file as it would read a user's, and
//! the image must not change.
//!
//! The comparison is paired. Seed `s` renders the scene and its placed copy with the same random
//! numbers, so their difference is zero except where rounding sends a path another way; per
//! block of 4 × 4 pixels and channel the difference of the two images' block sums, and the
//! difference of their whole-image sums, is t-tested over [`SEEDS`] seeds, whose differences are
//! independent: Student's t with `SEEDS − 1` degrees of freedom, the variance of the difference
//! estimated from the seeds. Rounding differs between placements deterministically, so the
//! standard error has a floor of [`ROUNDING`] of the block's magnitude. Each scene is one family
//! at α = 0.01 with Šidák correction over its 4 × (64 × 3 + 1) tests per technique, and every test
//! must pass. The variance comes from seeds, not pixels, so it holds for path reuse too, whose
//! pixels share paths.
//!
//! Techniques: MIS with the power heuristic everywhere; also path reuse on the Cornell box and
//! the thin light (`auto`'s choice there), and light tracing on the glass box (its choice for
//! caustics), so that every kind of spawned ray is placed: bounces, shadow rays, connections
//! between pixels, rays leaving lights and connections to the camera.
//!
//! The test sees what it is for: it fails a render with one 4 × 4 region × 1.05, one whose whole
//! image is × 1.005, and the thin light lowered by 0.004 (the largest error of a world-space `f32`
//! vertex 1e5 from the origin), each against the unchanged render with the same seeds. Before
//! positions were made camera-relative in double precision and offsets came from error bounds,
//! every suite scene but the furnace and the thin lens failed translated, and every one failed
//! scaled by 1e-4.

mod common;

use std::ops::Range;
use std::path::Path;

use common::{mis_power, render, scenes_dir, suite_scenes};
use glam::{DVec3, UVec2};
use integrators::{LightTracing, PathReuse, PathSettings};
use render::plan::Transport;
use roxmltree::Node;
use sampling::sampler::SamplerKind;
use sampling::ztest::{sidak_alpha, student_t_two_sided_p_value};
use scene::RenderScene;

/// Image side, pixels.
const SIZE: u32 = 32;
/// Samples per pixel of each render.
const SPP: u32 = 8;
/// Seeds per scene: the repetitions the variance of a difference is estimated from.
const SEEDS: u32 = 16;
/// Edge of the pixel blocks tested.
const BLOCK: u32 = 4;
/// Family-wise level per scene.
const ALPHA: f64 = 0.01;
/// Floor on the standard error of a difference, relative to the block's (or image's) mean sum of
/// absolute values: a path's value goes through dozens of `f32` operations whose rounding
/// differs between placements of the same scene, the same way for every seed.
const ROUNDING: f64 = 1e-5;

/// Where a placed copy of a scene lies: `x → scale · x + offset · (1, 1, 1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Placement {
    scale: f64,
    offset: f64,
}

/// The four placements every scene is tested at.
const PLACEMENTS: [Placement; 4] = [
    Placement {
        scale: 1.0,
        offset: 1e5,
    },
    Placement {
        scale: 1.0,
        offset: 1e6,
    },
    Placement {
        scale: 1e-4,
        offset: 0.0,
    },
    Placement {
        scale: 1e4,
        offset: 0.0,
    },
];

impl Placement {
    fn point(self, p: DVec3) -> DVec3 {
        p * self.scale + DVec3::splat(self.offset)
    }

    /// The transform elements that follow a `to_world` to place what it places.
    fn elements(self) -> String {
        format!(
            r#"<scale value="{s}"/><translate x="{t}" y="{t}" z="{t}"/>"#,
            s = self.scale,
            t = self.offset
        )
    }
}

impl std::fmt::Display for Placement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.scale == 1.0 {
            write!(f, "translated by {:e}", self.offset)
        } else {
            write!(f, "scaled by {:e}", self.scale)
        }
    }
}

/// A replacement of `range` of a file's text.
type Edit = (Range<usize>, String);

/// `text` with `edits` (non-overlapping ranges) applied.
fn edited(text: &str, mut edits: Vec<Edit>) -> String {
    edits.sort_by_key(|(range, _)| std::cmp::Reverse(range.start));
    let mut text = text.to_string();
    for (range, replacement) in edits {
        text.replace_range(range, &replacement);
    }
    text
}

/// The numbers of a Mitsuba list value (`"1, 2, 3"` or `"1 2 3"`).
fn numbers(value: &str) -> Vec<f64> {
    value
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse()
                .unwrap_or_else(|_| panic!("\"{value}\" is not a list of numbers"))
        })
        .collect()
}

fn point_value(p: DVec3) -> String {
    format!("{}, {}, {}", p.x, p.y, p.z)
}

/// A `<point>` element's value, given as `value` or as `x`, `y`, `z`.
fn point_of(node: Node) -> DVec3 {
    match node.attribute("value") {
        Some(value) => DVec3::from_slice(&numbers(value)),
        None => DVec3::from_array(
            ["x", "y", "z"].map(|a| node.attribute(a).map_or(0.0, |v| numbers(v)[0])),
        ),
    }
}

/// The element child of `node` named `name` by its `name` attribute.
fn named<'a, 'i>(node: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    node.children()
        .find(|c| c.is_element() && c.attribute("name") == Some(name))
}

/// The edit that makes `node`'s `to_world` place it by `placement`: the placement's elements
/// appended to its transform (to each keyframe's, where it moves), or a transform of them alone
/// where it has none.
fn to_world_edit(text: &str, node: Node, placement: Placement) -> Edit {
    match named(node, "to_world") {
        Some(animation) if animation.has_tag_name("animation") => {
            let keyframes: String = animation
                .children()
                .filter(Node::is_element)
                .map(|keyframe| {
                    let time = keyframe.attribute("time").expect("a keyframe has a time");
                    let own: String = keyframe
                        .children()
                        .filter(Node::is_element)
                        .map(|c| &text[c.range()])
                        .collect();
                    format!(
                        r#"<transform time="{time}">{own}{}</transform>"#,
                        placement.elements()
                    )
                })
                .collect();
            (
                animation.range(),
                format!(r#"<animation name="to_world">{keyframes}</animation>"#),
            )
        }
        Some(to_world) => {
            let own: String = to_world
                .children()
                .filter(Node::is_element)
                .map(|c| &text[c.range()])
                .collect();
            (
                to_world.range(),
                format!(
                    r#"<transform name="to_world">{own}{}</transform>"#,
                    placement.elements()
                ),
            )
        }
        None => {
            let start = node
                .first_child()
                .unwrap_or_else(|| {
                    panic!(
                        "the generator needs <{}> with children",
                        node.tag_name().name()
                    )
                })
                .range()
                .start;
            (
                start..start,
                format!(
                    r#"<transform name="to_world">{}</transform>"#,
                    placement.elements()
                ),
            )
        }
    }
}

/// The edits that place the sensor `node`: its `lookat` points moved; its clip and focus
/// distances and aperture scaled (the clip distances' defaults written out scaled).
fn sensor_edits(node: Node, placement: Placement) -> Vec<Edit> {
    let to_world = named(node, "to_world").expect("the generator needs the sensor's to_world");
    let elements: Vec<Node> = to_world.children().filter(Node::is_element).collect();
    let [lookat] = elements.as_slice() else {
        panic!("the generator needs a sensor placed by one <lookat>");
    };
    assert!(
        lookat.has_tag_name("lookat"),
        "the generator needs a <lookat> sensor"
    );
    let moved = |name: &str| {
        let value = lookat
            .attribute(name)
            .expect("lookat has origin and target");
        point_value(placement.point(DVec3::from_slice(&numbers(value))))
    };
    let up = lookat
        .attribute("up")
        .map_or(String::new(), |up| format!(r#" up="{up}""#));
    let mut edits = vec![(
        lookat.range(),
        format!(
            r#"<lookat origin="{}" target="{}"{up}/>"#,
            moved("origin"),
            moved("target")
        ),
    )];
    let first = node
        .first_child()
        .expect("the sensor has children")
        .range()
        .start;
    for (name, default) in [
        ("near_clip", Some(1e-2)),
        ("far_clip", Some(1e4)),
        ("focus_distance", None),
        ("aperture_radius", None),
    ] {
        match named(node, name) {
            Some(element) => {
                let value = numbers(element.attribute("value").expect("a float value"))[0];
                edits.push((
                    element.range(),
                    format!(
                        r#"<float name="{name}" value="{}"/>"#,
                        value * placement.scale
                    ),
                ));
            }
            None => {
                if let Some(value) = default {
                    edits.push((
                        first..first,
                        format!(
                            r#"<float name="{name}" value="{}"/>"#,
                            value * placement.scale
                        ),
                    ));
                }
            }
        }
    }
    edits
}

/// The edits that place the top-level emitter `node`: a point light moved, its intensity scaled
/// by the square of the scale (its irradiance falls with the square of the distance); lights at
/// infinity and environments unchanged.
fn emitter_edits(text: &str, node: Node, placement: Placement) -> Vec<Edit> {
    match node.attribute("type") {
        Some("constant" | "envmap" | "directional") => Vec::new(),
        Some("point") => {
            let mut edits = Vec::new();
            match named(node, "position") {
                Some(position) => edits.push((
                    position.range(),
                    format!(
                        r#"<point name="position" value="{}"/>"#,
                        point_value(placement.point(point_of(position)))
                    ),
                )),
                None => edits.push(to_world_edit(text, node, placement)),
            }
            let intensity = named(node, "intensity").expect("the generator needs an intensity");
            let value = numbers(intensity.attribute("value").expect("an intensity value"));
            let scaled: Vec<String> = value
                .iter()
                .map(|v| (v * placement.scale * placement.scale).to_string())
                .collect();
            edits.push((
                intensity.range(),
                format!(
                    r#"<{tag} name="intensity" value="{}"/>"#,
                    scaled.join(", "),
                    tag = intensity.tag_name().name()
                ),
            ));
            edits
        }
        other => panic!("the generator does not place {other:?} emitters"),
    }
}

/// The scene file `text` with everything in it placed by `placement`.
fn placed_xml(text: &str, placement: Placement) -> String {
    let document = roxmltree::Document::parse(text).expect("a scene file is XML");
    let mut edits = Vec::new();
    for node in document.root_element().children().filter(Node::is_element) {
        match node.tag_name().name() {
            // A shape group is placed by its instances.
            "shape" if node.attribute("type") == Some("shapegroup") => {}
            "shape" => edits.push(to_world_edit(text, node, placement)),
            "sensor" => edits.extend(sensor_edits(node, placement)),
            "emitter" => edits.extend(emitter_edits(text, node, placement)),
            "bsdf" | "integrator" | "default" | "texture" => {}
            other => panic!("the generator does not place <{other}>"),
        }
    }
    edited(text, edits)
}

/// `text` with the element `id` (anywhere) replaced by `replacement`.
fn with_element_replaced(text: &str, id: &str, replacement: &str) -> String {
    let document = roxmltree::Document::parse(text).expect("a scene file is XML");
    let node = document
        .descendants()
        .find(|n| n.attribute("id") == Some(id))
        .unwrap_or_else(|| panic!("no element {id}"));
    edited(text, vec![(node.range(), replacement.to_string())])
}

/// `text` with its sensor's `lookat` and field of view replaced.
fn with_camera(text: &str, lookat: &str, fov: f64) -> String {
    let document = roxmltree::Document::parse(text).expect("a scene file is XML");
    let sensor = document
        .root_element()
        .children()
        .find(|n| n.has_tag_name("sensor"))
        .expect("a sensor");
    let fov_element = named(sensor, "fov").expect("a field of view");
    let lookat_element = sensor
        .descendants()
        .find(|n| n.has_tag_name("lookat"))
        .expect("a lookat");
    edited(
        text,
        vec![
            (
                fov_element.range(),
                format!(r#"<float name="fov" value="{fov}"/>"#),
            ),
            (lookat_element.range(), lookat.to_string()),
        ],
    )
}

fn cbox_text() -> String {
    std::fs::read_to_string(scenes_dir().join("cbox.xml")).expect("scenes/cbox.xml")
}

/// The Cornell box with its light `below` under the ceiling (the suite's is 0.01 below), seen up
/// close from below and in front: the light's back edge, the ceiling behind it and the gap
/// between them (about a pixel at 0.002).
fn thin_light_xml(below: f64) -> String {
    let text = cbox_text();
    let light = format!(
        r#"<shape type="rectangle" id="light">
        <transform name="to_world">
            <scale x="0.23" y="0.19" z="0.19"/>
            <rotate x="1" angle="90"/>
            <translate x="0" y="{}" z="0.01"/>
        </transform>
        <ref id="white"/>
        <emitter type="area">
            <rgb name="radiance" value="18.387, 13.9873, 6.75357"/>
        </emitter>
    </shape>"#,
        1.0 - below
    );
    let text = with_element_replaced(&text, "light", &light);
    with_camera(
        &text,
        r#"<lookat origin="0.05, 0.6, 1.0" target="0.05, 0.998, -0.18" up="0, 1, 0"/>"#,
        3.0,
    )
}

/// The Cornell box with two boxes side by side 1e-3 apart in place of its small box, seen up
/// close from the front: the slot between them (about a pixel wide), lit from above.
fn thin_gap_xml() -> String {
    let text = cbox_text();
    let boxes = [-1.0, 1.0].map(|side: f64| {
        format!(
            r#"<shape type="cube">
        <transform name="to_world">
            <scale x="0.2" y="0.3" z="0.2"/>
            <translate x="{}" y="-0.7" z="0.2"/>
        </transform>
        <ref id="white"/>
    </shape>"#,
            side * 0.2005
        )
    });
    let text = with_element_replaced(&text, "small_box", &boxes.join("\n    "));
    with_camera(
        &text,
        r#"<lookat origin="0, -0.55, 1.6" target="0, -0.7, 0.4" up="0, 1, 0"/>"#,
        1.2,
    )
}

/// Linear RGB per pixel, row by row.
type Image = Vec<DVec3>;

/// Loads the scene file `text` as if read from `path` (whose folder holds its meshes), at the
/// test's resolution.
fn load(path: &Path, text: &str) -> RenderScene {
    let mut desc = scene::parse_bytes(text.as_bytes(), path, &[]).unwrap_or_else(|e| {
        panic!("{e}\n{text}");
    });
    desc.film = desc.film.resized(SIZE, SIZE);
    scene::build(desc).unwrap_or_else(|e| panic!("{e}"))
}

/// A technique configuration on top of MIS with the power heuristic at the scene's depth.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Technique {
    /// MIS alone.
    Mis,
    /// With path reuse in 4 × 4 blocks (which `auto` turns on for the Cornell box): the pixels
    /// of a block share paths, which the test allows for, since it takes variances from seeds.
    PathReuse,
    /// With light tracing (which `auto` turns on for caustics): rays leave the lights' surfaces
    /// and connect to the camera.
    LightTracing,
}

/// One render per seed `1..=SEEDS` with `technique`.
fn renders_with(scene: &RenderScene, technique: Technique, label: &str) -> Vec<Image> {
    let mis = PathSettings {
        skip_null_vertices: scene.desc.integrator.skip_null_vertices,
        ..mis_power(
            common::max_depth(scene),
            scene.desc.integrator.hide_emitters,
        )
    };
    let settings = match technique {
        Technique::Mis => mis,
        Technique::PathReuse => PathSettings {
            path_reuse: Some(PathReuse { block: 4 }),
            ..mis
        },
        Technique::LightTracing => PathSettings {
            light_tracing: Some(LightTracing::SPARSE),
            ..mis
        },
    };
    (1..=SEEDS)
        .map(|seed| {
            let film = render(
                scene,
                Transport::Path(settings),
                SamplerKind::Independent,
                SPP,
                seed,
                label,
            );
            (0..SIZE * SIZE)
                .map(|i| film.pixel_value(UVec2::new(i % SIZE, i / SIZE)).as_dvec3())
                .collect()
        })
        .collect()
}

/// [`renders_with`] MIS alone.
fn renders(scene: &RenderScene, label: &str) -> Vec<Image> {
    renders_with(scene, Technique::Mis, label)
}

/// One paired test: its name and p-value.
struct Outcome {
    what: String,
    p: f64,
}

/// The paired t-test of the sums over `pixels` (channel `channel`, or all three for `None`) of
/// `moved` against `base`, seed by seed.
fn paired(
    base: &[Image],
    moved: &[Image],
    pixels: &[usize],
    channel: Option<usize>,
    what: String,
) -> Outcome {
    let sum = |image: &Image, f: &dyn Fn(f64) -> f64| -> f64 {
        pixels
            .iter()
            .map(|&i| match channel {
                Some(c) => f(image[i][c]),
                None => image[i].to_array().map(f).iter().sum(),
            })
            .sum()
    };
    let n = base.len() as f64;
    let differences: Vec<f64> = base
        .iter()
        .zip(moved)
        .map(|(b, m)| sum(m, &|v| v) - sum(b, &|v| v))
        .collect();
    let magnitude = base.iter().map(|b| sum(b, &f64::abs)).sum::<f64>() / n;
    let mean = differences.iter().sum::<f64>() / n;
    let variance = differences.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let standard_error = (variance / n + (ROUNDING * magnitude).powi(2)).sqrt();
    let t = if mean == 0.0 {
        0.0
    } else {
        mean / standard_error
    };
    let p = student_t_two_sided_p_value(t, base.len() as u32 - 1);
    let relative = if magnitude > 0.0 {
        mean / magnitude
    } else {
        0.0
    };
    Outcome {
        what: format!(
            "{what}: mean difference {mean:.3e} ({:+.3}%), t = {t:.1}",
            100.0 * relative
        ),
        p,
    }
}

/// Every block-channel test and the image-mean test of `moved` against `base`.
fn outcomes(base: &[Image], moved: &[Image], label: &str) -> Vec<Outcome> {
    let blocks = SIZE / BLOCK;
    let mut outcomes = Vec::new();
    for by in 0..blocks {
        for bx in 0..blocks {
            let pixels: Vec<usize> = (0..BLOCK * BLOCK)
                .map(|i| ((by * BLOCK + i / BLOCK) * SIZE + bx * BLOCK + i % BLOCK) as usize)
                .collect();
            for c in 0..3 {
                let what = format!(
                    "{label}, block from pixel ({}, {}) channel {c}",
                    bx * BLOCK,
                    by * BLOCK
                );
                outcomes.push(paired(base, moved, &pixels, Some(c), what));
            }
        }
    }
    let all: Vec<usize> = (0..(SIZE * SIZE) as usize).collect();
    outcomes.push(paired(
        base,
        moved,
        &all,
        None,
        format!("{label}, image mean"),
    ));
    outcomes
}

/// The number of tests in one scene's family per technique: per placement, every block-channel
/// and the image mean.
const FAMILY: usize = PLACEMENTS.len() * ((SIZE / BLOCK) * (SIZE / BLOCK) * 3 + 1) as usize;

/// The tests that fail at family-wise [`ALPHA`] with Šidák correction over `family` tests,
/// worst first (`outcomes` sorted so).
fn failures(outcomes: &mut [Outcome], family: usize) -> Vec<String> {
    let each = sidak_alpha(ALPHA, family);
    outcomes.sort_by(|a, b| a.p.total_cmp(&b.p));
    outcomes
        .iter()
        .filter(|o| o.p < each)
        .map(|o| format!("{} (p = {:.2e} < {each:.2e})", o.what, o.p))
        .collect()
}

/// Renders the scene file `text` (read as if from `path`) and its copies at every placement with
/// MIS and with the `extra` techniques, and asserts that each copy renders like the scene with
/// the same technique. One family per scene: [`FAMILY`] tests per technique.
fn check(name: &str, path: &Path, text: &str, extra: &[Technique]) {
    let scene = load(path, text);
    let placed: Vec<(Placement, RenderScene)> = PLACEMENTS
        .iter()
        .map(|&placement| (placement, load(path, &placed_xml(text, placement))))
        .collect();
    let techniques: Vec<Technique> = [Technique::Mis].iter().chain(extra).copied().collect();
    let family = FAMILY * techniques.len();
    let mut all = Vec::new();
    for technique in techniques {
        let base = renders_with(&scene, technique, name);
        for (placement, moved) in &placed {
            let label = format!("{name} {technique:?} {placement}");
            let moved = renders_with(moved, technique, &label);
            let mut these = outcomes(&base, &moved, &label);
            let failed = failures(&mut these, family);
            println!(
                "figure: {label}: {} of {} tests fail, smallest p {:.2e} ({})",
                failed.len(),
                these.len(),
                these[0].p,
                these[0].what
            );
            all.extend(these);
        }
    }
    let tests = all.len();
    assert_eq!(tests, family);
    let failed = failures(&mut all, family);
    println!(
        "figure: {name}: {} of {tests} paired tests fail; smallest p {:.2e} ({})",
        failed.len(),
        all[0].p,
        all[0].what
    );
    assert!(
        failed.is_empty(),
        "{name} ({SIZE}x{SIZE}, {SPP} spp, seeds 1..={SEEDS}, {BLOCK}x{BLOCK} blocks): {} of {tests} \
         tests fail:\n{}",
        failed.len(),
        failed
            .iter()
            .take(12)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// [`check`] for the suite's scene `file`.
fn check_suite(file: &str, extra: &[Technique]) {
    let path = scenes_dir().join(file);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{file}: {e}"));
    check(file, &path, &text, extra);
}

/// The suite scenes the tests below cover, which must be all of them.
const SUITE: [&str; 11] = [
    "cbox-glass.xml",
    "cbox-mesh.xml",
    "cbox-smalllight.xml",
    "cbox.xml",
    "furnace.xml",
    "manylights.xml",
    "motion.xml",
    "pointlight.xml",
    "softshadow.xml",
    "thinlens.xml",
    "veach-mis.xml",
];

#[test]
fn every_suite_scene_is_covered() {
    let names: Vec<String> = suite_scenes()
        .iter()
        .map(|p| {
            p.file_name()
                .expect("a file")
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    assert_eq!(
        names, SUITE,
        "add the new scene to SUITE and give it a test"
    );
}

#[test]
fn cbox() {
    check_suite("cbox.xml", &[Technique::PathReuse]);
}

#[test]
fn cbox_glass() {
    check_suite("cbox-glass.xml", &[Technique::LightTracing]);
}

#[test]
fn cbox_mesh() {
    check_suite("cbox-mesh.xml", &[]);
}

#[test]
fn cbox_smalllight() {
    check_suite("cbox-smalllight.xml", &[]);
}

#[test]
fn furnace() {
    check_suite("furnace.xml", &[]);
}

#[test]
fn manylights() {
    check_suite("manylights.xml", &[]);
}

/// Moving boxes: their keyframes are placed, the rays go into their own space at their time.
#[test]
fn motion() {
    check_suite("motion.xml", &[]);
}

#[test]
fn pointlight() {
    check_suite("pointlight.xml", &[]);
}

#[test]
fn softshadow() {
    check_suite("softshadow.xml", &[]);
}

#[test]
fn thinlens() {
    check_suite("thinlens.xml", &[]);
}

#[test]
fn veach_mis() {
    check_suite("veach-mis.xml", &[]);
}

#[test]
fn light_just_below_the_ceiling() {
    check(
        "thin light",
        &scenes_dir().join("cbox.xml"),
        &thin_light_xml(0.002),
        &[Technique::PathReuse],
    );
}

#[test]
fn boxes_a_thousandth_apart() {
    check(
        "thin gap",
        &scenes_dir().join("cbox.xml"),
        &thin_gap_xml(),
        &[],
    );
}

/// The rewritten file places what the loader reads as the placement says: the camera, every
/// shape and the point light, with its intensity.
#[test]
fn the_generator_places_every_position() {
    let placement = Placement {
        scale: 1e-4,
        offset: 1e5,
    };
    let text = std::fs::read_to_string(scenes_dir().join("pointlight.xml")).expect("readable");
    let placed = placed_xml(&text, placement);
    let (path, overrides) = (scenes_dir().join("pointlight.xml"), []);
    let before = scene::parse_bytes(text.as_bytes(), &path, &overrides).expect("loads");
    let after = scene::parse_bytes(placed.as_bytes(), &path, &overrides).expect("loads");
    // Positions relative to the camera scale; the camera moves.
    assert!((after.sensor.position - placement.point(before.sensor.position)).length() < 1e-9);
    assert_eq!(after.sensor.to_world, before.sensor.to_world);
    assert_eq!(after.sensor.near_clip, (1e-2 * placement.scale) as f32);
    for (a, b) in after.shapes.iter().zip(&before.shapes) {
        match (&a.geometry, &b.geometry) {
            (scene::Geometry::Mesh(a), scene::Geometry::Mesh(b)) => {
                for (p, q) in a.positions.iter().zip(&b.positions) {
                    let expected = q.as_dvec3() * placement.scale;
                    assert!((p.as_dvec3() - expected).length() < 1e-6 * placement.scale);
                }
            }
            (scene::Geometry::Sphere(a), scene::Geometry::Sphere(b)) => {
                let expected = b.center.as_dvec3() * placement.scale;
                assert!((a.center.as_dvec3() - expected).length() < 1e-6 * placement.scale);
                assert!((f64::from(a.radius) / f64::from(b.radius) - placement.scale).abs() < 1e-9);
            }
            _ => panic!("shapes changed kind"),
        }
    }
    let point = |desc: &scene::SceneDesc| match desc.emitters[0] {
        scene::EmitterDesc::Point {
            position,
            intensity,
            ..
        } => (position.as_dvec3(), intensity.as_dvec3()),
        _ => panic!("pointlight.xml's first emitter is its point light"),
    };
    let ((p_after, i_after), (p_before, i_before)) = (point(&after), point(&before));
    assert!((p_after - p_before * placement.scale).length() < 1e-6 * placement.scale);
    assert!(
        (i_after / i_before - DVec3::splat(1e-8))
            .abs()
            .max_element()
            < 1e-14
    );
}

/// The films of one scene with seeds `1..=SEEDS`, and a copy of them changed by `change`.
fn changed(base: &[Image], change: impl Fn(usize, DVec3) -> DVec3) -> Vec<Image> {
    base.iter()
        .map(|image| {
            image
                .iter()
                .enumerate()
                .map(|(i, &v)| change(i, v))
                .collect()
        })
        .collect()
}

#[test]
fn fails_one_region_five_percent_too_bright() {
    let path = scenes_dir().join("cbox.xml");
    let base = renders(&load(&path, &cbox_text()), "cbox");
    // The 4 × 4 pixels from (14, 10), across four blocks: the back wall.
    let region = |i: usize| {
        let (x, y) = (i as u32 % SIZE, i as u32 / SIZE);
        (14..18).contains(&x) && (10..14).contains(&y)
    };
    let biased = changed(&base, |i, v| if region(i) { v * 1.05 } else { v });
    let mut all = outcomes(&base, &biased, "cbox with a region × 1.05");
    let failed = failures(&mut all, FAMILY);
    println!(
        "figure: region × 1.05: {} tests fail; worst {}",
        failed.len(),
        all[0].what
    );
    assert!(
        !failed.is_empty(),
        "a region × 1.05 passes: {}",
        all[0].what
    );
}

#[test]
fn fails_an_image_half_a_percent_too_bright() {
    let path = scenes_dir().join("cbox.xml");
    let base = renders(&load(&path, &cbox_text()), "cbox");
    let biased = changed(&base, |_, v| v * 1.005);
    let mut all = outcomes(&base, &biased, "cbox × 1.005");
    let failed = failures(&mut all, FAMILY);
    println!(
        "figure: image × 1.005: {} tests fail; worst {}",
        failed.len(),
        all[0].what
    );
    assert!(
        !failed.is_empty(),
        "an image × 1.005 passes: {}",
        all[0].what
    );
}

#[test]
fn fails_the_light_moved_by_a_world_space_rounding_error() {
    let path = scenes_dir().join("cbox.xml");
    let base = renders(&load(&path, &thin_light_xml(0.002)), "thin light");
    let lowered = renders(&load(&path, &thin_light_xml(0.006)), "thin light, lowered");
    let mut all = outcomes(&base, &lowered, "thin light lowered by 0.004");
    let failed = failures(&mut all, FAMILY);
    println!(
        "figure: light lowered by 0.004: {} tests fail; worst {}",
        failed.len(),
        all[0].what
    );
    assert!(
        !failed.is_empty(),
        "the lowered light passes: {}",
        all[0].what
    );
}
