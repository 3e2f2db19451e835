//! End-to-end tests of the `strata` binary: output format and exit statuses.

use std::path::Path;
use std::process::{Command, Output};

use glam::Vec3;
use render::diff::DiffReport;
use render::image::Image;

/// Runs the built `strata` binary with `args`.
fn strata(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_strata"))
        .args(args)
        .output()
        .unwrap()
}

/// Path as a `&str` for the command line.
fn arg(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn diff_prints_one_json_line_with_the_metrics() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.exr"), dir.path().join("b.exr"));
    Image::from_fn(2, 1, |x, _| Vec3::splat(x as f32 + 1.0))
        .write_exr(&a)
        .unwrap();
    Image::from_fn(2, 1, |_, _| Vec3::splat(1.0))
        .write_exr(&b)
        .unwrap();
    let output = strata(&["diff", arg(&a), arg(&b)]);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    let report: DiffReport = serde_json::from_str(stdout.trim()).unwrap();
    // A = (1, 2) per channel, B = 1: squared differences 0, 0, 0, 1, 1, 1.
    assert!((report.rmse - 0.5f64.sqrt()).abs() < 1e-12);
    assert!((report.relmse - 0.5 / 1.01).abs() < 1e-9);
    assert_eq!((report.mean_a, report.mean_b), (1.5, 1.0));
}

#[test]
fn diff_of_a_missing_file_exits_2_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.exr");
    Image::new(1, 1).write_exr(&a).unwrap();
    let output = strata(&["diff", arg(&a), arg(&dir.path().join("absent.exr"))]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("absent.exr"));
    assert!(output.stdout.is_empty());
}

#[test]
fn bad_flags_exit_2() {
    assert_eq!(
        strata(&["render", "s.xml", "--out", "o.exr", "--time", "-0.5"])
            .status
            .code(),
        Some(2)
    );
    assert_eq!(
        strata(&["render", "s.xml", "--out", "o.exr", "--integrator", "magic"])
            .status
            .code(),
        Some(2)
    );
    assert_eq!(strata(&[]).status.code(), Some(2));
}

#[test]
fn render_of_a_missing_scene_exits_2_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.exr");
    let output = strata(&["render", "no-such-scene.xml", "--out", arg(&out)]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("no-such-scene.xml"));
    assert!(
        !out.exists(),
        "no image may be written for a scene that failed to load"
    );
}

#[test]
fn defines_set_the_scenes_parameters_and_unused_ones_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.xml");
    std::fs::write(
        &scene,
        r#"<scene version="3.0.0">
    <default name="res" value="4"/>
    <default name="sky" value="0.5"/>
    <integrator type="path"/>
    <sensor type="perspective">
        <sampler type="independent"><integer name="sample_count" value="1"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="$res"/><integer name="height" value="3"/>
            <rfilter type="box"/>
        </film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="$sky"/></emitter>
</scene>"#,
    )
    .unwrap();
    let out = dir.path().join("o.exr");
    let output = strata(&[
        "render",
        arg(&scene),
        "--out",
        arg(&out),
        "-D",
        "res=7",
        "-D",
        "sky=0.25",
    ]);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let image = Image::read_exr(&out).unwrap();
    assert_eq!((image.width, image.height), (7, 3));
    // Every camera ray escapes to the sky: every pixel is its radiance exactly (with the box
    // filter; a wider one splats each sample with a random weight, exact only on average).
    assert!(
        image.data.iter().all(|&p| p == Vec3::splat(0.25)),
        "the sky is not the -D value: {:?}",
        image.data
    );

    let other = dir.path().join("other.exr");
    let output = strata(&[
        "render",
        arg(&scene),
        "--out",
        arg(&other),
        "-D",
        "resolution=7",
    ]);
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("resolution=7") && stderr.contains("s.xml"),
        "{stderr}"
    );
    assert!(!other.exists(), "no image for a scene that failed to load");
}
