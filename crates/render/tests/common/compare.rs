//! Unbiasedness comparisons whose variances come from independent renders, and the proof of
//! their power on deliberately biased inputs.
//!
//! A configuration is rendered `K` times with different seeds ([`Replicates`]), and so is the
//! oracle. The replicates are the independent units: whatever a configuration correlates within
//! one render (path reuse shares paths between the pixels of a block, light tracing splats one
//! light path into several pixels, blue noise and Sobol correlate samples and pixels), two
//! renders with different seeds are independent. So the variance of any sum of pixels is
//! estimated by the spread of that sum over the replicates, never by adding per-pixel variances
//! as if pixels were independent.
//!
//! [`compare`] tests, with Welch's t-test (Satterthwaite's degrees of freedom), the difference of
//! the replicate means of
//!
//! - the **whole image**: the sum of every pixel and channel (one test);
//! - **regions** of [`REGION`] × [`REGION`] pixels, per channel;
//! - **blocks** of [`BLOCK`] × [`BLOCK`] pixels, per channel (aligned to the image, so each is
//!   one block of path reuse's 4 × 4 blocks).
//!
//! The family-wise significance level of one comparison is `alpha` (see the callers): a third of
//! it for each level (Bonferroni), shared by the level's tests with Šidák's correction. Every
//! test must pass: no share of failing blocks is allowed.
//!
//! [`check_unbiased`] also runs the comparison on two biased copies of the configuration, which
//! it must reject: the whole-image test must reject the image × (1 + [`Power::image`]), and the
//! block test a typical block ([`median_block`]) × (1 + [`Power::block`]) ([`POWER`]: 0.5% and
//! 5%, for every comparison of every test). A biased copy scales
//! the replicates' pixel values, so its difference from the unbiased comparison is exact and its
//! rejection shows the test's power on this scene's noise. (Blocks that neither renderer varies,
//! a sky or a light seen directly, would reject any scaling whatever the power: so the power is
//! asked of the level the bias is meant for, and of a typical block.)

use super::render_plan;
use glam::{DVec3, UVec2};
use render::plan::RenderPlan;
use sampling::ztest::{sidak_alpha, welch_two_sided_p_value};
use scene::RenderScene;
use std::fmt;

/// Edge, in pixels, of the coarse regions tested.
pub const REGION: u32 = 8;
/// Edge, in pixels, of the blocks tested (path reuse's largest block).
pub const BLOCK: u32 = 4;
/// The biases a comparison must see (see [`check_unbiased`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Power {
    /// Relative bias of the whole image the whole-image test must reject.
    pub image: f64,
    /// Relative bias of one block the block test must reject.
    pub block: f64,
}

/// The biases every comparison should see: 0.5% of the image, 5% of a block.
pub const POWER: Power = Power {
    image: 0.005,
    block: 0.05,
};
/// Relative standard deviation assumed for `f32` rounding of any sum (a path's value goes
/// through dozens of `f32` operations): it keeps two estimators that agree to rounding, where
/// neither has variance (a sky seen directly), from failing.
const ROUNDING: f64 = 1e-5;

/// Independent renders of one configuration of one scene: per replicate, every pixel's value
/// (linear RGB, row-major).
#[derive(Clone, Debug)]
pub struct Replicates {
    /// The configuration, for messages.
    pub label: String,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Seed of each replicate.
    pub seeds: Vec<u32>,
    /// Samples per pixel asked of each replicate (the mean, with adaptive sampling).
    pub spp: u32,
    images: Vec<Vec<DVec3>>,
}

impl Replicates {
    /// Renders `scene` once per seed with the plan `plan(seed)` asks for (at `spp` samples per
    /// pixel, which is only reported). Panics, naming `label` and the seed, if any sample was NaN
    /// or infinite.
    pub fn render(
        scene: &RenderScene,
        label: &str,
        seeds: impl IntoIterator<Item = u32>,
        spp: u32,
        plan: impl Fn(u32) -> RenderPlan,
    ) -> Self {
        Self::render_with(scene, label, seeds, spp, plan, |_| {})
    }

