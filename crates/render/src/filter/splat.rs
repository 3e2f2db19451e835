//! Splatting camera samples into every pixel that a filter wider than a pixel covers, as
//! Mitsuba 3 and pbrt-v4 reconstruct pixels, with an estimator that is unbiased rather than
//! only consistent.
//!
//! Each camera sample of pixel `q` is taken at a film position `x` uniform in `q` (the sampler's
//! pixel dimensions, so stratified, blue-noise and Sobol patterns stay stratified) and counts
//! towards every pixel `p` with the weight `w_p(x) = f(x − centre(p)) / ∫_image f(y − centre(p))
//! dy` ([`Filter::pixel_weight`]). With `n(q)` samples in pixel `q`,
//!
//! `I_p = Σ_s w_p(x_s) L_s / D_p`,  `D_p = Σ_s W(q_s → p)`,  `W(q → p) = ∫_q w_p(x) dx`,
//!
//! where the sums run over all samples `s` (of all pixels) and `q_s` is the pixel sample `s`
//! belongs to. `D_p = Σ_q n(q) W(q → p)` is not random: it depends only on the sample counts.
//! So `E[I_p] = Σ_q n(q) ∫_q w_p L / D_p`, which with equal counts `n` is `n ∫_image w_p L / n`,
//! exactly the filtered pixel value `∫ f L / ∫ f` that filter importance sampling and Mitsuba
//! estimate (the partition of unity `Σ_q W(q → p) = 1` holds up to `f32` rounding, 1e-7). With
//! unequal counts (adaptive sampling) each sample instead weighs `1 / k(q)`, where pixel `q`
//! takes `k(q)` samples in each of `t` whole rounds ([`crate::adaptive::Allocation::in_rounds`]):
//! then `n(q) / k(q) = t` for every pixel and the same argument gives the filtered value again,
//! where Mitsuba's ratio `Σ f L / Σ f` would converge to the density-weighted value of `f · n`.
//!
//! Against filter importance sampling, where each pixel averages only its own samples, every
//! pixel now averages about `(2 · radius)²` pixels' samples weighted by the filter: for
//! Mitsuba's default gaussian (standard deviation 0.5 pixels) the variance of a pixel, where
//! the path noise dominates, falls to about `∫f² / (∫f)² ≈ 1/3` of the importance-sampled one.
//!
//! All offsets, radii and positions are in pixels.

use glam::{UVec2, Vec2};

use super::Filter;
use super::table::FilterTable;

/// The most pixels a sample reaches along one axis on either side of its own:
/// [`Splatter::new`] declines filters that reach further (tents or gaussians wider than
/// 16 pixels), which keep filter importance sampling.
pub const MAX_SPLAT_REACH: u32 = 16;

/// Most pixels along one axis that one sample reaches.
const MAX_SPAN: usize = 2 * MAX_SPLAT_REACH as usize + 1;

/// A filter's splat weights for one image size, tabulated per axis.
#[derive(Clone, Debug)]
pub struct Splatter {
    filter: Filter,
    density: SignedDensity,
    columns: AxisWeights,
    rows: AxisWeights,
}

/// A splatted filter's signed density `f₁ / ∫|f₁|` (per pixel) as its table
/// ([`FilterTable::signed_pdf`]), which is [`Filter::signed_pdf_1d`] without a dispatch on the
/// filter for each of the `2 · (2 reach + 1)` weights of every camera sample: the filters'
/// own tables, and the tent's as its three nodes (exact, the tent being linear between them).
#[derive(Clone, Debug)]
struct SignedDensity {
    table: FilterTable,
    /// Half-width of the support, in pixels.
    radius: f32,
}

impl SignedDensity {
    /// The density of a filter wider than a pixel; `None` for the box filter.
    fn new(filter: &Filter) -> Option<Self> {
        let table = match filter {
            Filter::Box => return None,
            Filter::Tent { radius } => FilterTable::new(*radius, 2, |x| filter.eval_1d(x)),
            Filter::Gaussian(g) => g.table().clone(),
            Filter::Mitchell(m) => m.table().clone(),
            Filter::Lanczos(l) => l.table().clone(),
        };
        Some(Self {
            table,
            radius: filter.radius(),
        })
    }

    /// The density at offset `x` (pixels); zero outside `(-radius, radius)`.
    #[inline]
    fn at(&self, x: f32) -> f32 {
        self.table.signed_pdf(x)
    }

