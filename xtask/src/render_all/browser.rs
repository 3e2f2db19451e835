//! `cargo xtask report-check`: loads `target/report/index.html` in headless Chromium and fails
//! on any image that does not load or decode, any console message and any page error; keeps a
//! screenshot at `target/report/screenshot.png`.
//!
//! How it sees: the page's own script ([`super::report`]'s check script) marks `<body>`, once the
//! page has loaded, with `data-image-check="ok N"` (N images, every one decoded, so
//! `naturalWidth` > 0) or `"broken SRC …"`, and with `data-page-errors` (failed loads and
//! uncaught exceptions it heard); Chromium's `--dump-dom` prints the DOM after the load event,
//! and `--enable-logging=stderr` prints every console message as a `:CONSOLE` line. A missing
//! mark (the script did not run) fails too. Before trusting a pass, the check proves it can
//! fail: on a copy of the report with one image deleted it must name that image, and on a copy
//! whose page logs a console error it must report the message.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Chromium's command, overridden by the `STRATA_CHROMIUM` environment variable.
const CHROMIUM: &str = "chromium";

/// Longest wait for one Chromium run.
const TIMEOUT: Duration = Duration::from_secs(120);

/// Flags of every run: headless, no sandbox (CI runs as root), and none of the background
/// connections that a machine without a network refuses.
const FLAGS: &[&str] = &[
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-extensions",
];

/// The planted console message of the power check.
const PLANTED: &str = "report-check: planted console error";

/// Runs `cargo xtask report-check`.
pub fn report_check(root: &Path, args: &[String]) -> Result<bool, String> {
    if let Some(arg) = args.first() {
        return Err(format!("report-check: unknown argument {arg}"));
    }
    let report = root.join("target/report");
    let page = report.join("index.html");
    if !page.is_file() {
        return Err(format!(
            "{}: no report; run `cargo xtask render-all` first",
            page.display()
        ));
    }
    prove_power(root, &report)?;
    let problems = check_page(root, &page)?;
    let screenshot = report.join("screenshot.png");
    take_screenshot(root, &page, &screenshot)?;
    if problems.is_empty() {
        println!(
            "report-check: {} loads in Chromium without a broken image or console message; \
             screenshot {}",
            page.display(),
            screenshot.display()
        );
        Ok(true)
    } else {
        for problem in &problems {
            eprintln!("report-check: {}: {problem}", page.display());
        }
        Ok(false)
    }
}

/// Fails unless the check catches a deleted image and a console error, each planted in a copy
/// of the report.
fn prove_power(root: &Path, report: &Path) -> Result<(), String> {
    let copy = root.join("target/report-check");
    let page_text = std::fs::read_to_string(report.join("index.html"))
        .map_err(|e| format!("{}: {e}", report.display()))?;
    let victim = first_image(&page_text).ok_or("index.html shows no image")?;
    let result = (|| {
        copy_dir(report, &copy)?;
        let deleted = copy.join(&victim);
        std::fs::remove_file(&deleted).map_err(|e| format!("{}: {e}", deleted.display()))?;
        let problems = check_page(root, &copy.join("index.html"))?;
        if !problems.iter().any(|p| p.contains(&victim)) {
            return Err(format!(
                "with {victim} deleted the browser check saw {problems:?}, not the missing \
                 image: it cannot be trusted"
            ));
        }
        copy_dir(report, &copy)?;
        let planted = page_text.replacen(
            "</body>",
            &format!("<script>console.error('{PLANTED}');</script></body>"),
            1,
        );
        let planted_page = copy.join("index.html");
        std::fs::write(&planted_page, planted)
            .map_err(|e| format!("{}: {e}", planted_page.display()))?;
        let problems = check_page(root, &planted_page)?;
        if !problems.iter().any(|p| p.contains(PLANTED)) {
            return Err(format!(
                "with a console error planted the browser check saw {problems:?}: it cannot be \
                 trusted"
            ));
        }
        Ok(())
    })();
    let _ = std::fs::remove_dir_all(&copy);
    result
}

/// The first `<img src="…">` of `page`.
fn first_image(page: &str) -> Option<String> {
    let start = page.find("<img ")?;
    let rest = &page[start..];
    let src = rest.find("src=\"")? + 5;
    let end = rest[src..].find('"')?;
    Some(rest[src..src + end].to_string())
}

/// Copies `from` into a fresh `to`, recursively.
fn copy_dir(from: &Path, to: &Path) -> Result<(), String> {
    if to.exists() {
        std::fs::remove_dir_all(to).map_err(|e| format!("{}: {e}", to.display()))?;
    }
    std::fs::create_dir_all(to).map_err(|e| format!("{}: {e}", to.display()))?;
    let entries = std::fs::read_dir(from).map_err(|e| format!("{}: {e}", from.display()))?;
    for entry in entries {
        let entry = entry.map_err(|e| format!("{}: {e}", from.display()))?;
        let path = entry.path();
        let target = to.join(entry.file_name());
        if path.is_dir() {
            copy_dir(&path, &target)?;
        } else {
            std::fs::copy(&path, &target).map_err(|e| format!("{}: {e}", path.display()))?;
        }
    }
    Ok(())
}

/// Loads `page` in Chromium and returns what is wrong with it (empty: nothing).
fn check_page(root: &Path, page: &Path) -> Result<Vec<String>, String> {
    let source = std::fs::read_to_string(page).map_err(|e| format!("{}: {e}", page.display()))?;
    let (dom, log) = run_chromium(
        root,
        &["--enable-logging=stderr", "--v=0", "--dump-dom"],
        page,
    )?;
    Ok(problems(&dom, &log, source.matches("<img ").count()))
}