    /// [`Replicates::render`], handing every render's output to `inspect` (to check or print
    /// what it says besides the image).
    pub fn render_with(
        scene: &RenderScene,
        label: &str,
        seeds: impl IntoIterator<Item = u32>,
        spp: u32,
        plan: impl Fn(u32) -> RenderPlan,
        mut inspect: impl FnMut(&render::driver::RenderOutput),
    ) -> Self {
        let (width, height) = (scene.desc.film.width, scene.desc.film.height);
        let mut seeds_used = Vec::new();
        let mut images = Vec::new();
        for seed in seeds {
            let output = render_plan(scene, &plan(seed), &format!("{label} (seed {seed})"));
            inspect(&output);
            let film = &output.film;
            images.push(
                (0..height)
                    .flat_map(|y| (0..width).map(move |x| UVec2::new(x, y)))
                    .map(|pixel| film.pixel_value(pixel).as_dvec3())
                    .collect(),
            );
            seeds_used.push(seed);
        }
        assert!(
            images.len() >= 2,
            "{label}: a variance needs two replicates"
        );
        Self {
            label: label.to_string(),
            width,
            height,
            seeds: seeds_used,
            spp,
            images,
        }
    }

    /// The exactly known expectation `image` (row-major, `width × height`) as a replicate set
    /// without variance: an oracle computed rather than rendered.
    pub fn exact(label: &str, width: u32, height: u32, image: Vec<DVec3>) -> Self {
        assert_eq!(
            image.len(),
            (width * height) as usize,
            "{label}: image size"
        );
        Self {
            label: label.to_string(),
            width,
            height,
            seeds: vec![0, 0],
            spp: 0,
            images: vec![image.clone(), image],
        }
    }

    /// Number of replicates.
    pub fn count(&self) -> usize {
        self.images.len()
    }

    /// A copy with every pixel of `area` (origin and size, pixels) of every replicate multiplied
    /// by `factor`: a biased input whose expectation is known exactly.
    pub fn scaled_area(&self, origin: UVec2, size: UVec2, factor: f64, label: &str) -> Self {
        let mut copy = self.clone();
        copy.label = label.to_string();
        for image in &mut copy.images {
            for y in origin.y..origin.y + size.y {
                for x in origin.x..origin.x + size.x {
                    image[(y * self.width + x) as usize] *= factor;
                }
            }
        }
        copy
    }

    /// A copy with the whole image multiplied by `factor`.
    pub fn scaled(&self, factor: f64, label: &str) -> Self {
        self.scaled_area(
            UVec2::ZERO,
            UVec2::new(self.width, self.height),
            factor,
            label,
        )
    }

    /// Per replicate, the sum of `unit`'s pixels and channels.
    fn unit_sums(&self, unit: &Unit) -> Vec<f64> {
        self.images
            .iter()
            .map(|image| {
                let mut sum = 0.0;
                for y in unit.origin.y..unit.origin.y + unit.size.y {
                    for x in unit.origin.x..unit.origin.x + unit.size.x {
                        let value = image[(y * self.width + x) as usize];
                        sum += match unit.channel {
                            Some(c) => value[c],
                            None => value.element_sum(),
                        };
                    }
                }
                sum
            })
            .collect()
    }

    /// The mean over replicates of the whole image's mean over pixels and channels.
    pub fn image_mean(&self) -> f64 {
        let unit = Unit::image(self.width, self.height);
        mean_and_variance(&self.unit_sums(&unit)).0 / f64::from(3 * self.width * self.height)
    }

    /// The standard error of the replicate mean of the whole image's sum, relative to that mean.
    pub fn image_relative_error(&self) -> f64 {
        self.relative_error(&Unit::image(self.width, self.height))
    }

    /// The standard error of the replicate mean of `unit`'s sum, relative to that mean.
    fn relative_error(&self, unit: &Unit) -> f64 {
        let (mean, variance) = mean_and_variance(&self.unit_sums(unit));
        (variance / self.count() as f64).sqrt() / mean.abs()
    }

