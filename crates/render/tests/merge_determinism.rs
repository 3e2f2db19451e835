//! `strata merge` and reproducibility, end to end: pieces of one render (`--samples`) merged in
//! any order are the single render, byte for byte, for every technique and thread count; merge
//! refuses inputs that do not belong together (the same samples twice, other scenes, settings or
//! sizes, an edited mesh, included file or texture); renders with different seeds pool their
//! samples, and match one full render statistically; and the same scene, seed and spp give
//! byte-identical files whatever the thread count.

mod binary;

use std::path::{Path, PathBuf};

use glam::DVec3;
use render::image::Image;

use binary::{arg, read_exr, read_stats, strata, strata_ok, suite_scene};

/// Renders `scene` to `out` at 22 × 14 pixels (not a multiple of path reuse's 4 × 4 blocks)
/// with `flags`.
fn render_small(scene: &Path, out: &Path, flags: &[&str]) {
    let mut args = vec!["render", arg(scene), "--out", arg(out)];
    args.extend(["--width", "22", "--height", "14"]);
    args.extend(flags);
    strata_ok(&args);
}

/// Runs `strata merge` on `inputs` into `out`.
fn merge(inputs: &[&Path], out: &Path) -> std::process::Output {
    let mut args = vec!["merge"];
    args.extend(inputs.iter().map(|p| arg(p)));
    args.extend(["--out", arg(out)]);
    strata(&args)
}

/// Asserts that `output` exited with status 2 and that its message contains every one of
/// `needles`.
fn assert_refused(output: &std::process::Output, needles: &[&str]) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "no '{needle}' in: {stderr}");
    }
}

/// Small spheres of radiance 1e9 over a floor lit by a dim environment: pixels at the spheres'
/// edges mix samples of about 1e9 with samples below 1e-3, whose `f64` running sum depends on
/// where it is split.
const FIREFLY_SCENE: &str = r#"<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 1, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="22"/><integer name="height" value="14"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="0.001"/></emitter>
    <shape type="sphere"><point name="center" x="-0.5" y="0.3" z="0"/><float name="radius" value="0.07"/>
        <emitter type="area"><rgb name="radiance" value="1e9"/></emitter></shape>
    <shape type="sphere"><point name="center" x="0.6" y="0.5" z="0.5"/><float name="radius" value="0.05"/>
        <emitter type="area"><rgb name="radiance" value="3e9"/></emitter></shape>
    <shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
    </shape>
</scene>
"#;

