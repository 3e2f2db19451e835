//! The verdict of a chi-square test: pooling of sparse cells, statistic, p-value and a replayable report.

use super::gamma::gamma_q;
use std::fmt;

/// How many of the largest deviations a report lists.
const WORST_BIN_COUNT: usize = 5;

/// One cell of a chi-square histogram, as listed among an outcome's worst deviations.
#[derive(Clone, Debug, PartialEq)]
pub struct Chi2Bin {
    /// Where the cell lies, e.g. "cos θ ∈ [0.500, 0.625), φ ∈ [-3.142, -2.945)" or "index 3".
    pub label: String,
    /// Number of samples that fell into the cell.
    pub observed: f64,
    /// Number of samples the pdf predicts: sample count × the pdf's integral over the cell.
    pub expected: f64,
}

impl Chi2Bin {
    /// The cell's term (observed − expected)² / expected of the statistic (∞ if nothing was expected).
    pub fn contribution(&self) -> f64 {
        let d = self.observed - self.expected;
        if self.expected > 0.0 {
            d * d / self.expected
        } else if self.observed > 0.0 {
            f64::INFINITY
        } else {
            0.0
        }
    }
}

/// The result of a chi-square goodness-of-fit test, with everything needed to replay and diagnose it.
#[derive(Clone, Debug)]
pub struct Chi2Outcome {
    /// What was tested: the domain and its grid.
    pub description: String,
    /// The seed of the [`crate::Rng`] handed to the sampling function.
    pub seed: u32,
    /// How many times the sampling function was called.
    pub sample_count: u32,
    /// Samples for which the sampling function returned `None` (absorbed, e.g. by a lossy BSDF).
    pub absorbed_samples: u64,
    /// Samples outside the domain: not finite, not unit length on the sphere, outside [0, 1]² on the
    /// square, or an index past the end in a discrete test.
    pub invalid_samples: u64,
    /// Samples at which the pdf (or pmf) is zero, negative, NaN or infinite: the sampler produced a
    /// value the pdf says it cannot produce.
    pub zero_pdf_samples: u64,
    /// The pdf's integral over the domain (or the pmf's sum); below 1 means absorbed mass.
    pub pdf_integral: f64,
    /// Pearson's statistic Σ (observed − expected)² / expected over the pooled cells.
    pub statistic: f64,
    /// Degrees of freedom: pooled cells − 1.
    pub dof: u32,
    /// Probability of a statistic at least this large if the samples follow the pdf.
    pub p_value: f64,
    /// The significance level the p-value was compared with: 1 − (1 − α)^(1 / test count) (Šidák).
    pub alpha_corrected: f64,
    /// Whether the samples are consistent with the pdf: no invalid or zero-pdf samples, an integral
    /// not above 1, no samples where nothing was expected, and p-value ≥ the corrected level.
    pub passed: bool,
    /// Every reason the test failed (empty if it passed).
    pub failures: Vec<String>,
    /// The cells with the largest terms of the statistic, largest first.
    pub worst_bins: Vec<Chi2Bin>,
}

impl Chi2Outcome {
    /// The multi-line report also printed by `Display`: what was tested, the seed and counts that replay
    /// it, the statistic, p-value and level, failures and the worst cells.
    pub fn report(&self) -> String {
        self.to_string()
    }

    /// One line for check summaries: the verdict, p-value against the corrected level, the
    /// pdf's integral and the sample count and seed that replay it.
    pub fn summary(&self) -> String {
        format!(
            "chi-square {}: p = {:.3} (level {:.1e}), pdf integral {:.4}, {} samples, seed {}",
            if self.passed { "passed" } else { "FAILED" },
            self.p_value,
            self.alpha_corrected,
            self.pdf_integral,
            self.sample_count,
            self.seed
        )
    }
}

impl fmt::Display for Chi2Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let verdict = if self.passed { "passed" } else { "FAILED" };
        writeln!(f, "chi-square test {}: {verdict}", self.description)?;
        writeln!(
            f,
            "  replay: seed {}, {} samples; {} absorbed (None), {} outside the domain, {} where the pdf is not positive",
            self.seed,
            self.sample_count,
            self.absorbed_samples,
            self.invalid_samples,
            self.zero_pdf_samples
        )?;
        writeln!(f, "  pdf integral {:.6}", self.pdf_integral)?;
        writeln!(
            f,
            "  statistic {:.2} with {} degrees of freedom: p-value {:.3e} against level {:.3e}",
            self.statistic, self.dof, self.p_value, self.alpha_corrected
        )?;
        for failure in &self.failures {
            writeln!(f, "  failure: {failure}")?;
        }
        writeln!(f, "  largest deviations (observed vs expected):")?;
        for bin in &self.worst_bins {
            writeln!(
                f,
                "    {}: {} vs {:.2} (term {:.2})",
                bin.label,
                bin.observed,
                bin.expected,
                bin.contribution()
            )?;
        }
        Ok(())
    }
}

