//! The whole unit sphere, sampled uniformly.

use super::turn::sin_cos_turn;
use super::{azimuth_fraction, safe_sqrt};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// A direction uniform over the unit sphere by solid angle: z = 1 − 2 u.x, φ = 2π u.y.
#[inline]
pub fn sample_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = safe_sqrt(1.0 - z * z);
    let (sin_phi, cos_phi) = sin_cos_turn(u.y);
    Vec3::new(r * cos_phi, r * sin_phi, z)
}

/// Density of [`sample_uniform_sphere`] per steradian: 1 / (4π).
#[inline]
pub fn uniform_sphere_pdf() -> f32 {
    0.25 * FRAC_1_PI
}

/// The `u` that [`sample_uniform_sphere`] maps to the unit direction `w`.
#[inline]
pub fn invert_uniform_sphere(w: Vec3) -> Vec2 {
    Vec2::new(
        ((1.0 - w.z) * 0.5).clamp(0.0, 1.0),
        azimuth_fraction(w.x, w.y),
    )
}
