//! Mitsuba 3's truncated Gaussian filter and its tabulated inverse CDF.

use super::{FilterError, check_positive};

/// Number of equal segments of the piecewise-linear table over `[-radius, radius]` (even, so the
/// peak at 0 is a node). The linear interpolant differs from the filter by at most
/// `h²/8 · max|f''| = (8σ/512)²/8 · 1/σ² ≈ 3e-5` of the peak, whatever σ.
const SEGMENTS: usize = 512;

/// Mitsuba's `gaussian` reconstruction filter:
/// `f₁(x) = max(0, exp(−x² / (2σ²)) − exp(−r² / (2σ²)))` with radius `r = 4σ`.
///
/// Sampling inverts the CDF of the piecewise-linear interpolant of `f₁` on a table of
/// 512 equal segments exactly (a quadratic per segment).
#[derive(Clone, Debug, PartialEq)]
pub struct GaussianFilter {
    stddev: f32,
    radius: f32,
    /// `f₁` at the table's nodes `x_i = −r + i·h`.
    values: Vec<f32>,
    /// Normalised CDF of the interpolant at the nodes: `cdf[0] = 0`, `cdf[SEGMENTS] = 1`.
    cdf: Vec<f32>,
    /// Integral of the interpolant over `[-r, r]`, in pixels.
    total: f32,
}

impl GaussianFilter {
    /// The filter with standard deviation `stddev` (pixels); an error unless positive and finite.
    pub fn new(stddev: f32) -> Result<Self, FilterError> {
        let stddev = check_positive("gaussian stddev", stddev)?;
        let radius = 4.0 * stddev;
        let h = 2.0 * f64::from(radius) / SEGMENTS as f64;
        let values: Vec<f32> = (0..=SEGMENTS)
            .map(|i| eval(stddev, radius, (-f64::from(radius) + i as f64 * h) as f32))
            .collect();
        let mut cumulative = Vec::with_capacity(SEGMENTS + 1);
        let mut sum = 0.0f64;
        cumulative.push(0.0);
        for pair in values.windows(2) {
            sum += 0.5 * h * (f64::from(pair[0]) + f64::from(pair[1]));
            cumulative.push(sum);
        }
        let cdf = cumulative.iter().map(|c| (c / sum) as f32).collect();
        Ok(Self {
            stddev,
            radius,
            values,
            cdf,
            total: sum as f32,
        })
    }

    /// Standard deviation in pixels.
    pub fn stddev(&self) -> f32 {
        self.stddev
    }

    /// Support half-width `4σ` in pixels.
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// The unnormalised filter `f₁(x)` at offset `x` (pixels); zero at and beyond the radius.
    pub fn eval_1d(&self, x: f32) -> f32 {
        eval(self.stddev, self.radius, x)
    }

    /// The density (per pixel) of [`Self::sample_1d`] at offset `x`: the piecewise-linear
    /// interpolant of `f₁` divided by its integral; zero outside `(-radius, radius)`.
    pub fn pdf_1d(&self, x: f32) -> f32 {
        let h = 2.0 * self.radius / SEGMENTS as f32;
        let position = (x + self.radius) / h;
        if !(position > 0.0 && position < SEGMENTS as f32) {
            return 0.0;
        }
        let i = (position as usize).min(SEGMENTS - 1);
        let s = position - i as f32;
        let (f0, f1) = (self.values[i], self.values[i + 1]);
        (f0 + (f1 - f0) * s) / self.total
    }

    /// The CDF of [`Self::pdf_1d`] at offset `x`: exactly 0 at and below `-radius`, exactly 1 at
    /// and above `radius`.
    pub fn cdf_1d(&self, x: f32) -> f32 {
        let h = 2.0 * self.radius / SEGMENTS as f32;
        let position = (x + self.radius) / h;
        if position.is_nan() || position <= 0.0 {
            return 0.0;
        }
        if position >= SEGMENTS as f32 {
            return 1.0;
        }
        let i = (position as usize).min(SEGMENTS - 1);
        let s = position - i as f32;
        let (f0, f1) = (self.values[i], self.values[i + 1]);
        let within = h * s * (f0 + 0.5 * (f1 - f0) * s) / self.total;
        (self.cdf[i] + within).min(1.0)
    }

    /// Maps `u ∈ [0, 1)` to an offset in `[-radius, radius]` (pixels) with density proportional
    /// to the piecewise-linear interpolant of `f₁`. Monotonic in `u`.
    pub fn sample_1d(&self, u: f32) -> f32 {
        let u = u.clamp(0.0, 1.0);
        let i = self.cdf.partition_point(|&c| c <= u).clamp(1, SEGMENTS) - 1;
        let h = 2.0 * self.radius / SEGMENTS as f32;
        let (f0, f1) = (self.values[i], self.values[i + 1]);
        // Mass to cover inside the segment, divided by the segment width.
        let m = ((u - self.cdf[i]) * self.total / h).max(0.0);
        // Solve h·(f0·s + (f1 − f0)·s²/2) = m·h for s ∈ [0, 1] in the cancellation-free form.
        let denom = f0 + (f0 * f0 + 2.0 * (f1 - f0) * m).max(0.0).sqrt();
        let s = if denom > 0.0 {
            (2.0 * m / denom).min(1.0)
        } else {
            0.0
        };
        -self.radius + (i as f32 + s) * h
    }
}

impl Default for GaussianFilter {
    /// Mitsuba's default standard deviation, 0.5 pixels.
    fn default() -> Self {
        Self::new(0.5).expect("0.5 is a positive, finite standard deviation")
    }
}

/// `max(0, exp(−x²/(2σ²)) − exp(−r²/(2σ²)))`.
fn eval(stddev: f32, radius: f32, x: f32) -> f32 {
    let alpha = -1.0 / (2.0 * stddev * stddev);
    ((alpha * x * x).exp() - (alpha * radius * radius).exp()).max(0.0)
}
