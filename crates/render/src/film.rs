//! The film: per-pixel sums of radiance samples, from which the mean image and the variance of
//! each pixel's mean are computed.
//!
//! The sums that make the image (of the samples, and of the light paths' splats) are kept
//! exactly, in fixed point ([`ExactSum`]), so that they do not depend on the order of their
//! terms: the samples of a pixel may be summed in one run, or in pieces (disjoint sample ranges
//! rendered by different processes, `strata render --samples`) whose sums are added later
//! (`strata merge`), and the image has the same bits either way. The sums of squares, which only
//! feed variance estimates, are kept in `f64` so that the variance is computed without
//! catastrophic cancellation; they depend on the order of their terms in the last bits.

use glam::{DVec3, UVec2, Vec3};

use crate::image::Image;
use crate::metrics::SizeMismatch;

/// The running sums of one pixel's samples (linear RGB radiance).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSum {
    /// Sum of the sample values, exact (each sample rounded once to the fixed point's step, see
    /// [`ExactSum`]).
    pub sum: ExactSum,
    /// Sum of the squared sample values, per channel.
    pub sum_sq: DVec3,
    /// Number of samples added.
    pub count: u32,
}

impl PixelSum {
    /// Adds one sample value.
    pub fn add(&mut self, value: Vec3) {
        let v = value.as_dvec3();
        self.sum.add(v);
        self.sum_sq += v * v;
        self.count += 1;
    }

    /// Adds another pixel's sums to this one.
    pub fn merge(&mut self, other: &PixelSum) {
        self.sum.merge(&other.sum);
        self.sum_sq += other.sum_sq;
        self.count += other.count;
    }

    /// The mean sample value, or zero when no sample was added.
    pub fn mean(&self) -> Vec3 {
        if self.count == 0 {
            Vec3::ZERO
        } else {
            (self.sum.value() / f64::from(self.count)).as_vec3()
        }
    }

    /// The unbiased sample variance `s²` of the samples (the variance of one sample), per
    /// channel; zero with fewer than two samples.
    pub fn sample_variance(&self) -> DVec3 {
        if self.count < 2 {
            return DVec3::ZERO;
        }
        let n = f64::from(self.count);
        let sum = self.sum.value();
        ((self.sum_sq - sum * sum / n) / (n - 1.0)).max(DVec3::ZERO)
    }

    /// The estimated variance of the mean, `s² / n` ([`Self::sample_variance`] over the sample
    /// count), per channel; zero with fewer than two samples.
    pub fn variance_of_mean(&self) -> Vec3 {
        if self.count < 2 {
            return Vec3::ZERO;
        }
        (self.sample_variance() / f64::from(self.count)).as_vec3()
    }
}

/// Fractional bits of [`ExactSum`]'s fixed point: a resolution of 2⁻⁴⁸ ≈ 3.6e-15 and room for
/// sums up to 2⁷⁹ ≈ 6e23. Sample values (`f32`) of magnitude 2⁻²⁵ ≈ 3e-8 and above are added
/// without any rounding; smaller ones are rounded to the step, which moves a pixel's mean by at
/// most half a step, below `f32` precision for means above about 3e-8. Splats below half the
/// resolution (and, in the splats' sums of squares, splats below about 4e-8) count as zero, so a
/// scene lit at radiances of order 1e-12 would lose its precision; scenes in physical units are
/// many orders of magnitude away from either end.
pub const EXACT_FRACTION_BITS: i32 = 48;

/// A per-channel sum kept exactly, in fixed point with [`EXACT_FRACTION_BITS`] fractional bits,
/// so that it does not depend on the order of its terms: light paths' splats reach a pixel in an
/// order that depends on how the samples were split into passes, a resumed render (whose passes
/// split differently) must give the same bits as an uninterrupted one, and the sums of disjoint
/// sample ranges rendered apart must add up to those of one render of all of them. Each term is
/// rounded to the nearest step once (ties to even); sums saturate instead of wrapping: [`Self::add`]
/// at ±[`SATURATION`], [`Self::merge`] at the `i128` range.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ExactSum(pub [i128; 3]);

/// 1.5 · 2⁵²: adding and subtracting it rounds an `f64` of magnitude below 2⁵¹ to an integer,
/// ties to even, in two additions (where `f64::round` is a library call on baseline x86-64).
const ROUNDING_BIAS: f64 = 6_755_399_441_055_744.0;

