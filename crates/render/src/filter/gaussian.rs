//! Mitsuba 3's truncated Gaussian filter and its tabulated inverse CDF.

use super::table::FilterTable;

/// Segments of the gaussian's table over `[-4σ, 4σ]`. The linear interpolant differs from the
/// filter by at most `h²/8 · max|f''| = (8σ/512)²/8 · 1/σ² ≈ 3e-5` of the peak, whatever σ.
const SEGMENTS: usize = 512;
use super::{FilterError, check_positive};

/// Mitsuba's `gaussian` reconstruction filter:
/// `f₁(x) = max(0, exp(−x² / (2σ²)) − exp(−r² / (2σ²)))` with radius `r = 4σ`.
///
/// Sampling inverts the CDF of the piecewise-linear interpolant of `f₁` on a table of
/// 512 equal segments exactly (a quadratic per segment).
#[derive(Clone, Debug, PartialEq)]
pub struct GaussianFilter {
    stddev: f32,
    radius: f32,
    table: FilterTable,
}

impl GaussianFilter {
    /// The filter with standard deviation `stddev` (pixels); an error unless positive and finite.
    pub fn new(stddev: f32) -> Result<Self, FilterError> {
        let stddev = check_positive("gaussian stddev", stddev)?;
        let radius = 4.0 * stddev;
        Ok(Self {
            stddev,
            radius,
            table: FilterTable::new(radius, SEGMENTS, |x| eval(stddev, radius, x)),
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
        self.table.pdf(x)
    }

    /// The CDF of [`Self::pdf_1d`] at offset `x`: exactly 0 at and below `-radius`, exactly 1 at
    /// and above `radius`.
    pub fn cdf_1d(&self, x: f32) -> f32 {
        self.table.cdf(x)
    }

    /// Maps `u ∈ [0, 1)` to an offset in `[-radius, radius]` (pixels) with density proportional
    /// to the piecewise-linear interpolant of `f₁`. Monotonic in `u`.
    pub fn sample_1d(&self, u: f32) -> f32 {
        self.table.sample(u)
    }

    /// The table the filter is sampled from.
    pub(super) fn table(&self) -> &FilterTable {
        &self.table
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
