//! A 1D reconstruction filter tabulated for sampling: its values at equally spaced nodes, the
//! piecewise-linear interpolant of their magnitudes as the sampling density (inverted exactly, a
//! quadratic per segment), and the signed interpolant's running integral for filters with
//! negative lobes.

/// Segments per pixel of radius of the tables of filters whose curvature does not scale with
/// their radius (Mitchell–Netravali, Lanczos): a linear interpolant differs from a smooth filter
/// by at most `h²/8 · max|f''|`, here `h = 1/256` pixel, so about `2e-5` of the peak for Lanczos
/// (`|f''| ≤ π²(1 + 1/lobes²)`) and less for the cubics.
pub(super) const SEGMENTS_PER_PIXEL: usize = 256;

/// `f₁` at the nodes `x_i = −r + i·h`, `h = 2r / segments`, with the normalised CDF of the
/// interpolant of `|f₁|` and the running integral of the interpolant of `f₁` itself.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct FilterTable {
    radius: f32,
    /// Number of equal segments over `[-radius, radius]` (even, so that 0 is a node).
    segments: usize,
    /// `f₁` at the nodes (signed).
    values: Vec<f32>,
    /// Normalised CDF of the interpolant of `|f₁|` at the nodes: `cdf[0] = 0`,
    /// `cdf[segments] = 1`.
    cdf: Vec<f32>,
    /// Integral of the interpolant of `|f₁|` over `[-r, r]`, in pixels.
    total: f32,
    /// `1 / total` and segments per pixel, `1 / h`: [`Self::pdf`] and [`Self::signed_pdf`] run
    /// for every weight of every splatted camera sample, so they multiply rather than divide.
    inv_total: f32,
    inv_spacing: f32,
    /// Nodes per pixel, `1 / h`, where it is a whole number: offsets a pixel apart then lie at
    /// the same place in their segments ([`Self::signed_pdf_steps`]).
    nodes_per_pixel: Option<usize>,
    /// Integral of the interpolant of `f₁` from `-r` to each node, divided by `total`.
    signed_cdf: Vec<f32>,
    /// Whether some node value is negative.
    negative_lobes: bool,
}

impl FilterTable {
    /// Tabulates `f` (unnormalised, zero beyond `radius`) over `[-radius, radius]` in `segments`
    /// equal segments (even, at least 2).
    pub(super) fn new(radius: f32, segments: usize, f: impl Fn(f32) -> f32) -> Self {
        debug_assert!(segments >= 2 && segments.is_multiple_of(2));
        let h = 2.0 * f64::from(radius) / segments as f64;
        let values: Vec<f32> = (0..=segments)
            .map(|i| f((-f64::from(radius) + i as f64 * h) as f32))
            .collect();
        let mut cumulative = Vec::with_capacity(segments + 1);
        let mut signed = Vec::with_capacity(segments + 1);
        let (mut sum, mut signed_sum) = (0.0f64, 0.0f64);
        cumulative.push(0.0);
        signed.push(0.0);
        for pair in values.windows(2) {
            let (f0, f1) = (f64::from(pair[0]), f64::from(pair[1]));
            sum += 0.5 * h * (f0.abs() + f1.abs());
            signed_sum += 0.5 * h * (f0 + f1);
            cumulative.push(sum);
            signed.push(signed_sum);
        }
        // Segments per pixel, `1 / h`.
        let per_pixel = segments as f64 / (2.0 * f64::from(radius));
        Self {
            radius,
            segments,
            cdf: cumulative.iter().map(|c| (c / sum) as f32).collect(),
            signed_cdf: signed.iter().map(|c| (c / sum) as f32).collect(),
            total: sum as f32,
            inv_total: (1.0 / sum) as f32,
            inv_spacing: per_pixel as f32,
            nodes_per_pixel: (per_pixel >= 1.0
                && (per_pixel - per_pixel.round()).abs() <= 1e-9 * per_pixel)
                .then_some(per_pixel.round() as usize),
            negative_lobes: values.iter().any(|&v| v < 0.0),
            values,
        }
    }

    /// Whether the filter is negative somewhere.
    pub(super) fn has_negative_lobes(&self) -> bool {
        self.negative_lobes
    }

    /// Node spacing in pixels.
    fn spacing(&self) -> f32 {
        2.0 * self.radius / self.segments as f32
    }

