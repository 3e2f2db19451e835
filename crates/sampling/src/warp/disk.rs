//! The unit disc, sampled uniformly by Shirley and Chiu's concentric map (low distortion).

use super::turn::sin_cos_quarter;
use glam::Vec2;
use std::f32::consts::{FRAC_1_PI, FRAC_PI_4, PI};

/// A point uniform on the unit disc by area: the square [-1, 1]² is mapped ring by ring onto the disc.
#[inline]
pub fn sample_concentric_disk(u: Vec2) -> Vec2 {
    let offset = 2.0 * u - Vec2::ONE;
    if offset.x == 0.0 && offset.y == 0.0 {
        return Vec2::ZERO;
    }
    if offset.x.abs() > offset.y.abs() {
        // θ = π/4 · y/x.
        let (sin, cos) = sin_cos_quarter(FRAC_PI_4 * (offset.y / offset.x));
        offset.x * Vec2::new(cos, sin)
    } else {
        // θ = π/2 − φ with φ = π/4 · x/y: cos θ = sin φ, sin θ = cos φ.
        let (sin, cos) = sin_cos_quarter(FRAC_PI_4 * (offset.x / offset.y));
        offset.y * Vec2::new(sin, cos)
    }
}

/// Density of [`sample_concentric_disk`] per unit area: 1 / π inside the unit disc.
#[inline]
pub fn concentric_disk_pdf() -> f32 {
    FRAC_1_PI
}

/// The `u` that [`sample_concentric_disk`] maps to the point `p` of the unit disc.
#[inline]
pub fn invert_concentric_disk(p: Vec2) -> Vec2 {
    let r = p.length();
    if r == 0.0 {
        return Vec2::splat(0.5);
    }
    let mut phi = p.y.atan2(p.x);
    if phi < -FRAC_PI_4 {
        phi += 2.0 * PI;
    }
    // Each wedge of π/2 around an axis came from one side of the square.
    let offset = if phi < FRAC_PI_4 {
        Vec2::new(r, r * phi / FRAC_PI_4)
    } else if phi < 3.0 * FRAC_PI_4 {
        Vec2::new(-r * (phi - 2.0 * FRAC_PI_4) / FRAC_PI_4, r)
    } else if phi < 5.0 * FRAC_PI_4 {
        Vec2::new(-r, -r * (phi - 4.0 * FRAC_PI_4) / FRAC_PI_4)
    } else {
        Vec2::new(r * (phi - 6.0 * FRAC_PI_4) / FRAC_PI_4, -r)
    };
    ((offset + Vec2::ONE) * 0.5).clamp(Vec2::ZERO, Vec2::ONE)
}
