//! Building the workspace's test binaries and reading the results libtest prints.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// Prefix of the lines a test prints to report what it measured.
const FIGURE_PREFIX: &str = "figure:";

/// One test executable of the workspace.
#[derive(Clone, Debug)]
pub struct TestBinary {
    /// `package/target`, e.g. `sampling/warps` or `render/lib`.
    pub label: String,
    /// The compiled test harness.
    pub executable: PathBuf,
    /// The package's directory, where cargo would run it.
    pub package_dir: PathBuf,
}

/// How one test ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// It ran and passed.
    Passed,
    /// It ran and failed.
    Failed,
    /// It was not run (marked `#[ignore]` and not asked for).
    Ignored,
}

/// One test's result with what it printed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TestResult {
    /// The test's path within its binary, e.g. `tests::chi2_fits`.
    pub name: String,
    /// How it ended.
    pub verdict: Verdict,
    /// Its `figure:` lines, without the prefix.
    pub figures: Vec<String>,
    /// Everything else it printed (for a failure: the panic message).
    pub output: Vec<String>,
}

/// Builds every test binary of the workspace in release mode and lists them in build order.
pub fn build_test_binaries(root: &Path) -> Result<Vec<TestBinary>, String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let output = Command::new(cargo)
        .current_dir(root)
        .args([
            "test",
            "--release",
            "--workspace",
            "--no-run",
            "--message-format=json-render-diagnostics",
        ])
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !output.status.success() {
        return Err("building the tests failed".to_string());
    }
    let stdout = String::from_utf8_lossy(&output.stdout);
    let mut binaries: Vec<TestBinary> = stdout.lines().filter_map(test_binary).collect();
    binaries.sort_by(|a, b| a.label.cmp(&b.label));
    Ok(binaries)
}

/// The test binary a cargo JSON message announces, if it announces one.
fn test_binary(line: &str) -> Option<TestBinary> {
    let message: Value = serde_json::from_str(line).ok()?;
    if message["reason"] != "compiler-artifact" || message["profile"]["test"] != true {
        return None;
    }
    let executable = PathBuf::from(message["executable"].as_str()?);
    let manifest = PathBuf::from(message["manifest_path"].as_str()?);
    let package_dir = manifest.parent()?.to_path_buf();
    let package = package_dir.file_name()?.to_string_lossy().into_owned();
    let target = message["target"]["name"].as_str()?;
    let kinds = message["target"]["kind"].as_array()?;
    let target = if kinds.iter().any(|k| k == "lib") {
        "lib"
    } else {
        target
    };
    Some(TestBinary {
        label: format!("{package}/{target}"),
        executable,
        package_dir,
    })
}

/// Reads libtest's report (run with `--show-output`): each `test NAME ... ok|FAILED|ignored`
/// line, and the `---- NAME stdout ----` sections that follow with what each test printed.
pub fn parse(stdout: &str) -> Vec<TestResult> {
    let mut results: Vec<TestResult> = Vec::new();
    let mut section: Option<usize> = None;
    for line in stdout.lines() {
        if let Some(rest) = line.strip_prefix("test ")
            && let Some((name, verdict)) = rest.rsplit_once(" ... ")
        {
            let verdict = match verdict.trim() {
                "ok" => Verdict::Passed,
                "FAILED" => Verdict::Failed,
                v if v.starts_with("ignored") => Verdict::Ignored,
                _ => continue,
            };
            results.push(TestResult {
                name: name.to_string(),
                verdict,
                figures: Vec::new(),
                output: Vec::new(),
            });
            continue;
        }
        if let Some(name) = line
            .strip_prefix("---- ")
            .and_then(|rest| rest.strip_suffix(" stdout ----"))
        {
            section = results.iter().position(|r| r.name == name);
            continue;
        }
        if matches!(line, "successes:" | "failures:") || line.starts_with("test result:") {
            section = None;
            continue;
        }
        if let Some(index) = section {
            let result = &mut results[index];
            match line.trim_start().strip_prefix(FIGURE_PREFIX) {
                Some(figure) => result.figures.push(figure.trim().to_string()),
                None if !line.is_empty() => result.output.push(line.to_string()),
                None => {}
            }
        }
    }
    results
}

#[cfg(test)]
mod tests {
    use super::*;

    const REPORT: &str = "\nrunning 3 tests\ntest a::one ... ok\ntest a::two ... FAILED\n\
        test a::slow ... ignored, full check only\n\nsuccesses:\n\n---- a::one stdout ----\n\
        figure: p = 0.42\nnoise\n\n\nsuccesses:\n    a::one\n\nfailures:\n\n---- a::two stdout ----\n\
        thread 'a::two' panicked at src/lib.rs:3:5:\nfigure: z = 9.1\n\nfailures:\n    a::two\n\n\
        test result: FAILED. 1 passed; 1 failed; 1 ignored; 0 measured; 0 filtered out\n";

    #[test]
    fn verdicts_figures_and_messages_go_to_their_tests() {
        let results = parse(REPORT);
        let names: Vec<&str> = results.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["a::one", "a::two", "a::slow"]);
        assert_eq!(
            results.iter().map(|r| r.verdict).collect::<Vec<_>>(),
            [Verdict::Passed, Verdict::Failed, Verdict::Ignored]
        );
        assert_eq!(results[0].figures, ["p = 0.42"]);
        assert_eq!(results[0].output, ["noise"]);
        assert_eq!(results[1].figures, ["z = 9.1"]);
        assert_eq!(
            results[1].output,
            ["thread 'a::two' panicked at src/lib.rs:3:5:"]
        );
        assert!(results[2].figures.is_empty());
    }

    #[test]
    fn library_and_integration_test_binaries_are_labelled_by_package() {
        let lib = r#"{"reason":"compiler-artifact","manifest_path":"/w/crates/sampling/Cargo.toml","target":{"kind":["lib"],"name":"sampling"},"profile":{"test":true},"executable":"/w/target/release/deps/sampling-1"}"#;
        let test = r#"{"reason":"compiler-artifact","manifest_path":"/w/crates/lights/Cargo.toml","target":{"kind":["test"],"name":"chi2"},"profile":{"test":true},"executable":"/w/target/release/deps/chi2-2"}"#;
        let not_a_test = r#"{"reason":"compiler-artifact","manifest_path":"/w/crates/lights/Cargo.toml","target":{"kind":["lib"],"name":"lights"},"profile":{"test":false},"executable":null}"#;
        assert_eq!(
            test_binary(lib).map(|b| b.label).as_deref(),
            Some("sampling/lib")
        );
        let binary = test_binary(test).expect("a test binary");
        assert_eq!(binary.label, "lights/chi2");
        assert_eq!(binary.package_dir, PathBuf::from("/w/crates/lights"));
        assert!(test_binary(not_a_test).is_none());
        assert!(test_binary("not json").is_none());
    }
}