/// Where [`ExactSum::add`] saturates: 2¹²⁶ steps, half the `i128` range.
pub const SATURATION: i128 = 1 << 126;

/// `x` rounded to the nearest integer, ties to even, saturated to the `i128` range.
fn round_to_i128(x: f64) -> i128 {
    if x.abs() < 2f64.powi(51) {
        ((x + ROUNDING_BIAS) - ROUNDING_BIAS) as i64 as i128
    } else {
        // `as` saturates; from 2⁵² up every f64 is an integer.
        x.round_ties_even() as i128
    }
}

impl ExactSum {
    /// Adds `value`, rounded to the nearest multiple of the resolution.
    pub fn add(&mut self, value: DVec3) {
        let scale = 2f64.powi(EXACT_FRACTION_BITS);
        for (sum, v) in self.0.iter_mut().zip(value.to_array()) {
            // Non-finite values never reach the film.
            *sum = sum
                .saturating_add(round_to_i128(v * scale))
                .clamp(-SATURATION, SATURATION);
        }
    }

    /// Adds another sum's terms.
    pub fn merge(&mut self, other: &ExactSum) {
        for (sum, o) in self.0.iter_mut().zip(other.0) {
            *sum = sum.saturating_add(o);
        }
    }

    /// The sum, rounded to `f64`.
    pub fn value(&self) -> DVec3 {
        let scale = 2f64.powi(-EXACT_FRACTION_BITS);
        DVec3::from_array(self.0.map(|sum| sum as f64 * scale))
    }
}

/// One pixel's share of the camera samples splatted by a filter wider than a pixel (see
/// [`crate::filter::Splatter`]): the exact sums of the weighted samples `w · L`, of their
/// squares, and of the samples' expected weights `W` and their squares. The pixel's value is
/// `Σ w L / Σ W`, unbiased for the filtered radiance (per pixel, linear RGB).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FilteredSum {
    /// Sum of the weighted samples `w · L`.
    pub sum: ExactSum,
    /// Sum of the weighted samples' squares `(w · L)²`, per channel.
    pub sum_sq: ExactSum,
    /// Sums of the expected weights `W` and of their squares `W²`, in the fixed point of
    /// [`ExactSum`] (units of 2^-[`EXACT_FRACTION_BITS`]).
    pub weight: [i128; 2],
}

impl FilteredSum {
    /// Adds one sample `value` (radiance) with weight `weight` here, from a pixel whose
    /// samples have here the mean weight `expected`: [`Self::add_weighted`] and
    /// [`Self::add_expected`] for one sample (the render adds the two apart).
    #[cfg(test)]
    pub(crate) fn add(&mut self, value: Vec3, weight: f32, expected: f64) {
        self.add_weighted(value, weight);
        self.add_expected(1, expected);
    }

    /// Adds one sample `value` (radiance) with weight `weight` to the weighted sums only.
    pub fn add_weighted(&mut self, value: Vec3, weight: f32) {
        if weight != 0.0 {
            let v = (value * weight).as_dvec3();
            self.sum.add(v);
            self.sum_sq.add(v * v);
        }
    }

    /// Adds the expected weights of `count` samples whose mean weight here is `expected`: each
    /// sample's `W` and `W²` rounded once to the fixed point, so that `count` at once gives the
    /// same bits as one at a time.
    #[inline]
    pub fn add_expected(&mut self, count: u32, expected: f64) {
        let scale = 2f64.powi(EXACT_FRACTION_BITS);
        for (sum, w) in self.weight.iter_mut().zip([expected, expected * expected]) {
            let scaled = w * scale;
            let term = if scaled.abs() < 2f64.powi(51) {
                // A 64 × 64-bit product, which cannot overflow: no library call.
                let rounded = ((scaled + ROUNDING_BIAS) - ROUNDING_BIAS) as i64;
                i128::from(rounded) * i128::from(count)
            } else {
                round_to_i128(scaled).saturating_mul(i128::from(count))
            };
            *sum = sum.saturating_add(term);
        }
    }

    /// Adds another pixel's sums to this one.
    pub fn merge(&mut self, other: &FilteredSum) {
        self.sum.merge(&other.sum);
        self.sum_sq.merge(&other.sum_sq);
        for (sum, o) in self.weight.iter_mut().zip(other.weight) {
            *sum = sum.saturating_add(o);
        }
    }