    /// The segment holding offset `x` and the position within it, `None` outside `(-r, r)`.
    fn segment(&self, x: f32) -> Option<(usize, f32)> {
        let position = (x + self.radius) * self.inv_spacing;
        if !(position > 0.0 && position < self.segments as f32) {
            return None;
        }
        let i = (position as u32 as usize).min(self.segments - 1);
        Some((i, position - i as f32))
    }

    /// The sampling density (per pixel) at offset `x`: the interpolant of `|f₁|` divided by its
    /// integral; zero outside `(-radius, radius)`.
    pub(super) fn pdf(&self, x: f32) -> f32 {
        let Some((i, s)) = self.segment(x) else {
            return 0.0;
        };
        let (f0, f1) = (self.values[i].abs(), self.values[i + 1].abs());
        (f0 + (f1 - f0) * s) * self.inv_total
    }

    /// The interpolant of `f₁` (signed) at offset `x`, divided by the same integral as
    /// [`Self::pdf`]; equal to it where the filter is not negative.
    pub(super) fn signed_pdf(&self, x: f32) -> f32 {
        let Some((i, s)) = self.segment(x) else {
            return 0.0;
        };
        let (f0, f1) = (self.values[i], self.values[i + 1]);
        (f0 + (f1 - f0) * s) * self.inv_total
    }

    /// [`Self::signed_pdf`] at the offsets `x`, `x − 1`, `x − 2`, … (pixels), one per entry of
    /// `out`, where the table has a whole number of nodes per pixel: their segments are then a
    /// fixed number of nodes apart and share the position within them, found once (equal to
    /// the offsets' own up to `f32` rounding). Returns `false`, writing nothing, for other
    /// tables.
    #[inline]
    pub(super) fn signed_pdf_steps(&self, x: f32, out: &mut [f32]) -> bool {
        let Some(step) = self.nodes_per_pixel else {
            return false;
        };
        let position = (x + self.radius) * self.inv_spacing;
        if position.is_nan() || position < 0.0 {
            // At or beyond the support's left end, and the later offsets further still.
            out.fill(0.0);
            return true;
        }
        let node = position as usize;
        let s = position - node as f32;
        for (k, value) in out.iter_mut().enumerate() {
            let segment = node
                .checked_sub(k * step)
                .and_then(|i| self.values.get(i..=i + 1));
            *value = match segment {
                Some(&[f0, f1]) => (f0 + (f1 - f0) * s) * self.inv_total,
                _ => 0.0,
            };
        }
        true
    }

    /// The CDF of [`Self::pdf`] at offset `x`: exactly 0 at and below `-radius`, exactly 1 at
    /// and above `radius`.
    pub(super) fn cdf(&self, x: f32) -> f32 {
        self.running_integral(x, &self.cdf, f32::abs).min(1.0)
    }

    /// The integral of [`Self::signed_pdf`] from `-radius` to `x`.
    pub(super) fn signed_cdf(&self, x: f32) -> f32 {
        self.running_integral(x, &self.signed_cdf, |v| v)
    }

    /// The integral from `-radius` to `x` of the interpolant of `node(f₁)` divided by `total`,
    /// from `at_nodes`, its values at the nodes: 0 at and below `-radius`, the last node's value
    /// at and above `radius`.
    fn running_integral(&self, x: f32, at_nodes: &[f32], node: impl Fn(f32) -> f32) -> f32 {
        let h = self.spacing();
        let position = (x + self.radius) / h;
        if position.is_nan() || position <= 0.0 {
            return 0.0;
        }
        if position >= self.segments as f32 {
            return at_nodes[self.segments];
        }
        let i = (position as usize).min(self.segments - 1);
        let s = position - i as f32;
        let (f0, f1) = (node(self.values[i]), node(self.values[i + 1]));
        at_nodes[i] + h * s * (f0 + 0.5 * (f1 - f0) * s) / self.total
    }

    /// Maps `u ∈ [0, 1)` to an offset in `[-radius, radius]` (pixels) with density
    /// [`Self::pdf`]. Monotonic in `u`.
    pub(super) fn sample(&self, u: f32) -> f32 {
        let u = u.clamp(0.0, 1.0);
        let i = self
            .cdf
            .partition_point(|&c| c <= u)
            .clamp(1, self.segments)
            - 1;
        let h = self.spacing();
        let (f0, f1) = (self.values[i].abs(), self.values[i + 1].abs());
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
