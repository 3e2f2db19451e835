//! Cones of directions around +z, sampled uniformly by solid angle.

use super::turn::sin_cos_turn;
use super::{azimuth_fraction, safe_sqrt};
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;

/// A direction uniform by solid angle within the cone θ ≤ θ_max around +z:
/// cos θ = 1 − u.x (1 − cos θ_max), φ = 2π u.y.
#[inline]
pub fn sample_uniform_cone(u: Vec2, cos_theta_max: f32) -> Vec3 {
    let cos_theta = 1.0 - u.x * (1.0 - cos_theta_max);
    let sin_theta = safe_sqrt(1.0 - cos_theta * cos_theta);
    let (sin_phi, cos_phi) = sin_cos_turn(u.y);
    Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta)
}

/// Density of [`sample_uniform_cone`] per steradian inside the cone: 1 / (2π (1 − cos θ_max)).
#[inline]
pub fn uniform_cone_pdf(cos_theta_max: f32) -> f32 {
    1.0 / (TAU * (1.0 - cos_theta_max))
}

/// The `u` that [`sample_uniform_cone`] maps to the unit direction `w` inside the cone.
#[inline]
pub fn invert_uniform_cone(w: Vec3, cos_theta_max: f32) -> Vec2 {
    let x = ((1.0 - w.z) / (1.0 - cos_theta_max)).clamp(0.0, 1.0);
    Vec2::new(x, azimuth_fraction(w.x, w.y))
}
