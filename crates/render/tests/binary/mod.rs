//! Helpers shared by the end-to-end tests that run the `strata` binary (the in-process render
//! helpers are in `common`).

// Each test binary uses a different subset of these helpers.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use render::image::Image;
use render::stats::RenderStats;

/// A scene of the suite, by file name (e.g. `cbox.xml`).
pub fn suite_scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name)
}

/// Path as a `&str` for the command line.
pub fn arg(path: &Path) -> &str {
    path.to_str().expect("UTF-8 path")
}

/// Runs the built `strata` binary with `args` to completion.
pub fn strata(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_strata"))
        .args(args)
        .output()
        .expect("run strata")
}

/// Runs `strata` and panics with its standard error unless it exits with status 0.
pub fn strata_ok(args: &[&str]) {
    let output = strata(args);
    assert_eq!(
        output.status.code(),
        Some(0),
        "strata {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Starts `strata` with `args` in the background, standard error captured.
pub fn spawn_strata(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_strata"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn strata")
}

/// Sends SIGINT (what Ctrl-C sends) to `child`.
pub fn interrupt(child: &Child) {
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("run kill");
    assert!(status.success(), "kill -INT failed");
}

/// Waits for `child` at most `limit`; its exit code (`None` if a signal ended it) and standard
/// error, or an error saying it was still running (it is killed then).
pub fn wait_at_most(mut child: Child, limit: Duration) -> Result<(Option<i32>, String), String> {
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("wait") {
            let mut stderr = String::new();
            use std::io::Read;
            child
                .stderr
                .take()
                .expect("stderr")
                .read_to_string(&mut stderr)
                .expect("read stderr");
            return Ok((status.code(), stderr));
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("strata still running after {limit:?}"));
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The image at `path` and the samples per pixel its header records.
pub fn read_exr(path: &Path) -> (Image, Option<u32>) {
    Image::read_exr_with_spp(path).expect("a readable EXR")
}

/// The stats JSON at `path`.
pub fn read_stats(path: &Path) -> RenderStats {
    serde_json::from_str(&std::fs::read_to_string(path).expect("stats file")).expect("stats JSON")
}
