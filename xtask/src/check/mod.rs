//! `cargo xtask check [--quick]`: the statistical and stiff-case checks, one pass/fail line each.
//!
//! The checks are the workspace's tests: chi-square and pdf-normalisation tests beside every warp,
//! BSDF and light; furnace scenes; unbiasedness of every configuration against the reference
//! integrator; the stiff and extreme suite. `check` builds every test binary once (`cargo test
//! --no-run`), runs each one itself and prints, per test, PASS or FAIL with the figures the test
//! reported (its output lines starting with `figure:`). `--quick` runs what `cargo test` runs in
//! CI; the full check adds the tests marked `#[ignore]` as too slow for CI (larger budgets, the
//! scenes whose references are expensive) and then measures what each technique buys
//! (`cargo xtask gains`, timing-based, so never in CI).

mod libtest;

use libtest::{TestBinary, TestResult, Verdict};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// Runs `cargo xtask check [--quick]`; `Ok(false)` when any check failed.
pub fn check(root: &Path, args: &[String]) -> Result<bool, String> {
    let mut quick = false;
    for arg in args {
        match arg.as_str() {
            "--quick" => quick = true,
            other => return Err(format!("check: unknown argument {other}")),
        }
    }
    let start = Instant::now();
    let binaries = libtest::build_test_binaries(root)?;
    let mut results: Vec<(String, TestResult)> = Vec::new();
    for binary in &binaries {
        let outcome = run_binary(binary, quick)?;
        for result in outcome {
            print_result(&binary.label, &result);
            results.push((binary.label.clone(), result));
        }
    }
    let mut failed_claims = Vec::new();
    if !quick {
        for claim in crate::gains::measure_all(root)? {
            crate::gains::print_claim(&claim);
            if !claim.passed {
                failed_claims.push(claim.name);
            }
        }
    }
    let count = |verdict: Verdict| results.iter().filter(|(_, r)| r.verdict == verdict).count();
    let (passed, failed, ignored) = (
        count(Verdict::Passed),
        count(Verdict::Failed),
        count(Verdict::Ignored),
    );
    println!(
        "check{}: {passed} passed, {failed} failed{} in {:.0} s ({} test binaries)",
        if quick { " --quick" } else { "" },
        if quick {
            format!(", {ignored} left for the full check")
        } else {
            format!("; technique gains: {} failed", failed_claims.len())
        },
        start.elapsed().as_secs_f64(),
        binaries.len()
    );
    for (label, result) in results.iter().filter(|(_, r)| r.verdict == Verdict::Failed) {
        println!("FAILED {label}::{}", result.name);
    }
    for name in &failed_claims {
        println!("FAILED gains::{name}");
    }
    Ok(failed == 0 && failed_claims.is_empty())
}

/// Runs one test binary from its package's directory and parses what it printed.
fn run_binary(binary: &TestBinary, quick: bool) -> Result<Vec<TestResult>, String> {
    let mut command = Command::new(&binary.executable);
    command
        .current_dir(&binary.package_dir)
        .arg("--show-output");
    if !quick {
        command.arg("--include-ignored");
    }
    let output = command
        .output()
        .map_err(|e| format!("cannot run {}: {e}", binary.executable.display()))?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    let results = libtest::parse(&stdout);
    if !output.status.success() && !results.iter().any(|r| r.verdict == Verdict::Failed) {
        return Err(format!(
            "{} exited with {} without a failed test:\n{stdout}\n{}",
            binary.label,
            output.status,
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    Ok(results)
}

/// One line per test that ran, then its figures (or, for a failure, its message) indented below.
fn print_result(label: &str, result: &TestResult) {
    let verdict = match result.verdict {
        Verdict::Passed => "PASS",
        Verdict::Failed => "FAIL",
        Verdict::Ignored => return,
    };
    println!("{verdict} {label}::{}", result.name);
    for line in &result.figures {
        println!("       {line}");
    }
    if result.verdict == Verdict::Failed {
        for line in result.output.iter().take(12) {
            println!("     | {line}");
        }
    }
}
