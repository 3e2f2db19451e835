//! Which sampler a render uses: the scene file's `<sampler>` mapped to the nearest Strata sampler,
//! unless `--sampler` overrides it.

use render::technique::plan_from_flags;
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
    for (scene_sampler, expected) in [
        ("independent", SamplerKind::Independent),
        ("stratified", SamplerKind::Stratified),
        ("multijitter", SamplerKind::Stratified),
        ("orthogonal", SamplerKind::Stratified),
        // Mitsuba's ldsampler: a scrambled (0, 2)-sequence with per-dimension index shuffles.
        ("ldsampler", SamplerKind::Sobol),
    ] {
        let scene = cornell_box_with_sampler(scene_sampler);
        let plan = plan_from_flags(&scene, &[]).expect("a plan");
        assert_eq!(plan.sampler, expected, "<sampler type=\"{scene_sampler}\">");
        let overridden = plan_from_flags(&scene, &["--sampler", "sobol"]).expect("a plan");
        assert_eq!(overridden.sampler, SamplerKind::Sobol, "{scene_sampler}");
    }
}
