//! Which light next event estimation samples: the preset's choice, `--lights` over it, and
//! `auto`'s pilot measuring the choices only where the user left them open.

mod common;

use common::{load_file, scenes_dir};
use integrators::LightSelection;
use render::plan::{RenderPlan, Transport, plan_from_flags};

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