    /// The samples' summed expected weight `D = Σ W` (dimensionless).
    pub fn total_weight(&self) -> f64 {
        self.weight[0] as f64 * 2f64.powi(-EXACT_FRACTION_BITS)
    }

    /// The pixel's value `Σ w L / Σ W` (radiance), zero before any sample reached it.
    pub fn value(&self) -> Vec3 {
        let total = self.total_weight();
        if total > 0.0 {
            (self.sum.value() / total).as_vec3()
        } else {
            Vec3::ZERO
        }
    }

    /// The estimated variance of [`Self::value`], per channel: `(Σ (wL)² − value² Σ W²) / D²`,
    /// exact for a radiance constant over the filter's footprint (the sample `w L` then varies
    /// only through `w`, whose mean over pixel `q` is `W`), an overestimate where the radiance
    /// varies across it (its spread between pixels is counted as noise).
    pub fn variance(&self) -> Vec3 {
        let total = self.total_weight();
        if total <= 0.0 {
            return Vec3::ZERO;
        }
        let mean = self.sum.value() / total;
        let weight_sq = self.weight[1] as f64 * 2f64.powi(-EXACT_FRACTION_BITS);
        ((self.sum_sq.value() - mean * mean * weight_sq).max(DVec3::ZERO) / (total * total))
            .as_vec3()
    }
}

/// Terms [`SplatSum`] keeps in `i64` before it adds them to its exact sums: each is below 2⁵¹
/// steps, so 2¹² of them cannot overflow.
const MAX_PENDING_TERMS: u32 = 1 << 12;

/// The magnitude below which a weighted sample's six terms (value and square per channel) are
/// all below 2⁵¹ steps of [`EXACT_FRACTION_BITS`], so fit [`SplatSum`]'s pending sums: just
/// under `√8`, since `(√8)² · 2⁴⁸ = 2⁵¹`.
const PENDING_MAGNITUDE: f32 = 2.828;

/// A tile's running [`FilteredSum::add_weighted`] for one pixel during a pass, the hot loop of
/// splatting (25 targets per sample with Mitsuba's gaussian): the six terms of a sample (its
/// weighted value and square per channel) are rounded together and added to `i64` sums, which
/// go into the exact `i128` sums every 4,096 samples and at [`Self::merge_into`].
/// Integer addition being exact, the result has the bits of [`FilteredSum::add_weighted`] for
/// every sample (short of [`SATURATION`], which the two reach in different steps).
#[derive(Clone, Copy, Debug, Default)]
pub struct SplatSum {
    /// Exact sums of `w L` and of `(w L)²` of the terms added or flushed so far.
    exact: [ExactSum; 2],
    /// Pending terms: `w L` per channel, then `(w L)²` per channel, in steps of the fixed point.
    pending: [i64; 6],
    /// Samples in `pending`.
    pending_samples: u32,
    /// Whether `exact` holds anything.
    has_exact: bool,
}

impl SplatSum {
    /// Adds one sample `value` (radiance) with weight `weight`: [`FilteredSum::add_weighted`].
    #[inline]
    pub fn add_weighted(&mut self, value: Vec3, weight: f32) {
        if weight == 0.0 {
            return;
        }
        let weighted = value * weight;
        // One test of magnitude for all six terms, on the three channels: below `√8` a value
        // and its square are both below 2⁵¹ steps. Then each term is rounded by the bias, and
        // its integer read off the bits: `x + bias` has unit spacing, so its bits less the
        // bias's are `x` rounded to the nearest integer, ties to even: the bits of
        // `ExactSum::add`.
        if weighted.abs().max_element() < PENDING_MAGNITUDE {
            let v = weighted.as_dvec3();
            let scale = 2f64.powi(EXACT_FRACTION_BITS);
            let terms = [v.x, v.y, v.z, v.x * v.x, v.y * v.y, v.z * v.z].map(|t| t * scale);
            for (sum, t) in self.pending.iter_mut().zip(terms) {
                *sum += (t + ROUNDING_BIAS).to_bits() as i64 - ROUNDING_BIAS.to_bits() as i64;
            }
            self.pending_samples += 1;
            if self.pending_samples == MAX_PENDING_TERMS {
                self.flush();
            }
        } else {
            self.add_large(weighted.as_dvec3());
        }
    }

