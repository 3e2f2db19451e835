//! The path tracer draws the sampler dimensions its documentation lists, and only those the scene
//! needs: per vertex the light choice (1D) only with more than one light to sample (and not when
//! every light is sampled), the light point (2D),
//! the BSDF lobe (1D) only when some material chooses a lobe (a dielectric), the BSDF direction
//! (2D), and the roulette number (1D) only from roulette's start depth. Every path's sequence of
//! draws must be a prefix of that per-vertex pattern repeated; a path may stop anywhere in it, and
//! `PathIntegrator::sampler_dimensions` (how many dimensions the renderer takes from the sampler's
//! pattern) must count the same draws.

mod common;

use common::{load_file, mis_power, scenes_dir};
use glam::{UVec2, Vec2};
use integrators::{LightSelection, PathIntegrator, RussianRoulette};
use sampling::Sampler;
use sampling::sampler::IndependentSampler;
use world::RayCounters;

/// Where roulette starts in these tests (vertices 1 and 2 draw no roulette number).
const ROULETTE_START: u32 = 3;

/// A sampler that records the width of every draw (1 or 2) and otherwise passes it on.
struct Recording {
    inner: IndependentSampler,
    draws: Vec<u8>,
}

impl Sampler for Recording {
    fn start_pixel_sample(&mut self, pixel: UVec2, sample_index: u32) {
        self.inner.start_pixel_sample(pixel, sample_index);
        self.draws.clear();
    }

    fn next_1d(&mut self) -> f32 {
        self.draws.push(1);
        self.inner.next_1d()
    }

    fn next_2d(&mut self) -> Vec2 {
        self.draws.push(2);
        self.inner.next_2d()
    }
}

/// The draws of vertex `depth` (from 1) as the documentation lists them.
fn vertex_pattern(depth: u32, light_choice: bool, lobe_choice: bool) -> Vec<u8> {
    let mut draws = Vec::new();
    if light_choice {
        draws.push(1);
    }
    draws.push(2);
    if lobe_choice {
        draws.push(1);
    }
    draws.push(2);
    if depth >= ROULETTE_START {
        draws.push(1);
    }
    draws
}

/// Traces 16 × 16 pixels × 4 paths of `name` and checks every path's draws against the pattern;
/// returns the longest sequence seen, so callers can check that roulette was reached.
fn check(name: &str, light_choice: bool, lobe_choice: bool) -> usize {
    check_selecting(name, LightSelection::Power, light_choice, lobe_choice)
}

/// [`check`] with `light_selection`.
fn check_selecting(
    name: &str,
    light_selection: LightSelection,
    light_choice: bool,
    lobe_choice: bool,
) -> usize {
    let scene = load_file(&scenes_dir().join(name), &[], 16, 16);
    let settings = integrators::PathSettings {
        russian_roulette: Some(RussianRoulette {
            start_depth: ROULETTE_START,
        }),
        light_selection,
        ..mis_power(common::max_depth(&scene), false)
    };
    let depth = settings.max_depth.unwrap_or(64);
    let expected: Vec<u8> = (1..=depth)
        .flat_map(|d| vertex_pattern(d, light_choice, lobe_choice))
        .collect();
    let integrator = PathIntegrator::new(&scene.world, settings);
    for vertices in 0..=depth {
        assert_eq!(
            integrator.sampler_dimensions(vertices) as usize,
            draws_through(vertices, light_choice, lobe_choice),
            "{name}: the dimensions the integrator reports for {vertices} vertices"
        );
    }
    let mut longest = 0;
    each_path_draws(&scene, &integrator, 4, |pixel, index, draws| {
        assert!(
            draws.len() <= expected.len() && expected.starts_with(draws),
            "{name}: pixel {pixel}, sample {index} (seed 5) drew {draws:?}, \
             not a prefix of {expected:?}"
        );
        longest = longest.max(draws.len());
    });
    longest
}

