//! Render budgets (samples per pixel and wall-clock seconds) and the choice of pass sizes.

use std::fmt;

/// When to stop rendering: after `max_spp` samples per pixel or once `max_seconds` of rendering
/// time are spent, whichever comes first. Rendering always stops at a pass boundary, so every
/// pixel has the same number of samples; a time budget may be overrun by at most one pass of
/// 1 sample per pixel once the passes have adapted to the measured speed. Passes last at most
/// about [`MAX_PASS_SECONDS`], so a request to stop (Ctrl-C) is honoured promptly.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderBudget {
    /// Stop once every pixel has this many samples.
    pub max_spp: Option<u32>,
    /// Stop at the first pass boundary after this many seconds of rendering.
    pub max_seconds: Option<f64>,
}

/// Longest a pass is planned to take, in seconds, once the speed is measured: the driver checks
/// for a request to stop (Ctrl-C) between passes, so this bounds how long stopping takes.
pub const MAX_PASS_SECONDS: f64 = 1.0;

/// A render that cannot start: its budget cannot be rendered, or what it continues from does
/// not fit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BudgetError {
    /// Neither a sample count nor a time limit was given: the render would never stop.
    Unbounded,
    /// The time limit is negative or not a number.
    InvalidSeconds(f64),
    /// The film to resume from is `film` (width, height) pixels but the image is `image`.
    ResumeSize {
        /// The resumed film's width and height in pixels.
        film: (u32, u32),
        /// The image's width and height in pixels.
        image: (u32, u32),
    },
}

impl fmt::Display for BudgetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Unbounded => write!(
                f,
                "the render budget needs a sample count, a time limit or both"
            ),
            Self::InvalidSeconds(s) => write!(
                f,
                "the time limit must be a non-negative number of seconds, got {s}"
            ),
            Self::ResumeSize { film, image } => write!(
                f,
                "the saved render is {}x{} pixels but the image is {}x{}",
                film.0, film.1, image.0, image.1
            ),
        }
    }
}

impl std::error::Error for BudgetError {}

impl RenderBudget {
    /// A budget of `spp` samples per pixel and no time limit.
    pub fn spp(spp: u32) -> Self {
        Self {
            max_spp: Some(spp),
            max_seconds: None,
        }
    }

    /// A budget of `seconds` of rendering time and no sample limit.
    pub fn seconds(seconds: f64) -> Self {
        Self {
            max_spp: None,
            max_seconds: Some(seconds),
        }
    }

    /// An error unless the budget has a limit and its time limit is a non-negative number
    /// (`+∞` is allowed: no time limit in effect).
    pub fn validate(&self) -> Result<(), BudgetError> {
        match (self.max_spp, self.max_seconds) {
            (None, None) => Err(BudgetError::Unbounded),
            (_, Some(s)) if s.is_nan() || s < 0.0 => Err(BudgetError::InvalidSeconds(s)),
            _ => Ok(()),
        }
    }

