//! A progress bar on standard error, drawn only when standard error is a terminal.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressStyle};

/// Resolution of the bar: positions per full render.
const STEPS: u64 = 1000;

/// A progress bar that shows the fraction of the render budget spent, or nothing at all when
/// disabled or when standard error is not a terminal (so logs and pipes get no extra output).
pub struct Progress {
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A bar on standard error if `enabled` and standard error is a terminal, else a silent one.
    pub fn new(enabled: bool) -> Self {
        if enabled && std::io::stderr().is_terminal() {
            let bar = ProgressBar::new(STEPS);
            let style =
                ProgressStyle::with_template("{elapsed_precise} [{wide_bar}] {percent:>3}% {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar());
            bar.set_style(style);
            Self { bar: Some(bar) }
        } else {
            Self::hidden()
        }
    }

    /// A bar that never draws.
    pub fn hidden() -> Self {
        Self { bar: None }
    }

    /// Whether anything is drawn; callers may skip computing progress when not.
    pub fn is_visible(&self) -> bool {
        self.bar.is_some()
    }

    /// Moves the bar to `fraction` (clamped to `[0, 1]`) of the budget.
    pub fn set_fraction(&self, fraction: f64) {
        if let Some(bar) = &self.bar {
            bar.set_position((fraction.clamp(0.0, 1.0) * STEPS as f64) as u64);
        }
    }

    /// Sets the text after the bar, e.g. the samples per pixel done.
    pub fn set_message(&self, message: String) {
        if let Some(bar) = &self.bar {
            bar.set_message(message);
        }
    }

    /// Prints `line` on standard error, above the bar when one is drawn.
    pub fn println(&self, line: String) {
        match &self.bar {
            Some(bar) => bar.println(line),
            None => eprintln!("{line}"),
        }
    }

    /// Removes the bar from the terminal.
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disabled_progress_draws_nothing() {
        assert!(!Progress::new(false).is_visible());
        assert!(!Progress::hidden().is_visible());
    }
}