    /// The densities at `x`, `x − 1`, … into `out`, as [`Self::at`] up to `f32` rounding, in
    /// one look-up of the position within a segment where the table allows
    /// ([`FilterTable::signed_pdf_steps`]); `false`, writing nothing, where it does not.
    #[inline]
    fn at_steps(&self, x: f32, out: &mut [f32]) -> bool {
        self.table.signed_pdf_steps(x, out)
    }
}

/// The splat weights along one image axis.
#[derive(Clone, Debug)]
struct AxisWeights {
    /// Pixels along the axis.
    size: u32,
    /// Pixels a sample reaches on either side of its own.
    reach: u32,
    /// Per target pixel: one over the signed filter's integral over the image, measured from
    /// the pixel's centre, in units of the filter's own normalisation (per pixel).
    inv_mass: Vec<f32>,
    /// Per source pixel `q`, `2 reach + 1` entries: `W₁(q → q + k − reach)`, the mean weight
    /// along this axis of a position uniform in `q` for the target `k − reach` pixels away
    /// (zero outside the image).
    expected: Vec<f64>,
}

impl AxisWeights {
    fn new(filter: &Filter, size: u32, reach: u32) -> Self {
        let centre = |p: u32| p as f32 + 0.5;
        let inv_mass: Vec<f32> = (0..size)
            .map(|p| {
                let c = centre(p);
                let mass = filter.signed_cdf_1d(size as f32 - c) - filter.signed_cdf_1d(-c);
                if mass != 0.0 { 1.0 / mass } else { 0.0 }
            })
            .collect();
        let span = 2 * reach as usize + 1;
        let mut expected = vec![0.0; size as usize * span];
        for q in 0..size {
            for k in 0..span {
                let p = i64::from(q) + k as i64 - i64::from(reach);
                if p < 0 || p >= i64::from(size) {
                    continue;
                }
                let c = centre(p as u32);
                let cell =
                    filter.signed_cdf_1d(q as f32 + 1.0 - c) - filter.signed_cdf_1d(q as f32 - c);
                expected[q as usize * span + k] = f64::from(cell) * f64::from(inv_mass[p as usize]);
            }
        }
        Self {
            size,
            reach,
            inv_mass,
            expected,
        }
    }

    /// Writes the weights of a position `x` in source pixel `q` for its targets to `weights`
    /// (from target `first` on) and returns `(first, count)`.
    #[inline]
    fn targets(
        &self,
        density: &SignedDensity,
        x: f32,
        q: u32,
        weights: &mut [f32; MAX_SPAN],
    ) -> (u32, usize) {
        // Only the pixels whose centres lie inside the filter's open support, `p + 0.5` in
        // `(x − radius, x + radius)`: as many each time (4 of the 5 within reach for a
        // gaussian of radius 2) unless a centre lies on the support's edge, so the splat loops
        // run a fixed number of times where a test for zero weights would be mispredicted. The
        // pixels left out have weight zero. Floors by truncating positive numbers, relative to
        // pixel `q − reach − 1` (`f32::floor` is a library call on baseline x86-64).
        let base = i64::from(q) - i64::from(self.reach) - 1;
        let relative = x - base as f32 - 0.5;
        let first = (base + (relative - density.radius) as i64 + 1)
            .max(i64::from(q.saturating_sub(self.reach))) as u32;
        let last = (base + (relative + density.radius) as i64)
            .min(i64::from((q + self.reach).min(self.size - 1))) as u32;
        let masses = self
            .inv_mass
            .get(first as usize..=last as usize)
            .unwrap_or(&[]);
        let weights = &mut weights[..masses.len()];
        // The first target's centre lies furthest left of `x`, each next one a pixel closer.
        if !density.at_steps(x - (first as f32 + 0.5), weights) {
            for (weight, p) in weights.iter_mut().zip(first..) {
                *weight = density.at(x - (p as f32 + 0.5));
            }
        }
        for (weight, &inv_mass) in weights.iter_mut().zip(masses) {
            *weight *= inv_mass;
        }
        (first, masses.len())
    }
}

