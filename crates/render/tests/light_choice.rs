//! Which light next event estimation samples: the preset's choice, `--lights` over it, and
//! `auto`'s pilot measuring the choices only where the user left them open, by the noise of
//! the paths alone.

mod common;

use common::{load_file, load_xml, scenes_dir};
use integrators::LightSelection;
use render::driver::RenderOptions;
use render::plan::{RenderPlan, Transport, plan_from_flags};
use render::session::{film_filter, render_scene};

fn selection(plan: &RenderPlan) -> LightSelection {
    match plan.transport {
        Transport::Path(settings) => settings.light_selection,
        Transport::Reference(_) => panic!("the reference integrator samples no light"),
    }
}

#[test]
fn lights_flag_pins_the_light_choice_and_auto_then_measures_no_other() {
    // Veach's scene: four sphere lights.
    let scene = load_file(&scenes_dir().join("veach-mis.xml"), &[], 32, 24);
    let plan = |flags: &[&str]| plan_from_flags(&scene, flags).unwrap();

    let open = plan(&[]);
    assert_eq!(selection(&open), LightSelection::Power);
    assert!(open.trials.ris && open.trials.uniform_lights && open.trials.every_light);

    for (flag, expected) in [
        ("uniform", LightSelection::Uniform),
        ("power", LightSelection::Power),
        ("ris", LightSelection::Ris { candidates: 4 }),
        ("all", LightSelection::All),
    ] {
        let pinned = plan(&["--lights", flag]);
        assert_eq!(selection(&pinned), expected, "--lights {flag}");
        let trials = pinned.trials;
        assert!(
            !(trials.ris || trials.uniform_lights || trials.every_light),
            "--lights {flag}: auto must not try another light choice: {trials:?}"
        );
        // Over a preset too.
        let preset = plan(&["--integrator", "nee", "--lights", flag]);
        assert_eq!(
            selection(&preset),
            expected,
            "--integrator nee --lights {flag}"
        );
    }
    assert_eq!(
        selection(&plan(&["--integrator", "mis"])),
        LightSelection::Power
    );
    assert!(plan_from_flags(&scene, &["--lights", "some"]).is_err());
}

#[test]
fn the_pilot_measures_the_noise_of_paths_not_of_where_samples_fall() {
    // Two sphere lights seen directly against a black diffuse wall, with Mitsuba's default
    // gaussian filter: a pixel's value depends only on where its camera samples fall (in the
    // pixel, and on the lens of a thin-lens camera focused elsewhere), not on any path, so
    // renders that take the same camera samples agree to the bit. `auto` measures its light
    // choices here (two lights); every candidate must measure no noise at all. Were the two
    // renders of a round to take their own film positions or lens points, the pixels on the
    // lights' blurred edges would differ between them.
    let dir = tempfile::tempdir().unwrap();
    let light = |x: f32, radius: f32, radiance: f32| {
        format!(
            r#"<shape type="sphere"><point name="center" value="{x}, 0, 0"/>
                <float name="radius" value="{radius}"/>
                <emitter type="area"><rgb name="radiance" value="{radiance}"/></emitter></shape>"#
        )
    };
    let lens = r#"<float name="aperture_radius" value="0.2"/>
                  <float name="focus_distance" value="3"/>"#;
    for (sensor, aperture) in [("perspective", ""), ("thinlens", lens)] {
        let xml = format!(
            r#"<scene version="3.0.0">
                <integrator type="path"><integer name="max_depth" value="4"/></integrator>
                <sensor type="{sensor}">
                    <float name="fov" value="40"/>
                    {aperture}
                    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
                    <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="64"/></film>
                </sensor>
                <shape type="rectangle">
                    <transform name="to_world"><scale value="10"/><translate z="-2"/></transform>
                    <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
                </shape>
                {}
                {}
            </scene>"#,
            light(-0.8, 0.5, 4.0),
            light(0.9, 0.3, 20.0)
        );
        let scene = load_xml(dir.path(), sensor, &xml, 64);
        let plan = plan_from_flags(&scene, &["--spp", "256", "--seed", "7"]).unwrap();
        assert!(
            plan.trials.ris && plan.trials.every_light,
            "{sensor}: {:?}",
            plan.trials
        );
        let filter = film_filter(scene.desc.film.filter).unwrap();
        let (output, _) = render_scene(&scene, &plan, &filter, &RenderOptions::quiet()).unwrap();
        let pilot = output.auto.expect("auto ran its pilot");
        assert!(pilot.choice.skipped.is_none(), "{}", pilot.choice.reason());
        for measured in &pilot.choice.measured {
            assert_eq!(
                measured.variance,
                0.0,
                "{sensor}, {}: the pilot measured noise where no path has any (seed 7): {}",
                measured.label,
                pilot.choice.reason()
            );
        }
        // The image itself takes its own camera samples: its lights' edges are not flat.
        let image = output.film.to_image();
        assert!(
            image.data.iter().any(|p| p.x > 0.0 && p.x < 3.0),
            "{sensor}"
        );
    }
}
