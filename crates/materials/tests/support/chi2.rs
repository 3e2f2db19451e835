//! Pearson chi-square goodness-of-fit test of a direction sampler against the density it claims,
//! over the unit sphere binned on a (cos θ, φ) grid (equal solid angle per bin).
//!
//! A private stand-in for the shared `sampling::chi2` harness, with the same call shape
//! (`chi2_test(Chi2Domain::Sphere, sample, pdf, &Chi2Config)`), so the tests can switch to it by
//! changing their imports. Following Mitsuba's `chi2.py`: expected counts are the pdf integrated
//! over each bin (Gauss–Legendre, 5 × 5 nodes per bin) times the sample count; bins with expected
//! count below `min_expected` are pooled; a sample in a bin of zero expected count fails at once;
//! the p-value of the statistic is compared with the stated significance level.

use glam::Vec3;
use sampling::Rng;
use std::f64::consts::TAU;

/// The domain the samples live on; only the sphere of directions is needed here.
pub enum Chi2Domain {
    /// Unit directions, binned by (cos θ, φ) about +z.
    Sphere,
}

/// Resolution, sample count, seed and significance of one test.
#[derive(Clone, Debug)]
pub struct Chi2Config {
    /// Bins in cos θ over [−1, 1] (even, so that the equator is a bin edge).
    pub cos_theta_bins: usize,
    /// Bins in φ over [0, 2π) (even, so that φ = 0 and φ = π are bin edges).
    pub phi_bins: usize,
    /// Number of calls to the sampler (failed samples count towards it).
    pub sample_count: usize,
    /// Seed of the `Rng` handed to the sampler.
    pub seed: u32,
    /// Significance level: the test fails when the p-value is below it.
    pub significance: f64,
    /// Bins expecting fewer samples than this are pooled into one.
    pub min_expected: f64,
}

impl Default for Chi2Config {
    fn default() -> Self {
        Self {
            cos_theta_bins: 128,
            phi_bins: 256,
            sample_count: 1_000_000,
            seed: 1,
            significance: 0.01,
            min_expected: 5.0,
        }
    }
}

/// What one test found; `failure` is `None` when the sampler matches the pdf.
#[derive(Debug)]
pub struct Chi2Outcome {
    /// Pearson's statistic over the (pooled) bins.
    pub statistic: f64,
    /// Degrees of freedom: bins used minus one.
    pub dof: usize,
    /// Probability of a statistic at least this large if the sampler matches the pdf.
    pub p_value: f64,
    /// ∫ pdf dω over the sphere by the bin quadrature (≤ 1; < 1 when samples can fail).
    pub pdf_integral: f64,
    /// Fraction of sampler calls that returned a direction.
    pub valid_fraction: f64,
    /// Why the test failed, with the config and worst bins for replay.
    pub failure: Option<String>,
}

const GAUSS_LEGENDRE_5: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// Runs the test: draws `config.sample_count` samples from `sample` (given one `Rng` seeded with
/// `config.seed`), bins them, and compares with `pdf` (density per steradian) integrated per bin.
pub fn chi2_test(
    domain: Chi2Domain,
    mut sample: impl FnMut(&mut Rng) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f32,
    config: &Chi2Config,
) -> Chi2Outcome {
    let Chi2Domain::Sphere = domain;
    let (nt, np) = (config.cos_theta_bins, config.phi_bins);
    let bin_of = |w: Vec3| -> usize {
        let w = w.as_dvec3().normalize();
        let t = (((w.z + 1.0) * 0.5 * nt as f64) as usize).min(nt - 1);
        let mut phi = w.y.atan2(w.x);
        if phi < 0.0 {
            phi += TAU;
        }
        let p = ((phi / TAU * np as f64) as usize).min(np - 1);
        t * np + p
    };

    let mut observed = vec![0.0_f64; nt * np];
    let mut rng = Rng::new(config.seed);
    let mut valid = 0usize;
    let mut bad_samples = Vec::new();
    for index in 0..config.sample_count {
        if let Some(w) = sample(&mut rng) {
            if !w.is_finite() || (w.length() - 1.0).abs() > 1e-3 {
                bad_samples.push(format!("sample #{index}: {w} is not a unit vector"));
                continue;
            }
            observed[bin_of(w)] += 1.0;
            valid += 1;
        }
    }

    let expected = integrate_bins(&pdf, nt, np, config.sample_count as f64);
    let pdf_integral = expected.iter().sum::<f64>() / config.sample_count as f64;
    let valid_fraction = valid as f64 / config.sample_count as f64;

    let mut failure = None;
    if !bad_samples.is_empty() {
        failure = Some(format!(
            "{} invalid samples, first: {}",
            bad_samples.len(),
            bad_samples[0]
        ));
    }
    if pdf_integral > 1.001 {
        failure = Some(format!("pdf integrates to {pdf_integral} > 1"));
    }

    // Pool the bins with small expected counts, as Mitsuba's chi2.py does.
    let mut order: Vec<usize> = (0..nt * np).collect();
    order.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]));
    let (mut statistic, mut bins_used) = (0.0, 0usize);
    let (mut pooled_obs, mut pooled_exp) = (0.0, 0.0);
    for &i in &order {
        let (obs, exp) = (observed[i], expected[i]);
        if exp <= 0.0 {
            if obs > 0.0 && failure.is_none() {
                failure = Some(format!(
                    "{obs} samples in bin {} (around {}) where the pdf is zero",
                    i,
                    bin_centre(i, nt, np)
                ));
            }
        } else if exp < config.min_expected
            || (pooled_exp > 0.0 && pooled_exp < config.min_expected)
        {
            pooled_obs += obs;
            pooled_exp += exp;
        } else {
            statistic += (obs - exp) * (obs - exp) / exp;
            bins_used += 1;
        }
    }
    if pooled_exp > 0.0 {
        statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        bins_used += 1;
    }
    let dof = bins_used.saturating_sub(1).max(1);
    let p_value = chi_square_survival(statistic, dof as f64);

    if failure.is_none() && p_value < config.significance {
        let mut worst: Vec<usize> = (0..nt * np).filter(|&i| expected[i] > 0.0).collect();
        worst.sort_by(|&a, &b| {
            let da = (observed[a] - expected[a]).powi(2) / expected[a];
            let db = (observed[b] - expected[b]).powi(2) / expected[b];
            db.total_cmp(&da)
        });
        let lines: Vec<String> = worst
            .iter()
            .take(5)
            .map(|&i| {
                format!(
                    "  bin {i} around {}: observed {}, expected {:.1}",
                    bin_centre(i, nt, np),
                    observed[i],
                    expected[i]
                )
            })
            .collect();
        failure = Some(format!(
            "p-value {p_value:.3e} < significance {} (chi2 {statistic:.1}, dof {dof}); worst bins:\n{}",
            config.significance,
            lines.join("\n")
        ));
    }
    if let Some(message) = failure.as_mut() {
        message.push_str(&format!(
            "\n  replay: {config:?}; pdf integral {pdf_integral:.5}, valid fraction {valid_fraction:.5}"
        ));
    }

    Chi2Outcome {
        statistic,
        dof,
        p_value,
        pdf_integral,
        valid_fraction,
        failure,
    }
}