    /// Adds a weighted sample `v` with a term too large for the pending sums.
    #[cold]
    #[inline(never)]
    fn add_large(&mut self, v: DVec3) {
        self.has_exact = true;
        self.exact[0].add(v);
        self.exact[1].add(v * v);
    }

    /// Moves the pending terms into the exact sums.
    #[cold]
    #[inline(never)]
    fn flush(&mut self) {
        self.has_exact = true;
        let [sum, sum_sq] = &mut self.exact;
        add_pending(sum, sum_sq, &self.pending);
        self.pending = [0; 6];
        self.pending_samples = 0;
    }

    /// Adds the sums of every sample added here to `sums`.
    #[inline]
    pub fn merge_into(&self, sums: &mut FilteredSum) {
        if self.has_exact {
            sums.sum.merge(&self.exact[0]);
            sums.sum_sq.merge(&self.exact[1]);
        }
        if self.pending_samples > 0 {
            add_pending(&mut sums.sum, &mut sums.sum_sq, &self.pending);
        }
    }
}

/// Adds [`SplatSum`]'s pending terms to the sums of `w L` and `(w L)²`, saturating as
/// [`ExactSum::add`].
fn add_pending(sum: &mut ExactSum, sum_sq: &mut ExactSum, pending: &[i64; 6]) {
    let exact = sum.0.iter_mut().chain(sum_sq.0.iter_mut());
    for (sum, &term) in exact.zip(pending) {
        *sum = sum
            .saturating_add(i128::from(term))
            .clamp(-SATURATION, SATURATION);
    }
}

/// A `width × height` grid of [`PixelSum`]s, row-major, top row first, and the contributions
/// light paths splatted onto it.
///
/// With a filter wider than a pixel the camera samples are splatted too ([`Film::splatting`]):
/// each pixel's value is then its [`FilteredSum`]'s, and its [`PixelSum`] keeps the plain sums
/// of its own samples (unweighted), for their count and for adaptive sampling's noise
/// estimates.
///
/// A pixel's value is the mean of its own samples plus its share of the light paths' splats:
/// with `L` light paths traced for an `N`-pixel image, `N / L · Σ splats` (each light path
/// stands for one pixel sample's worth of light, as in pbrt-v4's light tracer).
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    pixels: Vec<PixelSum>,
    /// Per pixel: the exact sum and sum of squares of the light paths' splats. The variance
    /// estimate treats each splat as one path's whole share of the pixel, which holds unless two
    /// vertices of one path land in the same pixel (rare), and treats pixels as independent,
    /// which a filter wider than a pixel makes them not (a path splats into its neighbours too).
    splat_sum: Vec<ExactSum>,
    splat_sum_sq: Vec<ExactSum>,
    /// Light paths traced, whether or not they splatted anything.
    light_paths: u64,
    /// Per pixel, the camera samples splatted into it; empty unless the film splats camera
    /// samples ([`Film::splatting`]).
    filtered: Vec<FilteredSum>,
}

/// The light paths' share of a film: per pixel the exact sums of their splats and of the
/// squares, and how many paths were traced.
#[derive(Clone, Debug, PartialEq)]
pub struct Splats {
    /// Per pixel, row-major, the sum of the splats.
    pub sums: Vec<ExactSum>,
    /// Per pixel, row-major, the sum of the splats' squares.
    pub sums_sq: Vec<ExactSum>,
    /// Light paths traced, whether or not they splatted anything.
    pub light_paths: u64,
}