impl Splatter {
    /// The splat weights of `filter` on a `width × height` image; `None` for the box filter (a
    /// sample stays in its pixel, filter importance sampling is exact and costs nothing), for
    /// filters reaching more than [`MAX_SPLAT_REACH`] pixels, and for an empty image.
    pub fn new(filter: &Filter, width: u32, height: u32) -> Option<Self> {
        let density = SignedDensity::new(filter)?;
        if width == 0 || height == 0 {
            return None;
        }
        // A position in pixel q is less than `radius` from the centres of pixels q − k with
        // k < radius + 0.5.
        let reach = (filter.radius() + 0.5).ceil() as u32 - 1;
        if reach > MAX_SPLAT_REACH {
            return None;
        }
        Some(Self {
            filter: filter.clone(),
            density,
            columns: AxisWeights::new(filter, width, reach),
            rows: AxisWeights::new(filter, height, reach),
        })
    }

    /// Pixels a sample reaches on either side of its own pixel, along each axis.
    pub fn reach(&self) -> u32 {
        self.columns.reach
    }

    /// The filter splatted.
    pub fn filter(&self) -> &Filter {
        &self.filter
    }

    /// Image width and height in pixels.
    pub fn size(&self) -> UVec2 {
        UVec2::new(self.columns.size, self.rows.size)
    }

    /// Calls `visit(first, weight_y, weights_x)` for every row of pixels that a camera sample of
    /// `source` at the film position `film` (pixels, inside `source`) counts towards, top row
    /// first: the row's pixels are `first + (i, 0)` for each `i` of `weights_x`, and pixel
    /// `first + (i, 0)` takes the weight `weights_x[i] · weight_y`, which is
    /// [`Filter::pixel_weight`] (per square pixel, up to rounding). The pixels are those inside
    /// the image whose centres lie inside the filter's support around `film`; all others have
    /// weight zero. Rows rather than pixels, so that a caller finds a row's sums once and the
    /// weight of the row once. The sample's expected weights, which depend only on `source`,
    /// are [`Self::for_each_expected`]'s.
    #[inline]
    pub fn splat(&self, film: Vec2, source: UVec2, mut visit: impl FnMut(UVec2, f32, &[f32])) {
        let mut wx = [0.0; MAX_SPAN];
        let mut wy = [0.0; MAX_SPAN];
        let (x0, nx) = self
            .columns
            .targets(&self.density, film.x, source.x, &mut wx);
        let (y0, ny) = self.rows.targets(&self.density, film.y, source.y, &mut wy);
        for (y, &weight_y) in (y0..).zip(&wy[..ny]) {
            visit(UVec2::new(x0, y), weight_y, &wx[..nx]);
        }
    }

    /// Calls `visit(pixel, expected)` for every pixel within [`Self::reach`] of `source` inside
    /// the image, with the mean weight there of a position uniform in `source`
    /// (`W(source → pixel)` of the module documentation). Row by row, left to right.
    pub fn for_each_expected(&self, source: UVec2, mut visit: impl FnMut(UVec2, f64)) {
        let (columns, rows) = (&self.columns, &self.rows);
        let span = |axis: &AxisWeights, q: u32| {
            let first = q.saturating_sub(axis.reach);
            let last = (q + axis.reach).min(axis.size - 1);
            let row = 2 * axis.reach as usize + 1;
            let base = q as usize * row + (first + axis.reach - q) as usize;
            (first..=last, base)
        };
        let (xs, x_base) = span(columns, source.x);
        let (ys, y_base) = span(rows, source.y);
        for (j, y) in ys.enumerate() {
            let ey = rows.expected[y_base + j];
            for (i, x) in xs.clone().enumerate() {
                visit(UVec2::new(x, y), columns.expected[x_base + i] * ey);
            }
        }
    }

