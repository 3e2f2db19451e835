//! The report's answer to "which technique wins here, and by how much?": per scene, the rung
//! with the best efficiency, its gain over MIS, and `auto` against it, with the spread over
//! seeds that tells a difference from noise.

use super::ladder::REFERENCE;
use super::report::{AUTO, SceneReport};

/// The rungs a scene's best is compared with, in order of preference: MIS where it applies,
/// else the rung closest to it (NEE where no light can be hit, BSDF sampling where none can be
/// sampled), else the reference integrator.
pub const BASELINES: &[&str] = &["mis", "nee", "bsdf", REFERENCE];

/// Median and range of a quantity over the seeds rendered at one budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spread {
    /// The median (the mean of the middle two for an even count).
    pub median: f64,
    /// The smallest value.
    pub min: f64,
    /// The largest value.
    pub max: f64,
}

impl Spread {
    /// The spread of `values`; `None` when there are none or one is NaN.
    pub fn of(values: &[f64]) -> Option<Self> {
        if values.is_empty() || values.iter().any(|v| v.is_nan()) {
            return None;
        }
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let median = if n % 2 == 1 {
            sorted[n / 2]
        } else if sorted[n / 2 - 1] == sorted[n / 2] {
            // Equal middle values (both infinite, say) are the median as they are.
            sorted[n / 2]
        } else {
            0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
        };
        Some(Self {
            median,
            min: sorted[0],
            max: sorted[n - 1],
        })
    }

    /// Every figure divided by `by` (for efficiencies relative to another rung's median).
    pub fn scaled(self, by: f64) -> Self {
        Self {
            median: self.median / by,
            min: self.min / by,
            max: self.max / by,
        }
    }
}

/// One scene's row of the summary table.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneSummary {
    /// The rung (not `auto`) with the highest median efficiency at the largest budget.
    pub best: String,
    /// Its efficiency over the seeds at the largest budget, 1/(relMSE × seconds), per second.
    pub best_efficiency: Spread,
    /// Other rungs whose efficiency range reaches the best's lowest seed: not told apart from
    /// it by these seeds.
    pub within_noise: Vec<String>,
    /// The rung the best is compared with (the first of [`BASELINES`] the scene has) and its
    /// efficiency.
    pub baseline: Option<(String, Spread)>,
    /// `auto`'s efficiency over the seeds at the largest budget.
    pub auto_efficiency: Option<Spread>,
}

impl SceneSummary {
    /// The summary of `report`; `None` when no rung but `auto` was measured.
    pub fn of(report: &SceneReport) -> Option<Self> {
        let measured: Vec<(&str, Spread)> = report
            .rungs
            .iter()
            .filter(|r| r.name != AUTO)
            .filter_map(|r| Some((r.name.as_str(), report.efficiency(&r.name)?)))
            .collect();
        let &(best, best_efficiency) = measured
            .iter()
            .max_by(|a, b| a.1.median.total_cmp(&b.1.median))?;
        let within_noise = measured
            .iter()
            .filter(|(name, spread)| *name != best && spread.max >= best_efficiency.min)
            .map(|(name, _)| name.to_string())
            .collect();
        let baseline = BASELINES.iter().find_map(|&name| {
            measured
                .iter()
                .find(|(n, _)| *n == name)
                .map(|&(n, spread)| (n.to_string(), spread))
        });
        Some(Self {
            best: best.to_string(),
            best_efficiency,
            within_noise,
            baseline,
            auto_efficiency: report.efficiency(AUTO),
        })
    }

    /// The best's median efficiency over the baseline's.
    pub fn best_over_baseline(&self) -> Option<f64> {
        let (_, baseline) = self.baseline.as_ref()?;
        Some(self.best_efficiency.median / baseline.median)
    }

    /// `auto`'s median efficiency over the best's (above 1 where `auto` beats every rung).
    pub fn auto_over_best(&self) -> Option<f64> {
        Some(self.auto_efficiency?.median / self.best_efficiency.median)
    }