impl Film {
    /// An empty film (no samples) of `width × height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Self::from_pixels(
            width,
            height,
            vec![PixelSum::default(); width as usize * height as usize],
        )
        .expect("the pixel count matches")
    }

    /// A film of `width × height` pixels holding `pixels` (row-major, top row first) and no
    /// splats; `None` unless there are exactly `width * height` of them.
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<PixelSum>) -> Option<Self> {
        let count = pixels.len();
        Self::from_parts(
            width,
            height,
            pixels,
            Splats {
                sums: vec![ExactSum::default(); count],
                sums_sq: vec![ExactSum::default(); count],
                light_paths: 0,
            },
        )
    }

    /// A film of `width × height` pixels holding `pixels` and `splats` (each row-major, top
    /// row first); `None` unless each has exactly `width * height` entries.
    pub fn from_parts(
        width: u32,
        height: u32,
        pixels: Vec<PixelSum>,
        splats: Splats,
    ) -> Option<Self> {
        let count = width as usize * height as usize;
        let sizes_match =
            pixels.len() == count && splats.sums.len() == count && splats.sums_sq.len() == count;
        sizes_match.then_some(Self {
            width,
            height,
            pixels,
            splat_sum: splats.sums,
            splat_sum_sq: splats.sums_sq,
            light_paths: splats.light_paths,
            filtered: Vec::new(),
        })
    }

    /// An empty film of `width × height` pixels whose camera samples are splatted by a filter
    /// wider than a pixel ([`Film::add_filtered`]).
    pub fn splatting(width: u32, height: u32) -> Self {
        Self::new(width, height)
            .with_filtered(vec![
                FilteredSum::default();
                width as usize * height as usize
            ])
            .expect("the pixel count matches")
    }

    /// This film with the splatted camera samples `filtered` (row-major, top row first), or
    /// without any when it is empty; `None` unless it is empty or has one entry per pixel.
    pub fn with_filtered(mut self, filtered: Vec<FilteredSum>) -> Option<Self> {
        if !filtered.is_empty() && filtered.len() != self.pixels.len() {
            return None;
        }
        self.filtered = filtered;
        Some(self)
    }

    /// Per pixel (row-major, top row first) the splatted camera samples, or `None` when the
    /// film does not splat them (the box filter: each pixel is the mean of its own samples).
    pub fn filtered(&self) -> Option<&[FilteredSum]> {
        (!self.filtered.is_empty()).then_some(self.filtered.as_slice())
    }

    /// Adds the splatted sums `sums` to `pixel`'s; panics outside the film or when the film does
    /// not splat camera samples.
    pub fn add_filtered(&mut self, pixel: UVec2, sums: &FilteredSum) {
        assert!(!self.filtered.is_empty(), "the film does not splat");
        let i = self.index(pixel);
        self.filtered[i].merge(sums);
    }

    /// Adds a tile's splats into `pixel` ([`Self::add_filtered`] without building the sums).
    pub fn add_splat_sum(&mut self, pixel: UVec2, sums: &SplatSum) {
        assert!(!self.filtered.is_empty(), "the film does not splat");
        let i = self.index(pixel);
        sums.merge_into(&mut self.filtered[i]);
    }

    /// Per pixel (row-major, top row first) the exact sums of the light paths' splats and of
    /// their squares.
    pub fn splat_sums(&self) -> (&[ExactSum], &[ExactSum]) {
        (&self.splat_sum, &self.splat_sum_sq)
    }

    /// Adds one light path's contribution `value` to `pixel`; panics outside the film.
    pub fn add_splat(&mut self, pixel: UVec2, value: Vec3) {
        let i = self.index(pixel);
        let v = value.as_dvec3();
        self.splat_sum[i].add(v);
        self.splat_sum_sq[i].add(v * v);
    }

    /// Counts `paths` more light paths traced (splatting or not).
    pub fn add_light_paths(&mut self, paths: u64) {
        self.light_paths += paths;
    }

    /// Light paths traced into this film.
    pub fn light_paths(&self) -> u64 {
        self.light_paths
    }

    /// The estimate of `pixel`: the mean of its samples (or, when the film splats camera
    /// samples, [`FilteredSum::value`]) plus its share of the light paths' splats.
    pub fn pixel_value(&self, pixel: UVec2) -> Vec3 {
        let i = self.index(pixel);
        self.value(i)
    }

    /// The estimated variance of [`Film::pixel_value`], per channel: the samples' variance of the
    /// mean (or [`FilteredSum::variance`]) plus that of the splat estimate, `N² / L · (Σs²/L − (Σs/L)²)`.
    pub fn pixel_variance(&self, pixel: UVec2) -> Vec3 {
        let i = self.index(pixel);
        self.variance(i)
    }

    fn value(&self, i: usize) -> Vec3 {
        let mean = match self.filtered.get(i) {
            Some(filtered) => filtered.value(),
            None => self.pixels[i].mean(),
        };
        if self.light_paths == 0 {
            return mean;
        }
        mean + (self.splat_sum[i].value() * self.splat_scale()).as_vec3()
    }

    fn variance(&self, i: usize) -> Vec3 {
        let variance = match self.filtered.get(i) {
            Some(filtered) => filtered.variance(),
            None => self.pixels[i].variance_of_mean(),
        };
        if self.light_paths < 2 {
            return variance;
        }
        let paths = self.light_paths as f64;
        let mean = self.splat_sum[i].value() / paths;
        let spread = (self.splat_sum_sq[i].value() / paths - mean * mean).max(DVec3::ZERO);
        variance + (spread * self.splat_scale() * self.splat_scale() * paths).as_vec3()
    }

    /// N / L: what a splat is worth in a pixel's value.
    fn splat_scale(&self) -> f64 {
        self.pixels.len() as f64 / self.light_paths as f64
    }

    /// Every pixel's sums, row-major, top row first.
    pub fn pixels(&self) -> &[PixelSum] {
        &self.pixels
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Row-major index of `pixel`; panics outside the film.
    fn index(&self, pixel: UVec2) -> usize {
        assert!(
            pixel.x < self.width && pixel.y < self.height,
            "pixel {pixel} outside the {}x{} film",
            self.width,
            self.height
        );
        pixel.y as usize * self.width as usize + pixel.x as usize
    }

    /// Adds one sample `value` to `pixel`; panics outside the film.
    pub fn add(&mut self, pixel: UVec2, value: Vec3) {
        let i = self.index(pixel);
        self.pixels[i].add(value);
    }

    /// The sums of `pixel`; panics outside the film.
    pub fn pixel(&self, pixel: UVec2) -> &PixelSum {
        &self.pixels[self.index(pixel)]
    }

    /// Mutable access to the sums of `pixel`; panics outside the film.
    pub fn pixel_mut(&mut self, pixel: UVec2) -> &mut PixelSum {
        let i = self.index(pixel);
        &mut self.pixels[i]
    }

    /// Adds every pixel's sums of `other` to this film's; an error if the sizes differ.
    pub fn merge(&mut self, other: &Film) -> Result<(), SizeMismatch> {
        if (self.width, self.height) != (other.width, other.height) {
            return Err(SizeMismatch {
                a: (self.width, self.height),
                b: (other.width, other.height),
            });
        }
        for (mine, theirs) in self.pixels.iter_mut().zip(&other.pixels) {
            mine.merge(theirs);
        }
        for (mine, theirs) in self.splat_sum.iter_mut().zip(&other.splat_sum) {
            mine.merge(theirs);
        }
        for (mine, theirs) in self.splat_sum_sq.iter_mut().zip(&other.splat_sum_sq) {
            mine.merge(theirs);
        }
        self.light_paths += other.light_paths;
        // A film without splatted samples counts as one whose splatted sums are all zero.
        if self.filtered.is_empty() {
            self.filtered = other.filtered.clone();
        } else {
            for (mine, theirs) in self.filtered.iter_mut().zip(&other.filtered) {
                mine.merge(theirs);
            }
        }
        Ok(())
    }

    /// The image of per-pixel values ([`Film::pixel_value`]; zero where a pixel has neither
    /// samples nor splats).
    pub fn to_image(&self) -> Image {
        self.map_to_image(|i| self.value(i))
    }

    /// The image of per-pixel variances of the values ([`Film::pixel_variance`]), as a per-pixel
    /// z-test against a reference needs.
    pub fn variance_of_mean_image(&self) -> Image {
        self.map_to_image(|i| self.variance(i))
    }

    /// Total number of samples added over all pixels.
    pub fn total_samples(&self) -> u64 {
        self.pixels.iter().map(|p| u64::from(p.count)).sum()
    }

    /// An image with `f` applied to every pixel's index.
    fn map_to_image(&self, f: impl Fn(usize) -> Vec3) -> Image {
        Image {
            width: self.width,
            height: self.height,
            data: (0..self.pixels.len()).map(f).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splats_add_their_share_and_their_variance() {
        // 2 pixels, 4 light paths: pixel 0 gets splats 1 and 3, pixel 1 none. Each splat is
        // worth N / L = 1/2: pixel 0 gains (1 + 3) / 2 = 2. Its splat variance:
        // N² / L · (Σs²/L − (Σs/L)²) = 4/4 · (10/4 − 1) = 1.5.
        let mut film = Film::new(2, 1);
        film.add(UVec2::new(0, 0), Vec3::splat(5.0));
        film.add_splat(UVec2::new(0, 0), Vec3::splat(1.0));
        film.add_splat(UVec2::new(0, 0), Vec3::splat(3.0));
        film.add_light_paths(4);
        assert_eq!(film.pixel_value(UVec2::new(0, 0)), Vec3::splat(7.0));
        assert_eq!(film.pixel_value(UVec2::new(1, 0)), Vec3::ZERO);
        assert_eq!(film.pixel_variance(UVec2::new(0, 0)), Vec3::splat(1.5));
        assert_eq!(film.to_image().pixel(0, 0), Vec3::splat(7.0));
        let mut other = film.clone();
        other.merge(&film).unwrap();
        assert_eq!(other.light_paths(), 8);
        assert_eq!(other.pixel_value(UVec2::new(0, 0)), Vec3::splat(7.0));
    }

    #[test]
    fn exact_sums_do_not_depend_on_the_order_of_their_terms() {
        // Terms over many magnitudes, whose f64 sum depends on the order.
        let terms: Vec<DVec3> = (0..200)
            .map(|k| {
                let k = f64::from(k);
                DVec3::new(1e6 / (k + 1.0), (k * 0.37).sin() * 1e-3, 1.0 + k * 1e-9)
            })
            .collect();
        let (mut forward, mut backward) = (ExactSum::default(), ExactSum::default());
        terms.iter().for_each(|&t| forward.add(t));
        terms.iter().rev().for_each(|&t| backward.add(t));
        assert_eq!(forward, backward);
        let f64_forward: DVec3 = terms.iter().sum();
        let f64_backward: DVec3 = terms.iter().rev().sum();
        assert_ne!(
            f64_forward, f64_backward,
            "the test's terms need an order-dependent f64 sum"
        );
        let error = (forward.value() - f64_forward).abs();
        let bound = f64_forward.abs() * 1e-12 + DVec3::splat(1e-12);
        assert!(error.cmple(bound).all(), "{error} beyond {bound}");
        // Multiples of the resolution are exact, and a merge is a sum.
        let mut half = ExactSum::default();
        half.add(DVec3::new(0.5, -0.25, 3.0));
        let mut twice = half;
        twice.merge(&half);
        assert_eq!(twice.value(), DVec3::new(1.0, -0.5, 6.0));
        // Far past the range, sums saturate instead of wrapping round to the other sign.
        let mut huge = ExactSum::default();
        huge.add(DVec3::splat(1e30));
        huge.add(DVec3::splat(1e30));
        assert!(huge.value().min_element() > 0.0);
    }

    #[test]
    fn a_tiles_splat_sum_has_the_bits_of_plain_exact_adds() {
        let (mut fast, mut plain) = (SplatSum::default(), FilteredSum::default());
        let finish = |fast: &SplatSum| {
            let mut sums = FilteredSum::default();
            fast.merge_into(&mut sums);
            sums
        };
        let cases = [
            (Vec3::new(0.1, -2.5, 1e-20), 0.75),
            (Vec3::new(7.999, 8.0, -8.001), 1.0),
            (Vec3::new(2.827_9, -2.828_1, 2.828_5), 1.0),
            (Vec3::new(1e20, -3.0, 0.5), 0.5),
            (
                Vec3::new(2.5 * 2f32.powi(-48), -2.5 * 2f32.powi(-48), 3e7),
                1.0,
            ),
            (Vec3::new(3e3, 1.0, -1.0), -0.125),
            (Vec3::new(0.3, 0.7, 2.0), 0.0),
        ];
        // Enough samples to flush the pending terms more than once.
        for i in 0..3 * MAX_PENDING_TERMS as usize {
            let (v, w) = cases[i % cases.len()];
            let v = v * (1.0 + i as f32 * 1e-4);
            fast.add_weighted(v, w);
            plain.add_weighted(v, w);
            if i % 997 == 0 {
                assert_eq!(finish(&fast), plain, "{v} × {w} after {i}");
            }
        }
        assert_eq!(finish(&fast), plain);
    }

    #[test]
    fn rounding_to_the_step_is_to_nearest_with_ties_to_even() {
        for (x, rounded) in [
            (2.5, 2),
            (3.5, 4),
            (-2.5, -2),
            (-2.6, -3),
            (0.49999999999999994, 0),
            (2f64.powi(51) + 1.5, (1i128 << 51) + 2),
            (-(2f64.powi(60)), -(1i128 << 60)),
            (1e300, i128::MAX),
            (-1e300, i128::MIN),
        ] {
            assert_eq!(round_to_i128(x), rounded, "{x}");
        }
    }

    #[test]
    fn pieces_of_a_pixel_sample_sequence_add_up_to_the_same_image() {
        // Values whose f64 running sum depends on where it is split: fireflies of 3e7 (an f64
        // step of 2⁻²⁷ there) among values with bits down to 2⁻³⁰.
        let values: Vec<Vec3> = (0..64)
            .map(|k| {
                let small = 1.0 / (k as f32 + 3.0);
                let large = if k % 5 == 0 { 3e7 } else { small };
                Vec3::new(large, small, -large)
            })
            .collect();
        let pixel = UVec2::new(1, 0);
        let mut whole = Film::new(2, 1);
        values.iter().for_each(|&v| whole.add(pixel, v));
        for split in [1, 17, 40] {
            let (mut head, mut tail) = (Film::new(2, 1), Film::new(2, 1));
            values[..split].iter().for_each(|&v| head.add(pixel, v));
            values[split..].iter().for_each(|&v| tail.add(pixel, v));
            tail.merge(&head).unwrap();
            assert_eq!(
                tail.pixel(pixel).sum,
                whole.pixel(pixel).sum,
                "split {split}"
            );
            assert_eq!(tail.to_image(), whole.to_image(), "split {split}");
        }
        let f64_sum = |range: &[Vec3]| range.iter().map(|v| v.as_dvec3()).sum::<DVec3>();
        assert_ne!(
            f64_sum(&values[17..]) + f64_sum(&values[..17]),
            f64_sum(&values),
            "the test needs values whose f64 sum depends on the split"
        );
    }

    #[test]
    fn mean_and_variance_by_hand() {
        let mut film = Film::new(3, 2);
        let p = UVec2::new(2, 1);
        for v in [1.0, 2.0, 6.0] {
            film.add(p, Vec3::new(v, 2.0 * v, 0.0));
        }
        let image = film.to_image();
        // Mean 3; unbiased sample variance ((1−3)² + (2−3)² + (6−3)²) / 2 = 7; of the mean 7/3.
        assert_eq!(image.pixel(2, 1), Vec3::new(3.0, 6.0, 0.0));
        let variance = film.variance_of_mean_image().pixel(2, 1);
        assert!(
            (variance - Vec3::new(7.0 / 3.0, 28.0 / 3.0, 0.0))
                .abs()
                .max_element()
                < 1e-6,
            "{variance}"
        );
        assert_eq!(
            image.pixel(0, 0),
            Vec3::ZERO,
            "a pixel without samples is black"
        );
        assert_eq!(film.variance_of_mean_image().pixel(0, 0), Vec3::ZERO);
        assert_eq!(film.total_samples(), 3);
        assert_eq!(image.data[5], image.pixel(2, 1), "row-major, top row first");
    }

    #[test]
    fn variance_survives_a_large_mean() {
        let mut sums = PixelSum::default();
        for k in 0..1000 {
            sums.add(Vec3::splat(1000.0 + if k % 2 == 0 { 0.5 } else { -0.5 }));
        }
        // Sample variance 0.25 · 1000/999; of the mean, divided by 1000.
        let expected = 0.25 / 999.0;
        assert!(
            (sums.variance_of_mean().x - expected).abs() < 1e-3 * expected,
            "{}",
            sums.variance_of_mean()
        );
    }

    #[test]
    fn merge_equals_adding_all_samples_to_one_film() {
        let (mut a, mut b, mut all) = (Film::new(2, 2), Film::new(2, 2), Film::new(2, 2));
        for (k, pixel) in [
            (0, UVec2::new(0, 0)),
            (1, UVec2::new(1, 1)),
            (2, UVec2::new(0, 0)),
        ] {
            let v = Vec3::new(k as f32, 1.0, 0.5);
            if k % 2 == 0 {
                a.add(pixel, v)
            } else {
                b.add(pixel, v)
            }
            all.add(pixel, v);
        }
        a.merge(&b).unwrap();
        assert_eq!(a, all);
        assert!(a.merge(&Film::new(2, 3)).is_err());
    }

    #[test]
    #[should_panic(expected = "outside the 2x2 film")]
    fn adding_outside_the_film_panics() {
        Film::new(2, 2).add(UVec2::new(2, 0), Vec3::ONE);
    }
}
