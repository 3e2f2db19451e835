//! A progress bar on standard error, drawn only when standard error is a terminal: elapsed
//! time, the bar, the percentage of the budget spent, the estimated time left and the samples
//! per pixel done, e.g. `00:00:12 [#####     ] 52% ETA 11s 64 spp`.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{HumanDuration, ProgressBar, ProgressState, ProgressStyle};

use crate::budget::RenderBudget;

/// Resolution of the bar: positions per full render.
const STEPS: u64 = 1000;

/// The bar's layout; `budget_eta` is the time left (see [`eta`]).
const TEMPLATE: &str = "{elapsed_precise} [{wide_bar}] {percent:>3}% ETA {budget_eta} {msg}";

/// A progress bar that shows the fraction of the render budget spent, or nothing at all when
/// disabled or when standard error is not a terminal (so logs and pipes get no extra output).
pub struct Progress {
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A bar on standard error if `enabled` and standard error is a terminal, else a silent one;
    /// its ETA is extrapolated from the bar's speed.
    pub fn new(enabled: bool) -> Self {
        Self::for_budget(enabled, &RenderBudget::default())
    }

    /// [`new`](Self::new) for a render with `budget` starting now. Its ETA is the time left of
    /// the budget's seconds when only those bound the render, and otherwise extrapolated from
    /// the bar's speed (the smaller of the two when both bound it).
    pub fn for_budget(enabled: bool, budget: &RenderBudget) -> Self {
        if enabled && std::io::stderr().is_terminal() {
            let bar = ProgressBar::new(STEPS);
            // A budget too long for an `Instant` (`--time 1e300`) has no deadline to show.
            let deadline = budget
                .max_seconds
                .and_then(|s| Duration::try_from_secs_f64(s).ok())
                .and_then(|s| Instant::now().checked_add(s));
            let spp_bounded = budget.max_spp.is_some();
            let eta_key = move |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                let left = deadline.map(|d| d.saturating_duration_since(Instant::now()));
                let _ = write!(
                    w,
                    "{:#}",
                    HumanDuration(eta(state.eta(), left, spp_bounded))
                );
            };
            let style = ProgressStyle::with_template(TEMPLATE)
                .map(|style| style.with_key("budget_eta", eta_key))
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

/// The time left of a render: `budget_left` (the time budget's remainder, if it has one) when
/// no sample count bounds the render; otherwise `estimate` (extrapolated from the progress so
/// far; zero while unknown), capped by `budget_left`.
fn eta(estimate: Duration, budget_left: Option<Duration>, spp_bounded: bool) -> Duration {
    match budget_left {
        None => estimate,
        Some(left) if !spp_bounded || estimate.is_zero() => left,
        Some(left) => estimate.min(left),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disabled_progress_draws_nothing() {
        assert!(!Progress::new(false).is_visible());
        assert!(!Progress::for_budget(false, &RenderBudget::spp(4)).is_visible());
        assert!(!Progress::hidden().is_visible());
    }

    #[test]
    fn the_template_is_valid() {
        assert!(ProgressStyle::with_template(TEMPLATE).is_ok());
    }

    #[test]
    fn the_eta_of_a_time_budget_is_the_time_left_of_it() {
        let s = Duration::from_secs;
        // Time budget only: whatever the speed suggests, the render runs until the budget ends.
        assert_eq!(eta(s(3), Some(s(40)), false), s(40));
        assert_eq!(eta(s(90), Some(s(40)), false), s(40));
        // Samples only: the estimate.
        assert_eq!(eta(s(7), None, true), s(7));
        // Both: whichever ends first; an unknown (zero) estimate falls back to the budget.
        assert_eq!(eta(s(7), Some(s(40)), true), s(7));
        assert_eq!(eta(s(90), Some(s(40)), true), s(40));
        assert_eq!(eta(Duration::ZERO, Some(s(40)), true), s(40));
    }
}
