//! Mitsuba 3's `lanczos` filter: a windowed sinc.

use super::FilterError;
use super::table::{FilterTable, SEGMENTS_PER_PIXEL};
pub use scene::limits::MAX_LANCZOS_LOBES;

/// The Lanczos filter with `lobes` lobes (Mitsuba's default 3), of radius `lobes` pixels:
/// `f₁(x) = sin(πx) sin(πx / lobes) / (πx · πx / lobes)`, 1 at 0, zero beyond the radius.
///
/// Its side lobes alternate in sign, so camera samples are drawn by `|f₁|` and carry the sign
/// (see [`super::Filter::sample_weight`]).
#[derive(Clone, Debug, PartialEq)]
pub struct LanczosFilter {
    lobes: u32,
    table: FilterTable,
}

impl LanczosFilter {
    /// The filter with `lobes` lobes; an error outside `1..=MAX_LANCZOS_LOBES`.
    pub fn new(lobes: u32) -> Result<Self, FilterError> {
        if !(1..=MAX_LANCZOS_LOBES).contains(&lobes) {
            return Err(FilterError {
                parameter: "lanczos lobes",
                value: lobes as f32,
                requirement: "a whole number from 1 to 16",
            });
        }
        let radius = lobes as f32;
        Ok(Self {
            lobes,
            table: FilterTable::new(radius, 2 * SEGMENTS_PER_PIXEL * lobes as usize, |x| {
                eval(radius, x)
            }),
        })
    }

    /// The number of lobes, which is the radius in pixels.
    pub fn lobes(&self) -> u32 {
        self.lobes
    }

    /// The unnormalised filter `f₁(x)` at offset `x` (pixels).
    pub fn eval_1d(&self, x: f32) -> f32 {
        eval(self.lobes as f32, x)
    }

    /// The table the filter is sampled from.
    pub(super) fn table(&self) -> &FilterTable {
        &self.table
    }
}

/// The windowed sinc of radius `radius` at `x`.
fn eval(radius: f32, x: f32) -> f32 {
    let x = x.abs();
    if x < f32::EPSILON {
        return 1.0;
    }
    if x > radius {
        return 0.0;
    }
    let x1 = std::f32::consts::PI * x;
    let x2 = x1 / radius;
    (x1.sin() * x2.sin()) / (x1 * x2)
}
