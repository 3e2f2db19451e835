//! Recording a render's rays must not change the render: same image bits, and one recorded ray
//! per counted ray.

use render::driver::RenderOptions;
use render::plan::plan_from_flags;
use render::session::{film_filter, render_scene, render_scene_recording};
use std::path::Path;

#[test]
fn recording_render_gives_the_same_image_and_logs_every_counted_ray() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/cbox.xml");
    let overrides = [("res", "24"), ("spp", "3")].map(|(k, v)| (k.to_string(), v.to_string()));
    let scene = scene::load(&path, &overrides).expect("the Cornell box loads");
    let filter = film_filter(scene.desc.film.filter).expect("its filter");
    for sampler in ["independent", "stratified"] {
        let plan = plan_from_flags(&scene, &["--seed", "5", "--sampler", sampler]).expect("a plan");
        let (plain, counters) =
            render_scene(&scene, &plan, &filter, &RenderOptions::quiet()).expect("renders");
        let (recorded, log) =
            render_scene_recording(&scene, &plan, &filter, &RenderOptions::quiet())
                .expect("renders while recording");
        assert_eq!(plain.film, recorded.film, "{sampler}: images differ");
        assert_eq!(log.counters, counters, "{sampler}");
        assert_eq!(log.closest.len() as u64, counters.rays, "{sampler}");
        assert_eq!(log.shadow.len() as u64, counters.shadow_rays, "{sampler}");
        // Every pixel sample starts with a camera ray, and the lit box casts shadow rays.
        assert!(counters.rays >= 24 * 24 * 3, "{sampler}: {counters:?}");
        assert!(counters.shadow_rays > 0, "{sampler}: {counters:?}");
    }
}
