//! `cargo xtask crosscheck`: renders scene files with Strata (its reference integrator unless
//! `--integrator` names another preset) and with Mitsuba 3, and compares the two images block by
//! block.
//!
//! Each renderer renders [`RENDERS`] times with different seeds. Per pixel, the variance of the
//! mean of the renders is their sample variance over the number of renders; summing it over an
//! 8 × 8 block gives the variance of the block mean with 64 · (RENDERS − 1) degrees of freedom
//! when pixels are independent. Mitsuba splats each sample into several pixels (tent and
//! gaussian filters), which correlates neighbours; the variance is scaled by a design effect
//! pooled over the image (the spread of the renders' block means against the independent-pixel
//! estimate) so that correlated pixels are not mistaken for disagreement. Strata's path reuse
//! correlates pixels unevenly (fully where a block's first and second vertices are all diffuse,
//! not at all elsewhere), so a block's variance is never taken below the spread of its own
//! renders' block means either. Each block and channel gets a z-score
//! (Strata − Mitsuba) / √(var_S + var_M); it passes when |z| is below the two-sided threshold
//! for α = 0.01 with Šidák correction over all blocks and channels. Needs `pip install mitsuba`.

use render::image::Image;
use render::metrics::{mean, relmse};
use sampling::ztest::{sidak_alpha, two_sided_threshold};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Block edge in pixels.
const BLOCK: u32 = 8;
/// Relative agreement expected in noise-free regions (a constant sky), added to each block's
/// variance: Mitsuba 3 (`scalar_rgb`) gives the sky of radiance (0.3, 0.35, 0.4) as (0.29999977,
/// 0.35000354, 0.39999613), up to 1.0e-5 off in every pixel of every render, which float32
/// rounding of its emitter's colour explains and no sample count averages away.
const NOISELESS_RELATIVE_PRECISION: f64 = 2e-5;
/// Independent renders per renderer (seeds 1, 2, …).
const RENDERS: u32 = 4;
/// Family-wise significance level of the block test.
const ALPHA: f64 = 0.01;
/// Failing blocks printed per scene, worst first.
const SHOWN_FAILURES: usize = 5;

/// Options of one crosscheck run.
pub struct Options {
    /// Scene files to compare.
    pub scenes: Vec<PathBuf>,
    /// Samples per pixel of each of the two renders per renderer.
    pub spp: u32,
    /// Strata's integrator preset (`strata render --integrator`).
    pub integrator: String,
    /// Where the images go.
    pub out_dir: PathBuf,
}

/// One scene's outcome.
struct Outcome {
    scene: String,
    blocks: usize,
    failed: usize,
    max_abs_z: f64,
    /// The failing block-channels, worst first.
    failures: Vec<Failure>,
    relmse: f64,
    mean_strata: f64,
    mean_mitsuba: f64,
}

/// Runs the comparison and prints one line per scene; false if any scene failed.
pub fn run(strata: &Path, options: &Options) -> Result<bool, String> {
    std::fs::create_dir_all(&options.out_dir)
        .map_err(|e| format!("cannot create {}: {e}", options.out_dir.display()))?;
    println!(
        "{:<16} {:>7} {:>7} {:>8} {:>10} {:>10} {:>10}",
        "scene", "blocks", "failed", "max|z|", "relmse", "mean S", "mean M"
    );
    let mut all_passed = true;
    for scene in &options.scenes {
        let outcome = compare(strata, scene, options)?;
        all_passed &= outcome.failed == 0;
        println!(
            "{:<16} {:>7} {:>7} {:>8.2} {:>10.2e} {:>10.5} {:>10.5}",
            outcome.scene,
            outcome.blocks,
            outcome.failed,
            outcome.max_abs_z,
            outcome.relmse,
            outcome.mean_strata,
            outcome.mean_mitsuba
        );
        for failure in outcome.failures.iter().take(SHOWN_FAILURES) {
            println!("  {failure}");
        }
    }
    Ok(all_passed)
}

