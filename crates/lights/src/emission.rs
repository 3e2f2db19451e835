//! Sampling light leaving an emitter's surface, for tracing paths from the lights (light
//! tracing). Area emitters are Lambertian: a point uniform by area and a cosine-distributed
//! direction about its emitting normal.

use glam::{Vec2, Vec3};
use sampling::Frame;
use sampling::warp::sample_cosine_hemisphere;
use std::f32::consts::PI;

/// A ray of light leaving an emitter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmissionSample {
    /// The point on the emitter, world space.
    pub p: Vec3,
    /// A bound on the rounding error of each coordinate of `p` (world units), which the ray
    /// leaving it is moved off the emitter by.
    pub p_error: Vec3,
    /// The unit geometric normal on the emitting side.
    pub n: Vec3,
    /// The unit direction the light leaves in (on the side of `n`).
    pub dir: Vec3,
    /// Lₑ · cos θ / (pdf_area · pdf_solid_angle): the power the sample carries (W, RGB), before
    /// dividing by the probability of having chosen this emitter.
    pub weight: Vec3,
}

/// The emission sample of a Lambertian emitter of `radiance` and total `area` (world units²)
/// at the point `p` (coordinate error bound `p_error`) with emitting normal `n`, chosen
/// uniformly by area, with `u_dir` for the cosine-distributed direction: the weight is
/// Lₑ · π · area.
#[inline]
pub(crate) fn lambertian_emission(
    p: Vec3,
    p_error: Vec3,
    n: Vec3,
    radiance: Vec3,
    area: f32,
    u_dir: Vec2,
) -> Option<EmissionSample> {
    let local = sample_cosine_hemisphere(u_dir);
    if local.z <= 0.0 || n == Vec3::ZERO {
        return None;
    }
    Some(EmissionSample {
        p,
        p_error,
        n,
        dir: Frame::from_normal(n).to_world(local).normalize(),
        weight: radiance * (PI * area),
    })
}
