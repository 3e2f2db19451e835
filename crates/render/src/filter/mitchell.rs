//! Mitsuba 3's `mitchell` and `catmullrom` filters: the Mitchell–Netravali family of cubics.

use super::FilterError;
use super::table::{FilterTable, SEGMENTS_PER_PIXEL};

/// The Mitchell–Netravali cubic with parameters `B`, `C` (Mitsuba's `mitchell`, default
/// `B = C = 1/3`; `catmullrom` is `B = 0`, `C = 1/2`), of radius 2 pixels:
///
/// `6 f₁(x) = (12 − 9B − 6C)|x|³ + (−18 + 12B + 6C)|x|² + (6 − 2B)` for `|x| < 1`,
/// `(−B − 6C)|x|³ + (6B + 30C)|x|² + (−12B − 48C)|x| + (8B + 24C)` for `1 ≤ |x| < 2`.
///
/// It dips below zero between 1 and 2 pixels for the usual parameters, so camera samples are
/// drawn by `|f₁|` and carry the sign (see [`super::Filter::sample_weight`]).
#[derive(Clone, Debug, PartialEq)]
pub struct MitchellFilter {
    b: f32,
    c: f32,
    table: FilterTable,
}

/// The support half-width of every Mitchell–Netravali filter, in pixels.
pub const MITCHELL_RADIUS: f32 = 2.0;

impl MitchellFilter {
    /// The cubic with parameters `b` and `c`; an error unless both are finite.
    pub fn new(b: f32, c: f32) -> Result<Self, FilterError> {
        for (parameter, value) in [("mitchell B", b), ("mitchell C", c)] {
            if !value.is_finite() {
                return Err(FilterError {
                    parameter,
                    value,
                    requirement: "finite",
                });
            }
        }
        Ok(Self {
            b,
            c,
            table: FilterTable::new(MITCHELL_RADIUS, 4 * SEGMENTS_PER_PIXEL, |x| eval(b, c, x)),
        })
    }

    /// Mitsuba's `catmullrom`: `B = 0`, `C = 1/2`.
    pub fn catmull_rom() -> Self {
        Self::new(0.0, 0.5).expect("finite parameters")
    }

    /// The parameters `(B, C)`.
    pub fn parameters(&self) -> (f32, f32) {
        (self.b, self.c)
    }

    /// The unnormalised filter `f₁(x)` at offset `x` (pixels); zero at and beyond 2.
    pub fn eval_1d(&self, x: f32) -> f32 {
        eval(self.b, self.c, x)
    }

    /// The table the filter is sampled from.
    pub(super) fn table(&self) -> &FilterTable {
        &self.table
    }
}

/// The Mitchell–Netravali cubic at `x`.
fn eval(b: f32, c: f32, x: f32) -> f32 {
    let x = x.abs();
    let (x2, x3) = (x * x, x * x * x);
    let value = if x < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b)
    } else if x < MITCHELL_RADIUS {
        (-b - 6.0 * c) * x3
            + (6.0 * b + 30.0 * c) * x2
            + (-12.0 * b - 48.0 * c) * x
            + (8.0 * b + 24.0 * c)
    } else {
        0.0
    };
    value / 6.0
}