    /// "label: K × spp spp, seeds a–b", for replay messages.
    pub fn replay(&self) -> String {
        format!(
            "{}: {} replicates x {} spp, seeds {}..={}, {}x{}",
            self.label,
            self.count(),
            self.spp,
            self.seeds.first().copied().unwrap_or(0),
            self.seeds.last().copied().unwrap_or(0),
            self.width,
            self.height
        )
    }
}

/// The sample mean and the unbiased sample variance of `values`.
fn mean_and_variance(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
    (mean, variance)
}

/// What a test compares: the sum of a rectangle's pixels, over one channel or all three.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unit {
    /// Top-left pixel.
    pub origin: UVec2,
    /// Width and height, pixels.
    pub size: UVec2,
    /// The channel (0 red, 1 green, 2 blue), or `None` for the sum of all three.
    pub channel: Option<usize>,
}

impl Unit {
    /// The whole image, all channels.
    fn image(width: u32, height: u32) -> Self {
        Self {
            origin: UVec2::ZERO,
            size: UVec2::new(width, height),
            channel: None,
        }
    }
}

/// The levels of a comparison, coarsest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    /// The whole image.
    Image,
    /// [`REGION`] × [`REGION`] regions.
    Region,
    /// [`BLOCK`] × [`BLOCK`] blocks.
    Block,
}

impl Level {
    const ALL: [Level; 3] = [Level::Image, Level::Region, Level::Block];

    /// The units of this level in a `width × height` image (edges that do not fill a whole
    /// region or block are left out).
    fn units(self, width: u32, height: u32) -> Vec<Unit> {
        let edge = match self {
            Level::Image => return vec![Unit::image(width, height)],
            Level::Region => REGION,
            Level::Block => BLOCK,
        };
        let mut units = Vec::new();
        for by in 0..height / edge {
            for bx in 0..width / edge {
                for channel in 0..3 {
                    units.push(Unit {
                        origin: UVec2::new(bx, by) * edge,
                        size: UVec2::splat(edge),
                        channel: Some(channel),
                    });
                }
            }
        }
        units
    }
}

impl fmt::Display for Level {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Level::Image => write!(f, "image"),
            Level::Region => write!(f, "{REGION}x{REGION} regions"),
            Level::Block => write!(f, "{BLOCK}x{BLOCK} blocks"),
        }
    }
}

/// Welch's t-test of one unit.
#[derive(Clone, Copy, Debug)]
pub struct UnitTest {
    /// What was compared.
    pub unit: Unit,
    /// Replicate mean of the configuration minus that of the oracle, relative to the oracle's.
    pub relative_difference: f64,
    /// Standard error of the difference, relative to the oracle's mean.
    pub relative_error: f64,
    /// Welch's t.
    pub t: f64,
    /// Satterthwaite's degrees of freedom (infinite when neither side has variance).
    pub dof: f64,
    /// Two-sided p-value.
    pub p: f64,
}

impl fmt::Display for UnitTest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let channel = match self.unit.channel {
            Some(c) => format!("channel {c}"),
            None => "all channels".to_string(),
        };
        write!(
            f,
            "from pixel {} ({}x{}, {channel}): {:+.3}% ± {:.3}%, t {:+.2}, {:.0} dof, p {:.1e}",
            self.unit.origin,
            self.unit.size.x,
            self.unit.size.y,
            100.0 * self.relative_difference,
            100.0 * self.relative_error,
            self.t,
            self.dof,
            self.p
        )
    }
}

