//! Interruption and resumption of `strata render`: Ctrl-C (SIGINT) stops at a pass boundary and
//! writes a complete image, its stats and its state; a second Ctrl-C quits without writing;
//! `--resume` continues a saved state to exactly the bits of one uninterrupted render.

mod binary;

use std::time::Duration;

use binary::{
    arg, interrupt, read_exr, read_stats, spawn_strata, strata, strata_ok, suite_scene,
    wait_at_most,
};

/// Longest an interrupted render may take to stop and write (passes last about 1 s).
const STOP_LIMIT: Duration = Duration::from_secs(30);

#[test]
fn ctrl_c_writes_a_complete_image_of_the_samples_done_and_resume_finishes_it_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let (out, stats, state) = (
        dir.path().join("cut.exr"),
        dir.path().join("cut.json"),
        dir.path().join("cut.state"),
    );
    let scene = suite_scene("cbox.xml");
    let common = [
        "--width",
        "24",
        "--height",
        "16",
        "--seed",
        "5",
        "--threads",
        "2",
    ];
    let mut args = vec![
        "render",
        arg(&scene),
        "--out",
        arg(&out),
        "--spp",
        "16777216",
    ];
    args.extend(["--stats", arg(&stats), "--state", arg(&state)]);
    args.extend(common);
    let child = spawn_strata(&args);
    std::thread::sleep(Duration::from_millis(1500));
    interrupt(&child);
    let (status, stderr) = wait_at_most(child, STOP_LIMIT).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status, Some(130), "interrupted renders exit 130: {stderr}");
    assert!(stderr.contains("interrupted: wrote"), "{stderr}");

    let (image, spp) = read_exr(&out);
    let spp = spp.expect("the EXR header records the samples per pixel");
    assert!((1..16_777_216).contains(&spp), "{spp} spp");
    assert_eq!((image.width, image.height), (24, 16));
    assert!(image.data.iter().all(|p| p.is_finite()));
    let stats = read_stats(&stats);
    assert!(stats.interrupted);
    assert_eq!(stats.spp, spp, "stats and header agree");

    // Resume to a few more samples than were done; compare with one render of that many.
    let total = (spp + 3).to_string();
    let (resumed, whole) = (dir.path().join("resumed.exr"), dir.path().join("whole.exr"));
    let mut resume_args = vec![
        "render",
        arg(&scene),
        "--out",
        arg(&resumed),
        "--spp",
        &total,
    ];
    resume_args.extend(["--resume", arg(&state)]);
    resume_args.extend(common);
    strata_ok(&resume_args);
    // A saved render keeps `auto`'s base techniques and samples every pixel alike; so does the
    // whole render that saves its state.
    let whole_state = dir.path().join("whole.state");
    let mut whole_args = vec!["render", arg(&scene), "--out", arg(&whole), "--spp", &total];
    whole_args.extend(["--state", arg(&whole_state)]);
    whole_args.extend(common);
    strata_ok(&whole_args);
    assert_eq!(
        std::fs::read(&resumed).unwrap(),
        std::fs::read(&whole).unwrap(),
        "{spp} spp interrupted + resumed to {total} must equal {total} in one go"
    );
}

#[test]
fn a_second_ctrl_c_quits_at_once_without_writing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("never.exr");
    let scene = suite_scene("cbox.xml");
    // One sample per pixel of 2048² on one thread takes seconds, so both signals arrive
    // during the first pass, which an interrupted render always finishes.
    let child = spawn_strata(&[
        "render",
        arg(&scene),
        "--out",
        arg(&out),
        "--spp",
        "64",
        "--width",
        "2048",
        "--height",
        "2048",
        "--threads",
        "1",
    ]);
    std::thread::sleep(Duration::from_millis(500));
    interrupt(&child);
    std::thread::sleep(Duration::from_millis(200));
    interrupt(&child);
    let (status, stderr) =
        wait_at_most(child, Duration::from_secs(5)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(status, Some(130), "{stderr}");
    assert!(!out.exists(), "the second Ctrl-C must not write the image");
}

#[test]
fn a_time_budget_records_the_samples_done() {
    let dir = tempfile::tempdir().unwrap();
    let (out, stats) = (dir.path().join("t.exr"), dir.path().join("t.json"));
    let scene = suite_scene("cbox.xml");
    strata_ok(&[
        "render",
        arg(&scene),
        "--out",
        arg(&out),
        "--time",
        "0.3",
        "--width",
        "16",
        "--height",
        "16",
        "--stats",
        arg(&stats),
    ]);
    let stats = read_stats(&stats);
    assert!(stats.spp >= 1 && !stats.interrupted);
    // The header counts the samples in the image; the stats count an adaptive pilot's too.
    assert_eq!(read_exr(&out).1, Some(stats.spp - stats.pilot_spp));
}

