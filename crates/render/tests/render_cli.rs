//! End-to-end tests of what `strata render` says and where it writes: the summary line on
//! standard error and `--quiet`, the default output path, `-o` and `-t`, `path` as another name
//! for `auto`, and `--exposure` for PNG previews (also in `strata merge`).

mod binary;

use std::path::Path;
use std::process::{Command, Output};

use binary::{arg, read_exr, read_stats, strata, suite_scene};

/// The suite's Cornell box (a path the binary can read from any working directory).
const CBOX: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/cbox.xml");

/// `strata render` of the Cornell box at 24 × 16 pixels (not square, so width and height cannot
/// be swapped unnoticed), seed 3, with `extra` flags.
fn cbox_args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let base = [
        "render", CBOX, "--width", "24", "--height", "16", "--seed", "3",
    ];
    [&base[..], extra].concat()
}

/// Runs `strata` with `args` in the working directory `dir`.
fn strata_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_strata"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run strata")
}

/// Standard error of `output`, after checking that it exited with status 0.
fn stderr_of_success(output: &Output) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    stderr
}

/// The fields of a summary line, parsed without the program's help.
#[derive(Debug)]
struct Summary {
    path: String,
    width: u32,
    height: u32,
    spp: u32,
    seconds: f64,
    rays_per_second: f64,
    preset: String,
    techniques: Vec<String>,
}

/// Panics: `line` is not a summary line.
fn not_a_summary<T>(line: &str) -> T {
    panic!("not a summary line: {line:?}")
}

/// `text` parsed as a `T`, or a panic naming `line`.
fn number<T: std::str::FromStr>(text: &str, line: &str) -> T {
    text.parse().unwrap_or_else(|_| not_a_summary(line))
}

/// Parses `OUT: W×H, N spp, S s, R [k|M|G|T ]rays/s, PRESET: T1+T2+…`.
fn parse_summary(line: &str) -> Summary {
    let (path, rest) = line.split_once(": ").unwrap_or_else(|| not_a_summary(line));
    let parts: Vec<&str> = rest.split(", ").collect();
    let [size, spp, seconds, rate, choice] = parts[..] else {
        return not_a_summary(line);
    };
    let (width, height) = size.split_once('×').unwrap_or_else(|| not_a_summary(line));
    let spp = spp
        .strip_suffix(" spp")
        .unwrap_or_else(|| not_a_summary(line));
    let seconds = seconds
        .strip_suffix(" s")
        .unwrap_or_else(|| not_a_summary(line));
    let rate = rate
        .strip_suffix(" rays/s")
        .unwrap_or_else(|| not_a_summary(line));
    let rays_per_second = match rate.split_once(' ') {
        None => number(rate, line),
        Some((value, prefix)) => {
            let scale = match prefix {
                "k" => 1e3,
                "M" => 1e6,
                "G" => 1e9,
                "T" => 1e12,
                _ => not_a_summary(line),
            };
            number::<f64>(value, line) * scale
        }
    };
    let (preset, techniques) = choice
        .split_once(": ")
        .unwrap_or_else(|| not_a_summary(line));
    Summary {
        path: path.to_string(),
        width: number(width, line),
        height: number(height, line),
        spp: number(spp, line),
        seconds: number(seconds, line),
        rays_per_second,
        preset: preset.to_string(),
        techniques: techniques.split('+').map(str::to_string).collect(),
    }
}

/// The one line of `stderr` (standard error is not a terminal here, so no progress bar).
fn only_line(stderr: &str) -> &str {
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 1, "one summary line expected: {stderr:?}");
    lines[0]
}