/// For `auto` with light tracing (the glass box), `mis` with one light path per four samples
/// (the glass box), `auto` with path reuse (the Cornell box),
/// `mis` with a stratified and a Sobol pattern, and [`FIREFLY_SCENE`]: three pieces 0..2, 2..5,
/// 5..7 of a 7-spp render, rendered with 1 or 2 threads, merged in two orders and by merging a
/// merge, are byte for byte the file the single `--spp 7` render writes (itself at 1 or 2
/// threads).
#[test]
fn pieces_merge_into_the_single_render_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let fireflies = dir.path().join("fireflies.xml");
    std::fs::write(&fireflies, FIREFLY_SCENE).unwrap();
    let cases: [(&str, &[&str], Option<&str>); 6] = [
        (
            "cbox-glass.xml",
            &["--integrator", "auto"],
            Some("light-tracing-caustics"),
        ),
        // One light path per four samples: the pieces split the period (0..2, 2..5, 5..7).
        (
            "cbox-glass.xml",
            &["--integrator", "mis", "--light-tracing", "4"],
            Some("light-tracing-caustics-1-per-4"),
        ),
        (
            "cbox.xml",
            &["--integrator", "auto", "--path-reuse", "4"],
            Some("path-reuse-4x4"),
        ),
        (
            "cbox.xml",
            &["--integrator", "mis", "--sampler", "stratified"],
            None,
        ),
        (
            "veach-mis.xml",
            &["--integrator", "mis", "--sampler", "sobol"],
            None,
        ),
        ("fireflies", &["--integrator", "mis"], None),
    ];
    for (case, (scene, flags, technique)) in cases.iter().enumerate() {
        let scene = if *scene == "fireflies" {
            fireflies.clone()
        } else {
            suite_scene(scene)
        };
        let path = |name: &str| dir.path().join(format!("{case}-{name}.exr"));
        let threads = |k: usize| {
            if (case + k).is_multiple_of(2) {
                "1"
            } else {
                "2"
            }
        };
        let common = [&["--seed", "5", "--spp", "7"][..], flags].concat();
        let single = path("single");
        let stats = dir.path().join(format!("{case}.json"));
        let single_flags = [
            &common[..],
            &["--threads", threads(0), "--stats", arg(&stats)],
        ];
        render_small(&scene, &single, &single_flags.concat());
        if let Some(technique) = technique {
            assert!(
                read_stats(&stats).techniques.iter().any(|t| t == technique),
                "case {case} is meant to cover {technique}"
            );
        }
        let pieces: Vec<PathBuf> = ["0..2", "2..5", "5..7"]
            .iter()
            .enumerate()
            .map(|(k, range)| {
                let out = path(&format!("piece{k}"));
                let piece_flags = [
                    &common[..],
                    &["--samples", range, "--threads", threads(k + 1)],
                ];
                render_small(&scene, &out, &piece_flags.concat());
                out
            })
            .collect();
        let single_bytes = std::fs::read(&single).unwrap();
        for (name, order) in [("m1", [2, 0, 1]), ("m2", [1, 2, 0])] {
            let merged = path(name);
            let inputs: Vec<&Path> = order.iter().map(|&i| pieces[i].as_path()).collect();
            let output = merge(&inputs, &merged);
            assert!(
                output.status.success(),
                "{}",
                String::from_utf8_lossy(&output.stderr)
            );
            assert!(
                std::fs::read(&merged).unwrap() == single_bytes,
                "case {case}: pieces merged in the order {order:?} differ from the single render"
            );
        }
        let (head, all) = (path("head"), path("all"));
        assert!(merge(&[&pieces[1], &pieces[0]], &head).status.success());
        assert!(merge(&[&pieces[2], &head], &all).status.success());
        assert!(
            std::fs::read(&all).unwrap() == single_bytes,
            "case {case}: a merge of a merge differs from the single render"
        );
        assert!(
            read_exr(&pieces[0]).0 != read_exr(&single).0,
            "case {case}: a piece must differ from the whole for the test to mean anything"
        );
    }
}

/// `auto` with its technique pilot: every piece of a render chooses as the whole render does,
/// and records what it chose. On the many-lights scene at 64 spp the pilot keeps RIS; a piece
/// `0..2` judged the pilot by its own 2 samples could not pay for it and kept the base, and the
/// pieces' records named the base either way, so the two merged into neither render.
#[test]
fn auto_pieces_choose_as_the_whole_render_and_merge_into_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name);
    let scene = suite_scene("manylights.xml");
    let render = |out: &Path, flags: &[&str]| {
        let mut args = vec!["render", arg(&scene), "--out", arg(out), "-q"];
        args.extend(["--spp", "64", "--seed", "3", "--integrator", "auto"]);
        args.extend(flags);
        strata_ok(&args);
    };
    let (single, stats) = (path("single.exr"), path("single.json"));
    render(&single, &["--adaptive", "off", "--stats", arg(&stats)]);
    let choice = read_stats(&stats).auto_choice.unwrap_or_default();
    assert!(
        choice.ends_with("chose +ris"),
        "the test needs a pilot that keeps a trial: {choice}"
    );
    let (a, b, merged) = (path("a.exr"), path("b.exr"), path("merged.exr"));
    render(&a, &["--samples", "0..2"]);
    render(&b, &["--samples", "2..64"]);
    let record = |file: &Path| {
        let bytes = std::fs::read(file).unwrap();
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let start = text.find("settings: ").expect("a settings record");
        text[start..start + text[start..].find('\n').unwrap()].to_string()
    };
    assert!(record(&a).contains("Ris"), "{}", record(&a));
    assert_eq!(record(&a), record(&single));
    let output = merge(&[&b, &a], &merged);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        std::fs::read(&merged).unwrap() == std::fs::read(&single).unwrap(),
        "the merged pieces differ from the single render"
    );
}

