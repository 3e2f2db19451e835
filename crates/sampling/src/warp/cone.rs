//! Cones of directions around +z, sampled uniformly by solid angle.
//!
//! A cone is given by 1 − cos θ_max rather than cos θ_max: for a narrow cone (a small or
//! distant sphere seen from a point) cos θ_max rounds to 1 in `f32` while 1 − cos θ_max,
//! computed as sin²θ_max / (1 + cos θ_max), keeps its precision.

use super::turn::sin_cos_turn;
use super::{azimuth_fraction, safe_sqrt};
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;

/// A direction uniform by solid angle within the cone θ ≤ θ_max around +z, given
/// `one_minus_cos_max` = 1 − cos θ_max ∈ (0, 2]: 1 − cos θ = u.x (1 − cos θ_max), φ = 2π u.y.
#[inline]
pub fn sample_uniform_cone(u: Vec2, one_minus_cos_max: f32) -> Vec3 {
    let one_minus_cos = u.x * one_minus_cos_max;
    // sin²θ = (1 − cos θ)(1 + cos θ), exact where 1 − cos²θ would cancel.
    let sin_theta = safe_sqrt(one_minus_cos * (2.0 - one_minus_cos));
    let (sin_phi, cos_phi) = sin_cos_turn(u.y);
    Vec3::new(
        sin_theta * cos_phi,
        sin_theta * sin_phi,
        1.0 - one_minus_cos,
    )
}

/// Density of [`sample_uniform_cone`] per steradian inside the cone, 1 / (2π (1 − cos θ_max)),
/// given `one_minus_cos_max` = 1 − cos θ_max.
#[inline]
pub fn uniform_cone_pdf(one_minus_cos_max: f32) -> f32 {
    1.0 / (TAU * one_minus_cos_max)
}

/// The `u` that [`sample_uniform_cone`] maps to the unit direction `w` inside the cone given
/// `one_minus_cos_max` = 1 − cos θ_max.
#[inline]
pub fn invert_uniform_cone(w: Vec3, one_minus_cos_max: f32) -> Vec2 {
    // 1 − cos θ = sin²θ / (1 + cos θ), without cancellation near the axis.
    let sin2 = w.x * w.x + w.y * w.y;
    let one_minus_cos = if w.z > 0.0 {
        sin2 / (1.0 + w.z)
    } else {
        1.0 - w.z
    };
    let x = (one_minus_cos / one_minus_cos_max).clamp(0.0, 1.0);
    Vec2::new(x, azimuth_fraction(w.x, w.y))
}
