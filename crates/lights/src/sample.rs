//! What a light returns when asked for a direction towards it.

use glam::Vec3;

/// A direction towards a light, with the radiance arriving along it (before occlusion).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Radiance arriving at the shading point along `wi` (W m⁻² sr⁻¹, RGB), or for a delta light
    /// the irradiance-producing term `intensity / distance²` so that `radiance / pdf_solid_angle`
    /// is the estimator's weight with `pdf_solid_angle = 1`.
    pub radiance: Vec3,
    /// Unit direction from the shading point towards the light.
    pub wi: Vec3,
    /// Distance from the shading point to the sampled point (∞ for the environment).
    pub distance: f32,
    /// Density of `wi` per steradian; 1 for delta lights (the direction is certain).
    pub pdf_solid_angle: f32,
    /// The sampled point on the light (the shading point plus `wi` for the environment).
    pub p_light: Vec3,
    /// A bound on the rounding error of each coordinate of `p_light` (world units; zero where it
    /// is no surface point), which a shadow ray's end is moved off the light by.
    pub p_light_error: Vec3,
    /// Unit normal of the light surface at `p_light` (zero for point lights and the environment).
    pub n_light: Vec3,
    /// True for lights that no random ray can hit (point lights).
    pub is_delta: bool,
}

/// The mean of the three channels, the scalar used for power and selection weights.
#[inline]
pub fn mean_rgb(c: Vec3) -> f32 {
    (c.x + c.y + c.z) * (1.0 / 3.0)
}