/// Expected counts per bin: `scale` · ∫_bin pdf d(cos θ) dφ by 5 × 5 Gauss–Legendre nodes.
fn integrate_bins(pdf: &impl Fn(Vec3) -> f32, nt: usize, np: usize, scale: f64) -> Vec<f64> {
    let dz = 2.0 / nt as f64;
    let dphi = TAU / np as f64;
    let mut expected = vec![0.0; nt * np];
    for t in 0..nt {
        for p in 0..np {
            let mut sum = 0.0;
            for (xz, wz) in GAUSS_LEGENDRE_5 {
                let z = -1.0 + (t as f64 + 0.5 + 0.5 * xz) * dz;
                let r = (1.0 - z * z).max(0.0).sqrt();
                for (xp, wp) in GAUSS_LEGENDRE_5 {
                    let phi = (p as f64 + 0.5 + 0.5 * xp) * dphi;
                    let w = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                    sum += wz * wp * f64::from(pdf(w));
                }
            }
            // The nodes' weights sum to 2 per axis on [−1, 1]; the bin is dz × dphi.
            expected[t * np + p] = sum * 0.25 * dz * dphi * scale;
        }
    }
    expected
}

/// The direction at the centre of bin `i`, for messages.
fn bin_centre(i: usize, nt: usize, np: usize) -> Vec3 {
    let (t, p) = (i / np, i % np);
    let z = -1.0 + (t as f64 + 0.5) * 2.0 / nt as f64;
    let phi = (p as f64 + 0.5) * TAU / np as f64;
    let r = (1.0 - z * z).sqrt();
    Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32)
}

/// P(X ≥ x) for X chi-square distributed with `dof` degrees of freedom: Q(dof/2, x/2).
fn chi_square_survival(x: f64, dof: f64) -> f64 {
    regularized_gamma_q(0.5 * dof, 0.5 * x)
}

/// The regularised upper incomplete gamma function Q(a, x), by its series for x < a + 1 and its
/// continued fraction otherwise (Numerical Recipes §6.2).
fn regularized_gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let log_prefactor = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        let (mut term, mut sum, mut ap) = (1.0 / a, 1.0 / a, a);
        for _ in 0..100_000 {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * log_prefactor.exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..100_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let delta = d * c;
            h *= delta;
            if (delta - 1.0).abs() < 1e-15 {
                break;
            }
        }
        log_prefactor.exp() * h
    }
}

/// ln Γ(x) for x > 0 by the Lanczos approximation (g = 7, 9 terms; ~1e-15 relative error).
fn ln_gamma(x: f64) -> f64 {
    const COEFFICIENTS: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let mut sum = COEFFICIENTS[0];
    for (i, c) in COEFFICIENTS.iter().enumerate().skip(1) {
        sum += c / (x + i as f64);
    }
    let t = x + 7.5;
    0.5 * TAU.ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

/// Self-checks of the statistics, so a broken p-value cannot make every test pass.
#[test]
fn chi_square_survival_matches_tables() {
    // Upper-tail critical values: P(X ≥ x) for the given dof (standard chi-square tables).
    let table = [
        (1.0, 6.635, 0.01),
        (10.0, 23.209, 0.01),
        (10.0, 2.558, 0.99),
        (100.0, 135.807, 0.01),
        (1000.0, 1106.969, 0.01),
    ];
    for (dof, x, p) in table {
        let q = chi_square_survival(x, dof);
        assert!((q - p).abs() < 1e-2 * p, "dof {dof}, x {x}: {q} vs {p}");
    }
    assert!((ln_gamma(5.0) - 24.0_f64.ln()).abs() < 1e-12);
    assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-12);
}