    /// Whether `auto` is worse than the best by more than the noise: every seed of `auto` less
    /// efficient than every seed of the best (their ranges over seeds do not overlap).
    ///
    /// As a test: if `auto` and the best had the same distribution of efficiency, the chance
    /// that all n of `auto`'s seeds fall below all n of the best's is 1 / C(2n, n), 5% for 3
    /// seeds each (a one-sided Mann–Whitney test with U = 0), per scene, uncorrected for the
    /// number of scenes. The best is the rung with the highest median, chosen after looking,
    /// so among rungs of equal efficiency it is the luckiest: the flag then fires more often
    /// than 5%; a flag is a lead to follow, a missing one is no proof that `auto` is as good.
    pub fn auto_flagged(&self) -> bool {
        self.auto_efficiency
            .is_some_and(|auto| auto.max < self.best_efficiency.min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render_all::report::{Measurement, Rung};

    fn measurement(configuration: &str, seed: u32, efficiency: f64) -> Measurement {
        Measurement {
            configuration: configuration.to_string(),
            budget: 1.0,
            seed,
            spp: 1,
            seconds: 1.0,
            rmse: 0.0,
            relmse: 1.0 / efficiency,
            non_finite: 0,
        }
    }

    /// A scene whose rungs have these efficiencies per seed at the one budget.
    fn report(efficiencies: &[(&str, &[f64])]) -> SceneReport {
        SceneReport {
            scene: "s".to_string(),
            rungs: efficiencies
                .iter()
                .map(|(name, _)| Rung {
                    name: name.to_string(),
                    builds_on: None,
                    techniques: Vec::new(),
                })
                .collect(),
            auto_choices: Vec::new(),
            measurements: efficiencies
                .iter()
                .flat_map(|(name, values)| {
                    values
                        .iter()
                        .enumerate()
                        .map(|(seed, &e)| measurement(name, seed as u32, e))
                })
                .collect(),
            exposure: 1.0,
        }
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * b.abs()
    }

    #[test]
    fn a_spread_is_the_median_and_range() {
        let s = Spread::of(&[3.0, 1.0, 2.0]).unwrap();
        assert_eq!((s.median, s.min, s.max), (2.0, 1.0, 3.0));
        let even = Spread::of(&[4.0, 1.0, 2.0, 10.0]).unwrap();
        assert_eq!((even.median, even.min, even.max), (3.0, 1.0, 10.0));
        let exact = Spread::of(&[f64::INFINITY, f64::INFINITY]).unwrap();
        assert_eq!(exact.median, f64::INFINITY);
        assert_eq!(Spread::of(&[]), None);
        assert_eq!(Spread::of(&[1.0, f64::NAN]), None);
    }

    #[test]
    fn the_best_rung_has_the_highest_median_and_auto_is_not_a_candidate() {
        let r = report(&[
            (REFERENCE, &[1.0, 1.1, 0.9]),
            ("nee", &[8.0, 9.0, 10.0]),
            ("mis", &[10.0, 11.0, 12.0]),
            // The highest single seed, but not the highest median.
            ("+sobol", &[5.0, 30.0, 6.0]),
            ("+adaptive", &[19.0, 20.0, 21.0]),
            (AUTO, &[100.0, 100.0, 100.0]),
        ]);
        let s = SceneSummary::of(&r).unwrap();
        assert_eq!(s.best, "+adaptive");
        assert_eq!(s.best_efficiency.median, 20.0);
        // +sobol's range reaches 19: not told apart from the best. MIS's does not.
        assert_eq!(s.within_noise, ["+sobol"]);
        assert_eq!(s.baseline.as_ref().map(|b| b.0.as_str()), Some("mis"));
        assert!(close(s.best_over_baseline().unwrap(), 20.0 / 11.0));
        assert!(close(s.auto_over_best().unwrap(), 5.0));
        assert!(!s.auto_flagged());
    }

    #[test]
    fn without_mis_the_best_is_compared_with_the_closest_rung() {
        let r = report(&[
            (REFERENCE, &[1.0, 1.0, 1.0]),
            ("nee", &[4.0, 4.0, 4.0]),
            ("+roulette", &[8.0, 8.0, 8.0]),
        ]);
        let s = SceneSummary::of(&r).unwrap();
        assert_eq!(s.baseline.as_ref().map(|b| b.0.as_str()), Some("nee"));
        assert!(close(s.best_over_baseline().unwrap(), 2.0));
        assert_eq!(s.auto_efficiency, None);
        assert!(!s.auto_flagged());
        let only_reference = report(&[(REFERENCE, &[1.0, 2.0, 3.0])]);
        let s = SceneSummary::of(&only_reference).unwrap();
        assert_eq!(s.baseline.map(|b| b.0), Some(REFERENCE.to_string()));
    }

    #[test]
    fn auto_is_flagged_exactly_when_its_best_seed_is_below_the_bests_worst() {
        let best: &[f64] = &[10.0, 12.0, 14.0];
        for (auto, flagged) in [
            // Far below: flagged.
            (&[1.0, 1.1, 1.2][..], true),
            // Just below the best's worst seed: flagged.
            (&[9.0, 9.5, 9.99], true),
            // Its best seed reaches the best's worst: within the noise.
            (&[8.0, 9.0, 10.0], false),
            // A lower median but overlapping ranges: within the noise.
            (&[5.0, 6.0, 11.0], false),
            // As good or better: never flagged.
            (&[12.0, 13.0, 14.0], false),
            (&[20.0, 30.0, 40.0], false),
        ] {
            let r = report(&[("mis", best), (AUTO, auto)]);
            let s = SceneSummary::of(&r).unwrap();
            assert_eq!(s.best, "mis");
            assert_eq!(s.auto_flagged(), flagged, "auto {auto:?} against {best:?}");
        }
    }

    #[test]
    fn an_exact_best_flags_any_noisy_auto() {
        // The furnace: BSDF sampling is exact (infinite efficiency); roulette adds noise.
        let r = report(&[
            ("bsdf", &[f64::INFINITY, f64::INFINITY, f64::INFINITY]),
            (AUTO, &[1e3, 2e3, 3e3]),
        ]);
        let s = SceneSummary::of(&r).unwrap();
        assert_eq!(s.best, "bsdf");
        assert_eq!(s.auto_over_best(), Some(0.0));
        assert!(s.auto_flagged());
    }
}