/// A block and channel whose two means differ beyond the threshold.
struct Failure {
    /// Left and top pixel of the block.
    x: u32,
    y: u32,
    /// 0, 1, 2 for R, G, B.
    channel: usize,
    z: f64,
    mean_strata: f64,
    mean_mitsuba: f64,
    /// Standard deviations of the two means, as the test estimates them.
    sd_strata: f64,
    sd_mitsuba: f64,
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "block at pixel ({}, {}) {}: z {:+.2}, Strata {:.5} ± {:.5}, Mitsuba {:.5} ± {:.5}",
            self.x,
            self.y,
            ["R", "G", "B"][self.channel],
            self.z,
            self.mean_strata,
            self.sd_strata,
            self.mean_mitsuba,
            self.sd_mitsuba
        )
    }
}

fn compare(strata: &Path, scene: &Path, options: &Options) -> Result<Outcome, String> {
    let name = scene
        .file_stem()
        .map_or_else(|| "scene".to_string(), |s| s.to_string_lossy().into_owned());
    let spp = options.spp.to_string();
    let mut strata_images = Vec::new();
    let mut mitsuba_images = Vec::new();
    for seed in 1..=RENDERS {
        let out = options.out_dir.join(format!("{name}-strata-{seed}.exr"));
        let seed_arg = seed.to_string();
        let args = [
            "render",
            path_str(scene)?,
            "--out",
            path_str(&out)?,
            "--integrator",
            &options.integrator,
            "--spp",
            &spp,
            "--seed",
            &seed_arg,
        ];
        run_command(Command::new(strata).args(args))?;
        strata_images.push(read(&out)?);

        let out = options.out_dir.join(format!("{name}-mitsuba-{seed}.exr"));
        let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("mitsuba_render.py");
        run_command(Command::new("python3").args([
            path_str(&script)?,
            path_str(scene)?,
            path_str(&out)?,
            &spp,
            &seed_arg,
        ]))?;
        mitsuba_images.push(read(&out)?);
    }
    let strata_mean = average(&strata_images);
    let mitsuba_mean = average(&mitsuba_images);
    if (strata_mean.width, strata_mean.height) != (mitsuba_mean.width, mitsuba_mean.height) {
        return Err(format!("{name}: the two renderers' images differ in size"));
    }
    let (blocks, failures, max_abs_z) = block_test(&strata_images, &mitsuba_images);
    Ok(Outcome {
        scene: name,
        blocks,
        failed: failures.len(),
        max_abs_z,
        failures,
        relmse: relmse(&strata_mean, &mitsuba_mean).map_err(|e| e.to_string())?,
        mean_strata: mean(&strata_mean),
        mean_mitsuba: mean(&mitsuba_mean),
    })
}

/// (block-channel tests, the failing ones worst first, largest |z|).
fn block_test(strata: &[Image], mitsuba: &[Image]) -> (usize, Vec<Failure>, f64) {
    let (w, h) = (strata[0].width, strata[0].height);
    let blocks_x = w.div_ceil(BLOCK);
    let blocks_y = h.div_ceil(BLOCK);
    let tests = (blocks_x * blocks_y * 3) as usize;
    let threshold = two_sided_threshold(sidak_alpha(ALPHA, tests));
    let strata_blocks = block_statistics(strata, blocks_x, blocks_y);
    let mitsuba_blocks = block_statistics(mitsuba, blocks_x, blocks_y);
    let strata_effect = design_effect(&strata_blocks);
    let mitsuba_effect = design_effect(&mitsuba_blocks);
    let (mut failures, mut max_abs_z) = (Vec::new(), 0.0_f64);
    for (index, (s, m)) in strata_blocks.iter().zip(&mitsuba_blocks).enumerate() {
        let rounding = NOISELESS_RELATIVE_PRECISION * s.mean.abs().max(m.mean.abs());
        let strata_variance = (s.pixel_variance * strata_effect).max(s.block_variance);
        let mitsuba_variance = (m.pixel_variance * mitsuba_effect).max(m.block_variance);
        let variance = strata_variance + mitsuba_variance + rounding * rounding;
        let difference = s.mean - m.mean;
        let z = if variance > 0.0 {
            difference / variance.sqrt()
        } else {
            0.0
        };
        max_abs_z = max_abs_z.max(z.abs());
        if z.abs() > threshold {
            // `block_statistics` orders blocks row by row, three channels each.
            let block = (index / 3) as u32;
            failures.push(Failure {
                x: block % blocks_x * BLOCK,
                y: block / blocks_x * BLOCK,
                channel: index % 3,
                z,
                mean_strata: s.mean,
                mean_mitsuba: m.mean,
                sd_strata: strata_variance.sqrt(),
                sd_mitsuba: mitsuba_variance.sqrt(),
            });
        }
    }
    failures.sort_by(|a, b| b.z.abs().total_cmp(&a.z.abs()));
    (tests, failures, max_abs_z)
}

