//! An environment map (Mitsuba's `envmap` emitter): radiance from infinitely far away, looked
//! up in a latitude-longitude image, sampled in proportion to its brightness.

use crate::light::{Emitter, Kind};
use crate::sample::{LightSample, mean_rgb};
use glam::{Mat3, Vec2, Vec3};
use sampling::distribution::CdfTable;
use std::f32::consts::{PI, TAU};
use std::sync::Arc;

/// Why an environment map cannot be built from an image.
#[derive(Clone, Debug, PartialEq)]
pub enum EnvironmentMapError {
    /// Fewer than 2 × 2 texels, or a texel count that does not match the size.
    BadSize {
        /// Texels per row.
        width: u32,
        /// Rows.
        height: u32,
    },
    /// A texel (column, row) that is negative, NaN or infinite.
    BadTexel {
        /// Column of the texel.
        x: u32,
        /// Row of the texel (0 at the top).
        y: u32,
    },
    /// `scale` is negative, NaN or infinite.
    BadScale,
    /// `to_world` does not rotate directions (it is singular or not finite).
    BadTransform,
}

impl std::fmt::Display for EnvironmentMapError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::BadSize { width, height } => write!(
                f,
                "an environment map needs at least 2 x 2 texels, got {width} x {height}"
            ),
            Self::BadTexel { x, y } => write!(
                f,
                "texel ({x}, {y}) of the environment map is negative, NaN or infinite"
            ),
            Self::BadScale => write!(f, "`scale` must be a finite non-negative number"),
            Self::BadTransform => write!(f, "`to_world` must be an invertible rotation"),
        }
    }
}

impl std::error::Error for EnvironmentMapError {}

/// Radiance L(ω) from every direction ω, from an RGB latitude-longitude image of `width` ×
/// `height` texels, placed by a rotation `to_world`, as Mitsuba 3 reads it:
///
/// - a direction d in the map's frame has u = atan2(d.x, −d.z) / 2π (wrapping) and
///   v = acos(d.y) / π (0 at +y, the top row);
/// - texel (column j, row i) sits at u = (j + ½) / width and v = i / (height − 1), so the top and
///   bottom rows lie on the poles; L is interpolated bilinearly between the four texels around
///   (u, v), wrapping in u, times `scale`.
///
/// Sampling picks a cell between four texels with probability proportional to its brightest
/// texel's mean over RGB times the cell's solid angle, then a point uniform in (u, v) within it,
/// so that every direction with L > 0 has a positive density. Under MIS a path tracer samples
/// [`Self::compensated`] instead.
#[derive(Clone, Debug)]
pub struct EnvironmentMap {
    width: u32,
    height: u32,
    /// Radiance times `scale`, W m⁻² sr⁻¹, row-major from the top row (shared with the
    /// compensated copy).
    texels: Arc<[Vec3]>,
    to_world: Mat3,
    to_local: Mat3,
    /// One entry per cell, row-major: height − 1 rows of width cells.
    cells: Arc<CdfTable>,
    /// The cells of [`Self::compensated`] and the mean excess they sample, W m⁻² sr⁻¹ (`None`
    /// when nothing exceeds the mean, and in the compensated copy itself).
    compensation: Option<(Arc<CdfTable>, f32)>,
    /// Mean over the sphere of the radiance's mean over RGB, W m⁻² sr⁻¹.
    mean_radiance: f32,
    /// Mean over the sphere of what `cells` samples, W m⁻² sr⁻¹: the radiance, or for the
    /// compensated copy its excess over `mean_radiance`. Power and irradiance estimates use it.
    sampled_radiance: f32,
    /// Radius of a sphere bounding the scene (world units), used only to estimate power.
    scene_radius: f32,
}

impl EnvironmentMap {
    /// The map of `texels` (RGB radiance, `width` × `height`, row-major from the top row),
    /// multiplied by `scale` and rotated by `to_world` (its inverse is taken as a rotation's
    /// transpose after normalising the columns); `scene_radius` bounds the scene for the power
    /// estimate. An error for a map smaller than 2 × 2, a bad texel, scale or transform.
    pub fn new(
        width: u32,
        height: u32,
        texels: &[Vec3],
        scale: f32,
        to_world: Mat3,
        scene_radius: f32,
    ) -> Result<Self, EnvironmentMapError> {
        if width < 2 || height < 2 || texels.len() != (width as usize) * (height as usize) {
            return Err(EnvironmentMapError::BadSize { width, height });
        }
        if !(scale.is_finite() && scale >= 0.0) {
            return Err(EnvironmentMapError::BadScale);
        }
        if let Some(i) = texels
            .iter()
            .position(|t| !(t.is_finite() && t.min_element() >= 0.0))
        {
            return Err(EnvironmentMapError::BadTexel {
                x: i as u32 % width,
                y: i as u32 / width,
            });
        }
        let columns = [to_world.x_axis, to_world.y_axis, to_world.z_axis];
        if !to_world.is_finite() || columns.iter().any(|c| c.length_squared() == 0.0) {
            return Err(EnvironmentMapError::BadTransform);
        }
        let rotation = Mat3::from_cols(
            columns[0].normalize(),
            columns[1].normalize(),
            columns[2].normalize(),
        );
        let texels: Arc<[Vec3]> = texels.iter().map(|&t| t * scale).collect();
        let weights = cell_weights(&texels, width, height, 0.0);
        // A black map is never sampled (its weight is zero); any valid table serves.
        let cells = CdfTable::new(&weights)
            .or_else(|_| CdfTable::new(&vec![1.0; weights.len()]))
            .expect("positive weights");
        let mean_radiance = mean_above(&texels, width, height, 0.0);
        let compensation = CdfTable::new(&cell_weights(&texels, width, height, mean_radiance))
            .ok()
            .map(|cells| {
                let excess = mean_above(&texels, width, height, mean_radiance);
                (Arc::new(cells), excess)
            });
        Ok(Self {
            width,
            height,
            texels,
            to_world: rotation,
            to_local: rotation.transpose(),
            cells: Arc::new(cells),
            compensation,
            mean_radiance,
            sampled_radiance: mean_radiance,
            scene_radius,
        })
    }

