//! A running Mitsuba 3 process (`xtask/mitsuba_server.py`) with one scene loaded and warmed up,
//! rendering on request and reporting each render's wall time.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

/// The Mitsuba process and its pipes.
pub struct MitsubaServer {
    child: Child,
    input: ChildStdin,
    output: BufReader<ChildStdout>,
}

/// What to try when Mitsuba fails: its messages are above, and the LLVM variants need libLLVM.
const HINT: &str = "see Mitsuba's messages above; `llvm_*` variants need DRJIT_LIBLLVM_PATH \
                    naming libLLVM (e.g. /usr/lib/x86_64-linux-gnu/libLLVM-19.so)";

/// The Python script that drives Mitsuba.
fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("mitsuba_server.py")
}

/// Loads each of `scenes` in Mitsuba with `variant`, without rendering; the error names the first
/// scene Mitsuba cannot load.
pub fn check_loads(scenes: &[PathBuf], variant: &str) -> Result<(), String> {
    let script = script();
    let status = Command::new("python3")
        .arg(&script)
        .arg("--check")
        .arg(variant)
        .args(scenes)
        .status()
        .map_err(|e| format!("cannot run python3 {}: {e}", script.display()))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("Mitsuba could not load every scene ({HINT})"))
    }
}

impl MitsubaServer {
    /// Starts Mitsuba on `scene` with `variant` and waits until its warm-up render is done.
    pub fn start(scene: &Path, variant: &str) -> Result<Self, String> {
        let script = script();
        let mut child = Command::new("python3")
            .arg(&script)
            .arg(scene)
            .arg(variant)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .map_err(|e| format!("cannot run python3 {}: {e}", script.display()))?;
        let input = child.stdin.take().ok_or("no stdin pipe to Mitsuba")?;
        let output = BufReader::new(child.stdout.take().ok_or("no stdout pipe from Mitsuba")?);
        let mut server = Self {
            child,
            input,
            output,
        };
        let ready = server.read_line()?;
        if ready != "ready" {
            return Err(format!("Mitsuba did not start: {ready:?}"));
        }
        Ok(server)
    }

    /// Renders `spp` samples per pixel with `seed` into `out` (EXR); returns the seconds the
    /// render took (loading and writing excluded).
    pub fn render(&mut self, spp: u32, seed: u32, out: &Path) -> Result<f64, String> {
        let out = out
            .to_str()
            .ok_or_else(|| format!("{} is not UTF-8", out.display()))?;
        writeln!(self.input, "{spp} {seed} {out}").map_err(|e| format!("to Mitsuba: {e}"))?;
        self.input.flush().map_err(|e| format!("to Mitsuba: {e}"))?;
        let line = self.read_line()?;
        line.parse()
            .map_err(|_| format!("Mitsuba answered {line:?} instead of seconds"))
    }

    fn read_line(&mut self) -> Result<String, String> {
        let mut line = String::new();
        let read = self
            .output
            .read_line(&mut line)
            .map_err(|e| format!("from Mitsuba: {e}"))?;
        if read == 0 {
            return Err(format!("Mitsuba exited ({HINT})"));
        }
        Ok(line.trim().to_string())
    }
}

impl Drop for MitsubaServer {
    fn drop(&mut self) {
        // The process is ours; end it and reap it so none is left behind.
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