/// What a sampling run gathered, before the statistics are computed.
pub(crate) struct Tally {
    pub(crate) description: String,
    pub(crate) observed: Vec<f64>,
    pub(crate) expected: Vec<f64>,
    pub(crate) pdf_integral: f64,
    pub(crate) absorbed_samples: u64,
    pub(crate) invalid_samples: u64,
    pub(crate) zero_pdf_samples: u64,
    pub(crate) failures: Vec<String>,
}

/// The test's settings that the verdict depends on.
pub(crate) struct Verdict {
    pub(crate) seed: u32,
    pub(crate) sample_count: u32,
    pub(crate) min_expected: f64,
    pub(crate) alpha_corrected: f64,
    pub(crate) pdf_integral_tolerance: f64,
}

/// Pools cells whose expected count is below `min_expected` (smallest first, as in Mitsuba's chi2.py)
/// into one, so that the chi-square approximation holds, and computes statistic, dof and p-value.
/// `label(i)` names cell `i` for the report.
pub(crate) fn conclude(
    mut tally: Tally,
    verdict: &Verdict,
    label: impl Fn(usize) -> String,
) -> Chi2Outcome {
    let cells = tally.observed.len();
    if tally.invalid_samples > 0 {
        tally.failures.push(format!(
            "{} samples were outside the domain",
            tally.invalid_samples
        ));
    }
    if tally.zero_pdf_samples > 0 {
        tally.failures.push(format!(
            "{} samples landed where the pdf is zero or not finite",
            tally.zero_pdf_samples
        ));
    }
    if tally.pdf_integral > 1.0 + verdict.pdf_integral_tolerance {
        tally.failures.push(format!(
            "the pdf integrates to {:.6}, more than 1",
            tally.pdf_integral
        ));
    }
    let impossible: Vec<usize> = (0..cells)
        .filter(|&i| tally.expected[i] <= 0.0 && tally.observed[i] > 0.0)
        .collect();
    if !impossible.is_empty() {
        tally.failures.push(format!(
            "{} cells received samples where the pdf integrates to 0, first {}",
            impossible.len(),
            label(impossible[0])
        ));
    }

    let mut order: Vec<usize> = (0..cells).collect();
    order.sort_by(|&i, &j| tally.expected[i].total_cmp(&tally.expected[j]));
    let (mut statistic, mut pooled_cells) = (0.0, 0_u32);
    let (mut pool_observed, mut pool_expected) = (0.0, 0.0);
    for &i in &order {
        let (o, e) = (tally.observed[i], tally.expected[i]);
        if e <= 0.0 {
            continue;
        }
        if e < verdict.min_expected || (pool_expected > 0.0 && pool_expected < verdict.min_expected)
        {
            pool_observed += o;
            pool_expected += e;
        } else {
            statistic += (o - e) * (o - e) / e;
            pooled_cells += 1;
        }
    }
    if pool_expected > 0.0 {
        statistic += (pool_observed - pool_expected).powi(2) / pool_expected;
        pooled_cells += 1;
    }
    let dof = pooled_cells.saturating_sub(1);
    let p_value = if dof > 0 {
        gamma_q(f64::from(dof) / 2.0, statistic / 2.0)
    } else {
        tally
            .failures
            .push("fewer than two cells expect samples: nothing to test".to_owned());
        f64::NAN
    };
    if p_value < verdict.alpha_corrected {
        tally.failures.push(format!(
            "p-value {p_value:.3e} is below the significance level {:.3e}",
            verdict.alpha_corrected
        ));
    }

    let bin = |i: usize| Chi2Bin {
        label: String::new(),
        observed: tally.observed[i],
        expected: tally.expected[i],
    };
    let mut worst: Vec<usize> = (0..cells)
        .filter(|&i| bin(i).contribution() > 0.0)
        .collect();
    worst.sort_by(|&i, &j| bin(j).contribution().total_cmp(&bin(i).contribution()));
    worst.truncate(WORST_BIN_COUNT);
    let worst_bins = worst
        .into_iter()
        .map(|i| Chi2Bin {
            label: label(i),
            ..bin(i)
        })
        .collect();

    Chi2Outcome {
        description: tally.description,
        seed: verdict.seed,
        sample_count: verdict.sample_count,
        absorbed_samples: tally.absorbed_samples,
        invalid_samples: tally.invalid_samples,
        zero_pdf_samples: tally.zero_pdf_samples,
        pdf_integral: tally.pdf_integral,
        statistic,
        dof,
        p_value,
        alpha_corrected: verdict.alpha_corrected,
        passed: tally.failures.is_empty(),
        failures: tally.failures,
        worst_bins,
    }
}