    /// A film position uniform in `pixel` for the sampler's `u ∈ [0, 1)²`: `pixel + u`, kept
    /// inside the pixel where `f32` rounding would put it on the next pixel's edge.
    pub fn film_position(pixel: UVec2, u: Vec2) -> Vec2 {
        let corner = pixel.as_vec2();
        (corner + u).min((corner + Vec2::ONE).map(f32::next_down))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_splat_density_is_the_filters_signed_density() {
        let filters = [
            Filter::tent(1.0).unwrap(),
            Filter::tent(1.7).unwrap(),
            Filter::gaussian(0.5).unwrap(),
            Filter::gaussian(0.3).unwrap(),
            Filter::mitchell(1.0 / 3.0, 1.0 / 3.0).unwrap(),
            Filter::catmull_rom(),
            Filter::lanczos(3).unwrap(),
        ];
        for filter in &filters {
            let density = SignedDensity::new(filter).expect("a filter wider than a pixel");
            let reach = filter.radius() + 0.5;
            let peak = filter.signed_pdf_1d(0.0);
            // Offsets over the support and beyond it, off the nodes.
            for k in 0..=4000 {
                let x = -reach + 2.0 * reach * (k as f32 + 0.37) / 4001.0;
                let (ours, expected) = (density.at(x), filter.signed_pdf_1d(x));
                assert!(
                    (ours - expected).abs() <= 1e-5 * peak,
                    "{filter:?} at {x}: {ours} against {expected}"
                );
            }
        }
        assert!(SignedDensity::new(&Filter::Box).is_none());
    }

    #[test]
    fn densities_a_pixel_apart_are_found_together_where_the_table_allows() {
        // Whole nodes per pixel: Mitsuba's gaussian, the cubics, Lanczos, the unit tent.
        let stepped = [
            Filter::gaussian(0.5).unwrap(),
            Filter::mitchell(1.0 / 3.0, 1.0 / 3.0).unwrap(),
            Filter::lanczos(3).unwrap(),
            Filter::tent(1.0).unwrap(),
        ];
        for filter in &stepped {
            let density = SignedDensity::new(filter).unwrap();
            let peak = density.at(0.0).abs();
            let span = 2 * (filter.radius() + 0.5).ceil() as usize + 1;
            for k in 0..=1000 {
                // From beyond the right end to the left one, off the nodes.
                let x = filter.radius() + 1.0
                    - 2.0 * (filter.radius() + 1.0) * (k as f32 + 0.31) / 1001.0;
                let mut stepped = vec![f32::NAN; span];
                assert!(density.at_steps(x, &mut stepped), "{filter:?}");
                for (j, &ours) in stepped.iter().enumerate() {
                    let expected = density.at(x - j as f32);
                    assert!(
                        (ours - expected).abs() <= 1e-5 * peak,
                        "{filter:?} at {x} − {j}: {ours} against {expected}"
                    );
                }
            }
        }
        // 512 segments over 2.4 pixels: not a whole number per pixel.
        let density = SignedDensity::new(&Filter::gaussian(0.3).unwrap()).unwrap();
        assert!(!density.at_steps(0.2, &mut [0.0; 3]));
    }

    #[test]
    fn a_splat_reaches_every_pixel_of_nonzero_weight_with_that_weight() {
        // Against Filter::pixel_weight at every pixel of a 7 × 6 image, for positions spread
        // over all its pixels (edges and corners included) and on pixel edges.
        let (width, height) = (7, 6);
        for filter in [
            Filter::tent(1.0).unwrap(),
            Filter::gaussian(0.5).unwrap(),
            Filter::gaussian(0.3).unwrap(),
            Filter::mitchell(1.0 / 3.0, 1.0 / 3.0).unwrap(),
            Filter::lanczos(3).unwrap(),
        ] {
            let splatter = Splatter::new(&filter, width, height).unwrap();
            let peak = filter.pixel_weight(Vec2::splat(3.5), UVec2::splat(3), width, height);
            for k in 0..2000u32 {
                let u = Vec2::new(
                    ((k as f32 * 0.618_034).fract() * 8.0).floor() / 8.0,
                    (k as f32 * 0.754_877_7).fract(),
                );
                let source = UVec2::new(k % width, (k / width) % height);
                let film = Splatter::film_position(source, u);
                let mut splat = vec![0.0; (width * height) as usize];
                let mut visits = 0;
                splatter.splat(film, source, |first, weight_y, weights_x| {
                    for (x, &weight_x) in (first.x..).zip(weights_x) {
                        splat[(first.y * width + x) as usize] += weight_x * weight_y;
                        visits += 1;
                    }
                });
                assert!(visits <= (2 * splatter.reach() + 1).pow(2));
                for y in 0..height {
                    for x in 0..width {
                        let pixel = UVec2::new(x, y);
                        let expected = filter.pixel_weight(film, pixel, width, height);
                        let ours = splat[(y * width + x) as usize];
                        assert!(
                            (ours - expected).abs() <= 1e-5 * peak.abs(),
                            "{filter:?}: sample of {source} at {film} in {pixel}: {ours} against {expected}"
                        );
                    }
                }
            }
        }
    }
}
