//! The upper (z ≥ 0) unit hemisphere, sampled uniformly or proportional to cos θ.

use super::turn::sin_cos_turn;
use super::{azimuth_fraction, safe_sqrt};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// A direction uniform over the upper hemisphere by solid angle: cos θ = u.x, φ = 2π u.y.
#[inline]
pub fn sample_uniform_hemisphere(u: Vec2) -> Vec3 {
    let z = u.x;
    let r = safe_sqrt(1.0 - z * z);
    let (sin_phi, cos_phi) = sin_cos_turn(u.y);
    Vec3::new(r * cos_phi, r * sin_phi, z)
}

/// Density of [`sample_uniform_hemisphere`] per steradian: 1 / (2π) on the upper hemisphere.
#[inline]
pub fn uniform_hemisphere_pdf() -> f32 {
    0.5 * FRAC_1_PI
}

/// The `u` that [`sample_uniform_hemisphere`] maps to the unit direction `w` (z ≥ 0).
#[inline]
pub fn invert_uniform_hemisphere(w: Vec3) -> Vec2 {
    Vec2::new(w.z, azimuth_fraction(w.x, w.y))
}

/// A direction over the upper hemisphere with density cos θ / π, by the lecture's disc projection:
/// a point uniform on the unit disc (r = √u.x, φ = 2π u.y) lifted to z = √(1 − u.x).
#[inline]
pub fn sample_cosine_hemisphere(u: Vec2) -> Vec3 {
    let r = u.x.sqrt();
    let (sin_phi, cos_phi) = sin_cos_turn(u.y);
    Vec3::new(r * cos_phi, r * sin_phi, safe_sqrt(1.0 - u.x))
}

/// Density of [`sample_cosine_hemisphere`] per steradian: cos θ / π, zero below the horizon.
#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// The `u` that [`sample_cosine_hemisphere`] maps to the unit direction `w` (z ≥ 0).
#[inline]
pub fn invert_cosine_hemisphere(w: Vec3) -> Vec2 {
    let r2 = (w.x * w.x + w.y * w.y).min(1.0);
    Vec2::new(r2, azimuth_fraction(w.x, w.y))
}