    /// The map as a path tracer's light sampling under MIS samples it: cells drawn in
    /// proportion to how far their brightest texel's mean over RGB exceeds the map's
    /// [mean radiance](Self::mean_radiance), times their solid angle (pbrt-v4's compensated
    /// distribution, after Karlík et al., "MIS Compensation", 2019). Where light sampling has no
    /// density, MIS gives the BSDF sample that finds the map weight 1, and BSDF samples already
    /// find a map's even part well; light samples then go to what stands out (a sun), not to
    /// the sky around it. The radiance is the same; [`Self::power`] is that of the excess.
    /// `None` where no cell exceeds the mean (a constant map): the map is then left to BSDF
    /// samples whole.
    pub fn compensated(&self) -> Option<EnvironmentMap> {
        let (cells, excess) = self.compensation.clone()?;
        Some(Self {
            cells,
            compensation: None,
            sampled_radiance: excess,
            ..self.clone()
        })
    }

    /// Whether some cell's brightest texel exceeds the mean radiance, so that there is a
    /// [compensated](Self::compensated) map.
    pub fn has_compensated(&self) -> bool {
        self.compensation.is_some()
    }

    /// (u, v) of the world direction `w` (unit length), and sin θ in the map's frame.
    fn uv(&self, w: Vec3) -> (Vec2, f32) {
        let d = (self.to_local * w).normalize_or_zero();
        let u = d.x.atan2(-d.z) / TAU;
        let u = u - u.floor();
        let v = d.y.clamp(-1.0, 1.0).acos() / PI;
        (Vec2::new(u, v), (d.x * d.x + d.z * d.z).sqrt())
    }

    /// The cell (row, column) holding (u, v): the four texels around it.
    fn cell(&self, uv: Vec2) -> (usize, usize) {
        let (w, h) = (self.width as usize, self.height as usize);
        let x = uv.x * w as f32 - 0.5;
        let column = (x.floor() as i64).rem_euclid(w as i64) as usize;
        let row = ((uv.y * (h - 1) as f32).floor().max(0.0) as usize).min(h - 2);
        (row, column)
    }

    /// Radiance arriving from the world direction `w` (unit length, pointing away from the
    /// scene), W m⁻² sr⁻¹.
    pub fn radiance(&self, w: Vec3) -> Vec3 {
        let (uv, _) = self.uv(w);
        let (w_texels, h) = (self.width as usize, self.height as usize);
        let x = uv.x * w_texels as f32 - 0.5;
        let y = (uv.y * (h - 1) as f32).clamp(0.0, (h - 1) as f32);
        let (x0, y0) = (x.floor(), y.floor().min((h - 2) as f32));
        let (fx, fy) = (x - x0, y - y0);
        let j0 = (x0 as i64).rem_euclid(w_texels as i64) as usize;
        let j1 = (j0 + 1) % w_texels;
        let i0 = y0 as usize;
        let texel = |i: usize, j: usize| self.texels[i * w_texels + j];
        let top = texel(i0, j0).lerp(texel(i0, j1), fx);
        let bottom = texel(i0 + 1, j0).lerp(texel(i0 + 1, j1), fx);
        top.lerp(bottom, fy)
    }

    /// Density per steradian with which [`Self::sample_li`] picks the world direction `w`.
    pub fn pdf_li(&self, w: Vec3) -> f32 {
        let (uv, sin_theta) = self.uv(w);
        if sin_theta <= 0.0 {
            return 0.0;
        }
        let (row, column) = self.cell(uv);
        self.cell_density(row, column) / (2.0 * PI * PI * sin_theta)
    }

    /// The density in (u, v) of a point of cell (`row`, `column`).
    fn cell_density(&self, row: usize, column: usize) -> f32 {
        let cells_per_row = self.width as usize;
        let area = 1.0 / (self.width as f32 * (self.height - 1) as f32);
        self.cells.pmf(row * cells_per_row + column) / area
    }