#[test]
fn resume_refuses_another_scene_or_other_settings() {
    let dir = tempfile::tempdir().unwrap();
    let (out, state) = (dir.path().join("a.exr"), dir.path().join("a.state"));
    let (cbox, glass) = (suite_scene("cbox.xml"), suite_scene("cbox-glass.xml"));
    let size = ["--width", "8", "--height", "8"];
    let mut args = vec!["render", arg(&cbox), "--out", arg(&out), "--spp", "2"];
    args.extend(["--state", arg(&state)]);
    args.extend(size);
    strata_ok(&args);
    for (scene, extra, expected) in [
        (&glass, &[][..], "different scene"),
        (&cbox, &["--seed", "9"][..], "other settings"),
        (&cbox, &["--integrator", "reference"][..], "other settings"),
    ] {
        let mut args = vec!["render", arg(scene), "--out", arg(&out), "--spp", "4"];
        args.extend(["--resume", arg(&state)]);
        args.extend(size);
        args.extend(extra);
        let output = strata(&args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{extra:?}: {stderr}");
        assert!(
            stderr.contains(expected) && stderr.contains("a.state"),
            "{stderr}"
        );
    }
}

#[test]
fn resume_follows_the_mesh_files_not_the_scene_files_place() {
    let dir = tempfile::tempdir().unwrap();
    let scene_xml = r#"<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <emitter type="constant"/>
    <shape type="obj"><string name="filename" value="quad.obj"/></shape>
</scene>"#;
    let quad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n";
    let (first, moved) = (dir.path().join("first"), dir.path().join("moved"));
    for folder in [&first, &moved] {
        std::fs::create_dir(folder).unwrap();
        std::fs::write(folder.join("scene.xml"), scene_xml).unwrap();
        std::fs::write(folder.join("quad.obj"), quad).unwrap();
    }
    let (out, state) = (dir.path().join("a.exr"), dir.path().join("a.state"));
    let render = |folder: &std::path::Path, spp: &str, state_flag: &str| {
        strata(&[
            "render",
            arg(&folder.join("scene.xml")),
            "--out",
            arg(&out),
            "--spp",
            spp,
            state_flag,
            arg(&state),
        ])
    };
    assert_eq!(render(&first, "2", "--state").status.code(), Some(0));
    // The same content elsewhere continues.
    let resumed = render(&moved, "4", "--resume");
    assert_eq!(
        resumed.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    // One vertex of the mesh moved: the saved samples are of another scene.
    let changed = quad.replace("v 1 1 0", "v 1 1 0.5");
    std::fs::write(moved.join("quad.obj"), changed).unwrap();
    let refused = render(&moved, "4", "--resume");
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("different scene") && stderr.contains("a.state"),
        "{stderr}"
    );
}

/// With light tracing (`auto` on the glass box) the saved state holds the light paths' splats
/// too, and their sums are exact, so a render saved at 2 samples per pixel and resumed to 5 (its
/// passes split the samples differently from one render's, so splats reach a pixel in another
/// order) ends with the same film sums, to the bit, and the same image as one render of 5.
#[test]
fn resuming_a_light_traced_render_gives_the_same_bits_as_one_render() {
    let dir = tempfile::tempdir().unwrap();
    let glass = suite_scene("cbox-glass.xml");
    let file = |name: &str| dir.path().join(name);
    let render = |spp: &str, extra: &[&str]| {
        let mut args = vec!["render", arg(&glass), "--spp", spp];
        args.extend(["--width", "16", "--height", "16"]);
        args.extend(extra);
        strata_ok(&args);
    };
    let path = |name: &str| file(name).to_str().expect("UTF-8 path").to_string();
    let (whole, whole_state, stats) = (path("whole.exr"), path("whole.state"), path("s.json"));
    let (part, part_state) = (path("part.exr"), path("part.state"));
    render(
        "5",
        &["--out", &whole, "--state", &whole_state, "--stats", &stats],
    );
    assert!(
        read_stats(&file("s.json"))
            .techniques
            .iter()
            .any(|t| t.contains("light-tracing")),
        "auto traces light paths on the glass box"
    );
    render("2", &["--out", &part, "--state", &part_state]);
    render(
        "5",
        &[
            "--out",
            &part,
            "--resume",
            &part_state,
            "--state",
            &part_state,
        ],
    );
    let film = |name: &str| {
        render::state::RenderState::read(&file(name))
            .unwrap_or_else(|e| panic!("{e}"))
            .film
    };
    let bits = |name: &str| {
        read_exr(&file(name))
            .0
            .data
            .iter()
            .flat_map(|p| p.to_array().map(f32::to_bits))
            .collect::<Vec<_>>()
    };
    assert!(film("whole.state").light_paths() > 0);
    assert!(
        film("part.state") == film("whole.state"),
        "the resumed film's sums differ from one render's"
    );
    assert_eq!(bits("part.exr"), bits("whole.exr"));
}
