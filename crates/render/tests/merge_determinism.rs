//! `strata merge` and reproducibility, end to end: merging is the exact sample-weighted mean;
//! two half renders with different seeds merged match one full render statistically; and the
//! same scene, seed and spp give byte-identical files whatever the thread count.

mod binary;

use glam::DVec3;
use render::image::Image;

use binary::{arg, read_exr, strata, strata_ok, suite_scene};

#[test]
fn merge_is_the_exact_sample_weighted_mean() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b, m) = (
        dir.path().join("a.exr"),
        dir.path().join("b.exr"),
        dir.path().join("m.exr"),
    );
    let scene = suite_scene("cbox.xml");
    let size = ["--width", "12", "--height", "10"];
    for (out, spp, seed) in [(&a, "3", "1"), (&b, "5", "2")] {
        let mut args = vec!["render", arg(&scene), "--out", arg(out), "--spp", spp];
        args.extend(["--seed", seed]);
        args.extend(size);
        strata_ok(&args);
    }
    strata_ok(&["merge", arg(&a), arg(&b), "--out", arg(&m)]);
    let ((ia, _), (ib, _), (im, spp)) = (read_exr(&a), read_exr(&b), read_exr(&m));
    assert_eq!(spp, Some(8), "the merged header holds the total");
    for ((pa, pb), pm) in ia.data.iter().zip(&ib.data).zip(&im.data) {
        let expected = ((3.0 * pa.as_dvec3() + 5.0 * pb.as_dvec3()) / 8.0).as_vec3();
        assert_eq!(*pm, expected);
    }
    let plain = dir.path().join("plain.exr");
    Image::new(12, 10).write_exr(&plain).unwrap();
    let output = strata(&["merge", arg(&a), arg(&plain), "--out", arg(&m)]);
    assert_eq!(output.status.code(), Some(2), "an image without spp");
    assert!(String::from_utf8_lossy(&output.stderr).contains("plain.exr"));
}

/// Per channel: mean over pixels, and mean squared difference from `reference`.
fn mean_and_mse(image: &Image, reference: &Image) -> (DVec3, DVec3) {
    let n = image.data.len() as f64;
    let mut mean = DVec3::ZERO;
    let mut mse = DVec3::ZERO;
    for (p, r) in image.data.iter().zip(&reference.data) {
        let (p, r) = (p.as_dvec3(), r.as_dvec3());
        mean += p / n;
        mse += (p - r) * (p - r) / n;
    }
    (mean, mse)
}

/// A diffuse sphere in a uniform environment: every sample is bounded (at most the
/// environment's radiance), so squared errors are not dominated by rare fireflies.
const SPHERE_SCENE: &str = r#"<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, -3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="1, 0.8, 0.6"/></emitter>
    <shape type="sphere"><bsdf type="diffuse"><rgb name="reflectance" value="0.7"/></bsdf></shape>
</scene>
"#;

/// Two 32-spp halves (seeds 11 and 12) merged against one 64-spp render (seed 13), both measured
/// against a 1024-spp reference (seed 14) of [`SPHERE_SCENE`].
///
/// - Same mean: per channel, z = (mean_merged − mean_full) / sqrt((mse_merged + mse_full) / P)
///   with P pixels (the per-pixel squared errors estimate the per-pixel variances, pixels are
///   independent); |z| < 3.29 (two-sided α = 0.001 per channel, about 0.003 over three).
/// - Comparable error: 2/3 < mse_merged / mse_full < 3/2 per channel. Both estimate the same
///   expected error (equal samples, unbiased, variance ∝ 1/spp); with bounded samples over a
///   few hundred sphere pixels the ratio's relative spread is about 0.1, so the bounds are about
///   four standard deviations away, while halves that repeated each other's samples (seeds that
///   did not decorrelate) would give a ratio near 2.
#[test]
fn merged_halves_have_the_statistics_of_one_full_render() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("sphere.xml");
    std::fs::write(&scene, SPHERE_SCENE).unwrap();
    let path = |name: &str| dir.path().join(name);
    let render = |name: &str, spp: &str, seed: &str| {
        let out = path(name);
        strata_ok(&[
            "render",
            arg(&scene),
            "--out",
            arg(&out),
            "--spp",
            spp,
            "--seed",
            seed,
            "--sampler",
            "independent",
        ]);
        out
    };
    let half_a = render("a.exr", "32", "11");
    let half_b = render("b.exr", "32", "12");
    let full = render("full.exr", "64", "13");
    let reference = render("ref.exr", "1024", "14");
    let merged = path("merged.exr");
    strata_ok(&["merge", arg(&half_a), arg(&half_b), "--out", arg(&merged)]);

    let (reference, _) = read_exr(&reference);
    let ((merged, merged_spp), (full, _)) = (read_exr(&merged), read_exr(&full));
    assert_eq!(merged_spp, Some(64));
    let (mean_m, mse_m) = mean_and_mse(&merged, &reference);
    let (mean_f, mse_f) = mean_and_mse(&full, &reference);
    let pixels = merged.data.len() as f64;
    let z = (mean_m - mean_f) / ((mse_m + mse_f) / pixels).powf(0.5);
    let ratio = mse_m / mse_f;
    let report = format!(
        "seeds 11+12 vs 13, reference 14; means {mean_m} vs {mean_f}, z {z}; mse {mse_m} vs \
         {mse_f}, ratio {ratio}"
    );
    assert!(z.abs().max_element() < 3.29, "means differ: {report}");
    assert!(
        ratio.min_element() > 2.0 / 3.0 && ratio.max_element() < 1.5,
        "errors differ: {report}"
    );
}

#[test]
fn output_is_byte_identical_for_1_2_and_8_threads_and_across_runs() {
    let dir = tempfile::tempdir().unwrap();
    let scene = suite_scene("cbox-glass.xml");
    let render = |name: &str, threads: &str| {
        let out = dir.path().join(name);
        strata_ok(&[
            "render",
            arg(&scene),
            "--out",
            arg(&out),
            "--spp",
            "6",
            "--seed",
            "3",
            "--width",
            "20",
            "--height",
            "16",
            "--threads",
            threads,
        ]);
        std::fs::read(out).unwrap()
    };
    let one = render("t1.exr", "1");
    for (name, threads) in [("t2.exr", "2"), ("t8.exr", "8"), ("t2-again.exr", "2")] {
        assert!(
            render(name, threads) == one,
            "{name} ({threads} threads) differs from the 1-thread render"
        );
    }
}