    /// Samples per pixel for the next pass, or 0 to stop, given `spp_done` samples per pixel
    /// rendered in `elapsed` seconds over passes the last of which had `last_pass` samples.
    ///
    /// - The sample limit is never exceeded.
    /// - The first pass has 1 sample per pixel, to measure the speed; each later pass fills the
    ///   remaining time, but at most [`MAX_PASS_SECONDS`], at the measured speed, at most
    ///   doubling the previous pass, and at least 1. With a time limit rendering stops once the
    ///   time is spent. At least one pass is always rendered (unless the sample limit is 0).
    ///
    /// How the samples are split into passes never changes the image (see [`crate::driver`]).
    pub fn next_pass_spp(
        &self,
        spp_done: u32,
        elapsed: f64,
        last_pass: u32,
        max_pass_seconds: f64,
    ) -> u32 {
        let remaining_spp = self
            .max_spp
            .map_or(u32::MAX - spp_done, |max| max.saturating_sub(spp_done));
        if remaining_spp == 0 {
            return 0;
        }
        if spp_done == 0 {
            return 1;
        }
        let remaining_seconds = self.max_seconds.map_or(f64::INFINITY, |max| max - elapsed);
        if remaining_seconds <= 0.0 {
            return 0;
        }
        let seconds_per_spp = elapsed / f64::from(spp_done);
        let pass_seconds = remaining_seconds.min(max_pass_seconds);
        let fitting = if seconds_per_spp > 0.0 {
            pass_seconds / seconds_per_spp
        } else {
            f64::INFINITY
        };
        let growth_cap = last_pass.saturating_mul(2).max(1);
        (fitting.min(f64::from(growth_cap)) as u32).clamp(1, remaining_spp)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation() {
        assert_eq!(
            RenderBudget::default().validate(),
            Err(BudgetError::Unbounded)
        );
        assert!(matches!(
            RenderBudget::seconds(f64::NAN).validate(),
            Err(BudgetError::InvalidSeconds(_))
        ));
        assert!(RenderBudget::seconds(-1.0).validate().is_err());
        assert!(RenderBudget::seconds(0.0).validate().is_ok());
        assert!(RenderBudget::spp(0).validate().is_ok());
    }

    #[test]
    fn spp_only_grows_short_passes_up_to_the_limit() {
        let budget = RenderBudget::spp(64);
        assert_eq!(
            budget.next_pass_spp(0, 0.0, 0, MAX_PASS_SECONDS),
            1,
            "first pass measures"
        );
        assert_eq!(
            budget.next_pass_spp(1, 0.001, 1, MAX_PASS_SECONDS),
            2,
            "at most doubling"
        );
        assert_eq!(
            budget.next_pass_spp(7, 0.7, 4, MAX_PASS_SECONDS),
            8,
            "0.1 s per spp: a pass of at most 1 s holds 10, doubling caps at 8"
        );
        assert_eq!(
            budget.next_pass_spp(30, 3.0, 16, MAX_PASS_SECONDS),
            10,
            "a pass lasts at most MAX_PASS_SECONDS"
        );
        assert_eq!(
            budget.next_pass_spp(60, 0.06, 32, MAX_PASS_SECONDS),
            4,
            "never past the limit"
        );
        assert_eq!(budget.next_pass_spp(64, 3.0, 4, MAX_PASS_SECONDS), 0);
        assert_eq!(
            RenderBudget::spp(0).next_pass_spp(0, 0.0, 0, MAX_PASS_SECONDS),
            0
        );
    }

    #[test]
    fn time_budget_measures_then_fills_the_remaining_time() {
        let budget = RenderBudget::seconds(10.0);
        assert_eq!(
            budget.next_pass_spp(0, 0.0, 0, MAX_PASS_SECONDS),
            1,
            "first pass measures the speed"
        );
        // 1 spp took 0.1 s: 99 more would fit, but the pass at most doubles.
        assert_eq!(budget.next_pass_spp(1, 0.1, 1, MAX_PASS_SECONDS), 2);
        assert_eq!(
            budget.next_pass_spp(64, 9.5, 32, MAX_PASS_SECONDS),
            3,
            "0.5 s left at 0.148 s per spp"
        );
        assert_eq!(
            budget.next_pass_spp(64, 8.0, 32, MAX_PASS_SECONDS),
            8,
            "2 s left at 0.125 s per spp, but a pass lasts at most 1 s"
        );
        assert_eq!(
            budget.next_pass_spp(99, 9.95, 35, MAX_PASS_SECONDS),
            1,
            "never less than one"
        );
        assert_eq!(
            budget.next_pass_spp(100, 10.0, 1, MAX_PASS_SECONDS),
            0,
            "time spent"
        );
        assert_eq!(
            budget.next_pass_spp(7, 0.0, 7, MAX_PASS_SECONDS),
            14,
            "an unmeasurably fast pass still only doubles"
        );
    }

    #[test]
    fn both_limits_stop_at_whichever_comes_first() {
        let budget = RenderBudget {
            max_spp: Some(10),
            max_seconds: Some(100.0),
        };
        assert_eq!(
            budget.next_pass_spp(8, 0.8, 4, MAX_PASS_SECONDS),
            2,
            "the sample limit caps the pass"
        );
        assert_eq!(budget.next_pass_spp(10, 1.0, 2, MAX_PASS_SECONDS), 0);
        let budget = RenderBudget {
            max_spp: Some(1000),
            max_seconds: Some(1.0),
        };
        assert_eq!(budget.next_pass_spp(5, 1.2, 2, MAX_PASS_SECONDS), 0);
        assert_eq!(
            RenderBudget {
                max_spp: Some(0),
                max_seconds: Some(1.0)
            }
            .next_pass_spp(0, 0.0, 0, MAX_PASS_SECONDS),
            0
        );
    }

    #[test]
    fn a_shorter_pass_limit_plans_shorter_passes() {
        let budget = RenderBudget::spp(1000);
        // 0.1 s per spp: 10 fit in the default second, 2 in a quarter of one.
        assert_eq!(budget.next_pass_spp(30, 3.0, 16, MAX_PASS_SECONDS), 10);
        assert_eq!(budget.next_pass_spp(30, 3.0, 16, 0.25), 2);
        assert_eq!(
            budget.next_pass_spp(30, 3.0, 16, 0.01),
            1,
            "never less than one"
        );
    }

    #[test]
    fn zero_seconds_still_renders_one_pass() {
        let budget = RenderBudget::seconds(0.0);
        assert_eq!(budget.next_pass_spp(0, 0.0, 0, MAX_PASS_SECONDS), 1);
        assert_eq!(budget.next_pass_spp(1, 0.01, 1, MAX_PASS_SECONDS), 0);
    }
}