#[test]
fn the_summary_line_reports_the_image_written_and_the_rays_of_the_stats() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra) in [
        ("fixed", &["--spp", "8"][..]),
        // Adaptive sampling: the mean spp, pilot included, as the stats record it.
        ("adaptive", &["--spp", "40", "--adaptive"][..]),
    ] {
        let out = dir.path().join(format!("{name}.exr"));
        let stats = dir.path().join(format!("{name}.json"));
        let args = cbox_args(&[&["-o", arg(&out), "--stats", arg(&stats)][..], extra].concat());
        let stderr = stderr_of_success(&strata(&args));
        let summary = parse_summary(only_line(&stderr));
        let (image, header_spp) = read_exr(&out);
        let stats = read_stats(&stats);

        assert_eq!(summary.path, out.display().to_string());
        assert_eq!((summary.width, summary.height), (24, 16));
        assert_eq!((summary.width, summary.height), (image.width, image.height));
        assert_eq!(summary.spp, stats.spp, "{name}");
        // The header counts the image's samples; the summary, like the stats, the pilot's too.
        assert_eq!(Some(summary.spp - stats.pilot_spp), header_spp, "{name}");
        assert_eq!(summary.preset, "auto");
        assert_eq!(summary.techniques, stats.techniques);
        assert_eq!(
            summary.techniques.contains(&"adaptive".to_string()),
            name == "adaptive"
        );
        assert!(
            (summary.seconds - stats.seconds).abs() <= 0.005 + 1e-9,
            "{summary:?} {stats:?}"
        );
        // Three significant digits: within 0.5% of every ray traced (shadow rays included) per
        // second of rendering.
        assert!(stats.shadow_rays > 0 && stats.rays > 0, "{stats:?}");
        let all = (stats.rays + stats.shadow_rays) as f64 / stats.seconds;
        let closest_hit_only = stats.rays as f64 / stats.seconds;
        assert!(
            (summary.rays_per_second / all - 1.0).abs() <= 0.005,
            "{summary:?}: {all} rays/s"
        );
        assert!(
            (summary.rays_per_second / closest_hit_only - 1.0).abs() > 0.005,
            "the shadow rays are not counted: {summary:?}"
        );
    }
    // Fixed samples: exactly those asked for.
    assert_eq!(read_exr(&dir.path().join("fixed.exr")).1, Some(8));
}

#[test]
fn quiet_renders_say_nothing() {
    let dir = tempfile::tempdir().unwrap();
    for quiet in ["--quiet", "-q"] {
        let out = dir.path().join(format!("{quiet}.exr"));
        let output = strata(&cbox_args(&["--spp", "2", "--out", arg(&out), quiet]));
        assert_eq!(stderr_of_success(&output), "", "{quiet}");
        assert!(output.stdout.is_empty());
        assert_eq!(read_exr(&out).1, Some(2), "{quiet} still writes the image");
    }
}

#[test]
fn without_out_the_image_is_the_scenes_name_in_the_working_directory() {
    let dir = tempfile::tempdir().unwrap();
    let stderr = stderr_of_success(&strata_in(dir.path(), &cbox_args(&["--spp", "2"])));
    let written = dir.path().join("cbox.exr");
    assert_eq!(read_exr(&written).1, Some(2));
    assert_eq!(parse_summary(only_line(&stderr)).path, "cbox.exr");
    let files: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(files.len(), 1, "only the image: {files:?}");
    assert!(
        !suite_scene("cbox.exr").exists(),
        "nothing is written beside the scene"
    );
}

#[test]
fn the_scene_file_is_never_written_over() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read(suite_scene("cbox.xml")).unwrap();
    // A scene file whose default output name is its own name.
    let odd = dir.path().join("box.exr");
    std::fs::write(&odd, &text).unwrap();
    let scene = dir.path().join("box.xml");
    std::fs::write(&scene, &text).unwrap();
    for (args, named) in [
        (vec!["render", "box.exr", "--spp", "1"], "box.exr"),
        (
            vec!["render", "box.xml", "--spp", "1", "-o", "box.xml"],
            "box.xml",
        ),
        (
            vec![
                "render",
                "box.xml",
                "--spp",
                "1",
                "-o",
                "o.exr",
                "--png",
                "./box.xml",
            ],
            "box.xml",
        ),
    ] {
        let output = strata_in(dir.path(), &args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains("is the scene file") && stderr.contains(named),
            "{args:?}: {stderr}"
        );
    }
    assert_eq!(std::fs::read(&odd).unwrap(), text);
    assert_eq!(std::fs::read(&scene).unwrap(), text);
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        2,
        "nothing written"
    );
}

#[test]
fn short_out_and_threads_flags_work_and_threads_do_not_change_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let mut images = Vec::new();
    for threads in ["1", "2"] {
        let out = dir.path().join(format!("t{threads}.exr"));
        let stats = dir.path().join(format!("t{threads}.json"));
        let output = strata(&cbox_args(&[
            "--spp",
            "4",
            "-o",
            arg(&out),
            "-t",
            threads,
            "--stats",
            arg(&stats),
        ]));
        stderr_of_success(&output);
        assert_eq!(read_stats(&stats).threads.to_string(), threads);
        images.push(read_exr(&out));
    }
    assert_eq!(images[0], images[1]);
}

#[test]
fn path_is_auto_by_another_name() {
    let dir = tempfile::tempdir().unwrap();
    let render = |preset: &str| {
        let out = dir.path().join(format!("{preset}.exr"));
        let output = strata(&cbox_args(&[
            "--spp",
            "4",
            "-o",
            arg(&out),
            "--integrator",
            preset,
        ]));
        let stderr = stderr_of_success(&output);
        (read_exr(&out), parse_summary(only_line(&stderr)))
    };
    let (path_image, path_summary) = render("path");
    let (auto_image, auto_summary) = render("auto");
    let (mis_image, _) = render("mis");
    assert_eq!(path_image, auto_image, "same bits");
    assert_eq!(path_summary.preset, "auto");
    assert_eq!(path_summary.techniques, auto_summary.techniques);
    // The comparison can tell presets apart: `mis` (no path reuse here) gives other bits.
    assert_ne!(mis_image, auto_image);
}