/// Traces `samples` paths through the centre of each of the scene's 16 × 16 pixels with
/// independent numbers (seed 5) and hands `visit` each path's pixel, sample index and draws.
fn each_path_draws(
    scene: &scene::RenderScene,
    integrator: &PathIntegrator,
    samples: u32,
    mut visit: impl FnMut(UVec2, u32, &[u8]),
) {
    let mut sampler = Recording {
        inner: IndependentSampler::new(5, 4),
        draws: Vec::new(),
    };
    let mut counters = RayCounters::default();
    let mut slot = world::BsdfSlot::default();
    for y in 0..16 {
        for x in 0..16 {
            for index in 0..samples {
                let pixel = UVec2::new(x, y);
                sampler.start_pixel_sample(pixel, index);
                let ray = scene
                    .camera
                    .generate_ray(pixel.as_vec2() + Vec2::splat(0.5), Vec2::ZERO);
                integrator.radiance(&scene.world, ray, &mut sampler, &mut counters, &mut slot);
                visit(pixel, index, &sampler.draws);
            }
        }
    }
}

/// How many draws a path makes through vertex `depth` if it goes on past it.
fn draws_through(depth: u32, light_choice: bool, lobe_choice: bool) -> usize {
    (1..=depth)
        .map(|d| vertex_pattern(d, light_choice, lobe_choice).len())
        .sum()
}

#[test]
fn one_light_and_no_dielectric_draw_only_the_light_point_and_direction() {
    let longest = check("cbox.xml", false, false);
    assert!(
        longest >= draws_through(ROULETTE_START, false, false),
        "no path of cbox reached roulette"
    );
}

#[test]
fn a_dielectric_adds_the_lobe_number() {
    let longest = check("cbox-glass.xml", false, true);
    assert!(
        longest >= draws_through(ROULETTE_START, false, true),
        "no path of cbox-glass reached roulette"
    );
}

#[test]
fn many_lights_add_the_light_choice_number() {
    // The scene's depth is 3: vertices 1 and 2 draw, vertex 3 only gathers emission.
    let longest = check("manylights.xml", true, false);
    assert_eq!(
        longest,
        draws_through(2, true, false),
        "no path of manylights drew at its second vertex"
    );
}

#[test]
fn sampling_every_light_draws_no_choice_number() {
    let longest = check_selecting("manylights.xml", LightSelection::All, false, false);
    assert_eq!(
        longest,
        draws_through(2, false, false),
        "no path of manylights drew at its second vertex"
    );
}

/// Mitsuba's `direct` integrator with 3 light and 2 BSDF samples, two lights and a dielectric:
/// a camera ray that hits anything draws the light numbers (choice, point) three times, then the
/// BSDF numbers (lobe, direction) twice, and nothing else; one that misses draws nothing.
#[test]
fn direct_sample_counts_repeat_the_first_vertex_draws() {
    let dir = tempfile::tempdir().unwrap();
    let xml = r#"<scene version="3.0.0">
    <integrator type="direct"><integer name="emitter_samples" value="3"/><integer name="bsdf_samples" value="2"/></integrator>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 1, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><rfilter type="box"/></film>
    </sensor>
    <emitter type="point"><point name="position" value="-1, 2, 1"/></emitter>
    <shape type="sphere"><point name="center" value="1, 2, 0"/><float name="radius" value="0.3"/><emitter type="area"/></shape>
    <shape type="sphere"><float name="radius" value="0.5"/><bsdf type="dielectric"/></shape>
    <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><translate y="-0.5"/></transform></shape>
</scene>"#;
    let scene = common::load_xml(dir.path(), "direct", xml, 16);
    let settings = render::plan::plan_from_flags(&scene, &[]).expect("a plan");
    let render::plan::Transport::Path(settings) = settings.transport else {
        panic!("auto plans the path tracer");
    };
    let integrator = PathIntegrator::new(&scene.world, settings);
    let expected: Vec<u8> = [1, 2, 1, 2, 1, 2, 1, 2, 1, 2].into();
    for vertices in 0..4 {
        assert_eq!(
            integrator.sampler_dimensions(vertices) as usize,
            if vertices == 0 { 0 } else { expected.len() },
            "the dimensions the integrator reports for {vertices} vertices"
        );
    }
    let mut hits = 0;
    each_path_draws(&scene, &integrator, 1, |pixel, index, draws| {
        assert!(
            draws.is_empty() || draws == expected,
            "pixel {pixel}, sample {index} (seed 5) drew {draws:?}, not {expected:?} or nothing"
        );
        hits += usize::from(!draws.is_empty());
    });
    assert!(hits > 0, "no camera ray hit the scene");
}
