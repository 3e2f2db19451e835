//! Render budgets (samples per pixel and wall-clock seconds) and the choice of pass sizes.

use std::fmt;

/// When to stop rendering: after `max_spp` samples per pixel or once `max_seconds` of rendering
/// time are spent, whichever comes first. Rendering always stops at a pass boundary, so every
/// pixel has the same number of samples; a time budget may be overrun by at most one pass of
/// 1 sample per pixel once the passes have adapted to the measured speed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderBudget {
    /// Stop once every pixel has this many samples.
    pub max_spp: Option<u32>,
    /// Stop at the first pass boundary after this many seconds of rendering.
    pub max_seconds: Option<f64>,
}

/// A budget that cannot be rendered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BudgetError {
    /// Neither a sample count nor a time limit was given: the render would never stop.
    Unbounded,
    /// The time limit is negative or not a number.
    InvalidSeconds(f64),
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
    /// - The sample limit is never exceeded, and with only a sample limit one pass renders
    ///   everything (the tiles still spread over the threads).
    /// - With a time limit the first pass has 1 sample per pixel, to measure the speed; each
    ///   later pass fills the remaining time at the measured speed, at most doubling the
    ///   previous pass, and at least 1; rendering stops once the time is spent. At least one
    ///   pass is always rendered (unless the sample limit is 0).
    pub fn next_pass_spp(&self, spp_done: u32, elapsed: f64, last_pass: u32) -> u32 {
        let remaining_spp = self
            .max_spp
            .map_or(u32::MAX - spp_done, |max| max.saturating_sub(spp_done));
        let Some(max_seconds) = self.max_seconds else {
            return remaining_spp;
        };
        if remaining_spp == 0 {
            return 0;
        }
        if spp_done == 0 {
            return 1;
        }
        let remaining_seconds = max_seconds - elapsed;
        if remaining_seconds <= 0.0 {
            return 0;
        }
        let seconds_per_spp = elapsed / f64::from(spp_done);
        let fitting = if seconds_per_spp > 0.0 {
            remaining_seconds / seconds_per_spp
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
    fn spp_only_is_one_pass_of_everything() {
        let budget = RenderBudget::spp(64);
        assert_eq!(budget.next_pass_spp(0, 0.0, 0), 64);
        assert_eq!(budget.next_pass_spp(64, 3.0, 64), 0);
        assert_eq!(RenderBudget::spp(0).next_pass_spp(0, 0.0, 0), 0);
    }

    #[test]
    fn time_budget_measures_then_fills_the_remaining_time() {
        let budget = RenderBudget::seconds(10.0);
        assert_eq!(
            budget.next_pass_spp(0, 0.0, 0),
            1,
            "first pass measures the speed"
        );
        // 1 spp took 0.1 s: 99 more would fit, but the pass at most doubles.
        assert_eq!(budget.next_pass_spp(1, 0.1, 1), 2);
        assert_eq!(
            budget.next_pass_spp(64, 8.0, 32),
            16,
            "2 s left at 0.125 s per spp"
        );
        assert_eq!(budget.next_pass_spp(99, 9.95, 35), 1, "never less than one");
        assert_eq!(budget.next_pass_spp(100, 10.0, 1), 0, "time spent");
        assert_eq!(
            budget.next_pass_spp(7, 0.0, 7),
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
            budget.next_pass_spp(8, 0.8, 4),
            2,
            "the sample limit caps the pass"
        );
        assert_eq!(budget.next_pass_spp(10, 1.0, 2), 0);
        let budget = RenderBudget {
            max_spp: Some(1000),
            max_seconds: Some(1.0),
        };
        assert_eq!(budget.next_pass_spp(5, 1.2, 2), 0);
        assert_eq!(
            RenderBudget {
                max_spp: Some(0),
                max_seconds: Some(1.0)
            }
            .next_pass_spp(0, 0.0, 0),
            0
        );
    }

    #[test]
    fn zero_seconds_still_renders_one_pass() {
        let budget = RenderBudget::seconds(0.0);
        assert_eq!(budget.next_pass_spp(0, 0.0, 0), 1);
        assert_eq!(budget.next_pass_spp(1, 0.01, 1), 0);
    }
}