    /// A direction from `p` towards the environment, its radiance and density, with `u`
    /// uniform in [0, 1)²: a cell by `u.x` (whose leftover places the point in u), the point's v
    /// by `u.y`. `None` at a pole, where the density is undefined.
    pub fn sample_li(&self, p: Vec3, u: Vec2) -> Option<LightSample> {
        let (index, _, u_rest) = self.cells.sample(u.x);
        let cells_per_row = self.width as usize;
        let (row, column) = (index / cells_per_row, index % cells_per_row);
        let map_u = (column as f32 + 0.5 + u_rest) / self.width as f32;
        let map_u = map_u - map_u.floor();
        let map_v = (row as f32 + u.y) / (self.height - 1) as f32;
        let (theta, phi) = (map_v * PI, map_u * TAU);
        let sin_theta = theta.sin();
        if sin_theta <= 0.0 {
            return None;
        }
        let local = Vec3::new(phi.sin() * sin_theta, theta.cos(), -phi.cos() * sin_theta);
        let wi = (self.to_world * local).normalize();
        // The density of the cell `wi` falls in when looked up again, which rounding can make a
        // neighbour of the one sampled at a cell's edge: so that the sample's density is the
        // one MIS computes for the same direction (a neighbour of a compensated map's cell may
        // have none).
        let pdf = self.pdf_li(wi);
        (pdf > 0.0 && pdf.is_finite()).then(|| LightSample {
            radiance: self.radiance(wi),
            wi,
            distance: f32::INFINITY,
            pdf_solid_angle: pdf,
            p_light: p + wi,
            p_light_error: Vec3::ZERO,
            n_light: Vec3::ZERO,
            is_delta: false,
        })
    }

    /// Mean over the sphere of the radiance's mean over RGB, W m⁻² sr⁻¹.
    pub fn mean_radiance(&self) -> f32 {
        self.mean_radiance
    }

    /// Power reaching the scene (W, mean over channels) of what [`Self::sample_li`] samples:
    /// mean radiance (for a [compensated](Self::compensated) map, mean excess over it) · π ·
    /// π r² of the bounding disc, as for a constant environment.
    pub fn power(&self) -> f32 {
        self.sampled_radiance * PI * PI * self.scene_radius * self.scene_radius
    }
}

/// The sampling weight of every cell of a `width` × `height` map of `texels` (row-major: height
/// − 1 rows of width cells): the amount by which its brightest texel's mean over RGB exceeds
/// `floor` (0 or more), times its solid angle.
fn cell_weights(texels: &[Vec3], width: u32, height: u32, floor: f32) -> Vec<f32> {
    let (w, h) = (width as usize, height as usize);
    let lum = |i: usize, j: usize| mean_rgb(texels[i * w + j % w]);
    let theta = |i: usize| PI * i as f32 / (h - 1) as f32;
    let mut weights = Vec::with_capacity((h - 1) * w);
    for i in 0..h - 1 {
        let band = theta(i).cos() - theta(i + 1).cos();
        for j in 0..w {
            let brightest = lum(i, j)
                .max(lum(i, j + 1))
                .max(lum(i + 1, j))
                .max(lum(i + 1, j + 1));
            weights.push((brightest - floor).max(0.0) * band);
        }
    }
    weights
}

/// The mean over the sphere of the amount by which the radiance's mean over RGB exceeds `floor`
/// (0 or more; with 0 the mean radiance), W m⁻² sr⁻¹: each texel weighted by the solid angle
/// of the rows around it.
fn mean_above(texels: &[Vec3], width: u32, height: u32, floor: f32) -> f32 {
    let (w, h) = (width as usize, height as usize);
    let theta = |i: usize| PI * i as f32 / (h - 1) as f32;
    let mut sum = 0.0_f64;
    let mut solid_angle = 0.0_f64;
    for i in 0..h {
        let (lo, hi) = (theta(i.saturating_sub(1)), theta((i + 1).min(h - 1)));
        let band = f64::from((0.5 * (lo + theta(i))).cos() - (0.5 * (theta(i) + hi)).cos());
        for texel in &texels[i * w..(i + 1) * w] {
            sum += f64::from((mean_rgb(*texel) - floor).max(0.0)) * band;
            solid_angle += band;
        }
    }
    (sum / solid_angle) as f32
}

impl Emitter for EnvironmentMap {
    const KIND: Kind = Kind::Environment;

    #[inline]
    fn sample_li(&self, p: Vec3, u: Vec2, _time: f32) -> Option<LightSample> {
        EnvironmentMap::sample_li(self, p, u)
    }

    #[inline]
    fn radiance_from_direction(&self, w: Vec3) -> Vec3 {
        self.radiance(w)
    }

    #[inline]
    fn pdf_li_environment(&self, w: Vec3) -> f32 {
        self.pdf_li(w)
    }

    /// π times the mean over the sphere of the radiance sampled (of its excess over the mean
    /// for a [compensated](EnvironmentMap::compensated) map).
    fn irradiance_estimate(&self, _p: Vec3, _n: Vec3) -> f32 {
        PI * self.sampled_radiance
    }

    fn power(&self) -> f32 {
        EnvironmentMap::power(self)
    }
}
