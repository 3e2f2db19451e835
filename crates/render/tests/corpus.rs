//! Replays the hostile-input corpus `tests/corpus/` through the `strata` binary, case by case as
//! `tests/corpus/MANIFEST` says: rejected inputs exit with status 2 and a message naming the
//! file, line and element; legal ones render a complete image. No case may panic, run past
//! [`TIME_LIMIT`] or need more than [`ADDRESS_SPACE_KIB`] of address space.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;

mod binary;

use binary::wait_at_most;
use render::image::Image;

/// Longest a case may run (debug builds included) before it counts as a hang.
const TIME_LIMIT: Duration = Duration::from_secs(60);

/// Address-space limit of each case (`ulimit -v`, KiB): an allocation the input does not
/// justify fails under it instead of exhausting the machine.
const ADDRESS_SPACE_KIB: u64 = 4 << 20;

/// What a case must do.
#[derive(Debug, PartialEq)]
enum Expect {
    /// Exit status 2, standard error containing every text.
    Reject(Vec<String>),
    /// Exit status 0 and a complete image at `{out}`.
    Render,
}

/// One line of the manifest.
#[derive(Debug)]
struct Case {
    line: usize,
    args: Vec<String>,
    expect: Expect,
}

fn corpus_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/corpus")
}

fn read_manifest() -> Vec<Case> {
    let text = std::fs::read_to_string(corpus_dir().join("MANIFEST")).expect("MANIFEST");
    let mut cases = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let line_no = index + 1;
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(" | ").map(str::trim).collect();
        let args = fields[1].split_whitespace().map(str::to_string).collect();
        let expect = match (fields[0], fields.get(2)) {
            ("reject", Some(texts)) => {
                Expect::Reject(texts.split(" ; ").map(|t| t.trim().to_string()).collect())
            }
            ("render", None) => Expect::Render,
            other => panic!("MANIFEST line {line_no}: bad case {other:?}"),
        };
        cases.push(Case {
            line: line_no,
            args,
            expect,
        });
    }
    cases
}

/// Runs strata with `args` in the corpus folder under the limits; returns (status, stderr).
fn run_limited(args: &[String]) -> (Option<i32>, String) {
    let child = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {ADDRESS_SPACE_KIB} && exec \"$0\" \"$@\""
        ))
        .arg(env!("CARGO_BIN_EXE_strata"))
        .args(args)
        .current_dir(corpus_dir())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn strata");
    wait_at_most(child, TIME_LIMIT).unwrap_or_else(|still_running| (None, still_running))
}

/// Checks one case; returns a description of what went wrong.
fn check(case: &Case, scratch: &Path) -> Result<(), String> {
    let out = scratch.join(format!("case{}.exr", case.line));
    let args: Vec<String> = case
        .args
        .iter()
        .map(|a| a.replace("{out}", &out.to_string_lossy()))
        .collect();
    let (status, stderr) = run_limited(&args);
    if stderr.contains("panicked") || stderr.contains("memory allocation") {
        return Err(format!("crashed: {stderr}"));
    }
    match &case.expect {
        Expect::Reject(texts) => {
            if status != Some(2) {
                return Err(format!("exit status {status:?}, not 2: {stderr}"));
            }
            if let Some(missing) = texts.iter().find(|t| !stderr.contains(t.as_str())) {
                return Err(format!("message lacks \"{missing}\": {stderr}"));
            }
            if out.exists() {
                return Err("a rejected input left an output file".to_string());
            }
        }
        Expect::Render => {
            if status != Some(0) {
                return Err(format!("exit status {status:?}, not 0: {stderr}"));
            }
            let (image, spp) = Image::read_exr_with_spp(&out).map_err(|e| e.to_string())?;
            if (image.width, image.height) != (8, 6) || spp.is_none_or(|s| s == 0) {
                return Err(format!(
                    "{}x{} image with spp {spp:?}",
                    image.width, image.height
                ));
            }
            if !image.data.iter().all(|p| p.is_finite()) {
                return Err("non-finite pixels".to_string());
            }
        }
    }
    Ok(())
}

#[test]
fn every_corpus_case_behaves_as_the_manifest_says() {
    let cases = read_manifest();
    assert!(cases.len() >= 30, "the corpus needs at least 30 cases");
    let scratch = tempfile::tempdir().unwrap();
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|case| {
            check(case, scratch.path()).err().map(|e| {
                format!(
                    "MANIFEST line {} (strata {}): {e}",
                    case.line,
                    case.args.join(" ")
                )
            })
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} corpus cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

#[test]
fn every_corpus_file_is_used_by_a_case() {
    let manifest = std::fs::read_to_string(corpus_dir().join("MANIFEST")).unwrap();
    let mut unused = Vec::new();
    for entry in std::fs::read_dir(corpus_dir()).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        let referenced_elsewhere = name == "meshes" || name == "MANIFEST";
        if !referenced_elsewhere && !manifest.contains(&name) {
            unused.push(name);
        }
    }
    assert!(unused.is_empty(), "corpus files no case uses: {unused:?}");
}