/// Welch's t-test of `unit` between `a` and `b`.
fn unit_test(a: &Replicates, b: &Replicates, unit: Unit) -> UnitTest {
    let (mean_a, var_a) = mean_and_variance(&a.unit_sums(&unit));
    let (mean_b, var_b) = mean_and_variance(&b.unit_sums(&unit));
    let (ka, kb) = (a.count() as f64, b.count() as f64);
    let (va, vb) = (var_a / ka, var_b / kb);
    let rounding = ROUNDING * mean_a.abs().max(mean_b.abs());
    let variance = va + vb + rounding * rounding;
    let difference = mean_a - mean_b;
    let t = difference / variance.sqrt().max(f64::MIN_POSITIVE);
    let dof_denominator = va * va / (ka - 1.0) + vb * vb / (kb - 1.0);
    // Welch–Satterthwaite; never below the smaller sample's own degrees of freedom (its
    // mathematical bound, which rounding of tiny variances could cross).
    let dof = if dof_denominator > 0.0 {
        ((va + vb) * (va + vb) / dof_denominator).max(ka.min(kb) - 1.0)
    } else {
        f64::INFINITY
    };
    let scale = mean_b.abs().max(f64::MIN_POSITIVE);
    UnitTest {
        unit,
        relative_difference: difference / scale,
        relative_error: variance.sqrt() / scale,
        t,
        dof,
        p: welch_two_sided_p_value(t, dof),
    }
}

/// One level's tests.
#[derive(Clone, Debug)]
pub struct LevelOutcome {
    /// Which level.
    pub level: Level,
    /// Number of tests (units × channels).
    pub tests: usize,
    /// Significance level of each test (Šidák over the level's tests).
    pub alpha_each: f64,
    /// The test with the smallest p-value.
    pub worst: UnitTest,
    /// Tests whose p-value is below `alpha_each`.
    pub failed: usize,
}

/// A comparison of a configuration's replicates with an oracle's at every level.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The image, region and block levels, in that order.
    pub levels: Vec<LevelOutcome>,
    /// The family-wise level of the whole comparison.
    pub alpha: f64,
}

impl Comparison {
    /// Whether every test of every level passed.
    pub fn passed(&self) -> bool {
        self.levels.iter().all(|l| l.failed == 0)
    }

    /// The whole-image test.
    pub fn image(&self) -> &UnitTest {
        &self.levels[0].worst
    }
}

impl fmt::Display for Comparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let parts: Vec<String> = self
            .levels
            .iter()
            .map(|l| {
                format!(
                    "{}: {} of {} fail at p < {:.1e}, worst {}",
                    l.level, l.failed, l.tests, l.alpha_each, l.worst
                )
            })
            .collect();
        write!(f, "{}", parts.join("; "))
    }
}

/// `a` against `b` at every level, at the family-wise level `alpha` (see the module
/// documentation). Both must have the same image size.
pub fn compare(a: &Replicates, b: &Replicates, alpha: f64) -> Comparison {
    assert_eq!(
        (a.width, a.height),
        (b.width, b.height),
        "{} and {} differ in size",
        a.label,
        b.label
    );
    let levels = Level::ALL
        .iter()
        .map(|&level| {
            let units = level.units(a.width, a.height);
            let alpha_each = sidak_alpha(alpha / Level::ALL.len() as f64, units.len());
            let tests: Vec<UnitTest> = units.into_iter().map(|u| unit_test(a, b, u)).collect();
            let failed = tests.iter().filter(|t| t.p < alpha_each).count();
            let worst = *tests
                .iter()
                .min_by(|x, y| x.p.total_cmp(&y.p))
                .expect("every level has a unit");
            LevelOutcome {
                level,
                tests: tests.len(),
                alpha_each,
                worst,
                failed,
            }
        })
        .collect();
    Comparison { levels, alpha }
}

/// A typical block: the aligned [`BLOCK`] × [`BLOCK`] block whose standard error (of the
/// difference of `a` and `b`, relative to `b`'s mean, in its best channel) is the median over
/// the blocks where `b`'s mean is not zero.
pub fn median_block(a: &Replicates, b: &Replicates) -> UVec2 {
    let mut blocks: Vec<(f64, UVec2)> = Level::Block
        .units(a.width, a.height)
        .chunks(3)
        .filter_map(|channels| {
            let error = channels
                .iter()
                .map(|&unit| unit_test(a, b, unit))
                .filter(|t| t.relative_error.is_finite() && t.relative_error < 1e300)
                .map(|t| t.relative_error)
                .fold(f64::INFINITY, f64::min);
            error.is_finite().then_some((error, channels[0].origin))
        })
        .collect();
    assert!(!blocks.is_empty(), "{}: every block is black", b.label);
    blocks.sort_by(|x, y| x.0.total_cmp(&y.0));
    blocks[blocks.len() / 2].1
}

