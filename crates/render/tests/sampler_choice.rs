//! Which sampler a render uses: the scene file's `<sampler>` mapped to the nearest Strata sampler,
//! unless `--sampler` overrides it; `auto` takes Sobol where the file asks for `independent`,
//! Mitsuba's default, which carries no intent.

use render::plan::plan_from_flags;
use sampling::sampler::SamplerKind;
use std::path::Path;

/// The Cornell box with its `<sampler type="independent">` replaced by `<sampler type="{kind}">`.
fn cornell_box_with_sampler(kind: &str) -> scene::RenderScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/cbox.xml");
    let text = std::fs::read_to_string(&path).expect("the Cornell box is readable");
    let original = r#"<sampler type="independent">"#;
    assert!(
        text.contains(original),
        "cbox.xml names its sampler as expected"
    );
    let text = text.replace(original, &format!(r#"<sampler type="{kind}">"#));
    let desc = scene::parse_bytes(text.as_bytes(), &path, &[]).expect("the edited box parses");
    scene::build(desc).expect("the edited box builds")
}

#[test]
fn scene_samplers_map_to_the_nearest_strata_sampler() {
    for (scene_sampler, expected, auto) in [
        ("independent", SamplerKind::Independent, SamplerKind::Sobol),
        (
            "stratified",
            SamplerKind::Stratified,
            SamplerKind::Stratified,
        ),
        (
            "multijitter",
            SamplerKind::Stratified,
            SamplerKind::Stratified,
        ),
        (
            "orthogonal",
            SamplerKind::Stratified,
            SamplerKind::Stratified,
        ),
        // Mitsuba's ldsampler: a scrambled (0, 2)-sequence with per-dimension index shuffles.
        ("ldsampler", SamplerKind::Sobol, SamplerKind::Sobol),
    ] {
        let scene = cornell_box_with_sampler(scene_sampler);
        let plan = plan_from_flags(&scene, &[]).expect("a plan");
        assert_eq!(
            plan.sampler, auto,
            "auto, <sampler type=\"{scene_sampler}\">"
        );
        for preset in ["mis", "nee", "ris", "reference"] {
            let plan = plan_from_flags(&scene, &["--integrator", preset]).expect("a plan");
            assert_eq!(
                plan.sampler, expected,
                "{preset}, <sampler type=\"{scene_sampler}\">"
            );
        }
        for flags in [
            &["--sampler", "independent"][..],
            &["--integrator", "mis", "--sampler", "independent"],
        ] {
            let overridden = plan_from_flags(&scene, flags).expect("a plan");
            assert_eq!(
                overridden.sampler,
                SamplerKind::Independent,
                "{scene_sampler}: {flags:?}"
            );
        }
    }
}

#[test]
fn auto_samples_adaptively_where_the_budget_pays_for_the_pilot() {
    let scene = cornell_box_with_sampler("independent");
    let adaptive = |flags: &[&str]| plan_from_flags(&scene, flags).expect("a plan").adaptive;
    assert!(adaptive(&["--spp", "32"]));
    assert!(adaptive(&["--time", "1"]));
    assert!(
        !adaptive(&["--spp", "31"]),
        "below 32 spp the pilot costs more than 1/16"
    );
    assert!(!adaptive(&["--spp", "64", "--adaptive", "off"]));
    assert!(adaptive(&["--spp", "8", "--adaptive"]), "asked for");
    assert!(
        !adaptive(&["--spp", "64", "--integrator", "mis"]),
        "presets only when asked"
    );
    assert!(adaptive(&[
        "--spp",
        "64",
        "--integrator",
        "mis",
        "--adaptive",
        "on"
    ]));
}