#[test]
fn merge_refuses_what_does_not_belong_together_naming_the_files() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name);
    let cbox = suite_scene("cbox.xml");
    let piece = |name: &str, scene: &Path, flags: &[&str]| {
        let out = path(name);
        let spp = if flags.contains(&"--spp") {
            &[][..]
        } else {
            &["--spp", "8"]
        };
        render_small(scene, &out, &[&["--seed", "2"][..], spp, flags].concat());
        out
    };
    let a = piece("a.exr", &cbox, &["--samples", "0..4"]);
    let out = path("out.exr");
    assert_refused(&merge(&[&a, &a], &out), &["'", "a.exr' is given twice"]);
    let copy = path("copy.exr");
    std::fs::copy(&a, &copy).unwrap();
    assert_refused(
        &merge(&[&a, &copy], &out),
        &["a.exr' and '", "copy.exr' both hold samples 0..4 of seed"],
    );
    let overlapping = piece("overlapping.exr", &cbox, &["--samples", "2..6"]);
    assert_refused(
        &merge(&[&a, &overlapping], &out),
        &["overlapping.exr' both hold samples 2..4"],
    );
    let veach = piece(
        "veach.exr",
        &suite_scene("veach-mis.xml"),
        &["--samples", "4..8"],
    );
    assert_refused(
        &merge(&[&a, &veach], &out),
        &["veach.exr' and '", "a.exr' are renders of different scenes"],
    );
    let nee = piece(
        "nee.exr",
        &cbox,
        &["--samples", "4..8", "--integrator", "nee"],
    );
    assert_refused(
        &merge(&[&a, &nee], &out),
        &["nee.exr' and '", "different settings"],
    );
    let deeper = piece(
        "deeper.exr",
        &cbox,
        &["--samples", "4..8", "--max-depth", "3"],
    );
    assert_refused(
        &merge(&[&a, &deeper], &out),
        &["deeper.exr", "different settings"],
    );
    // A stratified 16-sample pattern is another render than an 8-sample one.
    let stratified = ["--sampler", "stratified"];
    let narrow = piece(
        "narrow.exr",
        &cbox,
        &[&["--samples", "0..4"][..], &stratified].concat(),
    );
    let wider = piece(
        "wider.exr",
        &cbox,
        &[&["--samples", "4..8", "--spp", "16"][..], &stratified].concat(),
    );
    assert_refused(
        &merge(&[&narrow, &wider], &out),
        &["wider.exr", "different settings"],
    );
    let larger = path("larger.exr");
    strata_ok(&[
        "render",
        arg(&cbox),
        "--out",
        arg(&larger),
        "--seed",
        "2",
        "--spp",
        "8",
        "--samples",
        "4..8",
        "--width",
        "22",
        "--height",
        "16",
    ]);
    assert_refused(
        &merge(&[&a, &larger], &out),
        &["larger.exr' is 22x16 pixels but '", "a.exr' is 22x14"],
    );
    let plain = path("plain.exr");
    Image::new(22, 14).write_exr_with_spp(&plain, 4).unwrap();
    assert_refused(
        &merge(&[&a, &plain], &out),
        &["plain.exr", "no \"strata\" header"],
    );
    assert!(!out.exists(), "a refused merge writes nothing");
    // The rest of the render merges (the refusals above are about what differs).
    let b = piece("b.exr", &cbox, &["--samples", "4..8"]);
    assert!(merge(&[&a, &b], &out).status.success());
}

#[test]
fn samples_past_the_render_or_with_a_time_budget_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.exr");
    let scene = suite_scene("cbox.xml");
    let base = [
        "render",
        arg(&scene),
        "--out",
        arg(&out),
        "--width",
        "8",
        "--height",
        "8",
    ];
    let run = |extra: &[&str]| strata(&[&base[..], extra].concat());
    assert_refused(
        &run(&["--samples", "0..32", "--spp", "16"]),
        &["--samples 0..32 goes past --spp 16"],
    );
    assert_refused(
        &run(&["--samples", "0..4", "--time", "1"]),
        &["--samples", "--time"],
    );
    assert_refused(
        &run(&["--samples", "0..4", "--adaptive"]),
        &["--samples", "--adaptive"],
    );
    assert_refused(&run(&["--samples", "4..2"]), &["4..2"]);
    assert!(!out.exists());
}

/// A scene made of a main file, an included file, an OBJ mesh and a PNG texture.
const MAIN_SCENE: &str = r#"<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, -3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <include filename="light.xml"/>
    <shape type="obj">
        <string name="filename" value="quad.obj"/>
        <bsdf type="diffuse">
            <texture type="bitmap" name="reflectance"><string name="filename" value="tex.png"/></texture>
        </bsdf>
    </shape>