/// One block and channel of a set of renders.
struct BlockStatistics {
    /// Mean over the renders and the block's pixels.
    mean: f64,
    /// Variance of `mean` assuming independent pixels: Σ per-pixel variance of the mean / n².
    pixel_variance: f64,
    /// Variance of `mean` from the spread of the renders' block means (captures correlation
    /// between pixels, with few degrees of freedom).
    block_variance: f64,
}

fn block_statistics(images: &[Image], blocks_x: u32, blocks_y: u32) -> Vec<BlockStatistics> {
    let mut blocks = Vec::with_capacity((blocks_x * blocks_y * 3) as usize);
    for by in 0..blocks_y {
        for bx in 0..blocks_x {
            for channel in 0..3 {
                blocks.push(block_stats(images, bx, by, channel));
            }
        }
    }
    blocks
}

/// How much correlation between neighbouring pixels inflates a block mean's variance over the
/// independent-pixel estimate, pooled over the image: Σ block variance / Σ pixel variance. About
/// 1 for renderers whose pixels are independent (Strata's filter importance sampling), above 1
/// where samples are splatted into several pixels (Mitsuba's tent and gaussian filters).
fn design_effect(blocks: &[BlockStatistics]) -> f64 {
    let pixel: f64 = blocks.iter().map(|b| b.pixel_variance).sum();
    let block: f64 = blocks.iter().map(|b| b.block_variance).sum();
    if pixel > 0.0 {
        (block / pixel).max(1.0)
    } else {
        1.0
    }
}

/// Statistics of one block and channel over the renders.
fn block_stats(images: &[Image], bx: u32, by: u32, channel: usize) -> BlockStatistics {
    let (w, h) = (images[0].width, images[0].height);
    let k = images.len() as f64;
    let (mut sum, mut variance_sum, mut n) = (0.0, 0.0, 0.0);
    let mut render_sums = vec![0.0; images.len()];
    for y in by * BLOCK..((by + 1) * BLOCK).min(h) {
        for x in bx * BLOCK..((bx + 1) * BLOCK).min(w) {
            let values: Vec<f64> = images
                .iter()
                .map(|i| f64::from(i.pixel(x, y)[channel]))
                .collect();
            let mean = values.iter().sum::<f64>() / k;
            let sample_variance =
                values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (k - 1.0);
            for (total, v) in render_sums.iter_mut().zip(&values) {
                *total += v;
            }
            sum += mean;
            variance_sum += sample_variance / k;
            n += 1.0;
        }
    }
    let block_means: Vec<f64> = render_sums.iter().map(|s| s / n).collect();
    let mean = sum / n;
    let block_variance = block_means
        .iter()
        .map(|b| (b - mean) * (b - mean))
        .sum::<f64>()
        / ((k - 1.0) * k);
    BlockStatistics {
        mean,
        pixel_variance: variance_sum / (n * n),
        block_variance,
    }
}

fn average(images: &[Image]) -> Image {
    let k = images.len() as f32;
    Image::from_fn(images[0].width, images[0].height, |x, y| {
        images.iter().map(|i| i.pixel(x, y)).sum::<glam::Vec3>() / k
    })
}

fn read(path: &Path) -> Result<Image, String> {
    Image::read_exr(path).map_err(|e| e.to_string())
}

fn path_str(path: &Path) -> Result<&str, String> {
    path.to_str()
        .ok_or_else(|| format!("{} is not UTF-8", path.display()))
}

fn run_command(command: &mut Command) -> Result<(), String> {
    let output = command
        .output()
        .map_err(|e| format!("cannot run {command:?}: {e}"))?;
    if output.status.success() {
        Ok(())
    } else {
        Err(format!(
            "{command:?} failed: {}",
            String::from_utf8_lossy(&output.stderr)
        ))
    }
}