/// Checks that `config` agrees with `oracle` on `scene` at the family-wise level `alpha`, and
/// that the test has the power to see two biases of `config` ([`POWER`]): the whole-image test
/// must reject the image × (1 + [`Power::image`]), and the block test must reject the typical
/// block ([`median_block`]) × (1 + [`Power::block`]). Prints one figure line per comparison; the error
/// names the scene, both replicate sets (seeds, spp, size) and the worst unit of each level, to
/// replay it.
pub fn check_unbiased(
    scene: &str,
    config: &Replicates,
    oracle: &Replicates,
    alpha: f64,
) -> Result<(), String> {
    let (image_bias, block_bias) = (POWER.image, POWER.block);
    let replay = format!("{scene}: {}; oracle {}", config.replay(), oracle.replay());
    let mut problems = Vec::new();
    let outcome = compare(config, oracle, alpha);
    let block = median_block(config, oracle);
    let block_unit = |channel| Unit {
        origin: block,
        size: UVec2::splat(BLOCK),
        channel: Some(channel),
    };
    let block_error = (0..3)
        .map(|channel| unit_test(config, oracle, block_unit(channel)).relative_error)
        .fold(f64::INFINITY, f64::min);
    let own_errors = |r: &Replicates| {
        let image = r.relative_error(&Unit::image(r.width, r.height));
        let block = (0..3)
            .map(|channel| r.relative_error(&block_unit(channel)))
            .fold(f64::INFINITY, f64::min);
        format!("{:.3}% and {:.2}%", 100.0 * image, 100.0 * block)
    };
    println!(
        "figure: {scene} / {} vs {}: {} | power: image +{:.1}% is {:.1} standard errors, \
         block from {block} +{:.0}% is {:.1}; standard errors of the image and block: {} {}, \
         {} {}",
        config.label,
        oracle.label,
        outcome,
        100.0 * image_bias,
        image_bias / outcome.image().relative_error,
        100.0 * block_bias,
        block_bias / block_error,
        config.label,
        own_errors(config),
        oracle.label,
        own_errors(oracle),
    );
    if !outcome.passed() {
        problems.push(format!("differs from the oracle: {outcome}"));
    }
    let biased_image = config.scaled(
        1.0 + image_bias,
        &format!("{} x {}", config.label, 1.0 + image_bias),
    );
    let image_outcome = compare(&biased_image, oracle, alpha);
    println!("figure: {scene} / {}: {image_outcome}", biased_image.label);
    if image_outcome.levels[0].failed == 0 {
        problems.push(format!(
            "the whole-image test does not see the bias of `{}` (too little power): {}",
            biased_image.label,
            image_outcome.image()
        ));
    }
    let biased_block = config.scaled_area(
        block,
        UVec2::splat(BLOCK),
        1.0 + block_bias,
        &format!(
            "{} with the block from pixel {block} x {}",
            config.label,
            1.0 + block_bias
        ),
    );
    let block_outcome = compare(&biased_block, oracle, alpha);
    let alpha_each = block_outcome.levels[2].alpha_each;
    let block_tests: Vec<UnitTest> = (0..3)
        .map(|channel| unit_test(&biased_block, oracle, block_unit(channel)))
        .collect();
    println!("figure: {scene} / {}: {block_outcome}", biased_block.label);
    if block_tests.iter().all(|t| t.p >= alpha_each) {
        problems.push(format!(
            "the block test does not see the bias of `{}` (too little power): {}",
            biased_block.label, block_tests[0]
        ));
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(format!("{replay}\n  {}", problems.join("\n  ")))
    }
}