/// What is wrong, from the DOM Chromium dumped after loading a page with `images` `<img>`
/// elements and its log: a missing or failing mark of the page's check script, a count of
/// images other than `images`, page errors, and every console message.
pub fn problems(dom: &str, log: &str, images: usize) -> Vec<String> {
    let mut found = Vec::new();
    match attribute(dom, "data-image-check") {
        None => found.push(
            "the page's check script left no mark (it did not run, or the page did not load)"
                .to_string(),
        ),
        Some(mark) => match mark.strip_prefix("ok ") {
            Some(count) if count == images.to_string() => {}
            Some(count) => found.push(format!("{count} images loaded where the page has {images}")),
            None => found.push(format!(
                "images that did not load: {}",
                mark.trim_start_matches("broken ")
            )),
        },
    }
    match attribute(dom, "data-page-errors").as_deref() {
        Some("0") | None => {}
        Some(n) => found.push(format!("{n} page errors (failed loads or exceptions)")),
    }
    found.extend(
        log.lines()
            .filter(|line| line.contains(":CONSOLE"))
            .map(|line| format!("console message: {}", line.trim())),
    );
    found
}

/// The value of the first `name="…"` attribute in `dom`.
fn attribute(dom: &str, name: &str) -> Option<String> {
    let key = format!("{name}=\"");
    let start = dom.find(&key)? + key.len();
    let end = dom[start..].find('"')?;
    Some(dom[start..start + end].to_string())
}

/// Saves a 1280 × 2000 screenshot of `page` at `out`.
fn take_screenshot(root: &Path, page: &Path, out: &Path) -> Result<(), String> {
    let _ = std::fs::remove_file(out);
    let screenshot = format!("--screenshot={}", out.display());
    run_chromium(root, &[&screenshot, "--window-size=1280,2000"], page)?;
    let size = std::fs::metadata(out).map(|m| m.len()).unwrap_or(0);
    if size == 0 {
        return Err(format!("Chromium wrote no screenshot at {}", out.display()));
    }
    Ok(())
}

/// Runs Chromium with [`FLAGS`], a fresh profile and `args` on `page`; returns its standard
/// output and error. Fails when it cannot start, exits with an error or outlasts [`TIMEOUT`].
fn run_chromium(root: &Path, args: &[&str], page: &Path) -> Result<(String, String), String> {
    let chromium = std::env::var("STRATA_CHROMIUM").unwrap_or_else(|_| CHROMIUM.to_string());
    let profile = root.join(format!(
        "target/report-check-profile-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&profile);
    let page = std::fs::canonicalize(page).map_err(|e| format!("{}: {e}", page.display()))?;
    let out = profile.with_extension("out");
    let err = profile.with_extension("err");
    let file = |path: &PathBuf| {
        std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))
    };
    let mut child = Command::new(&chromium)
        .args(FLAGS)
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .arg(format!("file://{}", page.display()))
        .stdin(Stdio::null())
        .stdout(file(&out)?)
        .stderr(file(&err)?)
        .spawn()
        .map_err(|e| {
            format!(
                "cannot run {chromium}: {e} (install Debian's chromium package, or set \
                 STRATA_CHROMIUM)"
            )
        })?;
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        if start.elapsed() > TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            let _ = std::fs::remove_dir_all(&profile);
            return Err(format!("{chromium} took more than {} s", TIMEOUT.as_secs()));
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let read = |path: &PathBuf| std::fs::read_to_string(path).unwrap_or_default();
    let (stdout, stderr) = (read(&out), read(&err));
    for path in [&out, &err] {
        let _ = std::fs::remove_file(path);
    }
    let _ = std::fs::remove_dir_all(&profile);
    if !status.success() {
        return Err(format!("{chromium} failed ({status}):\n{stderr}"));
    }
    Ok((stdout, stderr))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_page_whose_images_all_loaded_without_messages_passes() {
        let dom = "<body data-image-check=\"ok 3\" data-page-errors=\"0\">";
        let log = "[1:1:1205/084318.951055:ERROR:dbus/bus.cc:405] Failed to connect to the bus";
        assert!(problems(dom, log, 3).is_empty());
    }

    #[test]
    fn broken_images_missing_marks_miscounts_errors_and_console_lines_fail() {
        let broken = "<body data-image-check=\"broken cbox/auto.png\" data-page-errors=\"1\">";
        let found = problems(broken, "", 3);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found[0].contains("cbox/auto.png"));
        assert!(found[1].contains("1 page errors"));
        assert_eq!(problems("<body>", "", 3).len(), 1);
        let miscounted = problems("<body data-image-check=\"ok 2\">", "", 3);
        assert!(miscounted[0].contains("2 images loaded where the page has 3"));
        let log = "[9:9:1205/084319.784196:INFO:CONSOLE:11] \"boom\", source: file:///r.html (11)";
        let found = problems("<body data-image-check=\"ok 3\">", log, 3);
        assert_eq!(found.len(), 1);
        assert!(found[0].contains("boom"));
    }

    #[test]
    fn the_power_check_deletes_the_first_image_shown() {
        let page = "<a href=\"errors.csv\"></a><figure><a href=\"cbox/x.png\">\
                    <img src=\"cbox/x.png\" alt=\"x\"></a><img src=\"cbox/y.png\">";
        assert_eq!(first_image(page).as_deref(), Some("cbox/x.png"));
        assert_eq!(first_image("<p>no images</p>"), None);
    }
}