</scene>
"#;

const LIGHT: &str = r#"<scene version="3.0.0">
    <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
</scene>
"#;

const QUAD: &str = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";

/// Editing the mesh, the included file or the texture changes the scene's fingerprint, so a
/// piece rendered after the edit does not merge with one rendered before; restored, it does.
#[test]
fn an_edited_mesh_include_or_texture_is_another_scene() {
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str| dir.path().join(name);
    let scene = file("main.xml");
    std::fs::write(&scene, MAIN_SCENE).unwrap();
    let write_inputs = |light: &str, quad: &str, texel: f32| {
        std::fs::write(file("light.xml"), light).unwrap();
        std::fs::write(file("quad.obj"), quad).unwrap();
        Image::from_fn(2, 2, |x, y| {
            glam::Vec3::new(texel, 0.2 * x as f32, 0.3 * y as f32)
        })
        .write_png(&file("tex.png"))
        .unwrap();
    };
    let piece = |name: &str, range: &str| {
        let out = file(name);
        let flags = ["--spp", "4", "--samples", range, "--seed", "1"];
        strata_ok(&[&["render", arg(&scene), "--out", arg(&out)][..], &flags].concat());
        out
    };
    write_inputs(LIGHT, QUAD, 0.5);
    let first = piece("first.exr", "0..2");
    let out = file("out.exr");
    for (name, light, quad, texel) in [
        (
            "mesh.exr",
            LIGHT,
            QUAD.replacen("v 1 1 0", "v 1 1 0.5", 1),
            0.5,
        ),
        (
            "include.exr",
            &LIGHT.replace("1, 1, 1", "1, 1, 2"),
            QUAD.to_string(),
            0.5,
        ),
        ("texture.exr", LIGHT, QUAD.to_string(), 0.75),
    ] {
        write_inputs(light, &quad, texel);
        let edited = piece(name, "2..4");
        assert_refused(
            &merge(&[&first, &edited], &out),
            &[name, "different scenes"],
        );
    }
    write_inputs(LIGHT, QUAD, 0.5);
    let second = piece("second.exr", "2..4");
    let output = merge(&[&first, &second], &out);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Two independent-sampler renders with seeds 1 (4 spp) and 2 (12 spp) merge into the pool of
/// their samples: the header records 16 spp, and each pixel is (4 a + 12 b) / 16 up to `f32`
/// rounding (the Cornell box has no non-finite samples, so every pixel has all its samples).
/// Stratified renders laid out for 4 and 5 samples are different patterns and are refused.
#[test]
fn renders_with_different_seeds_pool_their_samples() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name);
    let scene = suite_scene("cbox.xml");
    let render = |name: &str, seed: &str, spp: &str, sampler: &str| {
        let out = path(name);
        let flags = [
            "--seed",
            seed,
            "--spp",
            spp,
            "--integrator",
            "mis",
            "--sampler",
            sampler,
        ];
        render_small(&scene, &out, &flags);
        out
    };
    let a = render("a.exr", "1", "4", "independent");
    let b = render("b.exr", "2", "12", "independent");
    let m = path("m.exr");
    assert!(merge(&[&b, &a], &m).status.success());
    let ((ia, _), (ib, _), (im, spp)) = (read_exr(&a), read_exr(&b), read_exr(&m));
    assert_eq!(spp, Some(16), "the merged header holds the total");
    for ((pa, pb), pm) in ia.data.iter().zip(&ib.data).zip(&im.data) {
        let expected = (4.0 * pa.as_dvec3() + 12.0 * pb.as_dvec3()) / 16.0;
        let error = (pm.as_dvec3() - expected).abs();
        let bound = expected.abs() * 2e-7 + DVec3::splat(1e-12);
        assert!(
            error.cmple(bound).all(),
            "{pm} is not (4 · {pa} + 12 · {pb}) / 16"
        );
    }
    let four = render("four.exr", "1", "4", "stratified");
    let five = render("five.exr", "3", "5", "stratified");
    assert_refused(
        &merge(&[&four, &five], &m),
        &["five.exr", "different settings"],
    );
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
            "--adaptive",
            "off",
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