/// The 8-bit RGB codes of the PNG at `path`.
fn png_codes(path: &Path) -> Vec<u8> {
    let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
    let mut reader = png::Decoder::new(file).read_info().unwrap();
    let mut buffer = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buffer).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buffer.truncate(info.buffer_size());
    buffer
}

/// The linear value an sRGB code stands for (IEC 61966-2-1's decoding), code `c` as `c / 255`.
fn srgb_decode(code: f64) -> f64 {
    let v = code / 255.0;
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// The linear interval an 8-bit code was rounded from.
fn linear_interval(code: u8) -> (f64, f64) {
    let c = f64::from(code);
    (srgb_decode((c - 0.5).max(0.0)), srgb_decode(c + 0.5))
}

/// How many codes of `bright` lie where `ratio` × the linear values behind `dark` would be
/// encoded, within 8-bit rounding; and how many pairs were comparable (neither clipped).
fn codes_in_ratio(dark: &[u8], bright: &[u8], ratio: f64) -> (usize, usize) {
    let mut comparable = 0;
    let mut agreeing = 0;
    for (&d, &b) in dark.iter().zip(bright) {
        if d == 0 || d == 255 || b == 255 {
            continue;
        }
        comparable += 1;
        let (d_low, d_high) = linear_interval(d);
        let (b_low, b_high) = linear_interval(b);
        if ratio * d_low <= b_high && b_low <= ratio * d_high {
            agreeing += 1;
        }
    }
    (agreeing, comparable)
}

#[test]
fn exposure_brightens_png_previews_by_powers_of_two_and_leaves_the_exr_alone() {
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str| dir.path().join(name);
    for (stops, name) in [("0", "e0"), ("1", "e1")] {
        let output = strata(&cbox_args(&[
            "--spp",
            "16",
            "-o",
            arg(&file(&format!("{name}.exr"))),
            "--png",
            arg(&file(&format!("{name}.png"))),
            "--exposure",
            stops,
        ]));
        stderr_of_success(&output);
    }
    assert_eq!(
        read_exr(&file("e0.exr")),
        read_exr(&file("e1.exr")),
        "EXR unaffected"
    );
    let (e0, e1) = (png_codes(&file("e0.png")), png_codes(&file("e1.png")));
    let (agreeing, comparable) = codes_in_ratio(&e0, &e1, 2.0);
    assert!(
        comparable > e0.len() / 2,
        "{comparable} of {} comparable",
        e0.len()
    );
    assert_eq!(agreeing, comparable, "exposure 1 is twice the linear value");
    // The check has power: a ratio of 1.5 or 2.5 does not fit these codes.
    for wrong in [1.5, 2.5] {
        let (agreeing, comparable) = codes_in_ratio(&e0, &e1, wrong);
        assert!(
            agreeing < comparable / 2,
            "ratio {wrong}: {agreeing} of {comparable}"
        );
    }

    // `strata merge` of the one render gives its image, with the exposure asked for.
    let output = strata(&[
        "merge",
        arg(&file("e0.exr")),
        "--out",
        arg(&file("m.exr")),
        "--png",
        arg(&file("m.png")),
        "--exposure",
        "1",
    ]);
    stderr_of_success(&output);
    assert_eq!(png_codes(&file("m.png")), e1);
}

#[test]
fn exposures_that_are_not_finite_exit_2_without_writing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.exr");
    let png = dir.path().join("o.png");
    for bad in ["nan", "inf", "-inf", "1e40", "bright"] {
        let output = strata(&cbox_args(&[
            "--spp",
            "1",
            "-o",
            arg(&out),
            "--png",
            arg(&png),
            "--exposure",
            bad,
        ]));
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{bad}: {stderr}");
        assert!(
            stderr.contains("--exposure") && stderr.contains(bad),
            "{bad}: {stderr}"
        );
        let merge = strata(&["merge", "a.exr", "--out", arg(&out), "--exposure", bad]);
        let stderr = String::from_utf8_lossy(&merge.stderr);
        assert_eq!(merge.status.code(), Some(2), "merge {bad}: {stderr}");
        assert!(stderr.contains("--exposure"), "merge {bad}: {stderr}");
    }
    assert!(!out.exists() && !png.exists());
}
